// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The world's bookkeeping (bodies, actions, gravity, solver) and the step itself: stepSimulation's
// substeps and internalSingleStepSimulation's pipeline. The stages live in
// btDiscreteDynamicsWorldStages.cpp.
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"

#include <cstring>
#include <typeinfo>

#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btActionInterface.h"
#include "BulletDynamics/Dynamics/btInplaceSolverIslandCallback.h"
#include "BulletDynamics/Dynamics/btPredictionPrologue.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "BulletDynamics/Dynamics/btSpeculativeContactRestitution.h"
#include "BulletDynamics/Dynamics/btWorldStepContext.h"
#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "LinearMath/btAlignedObject.h"
#include "LinearMath/btDefaultMotionState.h"
#include "LinearMath/btIDebugDraw.h"
#include "LinearMath/btMotionState.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btTransformUtil.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// stepSimulation's bookkeeping of time, as a pure function of the call and the world's clock.
struct SubstepPlan
{
	int substepsDue;          // whole substeps the clock has reached (stepSimulation's return value)
	int substepsToRun;        // substepsDue capped at the call's maxSubSteps
	btScalar substepSeconds;  // length of each substep run
	btScalar localTime;       // the world's new m_localTime
	btScalar fixedTimeStep;   // the world's new m_fixedTimeStep (0 after a zero-length variable step)
};

// With maxSubSteps > 0 time accumulates in localTime and leaves it in whole fixed substeps; the rest
// waits for the next call. With maxSubSteps == 0 the call is one variable substep of exactly timeStep
// (none when timeStep is about zero). Substeps beyond maxSubSteps are dropped: the simulation runs
// slower than real time rather than spiralling into ever longer frames.
SubstepPlan planSubsteps(btScalar localTime, bool latencyInterpolation, btScalar timeStep, int maxSubSteps,
                         btScalar fixedTimeStep)
{
	SubstepPlan plan;
	if (maxSubSteps == 0)
	{
		const int substeps = btFuzzyZero(timeStep) ? 0 : 1;
		plan.substepsDue = substeps;
		plan.substepsToRun = substeps;
		plan.substepSeconds = timeStep;
		plan.localTime = latencyInterpolation ? btScalar(0) : timeStep;
		plan.fixedTimeStep = substeps ? timeStep : btScalar(0);
		return plan;
	}
	plan.localTime = localTime + timeStep;
	plan.substepsDue = 0;
	if (plan.localTime >= fixedTimeStep)
	{
		plan.substepsDue = int(plan.localTime / fixedTimeStep);
		plan.localTime -= plan.substepsDue * fixedTimeStep;
	}
	plan.substepsToRun = btMin(plan.substepsDue, maxSubSteps);
	plan.substepSeconds = fixedTimeStep;
	plan.fixedTimeStep = fixedTimeStep;
	return plan;
}

// The one-argument addRigidBody's broadphase filter, and what the world does with a body, by the body's
// role. A body flagged both static and kinematic counts as static.
enum BodyRole
{
	kDynamicBody,
	kKinematicBody,
	kStaticBody,
	kBodyRoleCount
};

struct BodyRoleRules
{
	int defaultGroup;
	int defaultMask;
	bool takesWorldGravity;  // unless the body has BT_DISABLE_WORLD_GRAVITY
	bool steppedByWorld;     // listed in m_nonStaticRigidBodies; otherwise parked asleep
};

const BodyRoleRules kBodyRoleRules[kBodyRoleCount] = {
    {btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, true, true},
    {btBroadphaseProxy::StaticFilter, btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter, false, true},
    {btBroadphaseProxy::StaticFilter, btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter, false, false},
};

BodyRole roleOf(const btRigidBody& body)
{
	if (body.isStaticObject()) return kStaticBody;
	return body.isKinematicObject() ? kKinematicBody : kDynamicBody;
}

