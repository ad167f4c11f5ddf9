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

namespace
{
// Contacts for the moved bodies, with the step's length on record for the algorithms that read it.
void findContacts(btCollisionWorld& world, btScalar timeStep)
{
	btDispatcherInfo& dispatchInfo = world.getDispatchInfo();
	dispatchInfo.m_debugDraw = world.getDebugDrawer();
	dispatchInfo.m_stepCount = 0;
	dispatchInfo.m_timeStep = timeStep;
	world.performDiscreteCollisionDetection();
}

// The simple world has no islands and no joints: every collision object and every manifold go to the
// solver as one group (the solver gives static and non-rigid objects its shared fixed entry).
void solveContactsAsOneGroup(btCollisionWorld& world, btConstraintSolver& solver, btContactSolverInfo info,
                             btScalar timeStep)
{
	btCollisionObjectArray& objects = world.getCollisionObjectArray();
	btDispatcher* dispatcher = world.getDispatcher();
	const int numManifolds = dispatcher->getNumManifolds();
	btPersistentManifold** manifolds = numManifolds ? dispatcher->getInternalManifoldPointer() : 0;
	btCollisionObject** bodies = objects.size() ? &objects[0] : 0;
	info.m_timeStep = timeStep;
	solver.prepareSolve(objects.size(), numManifolds);
	solver.solveGroup(bodies, objects.size(), manifolds, numManifolds, 0, 0, info, world.getDebugDrawer(), dispatcher);
	solver.allSolved(info, world.getDebugDrawer());
}
}  // namespace

int btSimpleDynamicsWorld::stepSimulation(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
	// One step of exactly timeStep: this world does not substep.
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
	findContacts(*this, timeStep);
	solveContactsAsOneGroup(*this, *m_constraintSolver, getSolverInfo(), timeStep);
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
