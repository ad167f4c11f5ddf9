// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btPoint2PointConstraint and the joint machinery every joint shares: rows through the solver,
// feedback, breaking, the fixed body, islands, collision filtering between linked bodies, removal.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "Caliber/JointPositionCorrection.h"
#include "JointTestUtil.h"

using caliber_test::CrossingTimer;
using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kG = btScalar(10);

// A small sphere hanging at distance L below a world pivot at the origin, released at angle theta0
// (about z); returns the measured period of x(t) over several swings.
double measurePendulumPeriod(double L, double theta0, double radius, btScalar h, int steps)
{
	TestWorld w(btVector3(0, -kG, 0));
	btTransform pose(btQuaternion(btVector3(0, 0, 1), btScalar(theta0)),
	                 btVector3(btScalar(L * std::sin(theta0)), btScalar(-L * std::cos(theta0)), 0));
	btRigidBody* bob = w.addBody(w.shape<btSphereShape>(btScalar(radius)), 1, pose);
	bob->setSleepingThresholds(0, 0);
	w.addJoint<btPoint2PointConstraint>(false, *bob, btVector3(0, btScalar(L), 0));
	CrossingTimer timer;
	for (int i = 0; i < steps; ++i)
	{
		w.world()->stepSimulation(h, 1, h);
		timer.sample(double(h) * (i + 1), double(bob->getCenterOfMassPosition().x()));
	}
	return timer.period();
}
}  // namespace

TEST(Point2PointConstraint, PendulumPeriodMatchesTheExactLargeAmplitudePeriod)
{
	// A sphere of radius r on a massless rod is a physical pendulum of equivalent length
	// L + (2/5) r^2 / L. Released at 60 degrees its period is 7.3 % longer than the small-angle one.
	const double L = 1.0, r = 0.05, theta0 = M_PI / 3;
	const double equivalent = L + 0.4 * r * r / L;
	const double exact = caliber_test::exactPendulumPeriod(equivalent, kG, theta0);
	const double measured = measurePendulumPeriod(L, theta0, r, btScalar(1. / 240.), 240 * 8);
	// Tolerance: semi-implicit Euler's phase error (omega h)^2 / 12 is 1.5e-5 at this step; the rest is
	// the joint's residual error (ERP correction), well under 0.2 %. The large-amplitude correction it
	// must resolve is 7.3 %.
	EXPECT_NEAR(measured, exact, 0.002 * exact);
	EXPECT_GT(measured, 1.05 * 2 * M_PI * std::sqrt(equivalent / kG));
}

TEST(Point2PointConstraint, SmallSwingPeriodIsTwoPiSqrtLOverG)
{
	const double L = 0.5, r = 0.02, theta0 = 0.05;
	const double equivalent = L + 0.4 * r * r / L;
	const double smallAngle = 2 * M_PI * std::sqrt(equivalent / kG);
	const double measured = measurePendulumPeriod(L, theta0, r, btScalar(1. / 240.), 240 * 6);
	// At 0.05 rad the finite-amplitude correction is theta0^2 / 16 = 1.6e-4; same error budget as above.
	EXPECT_NEAR(measured, smallAngle, 0.002 * smallAngle);
}

TEST(Point2PointConstraint, FeedbackReportsTheWeightOfAHangingMass)
{
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar mass = 3;
	btRigidBody* bob = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), mass, btVector3(0, -1, 0));
	btPoint2PointConstraint* joint = w.addJoint<btPoint2PointConstraint>(false, *bob, btVector3(0, 1, 0));
	btJointFeedback feedback;
	joint->setJointFeedback(&feedback);
	joint->enableFeedback(true);
	w.run(60);
	// At rest the joint carries the weight: force on the bob m g upwards, on the world m g downwards.
	// Tolerance: the bob hangs still, so only float rounding of the impulse / h remains.
	EXPECT_NEAR(feedback.m_appliedForceBodyA.y(), mass * kG, 1e-3 * mass * kG);
	EXPECT_NEAR(feedback.m_appliedForceBodyA.x(), 0, 1e-3);
	EXPECT_NEAR(feedback.m_appliedForceBodyB.y(), -mass * kG, 1e-3 * mass * kG);
	EXPECT_NEAR(joint->getAppliedImpulse(), mass * kG / 60, 1e-3 * mass * kG / 60);
	EXPECT_NEAR(bob->getCenterOfMassPosition().y(), -1, 1e-4);
}

