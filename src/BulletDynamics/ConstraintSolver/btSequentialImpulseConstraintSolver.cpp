// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"

#include "BulletCollision/NarrowPhaseCollision/ManifoldPrefetch.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletDynamics/ConstraintSolver/btSolverRowKernels.h"
#include "BulletDynamics/ConstraintSolver/btSolverRowSolvers.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "BulletDynamics/Dynamics/btSpinMomentum.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btTransformUtil.h"

namespace
{
const unsigned long kDefaultSeed = 0;

void shuffle(btAlignedObjectArray<int>& order, btSequentialImpulseConstraintSolver& solver)
{
	for (int i = order.size() - 1; i > 0; --i) order.swap(i, solver.btRandInt2(i + 1));
}

// Every line of a solver row (160 bytes, so up to three lines).
SIMD_FORCE_INLINE void prefetchRow(const btSolverConstraint* row)
{
#if defined(__GNUC__)
	const char* bytes = reinterpret_cast<const char*>(row);
	__builtin_prefetch(bytes);
	__builtin_prefetch(bytes + 64);
	__builtin_prefetch(bytes + sizeof(btSolverConstraint) - 1);
#else
	(void)row;
#endif
}

void identityOrder(btAlignedObjectArray<int>& order, int count)
{
	order.resizeNoInitialize(count);
	for (int i = 0; i < count; ++i) order[i] = i;
}
}  // namespace

btSequentialImpulseConstraintSolver::btSequentialImpulseConstraintSolver()
    : m_fixedBodyId(-1),
      m_btSeed2(kDefaultSeed),
      m_leastSquaresResidual(0),
      m_maxOverrideNumSolverIterations(0),
      m_resolveSingleConstraintRowGeneric(0),
      m_resolveSingleConstraintRowLowerLimit(0),
      m_resolveSplitPenetrationImpulse(0),
      m_cachedSolverMode(0)
{
	setupSolverFunctions(true);
	caliber::solverScratchOf(*this);
}

btSequentialImpulseConstraintSolver::~btSequentialImpulseConstraintSolver() { caliber::releaseSolverScratch(*this); }

void btSequentialImpulseConstraintSolver::reset()
{
	m_btSeed2 = kDefaultSeed;
	caliber::solverScratchOf(*this).solveCount = 0;
}

unsigned long btSequentialImpulseConstraintSolver::btRand2()
{
	// A 32-bit linear congruential generator (Numerical Recipes' constants): cheap, and the same on
	// every platform, which is all the shuffle needs.
	m_btSeed2 = (1664525UL * m_btSeed2 + 1013904223UL) & 0xffffffffUL;
	return m_btSeed2;
}

int btSequentialImpulseConstraintSolver::btRandInt2(int n)
{
	btAssert(n > 0);
	// The high bits of an LCG are the random ones.
	const unsigned long r = btRand2() >> 8;
	return int(r % (unsigned long)n);
}

void btSequentialImpulseConstraintSolver::initSolverBody(btSolverBody* solverBody, btCollisionObject* collisionObject,
                                                         btScalar timeStep)
{
	(void)timeStep;
	const btVector3 zero(btScalar(0), btScalar(0), btScalar(0));
	btRigidBody* rb = btRigidBody::upcast(collisionObject);
	solverBody->m_deltaLinearVelocity = zero;
	solverBody->m_deltaAngularVelocity = zero;
	solverBody->m_pushVelocity = zero;
	solverBody->m_turnVelocity = zero;
	solverBody->m_externalForceImpulse = zero;
	solverBody->m_externalTorqueImpulse = zero;
	if (rb)
	{
		solverBody->m_worldTransform = rb->getWorldTransform();
		solverBody->m_invMass = rb->getInvMass() * rb->getLinearFactor();
		solverBody->m_originalBody = rb;
		solverBody->m_angularFactor = rb->getAngularFactor();
		solverBody->m_linearFactor = rb->getLinearFactor();
		solverBody->m_linearVelocity = rb->getLinearVelocity();
		solverBody->m_angularVelocity = rb->getAngularVelocity();
	}
	else
	{
		solverBody->m_worldTransform.setIdentity();
		solverBody->m_invMass = zero;
		solverBody->m_originalBody = 0;
		solverBody->m_angularFactor.setValue(btScalar(1), btScalar(1), btScalar(1));
		solverBody->m_linearFactor.setValue(btScalar(1), btScalar(1), btScalar(1));
		solverBody->m_linearVelocity = zero;
		solverBody->m_angularVelocity = zero;
	}
}

