// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGearConstraint: the speeds keep wA . axisA = -ratio wB . axisB, the exchange conserves what the gear
// cannot change, the sign of the ratio picks the sense, and bad axes disable it.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btSliderConstraint.h"
#include "JointTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
// Two equal spheres (I = 2/5 m r^2 = 0.1 kg m^2), far apart, in zero gravity, awake.
struct GearScene
{
	TestWorld world{btVector3(0, 0, 0)};
	btRigidBody* a;
	btRigidBody* b;
	static constexpr double kInertia = 0.4 * 1.0 * 0.5 * 0.5;

	GearScene()
	{
		btCollisionShape* ball = world.shape<btSphereShape>(btScalar(0.5));
		a = world.addBody(ball, 1, btVector3(0, 0, 0));
		b = world.addBody(ball, 1, btVector3(3, 0, 0));
		a->setSleepingThresholds(0, 0);
		b->setSleepingThresholds(0, 0);
	}
};

// One equality row solved exactly; what is left is float rounding of speeds of order 1 rad/s.
const double kSpeedTolerance = 1e-5;
}  // namespace

TEST(GearConstraint, SpinIsSharedAsTheGearRelationAndConservationPredict)
{
	// A spins at w0 about x, B rests; the gear's impulse lambda turns A by lambda / I and B by
	// ratio * lambda / I. With wA + ratio wB = 0 afterwards: wA = w0 r^2 / (1 + r^2),
	// wB = -w0 r / (1 + r^2). The gear cannot change I wA - I wB / r (its impulses change the two terms
	// equally), so that stays I w0.
	for (const double ratio : {2.0, 0.5, 1.0})
	{
		GearScene s;
		const double w0 = 3;
		s.a->setAngularVelocity(btVector3(btScalar(w0), 0, 0));
		btGearConstraint* gear = s.world.addJoint<btGearConstraint>(true, *s.a, *s.b, btVector3(1, 0, 0),
		                                                            btVector3(1, 0, 0), btScalar(ratio));
		EXPECT_EQ(gear->getRatio(), btScalar(ratio));
		s.world.run(1);
		const double wA = double(s.a->getAngularVelocity().x()), wB = double(s.b->getAngularVelocity().x());
		EXPECT_NEAR(wA, w0 * ratio * ratio / (1 + ratio * ratio), kSpeedTolerance) << "ratio " << ratio;
		EXPECT_NEAR(wB, -w0 * ratio / (1 + ratio * ratio), kSpeedTolerance) << "ratio " << ratio;
		EXPECT_NEAR(wA + ratio * wB, 0, kSpeedTolerance) << "ratio " << ratio;
		EXPECT_NEAR(GearScene::kInertia * wA - GearScene::kInertia * wB / ratio, GearScene::kInertia * w0,
		            kSpeedTolerance)
		    << "ratio " << ratio;
		// Nothing else acts, so the shared spin stays as it is.
		s.world.run(120);
		EXPECT_NEAR(double(s.a->getAngularVelocity().x()), wA, kSpeedTolerance) << "ratio " << ratio;
		EXPECT_NEAR(double(s.b->getAngularVelocity().x()), wB, kSpeedTolerance) << "ratio " << ratio;
		EXPECT_NEAR(double(s.b->getAngularVelocity().y()), 0, kSpeedTolerance);
		EXPECT_NEAR(double(s.b->getAngularVelocity().z()), 0, kSpeedTolerance);
	}
}

TEST(GearConstraint, NegativeRatioTurnsBothTheSameWay)
{
	GearScene s;
	s.a->setAngularVelocity(btVector3(2, 0, 0));
	s.world.addJoint<btGearConstraint>(true, *s.a, *s.b, btVector3(1, 0, 0), btVector3(1, 0, 0), btScalar(-1));
	s.world.run(10);
	// Ratio -1 and equal inertias: both end at w0 / 2, the same sense.
	EXPECT_NEAR(s.a->getAngularVelocity().x(), 1, kSpeedTolerance);
	EXPECT_NEAR(s.b->getAngularVelocity().x(), 1, kSpeedTolerance);
}

