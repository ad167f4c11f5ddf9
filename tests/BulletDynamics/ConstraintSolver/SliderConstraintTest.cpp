// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSliderConstraint: the rows across the axis hold, the free slide follows gravity's component along the
// axis exactly, limits stop it on the limit, motors reach their targets within their force or torque,
// the positions it reports are the measured ones, and bad frames disable it.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "BulletDynamics/ConstraintSolver/btSliderConstraint.h"
#include "JointTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kG = btScalar(10);
const btScalar kH = btScalar(1. / 60.);

// Float rounding budget for positions of order 1 m kept for up to a few hundred steps: the exact rows
// leave only rounding (1.2e-7 relative per operation), which stays below 1e-5 m in double and float.
const double kRoundingTolerance = 1e-5;

// The angle of a rotation, accurate for small angles too (acos near 1 is not).
double rotationAngle(const btQuaternion& q)
{
	const double v = std::sqrt(double(q.x()) * q.x() + double(q.y()) * q.y() + double(q.z()) * q.z());
	return 2.0 * std::atan2(v, std::fabs(double(q.w())));
}

// A frame at origin whose X axis is turned by angle about z (towards +y for a positive angle).
btTransform frameTurnedAboutZ(btScalar angle, const btVector3& origin = btVector3(0, 0, 0))
{
	return btTransform(btQuaternion(btVector3(0, 0, 1), angle), origin);
}

// Bullet's default locks the turn about the axis (both angular limits 0); lower > upper frees it.
void freeTheTurn(btSliderConstraint* slider)
{
	slider->setLowerAngLimit(1);
	slider->setUpperAngLimit(-1);
}

btRigidBody* addAwakeBody(TestWorld& w, btCollisionShape* shape, btScalar mass, const btTransform& pose)
{
	btRigidBody* body = w.addBody(shape, mass, pose);
	body->setSleepingThresholds(0, 0);
	return body;
}

// Distance of the world point from the line through origin along unit axis.
double distanceFromLine(const btVector3& point, const btVector3& origin, const btVector3& axis)
{
	const btVector3 d = point - origin;
	return double((d - axis * d.dot(axis)).length());
}
}  // namespace

TEST(SliderConstraint, HorizontalSliderHoldsItsBodyAgainstGravityWithoutTurning)
{
	// Two pivots: at the centre of mass, and 0.5 m behind it along the axis, so that gravity's torque
	// about the pivot (0.5 m g about z) must be carried by the angular rows across the axis.
	for (int trial = 0; trial < 2; ++trial)
	{
		TestWorld w(btVector3(0, -kG, 0));
		const btVector3 start(0, 1, 0);
		btRigidBody* body = addAwakeBody(w, w.shape<btBoxShape>(btVector3(0.6, 0.1, 0.1)), 2,
		                                 btTransform(btQuaternion::getIdentity(), start));
		const btVector3 pivotInBody = trial == 0 ? btVector3(0, 0, 0) : btVector3(-0.5, 0, 0);
		btSliderConstraint* slider =
		    w.addJoint<btSliderConstraint>(false, *body, btTransform(btQuaternion::getIdentity(), pivotInBody), true);
		freeTheTurn(slider);
		double worstDrop = 0, worstAcross = 0, worstTurn = 0;
		for (int i = 0; i < 120; ++i)
		{
			w.run(1);
			const btVector3 p = body->getCenterOfMassPosition();
			worstDrop = std::max(worstDrop, std::fabs(double(p.y() - start.y())));
			worstAcross = std::max(worstAcross, std::fabs(double(p.z() - start.z())));
			worstTurn = std::max(worstTurn, rotationAngle(body->getOrientation()));
		}
		// Free, the body would fall g t^2 / 2 = 20 m in these 2 s; the joint's rows are exact velocity
		// constraints solved as one block, so only rounding remains. Gravity has no component along the
		// axis, so the body does not slide either.
		EXPECT_LT(worstDrop, kRoundingTolerance) << "trial " << trial;
		EXPECT_LT(worstAcross, kRoundingTolerance) << "trial " << trial;
		EXPECT_LT(worstTurn, kRoundingTolerance) << "trial " << trial;
		EXPECT_NEAR(body->getCenterOfMassPosition().x(), start.x(), kRoundingTolerance);
		EXPECT_NEAR(slider->getLinearPos(), 0, kRoundingTolerance);
	}
}