int btSequentialImpulseConstraintSolver::getOrInitSolverBody(btCollisionObject& body, btScalar timeStep)
{
	// The companion id is a hint, not a promise: the island manager resets it every step, but a user
	// calling solveGroup directly, or a kinematic body shared by two islands, may leave a stale one.
	const int hint = body.getCompanionId();
	if (hint >= 0 && hint < m_tmpSolverBodyPool.size() && m_tmpSolverBodyPool[hint].m_originalBody == &body)
		return hint;

	btRigidBody* rb = btRigidBody::upcast(&body);
	// Moving bodies get their own entry: dynamic ones to be solved, kinematic ones because their velocity
	// matters to the bodies they touch even though nothing pushes them back.
	if (rb && (rb->getInvMass() != btScalar(0) || rb->isKinematicObject()))
	{
		const int index = m_tmpSolverBodyPool.size();
		btSolverBody& solverBody = m_tmpSolverBodyPool.expandNonInitializing();
		initSolverBody(&solverBody, &body, timeStep);
		body.setCompanionId(index);
		return index;
	}
	if (m_fixedBodyId < 0)
	{
		m_fixedBodyId = m_tmpSolverBodyPool.size();
		btSolverBody& fixedBody = m_tmpSolverBodyPool.expandNonInitializing();
		initSolverBody(&fixedBody, 0, timeStep);
	}
	return m_fixedBodyId;
}

