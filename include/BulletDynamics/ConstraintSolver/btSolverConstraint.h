// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOLVER_CONSTRAINT_H
#define BT_SOLVER_CONSTRAINT_H

#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

/// One row of the velocity problem between two solver bodies A and B: the relative velocity
/// n1 . vA + (r1 x n1) . wA + n2 . vB + (r2 x n2) . wB is driven towards the row's target, with the
/// accumulated impulse kept within [m_lowerLimit, m_upperLimit] (friction rows: +- friction times the
/// normal row's impulse). Rows refer to bodies by index, so that batches of independent rows can be
/// solved together.
ATTRIBUTE_ALIGNED16(struct)
btSolverConstraint
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	btVector3 m_relpos1CrossNormal;
	btVector3 m_contactNormal1;
	btVector3 m_relpos2CrossNormal;
	btVector3 m_contactNormal2;
	/// I_A^-1 (r1 x n1) and I_B^-1 (r2 x n2): the angular velocity change per unit impulse.
	btVector3 m_angularComponentA;
	btVector3 m_angularComponentB;

	/// Accumulated split-impulse (position) impulse.
	btScalar m_appliedPushImpulse;
	/// Accumulated velocity impulse.
	btScalar m_appliedImpulse;

	btScalar m_friction;
	/// 1 / (J M^-1 J^T): impulse per unit of velocity error.
	btScalar m_jacDiagABInv;
	/// Velocity-level right-hand side: the impulse that would reach the target from the start velocities.
	btScalar m_rhs;
	btScalar m_cfm;
	btScalar m_lowerLimit;
	btScalar m_upperLimit;
	/// Right-hand side of the split-impulse (position) pass.
	btScalar m_rhsPenetration;
	/// The manifold point the row came from (contact and friction rows), for warm starting and write-back.
	void* m_originalContactPoint;

	int m_overrideNumSolverIterations;
	/// Friction rows: the index of their normal row.
	int m_frictionIndex;
	int m_solverBodyIdA;
	int m_solverBodyIdB;

	enum btSolverConstraintType
	{
		BT_SOLVER_CONTACT_1D = 0,
		BT_SOLVER_FRICTION_1D
	};
};

typedef btAlignedObjectArray<btSolverConstraint> btConstraintArray;

#endif  // BT_SOLVER_CONSTRAINT_H
