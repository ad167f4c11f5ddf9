// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The world's bookkeeping (bodies, actions, gravity, solver) and the step itself: stepSimulation's
// substeps and internalSingleStepSimulation's pipeline. The stages live in
// btDiscreteDynamicsWorldStages.cpp.
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"

#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btActionInterface.h"
#include "BulletDynamics/Dynamics/btInplaceSolverIslandCallback.h"
#include "BulletDynamics/Dynamics/btJointAnchorTree.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btIDebugDraw.h"
#include "LinearMath/btMotionState.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btTransformUtil.h"
#include "LinearMath/btWarningHook.h"

btDiscreteDynamicsWorld::btDiscreteDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
                                                 btConstraintSolver* constraintSolver,
                                                 btCollisionConfiguration* collisionConfiguration)
    : btDynamicsWorld(dispatcher, pairCache, collisionConfiguration),
      m_solverIslandCallback(0),
      m_constraintSolver(constraintSolver),
      m_gravity(0, -10, 0),
      m_localTime(0),
      m_fixedTimeStep(0),
      m_synchronizeAllMotionStates(false),
      m_applySpeculativeContactRestitution(false),
      m_profileTimings(0),
      m_latencyMotionStateInterpolation(true),
      m_reportedNonFiniteBody(false),
      m_jointAnchorTree(new caliber::JointAnchorTree())
{
	if (!m_constraintSolver)
	{
		void* memory = btAlignedAlloc(sizeof(btSequentialImpulseConstraintSolver), 16);
		m_constraintSolver = new (memory) btSequentialImpulseConstraintSolver;
		m_ownsConstraintSolver = true;
	}
	else
	{
		m_ownsConstraintSolver = false;
	}
	{
		void* memory = btAlignedAlloc(sizeof(btSimulationIslandManager), 16);
		m_islandManager = new (memory) btSimulationIslandManager();
	}
	m_ownsIslandManager = true;
	{
		void* memory = btAlignedAlloc(sizeof(InplaceSolverIslandCallback), 16);
		m_solverIslandCallback = new (memory) InplaceSolverIslandCallback(m_constraintSolver, dispatcher);
	}
}

btDiscreteDynamicsWorld::~btDiscreteDynamicsWorld()
{
	delete m_jointAnchorTree;
	if (m_ownsIslandManager)
	{
		m_islandManager->~btSimulationIslandManager();
		btAlignedFree(m_islandManager);
	}
	if (m_solverIslandCallback)
	{
		m_solverIslandCallback->~InplaceSolverIslandCallback();
		btAlignedFree(m_solverIslandCallback);
	}
	if (m_ownsConstraintSolver)
	{
		m_constraintSolver->~btConstraintSolver();
		btAlignedFree(m_constraintSolver);
	}
}

int btDiscreteDynamicsWorld::stepSimulation(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
	BT_PROFILE("stepSimulation");
	const bool validArguments = btIsFinite(timeStep) && timeStep >= btScalar(0) && maxSubSteps >= 0 &&
	                            (maxSubSteps == 0 || (btIsFinite(fixedTimeStep) && fixedTimeStep > btScalar(0)));
	btAssert(validArguments && "btDiscreteDynamicsWorld::stepSimulation: bad time step or substep count");
	if (!validArguments)
	{
		btReportWarning(
		    "Caliber: stepSimulation: time step not finite and >= 0, or bad substep arguments; "
		    "step ignored\n",
		    getDebugDrawer());
		return 0;
	}

	startProfiling(timeStep);
	int numSimulationSubSteps = 0;
	if (maxSubSteps)
	{
		// Fixed substeps; what is left over waits in m_localTime for the next call.
		m_localTime += timeStep;
		if (m_localTime >= fixedTimeStep)
		{
			numSimulationSubSteps = int(m_localTime / fixedTimeStep);
			m_localTime -= numSimulationSubSteps * fixedTimeStep;
		}
	}
	else
	{
		// One variable step of exactly timeStep.
		fixedTimeStep = timeStep;
		m_localTime = m_latencyMotionStateInterpolation ? btScalar(0) : timeStep;
		m_fixedTimeStep = btScalar(0);
		if (btFuzzyZero(timeStep))
		{
			numSimulationSubSteps = 0;
			maxSubSteps = 0;
		}
		else
		{
			numSimulationSubSteps = 1;
			maxSubSteps = 1;
		}
	}
	if (maxSubSteps) m_fixedTimeStep = fixedTimeStep;

	if (getDebugDrawer())
		gDisableDeactivation = (getDebugDrawer()->getDebugMode() & btIDebugDraw::DBG_NoDeactivation) != 0;

	if (numSimulationSubSteps)
	{
		// Steps beyond maxSubSteps are dropped (the simulation runs slower than real time rather than
		// spiralling into ever longer frames).
		const int clampedSimulationSteps = numSimulationSubSteps > maxSubSteps ? maxSubSteps : numSimulationSubSteps;
		saveKinematicState(fixedTimeStep * clampedSimulationSteps);
		applyGravity();
		for (int i = 0; i < clampedSimulationSteps; ++i)
		{
			internalSingleStepSimulation(fixedTimeStep);
			synchronizeMotionStates();
		}
	}
	else
	{
		synchronizeMotionStates();
	}
	clearForces();
	return numSimulationSubSteps;
}

