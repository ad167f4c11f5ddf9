// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_INPLACE_SOLVER_ISLAND_CALLBACK_H
#define CALIBER_INPLACE_SOLVER_ISLAND_CALLBACK_H

#include "BulletCollision/CollisionDispatch/btLoneIslandSink.h"
#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletDynamics/ConstraintSolver/btConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btContactSolverInfo.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMinMax.h"

class btCollisionObject;
class btDispatcher;
class btIDebugDraw;
class btPersistentManifold;
class btTypedConstraint;

// Hands islands to the solver. Small islands are gathered into one batch (up to
// m_minimumSolverBatchSize bodies and manifolds) and solved together: islands share no moving body, so
// solving them in one call gives the same answer, without paying the solver's per-call setup for each
// of a thousand two-body islands.
//
// The island manager's walk only gathers the batches; solveBatches then solves them, one after another
// or, in btDiscreteDynamicsWorldMt, on the task scheduler's threads. Batches share no dynamic body, so
// the order they are solved in does not change a bit of the result. Each batch's solve gets the index
// it has in the step (caliber::SolveIndexScope), so that the solver's step-to-step variation of its row
// order depends on the batch, never on which solver or thread solves it.
//
// It is also a caliber::LoneIslandSink: the island manager hands it runs of lone islands (one body, no
// manifold) at once, which it gathers as processIsland would, island by island, into the same batches.
struct InplaceSolverIslandCallback : public btSimulationIslandManager::IslandCallback, public caliber::LoneIslandSink
{
	struct Batch
	{
		int firstBody, numBodies;
		int firstManifold, numManifolds;
		int firstConstraint, numConstraints;
		// A kinematic body gets a solver entry in every batch that touches it (its companion id is
		// written), so such batches are never solved at the same time. Found by solveBatches when it solves
		// in parallel (false until then).
		bool touchesKinematic;
		bool large;  // for m_largeBatchSolver
	};

	btContactSolverInfo* m_solverInfo;
	btConstraintSolver* m_solver;
	// btDiscreteDynamicsWorldMt's solver for batches of at least m_largeBatchManifolds manifolds (it
	// spreads one solve over the threads itself), or null.
	btConstraintSolver* m_largeBatchSolver;
	int m_largeBatchManifolds;
	btIDebugDraw* m_debugDrawer;
	btDispatcher* m_dispatcher;
	btAlignedObjectArray<btCollisionObject*> m_bodies;
	btAlignedObjectArray<btPersistentManifold*> m_manifolds;
	btAlignedObjectArray<btTypedConstraint*> m_gatheredConstraints;
	btAlignedObjectArray<Batch> m_batches;
	btAlignedObjectArray<int> m_parallelBatches;
	// The large batches of a parallel solve, the whole group's first (see solveBatches).
	btAlignedObjectArray<int> m_wholeBatches;
	Batch m_open;
	// The step's joints grouped by island (see caliber::sortConstraintsByIsland).
	btTypedConstraint** m_sortedConstraints;
	int m_numConstraints;
	const int* m_islandConstraintStart;
	int m_numIslands;

	InplaceSolverIslandCallback(btConstraintSolver* solver, btDispatcher* dispatcher)
	    : m_solverInfo(0),
	      m_solver(solver),
	      m_largeBatchSolver(0),
	      m_largeBatchManifolds(0),
	      m_debugDrawer(0),
	      m_dispatcher(dispatcher),
	      m_sortedConstraints(0),
	      m_numConstraints(0),
	      m_islandConstraintStart(0),
	      m_numIslands(0)
	{
		openBatch();
	}

	void setConstraints(btTypedConstraint** sortedConstraints, int numConstraints, const int* islandStart,
	                    int numIslands)
	{
		m_sortedConstraints = sortedConstraints;
		m_numConstraints = numConstraints;
		m_islandConstraintStart = islandStart;
		m_numIslands = numIslands;
	}

	void setup(btContactSolverInfo* solverInfo, btIDebugDraw* debugDrawer)
	{
		m_solverInfo = solverInfo;
		m_debugDrawer = debugDrawer;
		m_bodies.resize(0);
		m_manifolds.resize(0);
		m_gatheredConstraints.resize(0);
		m_batches.resize(0);
		openBatch();
	}