btScalar btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySetup(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifoldPtr, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& infoGlobal,
    btIDebugDraw* debugDrawer)
{
	BT_PROFILE("solveGroupCacheFriendlySetup");
	(void)debugDrawer;
	m_fixedBodyId = -1;
	m_maxOverrideNumSolverIterations = 0;
	m_tmpSolverBodyPool.resize(0);
	m_tmpSolverContactConstraintPool.resize(0);
	m_tmpSolverContactFrictionConstraintPool.resize(0);
	m_tmpSolverContactRollingFrictionConstraintPool.resize(0);
	caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	scratch.bounceRows.resize(0);
	scratch.shockPropagationNeeded = false;
	scratch.pushRowsListed = false;
	// Rough upper bound, so the pool grows at most once per new record scene size.
	m_tmpSolverBodyPool.reserve(numBodies + 1);

	m_cachedSolverMode = infoGlobal.m_solverMode;
	convertBodies(bodies, numBodies, infoGlobal);

	// Joints first: their warm-start impulses are in the bodies before the contacts measure velocities.
	convertJoints(constraints, numConstraints, infoGlobal);

	const int frictionRowsPerContact = caliber::frictionRowsPerContact(infoGlobal);
	scratch.manifoldFirstRow.resize(0);
	convertContacts(manifoldPtr, numManifolds, infoGlobal);
	// A subclass's convertContacts that does not record where each manifold's rows start leaves them as one
	// run (the sweep order below only needs runs of rows).
	if (scratch.manifoldFirstRow.size() == 0 && m_tmpSolverContactConstraintPool.size() > 0)
		scratch.manifoldFirstRow.push_back(0);
	scratch.manifoldFirstRow.push_back(m_tmpSolverContactConstraintPool.size());
	unsigned int solveIndex;
	scratch.solveCount = caliber::scopedSolveIndex(solveIndex) ? solveIndex : scratch.solveCount + 1u;
	caliber::findBouncesAndMassRatios(scratch, m_tmpSolverBodyPool, m_tmpSolverContactConstraintPool, infoGlobal);

	identityOrder(m_orderNonContactConstraintPool, scratch.joints.size());
	if (scratch.ownContactOrder)
	{
		m_orderTmpConstraintPool.resize(0);
		m_orderFrictionConstraintPool.resize(0);
		m_orderRollingFrictionConstraintPool.resize(0);
		return btScalar(0);
	}
	identityOrder(m_orderTmpConstraintPool, m_tmpSolverContactConstraintPool.size());
	identityOrder(m_orderFrictionConstraintPool, m_tmpSolverContactFrictionConstraintPool.size());
	identityOrder(m_orderRollingFrictionConstraintPool, m_tmpSolverContactRollingFrictionConstraintPool.size());
	if (!(infoGlobal.m_solverMode & SOLVER_RANDMIZE_ORDER))
	{
		// A fixed order is biased: the first point of a manifold takes more than its share of the impulse
		// in every sweep, and in a stack that bias tilts every box the same way, step after step, until
		// the tower leans. So within each manifold the first point rotates from step to step, and the
		// sweeps alternate direction (solveSingleIteration). Deterministic, and no shuffle to pay for.
		//
		// The points of one manifold share both bodies, so solving them back to back makes every row wait
		// for the previous one's body update. Taking the manifolds' k-th points in turn, in blocks of a
		// few manifolds, gives the processor independent rows to overlap while the sweep stays local.
		const btAlignedObjectArray<int>& manifoldFirstRow = scratch.manifoldFirstRow;
		const int numManifoldsWithRows = manifoldFirstRow.size() - 1;
		const int kInterleave = 8;
		int next = 0;
		for (int blockStart = 0; blockStart < numManifoldsWithRows; blockStart += kInterleave)
		{
			const int blockEnd = btMin(blockStart + kInterleave, numManifoldsWithRows);
			int maxCount = 0;
			for (int m = blockStart; m < blockEnd; ++m)
				maxCount = btMax(maxCount, manifoldFirstRow[m + 1] - manifoldFirstRow[m]);
			for (int p = 0; p < maxCount; ++p)
			{
				for (int m = blockStart; m < blockEnd; ++m)
				{
					const int first = manifoldFirstRow[m];
					const int count = manifoldFirstRow[m + 1] - first;
					if (p >= count) continue;
					int offset = p + int(scratch.solveCount % unsigned(count));
					if (offset >= count) offset -= count;
					m_orderTmpConstraintPool[next++] = first + offset;
				}
			}
		}
		btAssert(next == m_orderTmpConstraintPool.size());
		for (int j = 0; j < m_orderTmpConstraintPool.size(); ++j)
			for (int f = 0; f < frictionRowsPerContact; ++f)
				m_orderFrictionConstraintPool[j * frictionRowsPerContact + f] =
				    m_orderTmpConstraintPool[j] * frictionRowsPerContact + f;
	}
	return btScalar(0);
}

btScalar caliber::solveFrictionRow(btSolverBody* solverBodies, btConstraintArray& contacts, btConstraintArray& friction,
                                   int rowIndex)
{
	btSolverConstraint& row = friction[rowIndex];
	return caliber::resolveFrictionRow(solverBodies, row, contacts[row.m_frictionIndex].m_appliedImpulse);
}

btScalar caliber::sweepJoints(const SolverScratch& scratch, btSolverBody* bodies, btConstraintArray& jointRows,
                              const btAlignedObjectArray<btTypedConstraint::btConstraintInfo1>& sizes,
                              const btAlignedObjectArray<int>& order, int iteration, bool reverse)
{
	// A joint with its own iteration count stops when it is used up.
	btScalar residual = btScalar(0);
	const int numJoints = scratch.joints.size();
	for (int k = 0; k < numJoints; ++k)
	{
		const int j = order[reverse ? numJoints - 1 - k : k];
		if (iteration >= jointRows[scratch.jointFirstRow[j]].m_overrideNumSolverIterations) continue;
		residual += solveJoint(scratch, bodies, jointRows, sizes, j);
	}
	return residual;
}

