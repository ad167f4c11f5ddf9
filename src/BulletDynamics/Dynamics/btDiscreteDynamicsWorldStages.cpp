// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The stages of one substep of btDiscreteDynamicsWorld, in the order internalSingleStepSimulation runs
// them: predict, (collision detection: btCollisionWorld), islands, solve, integrate (with CCD),
// sleeping. Kinematic state and quarantine of non-finite bodies come first.
#include <typeinfo>

#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletCollision/CollisionDispatch/btUniteInOrder.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletDynamics/ConstraintSolver/btConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "BulletDynamics/Dynamics/btSpinMomentum.h"
#include "BulletDynamics/Dynamics/btInplaceSolverIslandCallback.h"
#include "BulletDynamics/Dynamics/btPredictionPrologue.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "BulletDynamics/Dynamics/btWorldStepContext.h"
#include "LinearMath/btCountingSortOnThreads.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// The sweep of a fast body's sphere: the closest object that responds to contact with it, among those
// it is moving towards (a hit whose normal faces along the motion is the body leaving a surface it
// touches). It filters like the body's own broadphase proxy.
class FirstContactOfSweep : public btCollisionWorld::ClosestConvexResultCallback
{
public:
	FirstContactOfSweep(btCollisionWorld& world, btCollisionObject& body, const btVector3& from, const btVector3& to)
	    : btCollisionWorld::ClosestConvexResultCallback(from, to),
	      m_body(&body),
	      m_pairCache(world.getBroadphase()->getOverlappingPairCache()),
	      m_dispatcher(world.getDispatcher()),
	      m_allowedPenetration(world.getDispatchInfo().m_allowedCcdPenetration)
	{
		m_collisionFilterGroup = body.getBroadphaseHandle()->m_collisionFilterGroup;
		m_collisionFilterMask = body.getBroadphaseHandle()->m_collisionFilterMask;
	}

	bool needsCollision(btBroadphaseProxy* proxy) const override
	{
		if (proxy->m_clientObject == m_body || !ClosestConvexResultCallback::needsCollision(proxy)) return false;
		btOverlapFilterCallback* filter = m_pairCache->getOverlapFilterCallback();
		if (filter && !filter->needBroadphaseCollision(m_body->getBroadphaseHandle(), proxy)) return false;
		return m_dispatcher->needsResponse(m_body, static_cast<const btCollisionObject*>(proxy->m_clientObject));
	}

	btScalar addSingleResult(btCollisionWorld::LocalConvexResult& hit, bool normalInWorldSpace) override
	{
		const btCollisionObject* other = hit.m_hitCollisionObject;
		if (other == m_body || !other->hasContactResponse()) return btScalar(1);
		const btVector3 worldNormal =
		    normalInWorldSpace ? hit.m_hitNormalLocal : other->getWorldTransform().getBasis() * hit.m_hitNormalLocal;
		const bool leaving = worldNormal.dot(m_convexToWorld - m_convexFromWorld) >= -m_allowedPenetration;
		return leaving ? btScalar(1) : ClosestConvexResultCallback::addSingleResult(hit, normalInWorldSpace);
	}

private:
	btCollisionObject* m_body;
	btOverlappingPairCache* m_pairCache;
	btDispatcher* m_dispatcher;
	btScalar m_allowedPenetration;
};

// Continuous collision: the fraction of this step a body may move before it would pass through
// something, or 1 when it may take the whole step. Only a convex body in the broadphase that would move
// further than its CCD motion threshold is checked, by sweeping a sphere of its swept-sphere radius
// (with the body's orientation kept: only the path of its centre matters) to its predicted position.
btScalar freeFractionOfStep(btCollisionWorld& world, btRigidBody& body, const btTransform& predicted)
{
	const btTransform& start = body.getWorldTransform();
	const btScalar squareMotion = (predicted.getOrigin() - start.getOrigin()).length2();
	const btScalar squareThreshold = body.getCcdSquareMotionThreshold();
	const bool sweep = world.getDispatchInfo().m_useContinuous && squareThreshold != btScalar(0) &&
	                   squareThreshold < squareMotion && body.getCollisionShape()->isConvex() &&
	                   body.getBroadphaseHandle();
	if (!sweep) return btScalar(1);
	FirstContactOfSweep firstContact(world, body, start.getOrigin(), predicted.getOrigin());
	const btSphereShape sphere(body.getCcdSweptSphereRadius());
	world.convexSweepTest(&sphere, start, btTransform(start.getBasis(), predicted.getOrigin()), firstContact);
	return firstContact.hasHit() ? firstContact.m_closestHitFraction : btScalar(1);
}
}  // namespace

