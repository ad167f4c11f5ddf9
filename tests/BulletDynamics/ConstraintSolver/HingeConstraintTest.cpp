// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btHingeConstraint: angle convention, limits, motors, amplitude kept over long swings, bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "BulletDynamics/ConstraintSolver/btHingeConstraint.h"
#include "JointTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kG = btScalar(10);

// A bob of radius 0.1 on a 1 m arm hinged to the world about z at the origin, released at theta0.
struct HingePendulum
{
	explicit HingePendulum(btScalar theta0, TestWorld& w)
	{
		btTransform pose(btQuaternion(btVector3(0, 0, 1), theta0), btVector3(btSin(theta0), -btCos(theta0), 0));
		bob = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1, pose);
		bob->setSleepingThresholds(0, 0);
		hinge = w.addJoint<btHingeConstraint>(false, *bob, btVector3(0, 1, 0), btVector3(0, 0, 1));
	}
	btScalar angle() const { return btAtan2(bob->getCenterOfMassPosition().x(), -bob->getCenterOfMassPosition().y()); }
	btRigidBody* bob;
	btHingeConstraint* hinge;
};
}  // namespace

TEST(HingeConstraint, HingeAngleIsTheTurnOfAAgainstB)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.1, 0.1)), 1, btVector3(0, 0, 0));
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(false, *body, btVector3(0, 0, 0), btVector3(0, 0, 1));
	EXPECT_NEAR(hinge->getHingeAngle(), 0, 1e-6);
	body->setCenterOfMassTransform(btTransform(btQuaternion(btVector3(0, 0, 1), btScalar(0.4)), btVector3(0, 0, 0)));
	// Body A is turned +0.4 rad about the axis against the world (B).
	EXPECT_NEAR(hinge->getHingeAngle(), 0.4, 1e-5);
	hinge->setUseReferenceFrameA(true);
	EXPECT_NEAR(hinge->getHingeAngle(), -0.4, 1e-5);
}

TEST(HingeConstraint, PendulumAmplitudeChangesLessThanOneHundredthOfARadianInTwentySeconds)
{
	// Bullet 3.24 loses 0.087 rad from 60 degrees in 20 s at 10 iterations and 1/60 s. With no damping
	// the exact motion keeps its amplitude; what is lost is numerical dissipation.
	TestWorld w(btVector3(0, -kG, 0));
	HingePendulum p(btScalar(M_PI / 3), w);
	btScalar lastPeak = 0, previous = p.angle(), slope = 0;
	for (int i = 0; i < 60 * 20; ++i)
	{
		w.run(1);
		const btScalar a = p.angle();
		const btScalar newSlope = a - previous;
		if (slope > 0 && newSlope <= 0) lastPeak = previous;  // a maximum on the positive side
		slope = newSlope;
		previous = a;
	}
	const btScalar loss = btScalar(M_PI / 3) - lastPeak;
	// The velocity rows predict the anchor's turning drift and the position correction closes what is
	// left without adding velocity, so the amplitude is neither bled away by error correction nor pumped
	// up. The peak is sampled at 1/60 s: near the turning point the angle changes by at most
	// (g/L) sin(60 deg) h^2 / 2 = 1.2e-3 rad between samples, so sampling hides at most that much.
	// Neither lost nor gained: the bound is 0.01 rad either way.
	EXPECT_LT(btFabs(loss), 0.01) << "amplitude lost " << loss;
	EXPECT_GT(lastPeak, 0.9) << "still swinging";
	std::printf("[ measured ] hinge pendulum amplitude loss over 20 s: %.5f rad\n", double(loss));
}

TEST(HingeConstraint, LimitsHoldAgainstADrivingTorque)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* door = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 1, 0.05)), 10, btVector3(0.5, 0, 0));
	door->setSleepingThresholds(0, 0);
	// Hinged about y at the door's edge (x = 0); limits -30..+45 degrees.
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(false, *door, btVector3(-0.5, 0, 0), btVector3(0, 1, 0));
	const btScalar low = btScalar(-M_PI / 6), high = btScalar(M_PI / 4);
	hinge->setLimit(low, high);
	btScalar highest = -10, lowest = 10;
	for (int i = 0; i < 240; ++i)
	{
		// Torque about y flips sign every second: the door is driven into each limit in turn.
		door->applyTorque(btVector3(0, (i / 60) % 2 ? -20 : 20, 0));
		w.run(1);
		highest = btMax(highest, hinge->getHingeAngle());
		lowest = btMin(lowest, hinge->getHingeAngle());
	}
	// The limit row is speculative: inside the range it allows only the approach speed that reaches the
	// limit at the end of the step, so the door stops at the limit instead of overshooting by a step's
	// travel (about 3 rad/s * 1/60 s = 0.05 rad at these speeds). What remains is the limit row's
	// Gauss-Seidel coupling with the hinge's other rows: well under a milliradian.
	EXPECT_LT(highest, high + 1e-3);
	EXPECT_GT(lowest, low - 1e-3);
	std::printf("[ measured ] hinge limit overshoot: %.2e above, %.2e below\n", double(highest - high),
	            double(low - lowest));
	EXPECT_GT(highest, high - 0.01) << "the torque reached the limit";
	EXPECT_LT(lowest, low + 0.01);
	// Held against the torque, it rests at the limit.
	EXPECT_NEAR(hinge->getHingeAngle(), low, 0.01);
}

