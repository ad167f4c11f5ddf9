// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_DYNAMICS_WORLD_TEST_UTIL_H
#define CALIBER_TESTS_DYNAMICS_WORLD_TEST_UTIL_H

// A complete rigid-body world for tests: it owns its configuration, dispatcher, broadphase, solver,
// shapes, motion states and bodies, and deletes them in the right order.

#include <memory>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "btBulletDynamicsCommon.h"

namespace caliber_test
{
class TestWorld
{
public:
	explicit TestWorld(const btVector3& gravity = btVector3(0, -10, 0))
	    : m_configuration(new btDefaultCollisionConfiguration()),
	      m_dispatcher(new btCollisionDispatcher(m_configuration.get())),
	      m_broadphase(new btDbvtBroadphase()),
	      m_solver(new btSequentialImpulseConstraintSolver()),
	      m_world(new btDiscreteDynamicsWorld(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
	                                          m_configuration.get()))
	{
		m_world->setGravity(gravity);
	}

	/// A plain world on broadphase (taken over; btDbvtBroadphase by default).
	explicit TestWorld(btBroadphaseInterface* broadphase, const btVector3& gravity = btVector3(0, -10, 0))
	    : m_configuration(new btDefaultCollisionConfiguration()),
	      m_dispatcher(new btCollisionDispatcher(m_configuration.get())),
	      m_broadphase(broadphase),
	      m_solver(new btSequentialImpulseConstraintSolver()),
	      m_world(new btDiscreteDynamicsWorld(m_dispatcher.get(), m_broadphase.get(), m_solver.get(),
	                                          m_configuration.get()))
	{
		m_world->setGravity(gravity);
	}

	/// Tag for the multithreaded constructor.
	struct Multithreaded
	{
	};
	/// Bullet 2.89's multithreaded world (btCollisionDispatcherMt, a btConstraintSolverPoolMt of poolSize
	/// solvers and a btSequentialImpulseConstraintSolverMt for large islands); solver() is then null.
	TestWorld(Multithreaded, int poolSize, const btVector3& gravity = btVector3(0, -10, 0))
	    : m_configuration(new btDefaultCollisionConfiguration()),
	      m_dispatcher(new btCollisionDispatcherMt(m_configuration.get())),
	      m_broadphase(new btDbvtBroadphase()),
	      m_solverPool(new btConstraintSolverPoolMt(poolSize)),
	      m_solverMt(new btSequentialImpulseConstraintSolverMt())
	{
		m_world.reset(new btDiscreteDynamicsWorldMt(m_dispatcher.get(), m_broadphase.get(), m_solverPool.get(),
		                                            m_solverMt.get(), m_configuration.get()));
		m_world->setGravity(gravity);
	}

	~TestWorld()
	{
		for (auto& constraint : m_constraints) m_world->removeConstraint(constraint.get());
		for (btRigidBody* body : m_bodies)
		{
			if (body->isInWorld() || body->getWorldArrayIndex() >= 0) m_world->removeRigidBody(body);
			delete body;
		}
		m_world.reset();
	}

	btDiscreteDynamicsWorld* world() { return m_world.get(); }
	btCollisionDispatcher* dispatcher() { return m_dispatcher.get(); }
	btSequentialImpulseConstraintSolver* solver() { return m_solver.get(); }

	/// A shape kept alive for the world's lifetime.
	template <class Shape, class... Args>
	Shape* shape(Args&&... args)
	{
		Shape* s = new Shape(std::forward<Args>(args)...);
		m_shapes.emplace_back(s);
		return s;
	}

	/// A body of the given mass (0: static) at pose, with the shape's inertia, added to the world.
	btRigidBody* addBody(btCollisionShape* collisionShape, btScalar mass, const btTransform& pose,
	                     bool withMotionState = true)
	{
		btRigidBody* body = makeBody(collisionShape, mass, pose, withMotionState);
		m_world->addRigidBody(body);
		return body;
	}