void btDiscreteDynamicsWorld::releasePredictiveContacts()
{
	for (int i = 0; i < m_predictiveManifolds.size(); ++i) getDispatcher()->releaseManifold(m_predictiveManifolds[i]);
	m_predictiveManifolds.clear();
}

void btDiscreteDynamicsWorld::createPredictiveContactsInternal(btRigidBody** bodies, int numBodies, btScalar timeStep)
{
	// Bullet sweeps a sphere ahead of each fast body and keeps what it would hit as contacts for one step.
	// Caliber's contacts are speculative already (each pair's contact distance grows with the pair's
	// closing speed) and integrateTransforms clamps a fast body at its time of impact, so nothing is
	// left for predictive contacts to catch.
	(void)bodies;
	(void)numBodies;
	(void)timeStep;
}

void btDiscreteDynamicsWorld::createPredictiveContacts(btScalar timeStep)
{
	releasePredictiveContacts();
	if (getDispatchInfo().m_useContinuous && m_nonStaticRigidBodies.size())
		createPredictiveContactsInternal(&m_nonStaticRigidBodies[0], m_nonStaticRigidBodies.size(), timeStep);
}

namespace
{
// The bodies saveKinematicState saves: awake kinematic rigid bodies.
btRigidBody* awakeKinematicBody(btCollisionObject* object)
{
	btRigidBody* body = btRigidBody::upcast(object);
	return body && body->getActivationState() != ISLAND_SLEEPING && body->isKinematicObject() ? body : 0;
}

// How many objects saveKinematicState would save: only reads the objects, so it runs on the threads, and
// the calling thread walks the objects (and calls the kinematic bodies' motion states, user code) only
// when there is one.
struct CountAwakeKinematicBodies : public btIParallelSumBody
{
	btCollisionObject* const* objects;

	btScalar sumLoop(int iBegin, int iEnd) const override
	{
		int count = 0;
		for (int i = iBegin; i < iEnd; ++i) count += awakeKinematicBody(objects[i]) ? 1 : 0;
		return btScalar(count);
	}
};

// Objects per task of that count.
const int kObjectsPerKinematicTask = 256;
}  // namespace

void btDiscreteDynamicsWorld::saveKinematicState(btScalar timeStep)
{
	BT_PROFILE("saveKinematicState");
	// All objects, not only the non-static list: a kinematic body made with mass 0 also carries
	// CF_STATIC_OBJECT, as in Bullet.
	const int numObjects = m_collisionObjects.size();
	if (numObjects == 0) return;
	if (numObjects >= 2 * kObjectsPerKinematicTask)
	{
		CountAwakeKinematicBodies count;
		count.objects = &m_collisionObjects[0];
		// Any such body gives a sum above zero (each adds 0 or 1), whatever the chunks and their order.
		if (btParallelSum(0, numObjects, kObjectsPerKinematicTask, count) == btScalar(0)) return;
	}
	for (int i = 0; i < numObjects; ++i)
		if (btRigidBody* body = awakeKinematicBody(m_collisionObjects[i])) body->saveKinematicState(timeStep);
}

