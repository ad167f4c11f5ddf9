// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btUniversalConstraint: the anchor holds, the two cross axes turn freely, twist is transmitted with the
// Cardan joint's velocity ratio, limits hold, and unusable axes are reported.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "BulletDynamics/ConstraintSolver/btUniversalConstraint.h"
#include "JointTestUtil.h"

using caliber_test::CrossingTimer;
using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kG = btScalar(10);
const btScalar kH = btScalar(1. / 240.);

double inertiaAbout(const btRigidBody* body, int i) { return 1.0 / double(body->getInvInertiaDiagLocal()[i]); }

// A box hanging 0.9 m below the anchor at the origin, from a static body by a universal joint with
// axis 1 = world x and axis 2 = world z. The box is built turned by theta0 about world axis `swing`.
struct UniversalPendulum
{
	TestWorld world{btVector3(0, -kG, 0)};
	btRigidBody* support;
	btRigidBody* bob;
	btUniversalConstraint* joint;
	const double d = 0.9;

	UniversalPendulum(const btVector3& swing, double theta0)
	{
		support = world.addBody(world.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), 0, btVector3(0, 0.2, 0));
		const btQuaternion tilt(swing, btScalar(theta0));
		bob = world.addBody(world.shape<btBoxShape>(btVector3(0.1, 0.15, 0.2)), 2,
		                    btTransform(tilt, btMatrix3x3(tilt) * btVector3(0, btScalar(-d), 0)));
		bob->setSleepingThresholds(0, 0);
		joint = world.addJoint<btUniversalConstraint>(true, *support, *bob, btVector3(0, 0, 0), btVector3(1, 0, 0),
		                                              btVector3(0, 0, 1));
	}

	btScalar anchorGap() { return (bob->getCenterOfMassTransform()(joint->getFrameOffsetB().getOrigin())).length(); }
};
}  // namespace

TEST(UniversalConstraint, BothCrossAxesSwingLikeHingePendulumsAndTheAnchorHolds)
{
	const double theta0 = 0.5;
	for (int axis = 0; axis < 2; ++axis)
	{
		const btVector3 swing = axis == 0 ? btVector3(1, 0, 0) : btVector3(0, 0, 1);
		UniversalPendulum p(swing, theta0);
		const int local = axis == 0 ? 0 : 2;  // the bob's local axis along the swing axis
		const double exact = caliber_test::exactPendulumPeriod((inertiaAbout(p.bob, local) + 2 * p.d * p.d) / (2 * p.d),
		                                                       double(kG), theta0);
		CrossingTimer timer;
		btScalar worstGap = 0, largestOther = 0;
		for (int i = 0; i < 240 * 6; ++i)
		{
			p.world.run(1, kH);
			const btVector3 position = p.bob->getCenterOfMassPosition();
			timer.sample(double(kH) * (i + 1), double(axis == 0 ? position.z() : position.x()));
			worstGap = btMax(worstGap, p.anchorGap());
			p.joint->calculateTransforms();
			largestOther = btMax(largestOther, btFabs(axis == 0 ? p.joint->getAngle2() : p.joint->getAngle1()));
		}
		// Tolerance: semi-implicit Euler's phase error (omega h)^2 / 12 = 1.5e-5, the joint's residual
		// motion smaller still, and the zero-crossing interpolation: 5e-4. The amplitude adds 1.6 %.
		EXPECT_NEAR(timer.period(), exact, 5e-4 * exact) << "swing about axis " << axis + 1;
		// Tolerance: the rows hold the anchor's relative velocity at zero; what is left is the
		// second-order drift of one step of turning, (w h)^2 d / 2 = 2e-5 m at the fastest w = 1.6 rad/s,
		// which the error reduction (erp = 0.2 per step) holds at drift / erp = 1e-4 m.
		EXPECT_LT(worstGap, btScalar(1.5e-4));
		EXPECT_LT(largestOther, btScalar(1e-4)) << "a swing about one axis does not turn the other";
	}
}

