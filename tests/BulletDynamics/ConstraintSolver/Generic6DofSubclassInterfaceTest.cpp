// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet's protected and public row helpers of btGeneric6DofConstraint, as a subclass written for Bullet
// uses them: get_limit_motor_info2's rows (Jacobian, target and bounds for a motor, each limit side and
// nothing when neither), setAngularLimits / setLinearLimits counting the rows they write, the mass
// shares m_factA / m_factB, and buildLinearJacobian's effective mass.

#include <gtest/gtest.h>

#include "btBulletDynamicsCommon.h"

namespace
{
class Exposed6Dof : public btGeneric6DofConstraint
{
public:
	using btGeneric6DofConstraint::btGeneric6DofConstraint;
	int angularRows(btConstraintInfo2* info)
	{
		calculateTransforms();
		return setAngularLimits(info, 0, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(),
		                        m_rbA.getLinearVelocity(), m_rbB.getLinearVelocity(), m_rbA.getAngularVelocity(),
		                        m_rbB.getAngularVelocity());
	}
	int linearRows(btConstraintInfo2* info)
	{
		calculateTransforms();
		return setLinearLimits(info, 0, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(),
		                       m_rbA.getLinearVelocity(), m_rbB.getLinearVelocity(), m_rbA.getAngularVelocity(),
		                       m_rbB.getAngularVelocity());
	}
	btScalar factA() const { return m_factA; }
	btScalar factB() const { return m_factB; }
	bool hasStaticBody() const { return m_hasStaticBody; }
	btScalar linearDiagonal(const btVector3& axis)
	{
		buildLinearJacobian(m_jacLinear[0], axis, m_rbA.getCenterOfMassPosition(), m_rbB.getCenterOfMassPosition());
		return m_jacLinear[0].getDiagonal();
	}
};

// Storage for 6 rows of btConstraintInfo2 (rowskip 8, as the solver uses: every per-row array is indexed by
// row * rowskip).
struct Rows
{
	btScalar J1l[48] = {}, J1a[48] = {}, J2l[48] = {}, J2a[48] = {}, error[48] = {}, cfm[48] = {}, lo[48] = {}, hi[48] = {};
	btTypedConstraint::btConstraintInfo2 info;
	Rows()
	{
		info.fps = 60;
		info.erp = btScalar(0.2);
		info.m_J1linearAxis = J1l;
		info.m_J1angularAxis = J1a;
		info.m_J2linearAxis = J2l;
		info.m_J2angularAxis = J2a;
		info.rowskip = 8;
		info.m_constraintError = error;
		info.cfm = cfm;
		info.m_lowerLimit = lo;
		info.m_upperLimit = hi;
		info.m_numIterations = 10;
		info.m_damping = 1;
	}
};

struct Pair
{
	btBoxShape shape{btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))};
	btRigidBody a{1, 0, &shape, btVector3(btScalar(1) / 6, btScalar(1) / 6, btScalar(1) / 6)};
	btRigidBody b{3, 0, &shape, btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))};
};
}  // namespace