void btDiscreteDynamicsWorld::internalSingleStepSimulation(btScalar timeStep)
{
	BT_PROFILE("internalSingleStepSimulation");
	if (m_internalPreTickCallback) (*m_internalPreTickCallback)(this, timeStep);

	quarantineNonFiniteBodies();
	predictUnconstraintMotion(timeStep);

	btDispatcherInfo& dispatchInfo = getDispatchInfo();
	dispatchInfo.m_timeStep = timeStep;
	dispatchInfo.m_stepCount = 0;
	dispatchInfo.m_debugDraw = getDebugDrawer();
	performDiscreteCollisionDetection();

	calculateSimulationIslands();

	getSolverInfo().m_timeStep = timeStep;
	solveConstraints(getSolverInfo());

	integrateTransforms(timeStep);
	correctJointPositions();
	quarantineNonFiniteBodies();

	updateActions(timeStep);
	updateActivationState(timeStep);

	if (m_internalTickCallback) (*m_internalTickCallback)(this, timeStep);
}

void btDiscreteDynamicsWorld::startProfiling(btScalar timeStep)
{
	(void)timeStep;
	++m_profileTimings;
}

void btDiscreteDynamicsWorld::setGravity(const btVector3& gravity)
{
	const bool finite = btIsFinite(gravity.x()) && btIsFinite(gravity.y()) && btIsFinite(gravity.z());
	btAssert(finite && "btDiscreteDynamicsWorld::setGravity: non-finite gravity");
	if (!finite)
	{
		btReportWarning("Caliber: setGravity: non-finite gravity ignored\n", getDebugDrawer());
		return;
	}
	m_gravity = gravity;
	for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i)
	{
		btRigidBody* body = m_nonStaticRigidBodies[i];
		if (body->isActive() && !(body->getFlags() & BT_DISABLE_WORLD_GRAVITY)) body->setGravity(gravity);
	}
}

btVector3 btDiscreteDynamicsWorld::getGravity() const { return m_gravity; }

void btDiscreteDynamicsWorld::addCollisionObject(btCollisionObject* collisionObject, int collisionFilterGroup,
                                                 int collisionFilterMask)
{
	btCollisionWorld::addCollisionObject(collisionObject, collisionFilterGroup, collisionFilterMask);
}

