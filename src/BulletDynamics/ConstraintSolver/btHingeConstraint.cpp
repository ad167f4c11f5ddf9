// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btHingeConstraint.h"

#include "BulletDynamics/ConstraintSolver/btJointLimitRow.h"
#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btWarningHook.h"

namespace
{
bool usableAxis(const btVector3& axis)
{
	const btScalar length2 = axis.length2();
	return length2 == length2 && length2 > SIMD_EPSILON && length2 < SIMD_INFINITY;
}

// A right-handed basis whose Z axis is the unit vector z.
btMatrix3x3 basisWithZ(const btVector3& z, const btVector3& x)
{
	const btVector3 y = z.cross(x);
	return btMatrix3x3(x.x(), y.x(), z.x(), x.y(), y.y(), z.y(), x.z(), y.z(), z.z());
}

// Reports a zero-length or non-finite axis and makes the joint inert.
void rejectAxis(btHingeConstraint& joint)
{
	btAssert(!"btHingeConstraint: zero-length or non-finite hinge axis");
	btReportWarning("Caliber: btHingeConstraint: zero-length or non-finite hinge axis; the joint is disabled\n", 0);
	joint.setFrames(btTransform::getIdentity(), btTransform::getIdentity());
	joint.setEnabled(false);
}

// Builds both frames from pivots and axes given in each body's frame (see the constructors).
void setFramesFromPivotsAndAxes(btHingeConstraint& joint, const btVector3& pivotInA, const btVector3& pivotInB,
                                const btVector3& axisInA, const btVector3& axisInB)
{
	if (!usableAxis(axisInA) || !usableAxis(axisInB))
	{
		rejectAxis(joint);
		return;
	}
	const btVector3 zA = axisInA.normalized();
	const btVector3 zB = axisInB.normalized();
	btVector3 xA, unused;
	btPlaneSpace1(zA, xA, unused);
	// B's X axis is A's carried along by the shortest turn from A's axis to B's, so the hinge angle of the
	// joint as built is zero.
	const btVector3 xB = quatRotate(shortestArcQuat(zA, zB), xA);
	joint.setFrames(btTransform(basisWithZ(zA, xA), pivotInA), btTransform(basisWithZ(zB, xB), pivotInB));
}
}  // namespace

btHingeConstraint::btHingeConstraint(btRigidBody& rbA, btRigidBody& rbB, const btVector3& pivotInA,
                                     const btVector3& pivotInB, const btVector3& axisInA, const btVector3& axisInB,
                                     bool useReferenceFrameA)
    : btTypedConstraint(HINGE_CONSTRAINT_TYPE, rbA, rbB)
{
	setUseReferenceFrameA(useReferenceFrameA);
	setFramesFromPivotsAndAxes(*this, pivotInA, pivotInB, axisInA, axisInB);
}

btHingeConstraint::btHingeConstraint(btRigidBody& rbA, const btVector3& pivotInA, const btVector3& axisInA,
                                     bool useReferenceFrameA)
    : btTypedConstraint(HINGE_CONSTRAINT_TYPE, rbA)
{
	setUseReferenceFrameA(useReferenceFrameA);
	// The world (the fixed body, at the identity) holds the pivot and axis where they are now.
	const btTransform& a = rbA.getCenterOfMassTransform();
	setFramesFromPivotsAndAxes(*this, pivotInA, a(pivotInA), axisInA, a.getBasis() * axisInA);
}

btHingeConstraint::btHingeConstraint(btRigidBody& rbA, btRigidBody& rbB, const btTransform& rbAFrame,
                                     const btTransform& rbBFrame, bool useReferenceFrameA)
    : btTypedConstraint(HINGE_CONSTRAINT_TYPE, rbA, rbB), m_rbAFrame(rbAFrame), m_rbBFrame(rbBFrame)
{
	setUseReferenceFrameA(useReferenceFrameA);
	if (!usableAxis(rbAFrame.getBasis().getColumn(2)) || !usableAxis(rbBFrame.getBasis().getColumn(2)))
		rejectAxis(*this);
}

