// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet 2.89's multithreaded world and its solver pool. The world runs btDiscreteDynamicsWorld's
// pipeline (whose per-body stages use the scheduler when one is set; docs/threading.md), with the pool
// as its constraint solver and btSimulationIslandManagerMt as its island manager.
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"

#include <new>

#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/Dynamics/btWorldStepContext.h"
#include "LinearMath/btAlignedObject.h"
#include "LinearMath/btSideTable.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// The joint warm-start store a pool's sequential-impulse solvers share (see init), for the world's
// large-batch solver to share too.
struct PoolState
{
	caliber::JointWarmStartStore* sharedWarmStarts = nullptr;
};
}  // namespace

// ---- btConstraintSolverPoolMt ------------------------------------------------------------------------

btConstraintSolverPoolMt::btConstraintSolverPoolMt(int numSolvers)
{
	if (numSolvers < 1)
	{
		btReportWarning("btConstraintSolverPoolMt: a pool needs at least one solver; making one");
		numSolvers = 1;
	}
	btAlignedObjectArray<btConstraintSolver*> solvers;
	for (int i = 0; i < numSolvers; ++i) solvers.push_back(new btSequentialImpulseConstraintSolver());
	init(&solvers[0], numSolvers);
}

btConstraintSolverPoolMt::btConstraintSolverPoolMt(btConstraintSolver** solvers, int numSolvers)
{
	// The pool takes the solvers over and deletes them, as Bullet's does; null entries are skipped.
	btAlignedObjectArray<btConstraintSolver*> given;
	for (int i = 0; solvers && i < numSolvers; ++i)
		if (solvers[i]) given.push_back(solvers[i]);
	if (given.size() != numSolvers)
		btReportWarning("btConstraintSolverPoolMt: null solvers or a bad count; only the valid solvers are used");
	if (given.size() == 0) given.push_back(new btSequentialImpulseConstraintSolver());
	init(&given[0], given.size());
}

void btConstraintSolverPoolMt::init(btConstraintSolver** solvers, int numSolvers)
{
	m_solverType = solvers[0]->getSolverType();
	m_solvers.resize(numSolvers);
	for (int i = 0; i < numSolvers; ++i)
	{
		new (&m_solvers[i].mutex) btSpinMutex();
		m_solvers[i].solver = solvers[i];
	}
	// A joint is solved by whichever solver of the pool is free: the sequential-impulse solvers of the
	// pool keep their joints' warm-start impulses in the first one's store, so every joint starts from
	// its own last impulses whichever solver solved it last (and the results do not depend on threads).
	const btSequentialImpulseConstraintSolver* first = dynamic_cast<btSequentialImpulseConstraintSolver*>(solvers[0]);
	if (!first) return;
	caliber::JointWarmStartStore* shared = &caliber::solverScratchOf(*first).warmStarts;
	caliber::sideTable<PoolState>().acquire(this).sharedWarmStarts = shared;
	for (int i = 1; i < numSolvers; ++i)
		if (const btSequentialImpulseConstraintSolver* solver = dynamic_cast<btSequentialImpulseConstraintSolver*>(solvers[i]))
			caliber::shareJointWarmStarts(*solver, shared);
}

btConstraintSolverPoolMt::~btConstraintSolverPoolMt()
{
	caliber::sideTable<PoolState>().release(this);
	// Last first: the first solver holds the store the others share.
	for (int i = m_solvers.size() - 1; i >= 0; --i)
	{
		delete m_solvers[i].solver;
		m_solvers[i].solver = 0;
	}
}

btConstraintSolverPoolMt::ThreadSolver* btConstraintSolverPoolMt::getAndLockThreadSolver()
{
	// Start at this thread's own solver: on the main thread (index 0) that is always the first one, so
	// a serial world uses one solver, as the single-threaded world does.
	const int count = m_solvers.size();
	const int start = int(btGetCurrentThreadIndex() % unsigned(count));
	for (;;)
	{
		for (int i = 0; i < count; ++i)
		{
			ThreadSolver& candidate = m_solvers[(start + i) % count];
			if (btMutexTryLock(&candidate.mutex)) return &candidate;
		}
	}
}