btScalar btSequentialImpulseConstraintSolver::solveSingleIteration(int iteration, btCollisionObject** bodies,
                                                                   int numBodies, btPersistentManifold** manifoldPtr,
                                                                   int numManifolds, btTypedConstraint** constraints,
                                                                   int numConstraints,
                                                                   const btContactSolverInfo& infoGlobal,
                                                                   btIDebugDraw* debugDrawer)
{
	(void)bodies;
	(void)numBodies;
	(void)manifoldPtr;
	(void)numManifolds;
	(void)constraints;
	(void)numConstraints;
	(void)debugDrawer;
	if ((infoGlobal.m_solverMode & SOLVER_RANDMIZE_ORDER) && (iteration & 7) == 0)
	{
		shuffle(m_orderNonContactConstraintPool, *this);
		shuffle(m_orderTmpConstraintPool, *this);
		shuffle(m_orderFrictionConstraintPool, *this);
		shuffle(m_orderRollingFrictionConstraintPool, *this);
	}

	btSolverBody* solverBodies = m_tmpSolverBodyPool.size() ? &m_tmpSolverBodyPool[0] : 0;
	btScalar residual = btScalar(0);
	const caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	if (!caliber::usesCaliberRowSolvers(m_resolveSingleConstraintRowGeneric, m_resolveSingleConstraintRowLowerLimit))
		return caliber::sweepWithRowSolvers(iteration, infoGlobal, scratch, solverBodies,
		                                    m_tmpSolverNonContactConstraintPool, m_tmpConstraintSizesPool,
		                                    m_orderNonContactConstraintPool, m_tmpSolverContactConstraintPool,
		                                    m_orderTmpConstraintPool, m_tmpSolverContactFrictionConstraintPool,
		                                    m_orderFrictionConstraintPool,
		                                    m_tmpSolverContactRollingFrictionConstraintPool,
		                                    m_orderRollingFrictionConstraintPool, m_resolveSingleConstraintRowGeneric,
		                                    m_resolveSingleConstraintRowLowerLimit);

	// Every other sweep runs backwards, starting with the other direction on every other step so that an
	// odd iteration count is balanced too (not in Bullet's shuffled mode).
	const bool reverse =
	    !(infoGlobal.m_solverMode & SOLVER_RANDMIZE_ORDER) && ((unsigned(iteration) + scratch.solveCount) & 1u) != 0;
	// Joint rows first (as in Bullet).
	residual += caliber::sweepJoints(scratch, solverBodies, m_tmpSolverNonContactConstraintPool, m_tmpConstraintSizesPool,
	                                 m_orderNonContactConstraintPool, iteration, reverse);
	// Contacts run the world's iteration count; only joints that ask for more go on beyond it.
	if (iteration >= infoGlobal.m_numIterations) return residual;

	// Normal rows first, so that friction sees this sweep's normal impulses as its bounds.
	// The interleaved order (see solveGroupCacheFriendlySetup) jumps between a few manifolds' rows, which
	// the hardware prefetcher does not follow: rows are requested a few places ahead.
	const int kRowPrefetchDistance = 8;
	// Each pool is swept through its order array from one end, index stepping by +1 or -1; the rows more
	// than kRowPrefetchDistance from the end are requested that far ahead, the rest are not (the loop
	// is split there instead of testing every row).
	const int step = reverse ? -1 : 1;
	const int numContacts = m_tmpSolverContactConstraintPool.size();
	if (numContacts > 0)
	{
		btSolverConstraint* rows = &m_tmpSolverContactConstraintPool[0];
		const int* order = &m_orderTmpConstraintPool[0];
		const auto solve = [&](int j)
		{
			btSolverConstraint& row = rows[order[j]];
			residual += caliber::resolveRow(solverBodies[row.m_solverBodyIdA], solverBodies[row.m_solverBodyIdB], row,
			                                row.m_lowerLimit, row.m_upperLimit);
		};
		int j = reverse ? numContacts - 1 : 0, k = 0;
		for (; k < numContacts - kRowPrefetchDistance; ++k, j += step)
		{
			prefetchRow(&rows[order[j + step * kRowPrefetchDistance]]);
			solve(j);
		}
		for (; k < numContacts; ++k, j += step) solve(j);
	}
	const int numFriction = m_tmpSolverContactFrictionConstraintPool.size();
	if (numFriction > 0)
	{
		btSolverConstraint* rows = &m_tmpSolverContactFrictionConstraintPool[0];
		btSolverConstraint* contactRows = numContacts ? &m_tmpSolverContactConstraintPool[0] : nullptr;
		const int* order = &m_orderFrictionConstraintPool[0];
		// The kernel inlined (not solveFrictionRow's call): the sweep's pools and residual stay in registers.
		const auto solve = [&](int j)
		{
			btSolverConstraint& row = rows[order[j]];
			residual +=
			    caliber::resolveFrictionRow(solverBodies, row, contactRows[row.m_frictionIndex].m_appliedImpulse);
		};
		int j = reverse ? numFriction - 1 : 0, k = 0;
		for (; k < numFriction - kRowPrefetchDistance; ++k, j += step)
		{
			prefetchRow(&rows[order[j + step * kRowPrefetchDistance]]);
			solve(j);
		}
		for (; k < numFriction; ++k, j += step) solve(j);
	}

	const int numRolling = m_tmpSolverContactRollingFrictionConstraintPool.size();
	for (int j = 0; j < numRolling; ++j)
	{
		btSolverConstraint& row =
		    m_tmpSolverContactRollingFrictionConstraintPool[m_orderRollingFrictionConstraintPool[j]];
		const btScalar normalImpulse = m_tmpSolverContactConstraintPool[row.m_frictionIndex].m_appliedImpulse;
		if (normalImpulse > btScalar(0))
		{
			// Rolling and spinning resistance: the coefficient (a length) times the normal impulse.
			const btScalar bound = row.m_friction * normalImpulse;
			residual += caliber::resolveRow(solverBodies[row.m_solverBodyIdA], solverBodies[row.m_solverBodyIdB], row,
			                                -bound, bound);
		}
	}
	return residual;
}

