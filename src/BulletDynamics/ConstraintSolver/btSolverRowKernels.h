// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SOLVER_ROW_KERNELS_H
#define CALIBER_SOLVER_ROW_KERNELS_H

// The inner loop of the sequential-impulse solver: one projected Gauss-Seidel update of one row.
// Everything a row needs is in the row and its two solver bodies, so a later batched solver can run
// rows that share no body side by side and get the same bits.

#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"

namespace caliber
{
// Written so that the compiler emits minss/maxss (the operand order matters for NaN handling).
SIMD_FORCE_INLINE btScalar btMinBranchless(btScalar a, btScalar b) { return b < a ? b : a; }
SIMD_FORCE_INLINE btScalar btMaxBranchless(btScalar a, btScalar b) { return a < b ? b : a; }

// The velocity error of the row measured through the solver's velocity changes so far.
SIMD_FORCE_INLINE btScalar rowDeltaVelocity(const btSolverBody& bodyA, const btSolverBody& bodyB,
                                            const btSolverConstraint& row)
{
	// Four lane-wise products summed as vectors, then one horizontal sum: cheaper in SIMD than four dot
	// products, each with its own horizontal sum.
	const btVector3 lanes =
	    row.m_contactNormal1 * bodyA.m_deltaLinearVelocity + row.m_relpos1CrossNormal * bodyA.m_deltaAngularVelocity +
	    row.m_contactNormal2 * bodyB.m_deltaLinearVelocity + row.m_relpos2CrossNormal * bodyB.m_deltaAngularVelocity;
	return lanes.x() + lanes.y() + lanes.z();
}

// Drives the row towards its target with the accumulated impulse clamped to [lower, upper]; returns the
// squared impulse change (the row's contribution to the least-squares residual).
SIMD_FORCE_INLINE btScalar resolveRow(btSolverBody& bodyA, btSolverBody& bodyB, btSolverConstraint& row, btScalar lower,
                                      btScalar upper)
{
	btScalar deltaImpulse =
	    row.m_rhs - row.m_appliedImpulse * row.m_cfm - rowDeltaVelocity(bodyA, bodyB, row) * row.m_jacDiagABInv;
	// Clamped without branches (minss/maxss): which bound is active changes from sweep to sweep, and a
	// mispredicted branch here costs more than the rest of the row.
	const btScalar sum = row.m_appliedImpulse + deltaImpulse;
	const btScalar clamped = btMaxBranchless(lower, btMinBranchless(upper, sum));
	deltaImpulse = clamped - row.m_appliedImpulse;
	row.m_appliedImpulse = clamped;
	bodyA.applyImpulse(row.m_contactNormal1, row.m_angularComponentA, deltaImpulse);
	bodyB.applyImpulse(row.m_contactNormal2, row.m_angularComponentB, deltaImpulse);
	return deltaImpulse * deltaImpulse;
}

// A friction row bounded by its coefficient times its contact row's normal impulse. A contact that carries
// no normal impulse (a speculative one, say) carries no friction either: the row is skipped, unless it
// holds a warm-started friction impulse, which the zero bound then takes back.
SIMD_FORCE_INLINE btScalar resolveFrictionRow(btSolverBody* bodies, btSolverConstraint& row, btScalar normalImpulse)
{
	if (!(normalImpulse > btScalar(0)) && row.m_appliedImpulse == btScalar(0)) return btScalar(0);
	const btScalar bound = row.m_friction * btMaxBranchless(btScalar(0), normalImpulse);
	return resolveRow(bodies[row.m_solverBodyIdA], bodies[row.m_solverBodyIdB], row, -bound, bound);
}

// The split-impulse counterpart: works on the push and turn velocities, impulse kept >= 0.
SIMD_FORCE_INLINE btScalar resolvePushRow(btSolverBody& bodyA, btSolverBody& bodyB, btSolverConstraint& row)
{
	const btVector3 lanes =
	    row.m_contactNormal1 * bodyA.m_pushVelocity + row.m_relpos1CrossNormal * bodyA.m_turnVelocity +
	    row.m_contactNormal2 * bodyB.m_pushVelocity + row.m_relpos2CrossNormal * bodyB.m_turnVelocity;
	const btScalar deltaVelocity = lanes.x() + lanes.y() + lanes.z();
	btScalar deltaImpulse =
	    row.m_rhsPenetration - row.m_appliedPushImpulse * row.m_cfm - deltaVelocity * row.m_jacDiagABInv;
	const btScalar clamped = btMaxBranchless(btScalar(0), row.m_appliedPushImpulse + deltaImpulse);
	deltaImpulse = clamped - row.m_appliedPushImpulse;
	row.m_appliedPushImpulse = clamped;
	bodyA.internalApplyPushImpulse(row.m_contactNormal1, row.m_angularComponentA, deltaImpulse);
	bodyB.internalApplyPushImpulse(row.m_contactNormal2, row.m_angularComponentB, deltaImpulse);
	return deltaImpulse * deltaImpulse;
}
}  // namespace caliber

#endif  // CALIBER_SOLVER_ROW_KERNELS_H
