// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"

#include "BulletDynamics/ConstraintSolver/btGeneric6DofRows.h"
#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btWarningHook.h"

// The coordinates and their rates.
//
// Linear: x_i = a_i . (pB - pA), a_i the reference frame's axis i, pA and pB the frame origins. Its rate
// is exactly a_i . (velocity of B at P - velocity of A at P) with P = pB when the reference frame is A's
// (the axes turn with A, so the rate is taken against the point of A that lies under pB) and P = pA when
// it is B's. The linear rows therefore act at one point P for both bodies.
//
// Angular: A^-1 B = Rz(z) Ry(y) Rx(x). Differentiating B = A Rz Ry Rx gives the relative angular velocity
//   wB - wA = x' e1 + y' e2 + z' e3,  e1 = B's X axis,  e2 = A Rz ey,  e3 = A's Z axis.
// e2 is perpendicular to e1 and e3, and e1 . e3 = -sin y, so the rates are read off with the dual basis
// (D_i . e_j = delta_ij): with u = A Rz ex (perpendicular to e2 and e3),
//   D_x = u / cos y,  D_y = e2,  D_z = e3 + tan y u,
// and angle i's rate is D_i . (wB - wA). Each row is built on D_i itself, so that its target is the
// angle's rate and its impulse the angle's generalised torque (times the step).

namespace
{
// Rows with 1 / cos y are clamped here, near the singular y = +-pi/2 (the joint is documented not to go
// there; this only keeps the rows finite if it does).
const btScalar kMinCosY = btScalar(1e-3);

}  // namespace

btRotationalLimitMotor::btRotationalLimitMotor()
    : m_loLimit(btScalar(1)),
      m_hiLimit(btScalar(-1)),
      m_targetVelocity(btScalar(0)),
      m_maxMotorForce(btScalar(6)),
      m_maxLimitForce(btScalar(300)),
      m_damping(btScalar(1)),
      m_limitSoftness(btScalar(0.5)),
      m_normalCFM(btScalar(0)),
      m_stopERP(btScalar(0.2)),
      m_stopCFM(btScalar(0)),
      m_bounce(btScalar(0)),
      m_enableMotor(false),
      m_currentLimitError(btScalar(0)),
      m_currentPosition(btScalar(0)),
      m_currentLimit(0),
      m_accumulatedImpulse(btScalar(0))
{
}

int btRotationalLimitMotor::testLimitValue(btScalar test_value)
{
	m_currentPosition = test_value;
	m_currentLimit = 0;
	m_currentLimitError = btScalar(0);
	if (m_loLimit > m_hiLimit) return 0;
	if (m_loLimit == m_hiLimit)
	{
		// Locked: which side it is on, the short way round.
		const btScalar error = btNormalizeAngle(test_value - m_loLimit);
		if (error != btScalar(0))
		{
			m_currentLimit = error < btScalar(0) ? 1 : 2;
			m_currentLimitError = error;
		}
		return m_currentLimit;
	}
	const btScalar angle = btAdjustAngleToLimits(test_value, m_loLimit, m_hiLimit);
	if (angle < m_loLimit)
	{
		m_currentLimit = 1;
		m_currentLimitError = angle - m_loLimit;
	}
	else if (angle > m_hiLimit)
	{
		m_currentLimit = 2;
		m_currentLimitError = angle - m_hiLimit;
	}
	return m_currentLimit;
}

btTranslationalLimitMotor::btTranslationalLimitMotor()
    : m_lowerLimit(0, 0, 0),
      m_upperLimit(0, 0, 0),
      m_accumulatedImpulse(0, 0, 0),
      m_limitSoftness(btScalar(0.7)),
      m_damping(btScalar(1)),
      m_restitution(btScalar(0.5)),
      m_normalCFM(0, 0, 0),
      m_stopERP(btScalar(0.2), btScalar(0.2), btScalar(0.2)),
      m_stopCFM(0, 0, 0),
      m_targetVelocity(0, 0, 0),
      m_maxMotorForce(0, 0, 0),
      m_currentLimitError(0, 0, 0),
      m_currentLinearDiff(0, 0, 0)
{
	for (int i = 0; i < 3; ++i)
	{
		m_enableMotor[i] = false;
		m_currentLimit[i] = 0;
	}
}