	void processIsland(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                   int islandId) override
	{
		btTypedConstraint** constraints = m_sortedConstraints;
		int numConstraints = m_numConstraints;
		if (islandId >= 0)
		{
			const bool known = islandId < m_numIslands;
			constraints = known ? m_sortedConstraints + m_islandConstraintStart[islandId] : 0;
			numConstraints = known ? m_islandConstraintStart[islandId + 1] - m_islandConstraintStart[islandId] : 0;
		}
		// The island manager reuses its island arrays, so the island is copied.
		append(m_bodies, bodies, numBodies);
		append(m_manifolds, manifolds, numManifolds);
		append(m_gatheredConstraints, constraints, numConstraints);
		// Everything at once (islands not split) or batching switched off: the island is a batch.
		const bool alone = islandId < 0 || m_solverInfo->m_minimumSolverBatchSize <= 1;
		if (alone || (m_bodies.size() - m_open.firstBody) + (m_manifolds.size() - m_open.firstManifold) +
		                     (m_gatheredConstraints.size() - m_open.firstConstraint) >=
		                 m_solverInfo->m_minimumSolverBatchSize)
			flush();
	}

	void processLoneIslands(btCollisionObject** bodies, const int* islandIds, int count) override
	{
		const int minimumBatchSize = m_solverInfo->m_minimumSolverBatchSize;
		if (m_numIslands == 0 && minimumBatchSize > 1)
		{
			// No island has joints: each island adds one body, so the open batch takes as many bodies as it
			// has room for and closes when full, as island-by-island calls would close it.
			for (int i = 0; i < count;)
			{
				const int gathered = (m_bodies.size() - m_open.firstBody) +
				                     (m_manifolds.size() - m_open.firstManifold) +
				                     (m_gatheredConstraints.size() - m_open.firstConstraint);
				const int room = btMax(1, minimumBatchSize - gathered);
				const int take = btMin(room, count - i);
				// Appended in one resize (the array grows as pushes would make it grow: to at least twice its
				// size), then copied without a capacity check each.
				const int oldSize = m_bodies.size();
				if (oldSize + take > m_bodies.capacity()) m_bodies.reserve(btMax(oldSize + take, 2 * oldSize));
				m_bodies.resizeNoInitialize(oldSize + take);
				btCollisionObject** out = &m_bodies[oldSize];
				for (int k = 0; k < take; ++k) out[k] = bodies[i + k];
				i += take;
				if (take == room) flush();
			}
			return;
		}
		for (int i = 0; i < count; ++i)
		{
			const int islandId = islandIds[i];
			// An island with joints (to a static body) takes the general path.
			if (islandId < m_numIslands && m_islandConstraintStart[islandId + 1] != m_islandConstraintStart[islandId])
			{
				processIsland(&bodies[i], 1, 0, 0, islandId);
				continue;
			}
			m_bodies.push_back(bodies[i]);
			// As processIsland: the island adds one body to the open batch, which closes when it is full.
			if (minimumBatchSize <= 1 || (m_bodies.size() - m_open.firstBody) +
			                                     (m_manifolds.size() - m_open.firstManifold) +
			                                     (m_gatheredConstraints.size() - m_open.firstConstraint) >=
			                                 minimumBatchSize)
				flush();
		}
	}

	/// Closes the batch being gathered (nothing if it is empty).
	void flush();

	/// Solves the gathered batches with m_solver, on the task scheduler's threads when parallel is true
	/// (m_solver must then be safe to call from several threads, as btConstraintSolverPoolMt is), else
	/// one after another on the calling thread. firstSolveIndex: the index the first batch's solve gets.
	void solveBatches(bool parallel, unsigned int firstSolveIndex);
	/// Solves batch index (solveBatches's loop body).
	void solveBatchAt(int index, unsigned int firstSolveIndex);
	/// Batches gathered since setup.
	int numBatches() const { return m_batches.size(); }
	/// Sets batch index's touchesKinematic (solveBatches's loop body, before the batches are solved in parallel).
	void noteKinematic(int index) { m_batches[index].touchesKinematic = touchesKinematic(m_batches[index]); }

private:
	/// Appends items[0 .. count) to array in one resize (the array grows as pushes would make it grow: to at
	/// least twice its size), then copies them without a capacity check each.
	template <class T>
	static void append(btAlignedObjectArray<T*>& array, T* const* items, int count)
	{
		if (count <= 0) return;
		const int oldSize = array.size();
		if (oldSize + count > array.capacity()) array.reserve(btMax(oldSize + count, 2 * oldSize));
		array.resizeNoInitialize(oldSize + count);
		T** out = &array[oldSize];
		for (int i = 0; i < count; ++i) out[i] = items[i];
	}

	void openBatch()
	{
		m_open.firstBody = m_bodies.size();
		m_open.firstManifold = m_manifolds.size();
		m_open.firstConstraint = m_gatheredConstraints.size();
		m_open.numBodies = m_open.numManifolds = m_open.numConstraints = 0;
		m_open.touchesKinematic = false;
		m_open.large = false;
	}
	bool touchesKinematic(const Batch& batch) const;
};

#endif  // CALIBER_INPLACE_SOLVER_ISLAND_CALLBACK_H
