// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btGeneric6DofRows.h"

#include "BulletDynamics/ConstraintSolver/btJointBlockMath.h"
#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btMemberAccess.h"
#include "LinearMath/btWarningHook.h"

// The joint's coordinates and row directions, as calculateTransforms left them (see
// btGeneric6DofConstraint.cpp for what they are). Read through pointers to members, so that the joint
// keeps Bullet's declarations and needs no friends.
CALIBER_MEMBER_ACCESS(SixDofLinearLimits, btGeneric6DofConstraint, btTranslationalLimitMotor, m_linearLimits)
CALIBER_MEMBER_ACCESS(SixDofAngularLimits, btGeneric6DofConstraint, btRotationalLimitMotor[3], m_angularLimits)
CALIBER_MEMBER_ACCESS(SixDofLinearDiff, btGeneric6DofConstraint, btVector3, m_calculatedLinearDiff)
CALIBER_MEMBER_ACCESS(SixDofAngleDiff, btGeneric6DofConstraint, btVector3, m_calculatedAxisAngleDiff)
CALIBER_MEMBER_ACCESS(SixDofFlags, btGeneric6DofConstraint, int, m_flags)
CALIBER_MEMBER_ACCESS(SixDofLinearRowAxis, btGeneric6DofConstraint, btVector3[3], m_linearRowAxis)
CALIBER_MEMBER_ACCESS(SixDofAngularRowAxis, btGeneric6DofConstraint, btVector3[3], m_angularRowAxis)
CALIBER_MEMBER_ACCESS(SixDofLinearRowPoint, btGeneric6DofConstraint, btVector3, m_linearRowPoint)
CALIBER_MEMBER_ACCESS(SixDofCenterOfMassA, btGeneric6DofConstraint, btVector3, m_centerOfMassA)
CALIBER_MEMBER_ACCESS(SixDofCenterOfMassB, btGeneric6DofConstraint, btVector3, m_centerOfMassB)
// Bullet's protected motor ramp, shared by every joint with a motor.
CALIBER_MEMBER_ACCESS(JointMotorFactor, btTypedConstraint, btScalar(btScalar, btScalar, btScalar, btScalar, btScalar),
                      getMotorFactor)

