// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOLVER_ROW_SOLVERS_H
#define CALIBER_SOLVER_ROW_SOLVERS_H

// Bullet's replaceable row solvers (btSingleConstraintRowSolver): Caliber's kernels behind the function
// pointers, and the sweep that calls a user's replacements row by row. Internal.

#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"

namespace caliber
{
/// Caliber's kernels: generic (between the row's limits), lower limit (from the row's lower limit up),
/// and the split-impulse push row.
btScalar rowSolverGeneric(btSolverBody& bodyA, btSolverBody& bodyB, const btSolverConstraint& row);
btScalar rowSolverLowerLimit(btSolverBody& bodyA, btSolverBody& bodyB, const btSolverConstraint& row);
btScalar rowSolverPush(btSolverBody& bodyA, btSolverBody& bodyB, const btSolverConstraint& row);

/// True when both velocity row solvers are Caliber's: the sweeps then run their inlined kernels.
inline bool usesCaliberRowSolvers(btSingleConstraintRowSolver generic, btSingleConstraintRowSolver lowerLimit)
{
	return generic == &rowSolverGeneric && lowerLimit == &rowSolverLowerLimit;
}
inline bool isCaliberPushRowSolver(btSingleConstraintRowSolver push) { return push == &rowSolverPush; }

/// One velocity sweep with a user's row solvers, in the order of the inlined sweep: joint rows (generic;
/// joints solved as rows, not as blocks), contact rows (lower limit), friction and rolling rows (generic,
/// with limits of +- their coefficient times this sweep's normal impulse). Returns the summed residual.
btScalar sweepWithRowSolvers(int iteration, const btContactSolverInfo& infoGlobal, const SolverScratch& scratch,
                             btSolverBody* bodies, btConstraintArray& jointRows,
                             const btAlignedObjectArray<btTypedConstraint::btConstraintInfo1>& jointSizes,
                             const btAlignedObjectArray<int>& jointOrder, btConstraintArray& contacts,
                             const btAlignedObjectArray<int>& contactOrder, btConstraintArray& friction,
                             const btAlignedObjectArray<int>& frictionOrder, btConstraintArray& rolling,
                             const btAlignedObjectArray<int>& rollingOrder, btSingleConstraintRowSolver generic,
                             btSingleConstraintRowSolver lowerLimit);
}  // namespace caliber

#endif  // CALIBER_SOLVER_ROW_SOLVERS_H