TEST(UniversalConstraint, TwistAboutTheThirdAxisIsLockedAndGoesToTheOtherBody)
{
	UniversalPendulum p(btVector3(1, 0, 0), 0);
	btJointFeedback feedback;
	p.joint->setJointFeedback(&feedback);
	p.joint->enableFeedback(true);
	// A steady twisting torque about the vertical (the third axis, perpendicular to both cross axes).
	const btVector3 torque(0, 3, 0);
	for (int i = 0; i < 120; ++i)
	{
		p.bob->applyTorque(torque);
		p.world.run(1, kH);
	}
	p.joint->calculateTransforms();
	// The twist is locked: the bob does not turn, and the joint hands the whole torque to the support.
	// Tolerance: the bob hangs still, so only float rounding of impulse / h remains.
	EXPECT_LT(p.bob->getAngularVelocity().length(), btScalar(1e-5));
	EXPECT_NEAR(p.joint->getAngle(0), 0, 1e-5);
	EXPECT_NEAR(feedback.m_appliedTorqueBodyB.y(), -torque.y(), 1e-3 * torque.y());
	EXPECT_NEAR(feedback.m_appliedTorqueBodyA.y(), torque.y(), 1e-3 * torque.y());
}

TEST(UniversalConstraint, BentShaftsTurnWithTheCardanVelocityRatio)
{
	// Input shaft A along x and output shaft B along u, bent by phi at the joint; each turns on a bearing
	// (a 6dof joint to the world whose only free coordinate is the turn about its own axis). A is driven
	// at a constant 1 rad/s. The cross has arm 1 on A along z (perpendicular to the shafts' plane at the
	// start) and arm 2 on B, perpendicular to u and to arm 1.
	const btScalar phi = btScalar(0.5);
	const btVector3 u(btCos(phi), btSin(phi), 0);
	TestWorld w(btVector3(0, 0, 0));
	btCollisionShape* shaft = w.shape<btBoxShape>(btVector3(0.5, 0.05, 0.05));
	btRigidBody* a = w.addBody(shaft, 1, btVector3(-0.6, 0, 0));
	btRigidBody* b = w.addBody(shaft, 1, btTransform(btQuaternion(btVector3(0, 0, 1), phi), u * btScalar(0.6)));
	btGeneric6DofConstraint* bearings[2];
	for (int k = 0; k < 2; ++k)
	{
		btRigidBody* body = k == 0 ? a : b;
		body->setSleepingThresholds(0, 0);
		bearings[k] = w.addJoint<btGeneric6DofConstraint>(false, *body, btTransform::getIdentity(), true);
		bearings[k]->setAngularLowerLimit(btVector3(1, 0, 0));  // turn about the shaft free
		bearings[k]->setAngularUpperLimit(btVector3(-1, 0, 0));
	}
	btRotationalLimitMotor* drive = bearings[0]->getRotationalLimitMotor(0);
	drive->m_enableMotor = true;
	drive->m_targetVelocity = 1;
	drive->m_maxMotorForce = 1000;
	btUniversalConstraint* cross = w.addJoint<btUniversalConstraint>(true, *a, *b, btVector3(0, 0, 0),
	                                                                 btVector3(0, 0, 1), btVector3(-u.y(), u.x(), 0));
	w.run(24, kH);
	// Over one turn of A: w_B / w_A = cos phi / (1 - sin^2 phi sin^2 theta), theta A's turn from the start
	// (arm 1 perpendicular to the shafts' plane gives the slowest output, cos phi; in the plane, the
	// fastest, 1 / cos phi).
	const double c = std::cos(double(phi)), s2 = std::sin(double(phi)) * std::sin(double(phi));
	double worst = 0, slowest = 10, fastest = 0, worstTurn = 0;
	const int steps = int(2 * M_PI / double(kH)) + 1;
	for (int i = 0; i < steps; ++i)
	{
		w.run(1, kH);
		bearings[0]->calculateTransforms();
		// The rows held the velocities to the joint's Jacobian at the step's start: A's angle one step back.
		const double inputRate = double(a->getAngularVelocity().x());
		const double theta = double(bearings[0]->getAngle(0)) - inputRate * double(kH);
		const double ratio = double(b->getAngularVelocity().dot(u)) / inputRate;
		const double expected = c / (1 - s2 * std::sin(theta) * std::sin(theta));
		worst = std::max(worst, std::fabs(ratio - expected));
		slowest = std::min(slowest, ratio);
		fastest = std::max(fastest, ratio);
		// Integrated, the ratio is the Cardan joint's turn relation tan(theta_B) = cos(phi) tan(theta_A).
		bearings[1]->calculateTransforms();
		const double thetaA = double(bearings[0]->getAngle(0)), thetaB = double(bearings[1]->getAngle(0));
		const double expectedB = std::atan2(c * std::sin(thetaA), std::cos(thetaA));
		worstTurn = std::max(worstTurn, std::fabs(double(btNormalizeAngle(btScalar(thetaB - expectedB)))));
	}
	// Tolerances: the three joints are solved one after another (10 sweeps) and their anchor rows are
	// redundant (both bearings and the cross hold the anchor), so the rates keep a residual of a few 1e-4;
	// 1.5e-3 is well below the 0.14 swing of the ratio that is checked.
	EXPECT_LT(worst, 1.5e-3);
	EXPECT_NEAR(slowest, c, 1e-3);
	EXPECT_NEAR(fastest, 1 / c, 1e-3);
	// Positions: the joints hold the positions (their drift is held by the error reduction); the
	// relation itself departs from theta_A by up to 0.065 rad.
	EXPECT_LT(worstTurn, 1e-4);
	(void)cross;
}