void btSequentialImpulseConstraintSolver::solveGroupCacheFriendlySplitImpulseIterations(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifoldPtr, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& infoGlobal,
    btIDebugDraw* debugDrawer)
{
	(void)bodies;
	(void)numBodies;
	(void)manifoldPtr;
	(void)numManifolds;
	(void)constraints;
	(void)numConstraints;
	(void)debugDrawer;
	if (!infoGlobal.m_splitImpulse) return;
	BT_PROFILE("solveGroupCacheFriendlySplitImpulseIterations");
	// A row without a push target starts with no push impulse and is never given one, so only the rows
	// with a target are visited (in the normal rows' order), instead of every row in every sweep.
	// The multithreaded solver may have listed them already, on the threads (the same list).
	const int numContacts = m_tmpSolverContactConstraintPool.size();
	caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	btAlignedObjectArray<int>& pushRows = scratch.pushRows;
	if (!scratch.pushRowsListed)
	{
		pushRows.resize(0);
		for (int j = 0; j < numContacts; ++j)
		{
			const int index = m_orderTmpConstraintPool[j];
			if (m_tmpSolverContactConstraintPool[index].m_rhsPenetration != btScalar(0)) pushRows.push_back(index);
		}
	}
	if (pushRows.size() == 0) return;

	btSolverBody* solverBodies = &m_tmpSolverBodyPool[0];
	const int numPushRows = pushRows.size();
	const bool customPush = !caliber::isCaliberPushRowSolver(m_resolveSplitPenetrationImpulse);
	for (int iteration = 0; iteration < infoGlobal.m_numIterations; ++iteration)
	{
		btScalar residual = btScalar(0);
		for (int k = 0; k < numPushRows; ++k)
		{
			if (k + 8 < numPushRows) prefetchRow(&m_tmpSolverContactConstraintPool[pushRows[k + 8]]);
			btSolverConstraint& row = m_tmpSolverContactConstraintPool[pushRows[k]];
			if (customPush)
				residual += m_resolveSplitPenetrationImpulse(solverBodies[row.m_solverBodyIdA],
				                                             solverBodies[row.m_solverBodyIdB], row);
			else
				residual +=
				    caliber::resolvePushRow(solverBodies[row.m_solverBodyIdA], solverBodies[row.m_solverBodyIdB], row);
		}
		if (residual <= infoGlobal.m_leastSquaresResidualThreshold) break;
	}
}

