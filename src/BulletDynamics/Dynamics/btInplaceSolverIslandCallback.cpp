// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Dynamics/btInplaceSolverIslandCallback.h"

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btThreads.h"

namespace
{
struct SolveBatches : public btIParallelForBody
{
	InplaceSolverIslandCallback* callback;
	const int* batches;
	unsigned int firstSolveIndex;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) callback->solveBatchAt(batches[i], firstSolveIndex);
	}
};

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
	m_parallelBatches.resize(0);
	for (int i = 0; i < numBatches; ++i)
	{
		if (m_batches[i].touchesKinematic || m_batches[i].large)
			solveBatchAt(i, firstSolveIndex);
		else
			m_parallelBatches.push_back(i);
	}
	if (m_parallelBatches.size() == 0) return;
	SolveBatches loop;
	loop.callback = this;
	loop.batches = &m_parallelBatches[0];
	loop.firstSolveIndex = firstSolveIndex;
	btParallelFor(0, m_parallelBatches.size(), 1, loop);
}
