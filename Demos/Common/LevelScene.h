// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_LEVEL_SCENE_H
#define CALIBER_DEMOS_COMMON_LEVEL_SCENE_H
// A demo world around a static level (a loaded map or mesh, whose shape belongs to the caller) with
// bodies dropped into it: BspDemo's and ObjDemo's scenes. The bodies and the level leave the world
// before it goes; shapes the scene made itself outlive both. Demo-side code.

#include <memory>
#include <vector>

#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace caliber
{
namespace demo
{
class LevelScene
{
public:
	LevelScene(btCollisionShape* level, const btVector3& gravity)
	{
		world().setGravity(gravity);
		m_level.reset(new btRigidBody(0, nullptr, level));
		world().addRigidBody(m_level.get());
	}
	~LevelScene()
	{
		for (const auto& body : m_bodies) world().removeRigidBody(body.get());
		world().removeRigidBody(m_level.get());
	}
	LevelScene(const LevelScene&) = delete;
	LevelScene& operator=(const LevelScene&) = delete;

	btDiscreteDynamicsWorld& world() { return m_physics.world(); }
	const std::vector<std::unique_ptr<btRigidBody>>& bodies() const { return m_bodies; }

	/// Keeps shape for the scene's life.
	template <class Shape>
	Shape* own(Shape* shape)
	{
		m_shapes.emplace_back(shape);
		return shape;
	}
	/// Drops a body of mass 1 with shape (which must outlive the scene) at pose into the world.
	btRigidBody* addBody(btCollisionShape* shape, const btTransform& pose, btScalar friction = btScalar(0.5),
	                     btScalar rollingFriction = btScalar(0))
	{
		btVector3 inertia;
		shape->calculateLocalInertia(1, inertia);
		m_bodies.emplace_back(new btRigidBody(1, nullptr, shape, inertia));
		btRigidBody* body = m_bodies.back().get();
		body->setWorldTransform(pose);
		body->setFriction(friction);
		body->setRollingFriction(rollingFriction);
		world().addRigidBody(body);
		return body;
	}

private:
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;  // first in, last out
	DemoWorld m_physics;
	std::unique_ptr<btRigidBody> m_level;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
};
}  // namespace demo
}  // namespace caliber

#endif