btHingeConstraint::btHingeConstraint(btRigidBody& rbA, const btTransform& rbAFrame, bool useReferenceFrameA)
    : btTypedConstraint(HINGE_CONSTRAINT_TYPE, rbA),
      m_rbAFrame(rbAFrame),
      m_rbBFrame(rbA.getCenterOfMassTransform() * rbAFrame)
{
	setUseReferenceFrameA(useReferenceFrameA);
	if (!usableAxis(rbAFrame.getBasis().getColumn(2))) rejectAxis(*this);
}

void btHingeConstraint::setFrames(const btTransform& frameA, const btTransform& frameB)
{
	m_rbAFrame = frameA;
	m_rbBFrame = frameB;
}

void btHingeConstraint::setAxis(btVector3& axisInA)
{
	if (!usableAxis(axisInA))
	{
		rejectAxis(*this);
		return;
	}
	const btVector3 zA = axisInA.normalized();
	btVector3 xA, unused;
	btPlaneSpace1(zA, xA, unused);
	m_rbAFrame.setBasis(basisWithZ(zA, xA));
	// B's frame is A's frame as it stands now, seen from B.
	const btTransform aToB = m_rbB.getCenterOfMassTransform().inverse() * m_rbA.getCenterOfMassTransform();
	m_rbBFrame = aToB * m_rbAFrame;
}

void btHingeConstraint::enableAngularMotor(bool enableMotor, btScalar targetVelocity, btScalar maxMotorImpulse)
{
	m_enableAngularMotor = enableMotor;
	m_motorTargetVelocity = targetVelocity;
	m_maxMotorImpulse = maxMotorImpulse;
}

void btHingeConstraint::setMotorTarget(const btQuaternion& qAinB, btScalar dt)
{
	// A's joint frame seen in B's joint frame; its turn about their common Z axis is the hinge angle.
	const btQuaternion qFrameAinFrameB = m_rbBFrame.getRotation().inverse() * qAinB * m_rbAFrame.getRotation();
	const btScalar angle = btNormalizeAngle(btScalar(2) * btAtan2(qFrameAinFrameB.z(), qFrameAinFrameB.w()));
	setMotorTarget(m_referenceSign * angle, dt);
}

void btHingeConstraint::setMotorTarget(btScalar targetAngle, btScalar dt)
{
	btAssert(dt > btScalar(0));
	if (!(dt > btScalar(0))) return;
	m_limit.fit(targetAngle);
	m_motorTargetVelocity = (targetAngle - getHingeAngle()) / dt;
}