bool holds(const btCollisionObjectArray& objects, const btCollisionObject* object)
{
	const int index = object->getWorldArrayIndex();
	return index >= 0 && index < objects.size() && objects[index] == object;
}
}  // namespace

btDiscreteDynamicsWorld::btDiscreteDynamicsWorld(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
                                                 btConstraintSolver* constraintSolver,
                                                 btCollisionConfiguration* collisionConfiguration)
    : btDynamicsWorld(dispatcher, pairCache, collisionConfiguration),
      m_solverIslandCallback(0),
      m_constraintSolver(constraintSolver ? constraintSolver
                                          : caliber::alignedNew<btSequentialImpulseConstraintSolver>()),
      m_islandManager(caliber::alignedNew<btSimulationIslandManager>()),
      m_gravity(0, -10, 0),
      m_localTime(0),
      m_fixedTimeStep(0),
      m_ownsIslandManager(true),
      m_ownsConstraintSolver(constraintSolver == 0),
      m_synchronizeAllMotionStates(false),
      m_applySpeculativeContactRestitution(false),
      m_profileTimings(0),
      m_latencyMotionStateInterpolation(true)
{
	caliber::stepContextOf(*this);
	// Declared before the solver it feeds, so made here rather than in the list above.
	m_solverIslandCallback = caliber::alignedNew<InplaceSolverIslandCallback>(m_constraintSolver, dispatcher);
}

btDiscreteDynamicsWorld::~btDiscreteDynamicsWorld()
{
	// The dispatcher outlives the world; a subclass's predictive manifolds must not outlive it in there.
	releasePredictiveContacts();
	caliber::alignedDelete(m_solverIslandCallback);
	if (m_ownsIslandManager) caliber::alignedDelete(m_islandManager);
	if (m_ownsConstraintSolver) caliber::alignedDelete(m_constraintSolver);
	caliber::releaseStepContext(*this);
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
	const SubstepPlan plan =
	    planSubsteps(m_localTime, m_latencyMotionStateInterpolation, timeStep, maxSubSteps, fixedTimeStep);
	m_localTime = plan.localTime;
	m_fixedTimeStep = plan.fixedTimeStep;

	if (getDebugDrawer())
		gDisableDeactivation = (getDebugDrawer()->getDebugMode() & btIDebugDraw::DBG_NoDeactivation) != 0;

	if (plan.substepsToRun == 0)
	{
		synchronizeMotionStates();
	}
	else
	{
		// The pool's workers slept since the last step (the Mt world's hint, or the time between steps):
		// woken now, they are awake for the first parallel loop (predictUnconstraintMotion) instead of
		// joining it late. A world whose predict runs on the calling thread alone leaves them asleep,
		// rather than have them poll for nothing.
		if (m_nonStaticRigidBodies.size() > caliber::kBodiesPerTask) caliber::wakeWorkerThreadsHint(btGetTaskScheduler());
		saveKinematicState(plan.substepSeconds * plan.substepsToRun);
		applyGravity();
		for (int substep = 0; substep < plan.substepsToRun; ++substep)
		{
			internalSingleStepSimulation(plan.substepSeconds);
			synchronizeMotionStates();
		}
	}
	clearForces();
	return plan.substepsDue;
}

