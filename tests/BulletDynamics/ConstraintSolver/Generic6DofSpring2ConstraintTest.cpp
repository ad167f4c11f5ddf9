// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGeneric6DofSpring2Constraint: Bullet's angle conventions for every rotation order, exact angle
// rates, locked / limited / free coordinates, implicit springs against the analytic backward-Euler
// oscillator, servos, motors, bounce, parameters and bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "JointTestUtil.h"

using caliber_test::CrossingTimer;
using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kG = btScalar(10);
const btVector3 kZero(0, 0, 0);

const RotateOrder kAllOrders[6] = {RO_XYZ, RO_XZY, RO_YXZ, RO_YZX, RO_ZXY, RO_ZYX};
// (first, middle, last) axis of each order, in the order of kAllOrders.
const int kOrderAxes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

btVector3 unitAxis(int i)
{
	btVector3 e(0, 0, 0);
	e[i] = 1;
	return e;
}

btMatrix3x3 rotation(int axis, btScalar angle) { return btMatrix3x3(btQuaternion(unitAxis(axis), angle)); }

// A body held to the world by a 6-DOF joint whose frames sit at the body's centre of mass, all six
// coordinates locked; tests open the ones they need.
btGeneric6DofSpring2Constraint* holdToWorld(TestWorld& w, btRigidBody* body, RotateOrder order = RO_XYZ,
                                            const btTransform& frameInB = btTransform::getIdentity())
{
	btGeneric6DofSpring2Constraint* joint = w.addJoint<btGeneric6DofSpring2Constraint>(false, *body, frameInB, order);
	joint->setAngularLowerLimit(kZero);
	joint->setAngularUpperLimit(kZero);
	body->setActivationState(DISABLE_DEACTIVATION);
	return joint;
}

typedef bool (*EulerFunction)(const btMatrix3x3&, btVector3&);
const EulerFunction kEulerFunctions[6] = {
    &btGeneric6DofSpring2Constraint::matrixToEulerXYZ, &btGeneric6DofSpring2Constraint::matrixToEulerXZY,
    &btGeneric6DofSpring2Constraint::matrixToEulerYXZ, &btGeneric6DofSpring2Constraint::matrixToEulerYZX,
    &btGeneric6DofSpring2Constraint::matrixToEulerZXY, &btGeneric6DofSpring2Constraint::matrixToEulerZYX};
}  // namespace

// ---- conventions --------------------------------------------------------------------------------

TEST(Generic6DofSpring2Constraint, EulerAnglesDecomposeBTransposeAInTheRotationOrder)
{
	// Bullet's convention: for order ijk, B^T A = R_i(angle_i) R_j(angle_j) R_k(angle_k). Random poses
	// with the middle angle inside (-pi/2, pi/2) must come back from both the static decomposition (of
	// A^T B) and the joint. Tolerance: a few float roundings of unit-size matrix entries, amplified by
	// at most 1 / cos(middle) <= 1 / cos(1.4) = 5.9 in the outer angles.
	std::mt19937 rng(7);
	std::uniform_real_distribution<float> outer(-3.1f, 3.1f), middle(-1.4f, 1.4f);
	for (int o = 0; o < 6; ++o)
	{
		// The joint, with A the world (identity) and B turned so that B^T A is each pose below.
		TestWorld w(kZero);
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
		btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity(), kAllOrders[o]);
		for (int trial = 0; trial < 50; ++trial)
		{
			btVector3 angles;
			angles[kOrderAxes[o][0]] = outer(rng);
			angles[kOrderAxes[o][1]] = middle(rng);
			angles[kOrderAxes[o][2]] = outer(rng);
			const btMatrix3x3 bTransposeA = rotation(kOrderAxes[o][0], angles[kOrderAxes[o][0]]) *
			                                rotation(kOrderAxes[o][1], angles[kOrderAxes[o][1]]) *
			                                rotation(kOrderAxes[o][2], angles[kOrderAxes[o][2]]);
			btVector3 measured;
			EXPECT_TRUE(kEulerFunctions[o](bTransposeA.transpose(), measured));
			body->setCenterOfMassTransform(btTransform(bTransposeA.transpose(), btVector3(0, 0, 0)));
			joint.calculateTransforms();
			for (int i = 0; i < 3; ++i)
			{
				EXPECT_NEAR(measured[i], angles[i], 2e-5) << "order " << o << " axis " << i;
				EXPECT_NEAR(joint.getAngle(i), angles[i], 2e-5) << "order " << o << " axis " << i;
			}
		}
	}
}

TEST(Generic6DofSpring2Constraint, AnglesMeasureARelativeToBAndPositionsBRelativeToA)
{
	// Bullet's signs: turning B by +phi about the shared z axis gives angle_z = -phi, while moving B by
	// +s along x gives relative pivot position +s. Exact up to float rounding of the pose.
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity());
	body->setCenterOfMassTransform(btTransform(btQuaternion(btVector3(0, 0, 1), btScalar(0.4)), btVector3(0.25, 0, 0)));
	joint.calculateTransforms();
	EXPECT_NEAR(joint.getAngle(2), -0.4, 1e-6);
	EXPECT_NEAR(joint.getAngle(0), 0, 1e-6);
	EXPECT_NEAR(joint.getRelativePivotPosition(0), 0.25, 1e-6);
	EXPECT_NEAR(joint.getAxis(2).z(), 1, 1e-6) << "the last angle (z) turns about A's z axis";
	btVector3 lower, upper;
	joint.setLimitReversed(5, btScalar(-0.1), btScalar(0.3));
	joint.getAngularLowerLimit(lower);
	joint.getAngularUpperLimit(upper);
	EXPECT_NEAR(lower.z(), -0.3, 1e-6) << "reversed limits are the negated, swapped limits";
	EXPECT_NEAR(upper.z(), 0.1, 1e-6);
}