btScalar btConstraintSolverPoolMt::solveGroup(btCollisionObject** bodies, int numBodies,
                                              btPersistentManifold** manifolds, int numManifolds,
                                              btTypedConstraint** constraints, int numConstraints,
                                              const btContactSolverInfo& info, btIDebugDraw* debugDrawer,
                                              btDispatcher* dispatcher)
{
	ThreadSolver* threadSolver = getAndLockThreadSolver();
	const btScalar residual = threadSolver->solver->solveGroup(bodies, numBodies, manifolds, numManifolds, constraints,
	                                                           numConstraints, info, debugDrawer, dispatcher);
	btMutexUnlock(&threadSolver->mutex);
	return residual;
}

void btConstraintSolverPoolMt::prepareSolve(int numBodies, int numManifolds)
{
	for (int i = 0; i < m_solvers.size(); ++i) m_solvers[i].solver->prepareSolve(numBodies, numManifolds);
}

void btConstraintSolverPoolMt::allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer)
{
	for (int i = 0; i < m_solvers.size(); ++i) m_solvers[i].solver->allSolved(info, debugDrawer);
}

void btConstraintSolverPoolMt::reset()
{
	for (int i = 0; i < m_solvers.size(); ++i) m_solvers[i].solver->reset();
}

// ---- btDiscreteDynamicsWorldMt ---------------------------------------------------------------------

btDiscreteDynamicsWorldMt::btDiscreteDynamicsWorldMt(btDispatcher* dispatcher, btBroadphaseInterface* pairCache,
                                                     btConstraintSolverPoolMt* solverPool,
                                                     btConstraintSolver* constraintSolverMt,
                                                     btCollisionConfiguration* collisionConfiguration)
    : btDiscreteDynamicsWorld(dispatcher, pairCache, solverPool, collisionConfiguration),
      m_constraintSolverMt(constraintSolverMt)
{
	if (m_ownsIslandManager) caliber::alignedDelete(m_islandManager);
	btSimulationIslandManagerMt* islandManager = caliber::alignedNew<btSimulationIslandManagerMt>();
	islandManager->setMinimumSolverBatchSize(m_solverInfo.m_minimumSolverBatchSize);
	m_islandManager = islandManager;
	m_ownsIslandManager = true;
	// Large batches go to constraintSolverMt, which shares the pool's joint warm starts, so a joint keeps
	// its impulses when its island grows past the threshold or shrinks below it.
	if (constraintSolverMt && constraintSolverMt != solverPool)
	{
		caliber::stepContextOf(*this).largeBatchSolver = constraintSolverMt;
		const btSequentialImpulseConstraintSolver* mt = dynamic_cast<btSequentialImpulseConstraintSolver*>(constraintSolverMt);
		caliber::JointWarmStartStore* shared =
		    solverPool ? caliber::sideTable<PoolState>().acquire(solverPool).sharedWarmStarts : nullptr;
		if (mt && shared) caliber::shareJointWarmStarts(*mt, shared);
	}
}

btDiscreteDynamicsWorldMt::~btDiscreteDynamicsWorldMt() {}

void btDiscreteDynamicsWorldMt::solveConstraints(btContactSolverInfo& solverInfo)
{
	btDiscreteDynamicsWorld::solveConstraints(solverInfo);
}

void btDiscreteDynamicsWorldMt::predictUnconstraintMotion(btScalar timeStep)
{
	btDiscreteDynamicsWorld::predictUnconstraintMotion(timeStep);
}

void btDiscreteDynamicsWorldMt::integrateTransforms(btScalar timeStep)
{
	btDiscreteDynamicsWorld::integrateTransforms(timeStep);
}

int btDiscreteDynamicsWorldMt::stepSimulation(btScalar timeStep, int maxSubSteps, btScalar fixedTimeStep)
{
	const int numSubSteps = btDiscreteDynamicsWorld::stepSimulation(timeStep, maxSubSteps, fixedTimeStep);
	// Between steps the workers would only spin: let other threads of the program have the cores.
	btGetTaskScheduler()->sleepWorkerThreadsHint();
	return numSubSteps;
}