TEST(SliderConstraint, TiltedSliderAcceleratesAtGSinAngleAlongTheAxis)
{
	const btScalar angle = btScalar(SIMD_PI / 6);  // 30 degrees: g sin = 5 m/s^2
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.1)), 1, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, frameTurnedAboutZ(angle), true);
	const btVector3 axis(btCos(angle), btSin(angle), 0);
	const int steps = 60;
	double worstAcross = 0;
	for (int i = 0; i < steps; ++i)
	{
		w.run(1);
		worstAcross =
		    std::max(worstAcross, distanceFromLine(body->getCenterOfMassPosition(), btVector3(0, 0, 0), axis));
	}
	// Semi-implicit Euler exactly: v_n = -g sin h n, s_n = -g sin h^2 n (n + 1) / 2 (the continuous
	// g sin t^2 / 2 is 1.7 % less after 60 steps, far outside the tolerance).
	const double a = double(kG) * std::sin(double(angle)), h = double(kH);
	const double expectedV = -a * h * steps, expectedS = -a * h * h * steps * (steps + 1) / 2;
	const double s = double(body->getCenterOfMassPosition().dot(axis));
	const double v = double(body->getLinearVelocity().dot(axis));
	// Relative rounding: 1e-5 of the 2.5 m travelled.
	EXPECT_NEAR(s, expectedS, 1e-5 * std::fabs(expectedS));
	EXPECT_NEAR(v, expectedV, 1e-5 * std::fabs(expectedV));
	EXPECT_LT(worstAcross, kRoundingTolerance);
	EXPECT_LT(std::fabs(double(body->getLinearVelocity().dot(btVector3(0, 0, 1)))), kRoundingTolerance);
	// getLinearPos is measured at the start of the last step: s_(n-1).
	const double previousS = -a * h * h * (steps - 1) * steps / 2;
	EXPECT_NEAR(slider->getLinearPos(), previousS, 1e-5 * std::fabs(previousS));
}

TEST(SliderConstraint, LinearLimitsStopTheBodyOnTheLimit)
{
	const btScalar angle = btScalar(SIMD_PI / 6);
	const btScalar lower = btScalar(-0.5), upper = btScalar(0.3);
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.1)), 1, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, frameTurnedAboutZ(angle), true);
	slider->setLowerLinLimit(lower);
	slider->setUpperLinLimit(upper);
	const btVector3 axis(btCos(angle), btSin(angle), 0);
	// Thrown up the slope at 3 m/s: free, it would rise v^2 / (2 g sin) = 0.9 m, past the upper limit.
	body->setLinearVelocity(axis * btScalar(3));
	double highest = 0, lowest = 0;
	for (int i = 0; i < 180; ++i)
	{
		w.run(1);
		const double s = double(body->getCenterOfMassPosition().dot(axis));
		highest = std::max(highest, s);
		lowest = std::min(lowest, s);
	}
	// The limit rows look one step ahead and let the body land on the limit, not past it: what is left is
	// rounding. It reached both limits: it rose to the upper one and slid down to rest on the lower one.
	EXPECT_LT(highest, upper + kRoundingTolerance);
	EXPECT_GT(highest, upper - kRoundingTolerance);
	EXPECT_GT(lowest, lower - kRoundingTolerance);
	EXPECT_NEAR(body->getCenterOfMassPosition().dot(axis), lower, kRoundingTolerance);
	EXPECT_NEAR(body->getLinearVelocity().length(), 0, kRoundingTolerance / double(kH));
	EXPECT_NEAR(slider->getLinearPos(), lower, kRoundingTolerance);
}

