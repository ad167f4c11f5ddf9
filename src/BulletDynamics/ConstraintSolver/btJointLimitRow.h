// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_LIMIT_ROW_H
#define CALIBER_JOINT_LIMIT_ROW_H

#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"

namespace caliber
{
// Makes r a one-sided limit row whose J v must not go below 0 (the row is oriented so that positive J v
// moves back into the allowed range). correctionRate is the velocity that removes the overshoot
// (fps * erp * overshoot); rowVelocity the row's J v at the start of the step. relaxation (0..1) is the
// share of a velocity into the limit that the limit stops in this step: 1 stops it dead, lower values
// let part of it through, so the limit gives way more gently.
inline void setLimitRow(JointRow& r, btScalar correctionRate, btScalar rowVelocity, btScalar relaxation)
{
	btScalar target = correctionRate;
	if (rowVelocity < btScalar(0))
		target += (btScalar(1) - btMax(btScalar(0), btMin(btScalar(1), relaxation))) * rowVelocity;
	r.error() = target;
	r.lower() = btScalar(0);
	r.upper() = SIMD_INFINITY;
}
}  // namespace caliber

#endif  // CALIBER_JOINT_LIMIT_ROW_H
