// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"

#include <cstdio>

#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// Below this cosine of the middle Euler angle the first and last rotation axes are parallel (gimbal
// lock): only their sum is defined, and the last angle is taken as 0.
const btScalar kGimbalCosine = btScalar(10) * SIMD_EPSILON;
// The first and last angles' rates are measured along u_j x u_k / cos(middle angle) and
// u_i x u_j / cos(middle angle); near gimbal lock the division is capped so the rows stay finite.
const btScalar kSmallestMiddleCosine = btScalar(1e-3);
// Springs are solved as a soft row while the solver's iteration for it contracts by at least this
// factor per sweep (see writeSpringRow); softer springs get their implicit impulse directly.
const btScalar kLargestSoftRowCfm = btScalar(0.5);

// One rotation order as axis indices: Q = B^T A = R_first(angle) R_middle(angle) R_last(angle), with
// parity +1 when (first, middle, last) is a cyclic permutation of (x, y, z).
struct EulerOrder
{
	int first, middle, last;
	btScalar parity;
};

EulerOrder eulerOrder(RotateOrder order)
{
	switch (order)
	{
		case RO_XZY:
			return {0, 2, 1, btScalar(-1)};
		case RO_YXZ:
			return {1, 0, 2, btScalar(-1)};
		case RO_YZX:
			return {1, 2, 0, btScalar(1)};
		case RO_ZXY:
			return {2, 0, 1, btScalar(1)};
		case RO_ZYX:
			return {2, 1, 0, btScalar(-1)};
		case RO_XYZ:
		default:
			return {0, 1, 2, btScalar(1)};
	}
}

// Writes the angles of q = R_i(a) R_j(b) R_k(c) into angles[i], angles[j], angles[k]. Multiplying out,
// with p the parity: q[i][k] = p sin b, q[j][k] = -p sin a cos b, q[k][k] = cos a cos b,
// q[i][j] = -p cos b sin c, q[i][i] = cos b cos c. At gimbal lock (cos b = 0) c is taken as 0, and
// then column j of q is R_i(a) e_j: q[j][j] = cos a, q[k][j] = p sin a. False at gimbal lock.
bool decomposeEuler(const btMatrix3x3& q, const EulerOrder& o, btVector3& angles)
{
	const int i = o.first, j = o.middle, k = o.last;
	const btScalar p = o.parity;
	const btScalar cosMiddle = btSqrt(q[i][i] * q[i][i] + q[i][j] * q[i][j]);
	angles[j] = btAtan2(p * q[i][k], cosMiddle);
	if (cosMiddle > kGimbalCosine)
	{
		angles[i] = btAtan2(-p * q[j][k], q[k][k]);
		angles[k] = btAtan2(-p * q[i][j], q[i][i]);
		return true;
	}
	angles[i] = btAtan2(p * q[k][j], q[j][j]);
	angles[k] = btScalar(0);
	return false;
}

void warn(const char* function, const char* what)
{
	char message[200];
	std::snprintf(message, sizeof(message), "Caliber: btGeneric6DofSpring2Constraint::%s: %s\n", function, what);
	btReportWarning(message, 0);
}

// The Jacobian of one coordinate's rate: rate = linA . vA + angA . wA + linB . vB + angB . wB.
struct CoordinateRow
{
	bool angular;
	btVector3 direction, armA, armB;  // linear: JointRow::setLinear(direction, armA, armB)
	btVector3 linA, angA, linB, angB;

	static CoordinateRow linear(const btVector3& direction, const btVector3& armA, const btVector3& armB)
	{
		CoordinateRow r;
		r.angular = false;
		r.direction = direction;
		r.armA = armA;
		r.armB = armB;
		r.linA = direction;
		r.angA = armA.cross(direction);
		r.linB = -direction;
		r.angB = -armB.cross(direction);
		return r;
	}
	static CoordinateRow rotation(const btVector3& axis)
	{
		CoordinateRow r;
		r.angular = true;
		r.direction = axis;
		r.armA = r.armB = btVector3(0, 0, 0);
		r.linA = r.linB = btVector3(0, 0, 0);
		r.angA = axis;
		r.angB = -axis;
		return r;
	}

	void write(caliber::JointRow& row) const
	{
		if (angular)
			row.setAngular(direction);
		else
			row.setLinear(direction, armA, armB);
	}

	btScalar rate(const btVector3& linVelA, const btVector3& angVelA, const btVector3& linVelB,
	              const btVector3& angVelB) const
	{
		return linA.dot(linVelA) + angA.dot(angVelA) + linB.dot(linVelB) + angB.dot(angVelB);
	}

	// J M^-1 J^T: the inverse of the mass the row moves, computed exactly as the solver computes it (so
	// that a soft row's CFM means what it was derived to mean).
	btScalar inverseMass(const btRigidBody& a, const btRigidBody& b) const
	{
		return bodyTerm(a, linA, angA) + bodyTerm(b, linB, angB);
	}

private:
	static btScalar bodyTerm(const btRigidBody& body, const btVector3& lin, const btVector3& ang)
	{
		btScalar k = lin.dot(lin * (body.getInvMass() * body.getLinearFactor()));
		if (!body.isStaticOrKinematicObject())
		{
			const btVector3 turned = ang * body.getAngularFactor();
			k += turned.dot(body.getInvInertiaTensorWorld() * turned);
		}
		return k;
	}
};

// The settings of one of the six coordinates, gathered from the linear or the angular motor.
struct CoordinateSettings
{
	btScalar lo, hi, position, bounce;
	bool motor, servo, spring;
	btScalar targetVelocity, maxMotorForce, servoTarget;
	btScalar stiffness, damping, equilibrium;
	int state;  // 0 free, 3 locked, 4 limited
	// The ERPs of the stop and motor rows (the world's unless set through setParam), and the CFMs set
	// through setParam (rows otherwise keep the world's CFM they start with).
	btScalar stopERP, motorERP;
	bool hasStopCFM, hasMotorCFM;
	btScalar stopCFM, motorCFM;
	// A plain (not servo) motor's velocity along the coordinate and getMotorFactor's slow-down near the
	// limits for it.
	btScalar motorVelocity, motorFactor;
};

// True for 0..5; anything else asserts, and in release builds is reported and ignored.
bool checkIndex(int index, const char* function)
{
	const bool valid = index >= 0 && index < 6;
	if (!valid) warn(function, "coordinate index outside 0..5; call ignored");
	btAssert(valid && "btGeneric6DofSpring2Constraint: coordinate index must be 0..5");
	return valid;
}

