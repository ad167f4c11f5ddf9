// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet's protected interface of btGeneric6DofSpring2Constraint, as a subclass written for Bullet uses
// it: a getInfo2 of its own built from setLinearLimits and setAngularLimits writes exactly the joint's
// rows (every coordinate kind at once), get_limit_motor_info2's row count and rows per coordinate state,
// calculateJacobi's Jacobian, testAngularLimitMotor's limit states, calculateLinearInfo /
// calculateAngleInfo, and the mass shares m_factA / m_factB / m_hasStaticBody.

#include <gtest/gtest.h>

#include <vector>

#include "btBulletDynamicsCommon.h"

namespace
{
class BulletStyleSpring2 : public btGeneric6DofSpring2Constraint
{
public:
	using btGeneric6DofSpring2Constraint::btGeneric6DofSpring2Constraint;

	// Bullet's own getInfo2 layout: the linear coordinates' rows, then the angular ones'.
	int writeRowsBulletStyle(btConstraintInfo2* info)
	{
		calculateTransforms();
		const btTransform& ta = m_rbA.getCenterOfMassTransform();
		const btTransform& tb = m_rbB.getCenterOfMassTransform();
		const btVector3 vA = m_rbA.getLinearVelocity(), wA = m_rbA.getAngularVelocity();
		const btVector3 vB = m_rbB.getLinearVelocity(), wB = m_rbB.getAngularVelocity();
		const int row = setLinearLimits(info, 0, ta, tb, vA, vB, wA, wB);
		return setAngularLimits(info, row, ta, tb, vA, vB, wA, wB);
	}
	int coordinateRows(btRotationalLimitMotor2* motor, btConstraintInfo2* info, int row, btVector3 axis, int rotational)
	{
		const btVector3 zero(0, 0, 0);
		return get_limit_motor_info2(motor, m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(), zero,
		                             zero, zero, zero, info, row, axis, rotational, 1);
	}
	void jacobi(btConstraintInfo2* info, int row, btVector3 axis, int rotational, int rotAllowed)
	{
		calculateJacobi(&m_angularLimits[0], m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform(), info,
		                row, axis, rotational, rotAllowed);
	}
	void remeasureFromCalculatedTransforms()
	{
		m_calculatedLinearDiff.setZero();
		m_calculatedAxisAngleDiff.setZero();
		calculateLinearInfo();
		calculateAngleInfo();
		for (int i = 0; i < 3; ++i) testAngularLimitMotor(i);
	}
	btScalar factA() const { return m_factA; }
	btScalar factB() const { return m_factB; }
	bool hasStaticBody() const { return m_hasStaticBody; }
	int jacobianEntries() const
	{
		return int(sizeof(m_jacLinear) / sizeof(m_jacLinear[0]) + sizeof(m_jacAng) / sizeof(m_jacAng[0]));
	}
};

const int kSkip = 8;  // the solver's row stride
const int kMaxRows = 18;

// Storage for kMaxRows rows, every value preset to a marker so that unwritten entries show.
struct Rows
{
	std::vector<btScalar> J1l, J1a, J2l, J2a, error, cfm, lo, hi;
	btTypedConstraint::btConstraintInfo2 info;
	explicit Rows(btScalar startingCfm = 0)
	{
		for (std::vector<btScalar>* v : {&J1l, &J1a, &J2l, &J2a, &error, &lo, &hi}) v->assign(kMaxRows * kSkip, 0);
		cfm.assign(kMaxRows * kSkip, startingCfm);
		for (int r = 0; r < kMaxRows; ++r)
		{
			lo[r * kSkip] = -SIMD_INFINITY;
			hi[r * kSkip] = SIMD_INFINITY;
		}
		info.fps = 60;
		info.erp = btScalar(0.2);
		info.m_J1linearAxis = J1l.data();
		info.m_J1angularAxis = J1a.data();
		info.m_J2linearAxis = J2l.data();
		info.m_J2angularAxis = J2a.data();
		info.rowskip = kSkip;
		info.m_constraintError = error.data();
		info.cfm = cfm.data();
		info.m_lowerLimit = lo.data();
		info.m_upperLimit = hi.data();
		info.m_numIterations = 10;
		info.m_damping = 1;
	}
	std::vector<btScalar> row(int r) const
	{
		std::vector<btScalar> out;
		for (const std::vector<btScalar>* v : {&J1l, &J1a, &J2l, &J2a})
			for (int k = 0; k < 3; ++k) out.push_back((*v)[r * kSkip + k]);
		for (const std::vector<btScalar>* v : {&error, &cfm, &lo, &hi}) out.push_back((*v)[r * kSkip]);
		return out;
	}
};

struct Pair
{
	btBoxShape shape{btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))};
	btRigidBody a{1, 0, &shape, btVector3(btScalar(1) / 6, btScalar(1) / 6, btScalar(1) / 6)};
	btRigidBody b{3, 0, &shape, btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))};
};

