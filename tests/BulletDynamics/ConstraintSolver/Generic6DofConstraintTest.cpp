// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGeneric6DofConstraint: locked coordinates hold like a weld, free ones move as the physics of the
// remaining degrees of freedom says, limits and motors act on the coordinates, and the reported
// coordinates are the measured ones.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"
#include "JointTestUtil.h"

using caliber_test::CrossingTimer;
using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kG = btScalar(10);
const btScalar kH = btScalar(1. / 240.);

btTransform pose(const btQuaternion& rotation, const btVector3& origin) { return btTransform(rotation, origin); }

// The rotation angle of q (radians, in [0, pi]); through atan2, which stays accurate for small angles.
btScalar rotationAngle(const btQuaternion& q)
{
	const btScalar sine = btVector3(q.getX(), q.getY(), q.getZ()).length();
	return btScalar(2) * btAtan2(sine, btFabs(q.getW()));
}

// Locks all three angles (the linear ones are locked by default).
void lockAngles(btGeneric6DofConstraint* joint)
{
	joint->setAngularLowerLimit(btVector3(0, 0, 0));
	joint->setAngularUpperLimit(btVector3(0, 0, 0));
}

// 1 / (moment of inertia) of body about its local axis i.
double inertiaAbout(const btRigidBody* body, int i) { return 1.0 / double(body->getInvInertiaDiagLocal()[i]); }

// A rotation that takes the local axis `axis` (0, 1, 2) to world z, so that a frame built from it turns
// about world z through that axis.
btQuaternion axisToWorldZ(int axis)
{
	if (axis == 0) return btQuaternion(btVector3(0, 1, 0), -SIMD_HALF_PI);
	if (axis == 1) return btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI);
	return btQuaternion::getIdentity();
}
}  // namespace

namespace
{
void checkLockedPairMovesRigidly(bool referenceFrameA, bool frameOffset)
{
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* a = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.2, 0.2)), 2, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)), 1,
	                           pose(btQuaternion(btVector3(0, 0, 1), btScalar(0.5)), btVector3(1.2, 0.3, 0)));
	const btTransform jointInWorld(btQuaternion(btVector3(1, 1, 0).normalized(), btScalar(0.4)),
	                               btVector3(0.6, 0.1, 0));
	btGeneric6DofConstraint* joint =
	    w.addJoint<btGeneric6DofConstraint>(true, *a, *b, a->getCenterOfMassTransform().inverse() * jointInWorld,
	                                        b->getCenterOfMassTransform().inverse() * jointInWorld, referenceFrameA);
	joint->setUseFrameOffset(frameOffset);
	lockAngles(joint);
	// Start them in one rigid motion: the same spin, and velocities v0 + w x (x - centre of mass).
	const btScalar massA = 2, massB = 1;
	const btVector3 centre =
	    (a->getCenterOfMassPosition() * massA + b->getCenterOfMassPosition() * massB) / (massA + massB);
	const btVector3 spin(0.5, 2, 1), v0(1, 2, 0);
	for (btRigidBody* body : {a, b})
	{
		body->setSleepingThresholds(0, 0);
		body->setAngularVelocity(spin);
		body->setLinearVelocity(v0 + spin.cross(body->getCenterOfMassPosition() - centre));
	}
	const btTransform relative0 = a->getCenterOfMassTransform().inverse() * b->getCenterOfMassTransform();
	btScalar worstGap = 0, worstTurn = 0;
	const int steps = 480;
	for (int i = 0; i < steps; ++i)
	{
		w.run(1, kH);
		const btTransform relative = a->getCenterOfMassTransform().inverse() * b->getCenterOfMassTransform();
		worstGap = btMax(worstGap, (relative.getOrigin() - relative0.getOrigin()).length());
		worstTurn = btMax(worstTurn, rotationAngle(relative.getRotation() * relative0.getRotation().inverse()));
	}
	// Tolerance: the rows hold the relative velocity at zero; what is left is the second-order drift of
	// a spinning pair within one step, (I + [w] h - exp([w] h)) (rB - rA) ~ |w|^2 h^2 |rB - rA| / 2 per step
	// (5.7e-5 m here), which the error reduction (erp = 0.2 per step) holds at drift / erp. Equal spins
	// turn both bodies alike, so the relative rotation has no such drift: float rounding only.
	const btScalar drift = btScalar(0.5) * spin.length2() * kH * kH * relative0.getOrigin().length();
	EXPECT_LT(worstGap, btScalar(1.5) * drift / btScalar(0.2));
	EXPECT_LT(worstTurn, btScalar(1e-5));
	// The joint's impulses are equal and opposite, so the centre of mass falls freely: semi-implicit Euler
	// gives exactly x0 + v0 t - g h^2 n (n + 1) / 2; what is left is float rounding of positions near
	// 16 m (ulp 2e-6) over 480 steps.
	const btVector3 centreNow =
	    (a->getCenterOfMassPosition() * massA + b->getCenterOfMassPosition() * massB) / (massA + massB);
	const btScalar t = kH * steps;
	const btVector3 expected = centre + v0 * t - btVector3(0, kG * kH * kH * steps * (steps + 1) / 2, 0);
	EXPECT_LT((centreNow - expected).length(), btScalar(2e-4)) << centreNow.y() << " vs " << expected.y();
}
}  // namespace

