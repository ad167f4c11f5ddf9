// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btHinge2Constraint: a wheel on a fixed chassis spins freely about its axle, sags on its suspension
// spring by m g / k, and steers only within its limits.

#include <gtest/gtest.h>

#include <cmath>

#include "BulletDynamics/ConstraintSolver/btHinge2Constraint.h"
#include "JointTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kG = btScalar(10);

// A static chassis block above a wheel (a cylinder with its axis along x) centred on the anchor at the
// origin: axis1 (suspension and steering) vertical, axis2 (axle) along x.
struct WheelRig
{
	explicit WheelRig(const btVector3& gravity, btScalar wheelMass = 2) : world(gravity)
	{
		chassis = world.addBody(world.shape<btBoxShape>(btVector3(1, 0.1, 1)), 0, btVector3(0, 1, 0));
		wheel = world.addBody(world.shape<btCylinderShapeX>(btVector3(0.1, 0.3, 0.3)), wheelMass, btVector3(0, 0, 0));
		wheel->setActivationState(DISABLE_DEACTIVATION);
		joint = world.addJoint<btHinge2Constraint>(true, *chassis, *wheel, btVector3(0, 0, 0), btVector3(0, 1, 0),
		                                           btVector3(1, 0, 0));
	}
	TestWorld world;
	btRigidBody* chassis;
	btRigidBody* wheel;
	btHinge2Constraint* joint;
};
}  // namespace

TEST(Hinge2Constraint, FramesAxesAndDefaultsFollowBullet)
{
	WheelRig rig(btVector3(0, 0, 0));
	btHinge2Constraint& joint = *rig.joint;
	EXPECT_EQ(joint.getAxis1(), btVector3(0, 1, 0));
	EXPECT_EQ(joint.getAxis2(), btVector3(1, 0, 0));
	EXPECT_NEAR((joint.getAnchor() - btVector3(0, 0, 0)).length(), 0, 1e-6);
	EXPECT_NEAR((joint.getAnchor2() - btVector3(0, 0, 0)).length(), 0, 1e-6);
	// Frame z is axis1, x the axle: suspension along linear z, steering angle 2, spin angle 0.
	EXPECT_NEAR(joint.getCalculatedTransformA().getBasis().getColumn(2).y(), 1, 1e-6);
	EXPECT_NEAR(joint.getCalculatedTransformA().getBasis().getColumn(0).x(), 1, 1e-6);
	EXPECT_FALSE(joint.isLimited(3)) << "spin free";
	EXPECT_TRUE(joint.isLimited(4)) << "tilt locked";
	EXPECT_NEAR(joint.getRotationalLimitMotor(2)->m_hiLimit, SIMD_PI / 4, 1e-6) << "steering +-pi/4";
	EXPECT_NEAR(joint.getTranslationalLimitMotor()->m_lowerLimit.z(), -1, 1e-6) << "suspension travel +-1";
	EXPECT_TRUE(joint.getTranslationalLimitMotor()->m_enableSpring[2]);
	EXPECT_NEAR(joint.getTranslationalLimitMotor()->m_springStiffness.z(), 4 * SIMD_PI * SIMD_PI, 1e-4);
}

TEST(Hinge2Constraint, WheelSpinsFreelyAboutItsAxle)
{
	// A cylinder spinning about its own axis feels no gyroscopic torque, and the joint's rows measure
	// the spin along the axle only through the free angle: nothing may slow it. The spin angle (A
	// relative to B, Bullet's sign) falls by w h per step. Gravity on, so the suspension works at the
	// same time. Tolerances: float rounding of a 10 rad/s spin over 120 steps.
	WheelRig rig(btVector3(0, -kG, 0));
	const btScalar spin = 10, h = btScalar(1. / 60.);
	rig.wheel->setAngularVelocity(btVector3(spin, 0, 0));
	const int steps = 120;
	btScalar worstTilt = 0;
	for (int i = 0; i < steps; ++i)
	{
		rig.world.run(1, h);
		rig.joint->calculateTransforms();
		worstTilt = btMax(worstTilt, btMax(btFabs(rig.joint->getAngle(1)), btFabs(rig.joint->getAngle1())));
		EXPECT_NEAR(btNormalizeAngle(rig.joint->getAngle2() + spin * h * (i + 1)), 0, 1e-4) << "step " << i;
	}
	EXPECT_NEAR(rig.wheel->getAngularVelocity().x(), spin, 1e-5 * spin);
	EXPECT_NEAR(btVector3(0, rig.wheel->getAngularVelocity().y(), rig.wheel->getAngularVelocity().z()).length(), 0,
	            1e-5);
	EXPECT_LT(worstTilt, 1e-5) << "neither steering nor tilt moved";
}