namespace
{
// Whether a body's pose and velocities are all finite, in one test: x * 0 is 0 for a finite x and NaN
// for an infinite or NaN one, and a sum of zeros stays exactly 0 (a plain sum could overflow).
bool stateIsFinite(const btRigidBody& body)
{
	const btMatrix3x3& basis = body.getWorldTransform().getBasis();
	const btVector3 zero(0, 0, 0);
	const btVector3 sum = basis[0] * zero + basis[1] * zero + basis[2] * zero +
	                      body.getWorldTransform().getOrigin() * zero + body.getLinearVelocity() * zero +
	                      body.getAngularVelocity() * zero;
	return sum.x() + sum.y() + sum.z() == btScalar(0);
}

// Whether the quarantine would take this body out of the simulation.
bool needsQuarantine(const btRigidBody& body)
{
	return body.getActivationState() != DISABLE_SIMULATION && !stateIsFinite(body);
}

// The number of bodies the quarantine would take out: only reads the bodies, so it runs on the threads,
// and the quarantine itself (which changes the broadphase) runs on the calling thread only when needed.
struct CountNonFiniteBodies : public btIParallelSumBody
{
	btRigidBody* const* bodies;

	btScalar sumLoop(int iBegin, int iEnd) const override
	{
		int count = 0;
		for (int i = iBegin; i < iEnd; ++i) count += needsQuarantine(*bodies[i]) ? 1 : 0;
		return btScalar(count);
	}
};
}  // namespace

void caliber::quarantineNonFiniteBodies(btDiscreteDynamicsWorld& world,
                                        const btAlignedObjectArray<btRigidBody*>& bodies, WorldStepContext& context)
{
	if (bodies.size() == 0) return;
	CountNonFiniteBodies count;
	count.bodies = &bodies[0];
	// Any body at all gives a sum above zero (each adds 0 or 1), whatever the chunks and their order.
	if (btParallelSum(0, bodies.size(), caliber::kBodiesPerTask, count) == btScalar(0)) return;
	for (int i = 0; i < bodies.size(); ++i)
	{
		btRigidBody* body = bodies[i];
		if (!needsQuarantine(*body)) continue;
		// A body whose state is no longer a number would hand NaN to everything it touches: it leaves the
		// broadphase (so it has no pairs) and the simulation, at its last finite pose when there is one.
		if (!context.reportedNonFiniteBody)
		{
			context.reportedNonFiniteBody = true;
			btReportWarning(
			    "Caliber: a rigid body's transform or velocity is not finite; the body is taken out "
			    "of the simulation (DISABLE_SIMULATION)\n",
			    world.getDebugDrawer());
		}
		if (!caliber::isFinite(body->getWorldTransform()))
		{
			btTransform lastPose = body->getInterpolationWorldTransform();
			if (!caliber::isFinite(lastPose)) lastPose.setIdentity();
			body->setWorldTransform(lastPose);
			body->setInterpolationWorldTransform(lastPose);
		}
		const btVector3 zero(0, 0, 0);
		body->setLinearVelocity(zero);
		body->setAngularVelocity(zero);
		body->setInterpolationLinearVelocity(zero);
		body->setInterpolationAngularVelocity(zero);
		body->clearForces();
		body->forceActivationState(DISABLE_SIMULATION);
		btBroadphaseProxy* proxy = body->getBroadphaseHandle();
		btBroadphaseInterface* broadphase = world.getBroadphase();
		if (proxy && broadphase)
		{
			broadphase->getOverlappingPairCache()->cleanProxyFromPairs(proxy, world.getDispatcher());
			broadphase->destroyProxy(proxy, world.getDispatcher());
			body->setBroadphaseHandle(0);
		}
	}
}