// The per-angle accessors take 0..2; a user's index outside is reported, never read.
bool angleIndexInRange(int index, const char* function)
{
	const bool valid = index >= 0 && index < 3;
	if (!valid) warn(function, "index outside 0..2");
	btAssert(valid && "btGeneric6DofSpring2Constraint: axis index must be 0..2");
	return valid;
}
}  // namespace

// ---- limit motors -------------------------------------------------------------------------------

void btRotationalLimitMotor2::testLimitValue(btScalar test_value)
{
	if (m_loLimit > m_hiLimit)
	{
		m_currentLimit = 0;
		m_currentLimitError = btScalar(0);
	}
	else if (m_loLimit == m_hiLimit)
	{
		m_currentLimit = 3;
		m_currentLimitError = test_value - m_loLimit;
	}
	else
	{
		m_currentLimit = 4;
		m_currentLimitError = test_value - m_loLimit;
		m_currentLimitErrorHi = test_value - m_hiLimit;
	}
}

void btTranslationalLimitMotor2::testLimitValue(int limitIndex, btScalar test_value)
{
	const btScalar lo = m_lowerLimit[limitIndex], hi = m_upperLimit[limitIndex];
	if (lo > hi)
	{
		m_currentLimit[limitIndex] = 0;
		m_currentLimitError[limitIndex] = btScalar(0);
	}
	else if (lo == hi)
	{
		m_currentLimit[limitIndex] = 3;
		m_currentLimitError[limitIndex] = test_value - lo;
	}
	else
	{
		m_currentLimit[limitIndex] = 4;
		m_currentLimitError[limitIndex] = test_value - lo;
		m_currentLimitErrorHi[limitIndex] = test_value - hi;
	}
}

// ---- construction and measurement ---------------------------------------------------------------

btGeneric6DofSpring2Constraint::btGeneric6DofSpring2Constraint(btRigidBody& rbA, btRigidBody& rbB,
                                                               const btTransform& frameInA, const btTransform& frameInB,
                                                               RotateOrder rotOrder)
    : btTypedConstraint(D6_SPRING_2_CONSTRAINT_TYPE, rbA, rbB),
      m_frameInA(frameInA),
      m_frameInB(frameInB),
      m_rotateOrder(rotOrder),
      m_factA(btScalar(0.5)),
      m_factB(btScalar(0.5)),
      m_hasStaticBody(false),
      m_flags(0)
{
	if (!caliber::isFinite(frameInA) || !caliber::isFinite(frameInB))
	{
		// An inert joint with harmless frames rather than one that spreads NaN.
		warn("constructor", "non-finite joint frame; the joint is disabled");
		m_frameInA.setIdentity();
		m_frameInB.setIdentity();
		setEnabled(false);
	}
	calculateTransforms();
}

btGeneric6DofSpring2Constraint::btGeneric6DofSpring2Constraint(btRigidBody& rbB, const btTransform& frameInB,
                                                               RotateOrder rotOrder)
    : btTypedConstraint(D6_SPRING_2_CONSTRAINT_TYPE, getFixedBody(), rbB),
      m_frameInB(frameInB),
      m_rotateOrder(rotOrder),
      m_factA(btScalar(0.5)),
      m_factB(btScalar(0.5)),
      m_hasStaticBody(false),
      m_flags(0)
{
	if (!caliber::isFinite(frameInB) || !caliber::isFinite(rbB.getCenterOfMassTransform()))
	{
		warn("constructor", "non-finite joint frame; the joint is disabled");
		m_frameInB.setIdentity();
		setEnabled(false);
	}
	// Without a body A the world is A, and its frame is where B's frame is now.
	m_frameInA = rbB.getCenterOfMassTransform() * m_frameInB;
	if (!caliber::isFinite(m_frameInA)) m_frameInA.setIdentity();
	calculateTransforms();
}