TEST(Hinge2Constraint, SuspensionSagsByMgOverK)
{
	// A critically damped suspension spring (c = 2 sqrt(k m)) settles within a few of its periods
	// (2 pi sqrt(m / k) = 0.63 s) at the static sag m g / k = 0.1 m below the anchor (relative pivot
	// position -0.1 along axis1), with the wheel still under the anchor. Tolerance: float rounding.
	const btScalar m = 2, k = 200;
	WheelRig rig(btVector3(0, -kG, 0), m);
	rig.joint->setStiffness(2, k);
	rig.joint->setDamping(2, 2 * btSqrt(k * m));
	rig.world.run(240);
	rig.joint->calculateTransforms();
	EXPECT_NEAR(rig.joint->getRelativePivotPosition(2), -m * kG / k, 1e-5);
	EXPECT_NEAR(rig.wheel->getCenterOfMassPosition().y(), -m * kG / k, 1e-5);
	EXPECT_NEAR(rig.joint->getRelativePivotPosition(0), 0, 1e-6);
	EXPECT_NEAR(rig.joint->getRelativePivotPosition(1), 0, 1e-6);
}

TEST(Hinge2Constraint, SteeringStaysWithinItsLimits)
{
	// A spinning wheel is steered hard one way, then the other, against limits [-0.3, 0.2]. The
	// steering angle turns about the chassis' axis, which the limit rows measure exactly; what a limit
	// lets through comes from the spin and the steering turning together within the step that reaches
	// it, the second-order term h^2 w_spin w_steer / 2. Once the wheel rests on the limit w_steer is 0
	// and nothing more leaks. The steering rate at impact is at most sqrt(2 (T / I) range), the whole
	// range crossed under the full torque.
	WheelRig rig(btVector3(0, 0, 0));
	const btScalar h = btScalar(1. / 60.), spin = 10, torque = 2, lower = btScalar(-0.3), upper = btScalar(0.2);
	rig.joint->setLowerLimit(lower);
	rig.joint->setUpperLimit(upper);
	EXPECT_FALSE(rig.joint->isLimited(3)) << "the limits keep the spin free";
	rig.wheel->setAngularVelocity(btVector3(spin, 0, 0));
	const btScalar inertiaSteer = 1 / rig.wheel->getInvInertiaDiagLocal().y();
	const btScalar steerRate = btSqrt(2 * torque / inertiaSteer * (upper - lower));
	const btScalar tolerance = h * h * spin * steerRate / 2;
	btScalar lowest = 0, highest = 0;
	for (int phase = 0; phase < 2; ++phase)
	{
		// Turning the wheel (B) positively about axis1 lowers the steering angle (A relative to B).
		const btVector3 push(0, phase == 0 ? torque : -torque, 0);
		for (int i = 0; i < 30; ++i)
		{
			rig.wheel->applyTorque(push);
			rig.world.run(1, h);
			rig.joint->calculateTransforms();
			lowest = btMin(lowest, rig.joint->getAngle1());
			highest = btMax(highest, rig.joint->getAngle1());
		}
	}
	EXPECT_GT(lowest, lower - tolerance);
	EXPECT_LT(highest, upper + tolerance);
	EXPECT_LT(lowest, lower + btScalar(0.01)) << "the lower limit was reached";
	EXPECT_GT(highest, upper - btScalar(0.01)) << "the upper limit was reached";
}

TEST(Hinge2Constraint, DegenerateAxesAreReported)
{
	WarningCounter warnings;
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* a = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 0, btVector3(0, 1, 0));
	btRigidBody* b = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
	btHinge2Constraint parallel(*a, *b, btVector3(0, 0, 0), btVector3(0, 1, 0), btVector3(0, 2, 0));
	EXPECT_FALSE(parallel.isEnabled());
	EXPECT_EQ(warnings.count(), 1);
	// A leaning axle is straightened: its part along axis1 is dropped.
	btHinge2Constraint leaning(*a, *b, btVector3(0, 0, 0), btVector3(0, 1, 0), btVector3(1, 0.5, 0));
	EXPECT_TRUE(leaning.isEnabled());
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_NEAR(leaning.getAxis2().dot(btVector3(1, 0, 0)), 1, 1e-6);
}
