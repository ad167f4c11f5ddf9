// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"

#include "LinearMath/btSideTable.h"

namespace caliber
{
SolverScratch& solverScratchOf(const btSequentialImpulseConstraintSolver& solver)
{
	return sideTable<SolverScratch>().acquire(&solver);
}

void releaseSolverScratch(const btSequentialImpulseConstraintSolver& solver)
{
	sideTable<SolverScratch>().release(&solver);
}
}  // namespace caliber
