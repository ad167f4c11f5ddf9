// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btConeTwistConstraint: swing and twist limits, locked twist, free motion inside the cone, motor.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "BulletDynamics/ConstraintSolver/btConeTwistConstraint.h"
#include "JointTestUtil.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kG = btScalar(10);

// A capsule hanging 1 m below a world pivot, the joint's twist axis (frame X) pointing down along it.
struct HangingLimb
{
	HangingLimb(TestWorld& w, btScalar swingSpan, btScalar twistSpan)
	{
		limb = w.addBody(w.shape<btCapsuleShape>(btScalar(0.1), btScalar(1.0)), 1, btVector3(0, -1, 0));
		limb->setSleepingThresholds(0, 0);
		btTransform frameInLimb;
		// Frame X along the capsule's axis (y), pointing up to the pivot at the capsule's top (+1 m).
		frameInLimb.setBasis(btMatrix3x3(0, -1, 0, 1, 0, 0, 0, 0, 1));
		frameInLimb.setOrigin(btVector3(0, 1, 0));
		joint = w.addJoint<btConeTwistConstraint>(false, *limb, frameInLimb);
		joint->setLimit(swingSpan, swingSpan, twistSpan);
	}
	// The swing: the angle between the limb's axis and the vertical.
	btScalar swing() const
	{
		const btVector3 axis = limb->getCenterOfMassTransform().getBasis().getColumn(1);
		return btAcos(btMax(btScalar(-1), btMin(btScalar(1), axis.dot(btVector3(0, 1, 0)))));
	}
	btRigidBody* limb;
	btConeTwistConstraint* joint;
};
}  // namespace

TEST(ConeTwistConstraint, SwingStaysInsideTheCone)
{
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar span = btScalar(M_PI / 6);
	HangingLimb h(w, span, btScalar(M_PI));
	h.limb->applyCentralImpulse(btVector3(6, 0, 3));  // a hard kick, far more than the cone allows
	btScalar widest = 0, worstGap = 0;
	for (int i = 0; i < 240; ++i)
	{
		w.run(1);
		widest = btMax(widest, h.swing());
		worstGap = btMax(worstGap, (h.limb->getCenterOfMassTransform()(btVector3(0, 1, 0))).length());
	}
	// The swing limit is speculative (it allows only the approach speed that reaches the cone at the end of
	// the step) and decoupled from the pivot rows, so the limb stops on the cone and the pivot stays shut;
	// what remains is float rounding and the 10 iterations' residual, far below a millimetre or milliradian.
	EXPECT_LT(widest, span + 1e-3);
	EXPECT_GT(widest, span - 0.01) << "the kick reached the cone";
	EXPECT_LT(worstGap, 1e-4);
	std::printf("[ measured ] cone swing: widest %.4f rad against a span of %.4f; pivot gap %.2e m\n", double(widest),
	            double(span), double(worstGap));
	// Settled inside the cone.
	EXPECT_LT(h.swing(), span + 0.01);
}

TEST(ConeTwistConstraint, TwistLimitHoldsAgainstATorque)
{
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar twistSpan = btScalar(0.5);
	HangingLimb h(w, btScalar(M_PI / 4), twistSpan);
	for (int i = 0; i < 120; ++i)
	{
		h.limb->applyTorque(btVector3(0, 0.5, 0));  // about the limb's own axis
		w.run(1);
	}
	h.joint->calcAngleInfo();
	// Held at the limit against a steady torque: the bias brings the overshoot back to the torque's
	// per-step push divided by the bias, tiny here.
	EXPECT_NEAR(btFabs(h.joint->getTwistAngle()), twistSpan, 0.02);
	EXPECT_TRUE(h.joint->getSolveTwistLimit() || btFabs(h.joint->getTwistAngle()) <= twistSpan);
}

TEST(ConeTwistConstraint, ZeroTwistSpanLocksTheTwist)
{
	TestWorld w(btVector3(0, -kG, 0));
	HangingLimb h(w, btScalar(M_PI / 4), 0);
	for (int i = 0; i < 120; ++i)
	{
		h.limb->applyTorque(btVector3(0, 0.5, 0));
		w.run(1);
	}
	h.joint->calcAngleInfo();
	// Locked twist is an equality row in the joint's block and in the position correction.
	EXPECT_LT(btFabs(h.joint->getTwistAngle()), 1e-3);
}

TEST(ConeTwistConstraint, InsideTheConeItSwingsLikeABallJoint)
{
	// A small swing never reaches the 45-degree cone: the period is the free physical pendulum's.
	TestWorld w(btVector3(0, -kG, 0));
	HangingLimb h(w, btScalar(M_PI / 4), btScalar(M_PI / 4));
	// Turning about the pivot at 0.3 rad/s: the centre (1 m below) moves at 0.3 m/s along +x.
	h.limb->setAngularVelocity(btVector3(0, 0, 0.3));
	h.limb->setLinearVelocity(btVector3(0.3, 0, 0));
	caliber_test::CrossingTimer timer;
	const btScalar step = btScalar(1. / 240.);
	for (int i = 0; i < 240 * 6; ++i)
	{
		w.world()->stepSimulation(step, 1, step);
		timer.sample(double(step) * (i + 1), double(h.limb->getCenterOfMassPosition().x()));
	}
	// Capsule: cylinder of height 1 and two hemispheres of radius 0.1; about the pivot at 1 m from the
	// centre the equivalent length is (I_cm + m d^2) / (m d), computed from the body's own inertia.
	const double inertiaCm = 1.0 / double(h.limb->getInvInertiaDiagLocal().z());
	const double inertiaPivot = inertiaCm + 1.0;
	const double equivalent = inertiaPivot / 1.0;
	// Amplitude from energy: I_pivot w^2 / 2 = m g d (1 - cos theta0).
	const double theta0 = std::acos(1.0 - inertiaPivot * 0.3 * 0.3 / (2.0 * kG));
	const double expected = caliber_test::exactPendulumPeriod(equivalent, kG, theta0);
	// Same error budget as the point-to-point pendulum (0.2 %).
	EXPECT_NEAR(timer.period(), expected, 0.002 * expected);
}