namespace
{
// One body's part of predictUnconstraintMotion: it reads and writes only that body, so bodies may be
// predicted on any threads in any order with the same bits (docs/threading.md).
void predictBody(btRigidBody* body, btScalar timeStep, const btContactSolverInfo& solverInfo)
{
	if (body->isStaticOrKinematicObject()) return;
	body->applyDamping(timeStep);
	if (body->isActive())
	{
		// Forces (gravity included) become velocity here, before the solver, so that contacts see the
		// velocity the body would have without them: semi-implicit Euler, v1 = v0 + a h, x1 = x0 + v1 h.
		btVector3 gyroscopicChange(0, 0, 0);
		const int flags = body->getFlags();
		if (flags & BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT)
			gyroscopicChange -= body->getInvInertiaTensorWorld() *
			                    body->computeGyroscopicForceExplicit(solverInfo.m_maxGyroscopicForce) * timeStep;
		if (flags & BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD)
			gyroscopicChange += body->computeGyroscopicImpulseImplicit_World(timeStep);
		// The default implicit flag is applied when the body turns (integrateTransformsInternal), as
		// conservation of angular momentum; bodies that do not turn freely keep Bullet's Newton step.
		// An isotropic body (a cube, a sphere) has no gyroscopic effect, w x (I w) = 0: Bullet's Newton step
		// would only add its rounding.
		if ((flags & BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY) && !caliber::spinFollowsAngularMomentum(*body) &&
		    !caliber::hasIsotropicInertia(*body))
			gyroscopicChange += body->computeGyroscopicImpulseImplicit_Body(timeStep);
		body->integrateVelocities(timeStep);
		if (!gyroscopicChange.fuzzyZero())
			body->setAngularVelocity(body->getAngularVelocity() + gyroscopicChange * body->getAngularFactor());
	}
	// The predicted pose widens the broadphase box of fast bodies (m_useContinuous), and the
	// velocity this step will move with sets the pair's speculative contact distance (the
	// dispatcher reads it from the interpolation velocities; integrateTransforms overwrites them).
	body->predictIntegratedTransform(timeStep, body->getInterpolationWorldTransform());
	body->setInterpolationLinearVelocity(body->getLinearVelocity());
	body->setInterpolationAngularVelocity(body->getAngularVelocity());
}

struct PredictBodies : public btIParallelForBody
{
	btRigidBody* const* bodies;
	btScalar timeStep;
	const btContactSolverInfo* solverInfo;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) predictBody(bodies[i], timeStep, *solverInfo);
	}
};
}  // namespace

void btDiscreteDynamicsWorld::predictUnconstraintMotion(btScalar timeStep)
{
	BT_PROFILE("predictUnconstraintMotion");
	if (m_nonStaticRigidBodies.size() == 0) return;
	PredictBodies loop;
	loop.bodies = &m_nonStaticRigidBodies[0];
	loop.timeStep = timeStep;
	loop.solverInfo = &getSolverInfo();
	btParallelFor(0, m_nonStaticRigidBodies.size(), caliber::kBodiesPerTask, loop);
}

bool caliber::PredictionPrologue::begin(btDiscreteDynamicsWorld& world,
                                        const btAlignedObjectArray<btRigidBody*>& bodies, btScalar timeStep)
{
	if (typeid(world) != typeid(btDiscreteDynamicsWorld) && typeid(world) != typeid(btDiscreteDynamicsWorldMt))
		return false;
	if (bodies.size() == 0 || btGetTaskScheduler()->getNumThreads() < 2) return false;
	// The bodies must be one run of the object array: a pass over two pointer arrays, no body read but the
	// first's index.
	const btCollisionObjectArray& objects = world.getCollisionObjectArray();
	const int first = bodies[0]->getWorldArrayIndex();
	if (first < 0 || first + bodies.size() > objects.size()) return false;
	btCollisionObject* const* run = &objects[first];
	for (int i = 0; i < bodies.size(); ++i)
		if (run[i] != bodies[i]) return false;
	m_bodies = &bodies[0];
	m_numBodies = bodies.size();
	m_firstObject = first;
	m_timeStep = timeStep;
	m_solverInfo = &world.getSolverInfo();
	return true;
}

void caliber::PredictionPrologue::prepareObjects(int objectBegin, int objectEnd) const
{
	const int begin = btMax(0, objectBegin - m_firstObject);
	const int end = btMin(m_numBodies, objectEnd - m_firstObject);
	for (int i = begin; i < end; ++i) predictBody(m_bodies[i], m_timeStep, *m_solverInfo);
}