TEST(Generic6DofSpring2Constraint, EachAngleMovesOnlyWhenBTurnsAlongItsAxis)
{
	// The rows measure angle n's rate as d_n . (wA - wB). Turning B by a small eps about any direction
	// perpendicular to getAxis(n) changes angle n by O(eps^2) only, while turning it about getAxis(n)
	// changes it at first order. eps = 1e-3: the second-order change is below
	// eps^2 |d|^2 ~ 1e-6 * (1 / cos 1.2)^2 ~ 1e-5; the first-order one is at least eps.
	std::mt19937 rng(11);
	std::uniform_real_distribution<float> angle(-1.2f, 1.2f);
	const btScalar eps = btScalar(1e-3);
	for (int o = 0; o < 6; ++o)
	{
		TestWorld w(kZero);
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
		btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity(), kAllOrders[o]);
		for (int trial = 0; trial < 10; ++trial)
		{
			const btQuaternion pose = btQuaternion(btVector3(1, 0, 0), angle(rng)) *
			                          btQuaternion(btVector3(0, 1, 0), angle(rng)) *
			                          btQuaternion(btVector3(0, 0, 1), angle(rng));
			body->setCenterOfMassTransform(btTransform(pose, kZero));
			joint.calculateTransforms();
			// Away from gimbal lock, where the outer angles' rates grow as 1 / cos(middle).
			if (btFabs(joint.getAngle(kOrderAxes[o][1])) > btScalar(1.2)) continue;
			for (int n = 0; n < 3; ++n)
			{
				const btVector3 axis = joint.getAxis(n);
				const btScalar before = joint.getAngle(n);
				btVector3 perpendicular = axis.cross(btVector3(0.3f, -0.7f, 0.5f)).normalized();
				for (int k = 0; k < 2; ++k)
				{
					const btVector3 about = k == 0 ? perpendicular : axis.cross(perpendicular);
					body->setCenterOfMassTransform(btTransform(btQuaternion(about, eps) * pose, kZero));
					joint.calculateTransforms();
					EXPECT_LT(std::fabs(btNormalizeAngle(joint.getAngle(n) - before)), 2e-5)
					    << "order " << o << " angle " << n;
				}
				body->setCenterOfMassTransform(btTransform(btQuaternion(axis, eps) * pose, kZero));
				joint.calculateTransforms();
				// B turned by +eps about the axis: the angle (A relative to B) falls by eps |d_n| >= eps.
				EXPECT_LT(btNormalizeAngle(joint.getAngle(n) - before), -0.98 * eps) << "order " << o << " angle " << n;
				body->setCenterOfMassTransform(btTransform(pose, kZero));
				joint.calculateTransforms();
			}
		}
	}
}

TEST(Generic6DofSpring2Constraint, RowsComeLockedFirstThenLimitsMotorsAndSprings)
{
	// Axis 0 and 3 locked, 1 limited, 2 free with a motor, 4 free with a spring, 5 limited with a motor:
	// the two locked rows lead as equality rows (the solver's exact block), then two one-sided rows per
	// limit, then the motors bounded by force times step, then the spring.
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity());
	joint.setLimit(0, 0, 0);
	joint.setLimit(1, -1, 1);
	joint.setLimit(2, 1, -1);
	joint.setLimit(3, 0, 0);
	joint.setLimit(4, 1, -1);
	joint.setLimit(5, btScalar(-0.5), btScalar(0.5));
	const btScalar force = 4;
	for (int axis : {2, 5})
	{
		joint.enableMotor(axis, true);
		joint.setMaxMotorForce(axis, force);
	}
	joint.enableSpring(4, true);
	joint.setStiffness(4, 10);
	btTypedConstraint::btConstraintInfo1 info1;
	joint.getInfo1(&info1);
	ASSERT_EQ(info1.m_numConstraintRows, 9);
	EXPECT_EQ(info1.nub, 2);

	const int rows = 9, skip = 3;
	btScalar j1l[rows * skip] = {}, j1a[rows * skip] = {}, j2l[rows * skip] = {}, j2a[rows * skip] = {};
	btScalar error[rows * skip] = {}, cfm[rows * skip] = {}, lower[rows * skip], upper[rows * skip];
	for (int i = 0; i < rows * skip; ++i)
	{
		lower[i] = -SIMD_INFINITY;
		upper[i] = SIMD_INFINITY;
	}
	btTypedConstraint::btConstraintInfo2 info2;
	info2.fps = 60;
	info2.erp = btScalar(0.2);
	info2.m_J1linearAxis = j1l;
	info2.m_J1angularAxis = j1a;
	info2.m_J2linearAxis = j2l;
	info2.m_J2angularAxis = j2a;
	info2.rowskip = skip;
	info2.m_constraintError = error;
	info2.cfm = cfm;
	info2.m_lowerLimit = lower;
	info2.m_upperLimit = upper;
	info2.m_numIterations = 10;
	info2.m_damping = 1;
	joint.getInfo2(&info2);
	auto linearRow = [&](int r) { return btVector3(j1l[r * skip], j1l[r * skip + 1], j1l[r * skip + 2]).length() > 0; };
	// Locked: x (linear), then angle x.
	EXPECT_TRUE(linearRow(0));
	EXPECT_FALSE(linearRow(1));
	for (int r = 0; r < 2; ++r)
	{
		EXPECT_LE(lower[r * skip], -SIMD_INFINITY) << "row " << r;
		EXPECT_GE(upper[r * skip], SIMD_INFINITY) << "row " << r;
	}
	// Limits: y (linear) then angle z, each a lower row (pushes up) and an upper row (pushes down).
	for (int r = 2; r < 6; r += 2)
	{
		EXPECT_EQ(lower[r * skip], 0) << "row " << r;
		EXPECT_GE(upper[r * skip], SIMD_INFINITY) << "row " << r;
		EXPECT_LE(lower[(r + 1) * skip], -SIMD_INFINITY) << "row " << r + 1;
		EXPECT_EQ(upper[(r + 1) * skip], 0) << "row " << r + 1;
	}
	EXPECT_TRUE(linearRow(2));
	EXPECT_FALSE(linearRow(4));
	// Motors: z (linear) then angle z, bounded by force / fps.
	for (int r = 6; r < 8; ++r)
	{
		EXPECT_NEAR(upper[r * skip], force / 60, 1e-7) << "row " << r;
		EXPECT_NEAR(lower[r * skip], -force / 60, 1e-7) << "row " << r;
	}
	EXPECT_TRUE(linearRow(6));
	EXPECT_FALSE(linearRow(7));
	// The spring on angle y, a soft spring: its implicit impulse as both bounds (0 at equilibrium).
	EXPECT_FALSE(linearRow(8));
	EXPECT_EQ(lower[8 * skip], upper[8 * skip]);
}

