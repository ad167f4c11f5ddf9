// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGeneric6DofSpringConstraint: springs on linear and angular coordinates oscillate at sqrt(k / m) and
// sqrt(k / I) about their rest positions, keep their energy when undamped, and decay at the rate their
// damping gives.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpringConstraint.h"
#include "JointTestUtil.h"

using caliber_test::CrossingTimer;
using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const double kG = 10;
const btScalar kH = btScalar(1. / 240.);

// The period semi-implicit Euler gives an undamped oscillator of angular frequency omega: its discrete
// frequency Omega satisfies sin(Omega h / 2) = omega h / 2, i.e. the period is short by (omega h)^2 / 24.
double symplecticEulerPeriod(double omega, double h) { return 2 * M_PI * h / (2 * std::asin(omega * h / 2)); }

// A body of mass m hanging from the world on a vertical spring (coordinate y free, everything else
// locked), released at the spring's rest length. Records y(t) of the joint coordinate.
struct VerticalSpring
{
	TestWorld world{btVector3(0, btScalar(-kG), 0)};
	btRigidBody* body;
	btGeneric6DofSpringConstraint* spring;

	VerticalSpring(double mass, double stiffness, double damping)
	{
		body = world.addBody(world.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), btScalar(mass), btVector3(0, 0, 0));
		body->setSleepingThresholds(0, 0);
		spring = world.addJoint<btGeneric6DofSpringConstraint>(false, *body, btTransform::getIdentity(), true);
		spring->setLinearLowerLimit(btVector3(0, 1, 0));  // y free
		spring->setLinearUpperLimit(btVector3(0, -1, 0));
		spring->setAngularLowerLimit(btVector3(0, 0, 0));
		spring->setAngularUpperLimit(btVector3(0, 0, 0));
		spring->enableSpring(1, true);
		spring->setStiffness(1, btScalar(stiffness));
		spring->setDamping(1, btScalar(damping));
		spring->setEquilibriumPoint(1, 0);
	}

	double step()
	{
		world.run(1, kH);
		spring->calculateTransforms();
		return double(spring->getRelativePivotPosition(1));
	}
};
}  // namespace

TEST(Generic6DofSpringConstraint, VerticalSpringOscillatesAtSqrtKOverMAboutTheSagMgOverK)
{
	const double mass = 2, omega = 2 * M_PI, stiffness = mass * omega * omega;  // 1 Hz
	VerticalSpring s(mass, stiffness, 0);
	const double sag = mass * kG / stiffness;  // 0.253 m
	CrossingTimer timer;
	double highest = -1e9, lowest = 1e9, firstHigh = -1e9, firstLow = 1e9;
	const int steps = 240 * 10;
	for (int i = 0; i < steps; ++i)
	{
		const double y = s.step();
		timer.sample(double(kH) * (i + 1), y + sag);
		highest = std::max(highest, y);
		lowest = std::min(lowest, y);
		if (i < 240)
		{
			firstHigh = std::max(firstHigh, y);
			firstLow = std::min(firstLow, y);
		}
	}
	const double exact = 2 * M_PI / omega;
	const double discrete = symplecticEulerPeriod(omega, double(kH));
	// Tolerance: the discrete period of semi-implicit Euler is known exactly; what remains is the linear
	// interpolation of the zero crossings over 10 periods, far below 1e-5 of the period.
	EXPECT_NEAR(timer.period(), discrete, 1e-5 * exact);
	// And it is the physical period to the integrator's phase error (omega h)^2 / 24 = 2.9e-5.
	EXPECT_NEAR(timer.period(), exact, 5e-5 * exact);
	// Released at rest at its rest length, it swings between 0 and -2 m g / k, centred on the sag.
	// Tolerance: extremes are sampled once per step: A (omega h)^2 / 8 = 2e-6 m; float rounding 1e-6.
	EXPECT_NEAR(0.5 * (highest + lowest), -sag, 1e-5);
	EXPECT_NEAR(highest - lowest, 2 * sag, 2e-5);
	// Undamped, it keeps its energy: the swing of the first second equals that of all ten (an implicit
	// spring would lose 8 % per period at this step).
	EXPECT_NEAR(firstHigh - firstLow, highest - lowest, 2e-5);
}