namespace caliber
{
namespace
{
const btTranslationalLimitMotor& linearLimits(const btGeneric6DofConstraint& joint)
{
	return joint.*memberOf(SixDofLinearLimits{});
}
const btRotationalLimitMotor (&angularLimits(const btGeneric6DofConstraint& joint))[3]
{
	return joint.*memberOf(SixDofAngularLimits{});
}
const btVector3& linearDiff(const btGeneric6DofConstraint& joint) { return joint.*memberOf(SixDofLinearDiff{}); }
const btVector3& angleDiff(const btGeneric6DofConstraint& joint) { return joint.*memberOf(SixDofAngleDiff{}); }
int flags(const btGeneric6DofConstraint& joint) { return joint.*memberOf(SixDofFlags{}); }
const btVector3 (&linearRowAxis(const btGeneric6DofConstraint& joint))[3]
{
	return joint.*memberOf(SixDofLinearRowAxis{});
}
const btVector3 (&angularRowAxis(const btGeneric6DofConstraint& joint))[3]
{
	return joint.*memberOf(SixDofAngularRowAxis{});
}
const btVector3& linearRowPoint(const btGeneric6DofConstraint& joint)
{
	return joint.*memberOf(SixDofLinearRowPoint{});
}
const btVector3& centerOfMassA(const btGeneric6DofConstraint& joint) { return joint.*memberOf(SixDofCenterOfMassA{}); }
const btVector3& centerOfMassB(const btGeneric6DofConstraint& joint) { return joint.*memberOf(SixDofCenterOfMassB{}); }
}  // namespace

bool sixDofFramesFinite(btGeneric6DofConstraint& joint)
{
	if (isFinite(joint.getFrameOffsetA()) && isFinite(joint.getFrameOffsetB())) return true;
	btReportWarning("Caliber: btGeneric6DofConstraint: a joint frame is not finite; the joint is disabled\n", 0);
	joint.setEnabled(false);
	return false;
}

bool sixDofIsLocked(const btGeneric6DofConstraint& joint, int coordinate)
{
	if (coordinate < 3)
		return linearLimits(joint).m_lowerLimit[coordinate] == linearLimits(joint).m_upperLimit[coordinate];
	return angularLimits(joint)[coordinate - 3].m_loLimit == angularLimits(joint)[coordinate - 3].m_hiLimit;
}

bool sixDofIsLimited(const btGeneric6DofConstraint& joint, int coordinate)
{
	if (coordinate < 3)
		return linearLimits(joint).m_lowerLimit[coordinate] < linearLimits(joint).m_upperLimit[coordinate];
	return angularLimits(joint)[coordinate - 3].m_loLimit < angularLimits(joint)[coordinate - 3].m_hiLimit;
}

bool sixDofHasMotorRow(const btGeneric6DofConstraint& joint, int coordinate)
{
	const bool enabled = coordinate < 3 ? linearLimits(joint).m_enableMotor[coordinate]
	                                    : angularLimits(joint)[coordinate - 3].m_enableMotor;
	return enabled && !sixDofIsLocked(joint, coordinate);
}

int sixDofLimitMotorRowCount(const btGeneric6DofConstraint& joint)
{
	int rows = 0;
	for (int c = 0; c < 6; ++c)
		rows += (sixDofIsLocked(joint, c) || sixDofIsLimited(joint, c) ? 1 : 0) + (sixDofHasMotorRow(joint, c) ? 1 : 0);
	return rows;
}

btScalar sixDofCoordinate(const btGeneric6DofConstraint& joint, int coordinate)
{
	return coordinate < 3 ? linearDiff(joint)[coordinate] : angleDiff(joint)[coordinate - 3];
}

btScalar sixDofCoordinateVelocity(const btGeneric6DofConstraint& joint, int coordinate, const btVector3& linVelA,
                                  const btVector3& linVelB, const btVector3& angVelA, const btVector3& angVelB)
{
	if (coordinate >= 3) return angularRowAxis(joint)[coordinate - 3].dot(angVelB - angVelA);
	const btVector3 velocityB = linVelB + angVelB.cross(linearRowPoint(joint) - centerOfMassB(joint));
	const btVector3 velocityA = linVelA + angVelA.cross(linearRowPoint(joint) - centerOfMassA(joint));
	return linearRowAxis(joint)[coordinate].dot(velocityB - velocityA);
}

void sixDofCoordinateJacobian(const btGeneric6DofConstraint& joint, int coordinate, btVector3& linearA,
                              btVector3& angularA, btVector3& linearB, btVector3& angularB)
{
	if (coordinate >= 3)
	{
		const btVector3& axis = angularRowAxis(joint)[coordinate - 3];
		linearA.setZero();
		linearB.setZero();
		angularA = -axis;
		angularB = axis;
		return;
	}
	const btVector3& axis = linearRowAxis(joint)[coordinate];
	linearA = -axis;
	linearB = axis;
	angularA = -(linearRowPoint(joint) - centerOfMassA(joint)).cross(axis);
	angularB = (linearRowPoint(joint) - centerOfMassB(joint)).cross(axis);
}

namespace
{
// One row's Jacobian as the solver reads it: J v = linA . vA + angA . wA + linB . vB + angB . wB.
struct RowJacobian
{
	btVector3 part[4];  // linear A, angular A, linear B, angular B

