// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BspScene.h"

namespace bsp_demo
{
Scene::Scene(btCollisionShape* level)
{
	world().setGravity(btVector3(0, 0, btScalar(-9.81)));
	m_level.reset(new btRigidBody(0, nullptr, level));
	world().addRigidBody(m_level.get());

	btCollisionShape* shapes[3] = {&m_sphere, &m_box, &m_cylinder};
	for (int i = 0; i < 40; ++i)
	{
		btCollisionShape* shape = shapes[i % 3];
		btVector3 inertia;
		shape->calculateLocalInertia(1, inertia);
		// An 8 x 5 grid 1.6 m apart covering pillars (4, 4), (4, -4), (-4, 5) and the ramp (x -7 to -3).
		const btScalar x = btScalar(1.6) * btScalar(i % 8) - btScalar(5.6);
		const btScalar y = btScalar(1.6) * btScalar(i / 8) - btScalar(3.2) + btScalar(0.5) * btScalar(i % 2);
		btTransform pose(btQuaternion(btVector3(1, 0, 1).normalized(), btScalar(0.4) * btScalar(i)),
		                 btVector3(x, y, btScalar(3 + (i % 4) * 2)));
		std::unique_ptr<btRigidBody> body(new btRigidBody(1, nullptr, shape, inertia));
		body->setWorldTransform(pose);
		body->setFriction(btScalar(0.7));
		body->setRollingFriction(btScalar(0.05));
		world().addRigidBody(body.get());
		m_bodies.push_back(std::move(body));
	}
	// One box over each pillar top (1 m across, 6 m up).
	const btVector3 pillarTops[4] = {btVector3(4, 4, 9), btVector3(4, -4, 9), btVector3(-4, 5, 9), btVector3(0, -5, 9)};
	for (const btVector3& top : pillarTops)
	{
		btVector3 inertia;
		m_box.calculateLocalInertia(1, inertia);
		std::unique_ptr<btRigidBody> body(new btRigidBody(1, nullptr, &m_box, inertia));
		body->setWorldTransform(btTransform(btQuaternion::getIdentity(), top));
		body->setFriction(btScalar(0.7));
		world().addRigidBody(body.get());
		m_bodies.push_back(std::move(body));
	}
}

Scene::~Scene()
{
	for (const auto& body : m_bodies) world().removeRigidBody(body.get());
	world().removeRigidBody(m_level.get());
}
}  // namespace bsp_demo