int btTranslationalLimitMotor::testLimitValue(int limitIndex, btScalar test_value)
{
	const btScalar lower = m_lowerLimit[limitIndex], upper = m_upperLimit[limitIndex];
	int& limit = m_currentLimit[limitIndex];
	limit = 0;
	m_currentLimitError[limitIndex] = btScalar(0);
	if (lower > upper) return 0;
	if (test_value < lower)
	{
		limit = 1;
		m_currentLimitError[limitIndex] = test_value - lower;
	}
	else if (test_value > upper)
	{
		limit = 2;
		m_currentLimitError[limitIndex] = test_value - upper;
	}
	return limit;
}

btGeneric6DofConstraint::btGeneric6DofConstraint(btRigidBody& rbA, btRigidBody& rbB, const btTransform& frameInA,
                                                 const btTransform& frameInB, bool useLinearReferenceFrameA)
    : btTypedConstraint(D6_CONSTRAINT_TYPE, rbA, rbB),
      m_frameInA(frameInA),
      m_frameInB(frameInB),
      m_timeStep(0),
      m_factA(btScalar(0.5)),
      m_factB(btScalar(0.5)),
      m_hasStaticBody(false),
      m_useLinearReferenceFrameA(useLinearReferenceFrameA),
      m_useOffsetForConstraintFrame(true),
      m_flags(0),
      m_useSolveConstraintObsolete(false)
{
	if (caliber::sixDofFramesFinite(*this)) calculateTransforms();
}

btGeneric6DofConstraint::btGeneric6DofConstraint(btRigidBody& rbB, const btTransform& frameInB,
                                                 bool useLinearReferenceFrameB)
    : btTypedConstraint(D6_CONSTRAINT_TYPE, getFixedBody(), rbB),
      m_frameInA(rbB.getCenterOfMassTransform() * frameInB),
      m_frameInB(frameInB),
      m_timeStep(0),
      m_factA(btScalar(0.5)),
      m_factB(btScalar(0.5)),
      m_hasStaticBody(false),
      m_useLinearReferenceFrameA(useLinearReferenceFrameB),
      m_useOffsetForConstraintFrame(true),
      m_flags(0),
      m_useSolveConstraintObsolete(false)
{
	if (caliber::sixDofFramesFinite(*this)) calculateTransforms();
}

