// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_FORK_LIFT_SCENE_H
#define CALIBER_DEMOS_FORK_LIFT_SCENE_H
// ForkLiftDemo's scene: the manual's fork lift (a raycast vehicle with an 800 kg chassis, a mast on a
// hinge at its front held upright by the hinge's limits, a fork that a slider's motor moves along the
// mast) and a 100 kg load on two rails 10 m ahead. Used by ForkLiftDemo, which scripts and measures
// it, and by the demo browser, where the keys drive it and move the fork.

#include <memory>

#include "btBulletDynamicsCommon.h"

namespace fork_lift_demo
{
const btScalar kWheelWidth = btScalar(0.24);

class Scene
{
public:
	Scene();
	~Scene();
	Scene(const Scene&) = delete;
	Scene& operator=(const Scene&) = delete;
	btDiscreteDynamicsWorld& world() { return m_world; }
	btRigidBody* chassis() { return m_chassis; }
	btRigidBody* fork() { return m_fork; }
	btRigidBody* load() { return m_load; }
	btSliderConstraint& slider() { return *m_slider; }
	btRaycastVehicle& vehicle() { return *m_vehicle; }
	/// A driver's keys: throttle in [-1, 1] towards 2 m/s (negative: reverse), steering in [-1, 1]
	/// (positive: left), lift in [-1, 1] at 0.4 m/s along the mast, brake on or off.
	void drive(btScalar throttle, btScalar steering, btScalar lift, bool brake);

private:
	btRigidBody* box(const btVector3& halfExtents, btScalar mass, const btVector3& origin, btScalar friction = 1);

	btDefaultCollisionConfiguration m_configuration;
	btCollisionDispatcher m_dispatcher{&m_configuration};
	btDbvtBroadphase m_broadphase;
	btSequentialImpulseConstraintSolver m_solver;
	btDiscreteDynamicsWorld m_world{&m_dispatcher, &m_broadphase, &m_solver, &m_configuration};
	btAlignedObjectArray<btCollisionShape*> m_shapes;
	btAlignedObjectArray<btRigidBody*> m_bodies;
	btRigidBody* m_load = nullptr;
	btRigidBody* m_chassis = nullptr;
	btRigidBody* m_mast = nullptr;
	btRigidBody* m_fork = nullptr;
	std::unique_ptr<btHingeConstraint> m_hinge;
	std::unique_ptr<btSliderConstraint> m_slider;
	btRaycastVehicle::btVehicleTuning m_tuning;
	std::unique_ptr<btDefaultVehicleRaycaster> m_raycaster;
	std::unique_ptr<btRaycastVehicle> m_vehicle;
};
}  // namespace fork_lift_demo

#endif