void btDiscreteDynamicsWorld::addRigidBody(btRigidBody* body)
{
	btAssert(body && "btDiscreteDynamicsWorld::addRigidBody: null body");
	if (!body) return;
	const bool isDynamic = !(body->isStaticObject() || body->isKinematicObject());
	const int group = isDynamic ? int(btBroadphaseProxy::DefaultFilter) : int(btBroadphaseProxy::StaticFilter);
	const int mask = isDynamic ? int(btBroadphaseProxy::AllFilter)
	                           : int(btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
	addRigidBody(body, group, mask);
}

void btDiscreteDynamicsWorld::addRigidBody(btRigidBody* body, int group, int mask)
{
	btAssert(body && "btDiscreteDynamicsWorld::addRigidBody: null body");
	if (!body) return;
	const bool alreadyAdded = body->getWorldArrayIndex() >= 0 &&
	                          body->getWorldArrayIndex() < m_collisionObjects.size() &&
	                          m_collisionObjects[body->getWorldArrayIndex()] == body;
	btAssert(!alreadyAdded && "btDiscreteDynamicsWorld::addRigidBody: body added twice");
	if (alreadyAdded)
	{
		btReportWarning("Caliber: addRigidBody: the body is already in the world; call ignored\n", getDebugDrawer());
		return;
	}
	if (!body->isStaticOrKinematicObject() && !(body->getFlags() & BT_DISABLE_WORLD_GRAVITY))
		body->setGravity(m_gravity);
	if (body->getCollisionShape())
	{
		if (!body->isStaticObject())
			m_nonStaticRigidBodies.push_back(body);
		else
			body->setActivationState(ISLAND_SLEEPING);
	}
	addCollisionObject(body, group, mask);
}

void btDiscreteDynamicsWorld::removeRigidBody(btRigidBody* body)
{
	btAssert(body && "btDiscreteDynamicsWorld::removeRigidBody: null body");
	if (!body) return;
	const bool inWorld = body->getWorldArrayIndex() >= 0 && body->getWorldArrayIndex() < m_collisionObjects.size() &&
	                     m_collisionObjects[body->getWorldArrayIndex()] == body;
	btAssert(inWorld && "btDiscreteDynamicsWorld::removeRigidBody: body is not in this world");
	if (!inWorld)
	{
		btReportWarning("Caliber: removeRigidBody: the body is not in this world; call ignored\n", getDebugDrawer());
		return;
	}
	int removedJoints = 0;
	for (int i = m_constraints.size() - 1; i >= 0; --i)
	{
		btTypedConstraint* constraint = m_constraints[i];
		if (&constraint->getRigidBodyA() != body && &constraint->getRigidBodyB() != body) continue;
		removeConstraint(constraint);
		++removedJoints;
	}
	if (removedJoints)
		btReportWarning(
		    "Caliber: removeRigidBody: the body still had joints in this world; they have been removed "
		    "from the world with it\n",
		    getDebugDrawer());
	m_nonStaticRigidBodies.remove(body);
	btCollisionWorld::removeCollisionObject(body);
}

void btDiscreteDynamicsWorld::addConstraint(btTypedConstraint* constraint, bool disableCollisionsBetweenLinkedBodies)
{
	btAssert(constraint && "btDiscreteDynamicsWorld::addConstraint: null constraint");
	if (!constraint)
	{
		btReportWarning("Caliber: addConstraint: null constraint; call ignored\n", getDebugDrawer());
		return;
	}
	btAssert(&constraint->getRigidBodyA() != &constraint->getRigidBodyB() &&
	         "btDiscreteDynamicsWorld::addConstraint: a constraint between a body and itself");
	if (&constraint->getRigidBodyA() == &constraint->getRigidBodyB())
	{
		btReportWarning("Caliber: addConstraint: the constraint links a body to itself; it is ignored\n",
		                getDebugDrawer());
		return;
	}
	btAssert(m_constraints.findLinearSearch(constraint) == m_constraints.size() &&
	         "btDiscreteDynamicsWorld::addConstraint: constraint added twice");
	if (m_constraints.findLinearSearch(constraint) != m_constraints.size())
	{
		btReportWarning("Caliber: addConstraint: the constraint is already in this world; call ignored\n",
		                getDebugDrawer());
		return;
	}
	m_constraints.push_back(constraint);
	if (disableCollisionsBetweenLinkedBodies)
	{
		// The fixed body collides with nothing and is shared by every world: it keeps no references.
		btRigidBody& fixedBody = btTypedConstraint::getFixedBody();
		if (&constraint->getRigidBodyA() != &fixedBody) constraint->getRigidBodyA().addConstraintRef(constraint);
		if (&constraint->getRigidBodyB() != &fixedBody) constraint->getRigidBodyB().addConstraintRef(constraint);
	}
}

void btDiscreteDynamicsWorld::removeConstraint(btTypedConstraint* constraint)
{
	if (!constraint) return;
	m_constraints.remove(constraint);
	constraint->getRigidBodyA().removeConstraintRef(constraint);
	constraint->getRigidBodyB().removeConstraintRef(constraint);
}

void btDiscreteDynamicsWorld::removeCollisionObject(btCollisionObject* collisionObject)
{
	btRigidBody* body = btRigidBody::upcast(collisionObject);
	if (body)
		removeRigidBody(body);
	else
		btCollisionWorld::removeCollisionObject(collisionObject);
}

void btDiscreteDynamicsWorld::addAction(btActionInterface* action)
{
	btAssert(action && "btDiscreteDynamicsWorld::addAction: null action");
	if (action) m_actions.push_back(action);
}

void btDiscreteDynamicsWorld::removeAction(btActionInterface* action) { m_actions.remove(action); }

void btDiscreteDynamicsWorld::addVehicle(btActionInterface* vehicle) { addAction(vehicle); }
void btDiscreteDynamicsWorld::removeVehicle(btActionInterface* vehicle) { removeAction(vehicle); }
void btDiscreteDynamicsWorld::addCharacter(btActionInterface* character) { addAction(character); }
void btDiscreteDynamicsWorld::removeCharacter(btActionInterface* character) { removeAction(character); }

void btDiscreteDynamicsWorld::updateActions(btScalar timeStep)
{
	BT_PROFILE("updateActions");
	// By index: an action may remove itself (or a later one) while it runs.
	for (int i = 0; i < m_actions.size(); ++i)
	{
		btActionInterface* action = m_actions[i];
		action->updateAction(this, timeStep);
		if (i < m_actions.size() && m_actions[i] != action) --i;
	}
}

void btDiscreteDynamicsWorld::setConstraintSolver(btConstraintSolver* solver)
{
	btAssert(solver && "btDiscreteDynamicsWorld::setConstraintSolver: null solver");
	if (!solver) return;
	if (m_ownsConstraintSolver)
	{
		m_constraintSolver->~btConstraintSolver();
		btAlignedFree(m_constraintSolver);
	}
	m_ownsConstraintSolver = false;
	m_constraintSolver = solver;
	m_solverIslandCallback->m_solver = solver;
}

btConstraintSolver* btDiscreteDynamicsWorld::getConstraintSolver() { return m_constraintSolver; }

void btDiscreteDynamicsWorld::clearForces()
{
	for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i) m_nonStaticRigidBodies[i]->clearForces();
}

