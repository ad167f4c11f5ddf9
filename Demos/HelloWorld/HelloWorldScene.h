// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_HELLO_WORLD_SCENE_H
#define CALIBER_DEMOS_HELLO_WORLD_SCENE_H
// HelloWorld's scene, the Bullet manual's first program: a world with the default collision
// configuration, a dbvt broadphase and the sequential-impulse solver, gravity 10 m/s^2 down; a static
// ground box whose top face is y = 0; a 1 kg ball of radius 1 m released at y = 10. Used by
// HelloWorld, which checks the fall, and by the demo browser.

#include <memory>

#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace hello_world
{
const btScalar kGravity = 10;
const btScalar kBallMass = 1, kBallRadius = 1, kReleaseHeight = 10;

/// The world, the ground and the ball, ready to step.
class Scene
{
public:
	Scene();
	~Scene();
	btDiscreteDynamicsWorld& world() { return m_world; }
	/// The ball's motion state: where HelloWorld reads the ball's height, as the manual does.
	btDefaultMotionState& ballMotionState() { return m_ballMotionState; }

private:
	caliber::demo::DemoWorld m_demoWorld;  // the demos' usual world
	btDiscreteDynamicsWorld& m_world{m_demoWorld.world()};
	btBoxShape m_groundShape{btVector3(50, 50, 50)};
	btDefaultMotionState m_groundMotionState{btTransform(btQuaternion::getIdentity(), btVector3(0, -50, 0))};
	std::unique_ptr<btRigidBody> m_ground;
	btSphereShape m_ballShape{kBallRadius};
	btDefaultMotionState m_ballMotionState{btTransform(btQuaternion::getIdentity(), btVector3(0, kReleaseHeight, 0))};
	std::unique_ptr<btRigidBody> m_ball;
};
}  // namespace hello_world

#endif
