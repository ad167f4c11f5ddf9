// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btConeTwistConstraint.h"

#include "BulletDynamics/ConstraintSolver/btJointLimitRow.h"
#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// A frame with a NaN or infinite number (origin or basis) would give the solver NaN rows: the joint is
// disabled instead, with one warning.
void disableIfFramesNotFinite(btConeTwistConstraint& joint)
{
	if (caliber::isFinite(joint.getAFrame()) && caliber::isFinite(joint.getBFrame())) return;
	btAssert(!"btConeTwistConstraint: non-finite frame");
	btReportWarning("Caliber: btConeTwistConstraint: non-finite frame; the joint is disabled\n", 0);
	joint.setEnabled(false);
}

const btScalar kDefaultFixThreshold = btScalar(0.05);
// A bound no real impulse reaches, yet below the solver's threshold for equality rows.
const btScalar kUnlimitedRowImpulse = btScalar(1e20);

// Splits rel (frame B seen in frame A, w >= 0) into a twist about X and a swing about an axis in the
// YZ plane, rel = swing * twist. Returns the twist angle in (-pi, pi]; swingAxis is the swing's unit
// axis in A's frame (Y when there is no swing), swingAngle in [0, pi].
btScalar decomposeSwingTwist(const btQuaternion& rel, btVector3& swingAxis, btScalar& swingAngle)
{
	btQuaternion q = rel;
	if (q.w() < 0) q = btQuaternion(-q.x(), -q.y(), -q.z(), -q.w());
	const btScalar twistNorm = btSqrt(q.x() * q.x() + q.w() * q.w());
	btQuaternion twist(0, 0, 0, 1);
	btScalar twistAngle = 0;
	if (twistNorm > SIMD_EPSILON)
	{
		twist = btQuaternion(q.x() / twistNorm, 0, 0, q.w() / twistNorm);
		twistAngle = btScalar(2) * btAtan2(twist.x(), twist.w());
	}
	const btQuaternion swing = q * twist.inverse();
	const btVector3 axis(0, swing.y(), swing.z());
	const btScalar sinHalf = axis.length();
	swingAngle = btScalar(2) * btAtan2(sinHalf, btFabs(swing.w()));
	if (sinHalf > SIMD_EPSILON)
		swingAxis = (swing.w() < 0 ? -axis : axis) / sinHalf;
	else
		swingAxis.setValue(0, 1, 0);
	return btNormalizeAngle(twistAngle);
}

// The cone's half-angle in the direction of a swing about unitAxis (in the YZ plane): swingSpan2
// bounds swings about Y, swingSpan1 swings about Z, and the rim in between is an ellipse.
btScalar coneLimitFor(const btVector3& unitAxis, btScalar swingSpan1, btScalar swingSpan2)
{
	const btScalar y = unitAxis.y() / swingSpan2;
	const btScalar z = unitAxis.z() / swingSpan1;
	const btScalar inverse = btSqrt(y * y + z * z);
	return inverse > SIMD_EPSILON ? btScalar(1) / inverse : btMax(swingSpan1, swingSpan2);
}
}  // namespace

btConeTwistConstraint::btConeTwistConstraint(btRigidBody& rbA, btRigidBody& rbB, const btTransform& rbAFrame,
                                             const btTransform& rbBFrame)
    : btTypedConstraint(CONETWIST_CONSTRAINT_TYPE, rbA, rbB), m_rbAFrame(rbAFrame), m_rbBFrame(rbBFrame)
{
	init();
}

btConeTwistConstraint::btConeTwistConstraint(btRigidBody& rbA, const btTransform& rbAFrame)
    : btTypedConstraint(CONETWIST_CONSTRAINT_TYPE, rbA),
      m_rbAFrame(rbAFrame),
      m_rbBFrame(rbA.getCenterOfMassTransform() * rbAFrame)
{
	init();
}