TEST(Generic6DofSpring2Constraint, SetEquilibriumPointTakesTheCurrentPose)
{
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity());
	body->setCenterOfMassTransform(btTransform(btQuaternion(btVector3(0, 1, 0), btScalar(0.3)), btVector3(1, 2, 3)));
	joint.setEquilibriumPoint(1);
	EXPECT_NEAR(joint.getTranslationalLimitMotor()->m_equilibriumPoint.y(), 2, 1e-6);
	EXPECT_EQ(joint.getTranslationalLimitMotor()->m_equilibriumPoint.x(), 0) << "only the index given";
	joint.setEquilibriumPoint();
	EXPECT_NEAR(joint.getTranslationalLimitMotor()->m_equilibriumPoint.z(), 3, 1e-6);
	EXPECT_NEAR(joint.getRotationalLimitMotor(1)->m_equilibriumPoint, -0.3, 1e-6);
	joint.setEquilibriumPoint(4, btScalar(0.7));
	EXPECT_EQ(joint.getRotationalLimitMotor(1)->m_equilibriumPoint, btScalar(0.7));
}

// ---- locked, limited and free coordinates -------------------------------------------------------

TEST(Generic6DofSpring2Constraint, LockedCoordinatesStayLockedWhileAFreeSliderFalls)
{
	// Gravity leans across every axis; only linear y is free. The five locked rows are solved as one
	// exact block, so the body moves along y exactly as a free body does under gravity's y part
	// (semi-implicit Euler: y_n = -g h^2 n (n + 1) / 2) and nothing else moves. Tolerances: float rounding
	// of positions of size ~10 m.
	const btVector3 gravity(3, -kG, 2);
	TestWorld w(gravity);
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.3, 0.4)), 2, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(1, 1, -1);  // lower > upper: free
	EXPECT_FALSE(joint->isLimited(1));
	EXPECT_TRUE(joint->isLimited(0));
	const btScalar h = btScalar(1. / 60.);
	const int steps = 90;
	w.run(steps, h);
	joint->calculateTransforms();
	const double expectedY = -kG * h * h * steps * (steps + 1) / 2.0;
	EXPECT_NEAR(joint->getRelativePivotPosition(1), expectedY, 1e-5 * std::fabs(expectedY));
	EXPECT_NEAR(joint->getRelativePivotPosition(0), 0, 1e-5);
	EXPECT_NEAR(joint->getRelativePivotPosition(2), 0, 1e-5);
	for (int i = 0; i < 3; ++i) EXPECT_NEAR(joint->getAngle(i), 0, 1e-6);
	EXPECT_NEAR(body->getLinearVelocity().x(), 0, 1e-5);
	EXPECT_NEAR(body->getAngularVelocity().length(), 0, 1e-6);
}

TEST(Generic6DofSpring2Constraint, LockedCoordinatesHoldAHingeWhoseFreeAngleSwings)
{
	// A rod hung from its end, free to turn about z only (the last angle of RO_XYZ). The rod swings
	// through a large angle while x and y stay 0: the angular rows make the relative angular velocity
	// exactly parallel to z, so the rotation never leaves the plane (float rounding only). The pivot
	// drifts by the centripetal term h^2 w^2 r / 2 per step, which the stop ERP corrects, so it stays
	// within h^2 w_max^2 r / (2 erp); w_max^2 <= 2 (m g r) / I = 3 g / (2 r) for a rod released level.
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar halfLength = btScalar(0.5);
	btRigidBody* rod = w.addBody(w.shape<btBoxShape>(btVector3(halfLength, 0.05, 0.05)), 1, btVector3(0, 0, 0));
	btTransform frameInB = btTransform::getIdentity();
	frameInB.setOrigin(btVector3(-halfLength, 0, 0));  // pivot at the rod's left end
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, rod, RO_XYZ, frameInB);
	joint->setLimit(5, 1, -1);
	const btScalar h = btScalar(1. / 60.);
	const btScalar erp = w.world()->getSolverInfo().m_erp;
	const btScalar wMaxSquared = btScalar(1.5) * kG / halfLength;
	const btScalar pivotBound = h * h * wMaxSquared * halfLength / (2 * erp);
	btScalar worstPivot = 0, worstTilt = 0, lowestAngle = 0, highestAngle = 0;
	for (int i = 0; i < 120; ++i)
	{
		w.run(1, h);
		joint->calculateTransforms();
		worstPivot = btMax(
		    worstPivot,
		    (joint->getCalculatedTransformB().getOrigin() - joint->getCalculatedTransformA().getOrigin()).length());
		worstTilt = btMax(worstTilt, btMax(btFabs(joint->getAngle(0)), btFabs(joint->getAngle(1))));
		lowestAngle = btMin(lowestAngle, joint->getAngle(2));
		highestAngle = btMax(highestAngle, joint->getAngle(2));
	}
	EXPECT_LT(worstPivot, pivotBound);
	EXPECT_LT(worstTilt, 1e-5);
	EXPECT_GT(highestAngle - lowestAngle, 1.5) << "the free angle swung";
}