TEST(Generic6DofConstraint, AllAxesLockedPairFallsAndSpinsAsOneRigidBody)
{
	// In every formulation: linear coordinates along frame A's or frame B's axes, rows at the exact point
	// or (frame offset off) at the shared anchor.
	for (int variant = 0; variant < 4; ++variant)
	{
		SCOPED_TRACE(variant);
		checkLockedPairMovesRigidly(variant < 2, variant % 2 == 0);
	}
}

namespace
{
// A rod hanging from the world by a 6dof joint whose angle about world z is free (a hinge), with a ball
// welded to its lower end by a second, all-locked 6dof joint; released at theta0. Returns the measured
// period and fills the exact one of the rigid compound pendulum.
double compoundPendulumPeriod(double theta0, double& exact)
{
	TestWorld w(btVector3(0, -kG, 0));
	const btQuaternion tilt(btVector3(0, 0, 1), btScalar(theta0));
	const btMatrix3x3 turn(tilt);
	btRigidBody* rod =
	    w.addBody(w.shape<btBoxShape>(btVector3(0.05, 0.5, 0.05)), 1, pose(tilt, turn * btVector3(0, -0.5, 0)));
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 2, pose(tilt, turn * btVector3(0, -1.1, 0)));
	for (btRigidBody* body : {rod, ball}) body->setSleepingThresholds(0, 0);
	btGeneric6DofConstraint* hinge = w.addJoint<btGeneric6DofConstraint>(
	    false, *rod, btTransform(btQuaternion::getIdentity(), btVector3(0, 0.5, 0)), true);
	hinge->setAngularLowerLimit(btVector3(0, 0, 1));  // z free (lower > upper), x and y locked
	hinge->setAngularUpperLimit(btVector3(0, 0, -1));
	const btTransform weldInWorld = ball->getCenterOfMassTransform();
	btGeneric6DofConstraint* weld = w.addJoint<btGeneric6DofConstraint>(
	    true, *rod, *ball, rod->getCenterOfMassTransform().inverse() * weldInWorld, btTransform::getIdentity(), true);
	lockAngles(weld);

	// The rigid compound about the pivot: I = sum (I_cm + m d^2), equivalent length I / (M d_cm).
	const double inertia = inertiaAbout(rod, 2) + 1 * 0.25 + inertiaAbout(ball, 2) + 2 * 1.1 * 1.1;
	const double moment = 1 * 0.5 + 2 * 1.1;
	exact = caliber_test::exactPendulumPeriod(inertia / moment, kG, theta0);
	CrossingTimer timer;
	for (int i = 0; i < 240 * 8; ++i)
	{
		w.run(1, kH);
		timer.sample(double(kH) * (i + 1), double(ball->getCenterOfMassPosition().x()));
	}
	return timer.period();
}
}  // namespace

TEST(Generic6DofConstraint, WeldedCompoundPendulumMatchesTheRigidPendulumPeriod)
{
	double exact = 0;
	const double measured = compoundPendulumPeriod(0.6, exact);
	// Tolerance: semi-implicit Euler's phase error (omega h)^2 / 12 is 1.3e-5 here, and the joints' residual
	// (error-reduction) motion is smaller still; 5e-4 leaves room for the zero-crossing interpolation. The
	// ball's own inertia is 0.3 % of the total (a ball free to turn would not carry it), and the 0.6 rad
	// amplitude adds 2.3 %.
	EXPECT_NEAR(measured, exact, 5e-4 * exact);
}

