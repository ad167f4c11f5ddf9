// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "CcdScene.h"

namespace ccd_demo
{
namespace
{
const btScalar kRadius = btScalar(0.05);
}

Scene::Scene(Mode mode)
    : m_wallShape(btVector3(btScalar(0.005), 10, 10)),
      m_ballShape(kRadius)
{
	world().setGravity(btVector3(0, -10, 0));
	world().getDispatchInfo().m_useContinuous = mode != kDiscreteOnly;

	// The wall: the slab 0 <= x <= 0.01, 20 m wide and tall.
	btRigidBody::btRigidBodyConstructionInfo wallInfo(0, 0, &m_wallShape);
	wallInfo.m_startWorldTransform.setOrigin(btVector3(btScalar(0.005), 0, 0));
	m_wall.reset(new btRigidBody(wallInfo));
	world().addRigidBody(m_wall.get());

	btVector3 inertia;
	m_ballShape.calculateLocalInertia(btScalar(0.1), inertia);
	for (int i = 0; i < 20; ++i)
	{
		btRigidBody::btRigidBodyConstructionInfo info(btScalar(0.1), 0, &m_ballShape, inertia);
		info.m_startWorldTransform.setOrigin(
		    btVector3(-5, btScalar(-4.5) + btScalar(0.5) * i, btScalar(0.3) * (i % 5)));
		m_balls.emplace_back(new btRigidBody(info));
		btRigidBody* ball = m_balls.back().get();
		ball->setLinearVelocity(btVector3(btScalar(100) + btScalar(10) * i, 0, 0));
		if (mode == kSweptCcd)
		{
			// Sweep whenever a step moves the ball more than its radius.
			ball->setCcdMotionThreshold(kRadius);
			ball->setCcdSweptSphereRadius(kRadius);
		}
		world().addRigidBody(ball);
	}
}

Scene::~Scene()
{
	for (auto& ball : m_balls) world().removeRigidBody(ball.get());
	world().removeRigidBody(m_wall.get());
}

int Scene::spheresThrough() const
{
	int through = 0;
	for (const auto& ball : m_balls)
		if (ball->getCenterOfMassPosition().getX() > 0) ++through;
	return through;
}
}  // namespace ccd_demo