TEST(Point2PointConstraint, BreakingThresholdBreaksAtTheImpulseItNamesAndNotBefore)
{
	// Holding a mass m at rest takes an impulse of m g h per step along the vertical row.
	const btScalar mass = 2, h = btScalar(1. / 60.);
	const btScalar holding = mass * kG * h;
	for (int trial = 0; trial < 2; ++trial)
	{
		const bool strongEnough = trial == 0;
		TestWorld w(btVector3(0, -kG, 0));
		btRigidBody* bob = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), mass, btVector3(0, -1, 0));
		btPoint2PointConstraint* joint = w.addJoint<btPoint2PointConstraint>(false, *bob, btVector3(0, 1, 0));
		joint->setBreakingImpulseThreshold(holding * (strongEnough ? btScalar(1.02) : btScalar(0.98)));
		w.run(120, h);
		EXPECT_EQ(joint->isEnabled(), strongEnough);
		if (strongEnough)
			EXPECT_NEAR(bob->getCenterOfMassPosition().y(), -1, 1e-3);
		else  // it broke in the first step and the bob fell freely for two seconds
			EXPECT_LT(bob->getCenterOfMassPosition().y(), -15);
	}
}

TEST(Point2PointConstraint, OneBodyJointHoldsTheBodyToTheWorldAtItsPivot)
{
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.1, 0.1)), 1, btVector3(3, 2, 1));
	// Pivot at the box's right end: the box swings down about that end.
	btPoint2PointConstraint* joint = w.addJoint<btPoint2PointConstraint>(false, *box, btVector3(0.5, 0, 0));
	EXPECT_EQ(&joint->getRigidBodyB(), &btTypedConstraint::getFixedBody());
	EXPECT_EQ(joint->getPivotInB(), btVector3(3.5, 2, 1));
	btScalar worst = 0, lowest = 2;
	for (int i = 0; i < 240; ++i)
	{
		w.run(1);
		worst = btMax(worst, (box->getCenterOfMassTransform()(btVector3(0.5, 0, 0)) - btVector3(3.5, 2, 1)).length());
		lowest = btMin(lowest, box->getCenterOfMassPosition().y());
	}
	EXPECT_LT(worst, btScalar(0.01));
	EXPECT_LT(lowest, btScalar(1.8)) << "it swung down";
	EXPECT_EQ(btTypedConstraint::getFixedBody().getInvMass(), btScalar(0));
}

TEST(Point2PointConstraint, LinkedBodiesShareAnIslandAndSleepAndWakeTogether)
{
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* upper = w.addBody(ball, 1, btVector3(0, -1, 0));
	btRigidBody* lower = w.addBody(ball, 1, btVector3(0, -2, 0));
	w.addJoint<btPoint2PointConstraint>(false, *upper, btVector3(0, 1, 0));
	w.addJoint<btPoint2PointConstraint>(false, *upper, *lower, btVector3(0, -0.5, 0), btVector3(0, 0.5, 0));
	w.run(2);
	EXPECT_EQ(upper->getIslandTag(), lower->getIslandTag()) << "they never touch; the joint unites them";
	w.run(240);
	EXPECT_EQ(upper->getActivationState(), ISLAND_SLEEPING);
	EXPECT_EQ(lower->getActivationState(), ISLAND_SLEEPING);
	lower->applyCentralImpulse(btVector3(1, 0, 0));
	lower->activate();
	w.run(1);
	EXPECT_TRUE(upper->isActive()) << "waking one wakes the island";
	EXPECT_NE(upper->getCenterOfMassPosition().x(), btScalar(0));
}

TEST(Point2PointConstraint, DisableCollisionsBetweenLinkedBodiesIsHonoured)
{
	for (int trial = 0; trial < 2; ++trial)
	{
		const bool disable = trial == 0;
		TestWorld w(btVector3(0, 0, 0));
		btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
		btRigidBody* a = w.addBody(box, 1, btVector3(0, 0, 0));
		btRigidBody* b = w.addBody(box, 1, btVector3(0.8, 0, 0));  // overlapping by 0.2
		w.addJoint<btPoint2PointConstraint>(disable, *a, *b, btVector3(0.4, 0, 0), btVector3(-0.4, 0, 0));
		w.run(1);
		int contacts = 0;
		for (int i = 0; i < w.dispatcher()->getNumManifolds(); ++i)
			contacts += w.dispatcher()->getManifoldByIndexInternal(i)->getNumContacts();
		if (disable)
			EXPECT_EQ(contacts, 0);
		else
			EXPECT_GT(contacts, 0);
		EXPECT_EQ(a->checkCollideWith(b), !disable);
	}
}