void btGeneric6DofConstraint::calculateTransforms()
{
	calculateTransforms(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
}

void btGeneric6DofConstraint::calculateTransforms(const btTransform& transA, const btTransform& transB)
{
	m_centerOfMassA = transA.getOrigin();
	m_centerOfMassB = transB.getOrigin();
	m_calculatedTransformA = transA * m_frameInA;
	m_calculatedTransformB = transB * m_frameInB;
	const btScalar invMassA = m_rbA.getInvMass(), invMassB = m_rbB.getInvMass();
	m_hasStaticBody = invMassA < SIMD_EPSILON || invMassB < SIMD_EPSILON;
	const btScalar invMassSum = invMassA + invMassB;
	m_factA = invMassSum > btScalar(0) ? invMassB / invMassSum : btScalar(0.5);
	m_factB = btScalar(1) - m_factA;
	calcAnchorPos();
	calculateLinearInfo();
	calculateAngleInfo();
}

void btGeneric6DofConstraint::calcAnchorPos(void)
{
	const btScalar imA = m_rbA.getInvMass(), imB = m_rbB.getInvMass();
	const btScalar sum = imA + imB;
	const btScalar weightA = sum > btScalar(0) ? imA / sum : btScalar(0.5);
	m_AnchorPos = m_calculatedTransformA.getOrigin() * weightA + m_calculatedTransformB.getOrigin() * (1 - weightA);
}

void btGeneric6DofConstraint::calculateLinearInfo()
{
	const btVector3& pA = m_calculatedTransformA.getOrigin();
	const btVector3& pB = m_calculatedTransformB.getOrigin();
	const btMatrix3x3& reference =
	    m_useLinearReferenceFrameA ? m_calculatedTransformA.getBasis() : m_calculatedTransformB.getBasis();
	const btVector3 separation = pB - pA;
	for (int i = 0; i < 3; ++i)
	{
		m_linearRowAxis[i] = reference.getColumn(i);
		m_calculatedLinearDiff[i] = m_linearRowAxis[i].dot(separation);
		m_linearLimits.m_currentLinearDiff[i] = m_calculatedLinearDiff[i];
		m_linearLimits.testLimitValue(i, m_calculatedLinearDiff[i]);
	}
	if (m_useOffsetForConstraintFrame)
		m_linearRowPoint = m_useLinearReferenceFrameA ? pB : pA;
	else
		m_linearRowPoint = m_AnchorPos;
}

void btGeneric6DofConstraint::calculateAngleInfo()
{
	const btMatrix3x3& basisA = m_calculatedTransformA.getBasis();
	const btMatrix3x3 relative = basisA.transposeTimes(m_calculatedTransformB.getBasis());
	// relative = Rz(z) Ry(y) Rx(x): its first column is (cos z cos y, sin z cos y, -sin y) and its last row
	// is (-sin y, sin x cos y, cos x cos y).
	const btScalar cosY = btSqrt(relative[0][0] * relative[0][0] + relative[1][0] * relative[1][0]);
	const btScalar y = btAtan2(-relative[2][0], cosY);
	btScalar x, z;
	if (cosY > SIMD_EPSILON)
	{
		x = btAtan2(relative[2][1], relative[2][2]);
		z = btAtan2(relative[1][0], relative[0][0]);
	}
	else
	{
		// At y = +-pi/2 only x -+ z is defined; take x = 0, where the middle column is (-sin z, cos z, 0).
		x = btScalar(0);
		z = btAtan2(-relative[0][1], relative[1][1]);
	}
	m_calculatedAxisAngleDiff.setValue(x, y, z);

	const btScalar cz = btCos(z), sz = btSin(z), sy = btSin(y);
	const btVector3 u = basisA.getColumn(0) * cz + basisA.getColumn(1) * sz;
	const btVector3 e2 = basisA.getColumn(1) * cz - basisA.getColumn(0) * sz;
	const btVector3 e3 = basisA.getColumn(2);
	const btScalar rowCosY = btMax(btCos(y), kMinCosY);
	m_angularRowAxis[0] = u / rowCosY;
	m_angularRowAxis[1] = e2;
	m_angularRowAxis[2] = e3 + u * (sy / rowCosY);
	m_calculatedAxis[0] = u;
	m_calculatedAxis[1] = e2;
	m_calculatedAxis[2] = e3 * btCos(y) + u * sy;

	for (int i = 0; i < 3; ++i) m_angularLimits[i].testLimitValue(m_calculatedAxisAngleDiff[i]);
}

namespace
{
// Public accessors take an index from the user: out of range is reported (and asserted), never read.
bool indexInRange(int index, int count, const char* warning)
{
	const bool valid = index >= 0 && index < count;
	if (!valid) btReportWarning(warning);
	btAssert(valid && "btGeneric6DofConstraint: index out of range");
	return valid;
}
}  // namespace

btVector3 btGeneric6DofConstraint::getAxis(int axis_index) const
{
	if (!indexInRange(axis_index, 3, "Caliber: btGeneric6DofConstraint::getAxis: index outside 0..2; zero\n"))
		return btVector3(0, 0, 0);
	return m_calculatedAxis[axis_index];
}

btScalar btGeneric6DofConstraint::getAngle(int axis_index) const
{
	if (!indexInRange(axis_index, 3, "Caliber: btGeneric6DofConstraint::getAngle: index outside 0..2; zero\n"))
		return btScalar(0);
	return m_calculatedAxisAngleDiff[axis_index];
}

btScalar btGeneric6DofConstraint::getRelativePivotPosition(int axis_index) const
{
	if (!indexInRange(axis_index, 3,
	                  "Caliber: btGeneric6DofConstraint::getRelativePivotPosition: index outside 0..2; zero\n"))
		return btScalar(0);
	return m_calculatedLinearDiff[axis_index];
}

btRotationalLimitMotor* btGeneric6DofConstraint::getRotationalLimitMotor(int index)
{
	if (!indexInRange(index, 3,
	                  "Caliber: btGeneric6DofConstraint::getRotationalLimitMotor: index outside 0..2; clamped\n"))
		index = index < 0 ? 0 : 2;
	return &m_angularLimits[index];
}

void btGeneric6DofConstraint::setFrames(const btTransform& frameA, const btTransform& frameB)
{
	m_frameInA = frameA;
	m_frameInB = frameB;
	if (caliber::sixDofFramesFinite(*this)) calculateTransforms();
}

bool btGeneric6DofConstraint::testAngularLimitMotor(int axis_index)
{
	btRotationalLimitMotor& motor = m_angularLimits[axis_index];
	motor.testLimitValue(btNormalizeAngle(m_calculatedAxisAngleDiff[axis_index]));
	return motor.needApplyTorques();
}

void btGeneric6DofConstraint::setAngularLowerLimit(const btVector3& angularLower)
{
	for (int i = 0; i < 3; ++i) m_angularLimits[i].m_loLimit = btNormalizeAngle(angularLower[i]);
}

void btGeneric6DofConstraint::getAngularLowerLimit(btVector3& angularLower) const
{
	for (int i = 0; i < 3; ++i) angularLower[i] = m_angularLimits[i].m_loLimit;
}

void btGeneric6DofConstraint::setAngularUpperLimit(const btVector3& angularUpper)
{
	for (int i = 0; i < 3; ++i) m_angularLimits[i].m_hiLimit = btNormalizeAngle(angularUpper[i]);
}

void btGeneric6DofConstraint::getAngularUpperLimit(btVector3& angularUpper) const
{
	for (int i = 0; i < 3; ++i) angularUpper[i] = m_angularLimits[i].m_hiLimit;
}

void btGeneric6DofConstraint::setLimit(int axis, btScalar lo, btScalar hi)
{
	if (!indexInRange(axis, 6, "Caliber: btGeneric6DofConstraint::setLimit: axis outside 0..5; ignored\n")) return;
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

bool btGeneric6DofConstraint::isLimited(int limitIndex) const
{
	if (!indexInRange(limitIndex, 6, "Caliber: btGeneric6DofConstraint::isLimited: index outside 0..5; false\n"))
		return false;
	if (limitIndex < 3) return m_linearLimits.isLimited(limitIndex);
	return m_angularLimits[limitIndex - 3].isLimited();
}

void btGeneric6DofConstraint::getInfo1(btConstraintInfo1* info) { getInfo1NonVirtual(info); }

void btGeneric6DofConstraint::getInfo1NonVirtual(btConstraintInfo1* info)
{
	info->m_numConstraintRows = caliber::sixDofLimitMotorRowCount(*this);
	int locked = 0;
	for (int c = 0; c < 6; ++c) locked += caliber::sixDofIsLocked(*this, c) ? 1 : 0;
	info->nub = locked;
}

void btGeneric6DofConstraint::getInfo2(btConstraintInfo2* info)
{
	getInfo2NonVirtual(info, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(),
	                   m_rbA.getLinearVelocity(), m_rbB.getLinearVelocity(), m_rbA.getAngularVelocity(),
	                   m_rbB.getAngularVelocity());
}

void btGeneric6DofConstraint::getInfo2NonVirtual(btConstraintInfo2* info, const btTransform& transA,
                                                 const btTransform& transB, const btVector3& linVelA,
                                                 const btVector3& linVelB, const btVector3& angVelA,
                                                 const btVector3& angVelB)
{
	calculateTransforms(transA, transB);
	if (info->fps > btScalar(0)) m_timeStep = btScalar(1) / info->fps;
	const int rows = caliber::writeSixDofLimitMotorRows(*this, info, linVelA, linVelB, angVelA, angVelB);
	btAssert(rows == caliber::sixDofLimitMotorRowCount(*this));
	(void)rows;
}

void btGeneric6DofConstraint::setParam(int num, btScalar value, int axis)
{
	if (!indexInRange(axis, 6, "Caliber: btGeneric6DofConstraint::setParam: axis outside 0..5; ignored\n")) return;
	const int shift = axis * BT_6DOF_FLAGS_AXIS_SHIFT;
	btRotationalLimitMotor* angular = axis >= 3 ? &m_angularLimits[axis - 3] : 0;
	switch (num)
	{
		case BT_CONSTRAINT_ERP:
		case BT_CONSTRAINT_STOP_ERP:
			if (angular)
				angular->m_stopERP = value;
			else
				m_linearLimits.m_stopERP[axis] = value;
			m_flags |= BT_6DOF_FLAGS_ERP_STOP << shift;
			break;
		case BT_CONSTRAINT_STOP_CFM:
			if (angular)
				angular->m_stopCFM = value;
			else
				m_linearLimits.m_stopCFM[axis] = value;
			m_flags |= BT_6DOF_FLAGS_CFM_STOP << shift;
			break;
		case BT_CONSTRAINT_CFM:
			if (angular)
				angular->m_normalCFM = value;
			else
				m_linearLimits.m_normalCFM[axis] = value;
			m_flags |= BT_6DOF_FLAGS_CFM_NORM << shift;
			break;
		default:
			btAssertConstrParams(0);
	}
}

btScalar btGeneric6DofConstraint::getParam(int num, int axis) const
{
	if (!indexInRange(axis, 6, "Caliber: btGeneric6DofConstraint::getParam: axis outside 0..5; infinity\n"))
		return SIMD_INFINITY;
	const int shift = axis * BT_6DOF_FLAGS_AXIS_SHIFT;
	const btRotationalLimitMotor* angular = axis >= 3 ? &m_angularLimits[axis - 3] : 0;
	switch (num)
	{
		case BT_CONSTRAINT_ERP:
		case BT_CONSTRAINT_STOP_ERP:
			btAssertConstrParams(m_flags & (BT_6DOF_FLAGS_ERP_STOP << shift));
			return angular ? angular->m_stopERP : m_linearLimits.m_stopERP[axis];
		case BT_CONSTRAINT_STOP_CFM:
			btAssertConstrParams(m_flags & (BT_6DOF_FLAGS_CFM_STOP << shift));
			return angular ? angular->m_stopCFM : m_linearLimits.m_stopCFM[axis];
		case BT_CONSTRAINT_CFM:
			btAssertConstrParams(m_flags & (BT_6DOF_FLAGS_CFM_NORM << shift));
			return angular ? angular->m_normalCFM : m_linearLimits.m_normalCFM[axis];
		default:
			btAssertConstrParams(0);
			return SIMD_INFINITY;
	}
}

void btGeneric6DofConstraint::setAxis(const btVector3& axis1, const btVector3& axis2)
{
	const btScalar length1 = axis1.length(), length2 = axis2.length();
	const bool usable = caliber::isFinite(axis1) && caliber::isFinite(axis2) && length1 > SIMD_EPSILON &&
	                    length2 > SIMD_EPSILON && (axis1 / length1).cross(axis2 / length2).length() > btScalar(1e-3);
	btAssert(usable && "btGeneric6DofConstraint::setAxis: the axes must be finite, non-zero and not parallel");
	if (!usable)
	{
		btReportWarning(
		    "Caliber: btGeneric6DofConstraint::setAxis: zero, parallel or non-finite axes; the frames are kept\n", 0);
		return;
	}
	const btVector3 zAxis = axis1 / length1;
	const btVector3 yAxis = (axis2 - zAxis * zAxis.dot(axis2)).normalized();
	const btVector3 xAxis = yAxis.cross(zAxis);
	const btMatrix3x3 world(xAxis.x(), yAxis.x(), zAxis.x(), xAxis.y(), yAxis.y(), zAxis.y(), xAxis.z(), yAxis.z(),
	                        zAxis.z());
	m_frameInA.setBasis(m_rbA.getCenterOfMassTransform().getBasis().transposeTimes(world));
	m_frameInB.setBasis(m_rbB.getCenterOfMassTransform().getBasis().transposeTimes(world));
	calculateTransforms();
}

int btGeneric6DofConstraint::get_limit_motor_info2(btRotationalLimitMotor* limot, const btTransform& transA,
                                                   const btTransform& transB, const btVector3& linVelA,
                                                   const btVector3& linVelB, const btVector3& angVelA,
                                                   const btVector3& angVelB, btConstraintInfo2* info, int row,
                                                   btVector3& ax1, int rotational, int rotAllowed)
{
	if (!limot || !info || !(limot->m_enableMotor || limot->m_currentLimit != 0)) return 0;
	const int at = row * info->rowskip;
	btScalar* J1linear = info->m_J1linearAxis + at;
	btScalar* J1angular = info->m_J1angularAxis + at;
	btScalar* J2linear = info->m_J2linearAxis ? info->m_J2linearAxis + at : 0;
	btScalar* J2angular = info->m_J2angularAxis + at;
	btVector3 angularA(0, 0, 0), angularB(0, 0, 0), linear(0, 0, 0);
	if (rotational)
	{
		angularA = ax1;
		angularB = -ax1;
	}
	else
	{
		linear = ax1;
		if (rotAllowed)
		{
			// Acting at the anchor: each body turns about its centre of mass.
			angularA = (m_AnchorPos - transA.getOrigin()).cross(ax1);
			angularB = -(m_AnchorPos - transB.getOrigin()).cross(ax1);
		}
	}
	for (int k = 0; k < 3; ++k)
	{
		J1linear[k] = linear[k];
		J1angular[k] = angularA[k];
		if (J2linear) J2linear[k] = -linear[k];
		J2angular[k] = angularB[k];
	}
	(void)linVelA;
	(void)linVelB;
	(void)angVelA;
	(void)angVelB;

	const btScalar fps = info->fps;
	const bool locked = limot->m_currentLimit != 0 && limot->m_loLimit == limot->m_hiLimit;
	if (limot->m_currentLimit != 0)
	{
		// J v = -(rate of the coordinate): a target of k * error moves the coordinate back by k * error per
		// second. Below the lower limit (error < 0) only a negative impulse may act, above only a positive.
		info->m_constraintError[at] = fps * limot->m_stopERP * limot->m_currentLimitError;
		info->cfm[at] = limot->m_stopCFM;
		if (locked || limot->m_currentLimit == 3)
		{
			info->m_lowerLimit[at] = -SIMD_INFINITY;
			info->m_upperLimit[at] = SIMD_INFINITY;
		}
		else if (limot->m_currentLimit == 1)
		{
			info->m_lowerLimit[at] = -SIMD_INFINITY;
			info->m_upperLimit[at] = 0;
		}
		else
		{
			info->m_lowerLimit[at] = 0;
			info->m_upperLimit[at] = SIMD_INFINITY;
		}
		return 1;
	}
	// A free motor: the coordinate's rate towards the target, within the force the motor has for a step.
	info->m_constraintError[at] = -limot->m_targetVelocity;
	info->cfm[at] = limot->m_normalCFM;
	const btScalar maxImpulse = fps > btScalar(0) ? limot->m_maxMotorForce / fps : btScalar(0);
	info->m_lowerLimit[at] = -maxImpulse;
	info->m_upperLimit[at] = maxImpulse;
	return 1;
}

int btGeneric6DofConstraint::setAngularLimits(btConstraintInfo2* info, int row_offset, const btTransform& transA,
                                              const btTransform& transB, const btVector3& linVelA,
                                              const btVector3& linVelB, const btVector3& angVelA,
                                              const btVector3& angVelB)
{
	int row = row_offset;
	for (int i = 0; i < 3; ++i)
	{
		if (!testAngularLimitMotor(i)) continue;
		btVector3 axis = getAxis(i);
		row += get_limit_motor_info2(&m_angularLimits[i], transA, transB, linVelA, linVelB, angVelA, angVelB, info,
		                             row, axis, 1);
	}
	return row;
}

int btGeneric6DofConstraint::setLinearLimits(btConstraintInfo2* info, int row, const btTransform& transA,
                                             const btTransform& transB, const btVector3& linVelA,
                                             const btVector3& linVelB, const btVector3& angVelA,
                                             const btVector3& angVelB)
{
	const btTransform& frame = m_useLinearReferenceFrameA ? m_calculatedTransformA : m_calculatedTransformB;
	for (int i = 0; i < 3; ++i)
	{
		m_linearLimits.testLimitValue(i, m_calculatedLinearDiff[i]);
		if (!m_linearLimits.needApplyForce(i)) continue;
		// The axis's settings as a one-axis limit motor.
		btRotationalLimitMotor motor;
		motor.m_loLimit = m_linearLimits.m_lowerLimit[i];
		motor.m_hiLimit = m_linearLimits.m_upperLimit[i];
		motor.m_targetVelocity = m_linearLimits.m_targetVelocity[i];
		motor.m_maxMotorForce = m_linearLimits.m_maxMotorForce[i];
		motor.m_enableMotor = m_linearLimits.m_enableMotor[i];
		motor.m_normalCFM = m_linearLimits.m_normalCFM[i];
		motor.m_stopERP = m_linearLimits.m_stopERP[i];
		motor.m_stopCFM = m_linearLimits.m_stopCFM[i];
		motor.m_currentLimit = m_linearLimits.m_currentLimit[i];
		motor.m_currentLimitError = m_linearLimits.m_currentLimitError[i];
		motor.m_currentPosition = m_calculatedLinearDiff[i];
		btVector3 axis = frame.getBasis().getColumn(i);
		row += get_limit_motor_info2(&motor, transA, transB, linVelA, linVelB, angVelA, angVelB, info, row, axis, 0,
		                             1);
	}
	return row;
}

void btGeneric6DofConstraint::buildLinearJacobian(btJacobianEntry& jacLinear, const btVector3& normalWorld,
                                                  const btVector3& pivotAInW, const btVector3& pivotBInW)
{
	jacLinear = btJacobianEntry(m_rbA.getCenterOfMassTransform().getBasis().transpose(),
	                            m_rbB.getCenterOfMassTransform().getBasis().transpose(),
	                            pivotAInW - m_rbA.getCenterOfMassPosition(), pivotBInW - m_rbB.getCenterOfMassPosition(),
	                            normalWorld, m_rbA.getInvInertiaDiagLocal(), m_rbA.getInvMass(),
	                            m_rbB.getInvInertiaDiagLocal(), m_rbB.getInvMass());
}

void btGeneric6DofConstraint::buildAngularJacobian(btJacobianEntry& jacAngular, const btVector3& jointAxisW)
{
	jacAngular = btJacobianEntry(jointAxisW, m_rbA.getCenterOfMassTransform().getBasis().transpose(),
	                             m_rbB.getCenterOfMassTransform().getBasis().transpose(),
	                             m_rbA.getInvInertiaDiagLocal(), m_rbB.getInvInertiaDiagLocal());
}