TEST(SliderConstraint, LinearLimitBouncesBackOneMinusDampingOfTheImpactSpeed)
{
	// Horizontal, no gravity along the axis: the body reaches the upper limit at 2 m/s.
	for (int trial = 0; trial < 2; ++trial)
	{
		const btScalar damping = trial == 0 ? btScalar(1) : btScalar(0.25);  // bounce 0 and 0.75
		TestWorld w(btVector3(0, -kG, 0));
		btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.1)), 1, btTransform::getIdentity());
		btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
		slider->setLowerLinLimit(-1);
		slider->setUpperLinLimit(btScalar(0.51));
		slider->setDampingLimLin(damping);
		EXPECT_EQ(slider->getDampingLimLin(), damping);
		body->setLinearVelocity(btVector3(2, 0, 0));
		w.run(30);  // the limit is reached in the 16th step
		// Nothing but the limit acts along the axis, so the speed after is exactly bounce * 2 m/s.
		EXPECT_NEAR(body->getLinearVelocity().x(), -2 * (1 - damping), 1e-5) << "damping " << damping;
		EXPECT_LT(body->getCenterOfMassPosition().x(), btScalar(0.51) + kRoundingTolerance);
	}
}

TEST(SliderConstraint, EqualLinearLimitsLockTheSlide)
{
	const btScalar angle = btScalar(SIMD_PI / 6);
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.1)), 1, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, frameTurnedAboutZ(angle), true);
	slider->setLowerLinLimit(btScalar(0.2));
	slider->setUpperLinLimit(btScalar(0.2));
	const btVector3 axis(btCos(angle), btSin(angle), 0);
	w.run(180);
	// The locked slide is an equality row: it pulls the body from 0 to 0.2 at ERP 0.2 per step (error
	// 0.2 * 0.8^180 ~ 1e-18 left) and holds it against g sin = 5 m/s^2 without sag.
	EXPECT_NEAR(body->getCenterOfMassPosition().dot(axis), 0.2, kRoundingTolerance);
	EXPECT_NEAR(body->getLinearVelocity().length(), 0, kRoundingTolerance / double(kH));
}

TEST(SliderConstraint, LinearMotorReachesItsTargetVelocity)
{
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar mass = 2;
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.2)), mass, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
	slider->setPoweredLinMotor(true);
	slider->setTargetLinMotorVelocity(btScalar(1.5));
	slider->setMaxLinMotorForce(1000);  // 1000 N for 1/60 s moves 2 kg by 8.3 m/s: enough in one step
	EXPECT_TRUE(slider->getPoweredLinMotor());
	EXPECT_EQ(slider->getTargetLinMotorVelocity(), btScalar(1.5));
	EXPECT_EQ(slider->getMaxLinMotorForce(), btScalar(1000));
	w.run(1);
	EXPECT_NEAR(body->getLinearVelocity().x(), 1.5, 1e-5);
	w.run(59);
	EXPECT_NEAR(body->getLinearVelocity().x(), 1.5, 1e-5);
	// The motor drives getLinearPos up: after 60 steps at 1.5 m/s it stood at 59 * 1.5 / 60.
	EXPECT_NEAR(slider->getLinearPos(), 59 * 1.5 / 60, kRoundingTolerance);
}

TEST(SliderConstraint, LinearMotorWithSmallForceAcceleratesAtForceOverMass)
{
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar mass = 2, force = 3;  // 1.5 m/s^2
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.2)), mass, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
	slider->setPoweredLinMotor(true);
	slider->setTargetLinMotorVelocity(10);
	slider->setMaxLinMotorForce(force);
	const int steps = 60;
	w.run(steps);
	// The row saturates at force * h every step: v = F / m * t exactly; s = F / m h^2 n (n + 1) / 2.
	const double a = double(force / mass), h = double(kH);
	EXPECT_NEAR(body->getLinearVelocity().x(), a * h * steps, 1e-5 * a * h * steps);
	EXPECT_NEAR(body->getCenterOfMassPosition().x(), a * h * h * steps * (steps + 1) / 2, kRoundingTolerance);
	EXPECT_NEAR(body->getCenterOfMassPosition().y(), 0, kRoundingTolerance);
}

