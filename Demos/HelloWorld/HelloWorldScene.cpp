// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "HelloWorldScene.h"

namespace hello_world
{
Scene::Scene()
{
	m_world.setGravity(btVector3(0, -kGravity, 0));
	m_ground.reset(new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(0, &m_groundMotionState, &m_groundShape)));
	m_world.addRigidBody(m_ground.get());
	btVector3 ballInertia(0, 0, 0);
	m_ballShape.calculateLocalInertia(kBallMass, ballInertia);
	m_ball.reset(new btRigidBody(
	    btRigidBody::btRigidBodyConstructionInfo(kBallMass, &m_ballMotionState, &m_ballShape, ballInertia)));
	m_world.addRigidBody(m_ball.get());
}

Scene::~Scene()
{
	m_world.removeRigidBody(m_ball.get());
	m_world.removeRigidBody(m_ground.get());
}
}  // namespace hello_world