TEST(Generic6DofConstraint, FreeLinearAxisSlidesWithGSinAngleAndTheRestStaysLocked)
{
	const btScalar slope = btScalar(0.5);  // the frame's X axis points down the slope at 0.5 rad
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.1, 0.1)), 3, btVector3(1, 2, 3));
	box->setSleepingThresholds(0, 0);
	btGeneric6DofConstraint* slider = w.addJoint<btGeneric6DofConstraint>(
	    false, *box, btTransform(btQuaternion(btVector3(0, 0, 1), -slope), btVector3(0, 0, 0)), true);
	slider->setLinearLowerLimit(btVector3(1, 0, 0));  // x free
	slider->setLinearUpperLimit(btVector3(-1, 0, 0));
	lockAngles(slider);
	const int steps = 240;
	w.run(steps, kH);
	slider->calculateTransforms();
	// Semi-implicit Euler with acceleration g sin(slope) along the axis: x_n = a h^2 n (n + 1) / 2 exactly.
	const double along = double(kG) * std::sin(double(slope)) * double(kH) * double(kH) * steps * (steps + 1) / 2;
	const btVector3 axis(btCos(slope), -btSin(slope), 0);
	const btVector3 moved = box->getCenterOfMassPosition() - btVector3(1, 2, 3);
	// Tolerances: the along-axis motion is unconstrained, so only float rounding remains (1e-5 of 2.4 m);
	// across the axis the rows hold the velocity at zero, with nothing to drift.
	EXPECT_NEAR(moved.dot(axis), along, 1e-5 * along + 1e-6);
	EXPECT_LT((moved - axis * moved.dot(axis)).length(), btScalar(1e-5));
	EXPECT_NEAR(slider->getRelativePivotPosition(0), moved.dot(axis), 1e-5);
	EXPECT_NEAR(slider->getRelativePivotPosition(1), 0, 1e-5);
	EXPECT_LT(rotationAngle(box->getOrientation()), btScalar(1e-5));
}

namespace
{
// A box hanging 0.8 m below a world pivot by a 6dof joint whose only free coordinate is angle `axis`,
// oriented so that this angle turns about world z; released at theta0. Returns the measured period.
double hingePendulumPeriod(int axis, double theta0, double& exact)
{
	TestWorld w(btVector3(0, -kG, 0));
	const double d = 0.8;
	const btQuaternion tilt(btVector3(0, 0, 1), btScalar(theta0));
	btRigidBody* bob = w.addBody(w.shape<btBoxShape>(btVector3(0.1, 0.15, 0.2)), 2,
	                             pose(tilt, btMatrix3x3(tilt) * btVector3(0, btScalar(-d), 0)));
	bob->setSleepingThresholds(0, 0);
	btGeneric6DofConstraint* joint = w.addJoint<btGeneric6DofConstraint>(
	    false, *bob, btTransform(axisToWorldZ(axis), btVector3(0, btScalar(d), 0)), true);
	btVector3 lower(0, 0, 0), upper(0, 0, 0);
	lower[axis] = 1;  // free
	upper[axis] = -1;
	joint->setAngularLowerLimit(lower);
	joint->setAngularUpperLimit(upper);
	// Physical pendulum about the pivot: equivalent length (I_cm + m d^2) / (m d).
	exact = caliber_test::exactPendulumPeriod((inertiaAbout(bob, 2) + 2 * d * d) / (2 * d), kG, theta0);
	CrossingTimer timer;
	for (int i = 0; i < 240 * 6; ++i)
	{
		w.run(1, kH);
		timer.sample(double(kH) * (i + 1), double(bob->getCenterOfMassPosition().x()));
	}
	return timer.period();
}
}  // namespace

TEST(Generic6DofConstraint, EachFreeAngleSwingsLikeAHingePendulum)
{
	for (int axis = 0; axis < 3; ++axis)
	{
		double exact = 0;
		const double measured = hingePendulumPeriod(axis, 0.7, exact);
		// Tolerance: semi-implicit Euler's phase error (omega h)^2 / 12 = 1.6e-5, the joint's residual motion
		// smaller still, and the zero-crossing interpolation: 5e-4. The 0.7 rad amplitude adds 3.2 % to the
		// small-angle period, and the box's own inertia 1.4 %; both are resolved.
		EXPECT_NEAR(measured, exact, 5e-4 * exact) << "free angle " << axis;
	}
}

TEST(Generic6DofConstraint, LinearLimitStopsTheSlideAtTheLimit)
{
	const btScalar slope = btScalar(0.5), upper = btScalar(0.3);
	TestWorld w(btVector3(0, -kG, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.1, 0.1)), 3, btVector3(0, 0, 0));
	box->setSleepingThresholds(0, 0);
	btGeneric6DofConstraint* slider = w.addJoint<btGeneric6DofConstraint>(
	    false, *box, btTransform(btQuaternion(btVector3(0, 0, 1), -slope), btVector3(0, 0, 0)), true);
	slider->setLinearLowerLimit(btVector3(-0.2, 0, 0));
	slider->setLinearUpperLimit(btVector3(upper, 0, 0));
	lockAngles(slider);
	EXPECT_TRUE(slider->isLimited(0));
	const btVector3 axis(btCos(slope), -btSin(slope), 0);
	btScalar furthest = -1;
	for (int i = 0; i < 240; ++i)
	{
		w.run(1, kH);
		furthest = btMax(furthest, box->getCenterOfMassPosition().dot(axis));
	}
	// It reaches the limit at 0.35 s at 2.9 m/s (12 mm per step). Tolerance: the limit row lets the box
	// close exactly the remaining gap in the step it arrives, so nothing passes but float rounding.
	EXPECT_LT(furthest, upper + btScalar(1e-5));
	EXPECT_NEAR(box->getCenterOfMassPosition().dot(axis), upper, 1e-5);
	EXPECT_NEAR(box->getLinearVelocity().length(), 0, 1e-3) << "it rests against the limit";
	slider->calculateTransforms();
	EXPECT_NEAR(slider->getRelativePivotPosition(0), upper, 1e-5);
}