TEST(SliderConstraint, LinearMotorOnAnOffAxisBodyStillAcceleratesAtForceOverMass)
{
	// The axis runs 0.3 m beside the centre of mass, so the motor's push (applied on the axis) also
	// twists the body about y; the angular rows hold that twist, and the body must still gain exactly
	// F / m along the axis, turn not at all, and carry its weight on the rows across the axis.
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar mass = 2, force = 3;
	btRigidBody* body =
	    addAwakeBody(w, w.shape<btBoxShape>(btVector3(0.2, 0.1, 0.4)), mass, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(
	    false, *body, btTransform(btQuaternion::getIdentity(), btVector3(0, 0, btScalar(0.3))), true);
	slider->setPoweredLinMotor(true);
	slider->setTargetLinMotorVelocity(10);
	slider->setMaxLinMotorForce(force);
	const int steps = 60;
	double worstTurn = 0;
	for (int i = 0; i < steps; ++i)
	{
		w.run(1);
		worstTurn = std::max(worstTurn, rotationAngle(body->getOrientation()));
	}
	const double a = double(force / mass), h = double(kH);
	EXPECT_NEAR(body->getLinearVelocity().x(), a * h * steps, 1e-5 * a * h * steps);
	EXPECT_NEAR(body->getCenterOfMassPosition().y(), 0, kRoundingTolerance);
	EXPECT_LT(worstTurn, kRoundingTolerance);
}

TEST(SliderConstraint, WithBsFrameAsReferenceTheMotorStillDrivesTheReportedPosition)
{
	// Reference frame B (the body's own): the position is the world frame's origin seen from the body,
	// (pA - pB) . xB, so a motor driving it up at 1.5 m/s moves the body along -x at 1.5 m/s.
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.2)), 2, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), false);
	slider->setPoweredLinMotor(true);
	slider->setTargetLinMotorVelocity(btScalar(1.5));
	slider->setMaxLinMotorForce(1000);
	w.run(60);
	EXPECT_NEAR(body->getLinearVelocity().x(), -1.5, 1e-5);
	EXPECT_NEAR(slider->getLinearPos(), 59 * 1.5 / 60, kRoundingTolerance);
	EXPECT_NEAR(body->getCenterOfMassPosition().y(), 0, kRoundingTolerance);
}

TEST(SliderConstraint, AngularMotorReachesItsTargetWithinItsTorque)
{
	// A sphere turning about the slider axis (world x) through its centre: I = 2/5 m r^2 = 0.2 kg m^2.
	TestWorld w(btVector3(0, -kG, 0));
	const btScalar mass = 2, radius = btScalar(0.5), torque = btScalar(0.5);
	const double inertia = 0.4 * double(mass) * double(radius) * double(radius);
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(radius), mass, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
	freeTheTurn(slider);
	slider->setPoweredAngMotor(true);
	slider->setTargetAngMotorVelocity(1);
	slider->setMaxAngMotorForce(torque);
	EXPECT_TRUE(slider->getPoweredAngMotor());
	EXPECT_EQ(slider->getTargetAngMotorVelocity(), btScalar(1));
	EXPECT_EQ(slider->getMaxAngMotorForce(), torque);
	// Torque-limited: alpha = 0.5 / 0.2 = 2.5 rad/s^2, so the target (1 rad/s) takes 0.4 s (24 steps).
	// The motor drives A's minus B's angular velocity about the axis (Bullet's sign): B, the body, turns at
	// -1 rad/s about x.
	w.run(12);
	const double alpha = double(torque) / inertia;
	EXPECT_NEAR(body->getAngularVelocity().x(), -alpha * 12 * double(kH), 1e-5);
	w.run(48);
	EXPECT_NEAR(body->getAngularVelocity().x(), -1, 1e-5);
	EXPECT_NEAR(body->getAngularVelocity().y(), 0, 1e-6);
	EXPECT_NEAR(body->getAngularVelocity().z(), 0, 1e-6);
	EXPECT_LT(slider->getAngularPos(), 0) << "a positive target turns the angle down";
}

TEST(SliderConstraint, AngularLimitsStopTheTurnOnTheLimit)
{
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.5)), 2, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
	slider->setLowerAngLimit(btScalar(-0.4));
	slider->setUpperAngLimit(btScalar(0.6));
	slider->setPoweredAngMotor(true);
	slider->setTargetAngMotorVelocity(2);  // turns the angle down at 2 rad/s, towards -0.4
	slider->setMaxAngMotorForce(100);
	double lowest = 0;
	for (int i = 0; i < 120; ++i)
	{
		w.run(1);
		const btQuaternion q = body->getOrientation();
		lowest = std::min(lowest, 2.0 * std::atan2(double(q.x()), double(q.w())));
	}
	// The look-ahead limit row lets the turn land on the limit: only rounding remains. The motor fades
	// as it nears the limit (getMotorFactor), so it does not push on the limit either.
	EXPECT_GT(lowest, -0.4 - kRoundingTolerance);
	EXPECT_LT(lowest, -0.4 + kRoundingTolerance);
	EXPECT_NEAR(body->getAngularVelocity().x(), 0, 1e-4);
	EXPECT_NEAR(slider->getAngularPos(), -0.4, kRoundingTolerance);
}