TEST(GearConstraint, PerpendicularAxesMakeABevelGear)
{
	// A turns about its x, B about its y: wA.x = -ratio wB.y, with the same sharing as parallel axes.
	GearScene s;
	const double w0 = 3, ratio = 2;
	s.a->setAngularVelocity(btVector3(btScalar(w0), 0, 0));
	s.world.addJoint<btGearConstraint>(true, *s.a, *s.b, btVector3(1, 0, 0), btVector3(0, 1, 0), btScalar(ratio));
	s.world.run(30);
	EXPECT_NEAR(s.a->getAngularVelocity().x(), w0 * ratio * ratio / (1 + ratio * ratio), kSpeedTolerance);
	EXPECT_NEAR(s.b->getAngularVelocity().y(), -w0 * ratio / (1 + ratio * ratio), kSpeedTolerance);
	EXPECT_NEAR(s.b->getAngularVelocity().x(), 0, kSpeedTolerance);
}

TEST(GearConstraint, AxesTurnWithTheirBodies)
{
	// B is turned 90 degrees about z, so its local x axis points along world y: coupling about B's x is
	// coupling about world y.
	GearScene s;
	s.b->setCenterOfMassTransform(btTransform(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI), btVector3(3, 0, 0)));
	s.a->setAngularVelocity(btVector3(3, 0, 0));
	s.world.addJoint<btGearConstraint>(true, *s.a, *s.b, btVector3(1, 0, 0), btVector3(1, 0, 0), btScalar(1));
	s.world.run(1);
	EXPECT_NEAR(s.a->getAngularVelocity().x(), 1.5, kSpeedTolerance);
	EXPECT_NEAR(s.b->getAngularVelocity().y(), -1.5, kSpeedTolerance);
	EXPECT_NEAR(s.b->getAngularVelocity().x(), 0, kSpeedTolerance);
}

TEST(GearConstraint, GearedWheelsOnSliderHingesFollowTheDrivenWheel)
{
	// Two wheels held by sliders locked along their axes (hinges about world x), under gravity; an
	// angular motor drives the first at -2 rad/s about x (the slider's motor drives A's minus B's
	// angular velocity, and the world is A), and a 1 : 2 gear makes the second follow at
	// -wFirst / ratio = +1 rad/s.
	TestWorld w(btVector3(0, -10, 0));
	btCollisionShape* wheel = w.shape<btCylinderShapeX>(btVector3(0.1, 0.5, 0.5));
	btRigidBody* first = w.addBody(wheel, 1, btVector3(0, 1, 0));
	btRigidBody* second = w.addBody(wheel, 4, btVector3(0, 1, 2));
	btSliderConstraint* hinges[2];
	int i = 0;
	for (btRigidBody* body : {first, second})
	{
		body->setSleepingThresholds(0, 0);
		btSliderConstraint* hinge = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
		hinge->setLowerLinLimit(0);
		hinge->setUpperLinLimit(0);
		hinge->setLowerAngLimit(1);  // free turn
		hinge->setUpperAngLimit(-1);
		hinges[i++] = hinge;
	}
	hinges[0]->setPoweredAngMotor(true);
	hinges[0]->setTargetAngMotorVelocity(2);
	hinges[0]->setMaxAngMotorForce(1000);
	const double ratio = 2;
	w.addJoint<btGearConstraint>(true, *first, *second, btVector3(1, 0, 0), btVector3(1, 0, 0), btScalar(ratio));
	w.run(120);
	// The motor row (on the first wheel) and the gear row meet only through the first wheel's inertia:
	// the Gauss-Seidel sweep between them contracts by 1 / (1 + ratio^2 I1 / I2) = 0.5 per sweep, and with
	// warm starting over 120 steps only rounding is left. The hinges' equality rows hold the wheels'
	// centres to rounding.
	EXPECT_NEAR(first->getAngularVelocity().x(), -2, kSpeedTolerance);
	EXPECT_NEAR(second->getAngularVelocity().x(), 2 / ratio, kSpeedTolerance);
	EXPECT_NEAR(second->getCenterOfMassPosition().y(), 1, 1e-5);
	EXPECT_NEAR(first->getCenterOfMassPosition().y(), 1, 1e-5);
}

