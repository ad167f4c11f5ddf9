// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_CHARACTER_SCENE_H
#define CALIBER_DEMOS_CHARACTER_SCENE_H
// CharacterDemo's course: a kinematic character (a capsule of radius 0.3 m and height 1.6 m on a ghost
// object, step height 0.35 m) and its lanes along +z, one every 10 m of x: flat ground, stairs of
// 0.3 m (x = 10), 30 and 50 degree slopes (x = 20, 30), a 10 cm wall (x = 50) and a kinematic platform
// (x = 60). Used by CharacterDemo, which scripts and measures it, and by the demo browser, where the
// keys walk the character.

#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletDynamics/Character/btKinematicCharacterController.h"
#include "btBulletDynamicsCommon.h"

namespace character_demo
{
const btScalar kStep = btScalar(1. / 60.);
const btScalar kRadius = btScalar(0.3), kCylinder = btScalar(1.0), kHalfHeight = kRadius + kCylinder / 2;

class Scene
{
public:
	Scene();
	~Scene();
	Scene(const Scene&) = delete;
	Scene& operator=(const Scene&) = delete;
	btDiscreteDynamicsWorld& world() { return m_world; }
	btKinematicCharacterController& character() { return m_character; }
	btPairCachingGhostObject& ghost() { return m_ghost; }
	/// The kinematic platform of the last lane.
	btRigidBody* platform() { return m_platform; }
	/// The character's feet (the bottom of its capsule).
	btVector3 feet() const;
	/// A walker's keys for the next step: forward in [-1, 1] at 3 m/s along the heading, turn in [-1, 1]
	/// at 2 rad/s (positive: left), jump when on the ground.
	void walk(btScalar forward, btScalar turn, bool jump);

private:
	btRigidBody* box(const btVector3& halfExtents, const btTransform& pose, bool kinematic = false);

	btDefaultCollisionConfiguration m_configuration;
	btCollisionDispatcher m_dispatcher{&m_configuration};
	btDbvtBroadphase m_broadphase;
	btSequentialImpulseConstraintSolver m_solver;
	btDiscreteDynamicsWorld m_world{&m_dispatcher, &m_broadphase, &m_solver, &m_configuration};
	btGhostPairCallback m_ghostCallback;
	btAlignedObjectArray<btCollisionShape*> m_shapes;
	btAlignedObjectArray<btRigidBody*> m_bodies;
	btRigidBody* m_platform = nullptr;
	btCapsuleShape m_capsule{kRadius, kCylinder};
	btPairCachingGhostObject m_ghost;
	btKinematicCharacterController m_character{&m_ghost, &m_capsule, btScalar(0.35), btVector3(0, 1, 0)};
	btScalar m_heading = 0;  // radians about +y; 0 walks along +z
};
}  // namespace character_demo

#endif