namespace
{
// A pendulum (free angle x about world z) released at +theta0 with its angle limited to [lower, +1];
// returns the lowest angle reached and the highest angle after the first return.
void limitedPendulum(btScalar lower, btScalar bounce, btScalar theta0, btScalar& lowest, btScalar& reboundPeak)
{
	TestWorld w(btVector3(0, -kG, 0));
	const double d = 0.8;
	const btQuaternion tilt(btVector3(0, 0, 1), theta0);
	btRigidBody* bob = w.addBody(w.shape<btSphereShape>(btScalar(0.1)), 1,
	                             pose(tilt, btMatrix3x3(tilt) * btVector3(0, btScalar(-d), 0)));
	bob->setSleepingThresholds(0, 0);
	btGeneric6DofConstraint* joint = w.addJoint<btGeneric6DofConstraint>(
	    false, *bob, btTransform(axisToWorldZ(0), btVector3(0, btScalar(d), 0)), true);
	joint->setAngularLowerLimit(btVector3(lower, 0, 0));
	joint->setAngularUpperLimit(btVector3(1, 0, 0));
	joint->getRotationalLimitMotor(0)->m_bounce = bounce;
	// The joint's angle is measured from where the bob was built: swing angle = theta0 + angle.
	lowest = 10;
	reboundPeak = -10;
	bool turned = false;
	btScalar previous = 0;
	for (int i = 0; i < 240 * 2; ++i)
	{
		w.run(1, kH);
		joint->calculateTransforms();
		const btScalar swing = theta0 + joint->getAngle(0);
		lowest = btMin(lowest, swing);
		if (i > 0 && swing > previous) turned = true;
		if (turned) reboundPeak = btMax(reboundPeak, swing);
		previous = swing;
	}
}
}  // namespace

TEST(Generic6DofConstraint, AngularLimitStopsTheSwingAndBounceReturnsTheEnergy)
{
	const btScalar theta0 = btScalar(0.3);
	// The limit sits at swing angle -0.1, i.e. joint angle -0.4.
	btScalar lowest, peak;
	limitedPendulum(-0.4, 0, theta0, lowest, peak);
	// Tolerance: the limit row closes exactly the remaining gap in the arrival step (it arrives at 1 rad/s,
	// 4 mrad per step), so only float rounding remains.
	EXPECT_GT(lowest, btScalar(-0.1 - 1e-5));
	EXPECT_LT(lowest, btScalar(-0.1 + 1e-5));
	// An inelastic stop leaves the bob at rest at -0.1, and it swings back to +0.1 by energy conservation
	// (without the limit it would return to +0.3). Tolerance: semi-implicit Euler's energy error,
	// O((w h)^2) = 2e-5 relative, and the 4 mrad of one step's travel bound the peak to 1e-3.
	EXPECT_NEAR(peak, 0.1, 1e-3);

	limitedPendulum(-0.4, 1, theta0, lowest, peak);
	// With bounce the speed is reversed up to one step before the limit (the row acts as soon as the step
	// would reach it), so the lowest point is within one step's travel above -0.1.
	EXPECT_GT(lowest, btScalar(-0.1 - 1e-5));
	EXPECT_LT(lowest, btScalar(-0.1 + 5e-3));
	// A bounce of 1 reverses the speed without changing it: the energy is kept and the swing returns to
	// +0.3 (same tolerance).
	EXPECT_NEAR(peak, theta0, 1e-3);
}