// ---- springs ------------------------------------------------------------------------------------

namespace
{
struct SpringRun
{
	double period;           // mean period of x = y + m g / k from its zero crossings
	double amplitudeRatio;   // energy-norm amplitude after the run over the starting one
	double finalMeanOffset;  // y averaged over the last period
};

// A mass m hanging on a vertical linear spring of stiffness k (damping c) to the world, released at
// rest from the spring's natural length; everything but linear y is locked. Measures x = y + m g / k.
SpringRun runVerticalSpring(btScalar m, btScalar k, btScalar c, btScalar h, int steps)
{
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), m, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(1, 1, -1);
	joint->enableSpring(1, true);
	joint->setStiffness(1, k);
	joint->setDamping(1, c);
	joint->setEquilibriumPoint(1, 0);
	const double omega = std::sqrt(double(k) / m), sag = m * kG / k;
	CrossingTimer timer;
	const double startAmplitude = sag;  // released at rest, sag away from where gravity and spring balance
	double lastAmplitude = startAmplitude, meanOffset = 0;
	const int lastPeriodSteps = int(2 * M_PI / omega / h);
	for (int i = 0; i < steps; ++i)
	{
		w.world()->stepSimulation(h, 1, h);
		const double x = body->getCenterOfMassPosition().y() + sag, v = body->getLinearVelocity().y();
		timer.sample(h * (i + 1), x);
		lastAmplitude = std::sqrt(x * x + v * v / (omega * omega));
		if (i >= steps - lastPeriodSteps) meanOffset += body->getCenterOfMassPosition().y() / lastPeriodSteps;
	}
	return {timer.period(), lastAmplitude / startAmplitude, meanOffset};
}
}  // namespace

TEST(Generic6DofSpring2Constraint, UndampedSpringOscillatesAtSqrtKOverMAboutItsSag)
{
	// Backward Euler on x'' = -w^2 x (with the world's x' = x + h v') maps (w x, v) by a rotation of
	// atan(w h) scaled by 1 / sqrt(1 + (w h)^2) per step. So the period is 2 pi h / atan(w h), within
	// (w h)^2 / 3 of 2 pi / w, and the amplitude after n steps is (1 + (w h)^2)^(-n / 2) exactly.
	const btScalar m = 2, h = btScalar(1. / 240.);
	const double omega = 2 * M_PI;  // 1 Hz
	const btScalar k = btScalar(omega * omega * m);
	const int steps = 240 * 6;
	const SpringRun run = runVerticalSpring(m, k, 0, h, steps);
	const double wh = omega * h;
	const double discretePeriod = 2 * M_PI * h / std::atan(wh), continuousPeriod = 2 * M_PI / omega;
	// The discrete period is exact up to the crossing interpolation (error ~ (w h)^2 h per crossing).
	EXPECT_NEAR(run.period, discretePeriod, 1e-4 * discretePeriod);
	EXPECT_NEAR(run.period, continuousPeriod, (wh * wh / 3 + 1e-4) * continuousPeriod);
	// Amplitude: the analytic ratio, up to float rounding of ~1e-7 per step over 1440 steps.
	const double expectedRatio = std::pow(1 + wh * wh, -steps / 2.0);
	EXPECT_NEAR(run.amplitudeRatio, expectedRatio, 1e-3 * expectedRatio);
	// "A little" per period: 1 - (1 + (w h)^2)^(-pi / atan(w h)) ~ pi w h = 8 % at 240 Hz.
	const double lossPerPeriod = 1 - std::pow(1 + wh * wh, -M_PI / std::atan(wh));
	EXPECT_LT(lossPerPeriod, M_PI * wh);
	EXPECT_NEAR(1 - std::pow(run.amplitudeRatio, 1.0 / 6.0), lossPerPeriod, 1e-3);
}

TEST(Generic6DofSpring2Constraint, VeryStiffSpringStaysStableAndSettlesAtMgOverK)
{
	// w h = 1000 / 60 = 17: an explicit spring would explode within a few steps (symplectic Euler is
	// stable only for w h < 2). Backward Euler shrinks the oscillation by 1 / sqrt(1 + (w h)^2) = 1 / 17
	// per step, so after 30 steps only the static sag m g / k = 1e-5 m remains. Tolerance: float
	// rounding of the ~1e-5 offset and of the impulse m g h balancing it (relative 1e-5).
	const btScalar m = 1, k = btScalar(1e6), h = btScalar(1. / 60.);
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), m, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(1, 1, -1);
	joint->enableSpring(1, true);
	joint->setStiffness(1, k);
	joint->setEquilibriumPoint(1, 0);
	btScalar largest = 0;
	for (int i = 0; i < 60; ++i)
	{
		w.run(1, h);
		largest = btMax(largest, btFabs(body->getCenterOfMassPosition().y()));
		ASSERT_TRUE(std::isfinite(body->getCenterOfMassPosition().y()));
	}
	const double sag = m * kG / k;
	EXPECT_LT(largest, 2 * sag) << "never beyond twice the sag (the undamped continuous bound)";
	EXPECT_NEAR(body->getCenterOfMassPosition().y(), -sag, 1e-3 * sag);
	EXPECT_NEAR(body->getLinearVelocity().y(), 0, 1e-3 * sag / h);
}