	/// The same without motion state, in collision group `group` and meeting only the groups in `mask`.
	btRigidBody* addFilteredBody(btCollisionShape* collisionShape, btScalar mass, const btVector3& origin, int group,
	                             int mask)
	{
		btRigidBody* body = makeBody(collisionShape, mass, btTransform(btQuaternion::getIdentity(), origin), false);
		m_world->addRigidBody(body, group, mask);
		return body;
	}

	btRigidBody* addBody(btCollisionShape* collisionShape, btScalar mass, const btVector3& origin,
	                     bool withMotionState = true)
	{
		return addBody(collisionShape, mass, btTransform(btQuaternion::getIdentity(), origin), withMotionState);
	}

	/// A static box whose top face is the plane y = 0 (100 x 100 units).
	btRigidBody* addGround(btScalar friction = btScalar(1), btScalar restitution = btScalar(1))
	{
		btRigidBody* ground = addBody(shape<btBoxShape>(btVector3(50, 1, 50)), 0, btVector3(0, -1, 0));
		ground->setFriction(friction);
		ground->setRestitution(restitution);
		return ground;
	}

	/// A joint kept alive for the world's lifetime and added to it.
	template <class Joint, class... Args>
	Joint* addJoint(bool disableCollisionsBetweenLinkedBodies, Args&&... args)
	{
		Joint* joint = new Joint(std::forward<Args>(args)...);
		m_constraints.emplace_back(joint);
		m_world->addConstraint(joint, disableCollisionsBetweenLinkedBodies);
		return joint;
	}

	/// Steps n fixed substeps of h.
	void run(int n, btScalar h = btScalar(1. / 60.))
	{
		for (int i = 0; i < n; ++i) m_world->stepSimulation(h, 1, h);
	}

	const std::vector<btRigidBody*>& bodies() const { return m_bodies; }

	/// Keeps object (anything a scene needs besides shapes, bodies and joints: vehicles, ghosts, their
	/// callbacks) until after the world is gone.
	template <class T>
	T* keep(T* object)
	{
		m_kept.emplace_back(object);
		return object;
	}

private:
	btRigidBody* makeBody(btCollisionShape* collisionShape, btScalar mass, const btTransform& pose,
	                      bool withMotionState)
	{
		btVector3 inertia(0, 0, 0);
		if (mass > 0) collisionShape->calculateLocalInertia(mass, inertia);
		btDefaultMotionState* motion = 0;
		if (withMotionState)
		{
			motion = new btDefaultMotionState(pose);
			m_motionStates.emplace_back(motion);
		}
		btRigidBody::btRigidBodyConstructionInfo info(mass, motion, collisionShape, inertia);
		info.m_startWorldTransform = pose;
		btRigidBody* body = new btRigidBody(info);
		m_bodies.push_back(body);
		return body;
	}

	// First, so destroyed last: kept objects may be referred to by the world until it is gone.
	std::vector<std::shared_ptr<void>> m_kept;
	std::unique_ptr<btDefaultCollisionConfiguration> m_configuration;
	std::unique_ptr<btCollisionDispatcher> m_dispatcher;
	std::unique_ptr<btBroadphaseInterface> m_broadphase;
	std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
	std::unique_ptr<btConstraintSolverPoolMt> m_solverPool;
	std::unique_ptr<btSequentialImpulseConstraintSolverMt> m_solverMt;
	std::unique_ptr<btDiscreteDynamicsWorld> m_world;
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btDefaultMotionState>> m_motionStates;
	std::vector<btRigidBody*> m_bodies;
	std::vector<std::unique_ptr<btTypedConstraint>> m_constraints;
};

/// Counts the warnings reported through btReportWarning while it lives.
class WarningCounter
{
public:
	WarningCounter() { btSetWarningHook(&WarningCounter::hook, this); }
	~WarningCounter() { btSetWarningHook(0, 0); }
	int count() const { return m_count; }

private:
	static void hook(const char*, void* self) { ++static_cast<WarningCounter*>(self)->m_count; }
	int m_count = 0;
};
}  // namespace caliber_test

#endif  // CALIBER_TESTS_DYNAMICS_WORLD_TEST_UTIL_H