TEST(Generic6DofConstraint, LinearMotorReachesItsTargetVelocityAtTheForceItIsAllowed)
{
	TestWorld w(btVector3(0, 0, 0));
	const btScalar mass = 2, force = 5, target = 2;
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.1, 0.1)), mass, btVector3(0, 0, 0));
	box->setSleepingThresholds(0, 0);
	btGeneric6DofConstraint* slider = w.addJoint<btGeneric6DofConstraint>(
	    false, *box, btTransform(btQuaternion(btVector3(0, 0, 1), btScalar(0.3)), btVector3(0, 0, 0)), true);
	slider->setLinearLowerLimit(btVector3(1, 0, 0));
	slider->setLinearUpperLimit(btVector3(-1, 0, 0));
	lockAngles(slider);
	btTranslationalLimitMotor* motor = slider->getTranslationalLimitMotor();
	motor->m_enableMotor[0] = true;
	motor->m_targetVelocity[0] = target;
	motor->m_maxMotorForce[0] = force;
	const btVector3 axis(btCos(btScalar(0.3)), btSin(btScalar(0.3)), 0);
	// F / m = 2.5 m/s^2: after 0.4 s it moves at 1 m/s (exactly n F h / m: the motor row is force-bound).
	w.run(96, kH);
	EXPECT_NEAR(box->getLinearVelocity().dot(axis), 96 * force * kH / mass, 1e-5);
	w.run(240, kH);
	// Tolerance: once reached, the row holds the target velocity exactly (float rounding).
	EXPECT_NEAR(box->getLinearVelocity().dot(axis), target, 1e-5);
	EXPECT_LT((box->getLinearVelocity() - axis * target).length(), btScalar(1e-5));
	slider->calculateTransforms();
	EXPECT_GT(slider->getRelativePivotPosition(0), btScalar(0)) << "a positive target makes the coordinate grow";
}

TEST(Generic6DofConstraint, AngularMotorReachesItsTargetRateAtTheTorqueItIsAllowed)
{
	TestWorld w(btVector3(0, 0, 0));
	const btScalar torque = btScalar(0.5), target = 3;
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.3, 0.4)), 2, btVector3(0, 0, 0));
	box->setSleepingThresholds(0, 0);
	// The frame's X axis is the body's local y axis.
	btGeneric6DofConstraint* joint = w.addJoint<btGeneric6DofConstraint>(
	    false, *box, btTransform(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI), btVector3(0, 0, 0)), true);
	joint->setAngularLowerLimit(btVector3(1, 0, 0));
	joint->setAngularUpperLimit(btVector3(-1, 0, 0));
	btRotationalLimitMotor* motor = joint->getRotationalLimitMotor(0);
	motor->m_enableMotor = true;
	motor->m_targetVelocity = target;
	motor->m_maxMotorForce = torque;
	const double inertia = inertiaAbout(box, 1);
	w.run(24, kH);
	// Torque-bound: the rate grows by tau h / I per step exactly.
	EXPECT_NEAR(box->getAngularVelocity().y(), 24 * torque * kH / inertia, 1e-5);
	w.run(240 * 2, kH);
	EXPECT_NEAR(box->getAngularVelocity().y(), target, 1e-4);
	EXPECT_LT(btFabs(box->getAngularVelocity().x()) + btFabs(box->getAngularVelocity().z()), btScalar(1e-5));
}

TEST(Generic6DofConstraint, ReportedAnglesAndPositionsAreTheMeasuredOnes)
{
	TestWorld w(btVector3(0, 0, 0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2));
	const btTransform poseA(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7)), btVector3(1, -2, 0.5));
	const btScalar x = btScalar(0.4), y = btScalar(-0.9), z = btScalar(2.5);
	const btVector3 offset(0.3, -0.2, 0.7);  // in frame A
	const btQuaternion relative =
	    btQuaternion(btVector3(0, 0, 1), z) * btQuaternion(btVector3(0, 1, 0), y) * btQuaternion(btVector3(1, 0, 0), x);
	const btTransform poseB = poseA * btTransform(relative, offset);
	btRigidBody* a = w.addBody(box, 1, poseA);
	btRigidBody* b = w.addBody(box, 1, poseB);
	for (int reference = 0; reference < 2; ++reference)
	{
		btGeneric6DofConstraint joint(*a, *b, btTransform::getIdentity(), btTransform::getIdentity(), reference == 0);
		joint.calculateTransforms();
		// A^-1 B = Rz(z) Ry(y) Rx(x): the angles come back to float rounding.
		EXPECT_NEAR(joint.getAngle(0), x, 1e-5);
		EXPECT_NEAR(joint.getAngle(1), y, 1e-5);
		EXPECT_NEAR(joint.getAngle(2), z, 1e-5);
		const btVector3 inB = btMatrix3x3(relative).transpose() * offset;
		for (int i = 0; i < 3; ++i)
			EXPECT_NEAR(joint.getRelativePivotPosition(i), reference == 0 ? offset[i] : inB[i], 1e-5) << i;
		// getAxis(i) is the direction along which angular velocity changes angle i: turning B a little
		// about any direction perpendicular to it leaves angle i unchanged to second order.
		for (int i = 0; i < 3; ++i)
		{
			const btVector3 axis = joint.getAxis(i);
			EXPECT_NEAR(axis.length(), 1, 1e-5);
			btVector3 p, q;
			btPlaneSpace1(axis, p, q);
			for (const btVector3& perpendicular : {p, q})
			{
				const btScalar eps = btScalar(1e-3);
				btTransform turned = b->getCenterOfMassTransform();
				turned.setBasis(btMatrix3x3(btQuaternion(perpendicular, eps)) * turned.getBasis());
				joint.calculateTransforms(a->getCenterOfMassTransform(), turned);
				const btScalar changed = joint.getAngle(i);
				joint.calculateTransforms();
				// Second order: eps^2 / cos(y) ~ 2e-6; a wrong axis would change it by ~eps.
				EXPECT_NEAR(changed, joint.getAngle(i), 2e-5) << "angle " << i;
			}
		}
	}
}