void btConeTwistConstraint::init()
{
	m_angularOnly = false;
	m_bMotorEnabled = false;
	m_bNormalizedMotorStrength = false;
	m_maxMotorImpulse = btScalar(-1);
	m_qTarget = btQuaternion::getIdentity();
	m_damping = btScalar(0.01);
	m_dampingSet = false;
	m_fixThresh = kDefaultFixThreshold;
	m_flags = 0;
	m_swingRowNeeded = m_twistRowNeeded = false;
	m_lastTimeStep = btScalar(1) / btScalar(60);
	m_linCFM = 0;
	m_linERP = btScalar(0.7);
	m_angCFM = 0;
	m_swingAngle = m_twistAngle = m_swingLimit = 0;
	m_swingAxis.setValue(0, 1, 0);
	m_twistAxis.setValue(1, 0, 0);
	m_solveTwistLimit = m_solveSwingLimit = false;
	m_twistLimitSign = 0;
	setLimit(btScalar(BT_LARGE_FLOAT), btScalar(BT_LARGE_FLOAT), btScalar(BT_LARGE_FLOAT));
	disableIfFramesNotFinite(*this);
}

void btConeTwistConstraint::setLimit(btScalar _swingSpan1, btScalar _swingSpan2, btScalar _twistSpan,
                                     btScalar _softness, btScalar _biasFactor, btScalar _relaxationFactor)
{
	m_swingSpan1 = _swingSpan1;
	m_swingSpan2 = _swingSpan2;
	m_twistSpan = _twistSpan;
	m_limitSoftness = _softness;
	m_biasFactor = _biasFactor;
	m_relaxationFactor = _relaxationFactor;
}

void btConeTwistConstraint::setLimit(int limitIndex, btScalar limitValue)
{
	switch (limitIndex)
	{
		case 3:
			m_twistSpan = limitValue;
			break;
		case 4:
			m_swingSpan2 = limitValue;
			break;
		case 5:
			m_swingSpan1 = limitValue;
			break;
		default:
			btAssert(!"btConeTwistConstraint::setLimit: index must be 3, 4 or 5");
	}
}

btScalar btConeTwistConstraint::getLimit(int limitIndex) const
{
	switch (limitIndex)
	{
		case 3:
			return m_twistSpan;
		case 4:
			return m_swingSpan2;
		case 5:
			return m_swingSpan1;
		default:
			btAssert(!"btConeTwistConstraint::getLimit: index must be 3, 4 or 5");
			return 0;
	}
}

void btConeTwistConstraint::setFrames(const btTransform& frameA, const btTransform& frameB)
{
	m_rbAFrame = frameA;
	m_rbBFrame = frameB;
	disableIfFramesNotFinite(*this);
}

void btConeTwistConstraint::calcAngleInfo()
{
	calcAngleInfo2(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(), m_rbA.getInvInertiaTensorWorld(),
	               m_rbB.getInvInertiaTensorWorld());
}

void btConeTwistConstraint::calcAngleInfo2(const btTransform& transA, const btTransform& transB,
                                           const btMatrix3x3& invInertiaWorldA, const btMatrix3x3& invInertiaWorldB)
{
	(void)invInertiaWorldA;
	(void)invInertiaWorldB;
	const btMatrix3x3 frameA = transA.getBasis() * m_rbAFrame.getBasis();
	const btMatrix3x3 frameB = transB.getBasis() * m_rbBFrame.getBasis();
	btQuaternion qA, qB;
	frameA.getRotation(qA);
	frameB.getRotation(qB);
	btVector3 swingAxisInA;
	m_twistAngle = decomposeSwingTwist(qA.inverse() * qB, swingAxisInA, m_swingAngle);
	m_swingAxis = frameA * swingAxisInA;
	m_twistAxis = frameB.getColumn(0);

	const bool swingLocked = m_swingSpan1 < m_fixThresh && m_swingSpan2 < m_fixThresh;
	m_swingLimit = coneLimitFor(swingAxisInA, btMax(m_swingSpan1, SIMD_EPSILON), btMax(m_swingSpan2, SIMD_EPSILON));
	m_solveSwingLimit = !swingLocked && m_swingAngle > m_swingLimit;

	const bool twistLocked = m_twistSpan < m_fixThresh;
	m_twistLimitSign = 0;
	if (!twistLocked && m_twistAngle > m_twistSpan)
		m_twistLimitSign = btScalar(-1);  // must turn back down
	else if (!twistLocked && m_twistAngle < -m_twistSpan)
		m_twistLimitSign = btScalar(1);
	m_solveTwistLimit = m_twistLimitSign != btScalar(0);
}

