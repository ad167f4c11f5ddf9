// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_CONSTRAINT_SCENE_H
#define CALIBER_DEMOS_CONSTRAINT_SCENE_H
// ConstraintDemo's scene: one of each joint type at work in a row along x (a ball-joint pendulum, a
// limited door hinge pushed by a flipping torque, a hinge motor, a cone-twist limb, a motorised slider,
// gears, a 6-DoF spring, a fixed joint, a Cardan joint). Used by ConstraintDemo, which measures it,
// and by the demo browser.

#include <memory>
#include <vector>

#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace constraint_demo
{
/// The world with every joint, and the bodies and joints the demo measures.
class Scene
{
public:
	Scene();
	~Scene();
	btDiscreteDynamicsWorld& world() { return m_physics.world(); }
	/// Step frame (1-based) of the run: the door's torque (flipping every second), then one 1/60 s step.
	void step(int frame);

	btRigidBody* bob = nullptr;
	btPoint2PointConstraint* ball = nullptr;
	btRigidBody* door = nullptr;
	btHingeConstraint* doorHinge = nullptr;
	btRigidBody* wheel = nullptr;
	btHingeConstraint* axle = nullptr;
	btRigidBody* limb = nullptr;
	btConeTwistConstraint* shoulder = nullptr;
	btRigidBody* carriage = nullptr;
	btSliderConstraint* rail = nullptr;
	btRigidBody* small = nullptr;
	btRigidBody* large = nullptr;
	btHingeConstraint* smallAxle = nullptr;
	btRigidBody* weight = nullptr;
	btGeneric6DofSpring2Constraint* spring = nullptr;
	btRigidBody* armA = nullptr;
	btRigidBody* armB = nullptr;
	btRigidBody* input = nullptr;
	btRigidBody* output = nullptr;
	btHingeConstraint* inputBearing = nullptr;
	/// The Cardan joint's bend, and the output shaft's axis.
	const btScalar bend = SIMD_PI / 6;
	const btVector3 outputAxis{btCos(SIMD_PI / 6), btSin(SIMD_PI / 6), 0};

private:
	btRigidBody* body(btCollisionShape* shape, btScalar mass, const btTransform& pose);
	template <class Joint>
	Joint* joint(Joint* j)
	{
		m_joints.emplace_back(j);
		world().addConstraint(j, true);
		return j;
	}

	caliber::demo::DemoWorld m_physics;  // the world, first in and last out
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
	std::vector<std::unique_ptr<btTypedConstraint>> m_joints;
};
}  // namespace constraint_demo

#endif