btScalar btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations(
    btCollisionObject** bodies, int numBodies, btPersistentManifold** manifoldPtr, int numManifolds,
    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& infoGlobal,
    btIDebugDraw* debugDrawer)
{
	BT_PROFILE("solveGroupCacheFriendlyIterations");
	solveGroupCacheFriendlySplitImpulseIterations(bodies, numBodies, manifoldPtr, numManifolds, constraints,
	                                              numConstraints, infoGlobal, debugDrawer);
	const int maxIterations = btMax(infoGlobal.m_numIterations, m_maxOverrideNumSolverIterations);
	m_leastSquaresResidual = btScalar(0);
	for (int iteration = 0; iteration < maxIterations; ++iteration)
	{
		m_leastSquaresResidual = solveSingleIteration(iteration, bodies, numBodies, manifoldPtr, numManifolds,
		                                              constraints, numConstraints, infoGlobal, debugDrawer);
		if (m_leastSquaresResidual <= infoGlobal.m_leastSquaresResidualThreshold) break;
	}
	caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	caliber::propagateShock(scratch, m_tmpSolverBodyPool, m_tmpSolverContactConstraintPool,
	                        m_tmpSolverContactFrictionConstraintPool, infoGlobal);
	if (m_tmpSolverBodyPool.size())
		caliber::solveRestitution(scratch, &m_tmpSolverBodyPool[0], m_tmpSolverContactConstraintPool, infoGlobal);
	return m_leastSquaresResidual;
}

namespace
{
// Whether any row of the manifold that contact row `row` belongs to took an impulse this step.
bool manifoldWasMet(const btAlignedObjectArray<int>& manifoldFirstRow, const btConstraintArray& contacts, int row)
{
	// manifoldFirstRow is ascending, with one past the last row at the end: find the range of row.
	int lo = 0, hi = manifoldFirstRow.size() - 1;
	while (hi - lo > 1)
	{
		const int mid = (lo + hi) / 2;
		if (manifoldFirstRow[mid] <= row)
			lo = mid;
		else
			hi = mid;
	}
	for (int r = manifoldFirstRow[lo]; r < manifoldFirstRow[hi]; ++r)
		if (contacts[r].m_appliedImpulse > btScalar(0)) return true;
	return false;
}
}  // namespace