TEST(GearConstraint, CfmParamSoftensTheCoupling)
{
	GearScene s;
	s.a->setAngularVelocity(btVector3(3, 0, 0));
	btGearConstraint* gear =
	    s.world.addJoint<btGearConstraint>(true, *s.a, *s.b, btVector3(1, 0, 0), btVector3(1, 0, 0), btScalar(1));
	const double cfm = 0.25;
	gear->setParam(BT_CONSTRAINT_CFM, btScalar(cfm));
	EXPECT_EQ(gear->getParam(BT_CONSTRAINT_CFM), btScalar(cfm));
	EXPECT_EQ(gear->getParam(BT_CONSTRAINT_STOP_CFM, 0), btScalar(cfm));
	s.world.run(1);
	// The solver's softness makes a lone row settle at 1 / (1 + cfm) of the hard impulse (each sweep
	// maps lambda to rhs - cfm lambda; ten sweeps leave cfm^10 = 1e-6 of the difference). The hard gear
	// would exchange 1.5 rad/s; the soft one exchanges 0.8 of it: wA = 3 - 1.2, wB = -1.2.
	EXPECT_NEAR(s.a->getAngularVelocity().x(), 3 - 1.5 / (1 + cfm), kSpeedTolerance);
	EXPECT_NEAR(s.b->getAngularVelocity().x(), -1.5 / (1 + cfm), kSpeedTolerance);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(gear->setParam(BT_CONSTRAINT_ERP, btScalar(0.5)), "");
#else
	gear->setParam(BT_CONSTRAINT_ERP, btScalar(0.5));  // ignored
	EXPECT_EQ(gear->getParam(BT_CONSTRAINT_CFM), btScalar(cfm));
#endif
}

TEST(GearConstraint, ZeroLengthOrNonFiniteAxisDisablesTheGearWithAWarning)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	GearScene s;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH({ btGearConstraint g(*s.a, *s.b, btVector3(0, 0, 0), btVector3(1, 0, 0)); }, "axis");
	EXPECT_DEATH({ btGearConstraint g(*s.a, *s.b, btVector3(1, 0, 0), btVector3(nan, 0, 0)); }, "axis");
	EXPECT_DEATH({ btGearConstraint g(*s.a, *s.b, btVector3(1, 0, 0), btVector3(1, 0, 0), nan); }, "ratio");
	btGearConstraint good(*s.a, *s.b, btVector3(1, 0, 0), btVector3(1, 0, 0));
	EXPECT_DEATH(good.setAxisB(btVector3(0, 0, 0)), "axis");
	(void)nan;
#else
	WarningCounter warnings;
	btGearConstraint* gear =
	    s.world.addJoint<btGearConstraint>(true, *s.a, *s.b, btVector3(0, 0, 0), btVector3(1, 0, 0), btScalar(1));
	EXPECT_FALSE(gear->isEnabled());
	EXPECT_EQ(warnings.count(), 1);
	// Re-enabled by hand with the axis still zero: checked again at the step, disabled, no rows.
	gear->setEnabled(true);
	s.a->setAngularVelocity(btVector3(3, 0, 0));
	s.world.run(10);
	EXPECT_FALSE(gear->isEnabled());
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_EQ(s.a->getAngularVelocity().x(), btScalar(3)) << "inert: A keeps its spin";
	EXPECT_EQ(s.b->getAngularVelocity().x(), btScalar(0));
	btGearConstraint other(*s.a, *s.b, btVector3(1, 0, 0), btVector3(1, 0, 0));
	other.setRatio(nan);
	EXPECT_FALSE(other.isEnabled());
	EXPECT_EQ(warnings.count(), 3);
#endif
}