void caliber::PredictionPrologue::prepareAll() const
{
	BT_PROFILE("predictUnconstraintMotion");
	PredictBodies loop;
	loop.bodies = m_bodies;
	loop.timeStep = m_timeStep;
	loop.solverInfo = m_solverInfo;
	btParallelFor(0, m_numBodies, caliber::kBodiesPerTask, loop);
}

namespace
{
// Joints per task of the per-joint passes of the island stage on the threads, and the fewest joints worth
// a loop (ragdolls136 has 1360).
const int kJointsPerIslandTask = 256;

bool jointPassesOnThreads(int numJoints)
{
	const btITaskScheduler* scheduler = btGetTaskScheduler();
	return numJoints >= 2 * kJointsPerIslandTask && scheduler && scheduler->getNumThreads() > 1 &&
	       !btThreadsAreRunning();
}

// The elements calculateSimulationIslands unites for joint (tags[0], tags[1]), or -1 in tags[0] for none.
void jointUnionTags(const btCollisionWorld& world, const btTypedConstraint& constraint, int numElements, int* tags)
{
	tags[0] = -1;
	if (!constraint.isEnabled()) return;
	const btRigidBody& a = constraint.getRigidBodyA();
	const btRigidBody& b = constraint.getRigidBodyB();
	if (!caliber::isSimulatedIn(world, a) || !caliber::isSimulatedIn(world, b)) return;
	const int tagA = a.getIslandTag(), tagB = b.getIslandTag();
	if (tagA < 0 || tagB < 0 || tagA >= numElements || tagB >= numElements) return;
	tags[0] = tagA;
	tags[1] = tagB;
}

// The island sortConstraintsByIsland files joint under (that of its simulated body, A first), or -1.
int jointIsland(const btCollisionWorld& world, const btTypedConstraint& constraint, int numIslands)
{
	if (!constraint.isEnabled()) return -1;
	const btRigidBody& a = constraint.getRigidBodyA();
	const btRigidBody& b = constraint.getRigidBodyB();
	const int island = caliber::isSimulatedIn(world, a) ? a.getIslandTag()
	                                                     : (caliber::isSimulatedIn(world, b) ? b.getIslandTag() : -1);
	return island >= 0 && island < numIslands ? island : -1;
}

// Both per-joint passes on the threads: each joint writes only its own slots, so any split of the loop
// gives the same lists, which the calling thread then reads in joint order (the serial passes' order).
struct JointIslandPass : public btIParallelForBody
{
	const btCollisionWorld* world;
	btTypedConstraint* const* constraints;
	int numElements;
	bool unions;  // jointUnionTags into out[2 i], out[2 i + 1]; else jointIsland into out[i]
	int* out;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			if (unions)
				jointUnionTags(*world, *constraints[i], numElements, out + 2 * i);
			else
				out[i] = jointIsland(*world, *constraints[i], numElements);
		}
	}
};

// sortConstraintsByIsland's sort on the threads: the key of joint i (its island, or -1), and its placement.
struct JointIslandKey
{
	const btCollisionWorld* world;
	btTypedConstraint* const* constraints;
	int numIslands;
	int operator()(int i) const { return jointIsland(*world, *constraints[i], numIslands); }
};

struct PlaceJoint
{
	btTypedConstraint* const* constraints;
	btTypedConstraint** sorted;
	void operator()(int i, int, int slot) const { sorted[slot] = constraints[i]; }
};
}  // namespace