void btDiscreteDynamicsWorld::internalSingleStepSimulation(btScalar timeStep)
{
	BT_PROFILE("internalSingleStepSimulation");
	if (m_internalPreTickCallback) (*m_internalPreTickCallback)(this, timeStep);

	// Caliber's own stages (quarantine, joint position correction) run from here, so a subclass that
	// replaces this function gets Bullet's pipeline (docs/architecture.md).
	caliber::WorldStepContext& context = caliber::stepContextOf(*this);
	caliber::quarantineNonFiniteBodies(*this, m_nonStaticRigidBodies, context);
	// With threads, the world classes themselves predict each chunk of bodies inside the box loop, just
	// before its boxes, while the broadphase's tree moves run (docs/threading.md): same bits.
	caliber::PredictionPrologue prediction;
	const bool predictWithBoxes = prediction.begin(*this, m_nonStaticRigidBodies, timeStep);
	if (!predictWithBoxes) predictUnconstraintMotion(timeStep);
	createPredictiveContacts(timeStep);
	if (m_applySpeculativeContactRestitution) caliber::giveSpeculativeContactsRestitution(m_predictiveManifolds);

	btDispatcherInfo& dispatchInfo = getDispatchInfo();
	dispatchInfo.m_timeStep = timeStep;
	dispatchInfo.m_stepCount = 0;
	dispatchInfo.m_debugDraw = getDebugDrawer();
	if (predictWithBoxes) caliber::setAabbChunkPrologue(this, &prediction);
	performDiscreteCollisionDetection();
	if (predictWithBoxes && !caliber::takeAabbChunkPrologueDone(this))
	{
		// Not reached: the world classes' collision step starts with updateAabbs, which takes it.
		btAssert(!"btDiscreteDynamicsWorld: the prediction was not made with the boxes");
		prediction.prepareAll();
	}

	calculateSimulationIslands();

	getSolverInfo().m_timeStep = timeStep;
	solveConstraints(getSolverInfo());

	integrateTransforms(timeStep);
	caliber::correctJointPositions(*this, m_constraints, context);
	caliber::quarantineNonFiniteBodies(*this, m_nonStaticRigidBodies, context);

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
	const BodyRoleRules& rules = kBodyRoleRules[roleOf(*body)];
	addRigidBody(body, rules.defaultGroup, rules.defaultMask);
}

void btDiscreteDynamicsWorld::addRigidBody(btRigidBody* body, int group, int mask)
{
	btAssert(body && "btDiscreteDynamicsWorld::addRigidBody: null body");
	if (!body) return;
	btAssert(!holds(m_collisionObjects, body) && "btDiscreteDynamicsWorld::addRigidBody: body added twice");
	if (holds(m_collisionObjects, body))
	{
		btReportWarning("Caliber: addRigidBody: the body is already in the world; call ignored\n", getDebugDrawer());
		return;
	}
	const BodyRoleRules& rules = kBodyRoleRules[roleOf(*body)];
	if (rules.takesWorldGravity && !(body->getFlags() & BT_DISABLE_WORLD_GRAVITY)) body->setGravity(m_gravity);
	// A body without a shape is in neither list; it still enters the collision world.
	if (body->getCollisionShape() && rules.steppedByWorld) m_nonStaticRigidBodies.push_back(body);
	if (body->getCollisionShape() && !rules.steppedByWorld) body->setActivationState(ISLAND_SLEEPING);
	addCollisionObject(body, group, mask);
}

void btDiscreteDynamicsWorld::removeRigidBody(btRigidBody* body)
{
	btAssert(body && "btDiscreteDynamicsWorld::removeRigidBody: null body");
	if (!body) return;
	const bool inWorld = holds(m_collisionObjects, body);
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
	if (m_ownsConstraintSolver) caliber::alignedDelete(m_constraintSolver);
	m_ownsConstraintSolver = false;
	m_constraintSolver = solver;
	m_solverIslandCallback->m_solver = solver;
}

btConstraintSolver* btDiscreteDynamicsWorld::getConstraintSolver() { return m_constraintSolver; }

namespace
{
// clearForces and applyGravity on the scheduler's threads: each body changes only its own forces, so any
// split of the loop gives the same bits, and the calling thread need not walk every body alone.
struct ForcesLoop : public btIParallelForBody
{
	btRigidBody* const* bodies;
	bool gravity;  // applyGravity to the awake bodies; else clearForces on every body

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			btRigidBody* body = bodies[i];
			if (!gravity)
				body->clearForces();
			else if (body->isActive())
				body->applyGravity();
		}
	}
};
}  // namespace