bool sameRow(const std::vector<btScalar>& x, const std::vector<btScalar>& y)
{
	// The same arithmetic on the same inputs: equal up to the last bit or two.
	for (size_t k = 0; k < x.size(); ++k)
	{
		const btScalar scale = btMax(btScalar(1), btFabs(x[k]));
		if (!(btFabs(x[k] - y[k]) <= btScalar(1e-5) * scale) && !(x[k] == y[k])) return false;
	}
	return true;
}
}  // namespace

TEST(Generic6DofSpring2SubclassInterface, BulletStyleGetInfo2WritesExactlyTheJointsRows)
{
	// Every kind of coordinate: linear x locked, y limited (with bounce), z motor; angle x spring, y
	// servo (with its own stop ERP and motor CFM through setParam), z limited. The bodies are turned and
	// moving so that every Jacobian, rate and target is non-trivial.
	Pair p;
	p.b.setCenterOfMassTransform(btTransform(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.3)),
	                                         btVector3(btScalar(0.1), btScalar(0.2), btScalar(-0.1))));
	p.a.setLinearVelocity(btVector3(btScalar(0.5), 0, btScalar(-0.2)));
	p.a.setAngularVelocity(btVector3(0, btScalar(0.7), btScalar(0.1)));
	p.b.setLinearVelocity(btVector3(0, btScalar(-0.4), btScalar(0.3)));
	p.b.setAngularVelocity(btVector3(btScalar(-0.2), 0, btScalar(0.6)));
	BulletStyleSpring2 joint(p.a, p.b, btTransform::getIdentity(), btTransform::getIdentity());
	joint.setLimit(0, 0, 0);
	joint.setLimit(1, btScalar(-0.1), btScalar(0.1));
	joint.setBounce(1, btScalar(0.5));
	joint.setLimit(2, 1, -1);
	joint.enableMotor(2, true);
	joint.setTargetVelocity(2, 1);
	joint.setMaxMotorForce(2, 50);
	joint.setLimit(3, 1, -1);
	joint.enableSpring(3, true);
	joint.setStiffness(3, 40);
	joint.setDamping(3, 2);
	joint.setLimit(4, 1, -1);
	joint.enableMotor(4, true);
	joint.setServo(4, true);
	joint.setServoTarget(4, btScalar(0.4));
	joint.setTargetVelocity(4, 3);
	joint.setMaxMotorForce(4, 20);
	joint.setParam(BT_CONSTRAINT_STOP_ERP, btScalar(0.6), 4);
	joint.setParam(BT_CONSTRAINT_CFM, btScalar(0.01), 4);
	joint.setLimit(5, btScalar(-0.2), btScalar(0.2));

	btTypedConstraint::btConstraintInfo1 info1;
	joint.getInfo1(&info1);
	// Locked 1, limited 2 + 2, motor 1, spring 1, servo 1.
	ASSERT_EQ(info1.m_numConstraintRows, 8);
	Rows own(btScalar(0.001)), bulletStyle(btScalar(0.001));
	joint.getInfo2(&own.info);
	EXPECT_EQ(joint.writeRowsBulletStyle(&bulletStyle.info), info1.m_numConstraintRows);
	// The same rows, in another order (getInfo2 groups them by kind, Bullet's layout by coordinate).
	std::vector<bool> matched(info1.m_numConstraintRows, false);
	for (int r = 0; r < info1.m_numConstraintRows; ++r)
	{
		bool found = false;
		for (int q = 0; q < info1.m_numConstraintRows && !found; ++q)
		{
			if (matched[q] || !sameRow(own.row(r), bulletStyle.row(q))) continue;
			matched[q] = true;
			found = true;
		}
		EXPECT_TRUE(found) << "getInfo2's row " << r << " is not among the rows Bullet's layout wrote";
	}
	EXPECT_EQ(bulletStyle.row(info1.m_numConstraintRows), Rows(btScalar(0.001)).row(0)) << "wrote past its rows";
}