TEST(Generic6DofSpring2Constraint, SpringsOnEitherSideOfTheSoftRowThresholdGiveTheSameStep)
{
	// The spring is a soft row when (w h)^2 >= 2 and a closed-form implicit impulse below; both forms
	// are the same backward-Euler step, so the discrete amplitude law holds on both sides of the
	// switch: (w h)^2 = 1.5 and 3 give (1 + (w h)^2)^(-n/2) after n steps. Tolerance: the soft row's
	// iterations converge by CFM = 1 / (w h)^2 per sweep; 10 sweeps leave 3^-10 ~ 2e-5 per step.
	for (double whSquared : {1.5, 3.0})
	{
		const btScalar m = 1, h = btScalar(1. / 60.);
		const btScalar k = btScalar(whSquared * m / (h * h));
		const int steps = 6;
		const SpringRun run = runVerticalSpring(m, k, 0, h, steps);
		const double expectedRatio = std::pow(1 + whSquared, -steps / 2.0);
		EXPECT_NEAR(run.amplitudeRatio, expectedRatio, 1e-3 * expectedRatio) << "(w h)^2 = " << whSquared;
	}
}

TEST(Generic6DofSpring2Constraint, DampedSpringSettlesAtItsSag)
{
	// Critically damped (c = 2 sqrt(k m)): after 5 natural periods the continuous solution is within
	// e^-(2 pi 5) of the sag; backward Euler only damps more. Tolerance: float rounding.
	const btScalar m = 3, k = 300, h = btScalar(1. / 60.);
	const btScalar c = 2 * btSqrt(k * m);
	const SpringRun run = runVerticalSpring(m, k, c, h, 60 * 6);
	EXPECT_NEAR(run.finalMeanOffset, -m * kG / k, 1e-4);
}

TEST(Generic6DofSpring2Constraint, AngularSpringOscillatesAtSqrtKOverI)
{
	// A box turning about z only (other angles and all positions locked) on an angular spring with
	// equilibrium 0.5 rad away: the same backward-Euler law as the linear spring, with w = sqrt(k / I).
	// The Euler rates about a single axis are exact, so the angle obeys the linear map exactly.
	const btScalar h = btScalar(1. / 240.), mass = 2;
	const btVector3 halfExtents(0.5, 0.2, 0.1);
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(halfExtents), mass, btVector3(0, 0, 0));
	const double inertia = 1.0 / body->getInvInertiaDiagLocal().z();
	const double omega = 3.0;
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(5, 1, -1);
	joint->enableSpring(5, true);
	joint->setStiffness(5, btScalar(omega * omega * inertia));
	const double theta0 = 0.5;
	joint->setEquilibriumPoint(5, btScalar(theta0));
	CrossingTimer timer;
	const int steps = 240 * 8;
	double x = 0, v = 0;
	for (int i = 0; i < steps; ++i)
	{
		w.run(1, h);
		joint->calculateTransforms();
		x = joint->getAngle(2) - theta0;
		v = -body->getAngularVelocity().z();  // the angle is A relative to B: it falls as B turns up
		timer.sample(h * (i + 1), x);
	}
	const double wh = omega * h;
	const double discretePeriod = 2 * M_PI * h / std::atan(wh);
	EXPECT_NEAR(timer.period(), discretePeriod, 1e-4 * discretePeriod);
	EXPECT_NEAR(timer.period(), 2 * M_PI / omega, (wh * wh / 3 + 1e-4) * 2 * M_PI / omega);
	const double ratio = std::sqrt(x * x + v * v / (omega * omega)) / theta0;
	const double expectedRatio = std::pow(1 + wh * wh, -steps / 2.0);
	EXPECT_NEAR(ratio, expectedRatio, 1e-3 * expectedRatio);
}

TEST(Generic6DofSpring2Constraint, SpringBetweenTwoBodiesOscillatesWithTheReducedMass)
{
	// Two free bodies joined by a linear spring along x, stretched by 0.2: they oscillate against each
	// other at w = sqrt(k (1/m1 + 1/m2)), and the joint's impulses are equal and opposite, so the total
	// momentum stays exactly 0 (float rounding). Same discrete period law as the hanging mass.
	const btScalar m1 = 1, m2 = 3, k = 40, h = btScalar(1. / 240.);
	TestWorld w(kZero);
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.1));
	btRigidBody* a = w.addBody(ball, m1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, m2, btVector3(1, 0, 0));
	a->setActivationState(DISABLE_DEACTIVATION);
	b->setActivationState(DISABLE_DEACTIVATION);
	btGeneric6DofSpring2Constraint* joint = w.addJoint<btGeneric6DofSpring2Constraint>(
	    true, *a, *b, btTransform::getIdentity(), btTransform::getIdentity());
	joint->setAngularLowerLimit(kZero);
	joint->setAngularUpperLimit(kZero);
	joint->setLimit(0, 1, -1);
	joint->enableSpring(0, true);
	joint->setStiffness(0, k);
	joint->setEquilibriumPoint(0, btScalar(0.8));
	const double omega = std::sqrt(k * (1 / m1 + 1 / m2));
	CrossingTimer timer;
	btScalar worstMomentum = 0;
	for (int i = 0; i < 240 * 4; ++i)
	{
		w.run(1, h);
		timer.sample(h * (i + 1), b->getCenterOfMassPosition().x() - a->getCenterOfMassPosition().x() - 0.8);
		worstMomentum = btMax(worstMomentum, btFabs(m1 * a->getLinearVelocity().x() + m2 * b->getLinearVelocity().x()));
	}
	const double wh = omega * h;
	EXPECT_NEAR(timer.period(), 2 * M_PI * h / std::atan(wh), 1e-4 * 2 * M_PI / omega);
	EXPECT_LT(worstMomentum, 1e-5);
}