bool btConeTwistConstraint::swingLimited() const
{
	const bool swingLocked = m_swingSpan1 < m_fixThresh && m_swingSpan2 < m_fixThresh;
	// A swing can be at most half a turn: wider spans limit nothing.
	return !swingLocked && btMin(m_swingSpan1, m_swingSpan2) < SIMD_PI;
}

bool btConeTwistConstraint::twistLimited() const { return m_twistSpan >= m_fixThresh && m_twistSpan < SIMD_PI; }

int btConeTwistConstraint::rowCount() const
{
	int rows = m_angularOnly ? 0 : 3;
	if (m_swingSpan1 < m_fixThresh && m_swingSpan2 < m_fixThresh) rows += 2;
	if (m_twistSpan < m_fixThresh) rows += 1;
	if (m_swingRowNeeded) rows += 1;
	if (m_twistRowNeeded) rows += 1;
	if (m_bMotorEnabled)
		rows += 3;
	else if (m_dampingSet && m_damping > btScalar(0))
		rows += 1;
	return rows;
}

void btConeTwistConstraint::getInfo1(btConstraintInfo1* info) { getInfo1NonVirtual(info); }

void btConeTwistConstraint::getInfo1NonVirtual(btConstraintInfo1* info)
{
	calcAngleInfo();
	// Limit rows only past a limit or within two steps' travel of it (plus a milliradian): far from its
	// limits the joint needs none, and rows cost solver time.
	const btVector3 relative = m_rbA.getAngularVelocity() - m_rbB.getAngularVelocity();
	const btScalar reach = 2 * m_lastTimeStep;
	const btScalar margin = btScalar(1e-3);
	m_swingRowNeeded = swingLimited() && (m_solveSwingLimit || m_swingLimit - m_swingAngle <=
	                                                               btFabs(relative.dot(m_swingAxis)) * reach + margin);
	m_twistRowNeeded = twistLimited() && (m_solveTwistLimit || m_twistSpan - btFabs(m_twistAngle) <=
	                                                               btFabs(relative.dot(m_twistAxis)) * reach + margin);
	info->m_numConstraintRows = rowCount();
	info->nub = m_angularOnly ? 0 : 3;
}

void btConeTwistConstraint::getInfo2(btConstraintInfo2* info)
{
	getInfo2NonVirtual(info, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(),
	                   m_rbA.getInvInertiaTensorWorld(), m_rbB.getInvInertiaTensorWorld());
}