TEST(HingeConstraint, MotorReachesItsTargetVelocityLimitedByItsMaximumImpulse)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* wheel = w.addBody(w.shape<btCylinderShapeZ>(btVector3(0.5, 0.5, 0.1)), 2, btVector3(0, 0, 0));
	wheel->setSleepingThresholds(0, 0);
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(false, *wheel, btVector3(0, 0, 0), btVector3(0, 0, 1));
	const btScalar inertia = btScalar(1) / wheel->getInvInertiaDiagLocal().z();
	const btScalar maxImpulse = btScalar(0.01), target = btScalar(3);
	hinge->enableAngularMotor(true, target, maxImpulse);
	w.run(10);
	// Impulse-limited: the spin grows by maxImpulse / I per step.
	EXPECT_NEAR(wheel->getAngularVelocity().z(), 10 * maxImpulse / inertia, 1e-4);
	w.run(600);
	EXPECT_NEAR(wheel->getAngularVelocity().z(), target, 1e-3);
}

TEST(HingeConstraint, MotorTargetAngleIsReached)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* arm = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.1, 0.1)), 1, btVector3(0.5, 0, 0));
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(false, *arm, btVector3(-0.5, 0, 0), btVector3(0, 0, 1));
	hinge->enableMotor(true);
	hinge->setMaxMotorImpulse(10);
	for (int i = 0; i < 120; ++i)
	{
		hinge->setMotorTarget(btScalar(1.0), btScalar(0.25));
		w.run(1);
	}
	EXPECT_NEAR(hinge->getHingeAngle(), 1.0, 1e-3);
}

TEST(HingeConstraint, AccumulatedAngleCountsWholeTurns)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* wheel = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(0, 0, 0));
	wheel->setSleepingThresholds(0, 0);
	btHingeAccumulatedAngleConstraint* hinge =
	    w.addJoint<btHingeAccumulatedAngleConstraint>(false, *wheel, btVector3(0, 0, 0), btVector3(0, 0, 1));
	hinge->enableAngularMotor(true, btScalar(2 * M_PI), 100);  // one turn per second
	w.run(150);
	// 2.5 s at one turn per second (the motor reaches its speed in the first step).
	EXPECT_NEAR(hinge->getAccumulatedHingeAngle(), 2.5 * 2 * M_PI, 0.02);
}

TEST(HingeConstraint, AxesStayAlignedBetweenTwoBodies)
{
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.5, 0.1, 0.1));
	btRigidBody* upper = w.addBody(box, 1, btVector3(0.5, 0, 0));
	btRigidBody* lower = w.addBody(box, 1, btVector3(1.5, 0, 0));
	upper->setSleepingThresholds(0, 0);
	lower->setSleepingThresholds(0, 0);
	w.addJoint<btHingeConstraint>(true, *upper, btVector3(-0.5, 0, 0), btVector3(0, 0, 1));
	w.addJoint<btHingeConstraint>(true, *upper, *lower, btVector3(0.5, 0, 0), btVector3(-0.5, 0, 0), btVector3(0, 0, 1),
	                              btVector3(0, 0, 1));
	btScalar worstTilt = 0, worstGap = 0;
	for (int i = 0; i < 600; ++i)
	{
		w.run(1);
		const btVector3 axisUpper = upper->getCenterOfMassTransform().getBasis().getColumn(2);
		const btVector3 axisLower = lower->getCenterOfMassTransform().getBasis().getColumn(2);
		worstTilt = btMax(worstTilt, axisUpper.cross(axisLower).length());
		worstGap = btMax(worstGap, caliber_test::pivotGap(*upper, btVector3(0.5, 0, 0), *lower, btVector3(-0.5, 0, 0)));
	}
	// A double pendulum swinging in its plane: nothing pushes out of the plane, and the hinge rows are
	// solved as one block per joint, so the axes stay aligned to rounding and the pivot gap small.
	EXPECT_LT(worstTilt, 1e-3);
	EXPECT_LT(worstGap, 0.01);
	std::printf("[ measured ] double hinge pendulum: worst gap %.5f m, worst axis tilt %.2e\n", double(worstGap),
	            double(worstTilt));
}

TEST(HingeConstraint, ZeroLengthAxisIsReportedAndTheJointIsInert)
{
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btHingeConstraint(*body, btVector3(0, 0, 0), btVector3(0, 0, 0)), "hinge axis");
#else
	WarningCounter warnings;
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(false, *body, btVector3(0, 0, 0), btVector3(0, 0, 0));
	EXPECT_EQ(warnings.count(), 1);
	EXPECT_FALSE(hinge->isEnabled());
	w.run(30);
	EXPECT_LT(body->getCenterOfMassPosition().y(), -1) << "the inert joint holds nothing; the body falls";
	EXPECT_TRUE(std::isfinite(body->getCenterOfMassPosition().y()));
#endif
}

TEST(HingeConstraint, ZeroRangeLimitLocksTheHinge)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* door = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 1, 0.05)), 10, btVector3(0.5, 0, 0));
	door->setSleepingThresholds(0, 0);
	btHingeConstraint* hinge = w.addJoint<btHingeConstraint>(false, *door, btVector3(-0.5, 0, 0), btVector3(0, 1, 0));
	hinge->setLimit(btScalar(0.2), btScalar(0.2));  // locked at 0.2 rad
	EXPECT_FALSE(hinge->hasLimit()) << "as in Bullet: a zero range is not a range";
	for (int i = 0; i < 120; ++i)
	{
		door->applyTorque(btVector3(0, i < 60 ? 20 : -20, 0));
		w.run(1);
	}
	// Pushed both ways, it stays at the locked angle: the limit row's bias holds it within what one
	// step's torque can push (alpha h^2 = 6 rad/s^2 / 3600 s^-2 = 1.7 mrad) over the bias.
	EXPECT_NEAR(hinge->getHingeAngle(), 0.2, 0.01);
}
