// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"

#include "LinearMath/btSideTable.h"

namespace
{
thread_local bool t_hasSolveIndex = false;
thread_local unsigned int t_solveIndex = 0;
thread_local btDispatcher* t_solveDispatcher = nullptr;
}  // namespace

namespace caliber
{
SolveIndexScope::SolveIndexScope(unsigned int index) : m_hadIndex(t_hasSolveIndex), m_previousIndex(t_solveIndex)
{
	t_hasSolveIndex = true;
	t_solveIndex = index;
}

SolveIndexScope::~SolveIndexScope()
{
	t_hasSolveIndex = m_hadIndex;
	t_solveIndex = m_previousIndex;
}

bool scopedSolveIndex(unsigned int& index)
{
	index = t_solveIndex;
	return t_hasSolveIndex;
}

SolveDispatcherScope::SolveDispatcherScope(btDispatcher* dispatcher) : m_previous(t_solveDispatcher)
{
	t_solveDispatcher = dispatcher;
}

SolveDispatcherScope::~SolveDispatcherScope() { t_solveDispatcher = m_previous; }

btDispatcher* scopedSolveDispatcher() { return t_solveDispatcher; }

void shareJointWarmStarts(const btSequentialImpulseConstraintSolver& solver, JointWarmStartStore* shared)
{
	SolverScratch& scratch = solverScratchOf(solver);
	scratch.sharedWarmStarts = shared == &scratch.warmStarts ? nullptr : shared;
}

SolverScratch& solverScratchOf(const btSequentialImpulseConstraintSolver& solver)
{
	return sideTable<SolverScratch>().acquire(&solver);
}

void releaseSolverScratch(const btSequentialImpulseConstraintSolver& solver)
{
	sideTable<SolverScratch>().release(&solver);
}
}  // namespace caliber
