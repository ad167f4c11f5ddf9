// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h"

#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"

btPoint2PointConstraint::btPoint2PointConstraint(btRigidBody& rbA, btRigidBody& rbB, const btVector3& pivotInA,
                                                 const btVector3& pivotInB)
    : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, rbA, rbB),
      m_pivotInA(pivotInA),
      m_pivotInB(pivotInB),
      m_flags(0),
      m_erp(btScalar(0)),
      m_cfm(btScalar(0)),
      m_useSolveConstraintObsolete(false)
{
}

btPoint2PointConstraint::btPoint2PointConstraint(btRigidBody& rbA, const btVector3& pivotInA)
    : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, rbA),
      m_pivotInA(pivotInA),
      m_pivotInB(rbA.getCenterOfMassTransform()(pivotInA)),
      m_flags(0),
      m_erp(btScalar(0)),
      m_cfm(btScalar(0)),
      m_useSolveConstraintObsolete(false)
{
}

void btPoint2PointConstraint::getInfo1(btConstraintInfo1* info) { getInfo1NonVirtual(info); }

void btPoint2PointConstraint::getInfo1NonVirtual(btConstraintInfo1* info)
{
	info->m_numConstraintRows = 3;
	info->nub = 3;
}

void btPoint2PointConstraint::getInfo2(btConstraintInfo2* info)
{
	getInfo2NonVirtual(info, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
}

void btPoint2PointConstraint::getInfo2NonVirtual(btConstraintInfo2* info, const btTransform& body0_trans,
                                                 const btTransform& body1_trans)
{
	const btVector3 armA = body0_trans.getBasis() * m_pivotInA;
	const btVector3 armB = body1_trans.getBasis() * m_pivotInB;
	const btVector3 gap = (body1_trans.getOrigin() + armB) - (body0_trans.getOrigin() + armA);
	const btScalar erp = (m_flags & BT_P2P_FLAGS_ERP) ? m_erp : info->erp;
	const btScalar clamp = m_setting.m_impulseClamp;
	const btVector3 targets =
	    caliber::linearRowTargets(*info, erp, gap, armA, m_rbA.getAngularVelocity(), armB, m_rbB.getAngularVelocity());
	for (int axis = 0; axis < 3; ++axis)
	{
		btVector3 direction(0, 0, 0);
		direction[axis] = btScalar(1);
		caliber::JointRow row(*info, axis);
		row.setLinear(direction, armA, armB);
		row.error() = targets[axis];
		if (m_flags & BT_P2P_FLAGS_CFM) row.cfm() = m_cfm;
		if (clamp > btScalar(0))
		{
			row.lower() = -clamp;
			row.upper() = clamp;
		}
	}
}

void btPoint2PointConstraint::setParam(int num, btScalar value, int axis)
{
	btAssertConstrParams(axis >= -1 && axis < 3);
	if (axis < -1 || axis >= 3) return;
	switch (num)
	{
		case BT_CONSTRAINT_ERP:
		case BT_CONSTRAINT_STOP_ERP:
			m_erp = value;
			m_flags |= BT_P2P_FLAGS_ERP;
			break;
		case BT_CONSTRAINT_CFM:
		case BT_CONSTRAINT_STOP_CFM:
			m_cfm = value;
			m_flags |= BT_P2P_FLAGS_CFM;
			break;
		default:
			btAssertConstrParams(0);
	}
}

btScalar btPoint2PointConstraint::getParam(int num, int axis) const
{
	btAssertConstrParams(axis >= -1 && axis < 3);
	switch (num)
	{
		case BT_CONSTRAINT_ERP:
		case BT_CONSTRAINT_STOP_ERP:
			btAssertConstrParams(m_flags & BT_P2P_FLAGS_ERP);
			return m_erp;
		case BT_CONSTRAINT_CFM:
		case BT_CONSTRAINT_STOP_CFM:
			btAssertConstrParams(m_flags & BT_P2P_FLAGS_CFM);
			return m_cfm;
		default:
			btAssertConstrParams(0);
			return SIMD_INFINITY;
	}
}