	btScalar dot(const RowJacobian& other) const
	{
		return part[0].dot(other.part[0]) + part[1].dot(other.part[1]) + part[2].dot(other.part[2]) +
		       part[3].dot(other.part[3]);
	}
	void addScaled(const RowJacobian& other, btScalar scale)
	{
		for (int i = 0; i < 4; ++i) part[i] += other.part[i] * scale;
	}
};

// M^-1 J^T with the solver's masses: linear and angular factors, nothing for static and kinematic bodies.
RowJacobian applyInverseMass(const btRigidBody& a, const btRigidBody& b, const RowJacobian& j)
{
	RowJacobian r;
	const btRigidBody* bodies[2] = {&a, &b};
	for (int k = 0; k < 2; ++k)
	{
		const btRigidBody& body = *bodies[k];
		if (body.isStaticOrKinematicObject())
		{
			r.part[2 * k].setZero();
			r.part[2 * k + 1].setZero();
			continue;
		}
		r.part[2 * k] = j.part[2 * k] * body.getLinearFactor() * body.getInvMass();
		r.part[2 * k + 1] =
		    (body.getInvInertiaTensorWorld() * (j.part[2 * k + 1] * body.getAngularFactor())) * body.getAngularFactor();
	}
	return r;
}

RowJacobian blockRow(const btVector3 (&parts)[4])
{
	RowJacobian r;
	for (int i = 0; i < 4; ++i) r.part[i] = parts[i];
	return r;
}

// Inverts the n x n matrix k (stride 6); pivots are judged against its largest diagonal entry.
bool invertSmall(const btScalar* k, int n, btScalar* inverse)
{
	if (n == 0) return true;
	btScalar largest = 0;
	for (int i = 0; i < n; ++i) largest = btMax(largest, btFabs(k[i * 6 + i]));
	if (!(largest > btScalar(0))) return false;
	return caliber::invertDense(k, n, 6, largest * btScalar(1e-6), inverse);
}

void writeJacobian(btTypedConstraint::btConstraintInfo2& info, int row, const RowJacobian& j)
{
	btScalar* targets[4] = {info.m_J1linearAxis, info.m_J1angularAxis, info.m_J2linearAxis, info.m_J2angularAxis};
	for (int k = 0; k < 4; ++k)
	{
		if (!targets[k]) continue;  // a solver may imply J2linear = -J1linear
		btScalar* p = targets[k] + row * info.rowskip;
		p[0] = j.part[k].x();
		p[1] = j.part[k].y();
		p[2] = j.part[k].z();
	}
}
}  // namespace

// Projection. The solver solves the hard locked rows J_e as one exact block. A limit, motor or spring row
// J_c solved after them would on its own see only each body's inertia about its own centre (a hinge's
// limit would act on the swinging body as if it were not pinned), and the solver would need many sweeps
// to share its impulse with the block. Removing from J_c its part along the block,
//   J_c' = J_c - a J_e,  a = (J_c M^-1 J_e^T) (J_e M^-1 J_e^T)^-1,
// makes the row's impulses M^-1-orthogonal to the block: they leave the locked rows' velocities alone,
// and J_c' M^-1 J_c'^T is the coordinate's true effective inverse mass with the locked coordinates held.
// While the block holds, J_e v = t_e, so J_c' v = J_c v - a t_e: the target moves by the same amount.
// The impulse along J_c' is still the coordinate's generalised force (the J_e part is the reaction the
// block would have supplied), so motor and spring forces keep their meaning.

namespace
{
// The hard locked rows of the joint whose rows are being written, which the rows after them are projected
// against: filled by writeLimitMotorRows, read by the rows written after it in the same getInfo2 (the
// spring joint's too), on the same thread. Scratch of one call, so it lives with the thread rather than
// in every joint.
struct LockedBlock
{
	const btGeneric6DofConstraint* joint;
	btVector3 jacobian[6][4];  // linear A, angular A, linear B, angular B
	btScalar target[6];
	btScalar inverse[36];  // of their J M^-1 J^T, row-major, stride 6
	int count;
};
thread_local LockedBlock t_lockedBlock = {};

// joint's block, or an empty one if the block on this thread belongs to another joint.
const LockedBlock& lockedBlockOf(const btGeneric6DofConstraint* joint)
{
	static const LockedBlock kNone = {};
	return t_lockedBlock.joint == joint ? t_lockedBlock : kNone;
}
}  // namespace

void forgetSixDofLockedBlock() { t_lockedBlock.joint = 0; }

btScalar sixDofCoordinateInverseMass(const btGeneric6DofConstraint& joint, int coordinate)
{
	RowJacobian j;
	sixDofCoordinateJacobian(joint, coordinate, j.part[0], j.part[1], j.part[2], j.part[3]);
	const RowJacobian weighted = applyInverseMass(joint.getRigidBodyA(), joint.getRigidBodyB(), j);
	btScalar k = j.dot(weighted);
	const LockedBlock& block = lockedBlockOf(&joint);
	const int n = block.count;
	btScalar coupling[6];
	for (int e = 0; e < n; ++e) coupling[e] = weighted.dot(blockRow(block.jacobian[e]));
	for (int e = 0; e < n; ++e)
		for (int f = 0; f < n; ++f) k -= coupling[e] * block.inverse[e * 6 + f] * coupling[f];
	return btMax(k, btScalar(0));
}

void writeSixDofCoordinateRow(const btGeneric6DofConstraint& joint, btTypedConstraint::btConstraintInfo2* info, int row,
                              int coordinate, btScalar targetRate)
{
	RowJacobian j;
	sixDofCoordinateJacobian(joint, coordinate, j.part[0], j.part[1], j.part[2], j.part[3]);
	const LockedBlock& block = lockedBlockOf(&joint);
	const int n = block.count;
	if (n > 0)
	{
		const RowJacobian weighted = applyInverseMass(joint.getRigidBodyA(), joint.getRigidBodyB(), j);
		btScalar coupling[6];
		for (int e = 0; e < n; ++e) coupling[e] = weighted.dot(blockRow(block.jacobian[e]));
		for (int f = 0; f < n; ++f)
		{
			btScalar a = 0;
			for (int e = 0; e < n; ++e) a += coupling[e] * block.inverse[e * 6 + f];
			j.addScaled(blockRow(block.jacobian[f]), -a);
			targetRate -= a * block.target[f];
		}
	}
	writeJacobian(*info, row, j);
	info->m_constraintError[row * info->rowskip] = targetRate;
}

namespace
{
// One coordinate's limit and motor settings, with the joint's flags applied (an ERP not set for the
// axis is the world's).
struct AxisSettings
{
	btScalar lower, upper, stopErp, stopCfm, normalCfm, targetVelocity, maxMotorForce, bounce;
	bool hasStopCfm, hasNormalCfm;
};

void readAxisSettings(const btGeneric6DofConstraint& joint, const btTypedConstraint::btConstraintInfo2& info,
                      AxisSettings axes[6])
{
	for (int c = 0; c < 6; ++c)
	{
		AxisSettings& a = axes[c];
		if (c < 3)
		{
			const btTranslationalLimitMotor& m = linearLimits(joint);
			a = AxisSettings{
			    m.m_lowerLimit[c],     m.m_upperLimit[c],    m.m_stopERP[c], m.m_stopCFM[c], m.m_normalCFM[c],
			    m.m_targetVelocity[c], m.m_maxMotorForce[c], btScalar(0),    false,          false};
		}
		else
		{
			const btRotationalLimitMotor& m = angularLimits(joint)[c - 3];
			a = AxisSettings{m.m_loLimit,        m.m_hiLimit,       m.m_stopERP, m.m_stopCFM, m.m_normalCFM,
			                 m.m_targetVelocity, m.m_maxMotorForce, m.m_bounce,  false,       false};
		}
		const int shift = c * BT_6DOF_FLAGS_AXIS_SHIFT;
		if (!(flags(joint) & (BT_6DOF_FLAGS_ERP_STOP << shift))) a.stopErp = info.erp;
		a.hasStopCfm = (flags(joint) & (BT_6DOF_FLAGS_CFM_STOP << shift)) != 0;
		a.hasNormalCfm = (flags(joint) & (BT_6DOF_FLAGS_CFM_NORM << shift)) != 0;
	}
}

// The locked coordinates' error-reduction targets; softLocked marks those with a stop CFM, which are
// written after the block as soft rows.
struct LockedCoordinates
{
	bool softLocked[6];
	btScalar target[6];
};

// Writes the hard locked rows from row 0 (the solver solves the leading rows without bounds or
// softness as one exact block) and keeps them in the thread's LockedBlock with the inverse of their
// J M^-1 J^T, to project the rows after them against. Returns the rows written.
int writeHardLockedRows(const btGeneric6DofConstraint& joint, btTypedConstraint::btConstraintInfo2& info,
                        const AxisSettings axes[6], LockedCoordinates& locked)
{
	int row = 0;
	LockedBlock& block = t_lockedBlock;
	block.joint = &joint;
	block.count = 0;
	for (int c = 0; c < 6; ++c)
	{
		locked.softLocked[c] = false;
		if (!sixDofIsLocked(joint, c)) continue;
		const AxisSettings& a = axes[c];
		btScalar error = a.lower - sixDofCoordinate(joint, c);
		if (c >= 3) error = btNormalizeAngle(error);
		locked.target[c] = info.fps * a.stopErp * error;
		if (a.hasStopCfm && a.stopCfm != btScalar(0))
		{
			locked.softLocked[c] = true;
			continue;
		}
		btVector3(&jacobian)[4] = block.jacobian[block.count];
		sixDofCoordinateJacobian(joint, c, jacobian[0], jacobian[1], jacobian[2], jacobian[3]);
		block.target[block.count] = locked.target[c];
		writeJacobian(info, row, blockRow(jacobian));
		info.m_constraintError[row * info.rowskip] = locked.target[c];
		++block.count;
		++row;
	}
	btScalar k[36];
	for (int e = 0; e < block.count; ++e)
	{
		const RowJacobian weighted =
		    applyInverseMass(joint.getRigidBodyA(), joint.getRigidBodyB(), blockRow(block.jacobian[e]));
		for (int f = 0; f < block.count; ++f) k[e * 6 + f] = weighted.dot(blockRow(block.jacobian[f]));
	}
	// A singular block (both bodies immovable, or a degenerate frame) leaves the other rows unprojected.
	if (!invertSmall(k, block.count, block.inverse)) block.count = 0;
	return row;
}

// The rate a limit row asks of a limited coordinate, against the nearer limit (lowerSide tells which).
// Away from it the row lets the coordinate approach by at most the remaining gap this step (so it never
// passes the limit); past it, the row pushes back with the error reduction; a bouncing limit about to be
// reached reverses the approach speed times the bounce.
btScalar limitRowTarget(const AxisSettings& a, btScalar position, btScalar velocity, btScalar fps, btScalar h,
                        bool& lowerSide)
{
	lowerSide = position - a.lower <= a.upper - position;
	if (lowerSide)
	{
		const btScalar gap = position - a.lower;
		btScalar target = -gap * fps * (gap >= btScalar(0) ? btScalar(1) : a.stopErp);
		if (a.bounce > btScalar(0) && velocity < btScalar(0) && gap + velocity * h <= btScalar(0))
			target = btMax(target, -a.bounce * velocity);
		return target;
	}
	const btScalar gap = a.upper - position;
	btScalar target = gap * fps * (gap >= btScalar(0) ? btScalar(1) : a.stopErp);
	if (a.bounce > btScalar(0) && velocity > btScalar(0) && gap - velocity * h <= btScalar(0))
		target = btMin(target, -a.bounce * velocity);
	return target;
}
}  // namespace

int writeSixDofLimitMotorRows(btGeneric6DofConstraint& joint, btTypedConstraint::btConstraintInfo2* info,
                              const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
                              const btVector3& angVelB)
{
	const btScalar fps = info->fps;
	const btScalar h = btScalar(1) / fps;
	AxisSettings axes[6];
	readAxisSettings(joint, *info, axes);

	// Locked coordinates first: the hard block, then the soft ones projected against it.
	LockedCoordinates locked;
	int row = writeHardLockedRows(joint, *info, axes, locked);
	for (int c = 0; c < 6; ++c)
	{
		if (!locked.softLocked[c]) continue;
		writeSixDofCoordinateRow(joint, info, row, c, locked.target[c]);
		info->cfm[row * info->rowskip] = axes[c].stopCfm;
		++row;
	}

	// Limits: one one-sided row per limited coordinate.
	for (int c = 0; c < 6; ++c)
	{
		if (!sixDofIsLimited(joint, c)) continue;
		const AxisSettings& a = axes[c];
		btScalar position = sixDofCoordinate(joint, c);
		if (c >= 3) position = btAdjustAngleToLimits(position, a.lower, a.upper);
		const btScalar velocity = sixDofCoordinateVelocity(joint, c, linVelA, linVelB, angVelA, angVelB);
		bool lowerSide;
		const btScalar target = limitRowTarget(a, position, velocity, fps, h, lowerSide);
		writeSixDofCoordinateRow(joint, info, row, c, target);
		caliber::JointRow jointRow(*info, row);
		if (lowerSide)
			jointRow.lower() = btScalar(0);
		else
			jointRow.upper() = btScalar(0);
		if (a.hasStopCfm) jointRow.cfm() = a.stopCfm;
		++row;
	}

	// Motors: drive the coordinate's rate to the target with at most the motor's force, slowing down as
	// a limit comes within one step.
	for (int c = 0; c < 6; ++c)
	{
		if (!sixDofHasMotorRow(joint, c)) continue;
		const AxisSettings& a = axes[c];
		btScalar position = sixDofCoordinate(joint, c);
		if (c >= 3 && a.lower < a.upper) position = btAdjustAngleToLimits(position, a.lower, a.upper);
		writeSixDofCoordinateRow(joint, info, row, c,
		                         a.targetVelocity * (joint.*memberOf(JointMotorFactor{}))(position, a.lower, a.upper,
		                                                                                  a.targetVelocity, fps));
		caliber::JointRow jointRow(*info, row);
		const btScalar maxImpulse = btFabs(a.maxMotorForce) * h;
		jointRow.lower() = -maxImpulse;
		jointRow.upper() = maxImpulse;
		if (a.hasNormalCfm) jointRow.cfm() = a.normalCfm;
		++row;
	}
	return row;
}

}  // namespace caliber