void btDiscreteDynamicsWorld::calculateSimulationIslands()
{
	BT_PROFILE("calculateSimulationIslands");
	getSimulationIslandManager()->updateActivationState(getCollisionWorld(), getCollisionWorld()->getDispatcher());
	// Jointed bodies share an island: they are solved together, and sleep and wake together. The unions'
	// result depends on their order: they are made in joint order (the joints' bodies may be read on the
	// threads first).
	btUnionFind& unionFind = getSimulationIslandManager()->getUnionFind();
	const int numElements = unionFind.getNumElements();
	const int numJoints = m_constraints.size();
	if (jointPassesOnThreads(numJoints))
	{
		btAlignedObjectArray<int>& tags = caliber::stepContextOf(*this).jointIslandTags;
		tags.resizeNoInitialize(2 * numJoints);
		JointIslandPass pass;
		pass.world = this;
		pass.constraints = &m_constraints[0];
		pass.numElements = numElements;
		pass.unions = true;
		pass.out = &tags[0];
		btParallelFor(0, numJoints, kJointsPerIslandTask, pass);
		caliber::uniteInOrder(unionFind, &tags[0], numJoints);
	}
	else
	{
		int tags[2];
		for (int i = 0; i < numJoints; ++i)
		{
			jointUnionTags(*this, *m_constraints[i], numElements, tags);
			if (tags[0] >= 0) unionFind.unite(tags[0], tags[1]);
		}
	}
	getSimulationIslandManager()->storeIslandActivationState(getCollisionWorld());
}

bool caliber::isSimulatedIn(const btCollisionWorld& world, const btRigidBody& body)
{
	if (body.isStaticOrKinematicObject()) return false;
	const int index = body.getWorldArrayIndex();
	const btCollisionObjectArray& objects = world.getCollisionObjectArray();
	return index >= 0 && index < objects.size() && objects[index] == &body;
}

void caliber::sortConstraintsByIsland(btDiscreteDynamicsWorld& world,
                                      const btAlignedObjectArray<btTypedConstraint*>& constraints,
                                      btAlignedObjectArray<btTypedConstraint*>& sorted, WorldStepContext& context)
{
	// A joint belongs to the island of its simulated body (A, or B when A is static, kinematic or the
	// fixed body). Joints whose bodies are both outside the simulation have nothing to move.
	const int numIslands = world.getSimulationIslandManager()->getUnionFind().getNumElements();
	btAlignedObjectArray<int>& islandStart = context.constraintIslandStart;
	btAlignedObjectArray<int>& islandFill = context.islandFill;
	islandStart.resize(0);
	sorted.resize(0);
	if (constraints.size() == 0)
	{
		// No joints: a list of no islands, which the island callback reads as "no island has joints".
		islandStart.resize(1, 0);
		return;
	}
	islandStart.resize(numIslands + 1, 0);
	const bool splitIslands = world.getSimulationIslandManager()->getSplitIslands();
	const int numJoints = constraints.size();
	if (splitIslands)
	{
		// Many joints: each joint's island and the counting sort on the threads (the same list: a stable sort).
		const int parts = caliber::countingSortParts(numJoints, 2 * kJointsPerIslandTask);
		if (parts > 0)
		{
			JointIslandKey keyOf;
			keyOf.world = &world;
			keyOf.constraints = &constraints[0];
			keyOf.numIslands = numIslands;
			PlaceJoint place;
			place.constraints = &constraints[0];
			place.sorted = 0;
			caliber::CountingSortOnThreads<JointIslandKey, PlaceJoint> sort(context.jointSort, numJoints, numIslands,
			                                                                parts);
			sort.count(keyOf);
			// Sized for every joint; the sort says how many are kept.
			sorted.resizeNoInitialize(numJoints);
			place.sorted = &sorted[0];
			sorted.resizeNoInitialize(sort.place(place, &islandStart[0]));
			return;
		}
	}
	// Each joint's island, on the threads when there are many joints (in joint order either way).
	btAlignedObjectArray<int>& islandOf = context.jointIslandTags;
	islandOf.resizeNoInitialize(numJoints);
	if (jointPassesOnThreads(numJoints))
	{
		JointIslandPass pass;
		pass.world = &world;
		pass.constraints = &constraints[0];
		pass.numElements = numIslands;
		pass.unions = false;
		pass.out = &islandOf[0];
		btParallelFor(0, numJoints, kJointsPerIslandTask, pass);
	}
	else
	{
		for (int i = 0; i < numJoints; ++i) islandOf[i] = jointIsland(world, *constraints[i], numIslands);
	}
	if (!splitIslands)
	{
		for (int i = 0; i < numJoints; ++i)
			if (islandOf[i] >= 0) sorted.push_back(constraints[i]);
		return;
	}
	for (int i = 0; i < numJoints; ++i)
		if (islandOf[i] >= 0) ++islandStart[islandOf[i] + 1];
	for (int i = 0; i < numIslands; ++i) islandStart[i + 1] += islandStart[i];
	sorted.resize(islandStart[numIslands]);
	// Second pass: place each joint after those of its island already placed (stable: insertion order).
	islandFill.resize(0);
	islandFill.resize(numIslands, 0);
	for (int i = 0; i < numJoints; ++i)
	{
		const int island = islandOf[i];
		if (island >= 0) sorted[islandStart[island] + islandFill[island]++] = constraints[i];
	}
}