void caliber::solveRestitution(SolverScratch& scratch, btSolverBody* solverBodies, btConstraintArray& contacts,
                               const btContactSolverInfo& infoGlobal)
{
	btAlignedObjectArray<SolverBounceRow>& bounceRows = scratch.bounceRows;
	// Only contacts that were met this step bounce: a manifold none of whose rows took an impulse was not
	// reached (a speculative gap that was never closed) or was held apart by others. The whole manifold
	// counts, not each row: a face landing flat is often stopped by one or two of its points, and a
	// rebound from those alone would turn the body.
	int numBouncing = 0;
	for (int i = 0; i < bounceRows.size(); ++i)
	{
		if (manifoldWasMet(scratch.manifoldFirstRow, contacts, bounceRows[i].row))
			bounceRows[numBouncing++] = bounceRows[i];
	}
	bounceRows.resize(numBouncing);
	if (numBouncing == 0) return;
	BT_PROFILE("solveRestitution");

	// Several points of one body (a box landing flat) rebound together: sweeps in alternating directions
	// until the impulses settle, as in the velocity sweeps.
	// The points of one landing face form a singular system (eight coplanar points of a compound hold
	// three degrees of freedom), on which Gauss-Seidel converges slowly; an unconverged pass tilts the
	// body. Bouncing rows are few and live one step, so they get more sweeps than the velocity pass.
	const int restitutionSweeps = btMax(4 * infoGlobal.m_numIterations, 32);
	for (int iteration = 0; iteration < restitutionSweeps; ++iteration)
	{
		btScalar residual = btScalar(0);
		for (int k = 0; k < numBouncing; ++k)
		{
			const SolverBounceRow& bounce = bounceRows[(iteration & 1) ? numBouncing - 1 - k : k];
			btSolverConstraint& row = contacts[bounce.row];
			btSolverBody& bodyA = solverBodies[row.m_solverBodyIdA];
			btSolverBody& bodyB = solverBodies[row.m_solverBodyIdB];
			const btScalar velocity = bounce.startVelocity + caliber::rowDeltaVelocity(bodyA, bodyB, row);
			const btScalar impulse = caliber::btMaxBranchless(
			    btScalar(0), row.m_appliedImpulse + (bounce.targetVelocity - velocity) * row.m_jacDiagABInv);
			const btScalar deltaImpulse = impulse - row.m_appliedImpulse;
			row.m_appliedImpulse = impulse;
			bodyA.applyImpulse(row.m_contactNormal1, row.m_angularComponentA, deltaImpulse);
			bodyB.applyImpulse(row.m_contactNormal2, row.m_angularComponentB, deltaImpulse);
			residual += deltaImpulse * deltaImpulse;
			if (bounce.targetPushVelocity != btScalar(0))
			{
				// An equality on the push velocities: the pair ends the step at its rebound's top.
				const btVector3 lanes =
				    row.m_contactNormal1 * bodyA.m_pushVelocity + row.m_relpos1CrossNormal * bodyA.m_turnVelocity +
				    row.m_contactNormal2 * bodyB.m_pushVelocity + row.m_relpos2CrossNormal * bodyB.m_turnVelocity;
				const btScalar pushImpulse =
				    (bounce.targetPushVelocity - (lanes.x() + lanes.y() + lanes.z())) * row.m_jacDiagABInv;
				bodyA.internalApplyPushImpulse(row.m_contactNormal1, row.m_angularComponentA, pushImpulse);
				bodyB.internalApplyPushImpulse(row.m_contactNormal2, row.m_angularComponentB, pushImpulse);
				residual += pushImpulse * pushImpulse;
			}
		}
		if (residual <= infoGlobal.m_leastSquaresResidualThreshold) break;
	}
}

void btSequentialImpulseConstraintSolver::writeBackContacts(int iBegin, int iEnd, const btContactSolverInfo& infoGlobal)
{
	const int frictionRowsPerContact = caliber::frictionRowsPerContact(infoGlobal);
	for (int j = iBegin; j < iEnd; ++j)
	{
		const btSolverConstraint& row = m_tmpSolverContactConstraintPool[j];
		btManifoldPoint* point = static_cast<btManifoldPoint*>(row.m_originalContactPoint);
		btAssert(point);
		point->m_appliedImpulse = row.m_appliedImpulse;
		// Friction rows follow the order of their contact rows, one or two per contact.
		const int firstFriction = j * frictionRowsPerContact;
		point->m_appliedImpulseLateral1 = m_tmpSolverContactFrictionConstraintPool[firstFriction].m_appliedImpulse;
		point->m_appliedImpulseLateral2 =
		    frictionRowsPerContact == 2 ? m_tmpSolverContactFrictionConstraintPool[firstFriction + 1].m_appliedImpulse
		                                : btScalar(0);
	}
}

