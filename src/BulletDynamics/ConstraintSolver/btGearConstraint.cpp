// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"

#include "LinearMath/btWarningHook.h"

namespace
{
// An axis needs a direction: finite and not (close to) zero. 1e-6 is far below any axis a user means
// and far above the rounding of a computed unit vector.
bool isUsableAxis(const btVector3& axis) { return caliber::isFinite(axis) && axis.length() > btScalar(1e-6); }

void writeVector(btScalar* row, const btVector3& v)
{
	row[0] = v.x();
	row[1] = v.y();
	row[2] = v.z();
}
}  // namespace

btGearConstraint::btGearConstraint(btRigidBody& rbA, btRigidBody& rbB, const btVector3& axisInA,
                                   const btVector3& axisInB, btScalar ratio)
    : btTypedConstraint(GEAR_CONSTRAINT_TYPE, rbA, rbB),
      m_axisInA(axisInA),
      m_axisInB(axisInB),
      m_useFrameA(false),
      m_ratio(ratio),
      m_cfm(btScalar(0)),
      m_hasCfm(false)
{
	checkInput(true);
}

bool btGearConstraint::checkInput(bool assertOnFailure)
{
	if (isUsableAxis(m_axisInA) && isUsableAxis(m_axisInB) && btIsFinite(m_ratio)) return true;
	btAssert(!assertOnFailure && "btGearConstraint: an axis is zero-length or not finite, or the ratio is not finite");
	(void)assertOnFailure;
	btReportWarning(
	    "Caliber: btGearConstraint: an axis is zero-length or not finite, or the ratio is not finite; it is "
	    "disabled\n",
	    0);
	setEnabled(false);
	return false;
}

void btGearConstraint::setAxisA(const btVector3& axisA)
{
	m_axisInA = axisA;
	checkInput(true);
}

void btGearConstraint::setAxisB(const btVector3& axisB)
{
	m_axisInB = axisB;
	checkInput(true);
}

void btGearConstraint::setRatio(btScalar ratio)
{
	m_ratio = ratio;
	checkInput(true);
}

void btGearConstraint::getInfo1(btConstraintInfo1* info)
{
	// Checked again because a joint disabled for bad input may have been enabled again by hand.
	const bool usable = checkInput(false);
	info->m_numConstraintRows = usable ? 1 : 0;
	info->nub = usable ? 1 : 0;
}

void btGearConstraint::getInfo2(btConstraintInfo2* info)
{
	// d/dt of (angle of A about axisA + ratio * angle of B about axisB) is wA . axisA + ratio wB . axisB:
	// the row's Jacobian is axisA for A's angular velocity and ratio * axisB for B's, target 0.
	const btVector3 axisA = m_rbA.getCenterOfMassTransform().getBasis() * m_axisInA;
	const btVector3 axisB = m_rbB.getCenterOfMassTransform().getBasis() * m_axisInB;
	writeVector(info->m_J1angularAxis, axisA);
	writeVector(info->m_J2angularAxis, axisB * m_ratio);
	info->m_constraintError[0] = btScalar(0);
	if (m_hasCfm) info->cfm[0] = m_cfm;
}

void btGearConstraint::setParam(int num, btScalar value, int axis)
{
	const bool known = (num == BT_CONSTRAINT_CFM || num == BT_CONSTRAINT_STOP_CFM) && (axis == -1 || axis == 0);
	btAssertConstrParams(known);
	if (!known) return;
	m_cfm = value;
	m_hasCfm = true;
}

btScalar btGearConstraint::getParam(int num, int axis) const
{
	const bool known = (num == BT_CONSTRAINT_CFM || num == BT_CONSTRAINT_STOP_CFM) && (axis == -1 || axis == 0);
	btAssertConstrParams(known);
	if (!known) return SIMD_INFINITY;
	btAssertConstrParams(m_hasCfm);
	return m_cfm;
}