namespace
{
// A user-written joint through the row interface: one row driving body A's x velocity to a target.
class VelocityDrive : public btTypedConstraint
{
public:
	VelocityDrive(btRigidBody& body, btScalar target)
	    : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, body), m_target(target)
	{
	}
	void getInfo1(btConstraintInfo1* info) override
	{
		info->m_numConstraintRows = 1;
		info->nub = 0;
	}
	void getInfo2(btConstraintInfo2* info) override
	{
		info->m_J1linearAxis[0] = 1;
		info->m_J2linearAxis[0] = -1;
		info->m_constraintError[0] = m_target;
		info->m_lowerLimit[0] = -0.5;  // at most 0.5 N s per step
		info->m_upperLimit[0] = 0.5;
	}
	void setParam(int, btScalar, int) override {}
	btScalar getParam(int, int) const override { return 0; }

private:
	btScalar m_target;
};
}  // namespace

TEST(TypedConstraint, UserWrittenJointDrivesThroughTheRowInterfaceWithinItsBounds)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 2, btVector3(0, 0, 0));
	w.addJoint<VelocityDrive>(false, *body, btScalar(3));
	w.run(1);
	// The bound allows 0.5 N s per step: 0.25 m/s for 2 kg.
	EXPECT_NEAR(body->getLinearVelocity().x(), 0.25, 1e-5);
	w.run(20);
	EXPECT_NEAR(body->getLinearVelocity().x(), 3, 1e-4);
}

TEST(TypedConstraint, RemovingABodyTakesItsJointsOutOfTheWorld)
{
	WarningCounter warnings;
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* a = w.addBody(ball, 1, btVector3(0, -1, 0));
	btRigidBody* b = w.addBody(ball, 1, btVector3(0, -2, 0));
	btPoint2PointConstraint* joint =
	    w.addJoint<btPoint2PointConstraint>(true, *a, *b, btVector3(0, -0.5, 0), btVector3(0, 0.5, 0));
	w.world()->removeRigidBody(a);
	EXPECT_EQ(w.world()->getNumConstraints(), 0);
	EXPECT_EQ(a->getNumConstraintRefs(), 0);
	EXPECT_EQ(b->getNumConstraintRefs(), 0);
	EXPECT_GE(warnings.count(), 1);
	w.run(30);
	EXPECT_LT(b->getCenterOfMassPosition().y(), btScalar(-2.5)) << "b falls freely";
	EXPECT_NEAR(a->getCenterOfMassPosition().y(), -1, 1e-6) << "a is out of the world";
	(void)joint;
}