void btDiscreteDynamicsWorld::solveConstraints(btContactSolverInfo& solverInfo)
{
	BT_PROFILE("solveConstraints");
	const int numManifolds = getDispatcher()->getNumManifolds();
	caliber::WorldStepContext& context = caliber::stepContextOf(*this);
	caliber::sortConstraintsByIsland(*this, m_constraints, m_sortedConstraints, context);
	m_solverIslandCallback->setup(&solverInfo, getDebugDrawer());
	m_solverIslandCallback->m_largeBatchSolver = context.largeBatchSolver;
	m_solverIslandCallback->m_largeBatchManifolds =
	    btMax(1, btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching);
	m_solverIslandCallback->setConstraints(m_sortedConstraints.size() ? &m_sortedConstraints[0] : 0,
	                                       m_sortedConstraints.size(), &context.constraintIslandStart[0],
	                                       context.constraintIslandStart.size() - 1);
	m_constraintSolver->prepareSolve(getCollisionWorld()->getNumCollisionObjects(), numManifolds);
	m_islandManager->buildAndProcessIslands(getCollisionWorld()->getDispatcher(), getCollisionWorld(),
	                                        m_solverIslandCallback);
	// Batches in parallel only with a pool of solvers (btDiscreteDynamicsWorldMt's), and not in Bullet's
	// shuffled order, whose random sequence belongs to one solver.
	const bool parallel = btGetTaskScheduler()->getNumThreads() > 1 &&
	                      dynamic_cast<btConstraintSolverPoolMt*>(m_constraintSolver) != 0 &&
	                      !(solverInfo.m_solverMode & SOLVER_RANDMIZE_ORDER);
	m_solverIslandCallback->flush();
	const int numBatches = m_solverIslandCallback->numBatches();
	m_solverIslandCallback->solveBatches(parallel, context.solveCounter + 1u);
	context.solveCounter += unsigned(numBatches);
	m_constraintSolver->allSolved(solverInfo, m_debugDrawer);
}

namespace
{
// True when the continuous collision of freeFractionOfStep may sweep this body this step. Only such a
// sweep reads other bodies (their poses, which the loop is changing), so without one the bodies of
// integrateTransforms are independent.
bool maySweep(const btCollisionWorld& world, const btRigidBody& body)
{
	return world.getDispatchInfo().m_useContinuous && body.getCcdSquareMotionThreshold() != btScalar(0) &&
	       body.isActive() && !body.isStaticOrKinematicObject();
}

void integrateBody(btCollisionWorld& world, btRigidBody* body, btScalar timeStep)
{
	body->setHitFraction(btScalar(1));
	if (!body->isActive() || body->isStaticOrKinematicObject()) return;
	// A body whose spin follows its angular momentum turns freely (btSpinMomentum.h); others turn by
	// their angular velocity, as in Bullet.
	btTransform predicted;
	const bool freeTurn = caliber::spinFollowsAngularMomentum(*body);
	btVector3 angularVelocityAfter = body->getAngularVelocity();
	if (freeTurn)
	{
		btQuaternion orientation;
		caliber::turnFreely(*body, body->getOrientation(), timeStep, orientation, angularVelocityAfter);
		predicted.setOrigin(body->getCenterOfMassPosition() + body->getLinearVelocity() * timeStep);
		predicted.setRotation(orientation);
	}
	else
	{
		body->predictIntegratedTransform(timeStep, predicted);
	}
	const btScalar freeFraction = freeFractionOfStep(world, *body, predicted);
	if (freeFraction < btScalar(1))
	{
		// The body stops where its sphere first touched; hit fraction 0 then says it was clamped.
		body->predictIntegratedTransform(timeStep * freeFraction, predicted);
		body->setHitFraction(btScalar(0));
		if (freeTurn)
			angularVelocityAfter =
			    caliber::angularVelocityAfterTurn(*body, body->getWorldTransform().getBasis(), predicted.getBasis());
	}
	body->proceedToTransform(predicted);
	if (freeTurn) body->setAngularVelocity(angularVelocityAfter);
}

struct IntegrateBodies : public btIParallelForBody
{
	btCollisionWorld* world;
	btRigidBody** bodies;
	btScalar timeStep;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) integrateBody(*world, bodies[i], timeStep);
	}
};
}  // namespace