void btGeneric6DofSpring2Constraint::calculateTransforms()
{
	calculateTransforms(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
}

void btGeneric6DofSpring2Constraint::calculateTransforms(const btTransform& transA, const btTransform& transB)
{
	m_calculatedTransformA = transA * m_frameInA;
	m_calculatedTransformB = transB * m_frameInB;
	calculateLinearInfo();
	calculateAngleInfo();
	for (int i = 0; i < 3; ++i) testAngularLimitMotor(i);
	const btScalar invMassA = m_rbA.getInvMass(), invMassB = m_rbB.getInvMass();
	m_hasStaticBody = invMassA < SIMD_EPSILON || invMassB < SIMD_EPSILON;
	const btScalar invMassSum = invMassA + invMassB;
	m_factA = invMassSum > btScalar(0) ? invMassB / invMassSum : btScalar(0.5);
	m_factB = btScalar(1) - m_factA;
}

void btGeneric6DofSpring2Constraint::calculateLinearInfo()
{
	// B's frame origin in A's frame.
	const btMatrix3x3& basisA = m_calculatedTransformA.getBasis();
	const btVector3 gap = m_calculatedTransformB.getOrigin() - m_calculatedTransformA.getOrigin();
	for (int i = 0; i < 3; ++i) m_calculatedLinearDiff[i] = basisA.getColumn(i).dot(gap);
	for (int i = 0; i < 3; ++i)
	{
		m_linearLimits.m_currentLinearDiff[i] = m_calculatedLinearDiff[i];
		m_linearLimits.testLimitValue(i, m_calculatedLinearDiff[i]);
	}
}

void btGeneric6DofSpring2Constraint::calculateAngleInfo()
{
	const btMatrix3x3& basisA = m_calculatedTransformA.getBasis();
	const btMatrix3x3& basisB = m_calculatedTransformB.getBasis();
	// Q = B^T A = R_i(a) R_j(b) R_k(c) (rows of Q: B's axes, columns: A's axes).
	const EulerOrder o = eulerOrder(m_rotateOrder);
	decomposeEuler(basisB.transposeTimes(basisA), o, m_calculatedAxisAngleDiff);

	// Differentiating Q with the bodies' angular velocities gives
	//   wA - wB = u_i da/dt + u_j db/dt + u_k dc/dt,
	// with u_i = B's axis i, u_j = B R_i(a) e_j (the intermediate axis, perpendicular to the other two)
	// and u_k = B R_i R_j e_k = A's axis k. Each angle's rate is then d_n . (wA - wB) with d_n the dual
	// basis of (u_i, u_j, u_k): d_j = u_j, d_i = u_j x u_k / T, d_k = u_i x u_j / T, T = det(u) = p cos b.
	const int i = o.first, j = o.middle, k = o.last;
	const btScalar a = m_calculatedAxisAngleDiff[i];
	const btVector3 ui = basisB.getColumn(i);
	const btVector3 uk = basisA.getColumn(k);
	const btVector3 uj = basisB.getColumn(j) * btCos(a) + basisB.getColumn(k) * (o.parity * btSin(a));
	btScalar triple = ui.dot(uj.cross(uk));
	if (!(btFabs(triple) >= kSmallestMiddleCosine)) triple = o.parity * kSmallestMiddleCosine;
	m_angularJacobian[i] = uj.cross(uk) / triple;
	m_angularJacobian[j] = uj;
	m_angularJacobian[k] = ui.cross(uj) / triple;
	for (int n = 0; n < 3; ++n)
	{
		m_calculatedAxis[n] = m_angularJacobian[n];
		m_calculatedAxis[n].safeNormalize();
	}
}

void btGeneric6DofSpring2Constraint::testAngularLimitMotor(int axis_index)
{
	if (!angleIndexInRange(axis_index, "testAngularLimitMotor")) axis_index = btMax(0, btMin(axis_index, 2));
	btRotationalLimitMotor2& limit = m_angularLimits[axis_index];
	// The same angle one turn away may be the one inside (or nearest) the limits.
	limit.m_currentPosition =
	    btAdjustAngleToLimits(m_calculatedAxisAngleDiff[axis_index], limit.m_loLimit, limit.m_hiLimit);
	limit.testLimitValue(limit.m_currentPosition);
}

// ---- rows ---------------------------------------------------------------------------------------

void btGeneric6DofSpring2Constraint::getInfo1(btConstraintInfo1* info)
{
	calculateTransforms();
	int rows = 0, locked = 0;
	for (int axis = 0; axis < 6; ++axis)
	{
		const int state = axis < 3 ? m_linearLimits.m_currentLimit[axis] : m_angularLimits[axis - 3].m_currentLimit;
		const bool motor = axis < 3 ? m_linearLimits.m_enableMotor[axis] : m_angularLimits[axis - 3].m_enableMotor;
		const bool spring = axis < 3 ? m_linearLimits.m_enableSpring[axis] : m_angularLimits[axis - 3].m_enableSpring;
		if (state == 3)
		{
			++rows;
			++locked;
			continue;  // a locked coordinate has nothing to drive
		}
		if (state == 4) rows += 2;
		if (motor) ++rows;
		if (spring) ++rows;
	}
	info->m_numConstraintRows = rows;
	info->nub = locked;
}

namespace
{
// The rows of one getInfo2 call, written in four groups by the steps below; next is the next free row.
struct RowWriter
{
	btTypedConstraint::btConstraintInfo2& info;
	btScalar fps, h;  // steps per second and step length (0 when fps is 0)
	const btRigidBody& bodyA;
	const btRigidBody& bodyB;
	const btVector3& linVelA;
	const btVector3& angVelA;
	const btVector3& linVelB;
	const btVector3& angVelB;
	const CoordinateRow* jacobian;       // [6], J v is each coordinate's rate
	const CoordinateSettings* settings;  // [6]
	int next;

	btScalar rate(int axis) const { return jacobian[axis].rate(linVelA, angVelA, linVelB, angVelB); }

	caliber::JointRow startRow(int axis)
	{
		caliber::JointRow row(info, next++);
		jacobian[axis].write(row);
		return row;
	}
};

// The settings of a coordinate held in a limit motor (an angle's, or a linear coordinate's copied into that
// form), ERPs and CFMs as they are.
void readMotorSettings(const btRotationalLimitMotor2& m, CoordinateSettings& s)
{
	s.lo = m.m_loLimit;
	s.hi = m.m_hiLimit;
	s.position = m.m_currentPosition;
	s.bounce = m.m_bounce;
	s.motor = m.m_enableMotor;
	s.servo = m.m_servoMotor;
	s.spring = m.m_enableSpring;
	s.targetVelocity = m.m_targetVelocity;
	s.maxMotorForce = m.m_maxMotorForce;
	s.servoTarget = m.m_servoTarget;
	s.stiffness = m.m_springStiffness;
	s.damping = m.m_springDamping;
	s.equilibrium = m.m_equilibriumPoint;
	s.state = m.m_currentLimit;
	s.stopERP = m.m_stopERP;
	s.motorERP = m.m_motorERP;
	s.stopCFM = m.m_stopCFM;
	s.motorCFM = m.m_motorCFM;
}

// A difference of two values of a coordinate: angles the short way round.
btScalar coordinateDifference(int axis, btScalar to, btScalar from)
{
	return axis < 3 ? to - from : btNormalizeAngle(to - from);
}

void setStopCFM(caliber::JointRow& row, const CoordinateSettings& s)
{
	if (s.hasStopCFM) row.cfm() = s.stopCFM;
}

// A locked coordinate's equality row.
void writeLockedRow(RowWriter& w, int axis)
{
	const CoordinateSettings& s = w.settings[axis];
	caliber::JointRow row = w.startRow(axis);
	row.error() = w.fps * s.stopERP * coordinateDifference(axis, s.lo, s.position);
	row.lower() = -SIMD_INFINITY;
	row.upper() = SIMD_INFINITY;
	setStopCFM(row, s);
}

// Locked coordinates: equality rows, first, so that the solver solves them as one exact block.
void writeLockedRows(RowWriter& w)
{
	for (int axis = 0; axis < 6; ++axis)
		if (w.settings[axis].state == 3) writeLockedRow(w, axis);
}

// Limits: one one-sided row per end, always present so that the row count (and with it the warm start)
// does not change as a limit comes into play. Each row is speculative: far from its end it allows the
// coordinate to close the whole gap in this step and so stays idle; past its end it pushes back at the
// stop ERP. A coordinate that would reach its end within the step and has a bounce leaves at bounce
// times its approach speed at once (no exact time of impact is solved).
void writeLimitRowPair(RowWriter& w, int axis)
{
	const CoordinateSettings& s = w.settings[axis];
	const btScalar erp = s.stopERP;
	const btScalar rate = w.rate(axis);
	const bool bounces = s.bounce > btScalar(0);

	caliber::JointRow lower = w.startRow(axis);
	const btScalar aboveLower = s.position - s.lo;
	btScalar target = aboveLower >= btScalar(0) ? -aboveLower * w.fps : -aboveLower * w.fps * erp;
	if (bounces && rate < btScalar(0) && aboveLower + rate * w.h < btScalar(0))
		target = btMax(target, -s.bounce * rate);
	lower.error() = target;
	lower.lower() = btScalar(0);
	lower.upper() = SIMD_INFINITY;
	setStopCFM(lower, s);

	caliber::JointRow upper = w.startRow(axis);
	const btScalar belowUpper = s.hi - s.position;
	target = belowUpper >= btScalar(0) ? belowUpper * w.fps : belowUpper * w.fps * erp;
	if (bounces && rate > btScalar(0) && belowUpper - rate * w.h < btScalar(0))
		target = btMin(target, -s.bounce * rate);
	upper.error() = target;
	upper.lower() = -SIMD_INFINITY;
	upper.upper() = btScalar(0);
	setStopCFM(upper, s);
}

void writeLimitRows(RowWriter& w)
{
	for (int axis = 0; axis < 6; ++axis)
		if (w.settings[axis].state == 4) writeLimitRowPair(w, axis);
}

// A motor's or servo's row, bounded by the largest force times the step.
void writeMotorRow(RowWriter& w, int axis)
{
	const CoordinateSettings& s = w.settings[axis];
	caliber::JointRow row = w.startRow(axis);
	const btScalar erp = s.motorERP;
	if (s.servo)
	{
		// Towards the target at up to |m_targetVelocity|, covering at most erp of the remaining gap
		// per step so that the servo settles on the target instead of overshooting it. A weak motor
		// also needs room to brake: decelerating at half its most, F K / 2 (the other half is left
		// for loads on the coordinate and for the rows it shares its bodies with), a speed v stops
		// within v^2 / (F K), so the servo never asks for more than sqrt(F K gap).
		const btScalar gap = coordinateDifference(axis, s.servoTarget, s.position);
		const btScalar brakingSpeed =
		    btSqrt(btFabs(s.maxMotorForce) * w.jacobian[axis].inverseMass(w.bodyA, w.bodyB) * btFabs(gap));
		const btScalar speed = btMin(btMin(btFabs(s.targetVelocity), w.fps * erp * btFabs(gap)), brakingSpeed);
		row.error() = gap > btScalar(0) ? speed : (gap < btScalar(0) ? -speed : btScalar(0));
	}
	else
	{
		row.error() = s.motorVelocity * s.motorFactor;
	}
	const btScalar bound = btFabs(s.maxMotorForce) * w.h;
	row.lower() = -bound;
	row.upper() = bound;
	if (s.hasMotorCFM) row.cfm() = s.motorCFM;
}

void writeMotorRows(RowWriter& w)
{
	for (int axis = 0; axis < 6; ++axis)
		if (w.settings[axis].state != 3 && w.settings[axis].motor) writeMotorRow(w, axis);
}

// Springs.
//
// Implicit (backward Euler) spring on the coordinate x = q - q0 with rate v: the impulse p of the step
// is the force at the END of the step,
//     p = -h (k x' + c v'),  x' = x + h v',  v' = v + K p,
// with K = J M^-1 J^T the inverse of the mass the row moves. Eliminating x',
//     p = -h k x - D v',  D = h (h k + c),
// which is exactly a soft constraint row: v' = -(h k / D) x - p / D, i.e. a row whose target is
// fps * ERP * (-x) with ERP = h k / (h k + c), and whose softness (velocity per impulse) is 1 / D. The
// solver's CFM is in impulse per impulse (it is scaled by 1 / K), so CFM = 1 / (K D). Backward Euler
// damps every mode and never gains energy, so any k and c are stable at any h.
// The solver's iteration for a lone soft row contracts by CFM per sweep and diverges for CFM > 1, which
// is where the spring is slow compared with the step ((omega h)^2 + 2 zeta omega h < 1). There the same
// implicit impulse is computed in closed form,
//     p = -(h k x + D v) / (1 + K D),
// and applied as a fixed impulse (both bounds p). Both forms give the same step for a spring on its
// own; the soft row also shares the work correctly with other rows through the iterations.
void writeSpringRow(RowWriter& w, int axis)
{
	const btScalar h = w.h;
	const CoordinateSettings& s = w.settings[axis];
	caliber::JointRow row = w.startRow(axis);
	const btScalar k = s.stiffness > btScalar(0) ? s.stiffness : btScalar(0);
	const btScalar c = s.damping > btScalar(0) ? s.damping : btScalar(0);
	const btScalar x = coordinateDifference(axis, s.position, s.equilibrium);
	const btScalar D = h * (h * k + c);
	const btScalar K = w.jacobian[axis].inverseMass(w.bodyA, w.bodyB);
	if (K * D * kLargestSoftRowCfm >= btScalar(1))
	{
		row.error() = -w.fps * (h * k / (h * k + c)) * x;
		row.cfm() = btScalar(1) / (K * D);
		row.lower() = -SIMD_INFINITY;
		row.upper() = SIMD_INFINITY;
	}
	else
	{
		const btScalar v = w.rate(axis) * w.info.m_damping;
		const btScalar p = -(h * k * x + D * v) / (btScalar(1) + K * D);
		row.error() = btScalar(0);
		row.cfm() = btScalar(0);
		row.lower() = p;
		row.upper() = p;
	}
}

void writeSpringRows(RowWriter& w)
{
	for (int axis = 0; axis < 6; ++axis)
		if (w.settings[axis].state != 3 && w.settings[axis].spring) writeSpringRow(w, axis);
}

// A coordinate's rows in the order Bullet's get_limit_motor_info2 writes them: the locked row, or the
// limit rows, then the motor and the spring; returns how many.
int writeCoordinateRows(RowWriter& w, int axis)
{
	const int first = w.next;
	const CoordinateSettings& s = w.settings[axis];
	if (s.state == 3)
	{
		writeLockedRow(w, axis);
		return 1;
	}
	if (s.state == 4) writeLimitRowPair(w, axis);
	if (s.motor) writeMotorRow(w, axis);
	if (s.spring) writeSpringRow(w, axis);
	return w.next - first;
}
}  // namespace

void btGeneric6DofSpring2Constraint::getInfo2(btConstraintInfo2* info)
{
	// Measured again (getInfo1 did so for the same poses): getInfo2 must stand on its own.
	calculateTransforms();

	// Each coordinate's Jacobian, written so that J v is the coordinate's rate.
	CoordinateRow jacobian[6];
	const btVector3 pivotB = m_calculatedTransformB.getOrigin();
	const btVector3 armA = pivotB - m_rbA.getCenterOfMassPosition();
	const btVector3 armB = pivotB - m_rbB.getCenterOfMassPosition();
	for (int i = 0; i < 3; ++i)
	{
		// d_i = a_i . (pB - pA) with a_i A's axis i. Its rate is a_i . (vB + wB x armB - vA - wA x armA)
		// with armA reaching from A's centre of mass to B's pivot: the turning of a_i itself,
		// (wA x a_i) . (pB - pA), is what moves A's arm from A's pivot out to B's.
		jacobian[i] = CoordinateRow::linear(-m_calculatedTransformA.getBasis().getColumn(i), armA, armB);
		jacobian[3 + i] = CoordinateRow::rotation(m_angularJacobian[i]);
	}

	// Each coordinate's settings, from the linear motor (0..2) or an angular one (3..5).
	const btScalar fps = info->fps;
	CoordinateSettings settings[6];
	for (int axis = 0; axis < 6; ++axis)
	{
		CoordinateSettings& s = settings[axis];
		const int flags = m_flags >> (axis * BT_6DOF_FLAGS_AXIS_SHIFT2);
		const bool ownStopERP = (flags & BT_6DOF_FLAGS_ERP_STOP2) != 0;
		const bool ownMotorERP = (flags & BT_6DOF_FLAGS_ERP_MOTO2) != 0;
		s.hasStopCFM = (flags & BT_6DOF_FLAGS_CFM_STOP2) != 0;
		s.hasMotorCFM = (flags & BT_6DOF_FLAGS_CFM_MOTO2) != 0;
		if (axis < 3)
		{
			const btTranslationalLimitMotor2& m = m_linearLimits;
			s.lo = m.m_lowerLimit[axis];
			s.hi = m.m_upperLimit[axis];
			s.position = m.m_currentLinearDiff[axis];
			s.bounce = m.m_bounce[axis];
			s.motor = m.m_enableMotor[axis];
			s.servo = m.m_servoMotor[axis];
			s.spring = m.m_enableSpring[axis];
			s.targetVelocity = m.m_targetVelocity[axis];
			s.maxMotorForce = m.m_maxMotorForce[axis];
			s.servoTarget = m.m_servoTarget[axis];
			s.stiffness = m.m_springStiffness[axis];
			s.damping = m.m_springDamping[axis];
			s.equilibrium = m.m_equilibriumPoint[axis];
			s.state = m.m_currentLimit[axis];
			s.stopERP = ownStopERP ? m.m_stopERP[axis] : info->erp;
			s.motorERP = ownMotorERP ? m.m_motorERP[axis] : info->erp;
			s.stopCFM = m.m_stopCFM[axis];
			s.motorCFM = m.m_motorCFM[axis];
		}
		else
		{
			const btRotationalLimitMotor2& m = m_angularLimits[axis - 3];
			readMotorSettings(m, s);
			s.stopERP = ownStopERP ? m.m_stopERP : info->erp;
			s.motorERP = ownMotorERP ? m.m_motorERP : info->erp;
		}
		// Bullet's sense: the motor drives A relative to B, which for a linear coordinate (B's pivot in
		// A's frame) is the opposite of the coordinate's rate.
		s.motorVelocity = (axis < 3 ? btScalar(-1) : btScalar(1)) * s.targetVelocity;
		s.motorFactor = getMotorFactor(s.position, s.lo, s.hi, s.motorVelocity, fps * s.motorERP);
	}

	RowWriter writer{*info,
	                 fps,
	                 fps > btScalar(0) ? btScalar(1) / fps : btScalar(0),
	                 m_rbA,
	                 m_rbB,
	                 m_rbA.getLinearVelocity(),
	                 m_rbA.getAngularVelocity(),
	                 m_rbB.getLinearVelocity(),
	                 m_rbB.getAngularVelocity(),
	                 jacobian,
	                 settings,
	                 0};
	writeLockedRows(writer);
	writeLimitRows(writer);
	writeMotorRows(writer);
	writeSpringRows(writer);
}

// ---- Bullet's protected row interface (for subclasses; getInfo2 writes the same rows, grouped by kind)

namespace
{
// Resolves a coordinate's stop and motor ERP and CFM as getInfo2 does: its own where set through setParam
// (flags), info's ERP and the starting CFM of the coordinate's first row otherwise.
void resolveParams(btRotationalLimitMotor2& motor, int flags, const btTypedConstraint::btConstraintInfo2& info, int row)
{
	const btScalar startingCfm = info.cfm[row * info.rowskip];
	if (!(flags & BT_6DOF_FLAGS_ERP_STOP2)) motor.m_stopERP = info.erp;
	if (!(flags & BT_6DOF_FLAGS_ERP_MOTO2)) motor.m_motorERP = info.erp;
	if (!(flags & BT_6DOF_FLAGS_CFM_STOP2)) motor.m_stopCFM = startingCfm;
	if (!(flags & BT_6DOF_FLAGS_CFM_MOTO2)) motor.m_motorCFM = startingCfm;
}
}  // namespace

int btGeneric6DofSpring2Constraint::setAngularLimits(btConstraintInfo2* info, int row_offset, const btTransform& transA,
                                                     const btTransform& transB, const btVector3& linVelA,
                                                     const btVector3& linVelB, const btVector3& angVelA,
                                                     const btVector3& angVelB)
{
	btAssert(info && "btGeneric6DofSpring2Constraint::setAngularLimits: no rows");
	if (!info) return row_offset;
	int row = row_offset;
	for (int i = 0; i < 3; ++i)
	{
		btRotationalLimitMotor2 motor(m_angularLimits[i]);
		resolveParams(motor, m_flags >> ((3 + i) * BT_6DOF_FLAGS_AXIS_SHIFT2), *info, row);
		btVector3 axis = m_angularJacobian[i];  // the exact rate direction (getAxis is its unit vector)
		row += get_limit_motor_info2(&motor, transA, transB, linVelA, linVelB, angVelA, angVelB, info, row, axis, 1);
	}
	return row;
}

int btGeneric6DofSpring2Constraint::setLinearLimits(btConstraintInfo2* info, int row, const btTransform& transA,
                                                    const btTransform& transB, const btVector3& linVelA,
                                                    const btVector3& linVelB, const btVector3& angVelA,
                                                    const btVector3& angVelB)
{
	btAssert(info && "btGeneric6DofSpring2Constraint::setLinearLimits: no rows");
	if (!info) return row;
	const btTranslationalLimitMotor2& m = m_linearLimits;
	for (int i = 0; i < 3; ++i)
	{
		// The axis's settings in a limit motor's form.
		btRotationalLimitMotor2 motor;
		motor.m_loLimit = m.m_lowerLimit[i];
		motor.m_hiLimit = m.m_upperLimit[i];
		motor.m_bounce = m.m_bounce[i];
		motor.m_stopERP = m.m_stopERP[i];
		motor.m_stopCFM = m.m_stopCFM[i];
		motor.m_motorERP = m.m_motorERP[i];
		motor.m_motorCFM = m.m_motorCFM[i];
		motor.m_enableMotor = m.m_enableMotor[i];
		motor.m_servoMotor = m.m_servoMotor[i];
		motor.m_enableSpring = m.m_enableSpring[i];
		motor.m_servoTarget = m.m_servoTarget[i];
		motor.m_springStiffness = m.m_springStiffness[i];
		motor.m_springStiffnessLimited = m.m_springStiffnessLimited[i];
		motor.m_springDamping = m.m_springDamping[i];
		motor.m_springDampingLimited = m.m_springDampingLimited[i];
		motor.m_equilibriumPoint = m.m_equilibriumPoint[i];
		motor.m_targetVelocity = m.m_targetVelocity[i];
		motor.m_maxMotorForce = m.m_maxMotorForce[i];
		motor.m_currentLimit = m.m_currentLimit[i];
		motor.m_currentLimitError = m.m_currentLimitError[i];
		motor.m_currentLimitErrorHi = m.m_currentLimitErrorHi[i];
		motor.m_currentPosition = m.m_currentLinearDiff[i];
		resolveParams(motor, m_flags >> (i * BT_6DOF_FLAGS_AXIS_SHIFT2), *info, row);
		btVector3 axis = m_calculatedTransformA.getBasis().getColumn(i);
		row += get_limit_motor_info2(&motor, transA, transB, linVelA, linVelB, angVelA, angVelB, info, row, axis, 0, 1);
	}
	return row;
}

void btGeneric6DofSpring2Constraint::calculateJacobi(btRotationalLimitMotor2* limot, const btTransform& transA,
                                                     const btTransform& transB, btConstraintInfo2* info, int srow,
                                                     btVector3& ax1, int rotational, int rotAllowed)
{
	(void)limot;
	btAssert(info && "btGeneric6DofSpring2Constraint::calculateJacobi: no rows");
	if (!info) return;
	caliber::JointRow row(*info, srow);
	if (rotational)
	{
		row.setAngular(ax1);
		return;
	}
	const btVector3 pivotB = m_calculatedTransformB.getOrigin();
	const btVector3 zero(0, 0, 0);
	row.setLinear(ax1, rotAllowed ? pivotB - transA.getOrigin() : zero,
	              rotAllowed ? pivotB - transB.getOrigin() : zero);
}

int btGeneric6DofSpring2Constraint::get_limit_motor_info2(btRotationalLimitMotor2* limot, const btTransform& transA,
                                                          const btTransform& transB, const btVector3& linVelA,
                                                          const btVector3& linVelB, const btVector3& angVelA,
                                                          const btVector3& angVelB, btConstraintInfo2* info, int row,
                                                          btVector3& ax1, int rotational, int rotAllowed)
{
	btAssert(limot && info && "btGeneric6DofSpring2Constraint::get_limit_motor_info2: no motor or no rows");
	if (!limot || !info) return 0;
	// The coordinate as axis 3 (an angle) or 0 (linear) of the row writers, whose Jacobian J has J v equal
	// to the coordinate's rate: for a linear coordinate (B's pivot relative to A) that is along -ax1.
	const int axis = rotational ? 3 : 0;
	CoordinateRow jacobian[6];
	CoordinateSettings settings[6];
	const btVector3 pivotB = m_calculatedTransformB.getOrigin();
	const btVector3 zero(0, 0, 0);
	jacobian[axis] = rotational ? CoordinateRow::rotation(ax1)
	                            : CoordinateRow::linear(-ax1, rotAllowed ? pivotB - transA.getOrigin() : zero,
	                                                    rotAllowed ? pivotB - transB.getOrigin() : zero);
	CoordinateSettings& s = settings[axis];
	readMotorSettings(*limot, s);
	s.hasStopCFM = true;
	s.hasMotorCFM = true;
	const btScalar fps = info->fps;
	s.motorVelocity = (rotational ? btScalar(1) : btScalar(-1)) * s.targetVelocity;
	s.motorFactor = getMotorFactor(s.position, s.lo, s.hi, s.motorVelocity, fps * s.motorERP);
	RowWriter writer{*info,    fps,      fps > btScalar(0) ? btScalar(1) / fps : btScalar(0),
	                 m_rbA,    m_rbB,    linVelA,
	                 angVelA,  linVelB,  angVelB,
	                 jacobian, settings, row};
	return writeCoordinateRows(writer, axis);
}

// ---- settings -----------------------------------------------------------------------------------

btRotationalLimitMotor2* btGeneric6DofSpring2Constraint::getRotationalLimitMotor(int index)
{
	if (!angleIndexInRange(index, "getRotationalLimitMotor")) index = index < 0 ? 0 : 2;
	return &m_angularLimits[index];
}

btVector3 btGeneric6DofSpring2Constraint::getAxis(int axis_index) const
{
	return angleIndexInRange(axis_index, "getAxis") ? m_calculatedAxis[axis_index] : btVector3(0, 0, 0);
}

btScalar btGeneric6DofSpring2Constraint::getAngle(int axis_index) const
{
	return angleIndexInRange(axis_index, "getAngle") ? m_calculatedAxisAngleDiff[axis_index] : btScalar(0);
}

btScalar btGeneric6DofSpring2Constraint::getRelativePivotPosition(int axis_index) const
{
	return angleIndexInRange(axis_index, "getRelativePivotPosition") ? m_calculatedLinearDiff[axis_index] : btScalar(0);
}

void btGeneric6DofSpring2Constraint::setFrames(const btTransform& frameA, const btTransform& frameB)
{
	if (!caliber::isFinite(frameA) || !caliber::isFinite(frameB))
	{
		warn("setFrames", "non-finite joint frame; frames kept and the joint is disabled");
		setEnabled(false);
		return;
	}
	m_frameInA = frameA;
	m_frameInB = frameB;
	calculateTransforms();
}

void btGeneric6DofSpring2Constraint::setLimit(int axis, btScalar lo, btScalar hi)
{
	if (!checkIndex(axis, "setLimit")) return;
	if (!btIsFinite(lo) || !btIsFinite(hi))
	{
		warn("setLimit", "non-finite limit ignored");
		return;
	}
	if (axis < 3)
	{
		m_linearLimits.m_lowerLimit[axis] = lo;
		m_linearLimits.m_upperLimit[axis] = hi;
	}
	else
	{
		m_angularLimits[axis - 3].m_loLimit = btNormalizeAngle(lo);
		m_angularLimits[axis - 3].m_hiLimit = btNormalizeAngle(hi);
	}
}

void btGeneric6DofSpring2Constraint::setLimitReversed(int axis, btScalar lo, btScalar hi)
{
	if (!checkIndex(axis, "setLimitReversed")) return;
	if (!btIsFinite(lo) || !btIsFinite(hi))
	{
		warn("setLimitReversed", "non-finite limit ignored");
		return;
	}
	if (axis < 3)
	{
		m_linearLimits.m_lowerLimit[axis] = lo;
		m_linearLimits.m_upperLimit[axis] = hi;
	}
	else
	{
		m_angularLimits[axis - 3].m_loLimit = -btNormalizeAngle(hi);
		m_angularLimits[axis - 3].m_hiLimit = -btNormalizeAngle(lo);
	}
}

bool btGeneric6DofSpring2Constraint::isLimited(int limitIndex) const
{
	if (!checkIndex(limitIndex, "isLimited")) return false;
	return limitIndex < 3 ? m_linearLimits.isLimited(limitIndex) : m_angularLimits[limitIndex - 3].isLimited();
}

void btGeneric6DofSpring2Constraint::setAxis(const btVector3& axis1, const btVector3& axis2)
{
	const btScalar length1 = caliber::isFinite(axis1) ? axis1.length() : btScalar(0);
	const btVector3 zAxis = length1 > SIMD_EPSILON ? axis1 / length1 : btVector3(0, 0, 0);
	const btVector3 across = caliber::isFinite(axis2) ? axis2 - zAxis * zAxis.dot(axis2) : btVector3(0, 0, 0);
	const btScalar length2 = across.length();
	if (!(length1 > SIMD_EPSILON) || !(length2 > SIMD_EPSILON * btMax(btScalar(1), axis2.length())))
	{
		warn("setAxis", "zero, non-finite or parallel axes ignored");
		return;
	}
	const btVector3 yAxis = across / length2;
	const btVector3 xAxis = yAxis.cross(zAxis);
	btTransform frameInWorld;
	frameInWorld.setIdentity();
	frameInWorld.getBasis().setValue(xAxis.x(), yAxis.x(), zAxis.x(), xAxis.y(), yAxis.y(), zAxis.y(), xAxis.z(),
	                                 yAxis.z(), zAxis.z());
	m_frameInA = m_rbA.getCenterOfMassTransform().inverse() * frameInWorld;
	m_frameInB = m_rbB.getCenterOfMassTransform().inverse() * frameInWorld;
	calculateTransforms();
}

void btGeneric6DofSpring2Constraint::setBounce(int index, btScalar bounce)
{
	if (!checkIndex(index, "setBounce")) return;
	if (!btIsFinite(bounce) || bounce < btScalar(0))
	{
		warn("setBounce", "negative or non-finite bounce ignored");
		return;
	}
	if (index < 3)
		m_linearLimits.m_bounce[index] = bounce;
	else
		m_angularLimits[index - 3].m_bounce = bounce;
}

void btGeneric6DofSpring2Constraint::enableMotor(int index, bool onOff)
{
	if (!checkIndex(index, "enableMotor")) return;
	if (index < 3)
		m_linearLimits.m_enableMotor[index] = onOff;
	else
		m_angularLimits[index - 3].m_enableMotor = onOff;
}

void btGeneric6DofSpring2Constraint::setServo(int index, bool onOff)
{
	if (!checkIndex(index, "setServo")) return;
	if (index < 3)
		m_linearLimits.m_servoMotor[index] = onOff;
	else
		m_angularLimits[index - 3].m_servoMotor = onOff;
}

void btGeneric6DofSpring2Constraint::setTargetVelocity(int index, btScalar velocity)
{
	if (!checkIndex(index, "setTargetVelocity")) return;
	if (!btIsFinite(velocity))
	{
		warn("setTargetVelocity", "non-finite velocity ignored");
		return;
	}
	if (index < 3)
		m_linearLimits.m_targetVelocity[index] = velocity;
	else
		m_angularLimits[index - 3].m_targetVelocity = velocity;
}

void btGeneric6DofSpring2Constraint::setServoTarget(int index, btScalar target)
{
	if (!checkIndex(index, "setServoTarget")) return;
	if (!btIsFinite(target))
	{
		warn("setServoTarget", "non-finite target ignored");
		return;
	}
	if (index < 3)
	{
		m_linearLimits.m_servoTarget[index] = target;
		return;
	}
	btScalar wrapped = btNormalizeAngle(target);
	if (wrapped >= SIMD_PI) wrapped -= SIMD_2_PI;  // [-pi, pi), as Bullet stores it
	m_angularLimits[index - 3].m_servoTarget = wrapped;
}

void btGeneric6DofSpring2Constraint::setMaxMotorForce(int index, btScalar force)
{
	if (!checkIndex(index, "setMaxMotorForce")) return;
	if (!btIsFinite(force) || force < btScalar(0))
	{
		warn("setMaxMotorForce", "negative or non-finite force ignored");
		return;
	}
	if (index < 3)
		m_linearLimits.m_maxMotorForce[index] = force;
	else
		m_angularLimits[index - 3].m_maxMotorForce = force;
}

void btGeneric6DofSpring2Constraint::enableSpring(int index, bool onOff)
{
	if (!checkIndex(index, "enableSpring")) return;
	if (index < 3)
		m_linearLimits.m_enableSpring[index] = onOff;
	else
		m_angularLimits[index - 3].m_enableSpring = onOff;
}

void btGeneric6DofSpring2Constraint::setStiffness(int index, btScalar stiffness, bool limitIfNeeded)
{
	if (!checkIndex(index, "setStiffness")) return;
	if (!btIsFinite(stiffness) || stiffness < btScalar(0))
	{
		warn("setStiffness", "negative or non-finite stiffness ignored");
		return;
	}
	if (index < 3)
	{
		m_linearLimits.m_springStiffness[index] = stiffness;
		m_linearLimits.m_springStiffnessLimited[index] = limitIfNeeded;
	}
	else
	{
		m_angularLimits[index - 3].m_springStiffness = stiffness;
		m_angularLimits[index - 3].m_springStiffnessLimited = limitIfNeeded;
	}
}

void btGeneric6DofSpring2Constraint::setDamping(int index, btScalar damping, bool limitIfNeeded)
{
	if (!checkIndex(index, "setDamping")) return;
	if (!btIsFinite(damping) || damping < btScalar(0))
	{
		warn("setDamping", "negative or non-finite damping ignored");
		return;
	}
	if (index < 3)
	{
		m_linearLimits.m_springDamping[index] = damping;
		m_linearLimits.m_springDampingLimited[index] = limitIfNeeded;
	}
	else
	{
		m_angularLimits[index - 3].m_springDamping = damping;
		m_angularLimits[index - 3].m_springDampingLimited = limitIfNeeded;
	}
}

void btGeneric6DofSpring2Constraint::setEquilibriumPoint()
{
	calculateTransforms();
	for (int i = 0; i < 3; ++i)
	{
		m_linearLimits.m_equilibriumPoint[i] = m_calculatedLinearDiff[i];
		m_angularLimits[i].m_equilibriumPoint = m_calculatedAxisAngleDiff[i];
	}
}

void btGeneric6DofSpring2Constraint::setEquilibriumPoint(int index)
{
	if (!checkIndex(index, "setEquilibriumPoint")) return;
	calculateTransforms();
	if (index < 3)
		m_linearLimits.m_equilibriumPoint[index] = m_calculatedLinearDiff[index];
	else
		m_angularLimits[index - 3].m_equilibriumPoint = m_calculatedAxisAngleDiff[index - 3];
}

void btGeneric6DofSpring2Constraint::setEquilibriumPoint(int index, btScalar val)
{
	if (!checkIndex(index, "setEquilibriumPoint")) return;
	if (!btIsFinite(val))
	{
		warn("setEquilibriumPoint", "non-finite equilibrium ignored");
		return;
	}
	if (index < 3)
		m_linearLimits.m_equilibriumPoint[index] = val;
	else
		m_angularLimits[index - 3].m_equilibriumPoint = val;
}

void btGeneric6DofSpring2Constraint::setParam(int num, btScalar value, int axis)
{
	const bool validAxis = axis >= 0 && axis < 6;
	btAssertConstrParams(validAxis && "btGeneric6DofSpring2Constraint::setParam: axis must be 0..5");
	if (!validAxis)
	{
		warn("setParam", "axis outside 0..5; call ignored");
		return;
	}
	const int shift = axis * BT_6DOF_FLAGS_AXIS_SHIFT2;
	btScalar* field = 0;
	int flag = 0;
	switch (num)
	{
		case BT_CONSTRAINT_STOP_ERP:
			field = axis < 3 ? &m_linearLimits.m_stopERP[axis] : &m_angularLimits[axis - 3].m_stopERP;
			flag = BT_6DOF_FLAGS_ERP_STOP2;
			break;
		case BT_CONSTRAINT_STOP_CFM:
			field = axis < 3 ? &m_linearLimits.m_stopCFM[axis] : &m_angularLimits[axis - 3].m_stopCFM;
			flag = BT_6DOF_FLAGS_CFM_STOP2;
			break;
		case BT_CONSTRAINT_ERP:
			field = axis < 3 ? &m_linearLimits.m_motorERP[axis] : &m_angularLimits[axis - 3].m_motorERP;
			flag = BT_6DOF_FLAGS_ERP_MOTO2;
			break;
		case BT_CONSTRAINT_CFM:
			field = axis < 3 ? &m_linearLimits.m_motorCFM[axis] : &m_angularLimits[axis - 3].m_motorCFM;
			flag = BT_6DOF_FLAGS_CFM_MOTO2;
			break;
		default:
			btAssertConstrParams(0 && "btGeneric6DofSpring2Constraint::setParam: unknown parameter");
			warn("setParam", "unknown parameter; call ignored");
			return;
	}
	if (!btIsFinite(value))
	{
		warn("setParam", "non-finite value ignored");
		return;
	}
	*field = value;
	m_flags |= flag << shift;
}

btScalar btGeneric6DofSpring2Constraint::getParam(int num, int axis) const
{
	const bool validAxis = axis >= 0 && axis < 6;
	btAssertConstrParams(validAxis && "btGeneric6DofSpring2Constraint::getParam: axis must be 0..5");
	if (!validAxis) return btScalar(0);
	const int flags = m_flags >> (axis * BT_6DOF_FLAGS_AXIS_SHIFT2);
	(void)flags;
	switch (num)
	{
		case BT_CONSTRAINT_STOP_ERP:
			btAssertConstrParams(flags & BT_6DOF_FLAGS_ERP_STOP2);
			return axis < 3 ? m_linearLimits.m_stopERP[axis] : m_angularLimits[axis - 3].m_stopERP;
		case BT_CONSTRAINT_STOP_CFM:
			btAssertConstrParams(flags & BT_6DOF_FLAGS_CFM_STOP2);
			return axis < 3 ? m_linearLimits.m_stopCFM[axis] : m_angularLimits[axis - 3].m_stopCFM;
		case BT_CONSTRAINT_ERP:
			btAssertConstrParams(flags & BT_6DOF_FLAGS_ERP_MOTO2);
			return axis < 3 ? m_linearLimits.m_motorERP[axis] : m_angularLimits[axis - 3].m_motorERP;
		case BT_CONSTRAINT_CFM:
			btAssertConstrParams(flags & BT_6DOF_FLAGS_CFM_MOTO2);
			return axis < 3 ? m_linearLimits.m_motorCFM[axis] : m_angularLimits[axis - 3].m_motorCFM;
		default:
			btAssertConstrParams(0 && "btGeneric6DofSpring2Constraint::getParam: unknown parameter");
			return btScalar(0);
	}
}

// ---- Euler angles -------------------------------------------------------------------------------

btScalar btGeneric6DofSpring2Constraint::btGetMatrixElem(const btMatrix3x3& mat, int index)
{
	return mat[index % 3][index / 3];
}

// mat is A^T B; the decomposition is of its transpose B^T A (see the header's conventions).
bool btGeneric6DofSpring2Constraint::matrixToEulerXYZ(const btMatrix3x3& mat, btVector3& xyz)
{
	return decomposeEuler(mat.transpose(), eulerOrder(RO_XYZ), xyz);
}
bool btGeneric6DofSpring2Constraint::matrixToEulerXZY(const btMatrix3x3& mat, btVector3& xyz)
{
	return decomposeEuler(mat.transpose(), eulerOrder(RO_XZY), xyz);
}
bool btGeneric6DofSpring2Constraint::matrixToEulerYXZ(const btMatrix3x3& mat, btVector3& xyz)
{
	return decomposeEuler(mat.transpose(), eulerOrder(RO_YXZ), xyz);
}
bool btGeneric6DofSpring2Constraint::matrixToEulerYZX(const btMatrix3x3& mat, btVector3& xyz)
{
	return decomposeEuler(mat.transpose(), eulerOrder(RO_YZX), xyz);
}
bool btGeneric6DofSpring2Constraint::matrixToEulerZXY(const btMatrix3x3& mat, btVector3& xyz)
{
	return decomposeEuler(mat.transpose(), eulerOrder(RO_ZXY), xyz);
}
bool btGeneric6DofSpring2Constraint::matrixToEulerZYX(const btMatrix3x3& mat, btVector3& xyz)
{
	return decomposeEuler(mat.transpose(), eulerOrder(RO_ZYX), xyz);
}
