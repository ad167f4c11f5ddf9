// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The joint position correction island by island on the task scheduler's threads. The serial pass
// (btDiscreteDynamicsWorldJointCorrection.cpp) does, per iteration, one tree solve over all joints, then
// in the first iteration one Gauss-Seidel sweep of the joints the trees left out. Joints of different
// islands move different bodies, and every step of the serial pass works articulation by articulation
// (an articulation lies in one island), except three global choices: whether another iteration runs
// (some tree moved), how far the trees move (their step is shortened by the largest turn of all), and
// whether they move at all (a singular block anywhere sends every tree's joints to the sweep). So the
// joints are grouped by island (each island's joints in the serial order) into fixed chunks, each chunk
// with its own tree solver and scratch; the chunks prepare their trees on the threads, the calling
// thread makes the three choices from the chunks' reports, and the chunks move, sweep and prepare the
// next iteration on the threads. Each body then sees the serial pass's operations in the serial order:
// the same bits at any thread count and with any scheduler.

#include "BulletDynamics/ConstraintSolver/btJointPositionPass.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "BulletDynamics/Dynamics/btJointCorrection.h"
#include "BulletDynamics/Dynamics/btWorldStepContext.h"
#include "LinearMath/btThreads.h"

namespace
{
using caliber::JointAnchorTree;
using caliber::JointCorrectionChunk;
using namespace caliber::joint_correction;

// A chunk closes once it holds this many joints (whole islands): about three ragdolls.
const int kJointsPerChunk = 32;

// What every chunk does in one loop, in this order.
struct ChunkStep : public btIParallelForBody
{
	btTypedConstraint** joints;  // grouped by island
	btAlignedObjectArray<JointCorrectionChunk>* chunks;
	int numIterations;  // the solver's (the rows' set-up reads it)
	bool move = false;  // move the prepared trees by share of their step
	btScalar share = 1;
	bool abandon = false;  // a block was singular somewhere: the prepared trees' joints go to the sweep
	bool sweep = false;    // sweep the left-over joints, unless done
	bool prepare = false;  // prepare the next iteration's trees
	bool first = false;    // ... of the first iteration (whose left-over joints are swept)
	bool finish = false;   // write the moved poses back (interpolation, inertia)

	// Over chunk numbers: a user's scheduler may split the loop anywhere.
	void forLoop(int chunkBegin, int chunkEnd) const override
	{
		for (int k = chunkBegin; k < chunkEnd; ++k) run((*chunks)[k]);
	}

	void run(JointCorrectionChunk& chunk) const
	{
		if (move && chunk.treeStatus == JointAnchorTree::kPrepared)
		{
			chunk.tree.move(share, chunk.corrected);
			chunk.writtenBack = false;
		}
		if (abandon && chunk.treeStatus != JointAnchorTree::kNothingToSolve) chunk.tree.abandon(chunk.leftOver);
		if (sweep && !chunk.swept) sweepLeftOver(chunk);
		if (prepare)
		{
			btAlignedObjectArray<btTypedConstraint*>& leftOver = first ? chunk.leftOver : chunk.discarded;
			leftOver.resize(0);
			chunk.treeStatus = chunk.tree.prepare(joints + chunk.begin, chunk.end - chunk.begin, kTreeMinJoints,
			                                      kNegligibleGap, leftOver, chunk.largestTurn);
			// Nothing any other chunk reports can change this chunk's first iteration now. Its poses are
			// written back at once too (iterations after the first read no inertia; should a later one move
			// the chunk's bodies again, they are written back again, which gives the same bits), so that a
			// world of short articulations only (ragdolls) needs no second loop.
			if (first && chunk.treeStatus == JointAnchorTree::kNothingToSolve)
			{
				sweepLeftOver(chunk);
				writeBack(chunk);
			}
		}
		if (finish && !chunk.writtenBack) writeBack(chunk);
	}

	// The serial sweep's order for these islands: the trees' left-over joints, then those without anchors.
	void sweepLeftOver(JointCorrectionChunk& chunk) const
	{
		for (int c = chunk.begin; c < chunk.end; ++c)
		{
			btVector3 unusedA, unusedB;
			if (!caliber::jointAnchors(*joints[c], unusedA, unusedB)) chunk.leftOver.push_back(joints[c]);
		}
		for (int c = 0; c < chunk.leftOver.size(); ++c)
			correctLeftOverJoint(chunk.leftOver[c], numIterations, chunk.rows, chunk.corrected);
		chunk.swept = true;
	}