void btDiscreteDynamicsWorld::integrateTransformsInternal(btRigidBody** bodies, int numBodies, btScalar timeStep)
{
	if (numBodies <= 0) return;
	// With a possible CCD sweep the bodies are moved in order, as the sweeps of later bodies see the
	// new poses of earlier ones; otherwise they go to the scheduler (same bits at any thread count).
	bool independent = true;
	for (int i = 0; i < numBodies && independent; ++i) independent = !maySweep(*this, *bodies[i]);
	if (!independent)
	{
		for (int i = 0; i < numBodies; ++i) integrateBody(*this, bodies[i], timeStep);
		return;
	}
	IntegrateBodies loop;
	loop.world = this;
	loop.bodies = bodies;
	loop.timeStep = timeStep;
	btParallelFor(0, numBodies, caliber::kBodiesPerTask, loop);
}

void btDiscreteDynamicsWorld::integrateTransforms(btScalar timeStep)
{
	BT_PROFILE("integrateTransforms");
	if (m_nonStaticRigidBodies.size() > 0)
		integrateTransformsInternal(&m_nonStaticRigidBodies[0], m_nonStaticRigidBodies.size(), timeStep);
}

namespace
{
// One body's sleeping bookkeeping: it reads and writes only that body (and reads the global deactivation
// settings), so bodies may be updated on any threads in any order with the same bits.
void updateBodyActivation(btRigidBody* body, btScalar timeStep)
{
	body->updateDeactivation(timeStep);
	if (body->wantsSleeping())
	{
		if (body->isStaticOrKinematicObject())
		{
			body->setActivationState(ISLAND_SLEEPING);
		}
		else
		{
			// The island decides: the body only says it could sleep; the island manager puts the whole
			// island to sleep when every body in it agrees.
			if (body->getActivationState() == ACTIVE_TAG) body->setActivationState(WANTS_DEACTIVATION);
			if (body->getActivationState() == ISLAND_SLEEPING)
			{
				body->setAngularVelocity(btVector3(0, 0, 0));
				body->setLinearVelocity(btVector3(0, 0, 0));
			}
		}
	}
	else if (body->getActivationState() != DISABLE_DEACTIVATION)
	{
		body->setActivationState(ACTIVE_TAG);
	}
}

struct UpdateBodyActivations : public btIParallelForBody
{
	btRigidBody* const* bodies;
	btScalar timeStep;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) updateBodyActivation(bodies[i], timeStep);
	}
};
}  // namespace

void btDiscreteDynamicsWorld::updateActivationState(btScalar timeStep)
{
	BT_PROFILE("updateActivationState");
	if (m_nonStaticRigidBodies.size() == 0) return;
	UpdateBodyActivations loop;
	loop.bodies = &m_nonStaticRigidBodies[0];
	loop.timeStep = timeStep;
	btParallelFor(0, m_nonStaticRigidBodies.size(), caliber::kBodiesPerTask, loop);
}