namespace
{
// The three point rows (rows 0..2): B's frame origin held on A's, along the world axes; linearCfm, when
// given, replaces the rows' starting CFM. Returns the next row.
int writePointRows(btTypedConstraint::btConstraintInfo2& info, const btTransform& transA, const btTransform& transB,
                   const btTransform& frameA, const btTransform& frameB, const btVector3& angularVelocityA,
                   const btVector3& angularVelocityB, btScalar linearErp, const btScalar* linearCfm)
{
	const btVector3 armA = frameA.getOrigin() - transA.getOrigin();
	const btVector3 armB = frameB.getOrigin() - transB.getOrigin();
	const btVector3 gap = frameB.getOrigin() - frameA.getOrigin();
	const btVector3 targets =
	    caliber::linearRowTargets(info, linearErp, gap, armA, angularVelocityA, armB, angularVelocityB);
	for (int axis = 0; axis < 3; ++axis)
	{
		btVector3 direction(0, 0, 0);
		direction[axis] = btScalar(1);
		caliber::JointRow r(info, axis);
		r.setLinear(direction, armA, armB);
		r.error() = targets[axis];
		if (linearCfm) r.cfm() = *linearCfm;
	}
	return 3;
}

// The twist's state as getInfo1 left it.
struct TwistLimit
{
	btVector3 axis;
	btScalar angle, span, limitSign;
	bool past;  // beyond a limit (limitSign says which)
};

// The twist limit row, oriented so that J v is the rate back into the range: -twist rate at the + end,
// +twist rate at the - end. Inside, the end guarded is the one the twist heads for (the nearer in the
// position pass); the row is speculative there (see getInfo2NonVirtual).
void writeTwistLimitRow(caliber::JointRow& r, const TwistLimit& twist, const btVector3& relativeAngularVelocity,
                        btScalar limitRate, btScalar fps, btScalar relaxation)
{
	btScalar sign = twist.limitSign;
	if (!twist.past)
	{
		const btScalar twistRate = -relativeAngularVelocity.dot(twist.axis);
		const bool towardsPlus = caliber::inJointPositionPass() ? twist.angle >= 0 : twistRate >= 0;
		sign = towardsPlus ? btScalar(-1) : btScalar(1);
	}
	const btVector3 axis = twist.axis * -sign;
	r.setAngular(axis);
	const btScalar overshoot = btFabs(twist.angle) - twist.span;
	if (twist.past)
	{
		caliber::setLimitRow(r, limitRate * overshoot, relativeAngularVelocity.dot(axis), relaxation);
	}
	else
	{
		const btScalar room = twist.span - (sign < 0 ? twist.angle : -twist.angle);
		r.error() = -btMax(btScalar(0), room) * fps;
		r.lower() = 0;
		r.upper() = SIMD_INFINITY;
	}
}

// The motor's settings.
struct MotorDrive
{
	btQuaternion target;  // frame A seen in frame B
	btScalar maxImpulse;  // negative: unbounded
	bool normalized;      // maxImpulse is an angular velocity change
};

// The motor's three rows from row `row` on: B's turn rate relative to A that reaches the target in one
// step, per world axis. Returns the next row.
int writeMotorRows(btTypedConstraint::btConstraintInfo2& info, int row, const btTransform& frameA,
                   const btTransform& frameB, const MotorDrive& drive, const btMatrix3x3& invInertiaWorldA,
                   const btMatrix3x3& invInertiaWorldB)
{
	btVector3 desiredRateOfB(0, 0, 0);
	btQuaternion qA, qB;
	frameA.getBasis().getRotation(qA);
	frameB.getBasis().getRotation(qB);
	const btQuaternion current = qA.inverse() * qB;
	const btQuaternion desired = drive.target.inverse();
	btQuaternion error = desired * current.inverse();
	if (error.w() < 0) error = btQuaternion(-error.x(), -error.y(), -error.z(), -error.w());
	const btVector3 vector(error.x(), error.y(), error.z());
	const btScalar sinHalf = vector.length();
	if (sinHalf > SIMD_EPSILON)
	{
		const btScalar angle = btScalar(2) * btAtan2(sinHalf, error.w());
		desiredRateOfB = frameA.getBasis() * (vector / sinHalf) * (angle * info.fps);
	}
	for (int k = 0; k < 3; ++k)
	{
		btVector3 axis(0, 0, 0);
		axis[k] = btScalar(-1);  // J v = (wB - wA)_k
		caliber::JointRow r(info, row++);
		r.setAngular(axis);
		r.error() = desiredRateOfB[k];
		// Motor rows are velocity goals, never equality rows: an impulse bound always (a very large one
		// when none is set), so the solver keeps them out of the joint's exact block and the position
		// correction leaves them alone.
		r.lower() = -kUnlimitedRowImpulse;
		r.upper() = kUnlimitedRowImpulse;
		if (drive.maxImpulse >= btScalar(0))
		{
			btScalar bound = drive.maxImpulse;
			if (drive.normalized)
			{
				// Normalised: an angular velocity change; times the pair's rotational inertia about the axis.
				const btScalar inverseInertia = axis.dot(invInertiaWorldA * axis) + axis.dot(invInertiaWorldB * axis);
				bound = inverseInertia > SIMD_EPSILON ? drive.maxImpulse / inverseInertia : btScalar(0);
			}
			r.lower() = -bound;
			r.upper() = bound;
		}
	}
	return row;
}
}  // namespace

