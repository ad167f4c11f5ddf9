// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOLVER_SCRATCH_H
#define CALIBER_SOLVER_SCRATCH_H

// The sequential-impulse solver's own per-solve state and stages, beside Bullet's class rather than in
// it: btSequentialImpulseConstraintSolver declares only Bullet's members, and what Caliber adds lives
// in a SolverScratch found by the solver's address (a side table, looked up once per solve or sweep,
// never per row), with the stages Bullet does not have as free functions over the solver's pools.

#include "BulletDynamics/ConstraintSolver/btContactSolverInfo.h"
#include "BulletDynamics/ConstraintSolver/btJointWarmStart.h"
#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "BulletDynamics/ConstraintSolver/btSolverJointBlock.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btAlignedObjectArray.h"

class btDispatcher;
class btManifoldPoint;
class btSequentialImpulseConstraintSolver;

namespace caliber
{
/// A contact row that rebounds this step if its contact is met (see solveRestitution).
struct SolverBounceRow
{
	int row;                      ///< index into the contact row pool
	btScalar startVelocity;       ///< J v at setup (the solver bodies' velocities, before any impulse)
	btScalar targetVelocity;      ///< J v the rebound leaves the step with
	btScalar targetPushVelocity;  ///< position correction over the step, as a push velocity (<= 0; 0: none)
};

/// One solver's Caliber-only state. The arrays keep their capacity between solves.
struct SolverScratch
{
	/// The joints of this solve, each joint's first row in the joint row pool, and its block of
	/// equality rows (see SolverJointBlock).
	btAlignedObjectArray<btTypedConstraint*> joints;
	btAlignedObjectArray<int> jointFirstRow;
	btAlignedObjectArray<SolverJointBlock> jointBlocks;
	/// Each joint's warm-start entry in warmStarts, resolved once per solve (see btJointWarmStart.h).
	btAlignedObjectArray<JointImpulses*> jointWarmStart;
	/// The joints of this solve that have no rows this step (their warm start is dropped).
	btAlignedObjectArray<btTypedConstraint*> idleJoints;
	/// The row impulses of every joint this solver has solved, for warm starting the next solve.
	JointWarmStartStore warmStarts;
	/// Another solver's store this one uses instead (shareJointWarmStarts), or null.
	JointWarmStartStore* sharedWarmStarts = nullptr;
	JointWarmStartStore& jointWarmStarts() { return sharedWarmStarts ? *sharedWarmStarts : warmStarts; }
	/// First contact row of each manifold (plus one past the last), so that sweeps can vary the order
	/// of the points within a manifold.
	btAlignedObjectArray<int> manifoldFirstRow;
	/// Contact rows (in solving order) with a split-impulse target: the only ones the push pass visits.
	btAlignedObjectArray<int> pushRows;
	/// Set by the multithreaded solver's setup when it has already listed pushRows (on the threads, in the
	/// contact order it wrote): the push pass then skips its own scan of every row. Cleared by each setup.
	bool pushRowsListed = false;
	/// Contact rows whose restitution applies if they are met this step (in setup order).
	btAlignedObjectArray<SolverBounceRow> bounceRows;
	/// findBouncesAndMassRatios on the task scheduler's threads: what each chunk of rows found.
	struct BounceChunk
	{
		btAlignedObjectArray<SolverBounceRow> bounces;
		bool massRatio;
		char padding[128];  // two chunks' array headers, written by two threads, on different cache lines
	};
	btAlignedObjectArray<BounceChunk> bounceChunks;
	/// Shock propagation (see propagateShock): whether a contact of this solve holds bodies of very
	/// different masses; the contact graph, each body's level above the ground, the rows bottom up.
	bool shockPropagationNeeded = false;
	btAlignedObjectArray<int> shockAdjacencyStart;
	btAlignedObjectArray<int> shockAdjacency;
	btAlignedObjectArray<int> shockCursor;
	btAlignedObjectArray<int> shockBodyLevel;
	btAlignedObjectArray<int> shockQueue;
	btAlignedObjectArray<int> shockRowOrder;
	/// Counts solves, so that the in-manifold order also changes from step to step (reset() clears it).
	unsigned int solveCount = 0;
	/// Set by the multithreaded solver for a solve whose contact rows it sweeps in its own batches: the
	/// serial setup then leaves the contact, friction and rolling sweep orders empty (the multithreaded
	/// solver makes the contact order itself, on the threads, for the split-impulse pass).
	bool ownContactOrder = false;
};

/// The world numbers the solves of its steps and tells the solver which one a solveGroup call is, on the
/// calling thread, for the length of the scope: the solver's step-to-step variation of its row order
/// (SolverScratch::solveCount) then follows the world's sequence of batches, not the history of the
/// solver instance, so a pool of solvers on any number of threads solves every batch as one solver
/// would. Without a scope (a solver called outside a world) the solver counts its own solves.
class SolveIndexScope
{
public:
	explicit SolveIndexScope(unsigned int index);
	~SolveIndexScope();
	SolveIndexScope(const SolveIndexScope&) = delete;
	SolveIndexScope& operator=(const SolveIndexScope&) = delete;

private:
	bool m_hadIndex;
	unsigned int m_previousIndex;
};
/// The index of the innermost SolveIndexScope of this thread, if there is one.
bool scopedSolveIndex(unsigned int& index);

/// solveGroup's dispatcher, on the calling thread for the length of the call: the Mt solver's write-back
/// notes there which thread wrote each manifold (BulletCollision's btManifoldOwners.h).
class SolveDispatcherScope
{
public:
	explicit SolveDispatcherScope(btDispatcher* dispatcher);
	~SolveDispatcherScope();
	SolveDispatcherScope(const SolveDispatcherScope&) = delete;
	SolveDispatcherScope& operator=(const SolveDispatcherScope&) = delete;

private:
	btDispatcher* m_previous;
};
/// The dispatcher of the innermost SolveDispatcherScope of this thread, or null.
btDispatcher* scopedSolveDispatcher();

/// Makes solver use shared's joint warm-start store instead of its own (null: its own again), so that
/// the solvers of a pool warm-start every joint alike whichever of them solves it. shared must outlive
/// solver's use of it.
void shareJointWarmStarts(const btSequentialImpulseConstraintSolver& solver, JointWarmStartStore* shared);

/// solver's scratch (made on first use).
SolverScratch& solverScratchOf(const btSequentialImpulseConstraintSolver& solver);
/// Drops solver's scratch (its destructor calls this).
void releaseSolverScratch(const btSequentialImpulseConstraintSolver& solver);

/// Friction rows per contact row: 2 with SOLVER_USE_2_FRICTION_DIRECTIONS, else 1. The friction rows of
/// contact row j are [j * rows, (j + 1) * rows).
inline int frictionRowsPerContact(const btContactSolverInfo& info)
{
	return (info.m_solverMode & SOLVER_USE_2_FRICTION_DIRECTIONS) ? 2 : 1;
}

/// After the contact rows are set up: lists the rows that rebound if met (see bounceTarget in
/// btSequentialImpulseContactRows.cpp), and notes whether a row joins dynamic bodies more than 4 times
/// apart in mass (shock propagation).
void findBouncesAndMassRatios(SolverScratch& scratch, btAlignedObjectArray<btSolverBody>& bodies,
                              const btConstraintArray& contacts, const btContactSolverInfo& infoGlobal);

/// Solves friction row rowIndex within the bounds its normal row's impulse allows.
btScalar solveFrictionRow(btSolverBody* bodies, btConstraintArray& contacts, btConstraintArray& friction, int rowIndex);

/// Fills the info1.m_numConstraintRows rows at firstRow for one joint, warm started from warmStart when it
/// has as many rows; false if the joint produced non-finite rows (it is then disabled, with a warning).
bool convertJoint(btAlignedObjectArray<btSolverBody>& bodies, btSolverConstraint* firstRow,
                  btTypedConstraint* constraint, const btTypedConstraint::btConstraintInfo1& info1, int solverBodyIdA,
                  int solverBodyIdB, const btContactSolverInfo& infoGlobal, SolverJointBlock& block,
                  const JointImpulses& warmStart);
/// One sweep over the rows of joint jointIndex (its block, then its other rows); returns the squared
/// impulse change.
btScalar solveJoint(const SolverScratch& scratch, btSolverBody* bodies, btConstraintArray& jointRows,
                    const btAlignedObjectArray<btTypedConstraint::btConstraintInfo1>& sizes, int jointIndex);

/// One sweep over the joints in order (backwards when reverse), skipping joints whose own iteration count
/// is used up; returns the squared impulse change.
btScalar sweepJoints(const SolverScratch& scratch, btSolverBody* bodies, btConstraintArray& jointRows,
                     const btAlignedObjectArray<btTypedConstraint::btConstraintInfo1>& sizes,
                     const btAlignedObjectArray<int>& order, int iteration, bool reverse);

/// The restitution pass, after the velocity sweeps: every bouncing row of a manifold that was met is
/// driven to its rebound velocity (accumulated impulse kept >= 0).
void solveRestitution(SolverScratch& scratch, btSolverBody* bodies, btConstraintArray& contacts,
                      const btContactSolverInfo& infoGlobal);
/// The bottom-up sweeps, each contact holding its lower body fixed, in solves where a contact joins bodies
/// of very different masses (heavy on light).
void propagateShock(SolverScratch& scratch, btAlignedObjectArray<btSolverBody>& bodies, btConstraintArray& contacts,
                    btConstraintArray& friction, const btContactSolverInfo& infoGlobal);
}  // namespace caliber

#endif  // CALIBER_SOLVER_SCRATCH_H
