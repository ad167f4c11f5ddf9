// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet 2.89's island manager for the multithreaded world: btSimulationIslandManager's islands copied
// into Island objects (kept and reused between steps) and handed to the island dispatch function.
#include "BulletDynamics/Dynamics/btSimulationIslandManagerMt.h"

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletDynamics/ConstraintSolver/btConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btAlignedObject.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// The island of a joint: that of its simulated body (A, or B when A is static or kinematic).
int islandOfConstraint(const btTypedConstraint& constraint)
{
	const btRigidBody& a = constraint.getRigidBodyA();
	const btRigidBody& b = constraint.getRigidBodyB();
	if (!a.isStaticOrKinematicObject()) return a.getIslandTag();
	if (!b.isStaticOrKinematicObject()) return b.getIslandTag();
	return -1;
}

// Copies each island the base class reports into an Island of the manager.
struct IslandGatherer : public btSimulationIslandManager::IslandCallback
{
	btAlignedObjectArray<btSimulationIslandManagerMt::Island*>* active;
	btSimulationIslandManagerMt::Island* (*take)(void* manager, int id);
	void* manager;

	void processIsland(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                   int islandId) override
	{
		btSimulationIslandManagerMt::Island* island = take(manager, islandId);
		for (int i = 0; i < numBodies; ++i) island->bodyArray.push_back(bodies[i]);
		for (int i = 0; i < numManifolds; ++i) island->manifoldArray.push_back(manifolds[i]);
		active->push_back(island);
	}
};
}  // namespace

void btSimulationIslandManagerMt::Island::append(const Island& other)
{
	for (int i = 0; i < other.bodyArray.size(); ++i) bodyArray.push_back(other.bodyArray[i]);
	for (int i = 0; i < other.manifoldArray.size(); ++i) manifoldArray.push_back(other.manifoldArray[i]);
	for (int i = 0; i < other.constraintArray.size(); ++i) constraintArray.push_back(other.constraintArray[i]);
}

btSimulationIslandManagerMt::btSimulationIslandManagerMt()
    : m_batchIsland(0), m_minimumSolverBatchSize(128), m_batchIslandMinBodyCount(32), m_islandDispatch(serialIslandDispatch)
{
}

btSimulationIslandManagerMt::~btSimulationIslandManagerMt()
{
	for (int i = 0; i < m_allocatedIslands.size(); ++i) caliber::alignedDelete(m_allocatedIslands[i]);
}

btSimulationIslandManagerMt::Island* btSimulationIslandManagerMt::getIsland(int id)
{
	return id >= 0 && id < m_lookupIslandFromId.size() ? m_lookupIslandFromId[id] : 0;
}

btSimulationIslandManagerMt::Island* btSimulationIslandManagerMt::allocateIsland(int id, int numBodies)
{
	Island* island = 0;
	if (m_freeIslands.size() > 0)
	{
		island = m_freeIslands[m_freeIslands.size() - 1];
		m_freeIslands.pop_back();
	}
	else
	{
		island = caliber::alignedNew<Island>();
		m_allocatedIslands.push_back(island);
	}
	island->id = id;
	island->isSleeping = false;
	island->bodyArray.resize(0);
	island->bodyArray.reserve(numBodies);
	island->manifoldArray.resize(0);
	island->constraintArray.resize(0);
	if (id >= 0)
	{
		if (m_lookupIslandFromId.size() <= id) m_lookupIslandFromId.resize(id + 1, 0);
		m_lookupIslandFromId[id] = island;
	}
	return island;
}