void btConeTwistConstraint::getInfo2NonVirtual(btConstraintInfo2* info, const btTransform& transA,
                                               const btTransform& transB, const btMatrix3x3& invInertiaWorldA,
                                               const btMatrix3x3& invInertiaWorldB)
{
	calcAngleInfo2(transA, transB, invInertiaWorldA, invInertiaWorldB);
	const btTransform frameA = transA * m_rbAFrame;
	const btTransform frameB = transB * m_rbBFrame;
	const btScalar angularRate = info->fps * info->erp;
	const bool angularCfm = (m_flags & BT_CONETWIST_FLAGS_ANG_CFM) != 0;
	int row = 0;

	if (!m_angularOnly)
	{
		const btScalar linearErp = (m_flags & BT_CONETWIST_FLAGS_LIN_ERP) ? m_linERP : info->erp;
		const btScalar* linearCfm = (m_flags & BT_CONETWIST_FLAGS_LIN_CFM) ? &m_linCFM : 0;
		row = writePointRows(*info, transA, transB, frameA, frameB, m_rbA.getAngularVelocity(),
		                     m_rbB.getAngularVelocity(), linearErp, linearCfm);
	}

	// Locked rotations are equality rows, so they join the linear rows in the solver's block.
	if (m_swingSpan1 < m_fixThresh && m_swingSpan2 < m_fixThresh)
	{
		// Turning A about (xA x xB) brings its twist axis onto B's.
		const btVector3 misalignment = frameA.getBasis().getColumn(0).cross(frameB.getBasis().getColumn(0));
		for (int k = 1; k <= 2; ++k, ++row)
		{
			const btVector3 perpendicular = frameA.getBasis().getColumn(k);
			caliber::JointRow r(*info, row);
			r.setAngular(perpendicular);
			r.error() = angularRate * misalignment.dot(perpendicular);
			if (angularCfm) r.cfm() = m_angCFM;
		}
	}
	// The position pass asks for position errors only: no velocity terms there.
	const btVector3 relativeAngularVelocity =
	    caliber::inJointPositionPass() ? btVector3(0, 0, 0) : m_rbA.getAngularVelocity() - m_rbB.getAngularVelocity();
	if (m_twistSpan < m_fixThresh)
	{
		// The twist grows when B turns about the axis relative to A, so (wA - wB) . x = rate * twist undoes it.
		caliber::JointRow r(*info, row++);
		r.setAngular(m_twistAxis);
		r.error() = angularRate * m_twistAngle;
		if (angularCfm) r.cfm() = m_angCFM;
	}
	const btScalar limitRate = info->fps * m_biasFactor;
	// Limit rows are there past a limit or near one (getInfo1). Past the limit they push back (bias) and stop the
	// velocity into it (relaxation); inside, they are speculative: they allow at most the approach speed
	// that reaches the limit at the end of the step, so a fast swing stops at the cone instead of
	// overshooting it by one step's travel.
	if (!caliber::inJointPositionPass() && info->fps > btScalar(0)) m_lastTimeStep = btScalar(1) / info->fps;
	if (m_swingRowNeeded)
	{
		// (wA - wB) . s is the rate at which the swing shrinks.
		caliber::JointRow r(*info, row++);
		r.setAngular(m_swingAxis);
		if (m_solveSwingLimit)
		{
			caliber::setLimitRow(r, limitRate * (m_swingAngle - m_swingLimit), relativeAngularVelocity.dot(m_swingAxis),
			                     m_relaxationFactor);
		}
		else
		{
			r.error() = -(m_swingLimit - m_swingAngle) * info->fps;
			r.lower() = 0;
			r.upper() = SIMD_INFINITY;
		}
		if (angularCfm) r.cfm() = m_angCFM;
	}
	if (m_twistRowNeeded)
	{
		TwistLimit twist = {m_twistAxis, m_twistAngle, m_twistSpan, m_twistLimitSign, m_solveTwistLimit};
		caliber::JointRow r(*info, row++);
		writeTwistLimitRow(r, twist, relativeAngularVelocity, limitRate, info->fps, m_relaxationFactor);
		if (angularCfm) r.cfm() = m_angCFM;
	}
	if (m_bMotorEnabled)
	{
		const MotorDrive drive = {m_qTarget, m_maxMotorImpulse, m_bNormalizedMotorStrength};
		row = writeMotorRows(*info, row, frameA, frameB, drive, invInertiaWorldA, invInertiaWorldB);
	}
	else if (m_dampingSet && m_damping > btScalar(0))
	{
		// Damping: one row along the present relative turn, keeping the share 1 - d of its rate (a single
		// row, so it can never disagree with itself, or with locked rotations, which the solver projects
		// out of it). Bounded like a motor row, so that it is never taken for an equality row.
		const btScalar rate = relativeAngularVelocity.length();
		const btVector3 direction = rate > SIMD_EPSILON ? relativeAngularVelocity / rate : btVector3(1, 0, 0);
		caliber::JointRow r(*info, row++);
		r.setAngular(direction);  // J v = (wA - wB) . direction
		r.error() = (btScalar(1) - btMin(btScalar(1), m_damping)) * rate;
		r.lower() = -kUnlimitedRowImpulse;
		r.upper() = kUnlimitedRowImpulse;
	}
}