TEST(Generic6DofSpring2SubclassInterface, LimitMotorInfoWritesTheRowsOfTheCoordinatesState)
{
	Pair p;
	BulletStyleSpring2 joint(p.a, p.b, btTransform::getIdentity(), btTransform::getIdentity());
	const btVector3 x(1, 0, 0);
	btRotationalLimitMotor2 motor;
	motor.m_loLimit = 1;  // free: lower above upper
	motor.m_hiLimit = -1;
	motor.m_currentLimit = 0;
	Rows rows;
	EXPECT_EQ(joint.coordinateRows(&motor, &rows.info, 0, x, 1), 0) << "a free, undriven coordinate has no row";

	// Locked at 0 while at 0.1: one equality row pulling the angle back at stop ERP (J v is the rate).
	motor.m_loLimit = motor.m_hiLimit = 0;
	motor.m_currentLimit = 3;
	motor.m_currentPosition = btScalar(0.1);
	motor.m_stopERP = btScalar(0.5);
	motor.m_stopCFM = 0;
	motor.m_enableMotor = true;  // a locked coordinate has nothing to drive
	ASSERT_EQ(joint.coordinateRows(&motor, &rows.info, 0, x, 1), 1);
	EXPECT_EQ(rows.J1a[0], 1);
	EXPECT_EQ(rows.J2a[0], -1);
	EXPECT_NEAR(rows.error[0], 60 * 0.5 * -0.1, 1e-5);
	EXPECT_LT(rows.lo[0], -1e10);
	EXPECT_GT(rows.hi[0], 1e10);

	// Limited with a motor and a spring: two one-sided limit rows, the motor's and the spring's.
	motor.m_loLimit = -1;
	motor.m_hiLimit = 1;
	motor.m_currentLimit = 4;
	motor.m_currentPosition = 0;
	motor.m_targetVelocity = 2;
	motor.m_maxMotorForce = 60;
	motor.m_motorERP = btScalar(0.9);
	motor.m_enableSpring = true;
	motor.m_springStiffness = 10;
	ASSERT_EQ(joint.coordinateRows(&motor, &rows.info, 1, x, 1), 4);
	EXPECT_EQ(rows.lo[1 * kSkip], 0) << "lower end: impulses that raise the angle only";
	EXPECT_EQ(rows.hi[2 * kSkip], 0) << "upper end: impulses that lower it only";
	EXPECT_NEAR(rows.error[3 * kSkip], 2, 1e-5) << "the motor's target rate";
	EXPECT_NEAR(rows.hi[3 * kSkip], 1, 1e-5) << "max force / fps";
	EXPECT_NE(rows.J1a[4 * kSkip], 0) << "the spring row";

	// A linear coordinate along x: its rows measure B's pivot relative to A, so J is along -x.
	motor.m_enableSpring = false;
	motor.m_enableMotor = false;
	ASSERT_EQ(joint.coordinateRows(&motor, &rows.info, 5, x, 0), 2);
	EXPECT_EQ(rows.J1l[5 * kSkip], -1);
	EXPECT_EQ(rows.J2l[5 * kSkip], 1);
}