TEST(SliderConstraint, AngularLimitsHoldAnOffCentreBodyAgainstGravity)
{
	// Centre of mass 0.3 m beside the axis (world x through (0, 1, 0)): gravity turns the body positively
	// about x with torque 0.3 m g. Limited to [-0.2, 0.2] it stops at 0.2; locked at 0.1 it stays there.
	for (int trial = 0; trial < 2; ++trial)
	{
		const bool locked = trial == 1;
		TestWorld w(btVector3(0, -kG, 0));
		btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.1)), 1,
		                                 btTransform(btQuaternion::getIdentity(), btVector3(0, 1, btScalar(0.3))));
		btSliderConstraint* slider = w.addJoint<btSliderConstraint>(
		    false, *body, btTransform(btQuaternion::getIdentity(), btVector3(0, 0, btScalar(-0.3))), true);
		slider->setLowerAngLimit(locked ? btScalar(0.1) : btScalar(-0.2));
		slider->setUpperAngLimit(locked ? btScalar(0.1) : btScalar(0.2));
		double highest = -1;
		for (int i = 0; i < 240; ++i)
		{
			w.run(1);
			const btQuaternion q = body->getOrientation();
			highest = std::max(highest, 2.0 * std::atan2(double(q.x()), double(q.w())));
		}
		const double expected = locked ? 0.1 : 0.2;
		// Locked: an equality row pulled from 0 to 0.1 at ERP 0.2 per step, holding without sag. Limited:
		// the look-ahead row stops the swing on the limit. Either way only rounding remains.
		EXPECT_LT(highest, expected + kRoundingTolerance) << "locked " << locked;
		const btQuaternion q = body->getOrientation();
		EXPECT_NEAR(2.0 * std::atan2(double(q.x()), double(q.w())), expected, kRoundingTolerance)
		    << "locked " << locked;
		EXPECT_NEAR(slider->getAngularPos(), expected, kRoundingTolerance) << "locked " << locked;
		// The pivot stays on the axis.
		const btVector3 pivot = body->getCenterOfMassTransform()(btVector3(0, 0, btScalar(-0.3)));
		EXPECT_LT((pivot - btVector3(pivot.x(), 1, 0)).length(), kRoundingTolerance) << "locked " << locked;
	}
}

