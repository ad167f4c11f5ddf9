// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOLVER_JOINT_BLOCK_H
#define CALIBER_SOLVER_JOINT_BLOCK_H

#include "LinearMath/btScalar.h"

namespace caliber
{
/// The equality rows of one joint (its leading rows without bounds: a ball joint's three, a hinge's
/// five) solved together as one small linear system per sweep instead of one row after another. Each
/// joint is then exact on its own in every sweep, however its rows couple through the bodies' inertia,
/// which is what makes chains and ragdolls hold at the usual iteration counts.
struct SolverJointBlock
{
	enum
	{
		MAX_ROWS = 6
	};
	/// First row in the solver's joint-row array and number of rows in the block (0: no block).
	int m_firstRow;
	int m_size;
	/// Per row: the velocity the row asks for minus J v at the start of the solve.
	btScalar m_target[MAX_ROWS];
	/// (J M^-1 J^T)^-1 of the block rows, column-major with stride MAX_ROWS, zero outside m_size x m_size.
	btScalar m_invK[MAX_ROWS * MAX_ROWS];
};
}  // namespace caliber

#endif  // CALIBER_SOLVER_JOINT_BLOCK_H