TEST(Generic6DofSpring2SubclassInterface, CalculateJacobiWritesTheAxisForBothBodies)
{
	Pair p;
	p.b.setCenterOfMassTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 2, 0)));
	// B's pivot 1 below B's centre, 1 above A's.
	BulletStyleSpring2 joint(p.a, p.b, btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)),
	                         btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
	joint.calculateTransforms();
	Rows rows;
	joint.jacobi(&rows.info, 0, btVector3(0, 0, 1), 1, 0);
	EXPECT_EQ(rows.J1a[2], 1);
	EXPECT_EQ(rows.J2a[2], -1);
	EXPECT_EQ(rows.J1l[2], 0);
	// Along x at the pivot: arm (0, 1, 0) from A, (0, -1, 0) from B; arm x axis = (0, 0, -1) for A.
	joint.jacobi(&rows.info, 1, btVector3(1, 0, 0), 0, 1);
	EXPECT_EQ(rows.J1l[kSkip + 0], 1);
	EXPECT_EQ(rows.J2l[kSkip + 0], -1);
	EXPECT_NEAR(rows.J1a[kSkip + 2], -1, 1e-6);
	EXPECT_NEAR(rows.J2a[kSkip + 2], -1, 1e-6) << "-(armB x axis) with armB = (0, -1, 0)";
	joint.jacobi(&rows.info, 2, btVector3(1, 0, 0), 0, 0);
	EXPECT_EQ(rows.J1a[2 * kSkip + 2], 0) << "no turning without rotAllowed";
}

TEST(Generic6DofSpring2SubclassInterface, MeasurementHelpersAndMassShares)
{
	Pair p;  // masses 1 and 3
	p.b.setCenterOfMassTransform(
	    btTransform(btQuaternion(btVector3(0, 0, 1), btScalar(0.25)), btVector3(btScalar(0.3), 0, 0)));
	BulletStyleSpring2 joint(p.a, p.b, btTransform::getIdentity(), btTransform::getIdentity());
	joint.setLimit(5, btScalar(-0.1), btScalar(0.1));  // angle z limited
	joint.setLimit(4, 0, 0);                           // angle y locked
	joint.calculateTransforms();
	joint.remeasureFromCalculatedTransforms();
	EXPECT_NEAR(joint.getRelativePivotPosition(0), 0.3, 1e-6);
	// B turned +0.25 about z relative to A: A turned -0.25 relative to B.
	EXPECT_NEAR(joint.getAngle(2), -0.25, 1e-5);
	EXPECT_EQ(joint.getRotationalLimitMotor(2)->m_currentLimit, 4);
	EXPECT_EQ(joint.getRotationalLimitMotor(1)->m_currentLimit, 3);
	EXPECT_EQ(joint.getRotationalLimitMotor(0)->m_currentLimit, 0) << "free by default";
	EXPECT_NEAR(joint.getRotationalLimitMotor(2)->m_currentPosition, -0.25, 1e-5);

	// Bullet's shares: m_factA = invMassB / (invMassA + invMassB) = (1/3) / (1 + 1/3).
	EXPECT_NEAR(joint.factA(), 0.25, 1e-6);
	EXPECT_NEAR(joint.factA() + joint.factB(), 1, 1e-6);
	EXPECT_FALSE(joint.hasStaticBody());
	BulletStyleSpring2 anchored(p.b, btTransform::getIdentity());
	anchored.calculateTransforms();
	EXPECT_TRUE(anchored.hasStaticBody());
	EXPECT_EQ(joint.jacobianEntries(), 6);
}
