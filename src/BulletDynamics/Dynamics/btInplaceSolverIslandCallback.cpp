// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Dynamics/btInplaceSolverIslandCallback.h"

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btThreads.h"

namespace
{
// Item 0 is the whole group when there is one (its large batches one after another on one thread), each
// other item one batch.
struct SolveBatches : public btIParallelForBody
{
	InplaceSolverIslandCallback* callback;
	const int* batches;
	const int* wholeBatches;
	int numWhole;
	unsigned int firstSolveIndex;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			if (numWhole == 0)
				callback->solveBatchAt(batches[i], firstSolveIndex);
			else if (i == 0)
				for (int k = 0; k < numWhole; ++k) callback->solveBatchAt(wholeBatches[k], firstSolveIndex);
			else
				callback->solveBatchAt(batches[i - 1], firstSolveIndex);
		}
	}
};

// A batch's rough solve cost, to balance the whole group against the other batches: each manifold's and
// joint's rows are swept every iteration, a body is set up and written back once.
int solveCost(const InplaceSolverIslandCallback::Batch& batch)
{
	return 8 * batch.numManifolds + 8 * batch.numConstraints + batch.numBodies;
}

// Whether each batch touches a kinematic body, on the threads: a batch reads only its own manifolds, joints
// and bodies (a cache miss or two each) and writes only its own flag.
struct FindKinematicBatches : public btIParallelForBody
{
	InplaceSolverIslandCallback* callback;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) callback->noteKinematic(i);
	}
};

// Batches per task of that loop.
const int kBatchesPerKinematicTask = 4;
}  // namespace

void InplaceSolverIslandCallback::flush()
{
	m_open.numBodies = m_bodies.size() - m_open.firstBody;
	m_open.numManifolds = m_manifolds.size() - m_open.firstManifold;
	m_open.numConstraints = m_gatheredConstraints.size() - m_open.firstConstraint;
	if (m_open.numBodies == 0 && m_open.numManifolds == 0 && m_open.numConstraints == 0) return;
	// Only the parallel solve needs it: solveBatches finds it then, on the threads.
	m_open.touchesKinematic = false;
	m_open.large = m_largeBatchSolver && m_open.numManifolds >= m_largeBatchManifolds;
	m_batches.push_back(m_open);
	openBatch();
}

bool InplaceSolverIslandCallback::touchesKinematic(const Batch& batch) const
{
	for (int i = 0; i < batch.numManifolds; ++i)
	{
		const btPersistentManifold* manifold = m_manifolds[batch.firstManifold + i];
		if (manifold->getBody0()->isKinematicObject() || manifold->getBody1()->isKinematicObject()) return true;
	}
	for (int i = 0; i < batch.numConstraints; ++i)
	{
		const btTypedConstraint* joint = m_gatheredConstraints[batch.firstConstraint + i];
		if (joint->getRigidBodyA().isKinematicObject() || joint->getRigidBodyB().isKinematicObject()) return true;
	}
	for (int i = 0; i < batch.numBodies; ++i)
		if (m_bodies[batch.firstBody + i]->isKinematicObject()) return true;
	return false;
}

void InplaceSolverIslandCallback::solveBatchAt(int index, unsigned int firstSolveIndex)
{
	const Batch& batch = m_batches[index];
	caliber::SolveIndexScope solveIndex(firstSolveIndex + unsigned(index));
	btConstraintSolver* solver = batch.large ? m_largeBatchSolver : m_solver;
	solver->solveGroup(batch.numBodies ? &m_bodies[batch.firstBody] : 0, batch.numBodies,
	                     batch.numManifolds ? &m_manifolds[batch.firstManifold] : 0, batch.numManifolds,
	                     batch.numConstraints ? &m_gatheredConstraints[batch.firstConstraint] : 0,
	                     batch.numConstraints, *m_solverInfo, m_debugDrawer, m_dispatcher);
}

void InplaceSolverIslandCallback::solveBatches(bool parallel, unsigned int firstSolveIndex)
{
	flush();
	const int numBatches = m_batches.size();
	if (!parallel || numBatches < 2)
	{
		for (int i = 0; i < numBatches; ++i) solveBatchAt(i, firstSolveIndex);
		return;
	}
	// Large batches (whose solver is parallel inside) and batches with a kinematic body one after another
	// here, the rest on the scheduler's threads.
	FindKinematicBatches findKinematic;
	findKinematic.callback = this;
	btParallelFor(0, numBatches, kBatchesPerKinematicTask, findKinematic);
	// Batches with a kinematic body first, one after another here; the small batches go to the threads.
	m_parallelBatches.resize(0);
	m_wholeBatches.resize(0);
	int smallCost = 0;
	for (int i = 0; i < numBatches; ++i)
	{
		const Batch& batch = m_batches[i];
		if (batch.touchesKinematic)
			solveBatchAt(i, firstSolveIndex);
		else if (batch.large)
			m_wholeBatches.push_back(i);
		else
		{
			m_parallelBatches.push_back(i);
			smallCost += solveCost(batch);
		}
	}
	// The large batches (whose solver spreads a solve over the threads itself) are spread one after another
	// here, but for a whole group, solved on one thread while the others solve the small batches: the
	// cheapest large batches while their costs add up to no more than the small batches' share of each other
	// thread. Spreading a solve of a few hundred manifolds over two threads gains little or loses (its loops'
	// waits and the rows crossing cores); beside the small batches it costs the step nothing. The solver
	// gives the same bits either way (nested in a task, its loops run on that thread).
	const int numThreads = btMax(2, btGetTaskScheduler()->getNumThreads());
	const int wholeBudget = smallCost / (numThreads - 1);
	// By cost, cheapest first (insertion sort: a step has a handful of large batches).
	for (int i = 1; i < m_wholeBatches.size(); ++i)
		for (int k = i; k > 0 && solveCost(m_batches[m_wholeBatches[k]]) < solveCost(m_batches[m_wholeBatches[k - 1]]);
		     --k)
			btSwap(m_wholeBatches[k], m_wholeBatches[k - 1]);
	int numWhole = 0;
	for (int wholeCost = 0; numWhole < m_wholeBatches.size(); ++numWhole)
	{
		wholeCost += solveCost(m_batches[m_wholeBatches[numWhole]]);
		if (wholeCost > wholeBudget) break;
	}
	// Spread in batch order (the order does not matter: batches share no moving body).
	for (int i = 0; i < numBatches; ++i)
	{
		if (!m_batches[i].large || m_batches[i].touchesKinematic) continue;
		bool whole = false;
		for (int k = 0; k < numWhole && !whole; ++k) whole = m_wholeBatches[k] == i;
		if (!whole) solveBatchAt(i, firstSolveIndex);
	}
	if (m_parallelBatches.size() == 0) return;
	SolveBatches loop;
	loop.callback = this;
	loop.batches = &m_parallelBatches[0];
	loop.wholeBatches = numWhole ? &m_wholeBatches[0] : 0;
	loop.numWhole = numWhole;
	loop.firstSolveIndex = firstSolveIndex;
	btParallelFor(0, m_parallelBatches.size() + (numWhole ? 1 : 0), 1, loop);
}