TEST(Generic6DofConstraint, LockedRowsComeFirstThenLimitsThenMotors)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)), 1, btVector3(0, 0, 0));
	btGeneric6DofConstraint joint(*box, btTransform::getIdentity(), true);
	joint.setLinearLowerLimit(btVector3(0, -1, 1));  // x locked, y limited, z free
	joint.setLinearUpperLimit(btVector3(0, 1, -1));
	joint.setAngularLowerLimit(btVector3(1, 0, -0.5));  // x free, y locked, z limited
	joint.setAngularUpperLimit(btVector3(-1, 0, 0.5));
	joint.getTranslationalLimitMotor()->m_enableMotor[2] = true;
	joint.getTranslationalLimitMotor()->m_maxMotorForce[2] = 1;
	joint.getRotationalLimitMotor(0)->m_enableMotor = true;
	joint.getRotationalLimitMotor(1)->m_enableMotor = true;  // on a locked angle: no row
	btTypedConstraint::btConstraintInfo1 info1;
	joint.getInfo1(&info1);
	EXPECT_EQ(info1.m_numConstraintRows, 2 + 2 + 2);
	const int n = info1.m_numConstraintRows, skip = 3;
	std::vector<btScalar> j1l(n * skip, 0), j1a(n * skip, 0), j2l(n * skip, 0), j2a(n * skip, 0);
	std::vector<btScalar> error(n * skip, 0), cfm(n * skip, 0), lower(n * skip, -SIMD_INFINITY),
	    upper(n * skip, SIMD_INFINITY);
	btTypedConstraint::btConstraintInfo2 info2;
	info2.fps = 60;
	info2.erp = btScalar(0.2);
	info2.m_J1linearAxis = j1l.data();
	info2.m_J1angularAxis = j1a.data();
	info2.m_J2linearAxis = j2l.data();
	info2.m_J2angularAxis = j2a.data();
	info2.rowskip = skip;
	info2.m_constraintError = error.data();
	info2.cfm = cfm.data();
	info2.m_lowerLimit = lower.data();
	info2.m_upperLimit = upper.data();
	info2.m_numIterations = 10;
	info2.m_damping = 1;
	joint.getInfo2(&info2);
	for (int r = 0; r < 2; ++r)  // the locked linear x and angle y: unbounded
	{
		EXPECT_EQ(lower[r * skip], -SIMD_INFINITY) << r;
		EXPECT_EQ(upper[r * skip], SIMD_INFINITY) << r;
	}
	EXPECT_EQ(j1l[0], btScalar(-1)) << "row 0 is linear x";
	EXPECT_EQ(j1a[1 * skip + 1], btScalar(-1)) << "row 1 is angle y";
	for (int r = 2; r < 4; ++r)  // limits: one-sided
		EXPECT_TRUE(lower[r * skip] == 0 || upper[r * skip] == 0) << r;
	for (int r = 4; r < 6; ++r)  // motors: bounded both ways by force * h
	{
		EXPECT_NEAR(upper[r * skip], r == 4 ? 1.0 / 60 : 6.0 / 60, 1e-7) << r;
		EXPECT_EQ(lower[r * skip], -upper[r * skip]) << r;
	}
}

TEST(Generic6DofConstraint, ParamsArePerAxisAndSoftenTheirRows)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)), 1, btVector3(0, 0, 0));
	btGeneric6DofConstraint joint(*box, btTransform::getIdentity(), true);
	joint.setParam(BT_CONSTRAINT_STOP_ERP, btScalar(0.7), 1);
	joint.setParam(BT_CONSTRAINT_STOP_CFM, btScalar(0.1), 4);
	joint.setParam(BT_CONSTRAINT_CFM, btScalar(0.3), 5);
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_STOP_ERP, 1), btScalar(0.7));
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_STOP_CFM, 4), btScalar(0.1));
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_CFM, 5), btScalar(0.3));
	EXPECT_EQ(joint.getFlags(),
	          (BT_6DOF_FLAGS_ERP_STOP << 3) | (BT_6DOF_FLAGS_CFM_STOP << 12) | (BT_6DOF_FLAGS_CFM_NORM << 15));
	EXPECT_EQ(joint.getRotationalLimitMotor(1)->m_stopCFM, btScalar(0.1));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(joint.setParam(BT_CONSTRAINT_CFM, 1, 6), "axis");
	EXPECT_DEATH(joint.getParam(BT_CONSTRAINT_CFM, 0), "m_flags");
