// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "CharacterScene.h"

namespace character_demo
{
namespace
{
btTransform at(btScalar x, btScalar y, btScalar z) { return btTransform(btQuaternion::getIdentity(), btVector3(x, y, z)); }
btTransform tilted(btScalar degrees, btScalar x, btScalar footZ, btScalar halfLength, btScalar halfThickness)
{
	// A plank rising towards +z from its foot at (x, 0, footZ).
	const btScalar a = btRadians(degrees);
	return btTransform(btQuaternion(btVector3(1, 0, 0), -a),
	                   btVector3(x, halfLength * btSin(a) - halfThickness / btCos(a), footZ + halfLength * btCos(a)));
}
}  // namespace

Scene::Scene()
{
	m_world.setGravity(btVector3(0, -10, 0));
	m_broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&m_ghostCallback);
	box(btVector3(100, 1, 100), at(0, -1, 0));  // the ground, top at y = 0
	// Stairs in lane x = 10: four steps of 0.3 m, 1 m deep, from z = 2.
	for (int i = 0; i < 4; ++i)
	{
		const btScalar top = btScalar(0.3) * (i + 1);
		box(btVector3(1, top / 2, btScalar(0.5)), at(10, top / 2, btScalar(2.5) + i));
	}
	box(btVector3(1, btScalar(0.6), 3), at(10, btScalar(0.6), btScalar(8.5)));  // landing at 1.2 m
	box(btVector3(1, btScalar(0.5), 10), tilted(30, 20, 2, 10, btScalar(0.5)));
	box(btVector3(1, btScalar(0.5), 10), tilted(50, 30, 2, 10, btScalar(0.5)));
	box(btVector3(2, 2, btScalar(0.05)), at(50, 2, 5));  // a 10 cm wall
	m_platform = box(btVector3(2, btScalar(0.1), 2), at(60, btScalar(1), 0), true);

	m_ghost.setCollisionShape(&m_capsule);
	m_ghost.setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
	m_ghost.setWorldTransform(at(0, kHalfHeight, 0));
	m_world.addCollisionObject(&m_ghost, btBroadphaseProxy::CharacterFilter,
	                           btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter |
	                               btBroadphaseProxy::KinematicFilter);
	m_world.addAction(&m_character);
}

Scene::~Scene()
{
	m_world.removeAction(&m_character);
	m_world.removeCollisionObject(&m_ghost);
	for (int i = 0; i < m_bodies.size(); ++i)
	{
		m_world.removeRigidBody(m_bodies[i]);
		delete m_bodies[i]->getMotionState();
		delete m_bodies[i];
	}
	for (int i = 0; i < m_shapes.size(); ++i) delete m_shapes[i];
}

btRigidBody* Scene::box(const btVector3& halfExtents, const btTransform& pose, bool kinematic)
{
	btBoxShape* shape = new btBoxShape(halfExtents);
	shape->setMargin(0);  // sharp edges: step heights are exact
	m_shapes.push_back(shape);
	btRigidBody* body =
	    new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(0, new btDefaultMotionState(pose), shape));
	if (kinematic)
	{
		body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
		body->setActivationState(DISABLE_DEACTIVATION);
	}
	m_bodies.push_back(body);
	m_world.addRigidBody(body);
	return body;
}

btVector3 Scene::feet() const { return m_ghost.getWorldTransform().getOrigin() - btVector3(0, kHalfHeight, 0); }

void Scene::walk(btScalar forward, btScalar turn, bool jump)
{
	m_heading += btScalar(2) * kStep * btMax(btScalar(-1), btMin(btScalar(1), turn));
	const btScalar speed = btScalar(3) * kStep * btMax(btScalar(-1), btMin(btScalar(1), forward));
	m_character.setWalkDirection(btVector3(btSin(m_heading), 0, btCos(m_heading)) * speed);
	if (jump && m_character.canJump()) m_character.jump();
}
}  // namespace character_demo
