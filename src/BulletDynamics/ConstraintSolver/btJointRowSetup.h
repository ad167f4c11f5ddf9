// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_ROW_SETUP_H
#define CALIBER_JOINT_ROW_SETUP_H

// The one row set-up of a joint, shared by the solver (caliber::convertJoint, velocity rows) and the
// world's joint position pass (position rows): clear the rows, point a btConstraintInfo2 at them and let
// the joint write them with getInfo2.

#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"

namespace caliber
{
/// What the rows are computed for, as getInfo2 sees it.
struct JointRowParameters
{
	btScalar fps;       ///< 1 / time step for velocity rows; 1 for position rows (the target is the error)
	btScalar erp;       ///< share of the position error the rows correct
	btScalar cfm;       ///< each row's constraint force mixing before the joint sets its own
	int numIterations;  ///< the solver's iteration count
	btScalar damping;   ///< the solver's damping
	int solverBodyIdA;  ///< the rows' solver bodies (the solver's; the position pass has none: -1)
	int solverBodyIdB;
	int rowIterations;  ///< each row's m_overrideNumSolverIterations
};

/// Clears numRows rows at firstRow (no Jacobian, no target, parameters.cfm, unbounded, no impulse; the
/// parameters' solver bodies and iterations, the joint as m_originalContactPoint) and lets constraint
/// write them through getInfo2.
void setUpJointRows(btTypedConstraint& constraint, btSolverConstraint* firstRow, int numRows,
                    const JointRowParameters& parameters);
}  // namespace caliber

#endif  // CALIBER_JOINT_ROW_SETUP_H