TEST(Generic6DofSpringConstraint, AngularSpringOscillatesAtSqrtKOverI)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.3, 0.2, 0.1)), 3, btVector3(0, 0, 0));
	box->setSleepingThresholds(0, 0);
	// Frame X along the body's local z.
	btGeneric6DofSpringConstraint* spring = w.addJoint<btGeneric6DofSpringConstraint>(
	    false, *box, btTransform(btQuaternion(btVector3(0, 1, 0), -SIMD_HALF_PI), btVector3(0, 0, 0)), true);
	spring->setAngularLowerLimit(btVector3(1, 0, 0));  // x free
	spring->setAngularUpperLimit(btVector3(-1, 0, 0));
	const double inertia = 1.0 / double(box->getInvInertiaDiagLocal().z());
	const double omega = 3.0, stiffness = inertia * omega * omega;
	spring->enableSpring(3, true);
	spring->setStiffness(3, btScalar(stiffness));
	spring->setEquilibriumPoint();
	EXPECT_EQ(spring->getEquilibriumPoint(3), btScalar(0));
	const double amplitude = 0.6;
	box->setAngularVelocity(btVector3(0, 0, btScalar(amplitude * omega)));
	CrossingTimer timer;
	double highest = -1;
	for (int i = 0; i < 240 * 12; ++i)
	{
		w.run(1, kH);
		spring->calculateTransforms();
		const double angle = double(spring->getAngle(0));
		timer.sample(double(kH) * (i + 1), angle);
		highest = std::max(highest, angle);
	}
	const double exact = 2 * M_PI / omega;
	// Tolerance: as for the linear spring, the integrator's phase error (omega h)^2 / 24 = 6.5e-6 plus the
	// crossing interpolation.
	EXPECT_NEAR(timer.period(), symplecticEulerPeriod(omega, double(kH)), 1e-5 * exact);
	EXPECT_NEAR(timer.period(), exact, 3e-5 * exact);
	// Amplitude w0 / omega, kept (energy conserved). Tolerance: semi-implicit Euler's conserved ellipse is
	// wider than the true one by (omega h)^2 / 8 = 2e-5, and the extreme is sampled once per step.
	EXPECT_NEAR(highest, amplitude, 2e-4 * amplitude);
	// The spring turns the body about the frame's axis only.
	EXPECT_LT(btFabs(box->getAngularVelocity().x()) + btFabs(box->getAngularVelocity().y()), btScalar(1e-5));
}

TEST(Generic6DofSpringConstraint, DampingMakesTheAmplitudeDecayAtRateDOverTwoM)
{
	const double mass = 2, omega = 2 * M_PI, stiffness = mass * omega * omega, damping = 0.8;
	VerticalSpring s(mass, stiffness, damping);
	const double sag = mass * kG / stiffness;
	// Successive maxima of the displacement from the sag.
	std::vector<double> peaks;
	double previous = -1e9, beforePrevious = -1e9;
	for (int i = 0; i < 240 * 8; ++i)
	{
		const double x = -(s.step() + sag);  // positive downwards from the rest point: starts at -sag
		if (i >= 2 && previous > beforePrevious && previous >= x) peaks.push_back(previous);
		beforePrevious = previous;
		previous = x;
	}
	ASSERT_GE(peaks.size(), 6u);
	// x(t) = A exp(-d t / 2m) cos(omega_d t): successive peaks one damped period apart shrink by
	// exp(-d T_d / 2m), T_d = 2 pi / sqrt(omega^2 - (d / 2m)^2).
	const double gamma = damping / (2 * mass);
	const double period = 2 * M_PI / std::sqrt(omega * omega - gamma * gamma);
	const double expected = gamma * period;  // logarithmic decrement, 0.2
	const double measured = std::log(peaks[1] / peaks[5]) / 4;
	// Tolerance: implicit damping shrinks the phase area by 1 / (1 + d h / m) per step, which matches
	// exp(-d h / m) to a relative d h / 2m = 8e-4; peak sampling once per step adds (omega h)^2 / 8.
	EXPECT_NEAR(measured, expected, 3e-3 * expected);
	EXPECT_LT(peaks.back(), 0.3 * peaks.front()) << "it decays";
}