TEST(UniversalConstraint, LimitsHoldEachTurnToItsOwnRange)
{
	for (int axis = 0; axis < 2; ++axis)
	{
		UniversalPendulum p(btVector3(1, 0, 0), 0);
		// Different ranges for the two turns, so that a mix-up shows.
		p.joint->setLowerLimit(btScalar(-0.3), btScalar(-0.2));
		p.joint->setUpperLimit(btScalar(0.3), btScalar(0.2));
		// A kick about axis 1 (world x) or axis 2 (world z) that would swing the bob up to about 1 rad.
		p.bob->setAngularVelocity(axis == 0 ? btVector3(3, 0, 0) : btVector3(0, 0, 3));
		p.bob->setLinearVelocity(p.bob->getAngularVelocity().cross(p.bob->getCenterOfMassPosition()));
		btScalar largest = 0;
		for (int i = 0; i < 240; ++i)
		{
			p.world.run(1, kH);
			p.joint->calculateTransforms();
			largest = btMax(largest, btFabs(axis == 0 ? p.joint->getAngle1() : p.joint->getAngle2()));
		}
		const btScalar limit = axis == 0 ? btScalar(0.3) : btScalar(0.2);
		// Tolerance: the limit row closes exactly the remaining gap in the arrival step; float rounding.
		EXPECT_LT(largest, limit + btScalar(1e-5)) << "axis " << axis + 1;
		EXPECT_GT(largest, limit - btScalar(1e-5)) << "it reached the limit";
		EXPECT_LT(p.anchorGap(), btScalar(1e-4));
	}
}