#else
	const int flags = joint.getFlags();
	WarningCounter warnings;
	joint.setParam(BT_CONSTRAINT_CFM, 1, 6);
	joint.setParam(BT_CONSTRAINT_STOP_ERP, 1, -1);
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_CFM, 6), SIMD_INFINITY);
	EXPECT_EQ(warnings.count(), 3);
	EXPECT_EQ(joint.getFlags(), flags) << "an axis out of range changes nothing";
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_CFM, 0), btScalar(0)) << "a parameter never set reads its default";
	EXPECT_EQ(joint.getParam(BT_CONSTRAINT_STOP_ERP, 0), btScalar(0.2));
#endif
}

TEST(Generic6DofConstraint, IndexedAccessorsOutOfRangeAreReportedNeverRead)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)), 1, btVector3(0, 0, 0));
	btGeneric6DofConstraint joint(*box, btTransform::getIdentity(), true);
	joint.setLimit(0, -1, 1);
	joint.calculateTransforms();
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(joint.getAxis(3), "index out of range");
	EXPECT_DEATH(joint.getRotationalLimitMotor(-1), "index out of range");
	EXPECT_DEATH(joint.setLimit(6, 0, 1), "index out of range");
#else
	WarningCounter warnings;
	EXPECT_EQ(joint.getAxis(3), btVector3(0, 0, 0));
	EXPECT_EQ(joint.getAngle(-1), btScalar(0));
	EXPECT_EQ(joint.getRelativePivotPosition(7), btScalar(0));
	EXPECT_FALSE(joint.isLimited(6));
	EXPECT_EQ(joint.getRotationalLimitMotor(-1), joint.getRotationalLimitMotor(0)) << "clamped to the first angle";
	EXPECT_EQ(joint.getRotationalLimitMotor(3), joint.getRotationalLimitMotor(2)) << "clamped to the last angle";
	joint.setLimit(6, 0, 1);
	joint.setLimit(-1, 0, 1);
	EXPECT_EQ(warnings.count(), 8);
#endif
	EXPECT_TRUE(joint.isLimited(0)) << "valid settings are untouched";
	EXPECT_EQ(joint.getAxis(0), btVector3(1, 0, 0));
}

TEST(Generic6DofConstraint, StopErpSetsHowFastALockedAxisIsPulledBack)
{
	// A body displaced by 0.1 m along a locked axis is pulled back by the fraction erp per step.
	for (const btScalar erp : {btScalar(0.2), btScalar(0.8)})
	{
		TestWorld w(btVector3(0, 0, 0));
		btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)), 1, btVector3(0, 0, 0));
		btGeneric6DofConstraint* joint =
		    w.addJoint<btGeneric6DofConstraint>(false, *box, btTransform::getIdentity(), true);
		lockAngles(joint);
		joint->setParam(BT_CONSTRAINT_STOP_ERP, erp, 0);
		box->translate(btVector3(0.1, 0, 0));
		w.run(1, kH);
		// The velocity row asks for erp * 0.1 / h back, and the block solve delivers it exactly.
		EXPECT_NEAR(box->getCenterOfMassPosition().x(), 0.1 * (1 - erp), 1e-5);
	}
}

TEST(Generic6DofConstraint, NonFiniteFrameIsReportedAndTheJointIsInert)
{
	WarningCounter warnings;
	TestWorld w(btVector3(0, -kG, 0));
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.2));
	btRigidBody* a = w.addBody(ball, 1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(ball, 1, btVector3(0, -1, 0));
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	btGeneric6DofConstraint* joint = w.addJoint<btGeneric6DofConstraint>(
	    false, *a, *b, btTransform(btQuaternion::getIdentity(), btVector3(0, nan, 0)), btTransform::getIdentity(),
	    true);
	EXPECT_FALSE(joint->isEnabled());
	EXPECT_EQ(warnings.count(), 1);
	w.run(30);
	for (btRigidBody* body : {a, b})
	{
		EXPECT_TRUE(std::isfinite(body->getCenterOfMassPosition().y()));
		EXPECT_LT(body->getCenterOfMassPosition().y(), btScalar(-0.5)) << "both fall freely";
	}
	// setFrames with a non-finite frame is reported the same way.
	btRigidBody* c = w.addBody(ball, 1, btVector3(5, 0, 0));
	btGeneric6DofConstraint* good = w.addJoint<btGeneric6DofConstraint>(false, *c, btTransform::getIdentity(), true);
	EXPECT_TRUE(good->isEnabled());
	good->setFrames(btTransform(btQuaternion::getIdentity(), btVector3(nan, 0, 0)), btTransform::getIdentity());
	EXPECT_FALSE(good->isEnabled());
	EXPECT_EQ(warnings.count(), 2);
}

