// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMULATION_ISLAND_MANAGER_MT_H
#define BT_SIMULATION_ISLAND_MANAGER_MT_H

#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"

class btTypedConstraint;
class btConstraintSolver;
struct btContactSolverInfo;
class btIDebugDraw;

/// Bullet 2.89's island manager for the multithreaded world: islands gathered into Island objects and
/// handed to an island dispatch function (serial or parallel). btDiscreteDynamicsWorldMt installs one;
/// its own step still solves islands through btSimulationIslandManager's path (docs/threading.md).
class btSimulationIslandManagerMt : public btSimulationIslandManager
{
public:
	/// The bodies, manifolds and joints of one island.
	struct Island
	{
		btAlignedObjectArray<btCollisionObject*> bodyArray;
		btAlignedObjectArray<btPersistentManifold*> manifoldArray;
		btAlignedObjectArray<btTypedConstraint*> constraintArray;
		int id;  ///< the island's tag (-1: everything, when islands are not split)
		bool isSleeping;

		/// Appends other's bodies, manifolds and joints to this island.
		void append(const Island& other);
	};

	/// What an island dispatch function passes to the solvers.
	struct SolverParams
	{
		btConstraintSolver* m_solverPool;
		btConstraintSolver* m_solverMt;
		btContactSolverInfo* m_solverInfo;
		btIDebugDraw* m_debugDrawer;
		btDispatcher* m_dispatcher;
	};

	/// Solves one island with solver.
	static void solveIsland(btConstraintSolver* solver, Island& island, const SolverParams& solverParams);

	/// A function that solves every island of the list.
	typedef void (*IslandDispatchFunc)(btAlignedObjectArray<Island*>* islands, const SolverParams& solverParams);
	/// Solves the islands one after another on the calling thread with the solver pool.
	static void serialIslandDispatch(btAlignedObjectArray<Island*>* islandsPtr, const SolverParams& solverParams);
	/// Solves the islands with btParallelFor, each with a solver of the pool.
	static void parallelIslandDispatch(btAlignedObjectArray<Island*>* islandsPtr, const SolverParams& solverParams);

protected:
	btAlignedObjectArray<Island*> m_allocatedIslands;
	btAlignedObjectArray<Island*> m_activeIslands;
	btAlignedObjectArray<Island*> m_freeIslands;
	btAlignedObjectArray<Island*> m_lookupIslandFromId;
	Island* m_batchIsland;
	int m_minimumSolverBatchSize;
	int m_batchIslandMinBodyCount;
	IslandDispatchFunc m_islandDispatch;

	Island* getIsland(int id);
	virtual Island* allocateIsland(int id, int numBodies);

public:
	btSimulationIslandManagerMt();
	virtual ~btSimulationIslandManagerMt();

	/// Builds the islands, gathers each awake one with its manifolds and its joints among constraints,
	/// and hands them to the island dispatch function.
	virtual void buildAndProcessIslands(btDispatcher* dispatcher, btCollisionWorld* collisionWorld,
	                                    btAlignedObjectArray<btTypedConstraint*>& constraints,
	                                    const SolverParams& solverParams);

	/// Islands with fewer bodies and manifolds than this are batched by the world's solve stage.
	int getMinimumSolverBatchSize() const { return m_minimumSolverBatchSize; }
	/// Sets it (below 1 counts as 1).
	void setMinimumSolverBatchSize(int sz) { m_minimumSolverBatchSize = sz < 1 ? 1 : sz; }
	/// The function buildAndProcessIslands hands the islands to.
	IslandDispatchFunc getIslandDispatchFunction() const { return m_islandDispatch; }
	/// Sets it (0 restores serialIslandDispatch).
	void setIslandDispatchFunction(IslandDispatchFunc func) { m_islandDispatch = func ? func : serialIslandDispatch; }
};

#endif  // BT_SIMULATION_ISLAND_MANAGER_MT_H