void btDiscreteDynamicsWorld::applyGravity()
{
	for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i)
	{
		btRigidBody* body = m_nonStaticRigidBodies[i];
		if (body->isActive()) body->applyGravity();
	}
}

void btDiscreteDynamicsWorld::synchronizeSingleMotionState(btRigidBody* body)
{
	btAssert(body);
	if (!body || !body->getMotionState() || body->isStaticOrKinematicObject()) return;
	// With latency interpolation the pose handed out lies between the last two substeps (m_localTime -
	// m_fixedTimeStep is in [-fixedTimeStep, 0)); without it, the pose is extrapolated by m_localTime.
	const btScalar interpolationTime = (m_latencyMotionStateInterpolation && m_fixedTimeStep != btScalar(0))
	                                       ? m_localTime - m_fixedTimeStep
	                                       : m_localTime * body->getHitFraction();
	btTransform interpolatedTransform;
	btTransformUtil::integrateTransform(body->getInterpolationWorldTransform(), body->getInterpolationLinearVelocity(),
	                                    body->getInterpolationAngularVelocity(), interpolationTime,
	                                    interpolatedTransform);
	body->getMotionState()->setWorldTransform(interpolatedTransform);
}

void btDiscreteDynamicsWorld::synchronizeMotionStates()
{
	BT_PROFILE("synchronizeMotionStates");
	if (m_synchronizeAllMotionStates)
	{
		for (int i = 0; i < m_collisionObjects.size(); ++i)
		{
			btRigidBody* body = btRigidBody::upcast(m_collisionObjects[i]);
			if (body) synchronizeSingleMotionState(body);
		}
		return;
	}
	for (int i = 0; i < m_nonStaticRigidBodies.size(); ++i)
	{
		btRigidBody* body = m_nonStaticRigidBodies[i];
		if (body->isActive()) synchronizeSingleMotionState(body);
	}
}

void btDiscreteDynamicsWorld::debugDrawWorld()
{
	BT_PROFILE("debugDrawWorld");
	btCollisionWorld::debugDrawWorld();
	btIDebugDraw* drawer = getDebugDrawer();
	if (!drawer) return;
	const int mode = drawer->getDebugMode();
	if (mode & (btIDebugDraw::DBG_DrawWireframe | btIDebugDraw::DBG_DrawAabb))
	{
		for (int i = 0; i < m_actions.size(); ++i) m_actions[i]->debugDraw(drawer);
	}
	if (mode & (btIDebugDraw::DBG_DrawConstraints | btIDebugDraw::DBG_DrawConstraintLimits))
	{
		for (int i = m_constraints.size() - 1; i >= 0; --i) debugDrawConstraint(m_constraints[i]);
	}
}