TEST(Generic6DofSpringConstraint, VeryStiffSpringStaysBoundedInsteadOfBlowingUp)
{
	// omega h = 5: an explicit spring would be unstable (it needs omega h < 2).
	const double mass = 1, omega = 5 * 240.0, stiffness = mass * omega * omega;
	VerticalSpring s(mass, stiffness, 0);
	const double sag = mass * kG / stiffness;
	double worst = 0;
	for (int i = 0; i < 240; ++i) worst = std::max(worst, std::fabs(s.step() + sag));
	// Released at 0 it may never move further from the rest point than it started (sag): the stiff
	// spring loses energy rather than gaining any.
	EXPECT_LE(worst, sag * (1 + 1e-6) + 1e-9);
	EXPECT_TRUE(std::isfinite(double(s.body->getCenterOfMassPosition().y())));
}

TEST(Generic6DofSpringConstraint, SpringOnALockedCoordinateDoesNothingAndSettersAreChecked)
{
	WarningCounter warnings;
	TestWorld w(btVector3(0, btScalar(-kG), 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), 1, btVector3(0, 0, 0));
	btGeneric6DofSpringConstraint* spring =
	    w.addJoint<btGeneric6DofSpringConstraint>(false, *box, btTransform::getIdentity(), true);
	EXPECT_EQ(spring->getConstraintType(), D6_SPRING_CONSTRAINT_TYPE);
	spring->enableSpring(0, true);  // linear x is locked by default
	spring->setStiffness(0, 100);
	spring->setEquilibriumPoint(0, btScalar(0.5));
	EXPECT_TRUE(spring->isSpringEnabled(0));
	EXPECT_EQ(spring->getStiffness(0), btScalar(100));
	EXPECT_EQ(spring->getEquilibriumPoint(0), btScalar(0.5));
	btTypedConstraint::btConstraintInfo1 info;
	spring->getInfo1(&info);
	EXPECT_EQ(info.m_numConstraintRows, 3) << "only the three locked linear rows";
	w.run(60);
	EXPECT_NEAR(box->getCenterOfMassPosition().x(), 0, 1e-5);

	spring->setStiffness(0, -1);
	spring->setDamping(0, std::numeric_limits<btScalar>::quiet_NaN());
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_EQ(spring->getStiffness(0), btScalar(100));
	EXPECT_EQ(spring->getDamping(0), btScalar(0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(spring->enableSpring(6, true), "index");
	EXPECT_DEATH(spring->getStiffness(-1), "index");
#else
	spring->enableSpring(6, true);
	spring->setStiffness(-1, 5);
	spring->setDamping(6, 5);
	spring->setEquilibriumPoint(9, 1);
	EXPECT_FALSE(spring->isSpringEnabled(6));
	EXPECT_EQ(spring->getStiffness(-1), btScalar(0));
	EXPECT_EQ(spring->getDamping(6), btScalar(0));
	EXPECT_EQ(spring->getEquilibriumPoint(9), btScalar(0));
	EXPECT_EQ(warnings.count(), 2 + 8) << "each out-of-range index is reported";
	EXPECT_EQ(spring->getStiffness(0), btScalar(100)) << "and changes nothing";
#endif
}

namespace
{
// A spring joint written for Bullet: its springs drive the 6-DoF joint's motors through
// internalUpdateSprings, and the base 6-DoF joint writes the rows.
class BulletStyleSpring : public btGeneric6DofSpringConstraint
{
public:
	BulletStyleSpring(btRigidBody& body, const btTransform& frame, bool useLinearReferenceFrameB)
	    : btGeneric6DofSpringConstraint(body, frame, useLinearReferenceFrameB)
	{
	}
	void getInfo1(btConstraintInfo1* info) override { btGeneric6DofConstraint::getInfo1(info); }
	void getInfo2(btConstraintInfo2* info) override
	{
		internalUpdateSprings(info);
		btGeneric6DofConstraint::getInfo2(info);
	}
	void updateSprings(btConstraintInfo2* info) { internalUpdateSprings(info); }
};
}  // namespace

TEST(Generic6DofSpringConstraint, InternalUpdateSpringsSetsTheMotorToTheSpringsForceAndNewRate)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), 2, btVector3(0, 0, 0));
	BulletStyleSpring* spring = w.addJoint<BulletStyleSpring>(false, *body, btTransform::getIdentity(), true);
	spring->setLinearLowerLimit(btVector3(0, 1, 0));
	spring->setLinearUpperLimit(btVector3(0, -1, 0));
	spring->enableSpring(1, true);
	spring->setStiffness(1, 50);
	spring->setEquilibriumPoint(1, btScalar(-0.2));  // the body sits 0.2 m above its rest point
	btTypedConstraint::btConstraintInfo2 info;
	memset(&info, 0, sizeof(info));
	info.fps = 240;
	info.m_numIterations = 10;
	spring->updateSprings(&info);
	const btTranslationalLimitMotor* motor = spring->getTranslationalLimitMotor();
	EXPECT_TRUE(motor->m_enableMotor[1]);
	// At rest, stretched 0.2 m: the spring's force is k x = 10 N, and one step of it gives the body
	// the rate -F h / m. Tolerance: float rounding of the products.
	EXPECT_NEAR(motor->m_maxMotorForce[1], 10, 1e-4);
	EXPECT_NEAR(motor->m_targetVelocity[1], -10.0 / 240 / 2, 1e-6);
	EXPECT_FALSE(motor->m_enableMotor[0]) << "a coordinate without a spring keeps its motor off";
}

