// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DISCRETE_DYNAMICS_WORLD_MT_H
#define BT_DISCRETE_DYNAMICS_WORLD_MT_H

#include "BulletDynamics/ConstraintSolver/btConstraintSolver.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "BulletDynamics/Dynamics/btSimulationIslandManagerMt.h"
#include "LinearMath/btThreads.h"

/// Bullet 2.89's pool of solvers: each solveGroup call locks one free solver of the pool, so islands can
/// be solved on several threads at once. Serial calls from the main thread always use the first one.
class btConstraintSolverPoolMt : public btConstraintSolver
{
public:
	/// A pool of numSolvers btSequentialImpulseConstraintSolvers, owned by the pool (below 1 counts as 1).
	explicit btConstraintSolverPoolMt(int numSolvers);
	/// A pool of the given solvers, which the pool deletes (as Bullet's); null entries are skipped.
	btConstraintSolverPoolMt(btConstraintSolver** solvers, int numSolvers);
	virtual ~btConstraintSolverPoolMt();

	/// Solves the group with a solver of the pool.
	btScalar solveGroup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
	                    btIDebugDraw* debugDrawer, btDispatcher* dispatcher) override;
	/// Forwarded to every solver of the pool.
	void prepareSolve(int numBodies, int numManifolds) override;
	/// Forwarded to every solver of the pool.
	void allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override;
	/// Resets every solver of the pool.
	void reset() override;
	/// The type of the pool's solvers.
	btConstraintSolverType getSolverType() const override { return m_solverType; }

private:
	const static size_t kCacheLineSize = 128;
	struct ThreadSolver
	{
		btConstraintSolver* solver;
		btSpinMutex mutex;
		char _cachelinePadding[kCacheLineSize - sizeof(btSpinMutex) - sizeof(void*)];  // one line each
	};
	btAlignedObjectArray<ThreadSolver> m_solvers;
	btConstraintSolverType m_solverType;

	ThreadSolver* getAndLockThreadSolver();
	void init(btConstraintSolver** solvers, int numSolvers);
};

/// Bullet 2.89's multithreaded world. Set up as in Bullet's examples (a scheduler set with
/// btSetTaskScheduler, btCollisionDispatcherMt, a btConstraintSolverPoolMt, an Mt solver); it steps as
/// btDiscreteDynamicsWorld and gives the same state bits. Which stages run in parallel: docs/threading.md.
ATTRIBUTE_ALIGNED16(class)
btDiscreteDynamicsWorldMt : public btDiscreteDynamicsWorld
{
protected:
	btConstraintSolver* m_constraintSolverMt;

	void solveConstraints(btContactSolverInfo & solverInfo) override;
	void predictUnconstraintMotion(btScalar timeStep) override;
	void integrateTransforms(btScalar timeStep) override;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// solverPool solves the islands (it becomes the world's constraint solver); constraintSolverMt is
	/// kept for large islands (not used by this version's solve stage).
	btDiscreteDynamicsWorldMt(btDispatcher * dispatcher, btBroadphaseInterface * pairCache,
	                          btConstraintSolverPoolMt * solverPool, btConstraintSolver * constraintSolverMt,
	                          btCollisionConfiguration * collisionConfiguration);
	virtual ~btDiscreteDynamicsWorldMt();

	/// Steps as btDiscreteDynamicsWorld, then hints the scheduler that its workers may sleep.
	int stepSimulation(btScalar timeStep, int maxSubSteps = 1, btScalar fixedTimeStep = btScalar(1.) / btScalar(60.))
	    override;
};

#endif  // BT_DISCRETE_DYNAMICS_WORLD_MT_H
