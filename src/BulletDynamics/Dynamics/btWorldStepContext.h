// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WORLD_STEP_CONTEXT_H
#define CALIBER_WORLD_STEP_CONTEXT_H

// The state and the stages Caliber adds to btDiscreteDynamicsWorld's step. btDiscreteDynamicsWorld
// declares exactly Bullet's members; what Caliber needs besides lives in a WorldStepContext, one per
// world, found through a side table (LinearMath/btSideTable.h) once per substep. The stages here are
// called from Bullet's stages (internalSingleStepSimulation, solveConstraints), so a subclass that
// replaces one of those gets Bullet's behaviour for it (docs/architecture.md).

#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "BulletDynamics/Dynamics/btJointAnchorTree.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btCountingSortOnThreads.h"

class btCollisionWorld;
class btConstraintSolver;
class btDiscreteDynamicsWorld;
class btMotionState;
class btRigidBody;
class btTypedConstraint;

namespace caliber
{
/// Bodies per task of the per-body stages (predictUnconstraintMotion, integrateTransforms): enough work
/// per task to pay for handing it out. A world with no more moving bodies runs them on the calling thread.
const int kBodiesPerTask = 64;

/// One world's Caliber-only step state, reused from step to step.
/// One chunk of the joint position correction on the threads (btDiscreteDynamicsWorldJointCorrection.cpp:
/// the sweep of the left-over joints; btJointCorrectionIslands.cpp: the whole pass island by island):
/// its row scratch and the bodies it moved; for the whole pass, also its joints, its tree solver and
/// their state. Kept from step to step, so nothing is allocated once the largest chunk has been seen.
struct JointCorrectionChunk
{
	btConstraintArray rows;
	btAlignedObjectArray<btRigidBody*> corrected;
	bool moved = false;
	int begin = 0, end = 0;  // its joints in WorldStepContext::jointCorrectionGrouped
	JointAnchorTree tree;
	int treeStatus = JointAnchorTree::kNothingToSolve;
	btScalar largestTurn = 0;
	bool swept = false;
	bool writtenBack = false;                            // its moved poses written back since they last moved
	btAlignedObjectArray<btTypedConstraint*> leftOver;   // the first iteration's joints for the sweep
	btAlignedObjectArray<btTypedConstraint*> discarded;  // later iterations' (not swept)
	btAlignedObjectArray<btRigidBody*> fixedBodies;      // bodies it listed but may not move
	char padding[128];  // chunks written by different threads stay on different cache lines
};

struct WorldStepContext
{
	/// Set once the "non-finite body" warning has been given (it is given once per world).
	bool reportedNonFiniteBody = false;
	/// Where each island's joints start in the world's m_sortedConstraints (plus one past the last), and
	/// the counting sort's fill cursor per island.
	btAlignedObjectArray<int> constraintIslandStart;
	btAlignedObjectArray<int> islandFill;
	/// sortConstraintsByIsland's counting sort on the threads.
	CountingSortScratch jointSort;
	/// The island stage's per-joint lists (the elements each joint unites, then each joint's island).
	btAlignedObjectArray<int> jointIslandTags;
	/// Scratch of the joint position correction.
	btConstraintArray jointCorrectionRows;
	btAlignedObjectArray<btRigidBody*> jointCorrectedBodies;
	btAlignedObjectArray<btTypedConstraint*> jointCorrectionJoints;
	btAlignedObjectArray<btTypedConstraint*> jointCorrectionLeftOver;
	/// The parallel sweep of the left-over joints: each joint's island, the islands' starts, the joints
	/// grouped by island, and one chunk per task.
	btAlignedObjectArray<int> jointCorrectionIslandOf;
	/// Set by joint_correction::selectJoints when it told jointCorrectionIslandOf for the selected joints.
	bool jointCorrectionIslandsKnown = false;
	btAlignedObjectArray<int> jointCorrectionSelection;
	btAlignedObjectArray<int> jointCorrectionIslandCount;
	btAlignedObjectArray<int> jointCorrectionIslandStart;
	btAlignedObjectArray<btTypedConstraint*> jointCorrectionGrouped;
	btAlignedObjectArray<JointCorrectionChunk> jointCorrectionChunks;
	/// The exact tree solve of the position correction.
	JointAnchorTree jointAnchorTree;
	/// Solver batches solved so far (the solve index of caliber::SolveIndexScope: each batch's solve is
	/// numbered in the world's sequence, whichever solver and thread solves it).
	unsigned int solveCounter = 0;
	/// The motion states' poses of a parallel synchronizeMotionStates, and the motion state each is for
	/// (null: no motion state to tell).
	btAlignedObjectArray<btTransform> motionStatePoses;
	btAlignedObjectArray<btMotionState*> motionStateTargets;
	/// Per body of that synchronizeMotionStates: its motion state (told or not), and whether the one told
	/// is a btDefaultMotionState (told on the threads when no two bodies share a motion state).
	btAlignedObjectArray<btMotionState*> motionStatesNow;
	btAlignedObjectArray<unsigned char> motionStateOnThreads;
	/// The bodies' motion states when last checked for sharing, whether they were distinct then, and the
	/// check's sorted copy.
	btAlignedObjectArray<btMotionState*> motionStatesChecked;
	btAlignedObjectArray<btMotionState*> motionStatesSorted;
	bool motionStatesDistinct = false;
	/// btDiscreteDynamicsWorldMt's solver for large batches (its constraintSolverMt), or null.
	btConstraintSolver* largeBatchSolver = nullptr;
	/// Sweeps of the joint position correction after each substep (0: off); see
	/// include/Caliber/JointPositionCorrection.h.
	int jointPositionIterations = 3;
};

/// world's step context, made on first use.
WorldStepContext& stepContextOf(const btDiscreteDynamicsWorld& world);
/// Drops world's step context (from the world's destructor).
void releaseStepContext(const btDiscreteDynamicsWorld& world);

/// Whether body takes part in world's islands (in the world, not static or kinematic).
bool isSimulatedIn(const btCollisionWorld& world, const btRigidBody& body);
/// Takes bodies whose state became non-finite out of the simulation, with a warning (once per world).
void quarantineNonFiniteBodies(btDiscreteDynamicsWorld& world, const btAlignedObjectArray<btRigidBody*>& bodies,
                               WorldStepContext& context);
/// Groups the enabled joints by island into sorted (counting sort, stable), with each island's start in
/// context.constraintIslandStart (just {0}, as for no islands, when there are no joints).
void sortConstraintsByIsland(btDiscreteDynamicsWorld& world,
                             const btAlignedObjectArray<btTypedConstraint*>& constraints,
                             btAlignedObjectArray<btTypedConstraint*>& sorted, WorldStepContext& context);
/// Moves jointed bodies so that their joints' equality rows hold at the new positions (velocities are
/// left alone): context.jointPositionIterations sweeps.
void correctJointPositions(btDiscreteDynamicsWorld& world, const btAlignedObjectArray<btTypedConstraint*>& constraints,
                           WorldStepContext& context);
}  // namespace caliber

#endif  // CALIBER_WORLD_STEP_CONTEXT_H