TEST(Generic6DofSpring2Constraint, ZeroStiffnessSpringIsAnExactImplicitDamper)
{
	// k = 0, damping c: the implicit step gives v' = v / (1 + h c / m) exactly; with c = 0 as well the
	// spring does nothing and the body keeps its speed. Tolerance: float rounding.
	for (int trial = 0; trial < 2; ++trial)
	{
		const btScalar m = 2, c = trial == 0 ? btScalar(3) : btScalar(0), h = btScalar(1. / 60.);
		TestWorld w(kZero);
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), m, btVector3(0, 0, 0));
		btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
		joint->setLimit(0, 1, -1);
		joint->enableSpring(0, true);
		joint->setStiffness(0, 0);
		joint->setDamping(0, c);
		body->setLinearVelocity(btVector3(2, 0, 0));
		const int steps = 30;
		w.run(steps, h);
		const double expected = 2 * std::pow(1 + h * c / m, -steps);
		EXPECT_NEAR(body->getLinearVelocity().x(), expected, 1e-5 * 2) << "c = " << c;
	}
}

// ---- motors and servos --------------------------------------------------------------------------

TEST(Generic6DofSpring2Constraint, MotorReachesItsTargetVelocityAtTheRateItsMaxForceAllows)
{
	// Linear and angular motors from rest: while the target is out of reach the motor pushes with
	// exactly its largest force, so after n steps the speed is F n h / m (or T n h / I); afterwards it
	// holds the target. Bullet's sense: a motor drives A relative to B, so with A the world the
	// relative pivot position falls at the target velocity and the angle rises at it. Tolerance: float.
	const btScalar h = btScalar(1. / 60.), m = 2, force = 5, target = 2;
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.3, 0.2, 0.1)), m, btVector3(0, 0, 0));
	const btScalar inertiaZ = 1 / body->getInvInertiaDiagLocal().z();
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(0, 1, -1);
	joint->setLimit(5, 1, -1);
	for (int axis : {0, 5})
	{
		joint->enableMotor(axis, true);
		joint->setTargetVelocity(axis, target);
		joint->setMaxMotorForce(axis, force);
	}
	const int rampSteps = 20;  // linear: F / m = 2.5 m/s^2 reaches 2 m/s after 48 steps
	w.run(rampSteps, h);
	EXPECT_NEAR(body->getLinearVelocity().x(), -force * rampSteps * h / m, 1e-5);
	const btScalar angularRamp = force * rampSteps * h / inertiaZ;
	ASSERT_GT(angularRamp, target) << "the angular motor reaches its target within the ramp";
	EXPECT_NEAR(-body->getAngularVelocity().z(), target, 1e-5);
	w.run(60, h);
	EXPECT_NEAR(body->getLinearVelocity().x(), -target, 1e-5);
	EXPECT_NEAR(-body->getAngularVelocity().z(), target, 1e-5);
}

TEST(Generic6DofSpring2Constraint, ServoReachesItsTargetWithinItsTorqueAndStopsThere)
{
	// An angular servo to 1 rad at up to 2 rad/s with at most 0.5 N m: it accelerates at exactly
	// T / I at first, never exceeds its speed limit, brakes in time (at most sqrt(T / I * gap), the
	// speed it can shed at half its torque) instead of overshooting, and settles on the target (the last
	// stretch closes the world's ERP, 0.2, of the gap per step: 0.8^n). Tolerances: float for the ramp;
	// 1e-4 rad at the end is 0.8^n for n well below the 3 s left after arrival.
	const btScalar h = btScalar(1. / 60.), torque = btScalar(0.5), speed = 2, goal = 1;
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.2, 0.1)), 2, btVector3(0, 0, 0));
	const btScalar inertiaZ = 1 / body->getInvInertiaDiagLocal().z();
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(5, 1, -1);
	joint->enableMotor(5, true);
	joint->setServo(5, true);
	joint->setServoTarget(5, goal);
	joint->setTargetVelocity(5, speed);
	joint->setMaxMotorForce(5, torque);
	w.run(5, h);
	EXPECT_NEAR(-body->getAngularVelocity().z(), torque * 5 * h / inertiaZ, 1e-5);
	btScalar fastest = 0, furthest = 0;
	for (int i = 0; i < 240; ++i)
	{
		w.run(1, h);
		fastest = btMax(fastest, body->getAngularVelocity().length());
		joint->calculateTransforms();
		furthest = btMax(furthest, joint->getAngle(2));
	}
	EXPECT_LE(fastest, speed + 1e-5);
	EXPECT_LE(fastest, btSqrt(torque / inertiaZ * goal) + 1e-5);
	EXPECT_LE(furthest, goal + 1e-5) << "no overshoot";
	EXPECT_NEAR(joint->getAngle(2), goal, 1e-4);
	EXPECT_NEAR(body->getAngularVelocity().z(), 0, 1e-3);
	w.run(60, h);
	joint->calculateTransforms();
	EXPECT_NEAR(joint->getAngle(2), goal, 1e-4) << "and stays there";
}

// ---- limits and bounce --------------------------------------------------------------------------