TEST(SliderConstraint, ReportedPositionsAreTheMeasuredSlideAndTurn)
{
	// Two free bodies in zero gravity: B slides along A's axis and turns about it while A drifts. Before
	// each step the expected position and angle are measured independently from the bodies' transforms
	// (distance along the reference axis, and the twist of the relative rotation of the frames); after the
	// step the joint reports what it measured at the start of the step.
	for (int trial = 0; trial < 2; ++trial)
	{
		const bool referenceA = trial == 0;
		TestWorld w(btVector3(0, 0, 0));
		btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
		btRigidBody* a =
		    addAwakeBody(w, ball, 3, btTransform(btQuaternion(btVector3(0, 1, 0), 0.3), btVector3(0, 0, 0)));
		// B's frame origin 1 m along A's axis: B's centre at R (1.5, 0, 0) for the body rotation R.
		const btQuaternion turn(btVector3(0, 1, 0), btScalar(0.3));
		btRigidBody* b =
		    addAwakeBody(w, ball, 1, btTransform(turn, btTransform(turn).getBasis() * btVector3(1.5, 0, 0)));
		const btTransform frameInA(btQuaternion::getIdentity(), btVector3(0.2, 0.1, 0));
		const btTransform frameInB(btQuaternion::getIdentity(), btVector3(-0.3, 0.1, 0));
		btSliderConstraint* slider = w.addJoint<btSliderConstraint>(true, *a, *b, frameInA, frameInB, referenceA);
		EXPECT_EQ(slider->getUseLinearReferenceFrameA(), referenceA);
		freeTheTurn(slider);
		const btVector3 axisWorld = a->getCenterOfMassTransform().getBasis() * btVector3(1, 0, 0);
		b->setLinearVelocity(axisWorld * btScalar(0.7));
		b->setAngularVelocity(axisWorld * btScalar(1.3));
		a->setLinearVelocity(btVector3(0.1, 0.2, 0));
		double worstS = 0, worstAngle = 0, largestAngle = 0;
		for (int i = 0; i < 90; ++i)
		{
			const btTransform fa = a->getCenterOfMassTransform() * frameInA;
			const btTransform fb = b->getCenterOfMassTransform() * frameInB;
			const btVector3 delta = fb.getOrigin() - fa.getOrigin();
			const double s = referenceA ? double(delta.dot(fa.getBasis().getColumn(0)))
			                            : -double(delta.dot(fb.getBasis().getColumn(0)));
			const btQuaternion relative = fa.getRotation().inverse() * fb.getRotation();
			double angle = 2.0 * std::atan2(double(relative.x()), double(relative.w()));
			angle = std::atan2(std::sin(angle), std::cos(angle));
			w.run(1);
			worstS = std::max(worstS, std::fabs(slider->getLinearPos() - s));
			worstAngle = std::max(worstAngle, std::fabs(slider->getAngularPos() - angle));
			largestAngle = std::max(largestAngle, std::fabs(angle));
		}
		// The frames stay aligned (the rows are exact), so the twist is the whole relative rotation and the
		// two measurements agree to rounding.
		EXPECT_LT(worstS, kRoundingTolerance) << "reference A " << referenceA;
		EXPECT_LT(worstAngle, 1e-4) << "reference A " << referenceA;
		EXPECT_GT(largestAngle, 0.5);
		// B moves away from A along the axis: with A's frame as reference the position grows, with B's it
		// is A's origin seen from B, so it shrinks.
		EXPECT_EQ(slider->getLinearPos() > 0.5, referenceA);
	}
}

TEST(SliderConstraint, SliderBetweenFreeBodiesConservesMomentumAndAngularMomentum)
{
	// The linear rows push both bodies at one point and the angular rows are pure couples, so the joint
	// cannot change the total momentum or angular momentum. Spheres keep I w a pure spin, and semi-implicit
	// Euler keeps each x cross m v, so both totals are conserved up to rounding.
	TestWorld w(btVector3(0, 0, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.3));
	btRigidBody* a = addAwakeBody(w, ball, 2, btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 0)));
	btRigidBody* b = addAwakeBody(w, ball, 1, btTransform(btQuaternion::getIdentity(), btVector3(1.5, 0.4, 0)));
	// A's frame origin is 0.4 m above A's centre; B's centre sits 0.4 above the axis too: off-axis bodies.
	btSliderConstraint* slider =
	    w.addJoint<btSliderConstraint>(true, *a, *b, btTransform(btQuaternion::getIdentity(), btVector3(0, 0.4, 0)),
	                                   btTransform(btQuaternion::getIdentity(), btVector3(-0.2, 0, 0)), true);
	freeTheTurn(slider);
	b->setLinearVelocity(btVector3(0.5, 1.0, -0.7));
	b->setAngularVelocity(btVector3(0.3, -0.2, 0.9));
	a->setAngularVelocity(btVector3(0, 0.4, 0));
	auto momentum = [&]() { return a->getLinearVelocity() * 2 + b->getLinearVelocity() * 1; };
	auto angularMomentum = [&]()
	{
		btVector3 total(0, 0, 0);
		for (btRigidBody* body : {a, b})
		{
			const btScalar m = 1 / body->getInvMass();
			total += body->getCenterOfMassPosition().cross(body->getLinearVelocity() * m);
			total += body->getInvInertiaTensorWorld().inverse() * body->getAngularVelocity();
		}
		return total;
	};
	const btVector3 p0 = momentum(), l0 = angularMomentum();
	w.run(120);
	// Rounding of impulses of order 1 N s over 120 steps.
	EXPECT_LT((momentum() - p0).length(), 1e-4) << "momentum";
	EXPECT_LT((angularMomentum() - l0).length(), 1e-4) << "angular momentum";
	// And the joint holds: B's frame origin on A's axis, the axes parallel. The rows are exact for the
	// velocities; what the step leaves is the second-order drift of B sliding (1.3 m/s) along an axis
	// that turns (0.34 rad/s): h^2 (2 w v + w^2 r) / 2 = 1.4e-4 m per step, which ERP 0.2 holds at
	// about 1.4e-4 / 0.2 = 7e-4 m.
	const btTransform faNow = a->getCenterOfMassTransform() * slider->getFrameOffsetA();
	const btTransform fbNow = b->getCenterOfMassTransform() * slider->getFrameOffsetB();
	EXPECT_LT(distanceFromLine(fbNow.getOrigin(), faNow.getOrigin(), faNow.getBasis().getColumn(0)), 1e-3);
	EXPECT_LT(double(faNow.getBasis().getColumn(0).cross(fbNow.getBasis().getColumn(0)).length()), 1e-3);
}