TEST(ConeTwistConstraint, MotorDrivesToTheTargetOrientation)
{
	TestWorld w(btVector3(0, 0, 0));
	HangingLimb h(w, btScalar(M_PI / 2), btScalar(M_PI / 2));
	// Target: frame A turned 0.4 rad about its Z relative to frame B, i.e. a 0.4 rad swing.
	h.joint->setMaxMotorImpulse(1);
	h.joint->enableMotor(true);
	h.joint->setMotorTargetInConstraintSpace(btQuaternion(btVector3(0, 0, 1), btScalar(0.4)));
	w.run(120);
	EXPECT_NEAR(h.swing(), 0.4, 0.01);
}

TEST(ConeTwistConstraint, DampingRowsDoNotFightALockedSwing)
{
	// Damping rows are velocity goals bounded like a motor; were they taken for equality rows they would
	// join the locked swing's rows in one block and contradict them (a singular block).
	TestWorld w(btVector3(0, -kG, 0));
	HangingLimb h(w, 0, btScalar(M_PI / 4));  // swing locked, twist free within 45 degrees
	h.joint->setDamping(btScalar(0.5));
	h.limb->applyTorqueImpulse(btVector3(0.3, 0, 0.3));
	btScalar widest = 0;
	for (int i = 0; i < 120; ++i)
	{
		w.run(1);
		widest = btMax(widest, h.swing());
	}
	// The locked swing holds to the solver's rounding (the impulse is mostly about the locked axes).
	EXPECT_LT(widest, 1e-3);
	EXPECT_TRUE(std::isfinite(h.limb->getCenterOfMassPosition().y()));
}

TEST(ConeTwistConstraint, DampingRemovesItsShareOfTheRelativeTurnPerStep)
{
	TestWorld w(btVector3(0, 0, 0));
	HangingLimb h(w, btScalar(M_PI / 2), btScalar(M_PI / 2));
	h.joint->setDamping(btScalar(0.5));
	// Spinning about its own axis (through the pivot, so the pivot does not move): the damping row keeps
	// half of the turn rate each step.
	h.limb->setAngularVelocity(btVector3(0, 2, 0));
	w.run(1);
	EXPECT_NEAR(h.limb->getAngularVelocity().y(), 1.0, 1e-3);
	w.run(1);
	EXPECT_NEAR(h.limb->getAngularVelocity().y(), 0.5, 1e-3);
}

// A NaN or infinite number anywhere in a frame (origin or basis) would give the solver NaN rows: the
// joint asserts, or without asserts is disabled with one warning and leaves its body falling freely.
TEST(ConeTwistConstraint, NonFiniteFrameAssertsOrDisablesTheJointWithAWarning)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btTransform nanOrigin(btQuaternion::getIdentity(), btVector3(0, nan, 0));
	btTransform nanBasis = btTransform::getIdentity();
	nanBasis.getBasis()[1].setZ(std::numeric_limits<btScalar>::infinity());
	for (const btTransform& bad : {nanOrigin, nanBasis})
	{
		TestWorld w(btVector3(0, -kG, 0));
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
#if CALIBER_ASSERTS_ENABLED
		EXPECT_DEATH({ btConeTwistConstraint joint(*body, bad); }, "non-finite frame");
		EXPECT_DEATH(
		    {
			    btConeTwistConstraint joint(*body, btTransform::getIdentity());
			    joint.setFrames(btTransform::getIdentity(), bad);
		    },
		    "non-finite frame");
#else
		caliber_test::WarningCounter warnings;
		btConeTwistConstraint* joint = w.addJoint<btConeTwistConstraint>(false, *body, bad);
		EXPECT_FALSE(joint->isEnabled());
		EXPECT_EQ(warnings.count(), 1) << "one warning for the joint";
		w.run(30);
		// Inert: the body falls freely (semi-implicit Euler: -g h^2 n (n + 1) / 2 = -1.29 m).
		EXPECT_NEAR(body->getCenterOfMassPosition().y(), -10.0 / 3600 * 30 * 31 / 2, 1e-4);
		btConeTwistConstraint* later = w.addJoint<btConeTwistConstraint>(false, *body, btTransform::getIdentity());
		EXPECT_TRUE(later->isEnabled());
		later->setFrames(btTransform::getIdentity(), bad);
		EXPECT_FALSE(later->isEnabled()) << "setFrames is checked too";
		EXPECT_EQ(warnings.count(), 2);
#endif
	}
}