void btSequentialImpulseConstraintSolver::writeBackBodies(int iBegin, int iEnd, const btContactSolverInfo& infoGlobal)
{
	for (int i = iBegin; i < iEnd; ++i)
	{
		btSolverBody& solverBody = m_tmpSolverBodyPool[i];
		btRigidBody* body = solverBody.m_originalBody;
		if (!body) continue;
		body->setCompanionId(-1);
		if (body->isStaticOrKinematicObject()) continue;
		body->setLinearVelocity(solverBody.m_linearVelocity + solverBody.m_deltaLinearVelocity);
		body->setAngularVelocity(solverBody.m_angularVelocity + solverBody.m_deltaAngularVelocity);
		// Split impulse and weak rebounds (see solveRestitution) leave push velocities.
		if (!solverBody.m_pushVelocity.fuzzyZero() || !solverBody.m_turnVelocity.fuzzyZero())
		{
			// The push moves the body without leaving it any velocity.
			btTransform moved;
			btTransformUtil::integrateTransform(solverBody.m_worldTransform, solverBody.m_pushVelocity,
			                                    solverBody.m_turnVelocity * infoGlobal.m_splitImpulseTurnErp,
			                                    infoGlobal.m_timeStep, moved);
			// A push that turns the body keeps its angular momentum, as a free turn does.
			if (caliber::spinFollowsAngularMomentum(*body) && !solverBody.m_turnVelocity.fuzzyZero())
				body->setAngularVelocity(
				    caliber::angularVelocityAfterTurn(*body, solverBody.m_worldTransform.getBasis(), moved.getBasis()));
			body->setWorldTransform(moved);
		}
	}
}

btScalar btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyFinish(btCollisionObject** bodies, int numBodies,
                                                                            const btContactSolverInfo& infoGlobal)
{
	BT_PROFILE("solveGroupCacheFriendlyFinish");
	(void)bodies;
	(void)numBodies;
	writeBackContacts(0, m_tmpSolverContactConstraintPool.size(), infoGlobal);
	writeBackJoints(0, caliber::solverScratchOf(*this).joints.size(), infoGlobal);
	writeBackBodies(0, m_tmpSolverBodyPool.size(), infoGlobal);
	return btScalar(0);
}

btScalar btSequentialImpulseConstraintSolver::solveGroup(btCollisionObject** bodies, int numBodies,
                                                         btPersistentManifold** manifoldPtr, int numManifolds,
                                                         btTypedConstraint** constraints, int numConstraints,
                                                         const btContactSolverInfo& infoGlobal,
                                                         btIDebugDraw* debugDrawer, btDispatcher* dispatcher)
{
	BT_PROFILE("solveGroup");
	caliber::SolveDispatcherScope dispatcherScope(dispatcher);
	btAssert(numBodies >= 0 && numManifolds >= 0);
	if ((numBodies > 0 && !bodies) || (numManifolds > 0 && !manifoldPtr) || numBodies < 0 || numManifolds < 0)
		return btScalar(0);
	if (numConstraints < 0 || !constraints) numConstraints = 0;
	btAssert(infoGlobal.m_timeStep > btScalar(0));
	if (!(infoGlobal.m_timeStep > btScalar(0))) return btScalar(0);
	solveGroupCacheFriendlySetup(bodies, numBodies, manifoldPtr, numManifolds, constraints, numConstraints, infoGlobal,
	                             debugDrawer);
	solveGroupCacheFriendlyIterations(bodies, numBodies, manifoldPtr, numManifolds, constraints, numConstraints,
	                                  infoGlobal, debugDrawer);
	solveGroupCacheFriendlyFinish(bodies, numBodies, infoGlobal);
	return m_leastSquaresResidual;
}