TEST(SliderConstraint, DefaultsAndParamsFollowBullet)
{
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
	btSliderConstraint slider(*body, btTransform::getIdentity(), true);
	EXPECT_EQ(slider.getConstraintType(), SLIDER_CONSTRAINT_TYPE);
	EXPECT_EQ(&slider.getRigidBodyA(), &btTypedConstraint::getFixedBody());
	EXPECT_EQ(&slider.getRigidBodyB(), body);
	EXPECT_GT(slider.getLowerLinLimit(), slider.getUpperLinLimit()) << "free slide by default";
	EXPECT_EQ(slider.getLowerAngLimit(), 0);
	EXPECT_EQ(slider.getUpperAngLimit(), 0) << "locked turn by default";
	EXPECT_EQ(slider.getSoftnessDirLin(), SLIDER_CONSTRAINT_DEF_SOFTNESS);
	EXPECT_EQ(slider.getRestitutionLimAng(), SLIDER_CONSTRAINT_DEF_RESTITUTION);
	EXPECT_EQ(slider.getDampingOrthoLin(), SLIDER_CONSTRAINT_DEF_DAMPING);
	EXPECT_EQ(slider.getDampingDirLin(), 0);
	EXPECT_TRUE(slider.getUseFrameOffset());
	EXPECT_EQ(slider.getFlags(), 0);
	slider.setUpperAngLimit(btScalar(SIMD_PI + 0.5));
	EXPECT_NEAR(slider.getUpperAngLimit(), -SIMD_PI + 0.5, 1e-6) << "angular limits are kept in [-pi, pi]";

	slider.setParam(BT_CONSTRAINT_STOP_ERP, btScalar(0.5), 0);
	EXPECT_EQ(slider.getFlags(), BT_SLIDER_FLAGS_ERP_LIMLIN);
	EXPECT_EQ(slider.getParam(BT_CONSTRAINT_STOP_ERP, 0), btScalar(0.5));
	EXPECT_EQ(slider.getSoftnessLimLin(), btScalar(0.5));
	slider.setParam(BT_CONSTRAINT_STOP_CFM, btScalar(0.01), 4);
	EXPECT_TRUE(slider.getFlags() & BT_SLIDER_FLAGS_CFM_ORTANG);
	EXPECT_EQ(slider.getParam(BT_CONSTRAINT_STOP_CFM, 5), btScalar(0.01));
	slider.setParam(BT_CONSTRAINT_CFM, btScalar(0.02), 3);
	EXPECT_TRUE(slider.getFlags() & BT_SLIDER_FLAGS_CFM_DIRANG);
	EXPECT_EQ(slider.getParam(BT_CONSTRAINT_CFM, 3), btScalar(0.02));
	slider.setParam(BT_CONSTRAINT_ERP, btScalar(0.3), 1);
	EXPECT_TRUE(slider.getFlags() & BT_SLIDER_FLAGS_ERP_ORTLIN);
	EXPECT_EQ(slider.getSoftnessOrthoLin(), btScalar(0.3));
	slider.setParam(BT_CONSTRAINT_ERP, btScalar(0.4));  // axis -1: the slide
	EXPECT_TRUE(slider.getFlags() & BT_SLIDER_FLAGS_ERP_DIRLIN);
	EXPECT_EQ(slider.getParam(BT_CONSTRAINT_ERP), btScalar(0.4));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(slider.setParam(BT_CONSTRAINT_ERP, 1, 6), "");
	EXPECT_DEATH(slider.getParam(BT_CONSTRAINT_STOP_CFM, 0), "") << "never set";
#else
	slider.setParam(BT_CONSTRAINT_ERP, 1, 6);  // ignored
	EXPECT_EQ(slider.getParam(BT_CONSTRAINT_ERP, 6), SIMD_INFINITY);
#endif
}