	// As the serial pass's end, for this chunk's bodies; bodies that cannot move (a static body may be
	// shared by many islands) are left to the calling thread.
	static void writeBack(JointCorrectionChunk& chunk)
	{
		btAlignedObjectArray<btRigidBody*>& corrected = chunk.corrected;
		for (int i = 0; i < corrected.size(); ++i) writeBackPose(*corrected[i]);
		chunk.fixedBodies.resize(0);
		for (int i = 0; i < corrected.size(); ++i)
		{
			if (movable(*corrected[i]))
				corrected[i]->setCompanionId(-1);
			else
				chunk.fixedBodies.push_back(corrected[i]);
		}
		chunk.writtenBack = true;
	}
};

// Groups joints by island (stable counting sort by island tag) into context.jointCorrectionGrouped and
// cuts the islands into chunks; false when some joint's island cannot be told.
bool groupIntoChunks(const btDiscreteDynamicsWorld& world, const btAlignedObjectArray<btTypedConstraint*>& joints,
                     caliber::WorldStepContext& context, int& numChunks)
{
	const int numObjects = world.getNumCollisionObjects();
	btAlignedObjectArray<int>& islandOf = context.jointCorrectionIslandOf;
	if (context.jointCorrectionIslandsKnown)
	{
		// Told on the threads by selectJoints.
		for (int c = 0; c < joints.size(); ++c)
			if (islandOf[c] == -1) return false;
	}
	else
	{
		islandOf.resizeNoInitialize(joints.size());
		for (int c = 0; c < joints.size(); ++c)
		{
			islandOf[c] = islandOfJoint(*joints[c], numObjects);
			if (islandOf[c] == -1) return false;
		}
	}
	// count[t + 1]: joints of island t; then prefix sums (joints that move no body are dropped: the serial
	// pass leaves them alone too).
	btAlignedObjectArray<int>& count = context.jointCorrectionIslandCount;
	count.resize(0);
	count.resize(numObjects + 1, 0);
	int numGrouped = 0;
	for (int c = 0; c < joints.size(); ++c)
		if (islandOf[c] >= 0)
		{
			++count[islandOf[c] + 1];
			++numGrouped;
		}
	btAlignedObjectArray<JointCorrectionChunk>& chunks = context.jointCorrectionChunks;
	// Every chunk but the last holds at least kJointsPerChunk joints; grown at once, as a chunk is large.
	const int mostChunks = numGrouped / kJointsPerChunk + 1;
	if (chunks.size() < mostChunks) chunks.resize(mostChunks);
	numChunks = 0;
	int chunkBegin = 0;
	for (int t = 0; t < numObjects; ++t)
	{
		count[t + 1] += count[t];
		// Island t ends at count[t + 1]; close the chunk after it when it is full.
		if (count[t + 1] - chunkBegin >= kJointsPerChunk || (t + 1 == numObjects && count[t + 1] > chunkBegin))
		{
			chunks[numChunks].begin = chunkBegin;
			chunks[numChunks].end = count[t + 1];
			++numChunks;
			chunkBegin = count[t + 1];
		}
	}
	btAlignedObjectArray<btTypedConstraint*>& grouped = context.jointCorrectionGrouped;
	grouped.resizeNoInitialize(numGrouped);
	for (int c = 0; c < joints.size(); ++c)
		if (islandOf[c] >= 0) grouped[count[islandOf[c]]++] = joints[c];
	return true;
}
}  // namespace

namespace
{
// Constraints per task of selectJoints's loop.
const int kConstraintsPerSelectTask = 256;

// Each constraint's island (islandOfJoint) when the correction works on it, else kNotSelected; every
// constraint writes only its own slot, so any split of the loop gives the same list.
const int kNotSelected = -3;
struct SelectJoints : public btIParallelForBody
{
	btTypedConstraint* const* constraints;
	int numObjects;
	int* selection;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int c = iBegin; c < iEnd; ++c)
		{
			const btTypedConstraint& constraint = *constraints[c];
			selection[c] = constraint.isEnabled() && caliber::correctsPosition(constraint)
			                   ? islandOfJoint(constraint, numObjects)
			                   : kNotSelected;
		}
	}
};
}  // namespace