void btDiscreteDynamicsWorld::clearForces()
{
	if (m_nonStaticRigidBodies.size() == 0) return;
	ForcesLoop loop;
	loop.bodies = &m_nonStaticRigidBodies[0];
	loop.gravity = false;
	btParallelFor(0, m_nonStaticRigidBodies.size(), caliber::kBodiesPerTask, loop);
}

void btDiscreteDynamicsWorld::applyGravity()
{
	if (m_nonStaticRigidBodies.size() == 0) return;
	ForcesLoop loop;
	loop.bodies = &m_nonStaticRigidBodies[0];
	loop.gravity = true;
	btParallelFor(0, m_nonStaticRigidBodies.size(), caliber::kBodiesPerTask, loop);
}

namespace
{
// The pose a body's motion state is given: with latency interpolation it lies between the last two
// substeps (localTime - fixedTimeStep is in [-fixedTimeStep, 0)); without it, the pose is extrapolated
// by localTime.
btTransform interpolatedPose(const btRigidBody& body, bool latencyInterpolation, btScalar localTime,
                             btScalar fixedTimeStep)
{
	const btScalar interpolationTime = (latencyInterpolation && fixedTimeStep != btScalar(0))
	                                       ? localTime - fixedTimeStep
	                                       : localTime * body.getHitFraction();
	btTransform pose;
	btTransformUtil::integrateTransform(body.getInterpolationWorldTransform(), body.getInterpolationLinearVelocity(),
	                                    body.getInterpolationAngularVelocity(), interpolationTime, pose);
	return pose;
}

// Bodies per task of the parallel motion-state poses.
const int kMotionStatesPerTask = 128;

// A motion state the world may tell from the scheduler's threads: a btDefaultMotionState itself (not a
// subclass, which may override setWorldTransform), whose setWorldTransform stores the pose in the motion
// state's own members and touches nothing else.
bool mayBeToldOnThreads(const btMotionState& state) { return typeid(state) == typeid(btDefaultMotionState); }

// Each body's motion state (states[i], told or not), the motion state to tell (targets[i]; null: none, or
// the body is asleep, static or kinematic), whether that one may be told on the threads, and its pose. The
// calling thread then reads only these arrays and the motion states, not the bodies, which the other
// threads' caches hold after the step's parallel stages.
struct InterpolatePoses : public btIParallelForBody
{
	btRigidBody* const* bodies;
	btMotionState** states;
	btMotionState** targets;
	unsigned char* onThreads;
	btTransform* poses;
	bool latencyInterpolation;
	btScalar localTime;
	btScalar fixedTimeStep;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			btRigidBody& body = *bodies[i];
			btMotionState* state = body.getMotionState();
			btMotionState* target = state && body.isActive() && !body.isStaticOrKinematicObject() ? state : 0;
			states[i] = state;
			targets[i] = target;
			onThreads[i] = target && mayBeToldOnThreads(*target) ? 1 : 0;
			if (target) poses[i] = interpolatedPose(body, latencyInterpolation, localTime, fixedTimeStep);
		}
	}
};

// The btDefaultMotionStates' setWorldTransform on the threads. Only used when no two bodies share a motion
// state: then each call writes a motion state no other call touches, so the split does not matter.
struct TellDefaultMotionStates : public btIParallelForBody
{
	btMotionState* const* targets;
	const unsigned char* onThreads;
	const btTransform* poses;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
			if (onThreads[i]) targets[i]->setWorldTransform(poses[i]);
	}
};

