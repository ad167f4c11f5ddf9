// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Dynamics/btSimpleDynamicsWorld.h"

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletDynamics/ConstraintSolver/btConstraintSolver.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btMotionState.h"
#include "LinearMath/btWarningHook.h"

btSimpleDynamicsWorld::btSimpleDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
                                             btConstraintSolver* constraintSolver,
                                             btCollisionConfiguration* collisionConfiguration)
    : btDynamicsWorld(dispatcher, pairCache, collisionConfiguration),
      m_constraintSolver(constraintSolver),
      m_ownsConstraintSolver(false),
      m_gravity(0, 0, -10)
{
	btAssert(constraintSolver && "btSimpleDynamicsWorld needs a constraint solver");
}

btSimpleDynamicsWorld::~btSimpleDynamicsWorld() {}

int btSimpleDynamicsWorld::stepSimulation(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
	(void)maxSubSteps;
	(void)fixedTimeStep;
	const bool valid = btIsFinite(timeStep) && timeStep >= btScalar(0);
	btAssert(valid && "btSimpleDynamicsWorld::stepSimulation: bad time step");
	if (!valid)
	{
		btReportWarning("Caliber: stepSimulation: time step not finite and >= 0; step ignored\n", getDebugDrawer());
		return 0;
	}
	if (timeStep == btScalar(0) || !m_constraintSolver) return 0;

	predictUnconstraintMotion(timeStep);
	btDispatcherInfo& dispatchInfo = getDispatchInfo();
	dispatchInfo.m_timeStep = timeStep;
	dispatchInfo.m_stepCount = 0;
	dispatchInfo.m_debugDraw = getDebugDrawer();
	performDiscreteCollisionDetection();

	// Every body and manifold in one group (the array keeps its capacity from step to step).
	btAlignedObjectArray<btCollisionObject*>& bodies = m_solverBodies;
	bodies.resize(0);
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i]);
		if (body && !body->isStaticOrKinematicObject()) bodies.push_back(body);
	}
	const int numManifolds = m_dispatcher1->getNumManifolds();
	btPersistentManifold** manifolds = numManifolds ? m_dispatcher1->getInternalManifoldPointer() : 0;
	btContactSolverInfo info = getSolverInfo();
	info.m_timeStep = timeStep;
	m_constraintSolver->prepareSolve(bodies.size(), numManifolds);
	m_constraintSolver->solveGroup(bodies.size() ? &bodies[0] : 0, bodies.size(), manifolds, numManifolds, 0, 0, info,
	                               getDebugDrawer(), m_dispatcher1);
	m_constraintSolver->allSolved(info, getDebugDrawer());

	integrateTransforms(timeStep);
	updateAabbs();
	synchronizeMotionStates();
	clearForces();
	return 1;
}

void btSimpleDynamicsWorld::predictUnconstraintMotion(btScalar timeStep)
{
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i]);
		if (!body || body->isStaticObject() || !body->isActive()) continue;
		body->applyGravity();
		body->integrateVelocities(timeStep);
		body->applyDamping(timeStep);
		body->predictIntegratedTransform(timeStep, body->getInterpolationWorldTransform());
	}
}

void btSimpleDynamicsWorld::integrateTransforms(btScalar timeStep)
{
	btTransform predictedTrans;
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i]);
		if (!body || !body->isActive() || body->isStaticOrKinematicObject()) continue;
		body->predictIntegratedTransform(timeStep, predictedTrans);
		body->proceedToTransform(predictedTrans);
	}
}

void btSimpleDynamicsWorld::setGravity(const btVector3& gravity)
{
	m_gravity = gravity;
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i]);
		if (body && !(body->getFlags() & BT_DISABLE_WORLD_GRAVITY)) body->setGravity(gravity);
	}
}

btVector3 btSimpleDynamicsWorld::getGravity() const { return m_gravity; }

void btSimpleDynamicsWorld::addRigidBody(btRigidBody* body)
{
	btAssert(body);
	if (!body) return;
	if (!(body->getFlags() & BT_DISABLE_WORLD_GRAVITY)) body->setGravity(m_gravity);
	if (body->getCollisionShape()) addCollisionObject(body);
}

void btSimpleDynamicsWorld::addRigidBody(btRigidBody* body, int group, int mask)
{
	btAssert(body);
	if (!body) return;
	if (!(body->getFlags() & BT_DISABLE_WORLD_GRAVITY)) body->setGravity(m_gravity);
	if (body->getCollisionShape()) addCollisionObject(body, group, mask);
}

void btSimpleDynamicsWorld::removeRigidBody(btRigidBody* body) { btCollisionWorld::removeCollisionObject(body); }

void btSimpleDynamicsWorld::removeCollisionObject(btCollisionObject* collisionObject)
{
	btCollisionWorld::removeCollisionObject(collisionObject);
}

void btSimpleDynamicsWorld::debugDrawWorld() { btCollisionWorld::debugDrawWorld(); }

void btSimpleDynamicsWorld::addAction(btActionInterface* action)
{
	(void)action;
	btReportWarning("Caliber: btSimpleDynamicsWorld does not run actions; use btDiscreteDynamicsWorld\n",
	                getDebugDrawer());
}

void btSimpleDynamicsWorld::removeAction(btActionInterface* action) { (void)action; }

void btSimpleDynamicsWorld::updateAabbs()
{
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		btCollisionObject* object = m_collisionObjects[i];
		if (object->isActive() && !object->isStaticObject()) updateSingleAabb(object);
	}
}

void btSimpleDynamicsWorld::synchronizeMotionStates()
{
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i]);
		if (body && body->getMotionState() && !body->isStaticOrKinematicObject() &&
		    body->getActivationState() != ISLAND_SLEEPING)
			body->getMotionState()->setWorldTransform(body->getWorldTransform());
	}
}

void btSimpleDynamicsWorld::setConstraintSolver(btConstraintSolver* solver)
{
	btAssert(solver);
	if (solver) m_constraintSolver = solver;
}

btConstraintSolver* btSimpleDynamicsWorld::getConstraintSolver() { return m_constraintSolver; }

void btSimpleDynamicsWorld::clearForces()
{
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i]);
		if (body) body->clearForces();
	}
}