btScalar btHingeConstraint::getHingeAngle()
{
	return getHingeAngle(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
}

btScalar btHingeConstraint::getHingeAngle(const btTransform& transA, const btTransform& transB)
{
	const btMatrix3x3 frameA = transA.getBasis() * m_rbAFrame.getBasis();
	const btVector3 bX = transB.getBasis() * m_rbBFrame.getBasis().getColumn(0);
	// The turn of B's X axis about A's Z axis, measured in A's frame, is B's angle relative to A.
	const btScalar angleOfBinA = btAtan2(bX.dot(frameA.getColumn(1)), bX.dot(frameA.getColumn(0)));
	return -m_referenceSign * angleOfBinA;
}

void btHingeConstraint::testLimit(const btTransform& transA, const btTransform& transB)
{
	m_hingeAngle = getHingeAngle(transA, transB);
	m_limit.test(m_hingeAngle);
}

void btHingeConstraint::getInfo1(btConstraintInfo1* info) { getInfo1NonVirtual(info); }

void btHingeConstraint::getInfo1NonVirtual(btConstraintInfo1* info)
{
	info->m_numConstraintRows = m_angularOnly ? 2 : 5;
	info->nub = info->m_numConstraintRows;
	testLimit(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
	m_limitRowNeeded = false;
	// A limit with a zero range (setLimit(a, a)) locks the hinge: hasLimit() says no, as in Bullet, but
	// the limit is there.
	const bool limitSet = m_limit.getHalfRange() >= btScalar(0);
	if (limitSet)
	{
		// A limit row only when past the limit or within two steps' travel of it (plus a milliradian):
		// far from its limits a hinge needs none, and rows cost solver time.
		const btVector3 axis = (m_rbA.getCenterOfMassTransform().getBasis() * m_rbAFrame.getBasis()).getColumn(2);
		const btScalar rate = (m_rbA.getAngularVelocity() - m_rbB.getAngularVelocity()).dot(axis) * m_referenceSign;
		const btScalar deviation = btNormalizeAngle(m_hingeAngle - m_limit.getCenter());
		const btScalar room = rate >= 0 ? m_limit.getHalfRange() - deviation : deviation + m_limit.getHalfRange();
		m_limitRowNeeded = m_limit.isLimit() || room <= btFabs(rate) * 2 * m_lastTimeStep + btScalar(1e-3);
	}
	if (m_limitRowNeeded) ++info->m_numConstraintRows;
	if (m_enableAngularMotor) ++info->m_numConstraintRows;
}

void btHingeConstraint::getInfo2(btConstraintInfo2* info)
{
	getInfo2Internal(info, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(),
	                 m_rbA.getAngularVelocity(), m_rbB.getAngularVelocity());
}

void btHingeConstraint::getInfo2NonVirtual(btConstraintInfo2* info, const btTransform& transA,
                                           const btTransform& transB, const btVector3& angVelA,
                                           const btVector3& angVelB)
{
	testLimit(transA, transB);
	getInfo2Internal(info, transA, transB, angVelA, angVelB);
}

void btHingeConstraint::getInfo2InternalUsingFrameOffset(btConstraintInfo2* info, const btTransform& transA,
                                                         const btTransform& transB, const btVector3& angVelA,
                                                         const btVector3& angVelB)
{
	getInfo2Internal(info, transA, transB, angVelA, angVelB);
}

void btHingeConstraint::getInfo2Internal(btConstraintInfo2* info, const btTransform& transA, const btTransform& transB,
                                         const btVector3& angVelA, const btVector3& angVelB)
{
	const btScalar erp = (m_flags & BT_HINGE_FLAGS_ERP_NORM) ? m_normalERP : info->erp;
	const btScalar rate = info->fps * erp;
	const btTransform frameA = transA * m_rbAFrame;
	const btTransform frameB = transB * m_rbBFrame;
	int row = 0;

	if (!m_angularOnly)
	{
		const btVector3 armA = frameA.getOrigin() - transA.getOrigin();
		const btVector3 armB = frameB.getOrigin() - transB.getOrigin();
		const btVector3 gap = frameB.getOrigin() - frameA.getOrigin();
		const btVector3 targets = caliber::linearRowTargets(*info, erp, gap, armA, angVelA, armB, angVelB);
		for (int axis = 0; axis < 3; ++axis, ++row)
		{
			btVector3 direction(0, 0, 0);
			direction[axis] = btScalar(1);
			caliber::JointRow r(*info, row);
			r.setLinear(direction, armA, armB);
			r.error() = targets[axis];
			if (m_flags & BT_HINGE_FLAGS_CFM_NORM) r.cfm() = m_normalCFM;
		}
	}

	// Keep the axes aligned: turning A about (axisA x axisB) brings its axis onto B's.
	const btVector3 axisA = frameA.getBasis().getColumn(2);
	const btVector3 axisB = frameB.getBasis().getColumn(2);
	const btVector3 misalignment = axisA.cross(axisB);
	for (int k = 0; k < 2; ++k, ++row)
	{
		const btVector3 perpendicular = frameA.getBasis().getColumn(k);
		caliber::JointRow r(*info, row);
		r.setAngular(perpendicular);
		r.error() = rate * misalignment.dot(perpendicular);
		if (m_flags & BT_HINGE_FLAGS_CFM_NORM) r.cfm() = m_normalCFM;
	}

	// Rows about the hinge axis, oriented so that J v is the hinge angle's rate.
	const btVector3 angleAxis = axisA * m_referenceSign;
	// The position pass asks for position errors only: no velocity terms there.
	const btScalar angleRate = caliber::inJointPositionPass() ? btScalar(0) : (angVelA - angVelB).dot(angleAxis);
	if (!caliber::inJointPositionPass() && info->fps > btScalar(0)) m_lastTimeStep = btScalar(1) / info->fps;
	if (m_limitRowNeeded)
	{
		// The limit row is there while the hinge is past or near a limit. Past the limit it pushes back (bias) and
		// stops the velocity into it (relaxation); inside, it is speculative: it allows at most the
		// approach speed that reaches the limit at the end of the step, so a fast swing stops at the
		// limit instead of overshooting it by one step's travel.
		caliber::JointRow r(*info, row++);
		if (m_limit.isLimit())
		{
			const btScalar sign = m_limit.getSign();
			r.setAngular(angleAxis * sign);
			const btScalar stopErp = (m_flags & BT_HINGE_FLAGS_ERP_STOP) ? m_stopERP : m_limit.getBiasFactor();
			caliber::setLimitRow(r, info->fps * stopErp * btFabs(m_limit.getCorrection()), sign * angleRate,
			                     m_limit.getRelaxationFactor());
		}
		else
		{
			const btScalar deviation = btNormalizeAngle(m_hingeAngle - m_limit.getCenter());
			// Guard the limit the hinge is heading for (the nearer one in the position pass).
			const bool towardsHigh = caliber::inJointPositionPass() ? deviation >= 0 : angleRate >= 0;
			const btScalar sign = towardsHigh ? btScalar(-1) : btScalar(1);
			const btScalar room = sign < 0 ? m_limit.getHalfRange() - deviation : deviation + m_limit.getHalfRange();
			r.setAngular(angleAxis * sign);
			r.error() = -btMax(btScalar(0), room) * info->fps;
			r.lower() = btScalar(0);
			r.upper() = SIMD_INFINITY;
		}
		if (m_flags & BT_HINGE_FLAGS_CFM_STOP) r.cfm() = m_stopCFM;
	}
	if (m_enableAngularMotor)
	{
		caliber::JointRow r(*info, row++);
		r.setAngular(angleAxis);
		const bool limitSet = m_limit.getHalfRange() >= btScalar(0);
		const btScalar low = limitSet ? getLowerLimit() : btScalar(1);
		const btScalar high = limitSet ? getUpperLimit() : btScalar(-1);
		const btScalar factor = getMotorFactor(m_hingeAngle, low, high, m_motorTargetVelocity, info->fps);
		r.error() = factor * m_motorTargetVelocity;
		r.lower() = -m_maxMotorImpulse;
		r.upper() = m_maxMotorImpulse;
	}
}

void btHingeConstraint::setParam(int num, btScalar value, int axis)
{
	const bool anyAxis = axis == -1 || (axis >= 0 && axis <= 5);
	btAssertConstrParams(anyAxis);
	if (!anyAxis) return;
	const bool limitAxis = axis == -1 || axis == 5;
	switch (num)
	{
		case BT_CONSTRAINT_STOP_ERP:
			if (!limitAxis) break;
			m_stopERP = value;
			m_flags |= BT_HINGE_FLAGS_ERP_STOP;
			break;
		case BT_CONSTRAINT_STOP_CFM:
			if (!limitAxis) break;
			m_stopCFM = value;
			m_flags |= BT_HINGE_FLAGS_CFM_STOP;
			break;
		case BT_CONSTRAINT_CFM:
			m_normalCFM = value;
			m_flags |= BT_HINGE_FLAGS_CFM_NORM;
			break;
		case BT_CONSTRAINT_ERP:
			m_normalERP = value;
			m_flags |= BT_HINGE_FLAGS_ERP_NORM;
			break;
		default:
			btAssertConstrParams(0);
	}
}

btScalar btHingeConstraint::getParam(int num, int axis) const
{
	btAssertConstrParams(axis == -1 || (axis >= 0 && axis <= 5));
	switch (num)
	{
		case BT_CONSTRAINT_STOP_ERP:
			return m_stopERP;
		case BT_CONSTRAINT_STOP_CFM:
			return m_stopCFM;
		case BT_CONSTRAINT_CFM:
			return m_normalCFM;
		case BT_CONSTRAINT_ERP:
			return m_normalERP;
		default:
			btAssertConstrParams(0);
			return SIMD_INFINITY;
	}
}

btScalar btHingeAccumulatedAngleConstraint::getAccumulatedHingeAngle()
{
	// The shortest turn from the last known angle to the measured one, added on: counts whole turns.
	const btScalar measured = getHingeAngle();
	m_accumulatedAngle += btNormalizeAngle(measured - btNormalizeAngle(m_accumulatedAngle));
	return m_accumulatedAngle;
}

void btHingeAccumulatedAngleConstraint::setAccumulatedHingeAngle(btScalar accAngle) { m_accumulatedAngle = accAngle; }

void btHingeAccumulatedAngleConstraint::getInfo1(btConstraintInfo1* info)
{
	getAccumulatedHingeAngle();
	btHingeConstraint::getInfo1(info);
}