// True when no two of the world's moving bodies share a motion state. Checked again (sorting a copy of
// the pointers) only when some body's motion state changed since the last check; otherwise one pass over
// an array the threads wrote.
bool motionStatesDistinct(caliber::WorldStepContext& context, const btAlignedObjectArray<btMotionState*>& states)
{
	btAlignedObjectArray<btMotionState*>& checked = context.motionStatesChecked;
	const int count = states.size();
	if (checked.size() == count &&
	    (count == 0 || std::memcmp(&checked[0], &states[0], sizeof(btMotionState*) * size_t(count)) == 0))
		return context.motionStatesDistinct;
	checked.copyFromArray(states);
	btAlignedObjectArray<btMotionState*>& sorted = context.motionStatesSorted;
	sorted.copyFromArray(states);
	struct ByAddress
	{
		bool operator()(const btMotionState* a, const btMotionState* b) const
		{
			return reinterpret_cast<size_t>(a) < reinterpret_cast<size_t>(b);
		}
	};
	sorted.quickSort(ByAddress());
	bool distinct = true;
	for (int i = 1; i < count && distinct; ++i)
		if (sorted[i] && sorted[i] == sorted[i - 1]) distinct = false;
	context.motionStatesDistinct = distinct;
	return distinct;
}
}  // namespace

void btDiscreteDynamicsWorld::synchronizeSingleMotionState(btRigidBody* body)
{
	btAssert(body);
	if (!body || !body->getMotionState() || body->isStaticOrKinematicObject()) return;
	body->getMotionState()->setWorldTransform(
	    interpolatedPose(*body, m_latencyMotionStateInterpolation, m_localTime, m_fixedTimeStep));
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
	const int numBodies = m_nonStaticRigidBodies.size();
	if (btGetTaskScheduler()->getNumThreads() < 2 || numBodies < 2 * kMotionStatesPerTask)
	{
		for (int i = 0; i < numBodies; ++i)
		{
			btRigidBody* body = m_nonStaticRigidBodies[i];
			if (body->isActive()) synchronizeSingleMotionState(body);
		}
		return;
	}
	// With a scheduler: the interpolated poses on its threads. Then, when no two bodies share a motion
	// state, the btDefaultMotionStates (whose setWorldTransform only stores the pose in itself) are told
	// on the threads, and every other motion state (a user's, which need not be thread-safe) in body order
	// on this thread; else all of them in body order on this thread. Same poses, same calls, and every
	// motion state ends with the same pose as in the serial loop above (docs/threading.md).
	caliber::WorldStepContext& context = caliber::stepContextOf(*this);
	btAlignedObjectArray<btTransform>& poses = context.motionStatePoses;
	btAlignedObjectArray<btMotionState*>& targets = context.motionStateTargets;
	btAlignedObjectArray<btMotionState*>& states = context.motionStatesNow;
	btAlignedObjectArray<unsigned char>& onThreads = context.motionStateOnThreads;
	poses.resizeNoInitialize(numBodies);
	targets.resizeNoInitialize(numBodies);
	states.resizeNoInitialize(numBodies);
	onThreads.resizeNoInitialize(numBodies);
	InterpolatePoses interpolate;
	interpolate.bodies = &m_nonStaticRigidBodies[0];
	interpolate.states = &states[0];
	interpolate.targets = &targets[0];
	interpolate.onThreads = &onThreads[0];
	interpolate.poses = &poses[0];
	interpolate.latencyInterpolation = m_latencyMotionStateInterpolation;
	interpolate.localTime = m_localTime;
	interpolate.fixedTimeStep = m_fixedTimeStep;
	btParallelFor(0, numBodies, kMotionStatesPerTask, interpolate);
	if (!motionStatesDistinct(context, states))
	{
		for (int i = 0; i < numBodies; ++i)
			if (targets[i]) targets[i]->setWorldTransform(poses[i]);
		return;
	}
	TellDefaultMotionStates tell;
	tell.targets = &targets[0];
	tell.onThreads = &onThreads[0];
	tell.poses = &poses[0];
	btParallelFor(0, numBodies, kMotionStatesPerTask, tell);
	for (int i = 0; i < numBodies; ++i)
		if (targets[i] && !onThreads[i]) targets[i]->setWorldTransform(poses[i]);
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