TEST(Generic6DofSpring2Constraint, AngularLimitsHoldInEveryRotationOrder)
{
	// A body spun at 6 rad/s about a slanted axis, its three angles limited (outer +-0.5, middle
	// +-0.3). Without limits the angles would sweep through +-pi. The limit rows act on each angle's
	// exact rate, so a limit is passed only by the second-order change of the angle within a step,
	// at most |w|^2 |d|^2 h^2 / 2 with |d| <= 1 / cos(0.3), which the stop ERP then removes:
	// overshoot <= |w|^2 h^2 / (2 erp cos^2 0.3).
	const btScalar h = btScalar(1. / 120.), spin = 6;
	for (int o = 0; o < 6; ++o)
	{
		TestWorld w(kZero);
		btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.3, 0.2, 0.1)), 1, btVector3(0, 0, 0));
		btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body, kAllOrders[o]);
		btVector3 lower(-0.5, -0.5, -0.5), upper(0.5, 0.5, 0.5);
		lower[kOrderAxes[o][1]] = btScalar(-0.3);
		upper[kOrderAxes[o][1]] = btScalar(0.3);
		joint->setAngularLowerLimit(lower);
		joint->setAngularUpperLimit(upper);
		body->setAngularVelocity(btVector3(1, 2, 3).normalized() * spin);
		const btScalar erp = w.world()->getSolverInfo().m_erp;
		const btScalar tolerance = spin * spin * h * h / (2 * erp * btCos(0.3) * btCos(0.3));
		btScalar worstExcess = -1, reached = 0;
		for (int i = 0; i < 240; ++i)
		{
			w.run(1, h);
			joint->calculateTransforms();
			for (int n = 0; n < 3; ++n)
			{
				const btScalar angle = joint->getAngle(n);
				worstExcess = btMax(worstExcess, btMax(angle - upper[n], lower[n] - angle));
				reached = btMax(reached, btFabs(angle) / upper[n]);
			}
		}
		EXPECT_LT(worstExcess, tolerance) << "order " << o;
		EXPECT_GT(reached, 0.99) << "order " << o << ": a limit was reached";
	}
}

TEST(Generic6DofSpring2Constraint, BounceOnALimitReturnsThatFractionOfTheSpeed)
{
	// A slider at 3 m/s meets its upper limit with bounce 0.5 and leaves at 1.5 m/s; the lower limit
	// (bounce 0.5 too) sends it back at 0.75 m/s. An angular limit with bounce 0.8 does the same with
	// the turning rate. Without bounce the body stops at the limit. Tolerance: float rounding.
	const btScalar h = btScalar(1. / 60.);
	for (btScalar bounce : {btScalar(0.5), btScalar(0)})
	{
		TestWorld w(kZero);
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
		btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
		joint->setLimit(0, btScalar(-0.5), btScalar(0.5));
		joint->setBounce(0, bounce);
		body->setLinearVelocity(btVector3(3, 0, 0));
		w.run(20, h);  // 0.5 m at 3 m/s takes 10 steps
		if (bounce > 0)
		{
			EXPECT_NEAR(body->getLinearVelocity().x(), -1.5, 1e-5);
			w.run(40, h);  // 1 m at 1.5 m/s takes 40 steps
			EXPECT_NEAR(body->getLinearVelocity().x(), 0.75, 1e-5);
		}
		else
		{
			EXPECT_NEAR(body->getLinearVelocity().x(), 0, 1e-5);
			EXPECT_NEAR(body->getCenterOfMassPosition().x(), 0.5, 1e-5);
		}
	}
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.3, 0.2, 0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(5, btScalar(-0.5), btScalar(0.5));
	joint->setBounce(5, btScalar(0.8));
	body->setAngularVelocity(btVector3(0, 0, 2));
	w.run(30, h);  // 0.5 rad at 2 rad/s takes 15 steps
	EXPECT_NEAR(body->getAngularVelocity().z(), -1.6, 1e-5);
}

TEST(Generic6DofSpring2Constraint, MotorEasesIntoALimitWithoutPassingIt)
{
	// A strong velocity motor drives the slider towards its upper limit. As in Bullet, the motor does not
	// fight the limit: once the limit is within one step's travel its target falls to erp fps times the
	// room left, so the slider closes (1 - erp) of the room per step and never passes the limit.
	// Tolerance: float rounding of the 0.5 m position.
	const btScalar h = btScalar(1. / 60.);
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
	joint->setLimit(0, btScalar(-0.5), btScalar(0.5));
	joint->enableMotor(0, true);
	joint->setTargetVelocity(0, -2);  // A relative to B: B moves at +2 along x
	joint->setMaxMotorForce(0, 100);
	const btScalar erp = w.world()->getSolverInfo().m_erp;
	btScalar furthest = 0;
	for (int i = 0; i < 40; ++i)
	{
		w.run(1, h);
		furthest = btMax(furthest, body->getCenterOfMassPosition().x());
	}
	EXPECT_LT(furthest, 0.5 + 1e-6);
	const btScalar room = btScalar(0.5) - body->getCenterOfMassPosition().x();
	EXPECT_GT(room, 0);
	EXPECT_LT(room, 0.01);
	w.run(1, h);
	EXPECT_NEAR(body->getLinearVelocity().x(), erp / h * room, 1e-3 * erp / h * room);
	EXPECT_NEAR(btScalar(0.5) - body->getCenterOfMassPosition().x(), (1 - erp) * room, 1e-6);
}

// ---- parameters ---------------------------------------------------------------------------------

TEST(Generic6DofSpring2Constraint, StopErpAndCfmSetHowMuchOfALockedErrorOneStepRemoves)
{
	// A locked coordinate 0.1 off: one step removes ERP of it (the world's 0.2 until setParam). A stop
	// CFM c softens the row so that it removes ERP / (1 + c) instead. Tolerance: float rounding (the
	// soft row converges by c per sweep: 0.25^10).
	const btScalar h = btScalar(1. / 60.), offset = btScalar(0.1);
	struct Case
	{
		bool setErp, setCfm;
		btScalar expectedRemaining;
	};
	const Case cases[3] = {{false, false, offset * btScalar(0.8)},
	                       {true, false, offset * btScalar(0.5)},
	                       {true, true, offset * btScalar(1 - 0.5 / 1.25)}};
	for (const Case& c : cases)
	{
		TestWorld w(kZero);
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
		btGeneric6DofSpring2Constraint* joint = holdToWorld(w, body);
		if (c.setErp) joint->setParam(BT_CONSTRAINT_STOP_ERP, btScalar(0.5), 0);
		if (c.setCfm) joint->setParam(BT_CONSTRAINT_STOP_CFM, btScalar(0.25), 0);
		body->setCenterOfMassTransform(btTransform(btQuaternion::getIdentity(), btVector3(offset, 0, 0)));
		w.run(1, h);
		EXPECT_NEAR(body->getCenterOfMassPosition().x(), c.expectedRemaining, 1e-6);
	}
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity());
	joint.setParam(BT_CONSTRAINT_STOP_ERP, btScalar(0.5), 4);
	joint.setParam(BT_CONSTRAINT_CFM, btScalar(0.01), 2);
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_STOP_ERP, 4), btScalar(0.5));
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_CFM, 2), btScalar(0.01));
	EXPECT_EQ(joint.getRotationalLimitMotor(1)->m_stopERP, btScalar(0.5));
	EXPECT_EQ(joint.getTranslationalLimitMotor()->m_motorCFM.z(), btScalar(0.01));
}