TEST(Generic6DofConstraint, DefaultsAreBulletsLinearLockedAngularFree)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)), 1, btVector3(0, 0, 0));
	btGeneric6DofConstraint joint(*box, btTransform::getIdentity(), true);
	for (int i = 0; i < 3; ++i) EXPECT_TRUE(joint.isLimited(i));
	for (int i = 3; i < 6; ++i) EXPECT_FALSE(joint.isLimited(i));
	EXPECT_TRUE(joint.getUseFrameOffset());
	EXPECT_TRUE(joint.getUseLinearReferenceFrameA());
	EXPECT_EQ(joint.getConstraintType(), D6_CONSTRAINT_TYPE);
	joint.setLimit(4, btScalar(-0.5), btScalar(0.5));
	EXPECT_TRUE(joint.isLimited(4));
	btVector3 lower, upper;
	joint.getAngularLowerLimit(lower);
	joint.getAngularUpperLimit(upper);
	EXPECT_EQ(lower.y(), btScalar(-0.5));
	EXPECT_EQ(upper.y(), btScalar(0.5));
}

TEST(Generic6DofConstraint, SetAxisReorientsTheFramesAboutTheirPivots)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)), 1, btVector3(1, 2, 3));
	box->setSleepingThresholds(0, 0);
	btGeneric6DofConstraint* slider = w.addJoint<btGeneric6DofConstraint>(
	    false, *box, btTransform(btQuaternion::getIdentity(), btVector3(0.1, 0, 0)), true);
	lockAngles(slider);
	slider->setLinearLowerLimit(btVector3(1, 0, 0));  // x free
	slider->setLinearUpperLimit(btVector3(-1, 0, 0));
	// Z along axis1 = world x, Y along axis2 = world y, so X = Y x Z = -z.
	slider->setAxis(btVector3(2, 0, 0), btVector3(0, 1, 0));
	EXPECT_LT((slider->getCalculatedTransformA().getBasis().getColumn(0) - btVector3(0, 0, -1)).length(), 1e-6);
	EXPECT_LT((slider->getCalculatedTransformB().getBasis().getColumn(2) - btVector3(1, 0, 0)).length(), 1e-6);
	EXPECT_LT((slider->getCalculatedTransformA().getOrigin() - btVector3(1.1, 2, 3)).length(), 1e-6) << "pivot kept";
	box->setLinearVelocity(btVector3(1, 0.5, -2));
	w.run(1, kH);
	// Only the motion along the new X (world -z) is free; the block removes the rest exactly.
	EXPECT_LT((box->getLinearVelocity() - btVector3(0, 0, -2)).length(), btScalar(1e-5));
}

TEST(Generic6DofConstraint, MotorBetweenTwoBodiesDrivesTheirRelativeVelocityAndKeepsMomentum)
{
	TestWorld w(btVector3(0, 0, 0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2));
	const btScalar massA = 1, massB = 3, force = 2, target = 1;
	btRigidBody* a = w.addBody(box, massA, btVector3(-0.5, 0, 0));
	btRigidBody* b = w.addBody(box, massB, btVector3(0.5, 0, 0));
	const btTransform middle = btTransform::getIdentity();
	btGeneric6DofConstraint* joint =
	    w.addJoint<btGeneric6DofConstraint>(true, *a, *b, a->getCenterOfMassTransform().inverse() * middle,
	                                        b->getCenterOfMassTransform().inverse() * middle, true);
	lockAngles(joint);
	joint->setLinearLowerLimit(btVector3(1, 0, 0));
	joint->setLinearUpperLimit(btVector3(-1, 0, 0));
	btTranslationalLimitMotor* motor = joint->getTranslationalLimitMotor();
	motor->m_enableMotor[0] = true;
	motor->m_targetVelocity[0] = target;
	motor->m_maxMotorForce[0] = force;
	// The force F pushes them apart: relative acceleration F (1 / mA + 1 / mB) = 2.67 m/s^2.
	w.run(24, kH);
	const btScalar relative = b->getLinearVelocity().x() - a->getLinearVelocity().x();
	EXPECT_NEAR(relative, 24 * force * kH * (1 / massA + 1 / massB), 1e-5);
	w.run(240, kH);
	EXPECT_NEAR(b->getLinearVelocity().x() - a->getLinearVelocity().x(), target, 1e-5);
	// Equal and opposite impulses: the total momentum stays zero (float rounding), split as 3 : 1.
	EXPECT_NEAR(massA * a->getLinearVelocity().x() + massB * b->getLinearVelocity().x(), 0, 1e-5);
	EXPECT_NEAR(a->getLinearVelocity().x(), -0.75, 1e-5);
	EXPECT_LT(a->getAngularVelocity().length() + b->getAngularVelocity().length(), btScalar(1e-5));
}
