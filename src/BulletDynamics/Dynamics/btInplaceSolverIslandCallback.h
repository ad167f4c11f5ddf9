// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_INPLACE_SOLVER_ISLAND_CALLBACK_H
#define CALIBER_INPLACE_SOLVER_ISLAND_CALLBACK_H

#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletDynamics/ConstraintSolver/btConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btContactSolverInfo.h"
#include "LinearMath/btAlignedObjectArray.h"

class btCollisionObject;
class btDispatcher;
class btIDebugDraw;
class btPersistentManifold;
class btTypedConstraint;

// Hands islands to the solver. Small islands are gathered into one batch (up to
// m_minimumSolverBatchSize bodies and manifolds) and solved together: islands share no moving body, so
// solving them in one call gives the same answer, without paying the solver's per-call setup for each
// of a thousand two-body islands.
struct InplaceSolverIslandCallback : public btSimulationIslandManager::IslandCallback
{
	btContactSolverInfo* m_solverInfo;
	btConstraintSolver* m_solver;
	btIDebugDraw* m_debugDrawer;
	btDispatcher* m_dispatcher;
	btAlignedObjectArray<btCollisionObject*> m_bodies;
	btAlignedObjectArray<btPersistentManifold*> m_manifolds;
	btAlignedObjectArray<btTypedConstraint*> m_gatheredConstraints;
	// The step's joints grouped by island (see caliber::sortConstraintsByIsland).
	btTypedConstraint** m_sortedConstraints;
	int m_numConstraints;
	const int* m_islandConstraintStart;
	int m_numIslands;

	InplaceSolverIslandCallback(btConstraintSolver* solver, btDispatcher* dispatcher)
	    : m_solverInfo(0),
	      m_solver(solver),
	      m_debugDrawer(0),
	      m_dispatcher(dispatcher),
	      m_sortedConstraints(0),
	      m_numConstraints(0),
	      m_islandConstraintStart(0),
	      m_numIslands(0)
	{
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
		if (islandId < 0 || m_solverInfo->m_minimumSolverBatchSize <= 1)
		{
			// Everything at once (islands not split), or batching switched off.
			m_solver->solveGroup(bodies, numBodies, manifolds, numManifolds, numConstraints ? constraints : 0,
			                     numConstraints, *m_solverInfo, m_debugDrawer, m_dispatcher);
			return;
		}
		for (int i = 0; i < numBodies; ++i) m_bodies.push_back(bodies[i]);
		for (int i = 0; i < numManifolds; ++i) m_manifolds.push_back(manifolds[i]);
		for (int i = 0; i < numConstraints; ++i) m_gatheredConstraints.push_back(constraints[i]);
		if (m_bodies.size() + m_manifolds.size() + m_gatheredConstraints.size() >=
		    m_solverInfo->m_minimumSolverBatchSize)
			flush();
	}

	// Solves what has been gathered.
	void flush()
	{
		if (m_bodies.size() == 0 && m_manifolds.size() == 0 && m_gatheredConstraints.size() == 0) return;
		m_solver->solveGroup(m_bodies.size() ? &m_bodies[0] : 0, m_bodies.size(),
		                     m_manifolds.size() ? &m_manifolds[0] : 0, m_manifolds.size(),
		                     m_gatheredConstraints.size() ? &m_gatheredConstraints[0] : 0, m_gatheredConstraints.size(),
		                     *m_solverInfo, m_debugDrawer, m_dispatcher);
		m_bodies.resize(0);
		m_manifolds.resize(0);
		m_gatheredConstraints.resize(0);
	}
};

#endif  // CALIBER_INPLACE_SOLVER_ISLAND_CALLBACK_H