// ---- bad input ----------------------------------------------------------------------------------

TEST(Generic6DofSpring2Constraint, NonFiniteFramesDisableTheJointWithAWarning)
{
	WarningCounter warnings;
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.1));
	btRigidBody* a = w.addBody(ball, 1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, 1, btVector3(1, 0, 0));
	btTransform bad = btTransform::getIdentity();
	bad.setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0));
	btGeneric6DofSpring2Constraint* joint =
	    w.addJoint<btGeneric6DofSpring2Constraint>(false, *a, *b, bad, btTransform::getIdentity());
	EXPECT_FALSE(joint->isEnabled());
	EXPECT_EQ(warnings.count(), 1);
	EXPECT_TRUE(std::isfinite(joint->getRelativePivotPosition(0)));
	w.run(30);
	for (btRigidBody* body : {a, b})
		EXPECT_LT(body->getCenterOfMassPosition().y(), -1) << "both fall freely, and finitely";

	// setFrames with a non-finite frame keeps the old frames and disables the joint.
	btGeneric6DofSpring2Constraint* other = w.addJoint<btGeneric6DofSpring2Constraint>(
	    false, *a, *b, btTransform::getIdentity(), btTransform::getIdentity());
	other->setFrames(btTransform::getIdentity(), bad);
	EXPECT_FALSE(other->isEnabled());
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_TRUE(std::isfinite(other->getFrameOffsetB().getOrigin().x()));
}

TEST(Generic6DofSpring2Constraint, BadSettingsAreReportedAndIgnored)
{
	WarningCounter warnings;
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity());
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	joint.setStiffness(1, 50);
	joint.setStiffness(1, -3);
	joint.setStiffness(1, nan);
	joint.setDamping(1, -1);
	joint.setLimit(4, nan, 1);
	joint.setMaxMotorForce(2, -5);
	joint.setBounce(0, nan);
	joint.setEquilibriumPoint(3, nan);
	joint.setAxis(btVector3(0, 0, 1), btVector3(0, 0, 2));  // parallel
	joint.setAxis(btVector3(0, 0, 0), btVector3(0, 1, 0));  // zero
	EXPECT_EQ(warnings.count(), 9);
	EXPECT_EQ(joint.getTranslationalLimitMotor()->m_springStiffness.y(), 50);
	EXPECT_EQ(joint.getTranslationalLimitMotor()->m_springDamping.y(), 0);
	EXPECT_FALSE(joint.isLimited(4)) << "the angular default (free) is kept";
	EXPECT_EQ(joint.getTranslationalLimitMotor()->m_maxMotorForce.z(), 0);
	EXPECT_TRUE(joint.isEnabled()) << "bad settings are ignored, the joint goes on";
	EXPECT_EQ(joint.getFrameOffsetA().getOrigin(), btVector3(0, 0, 0));
}

TEST(Generic6DofSpring2Constraint, CoordinateIndexOutsideZeroToFiveIsAProgrammingError)
{
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity());
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(joint.setLimit(6, 0, 1), "index must be 0..5");
	EXPECT_DEATH(joint.enableSpring(-1, true), "index must be 0..5");
	EXPECT_DEATH(joint.setParam(BT_CONSTRAINT_STOP_ERP, btScalar(0.5), 7), "axis must be 0..5");
#else
	WarningCounter warnings;
	joint.setLimit(6, 0, 1);
	joint.enableSpring(-1, true);
	joint.setParam(BT_CONSTRAINT_STOP_ERP, btScalar(0.5), 7);
	EXPECT_EQ(warnings.count(), 3);
	btTypedConstraint::btConstraintInfo1 info;
	joint.getInfo1(&info);
	EXPECT_EQ(info.m_numConstraintRows, 3) << "still the default: three locked positions, free angles";
#endif
}

TEST(Generic6DofSpring2Constraint, AngleAccessorsOutsideZeroToTwoAreReportedNeverRead)
{
	TestWorld w(kZero);
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpring2Constraint joint(*body, btTransform::getIdentity());
	joint.calculateTransforms();
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(joint.getAxis(3), "index must be 0..2");
	EXPECT_DEATH(joint.getRotationalLimitMotor(5), "index must be 0..2");
#else
	WarningCounter warnings;
	EXPECT_EQ(joint.getAxis(3), btVector3(0, 0, 0));
	EXPECT_EQ(joint.getAngle(-1), btScalar(0));
	EXPECT_EQ(joint.getRelativePivotPosition(3), btScalar(0));
	EXPECT_EQ(joint.getRotationalLimitMotor(5), joint.getRotationalLimitMotor(2)) << "clamped to the last angle";
	EXPECT_EQ(joint.getRotationalLimitMotor(-2), joint.getRotationalLimitMotor(0)) << "clamped to the first angle";
	EXPECT_EQ(warnings.count(), 5);
#endif
	EXPECT_EQ(joint.getAxis(2), btVector3(0, 0, 1)) << "valid indices read as before";
}