void btSimulationIslandManagerMt::buildAndProcessIslands(btDispatcher* dispatcher, btCollisionWorld* collisionWorld,
                                                         btAlignedObjectArray<btTypedConstraint*>& constraints,
                                                         const SolverParams& solverParams)
{
	if (!dispatcher || !collisionWorld)
	{
		btReportWarning("btSimulationIslandManagerMt::buildAndProcessIslands: no dispatcher or world; nothing solved");
		return;
	}
	// Last step's islands go back to the free list.
	for (int i = 0; i < m_activeIslands.size(); ++i) m_freeIslands.push_back(m_activeIslands[i]);
	m_activeIslands.resize(0);
	m_lookupIslandFromId.resize(0);
	m_lookupIslandFromId.resize(getUnionFind().getNumElements(), 0);

	buildIslands(dispatcher, collisionWorld);
	IslandGatherer gatherer;
	gatherer.active = &m_activeIslands;
	gatherer.manager = this;
	gatherer.take = [](void* manager, int id) {
		return static_cast<btSimulationIslandManagerMt*>(manager)->allocateIsland(id, 0);
	};
	processIslands(dispatcher, collisionWorld, &gatherer);

	for (int i = 0; i < constraints.size(); ++i)
	{
		btTypedConstraint* constraint = constraints[i];
		if (!constraint || !constraint->isEnabled()) continue;
		Island* island = 0;
		if (getSplitIslands())
			island = getIsland(islandOfConstraint(*constraint));
		else if (m_activeIslands.size() > 0)
			island = m_activeIslands[0];
		if (island) island->constraintArray.push_back(constraint);  // joints of sleeping islands stay out
	}
	if (m_activeIslands.size() > 0) m_islandDispatch(&m_activeIslands, solverParams);
}

void btSimulationIslandManagerMt::solveIsland(btConstraintSolver* solver, Island& island,
                                              const SolverParams& solverParams)
{
	if (!solver || !solverParams.m_solverInfo) return;
	solver->solveGroup(island.bodyArray.size() ? &island.bodyArray[0] : 0, island.bodyArray.size(),
	                   island.manifoldArray.size() ? &island.manifoldArray[0] : 0, island.manifoldArray.size(),
	                   island.constraintArray.size() ? &island.constraintArray[0] : 0, island.constraintArray.size(),
	                   *solverParams.m_solverInfo, solverParams.m_debugDrawer, solverParams.m_dispatcher);
}

void btSimulationIslandManagerMt::serialIslandDispatch(btAlignedObjectArray<Island*>* islandsPtr,
                                                       const SolverParams& solverParams)
{
	if (!islandsPtr) return;
	for (int i = 0; i < islandsPtr->size(); ++i) solveIsland(solverParams.m_solverPool, *(*islandsPtr)[i], solverParams);
}

namespace
{
struct SolveIslandsLoop : public btIParallelForBody
{
	btAlignedObjectArray<btSimulationIslandManagerMt::Island*>* islands;
	const btSimulationIslandManagerMt::SolverParams* params;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
			btSimulationIslandManagerMt::solveIsland(params->m_solverPool, *(*islands)[i], *params);
	}
};
}  // namespace

namespace
{
bool isKinematic(const btCollisionObject* object) { return object && object->isKinematicObject(); }

// A kinematic body is in no island, but the solver of every island that touches it gives it a solver
// entry and writes its companion id: two islands touching one kinematic body must not be solved at once.
bool touchesKinematicBody(const btSimulationIslandManagerMt::Island& island)
{
	for (int i = 0; i < island.manifoldArray.size(); ++i)
	{
		const btPersistentManifold* manifold = island.manifoldArray[i];
		if (isKinematic(manifold->getBody0()) || isKinematic(manifold->getBody1())) return true;
	}
	for (int i = 0; i < island.constraintArray.size(); ++i)
	{
		const btTypedConstraint* constraint = island.constraintArray[i];
		if (constraint->getRigidBodyA().isKinematicObject() || constraint->getRigidBodyB().isKinematicObject())
			return true;
	}
	return false;
}
}  // namespace

void btSimulationIslandManagerMt::parallelIslandDispatch(btAlignedObjectArray<Island*>* islandsPtr,
                                                         const SolverParams& solverParams)
{
	if (!islandsPtr) return;
	// Islands that touch kinematic bodies share those bodies' solver bookkeeping: they are solved one
	// after another on this thread first, and the rest in parallel.
	static thread_local btAlignedObjectArray<Island*> parallelIslands;  // keeps its capacity between steps
	parallelIslands.resize(0);
	for (int i = 0; i < islandsPtr->size(); ++i)
	{
		Island* island = (*islandsPtr)[i];
		if (touchesKinematicBody(*island))
			solveIsland(solverParams.m_solverPool, *island, solverParams);
		else
			parallelIslands.push_back(island);
	}
	islandsPtr = &parallelIslands;
	// Islands share no dynamic body, so each can be solved on its own thread with its own solver of the
	// pool (btConstraintSolverPoolMt locks one per call).
	SolveIslandsLoop loop;
	loop.islands = islandsPtr;
	loop.params = &solverParams;
	btParallelFor(0, islandsPtr->size(), 1, loop);
}