void btConeTwistConstraint::setMotorTarget(const btQuaternion& q)
{
	// q is body A seen in body B; frame A seen in frame B follows from the two joint frames.
	const btQuaternion frameAinFrameB = m_rbBFrame.getRotation().inverse() * q * m_rbAFrame.getRotation();
	setMotorTargetInConstraintSpace(frameAinFrameB);
}

void btConeTwistConstraint::setMotorTargetInConstraintSpace(const btQuaternion& q)
{
	m_qTarget = q;
	// Keep the target reachable: frame B in frame A is q^-1; clamp its swing into the cone and its twist
	// into the range.
	btVector3 swingAxis;
	btScalar swingAngle;
	btScalar twist = decomposeSwingTwist(q.inverse(), swingAxis, swingAngle);
	bool clamped = false;
	if (m_swingSpan1 >= m_fixThresh && m_swingSpan2 >= m_fixThresh)
	{
		const btScalar limit = coneLimitFor(swingAxis, m_swingSpan1, m_swingSpan2);
		if (swingAngle > limit)
		{
			swingAngle = limit;
			clamped = true;
		}
	}
	if (m_twistSpan >= m_fixThresh && btFabs(twist) > m_twistSpan)
	{
		twist = twist > 0 ? m_twistSpan : -m_twistSpan;
		clamped = true;
	}
	if (clamped)
	{
		const btQuaternion bInA = btQuaternion(swingAxis, swingAngle) * btQuaternion(btVector3(1, 0, 0), twist);
		m_qTarget = bInA.inverse();
	}
}

btVector3 btConeTwistConstraint::GetPointForAngle(btScalar fAngleInRadians, btScalar len) const
{
	const btVector3 axis(0, btCos(fAngleInRadians), btSin(fAngleInRadians));
	const btScalar limit = coneLimitFor(axis, m_swingSpan1, m_swingSpan2);
	return quatRotate(btQuaternion(axis, limit), btVector3(len, 0, 0));
}

void btConeTwistConstraint::setParam(int num, btScalar value, int axis)
{
	btAssertConstrParams(axis >= -1 && axis <= 5);
	switch (num)
	{
		case BT_CONSTRAINT_ERP:
		case BT_CONSTRAINT_STOP_ERP:
			if (axis >= 0 && axis < 3)
			{
				m_linERP = value;
				m_flags |= BT_CONETWIST_FLAGS_LIN_ERP;
			}
			else
			{
				m_biasFactor = value;
			}
			break;
		case BT_CONSTRAINT_CFM:
		case BT_CONSTRAINT_STOP_CFM:
			if (axis >= 0 && axis < 3)
			{
				m_linCFM = value;
				m_flags |= BT_CONETWIST_FLAGS_LIN_CFM;
			}
			else
			{
				m_angCFM = value;
				m_flags |= BT_CONETWIST_FLAGS_ANG_CFM;
			}
			break;
		default:
			btAssertConstrParams(0);
	}
}

btScalar btConeTwistConstraint::getParam(int num, int axis) const
{
	btAssertConstrParams(axis >= -1 && axis <= 5);
	switch (num)
	{
		case BT_CONSTRAINT_ERP:
		case BT_CONSTRAINT_STOP_ERP:
			return (axis >= 0 && axis < 3) ? m_linERP : m_biasFactor;
		case BT_CONSTRAINT_CFM:
		case BT_CONSTRAINT_STOP_CFM:
			return (axis >= 0 && axis < 3) ? m_linCFM : m_angCFM;
		default:
			btAssertConstrParams(0);
			return SIMD_INFINITY;
	}
}