TEST(Generic6DofSubclassInterface, LimitMotorRowsHaveTheDocumentedJacobianTargetAndBounds)
{
	Pair p;
	Exposed6Dof joint(p.a, p.b, btTransform::getIdentity(), btTransform::getIdentity(), true);
	Rows rows;
	btRotationalLimitMotor motor;
	btVector3 axis(1, 0, 0);
	const btTransform& ta = p.a.getCenterOfMassTransform();
	const btTransform& tb = p.b.getCenterOfMassTransform();
	const btVector3 zero(0, 0, 0);
	// Neither at a limit nor powered: no row.
	EXPECT_EQ(joint.get_limit_motor_info2(&motor, ta, tb, zero, zero, zero, zero, &rows.info, 0, axis, 1), 0);
	// A motor: J = (ax, -ax) angular, target J v = -target rate, impulse within max force / fps.
	motor.m_enableMotor = true;
	motor.m_targetVelocity = 2;
	motor.m_maxMotorForce = 120;
	ASSERT_EQ(joint.get_limit_motor_info2(&motor, ta, tb, zero, zero, zero, zero, &rows.info, 0, axis, 1), 1);
	EXPECT_EQ(rows.J1a[0], 1);
	EXPECT_EQ(rows.J2a[0], -1);
	EXPECT_EQ(rows.J1l[0], 0);
	EXPECT_FLOAT_EQ(rows.error[0], -2);
	EXPECT_FLOAT_EQ(rows.lo[0], -2);
	EXPECT_FLOAT_EQ(rows.hi[0], 2);
	// Below the lower limit by 0.1: pushed back at stop ERP, with impulses of one sign only (row 1).
	motor.m_enableMotor = false;
	motor.m_currentLimit = 1;
	motor.m_currentLimitError = btScalar(-0.1);
	motor.m_stopERP = btScalar(0.5);
	ASSERT_EQ(joint.get_limit_motor_info2(&motor, ta, tb, zero, zero, zero, zero, &rows.info, 1, axis, 1), 1);
	EXPECT_FLOAT_EQ(rows.error[1 * 8], 60 * btScalar(0.5) * btScalar(-0.1));
	EXPECT_EQ(rows.hi[1 * 8], 0);
	EXPECT_LT(rows.lo[1 * 8], -1e10);
	// Above the upper limit: the other sign.
	motor.m_currentLimit = 2;
	motor.m_currentLimitError = btScalar(0.1);
	ASSERT_EQ(joint.get_limit_motor_info2(&motor, ta, tb, zero, zero, zero, zero, &rows.info, 2, axis, 1), 1);
	EXPECT_EQ(rows.lo[2 * 8], 0);
	EXPECT_GT(rows.hi[2 * 8], 1e10);
	// A linear row: J = (ax, -ax) linear, no angular part without rotAllowed.
	ASSERT_EQ(joint.get_limit_motor_info2(&motor, ta, tb, zero, zero, zero, zero, &rows.info, 3, axis, 0), 1);
	EXPECT_EQ(rows.J1l[3 * 8], 1);
	EXPECT_EQ(rows.J2l[3 * 8], -1);
	EXPECT_EQ(rows.J1a[3 * 8], 0);
}

TEST(Generic6DofSubclassInterface, TheRowsSignMatchesTheAngleItLimits)
{
	// The row's J v is ax . (wA - wB), the opposite of the angle's rate: turning B by +0.1 about the
	// first axis raises getAngle(0) by 0.1.
	Pair p;
	p.b.setCenterOfMassTransform(btTransform(btQuaternion(btVector3(1, 0, 0), btScalar(0.1))));
	Exposed6Dof joint(p.a, p.b, btTransform::getIdentity(), btTransform::getIdentity(), true);
	joint.calculateTransforms();
	EXPECT_NEAR(joint.getAngle(0), 0.1, 1e-5);
}

TEST(Generic6DofSubclassInterface, SetLimitsWriteOneRowPerAxisThatNeedsOne)
{
	Pair p;
	// B turned 0.3 about x and moved 0.2 along y.
	p.b.setCenterOfMassTransform(btTransform(btQuaternion(btVector3(1, 0, 0), btScalar(0.3)), btVector3(0, btScalar(0.2), 0)));
	Exposed6Dof joint(p.a, p.b, btTransform::getIdentity(), btTransform::getIdentity(), true);
	// Angular x limited to [-0.1, 0.1] (violated), y and z free; linear y limited to [0, 0.1] (violated).
	joint.setAngularLowerLimit(btVector3(btScalar(-0.1), 1, 1));
	joint.setAngularUpperLimit(btVector3(btScalar(0.1), -1, -1));
	joint.setLinearLowerLimit(btVector3(1, 0, 1));
	joint.setLinearUpperLimit(btVector3(-1, btScalar(0.1), -1));
	Rows rows;
	EXPECT_EQ(joint.angularRows(&rows.info), 1);
	// Above the upper limit by 0.2: a positive impulse only.
	EXPECT_NEAR(rows.error[0], 60 * joint.getRotationalLimitMotor(0)->m_stopERP * btScalar(0.2), 1e-3);
	Rows linear;
	EXPECT_EQ(joint.linearRows(&linear.info), 1);
	EXPECT_EQ(linear.J1l[1], 1) << "the row acts along y";
}

TEST(Generic6DofSubclassInterface, MassSharesAndLinearJacobianFollowTheBodies)
{
	Pair p;  // masses 1 and 3
	Exposed6Dof joint(p.a, p.b, btTransform::getIdentity(), btTransform::getIdentity(), true);
	joint.calculateTransforms();
	EXPECT_FLOAT_EQ(joint.factA(), btScalar(1) / 3 / (1 + btScalar(1) / 3));
	EXPECT_FLOAT_EQ(joint.factA() + joint.factB(), 1);
	EXPECT_FALSE(joint.hasStaticBody());
	// Acting through both centres of mass: the effective mass's inverse is 1/mA + 1/mB.
	EXPECT_NEAR(joint.linearDiagonal(btVector3(0, 1, 0)), 1 + btScalar(1) / 3, 1e-5);
}