TEST(Generic6DofSpringConstraint, BulletStyleSubclassOscillatesLikeTheSpringRows)
{
	// The same spring twice: Caliber's spring rows, and a subclass driving the motors.
	const double mass = 2, omega = 2 * M_PI, stiffness = mass * omega * omega;
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* bodies[2];
	btGeneric6DofSpringConstraint* springs[2];
	for (int k = 0; k < 2; ++k)
	{
		bodies[k] =
		    w.addBody(w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), btScalar(mass), btVector3(btScalar(5 * k), 0, 0));
		bodies[k]->setSleepingThresholds(0, 0);
		const btTransform frame(btMatrix3x3::getIdentity(), btVector3(0, 0, 0));
		springs[k] = k == 0 ? w.addJoint<btGeneric6DofSpringConstraint>(false, *bodies[k], frame, true)
		                    : static_cast<btGeneric6DofSpringConstraint*>(
		                          w.addJoint<BulletStyleSpring>(false, *bodies[k], frame, true));
		springs[k]->setLinearLowerLimit(btVector3(0, 1, 0));
		springs[k]->setLinearUpperLimit(btVector3(0, -1, 0));
		springs[k]->setAngularLowerLimit(btVector3(0, 0, 0));
		springs[k]->setAngularUpperLimit(btVector3(0, 0, 0));
		springs[k]->enableSpring(1, true);
		springs[k]->setStiffness(1, btScalar(stiffness));
		springs[k]->setEquilibriumPoint(1, btScalar(-0.2));
	}
	// Bullet enables a spring coordinate's motor with the spring, so getInfo1 counts its row.
	springs[1]->getTranslationalLimitMotor()->m_enableMotor[1] = true;
	CrossingTimer timers[2];
	double maxGap = 0;
	for (int i = 0; i < 480; ++i)
	{
		w.run(1, kH);
		double y[2];
		for (int k = 0; k < 2; ++k) y[k] = double(bodies[k]->getCenterOfMassPosition().y());
		for (int k = 0; k < 2; ++k) timers[k].sample(double(kH) * (i + 1), y[k] + 0.2);
		maxGap = std::max(maxGap, std::fabs(y[0] - y[1]));
	}
	// Both are semi-implicit Euler springs of 1 s period. Tolerance: the motor row reaches the spring's
	// impulse only as the solver's iterations converge with the locked rows beside it; 1 % of the
	// 0.2 m amplitude.
	EXPECT_NEAR(timers[1].period(), timers[0].period(), 1e-3);
	EXPECT_LT(maxGap, 2e-3);
}

TEST(Generic6DofSpringConstraintDeathTest, InternalUpdateSpringsWithoutAStepAsserts)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), 2, btVector3(0, 0, 0));
	BulletStyleSpring* spring = w.addJoint<BulletStyleSpring>(false, *body, btTransform::getIdentity(), true);
	spring->enableSpring(1, true);
	spring->setStiffness(1, 50);
	btTypedConstraint::btConstraintInfo2 info;
	memset(&info, 0, sizeof(info));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(spring->updateSprings(&info), "no step");
#else
	spring->updateSprings(&info);
	EXPECT_FALSE(spring->getTranslationalLimitMotor()->m_enableMotor[1]) << "nothing changes without a step";
#endif
}
