// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_GENERIC_6DOF_ROWS_H
#define CALIBER_GENERIC_6DOF_ROWS_H

// Internal: the rows of btGeneric6DofConstraint, as free functions over the joint, shared with the
// joints built on it (the spring and universal joints). Coordinates 0..2 are the linear ones, 3..5 the
// Euler angles; everything reads the state of the joint's last calculateTransforms.

#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"

namespace caliber
{
/// True when both joint frames are finite; otherwise warns and disables the joint.
bool sixDofFramesFinite(btGeneric6DofConstraint& joint);

/// How coordinate i (0..5) is constrained: lower == upper, lower < upper, or lower > upper.
bool sixDofIsLocked(const btGeneric6DofConstraint& joint, int coordinate);
bool sixDofIsLimited(const btGeneric6DofConstraint& joint, int coordinate);
/// True when coordinate i has a motor row (motor on and the coordinate not locked).
bool sixDofHasMotorRow(const btGeneric6DofConstraint& joint, int coordinate);
/// The number of lock, limit and motor rows (without any a subclass adds).
int sixDofLimitMotorRowCount(const btGeneric6DofConstraint& joint);
/// Writes the lock, limit and motor rows from row 0 on (transforms already calculated); returns their
/// number.
int writeSixDofLimitMotorRows(btGeneric6DofConstraint& joint, btTypedConstraint::btConstraintInfo2* info,
                              const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
                              const btVector3& angVelB);
/// Coordinate i's measured value (angles in radians).
btScalar sixDofCoordinate(const btGeneric6DofConstraint& joint, int coordinate);
/// Coordinate i's rate for the given body velocities.
btScalar sixDofCoordinateVelocity(const btGeneric6DofConstraint& joint, int coordinate, const btVector3& linVelA,
                                  const btVector3& linVelB, const btVector3& angVelA, const btVector3& angVelB);
/// The Jacobian whose product with the bodies' velocities (vA, wA, vB, wB) is coordinate i's rate.
void sixDofCoordinateJacobian(const btGeneric6DofConstraint& joint, int coordinate, btVector3& linearA,
                              btVector3& angularA, btVector3& linearB, btVector3& angularB);
/// Writes into row a row that drives coordinate i's rate to targetRate, projected so that its impulses
/// leave the locked rows' velocities alone (the rows writeSixDofLimitMotorRows wrote earlier in the same
/// getInfo2; see the .cpp); its impulse is the coordinate's generalised force times the step.
void writeSixDofCoordinateRow(const btGeneric6DofConstraint& joint, btTypedConstraint::btConstraintInfo2* info, int row,
                              int coordinate, btScalar targetRate);
/// The rate change of coordinate i per unit impulse of its row, with the locked coordinates held (as
/// writeSixDofLimitMotorRows found them earlier in the same getInfo2): the inverse of the coordinate's
/// effective mass (0 if nothing can move it).
btScalar sixDofCoordinateInverseMass(const btGeneric6DofConstraint& joint, int coordinate);
/// Forgets this thread's block of locked rows, so that the coordinate functions above see no locked
/// coordinates held until the next writeSixDofLimitMotorRows (for callers outside a getInfo2, where the
/// block on the thread may be another joint's, even one that died at the same address).
void forgetSixDofLockedBlock();
}  // namespace caliber

#endif  // CALIBER_GENERIC_6DOF_ROWS_H