TEST(UniversalConstraint, AnchorAndAxesAreReportedAsGiven)
{
	TestWorld w(btVector3(0, 0, 0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1));
	btRigidBody* a = w.addBody(box, 1, btVector3(-1, 0, 0));
	btRigidBody* b = w.addBody(box, 1, btVector3(1, 0, 0));
	btUniversalConstraint joint(*a, *b, btVector3(0, 0.5, 0), btVector3(0, 0, 2), btVector3(0, 3, 0));
	EXPECT_TRUE(joint.isEnabled());
	EXPECT_LT((joint.getAnchor() - btVector3(0, 0.5, 0)).length(), btScalar(1e-6));
	EXPECT_LT((joint.getAnchor2() - btVector3(0, 0.5, 0)).length(), btScalar(1e-6));
	EXPECT_EQ(joint.getAxis1(), btVector3(0, 0, 1));
	EXPECT_EQ(joint.getAxis2(), btVector3(0, 1, 0));
	EXPECT_NEAR(joint.getAngle1(), 0, 1e-6);
	EXPECT_NEAR(joint.getAngle2(), 0, 1e-6);
	// Turning B by 0.2 about axis 1 (world z) shows in angle 1 only.
	btTransform turned = b->getCenterOfMassTransform();
	turned.setBasis(btMatrix3x3(btQuaternion(btVector3(0, 0, 1), btScalar(0.2))));
	joint.calculateTransforms(a->getCenterOfMassTransform(), turned);
	EXPECT_NEAR(joint.getAngle1(), 0.2, 1e-5);
	EXPECT_NEAR(joint.getAngle2(), 0, 1e-5);
	EXPECT_EQ(joint.getConstraintType(), D6_CONSTRAINT_TYPE);
}

TEST(UniversalConstraint, NonPerpendicularAxesAreReportedAndMadePerpendicular)
{
	WarningCounter warnings;
	UniversalPendulum reference(btVector3(1, 0, 0), 0);
	TestWorld& w = reference.world;
	btRigidBody* a = w.addBody(w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), 0, btVector3(5, 0.2, 0));
	btRigidBody* b = w.addBody(w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)), 1, btVector3(5, -0.9, 0));
	b->setSleepingThresholds(0, 0);
	const btVector3 tilted(btSin(btScalar(0.2)), 0, btCos(btScalar(0.2)));  // 78.5 degrees from axis 1 = x
	btUniversalConstraint* joint =
	    w.addJoint<btUniversalConstraint>(true, *a, *b, btVector3(5, 0, 0), btVector3(1, 0, 0), tilted);
	EXPECT_EQ(warnings.count(), 1);
	EXPECT_TRUE(joint->isEnabled());
	EXPECT_NEAR(joint->getAxis1().dot(joint->getAxis2()), 0, 1e-6);
	EXPECT_NEAR(joint->getAxis2().length(), 1, 1e-6);
	b->setLinearVelocity(btVector3(1, 0, 1));
	w.run(120, kH);
	EXPECT_LT((b->getCenterOfMassTransform()(joint->getFrameOffsetB().getOrigin()) - btVector3(5, 0, 0)).length(),
	          btScalar(1e-4));
}

TEST(UniversalConstraint, ZeroOrParallelAxesAreReported)
{
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1));
	btRigidBody* a = w.addBody(box, 0, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(box, 1, btVector3(0, -1, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btUniversalConstraint(*a, *b, btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1)), "axes");
	EXPECT_DEATH(btUniversalConstraint(*a, *b, btVector3(0, 0, 0), btVector3(0, 0, 1), btVector3(0, 0, -2)), "axes");
#else
	WarningCounter warnings;
	btUniversalConstraint* zero =
	    w.addJoint<btUniversalConstraint>(true, *a, *b, btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1));
	btUniversalConstraint* parallel =
	    w.addJoint<btUniversalConstraint>(true, *a, *b, btVector3(0, 0, 0), btVector3(0, 0, 1), btVector3(0, 0, -2));
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_FALSE(zero->isEnabled());
	EXPECT_FALSE(parallel->isEnabled());
	w.run(30);
	EXPECT_TRUE(std::isfinite(double(b->getCenterOfMassPosition().y())));
	EXPECT_LT(b->getCenterOfMassPosition().y(), btScalar(-1.5)) << "with no joint it falls";
#endif
}