TEST(SliderConstraint, StopCfmSoftensTheRowsAcrossTheAxisByTheExpectedSag)
{
	// With CFM a row settles where its impulse lambda = m g h satisfies erp fps C = -cfm lambda / m
	// (the solver's softness term), so a 1 kg body sags C = g h^2 cfm / erp below the axis: 1.4 mm for
	// cfm 0.1, 5.6 mm for 0.4. Hard rows hold it to rounding (first test).
	for (const btScalar cfm : {btScalar(0.1), btScalar(0.4)})
	{
		TestWorld w(btVector3(0, -kG, 0));
		btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.1)), 1, btTransform::getIdentity());
		btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
		slider->setParam(BT_CONSTRAINT_STOP_CFM, cfm, 1);
		slider->setParam(BT_CONSTRAINT_STOP_CFM, cfm, 2);
		w.run(240);
		const double erp = double(w.world()->getSolverInfo().m_erp), h = double(kH);
		const double expected = double(kG) * h * h * double(cfm) / erp;
		// Ten iterations of a lone row with CFM converge as cfm^10 (1e-4 at 0.4), and the approach at
		// ERP / (1 + cfm) per step is long over after 240 steps: 0.5 % covers both.
		EXPECT_NEAR(-body->getCenterOfMassPosition().y(), expected, 0.005 * expected) << "cfm " << cfm;
		EXPECT_NEAR(body->getCenterOfMassPosition().z(), 0, kRoundingTolerance);
	}
}

TEST(SliderConstraint, NonFiniteOrDegenerateFrameDisablesTheJointWithAWarning)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btTransform nanFrame(btQuaternion::getIdentity(), btVector3(0, nan, 0));
	btTransform zeroFrame;
	zeroFrame.getBasis().setValue(0, 0, 0, 0, 0, 0, 0, 0, 0);
	zeroFrame.setOrigin(btVector3(0, 0, 0));
	for (const btTransform& bad : {nanFrame, zeroFrame})
	{
		TestWorld w(btVector3(0, -kG, 0));
		btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 0, 0));
#if CALIBER_ASSERTS_ENABLED
		EXPECT_DEATH({ btSliderConstraint slider(*body, bad, true); }, "degenerate");
		EXPECT_DEATH({ btSliderConstraint slider(*body, *body, btTransform::getIdentity(), bad, true); }, "degenerate");
#else
		WarningCounter warnings;
		btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, bad, true);
		EXPECT_FALSE(slider->isEnabled());
		EXPECT_EQ(warnings.count(), 1);
		w.run(30);
		// Inert: the body falls freely (semi-implicit Euler: -g h^2 n (n + 1) / 2 = -1.29 m).
		EXPECT_NEAR(body->getCenterOfMassPosition().y(), -10.0 / 3600 * 30 * 31 / 2, 1e-4);
		EXPECT_TRUE(std::isfinite(body->getCenterOfMassPosition().x()));
#endif
	}
}

TEST(SliderConstraint, FrameMadeNonFiniteAfterConstructionDisablesTheJointAtTheNextStep)
{
	WarningCounter warnings;
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* body = addAwakeBody(w, w.shape<btSphereShape>(btScalar(0.2)), 1, btTransform::getIdentity());
	btSliderConstraint* slider = w.addJoint<btSliderConstraint>(false, *body, btTransform::getIdentity(), true);
	w.run(10);
	EXPECT_NEAR(body->getCenterOfMassPosition().y(), 0, kRoundingTolerance);
	slider->getFrameOffsetB().setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0));
	w.run(10);
	EXPECT_FALSE(slider->isEnabled());
	EXPECT_EQ(warnings.count(), 1);
	EXPECT_LT(body->getCenterOfMassPosition().y(), btScalar(-0.1)) << "falls once the joint is gone";
	EXPECT_TRUE(std::isfinite(body->getCenterOfMassPosition().y()));
}