void caliber::joint_correction::selectJoints(const btDiscreteDynamicsWorld& world,
                                             const btAlignedObjectArray<btTypedConstraint*>& constraints,
                                             btAlignedObjectArray<btTypedConstraint*>& joints,
                                             WorldStepContext& context)
{
	joints.resize(0);
	context.jointCorrectionIslandsKnown = false;
	const int numConstraints = constraints.size();
	const btITaskScheduler* scheduler = btGetTaskScheduler();
	if (numConstraints < btMax(kMinJointsForParallelCorrection, 2 * kConstraintsPerSelectTask) || !scheduler ||
	    scheduler->getNumThreads() <= 1 || btThreadsAreRunning())
	{
		for (int c = 0; c < numConstraints; ++c)
		{
			btTypedConstraint* constraint = constraints[c];
			if (constraint->isEnabled() && caliber::correctsPosition(*constraint)) joints.push_back(constraint);
		}
		return;
	}
	btAlignedObjectArray<int>& selection = context.jointCorrectionSelection;
	selection.resizeNoInitialize(numConstraints);
	SelectJoints select;
	select.constraints = &constraints[0];
	select.numObjects = world.getNumCollisionObjects();
	select.selection = &selection[0];
	btParallelFor(0, numConstraints, kConstraintsPerSelectTask, select);
	btAlignedObjectArray<int>& islandOf = context.jointCorrectionIslandOf;
	islandOf.resizeNoInitialize(numConstraints);
	int numSelected = 0;
	joints.resizeNoInitialize(numConstraints);
	for (int c = 0; c < numConstraints; ++c)
	{
		if (selection[c] == kNotSelected) continue;
		joints[numSelected] = constraints[c];
		islandOf[numSelected] = selection[c];
		++numSelected;
	}
	joints.resize(numSelected);
	islandOf.resize(numSelected);
	context.jointCorrectionIslandsKnown = true;
}

bool caliber::joint_correction::correctByIsland(btDiscreteDynamicsWorld& world,
                                                const btAlignedObjectArray<btTypedConstraint*>& joints,
                                                WorldStepContext& context)
{
	btITaskScheduler* scheduler = btGetTaskScheduler();
	if (joints.size() < kMinJointsForParallelCorrection || !scheduler || scheduler->getNumThreads() <= 1) return false;
	int numChunks = 0;
	if (!groupIntoChunks(world, joints, context, numChunks)) return false;
	if (numChunks == 0) return true;  // no joint moves a body
	btAlignedObjectArray<JointCorrectionChunk>& chunks = context.jointCorrectionChunks;
	for (int k = 0; k < numChunks; ++k)
	{
		chunks[k].corrected.resize(0);
		chunks[k].leftOver.resize(0);
		chunks[k].swept = false;
		chunks[k].writtenBack = false;
		chunks[k].fixedBodies.resize(0);
	}
	ChunkStep step;
	step.joints = &context.jointCorrectionGrouped[0];
	step.chunks = &chunks;
	step.numIterations = world.getSolverInfo().m_numIterations;
	step.prepare = true;
	step.first = true;
	btParallelFor(0, numChunks, 1, step);
	const int iterations = context.jointPositionIterations;
	for (int iteration = 0;; ++iteration)
	{
		// The serial pass's global choices, from the chunks' reports in chunk order.
		bool anyPrepared = false, anySingular = false;
		btScalar largestTurn = 0;
		for (int k = 0; k < numChunks; ++k)
		{
			if (chunks[k].treeStatus == JointAnchorTree::kSingular) anySingular = true;
			if (chunks[k].treeStatus != JointAnchorTree::kPrepared) continue;
			anyPrepared = true;
			if (chunks[k].largestTurn > largestTurn) largestTurn = chunks[k].largestTurn;
		}
		// Every chunk is done when no tree was prepared in the first iteration.
		if (iteration == 0 && !anyPrepared && !anySingular) break;
		const bool treesMove = anyPrepared && !anySingular;
		const bool last = !treesMove || iteration + 1 >= iterations;
		step.move = treesMove;
		step.share = JointAnchorTree::stepShare(largestTurn);
		step.abandon = anySingular && iteration == 0;
		step.sweep = iteration == 0;
		step.prepare = !last;
		step.first = false;
		step.finish = last;
		btParallelFor(0, numChunks, 1, step);
		if (last) break;
	}
	// Bodies the correction may not move were listed but not touched on the threads.
	for (int k = 0; k < numChunks; ++k)
		for (int i = 0; i < chunks[k].fixedBodies.size(); ++i) chunks[k].fixedBodies[i]->setCompanionId(-1);
	return true;
}