TEST(TypedConstraint, JointBetweenABodyAndItselfIsReportedAndIgnored)
{
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* a = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
	btPoint2PointConstraint self(*a, *a, btVector3(0, 0, 0), btVector3(1, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.world()->addConstraint(&self), "body and itself");
#else
	WarningCounter warnings;
	w.world()->addConstraint(&self);
	EXPECT_EQ(w.world()->getNumConstraints(), 0);
	EXPECT_EQ(warnings.count(), 1);
	w.run(10);
	EXPECT_LT(a->getCenterOfMassPosition().y(), 0);
#endif
}

TEST(TypedConstraint, NullOrDuplicateJointIsReportedAndIgnored)
{
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* a = w.addBody(ball, 0, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, 1, btVector3(0, -1, 0));
	btPoint2PointConstraint* joint =
	    w.addJoint<btPoint2PointConstraint>(true, *a, *b, btVector3(0, -0.5, 0), btVector3(0, 0.5, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.world()->addConstraint(0), "null constraint");
	EXPECT_DEATH(w.world()->addConstraint(joint), "added twice");
#else
	WarningCounter warnings;
	w.world()->addConstraint(0);
	w.world()->addConstraint(joint, true);
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_EQ(w.world()->getNumConstraints(), 1) << "the joint is in the world once";
	EXPECT_EQ(b->getNumConstraintRefs(), 1) << "and referenced once by its body";
#endif
	w.run(60);
	// The joint still holds b one metre below the static anchor (pivot drift well under a millimetre).
	EXPECT_NEAR(b->getCenterOfMassPosition().y(), -1, 1e-3);
	w.world()->removeConstraint(joint);
	EXPECT_EQ(w.world()->getNumConstraints(), 0);
	EXPECT_EQ(b->getNumConstraintRefs(), 0);
}

TEST(TypedConstraint, NonFinitePivotDisablesTheJointWithAWarningAndTheWorldGoesOn)
{
	WarningCounter warnings;
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* a = w.addBody(ball, 1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, 1, btVector3(0, -1, 0));
	btRigidBody* other = w.addBody(ball, 1, btVector3(5, 0, 0));
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	btPoint2PointConstraint* joint =
	    w.addJoint<btPoint2PointConstraint>(false, *a, *b, btVector3(0, nan, 0), btVector3(0, 0.5, 0));
	w.run(30);
	EXPECT_FALSE(joint->isEnabled());
	EXPECT_EQ(warnings.count(), 1);
	for (btRigidBody* body : {a, b, other})
	{
		EXPECT_TRUE(std::isfinite(body->getCenterOfMassPosition().y()));
		EXPECT_LT(body->getCenterOfMassPosition().y(), btScalar(-0.5)) << "everything keeps falling";
	}
}

TEST(TypedConstraint, OverrideIterationsTightenOneJoint)
{
	// A heavy weight on a light 10-link chain: with 1 world iteration the chain stretches; the same chain
	// with 30 iterations of its own holds far tighter, while the world still runs 1 iteration.
	btScalar gaps[2];
	for (int trial = 0; trial < 2; ++trial)
	{
		TestWorld w(btVector3(0, -kG, 0));
		w.world()->getSolverInfo().m_numIterations = 1;
		// The velocity solve alone: the position correction would close the chain in either case.
		caliber::setJointPositionIterations(*w.world(), 0);
		btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.05));
		btRigidBody* previous = 0;
		std::vector<btPoint2PointConstraint*> joints;
		for (int i = 0; i < 10; ++i)
		{
			btRigidBody* link = w.addBody(ball, i == 9 ? 20 : 0.1, btVector3(0, -0.2 * (i + 1), 0));
			link->setSleepingThresholds(0, 0);
			if (previous)
				joints.push_back(w.addJoint<btPoint2PointConstraint>(true, *previous, *link, btVector3(0, -0.1, 0),
				                                                     btVector3(0, 0.1, 0)));
			else
				joints.push_back(w.addJoint<btPoint2PointConstraint>(true, *link, btVector3(0, 0.1, 0)));
			previous = link;
		}
		if (trial == 1)
			for (btPoint2PointConstraint* j : joints) j->setOverrideNumSolverIterations(30);
		w.run(60);
		gaps[trial] = -0.2 * 10 - previous->getCenterOfMassPosition().y();
	}
	EXPECT_GT(gaps[0], 0.02);
	EXPECT_LT(gaps[1], 0.5 * gaps[0]);
}

namespace
{
// One soft row holding body A's x velocity at 0 with the given cfm.
class SoftBrake : public btTypedConstraint
{
public:
	SoftBrake(btRigidBody& body, btScalar cfm) : btTypedConstraint(POINT2POINT_CONSTRAINT_TYPE, body), m_cfm(cfm) {}
	void getInfo1(btConstraintInfo1* info) override
	{
		info->m_numConstraintRows = 1;
		info->nub = 0;
	}
	void getInfo2(btConstraintInfo2* info) override
	{
		info->m_J1linearAxis[0] = 1;
		info->m_J2linearAxis[0] = -1;
		info->cfm[0] = m_cfm;
	}
	void setParam(int, btScalar, int) override {}
	btScalar getParam(int, int) const override { return 0; }

private:
	btScalar m_cfm;
};
}  // namespace

TEST(TypedConstraint, SoftRowsReachBulletsSoftSolutionForAnyCfm)
{
	// A soft row solves J v = target - cfm K lambda (Bullet's meaning of cfm). For a body of mass m
	// moving at v0 along the row (K = 1/m, target 0): lambda = m (v - v0) and v = -cfm lambda / m, so
	// v = v0 cfm / (1 + cfm): a harder row (smaller cfm) brakes more. Gauss-Seidel on Bullet's own form of the row
	// overshoots once cfm >= 1; the rows are rescaled so that it converges for any cfm, to the same solution.
	for (btScalar cfm : {btScalar(0.5), btScalar(2), btScalar(10)})
	{
		TestWorld w(btVector3(0, 0, 0));
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 2, btVector3(0, 0, 0));
		body->setLinearVelocity(btVector3(3, 0, 0));
		w.addJoint<SoftBrake>(false, *body, cfm);
		w.run(1);
		// One row, 10 iterations: converged to float rounding.
		EXPECT_NEAR(body->getLinearVelocity().x(), 3 * cfm / (1 + cfm), 1e-5) << "cfm " << cfm;
	}
}
