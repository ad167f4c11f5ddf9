// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btTransformUtil.h"

#include <gtest/gtest.h>

#include <math.h>

#include <string>

#include "MathTestUtil.h"

using caliber_test::kTightTolerance;
using caliber_test::Random;
using caliber_test::rotationsNear;
using caliber_test::vectorsNear;

namespace
{
const btScalar kThreshold = ANGULAR_MOTION_THRESHOLD;

// The rotation by angleRadians about the direction of axis, evaluated in double and rounded once to
// btScalar: a reference that does not share the code under test.
btQuaternion exactRotation(const btVector3& axis, double angleRadians)
{
	const double x = axis.x(), y = axis.y(), z = axis.z();
	const double s = sin(0.5 * angleRadians) / sqrt(x * x + y * y + z * z);
	return btQuaternion(btScalar(x * s), btScalar(y * s), btScalar(z * s), btScalar(cos(0.5 * angleRadians)));
}

double lengthInDouble(const btVector3& v)
{
	return sqrt(double(v.x()) * v.x() + double(v.y()) * v.y() + double(v.z()) * v.z());
}

// Half of the antisymmetric part of a rotation matrix, (m21 - m12, m02 - m20, m10 - m01) / 2, equals
// sin(angle) * axis. Unlike the angle recovered through a quaternion's w, it keeps full relative
// precision for tiny rotations, so it measures a tiny rotation without cancellation.
btVector3 sinAngleTimesAxis(const btMatrix3x3& m)
{
	return btScalar(0.5) * btVector3(m[2][1] - m[1][2], m[0][2] - m[2][0], m[1][0] - m[0][1]);
}

btTransform randomTransform(Random& rng, btScalar positionRange)
{
	return btTransform(rng.rotation(), rng.vector(positionRange));
}
}  // namespace

// ---- integrateTransform -------------------------------------------------------------------------

TEST(TransformUtilIntegrate, OneStepMatchesExactRotationForConstantAngularVelocity)
{
	Random rng(101);
	for (int i = 0; i < 500; ++i)
	{
		const btTransform start = randomTransform(rng, 10);
		const btScalar dt = rng.uniform(btScalar(1.0 / 240), btScalar(1.0 / 30));
		// |w| dt from far below to just below the clamp, so only the exact exponential map is involved.
		const btScalar stepAngle = rng.uniform(btScalar(1e-3), btScalar(0.99) * kThreshold);
		const btVector3 w = rng.unitVector() * (stepAngle / dt);
		btTransform predicted;
		btTransformUtil::integrateTransform(start, rng.vector(5), w, dt, predicted);

		const btQuaternion expected = exactRotation(w, lengthInDouble(w) * dt) * start.getRotation();
		// The step quaternion, one product, a normalisation and a quaternion -> matrix -> quaternion round
		// trip each round a few times on values of order 1: well inside kTightTolerance (64 eps).
		EXPECT_TRUE(rotationsNear(predicted.getRotation(), expected, kTightTolerance)) << "case " << i;
		EXPECT_TRUE(caliber_test::matricesNear(predicted.getBasis(), btMatrix3x3(expected), kTightTolerance))
		    << "case " << i;
	}
}

TEST(TransformUtilIntegrate, ManyStepsAboutFixedAxisComposeToExactRotation)
{
	Random rng(102);
	const int kSteps = 1000;
	const btScalar dt = btScalar(1.0 / 60);
	const btVector3 w = btVector3(1, 2, 2) * btScalar(1.5 / 3.0);  // |w| about 1.5 rad/s: 25 rad in total
	const btTransform start(rng.rotation(), btVector3(1, -2, 3));
	btTransform current = start;
	for (int i = 0; i < kSteps; ++i)
	{
		btTransform next;
		btTransformUtil::integrateTransform(current, btVector3(0, 0, 0), w, dt, next);
		current = next;
	}
	// Reference: the whole turn |w| N dt at once, in double.
	const btQuaternion expected = exactRotation(w, lengthInDouble(w) * double(dt) * kSteps) * start.getRotation();
	// Each step adds at most ~3 eps of rounding (the worst single step in the test above) and every later
	// step is a rotation, which carries earlier errors along without amplifying them, so the error grows at
	// most linearly: N steps * 4 eps. (Measured: about 30 eps, since the per-step errors mostly cancel.)
	// The rounding of |w| dt itself is a relative eps per step in the angle, i.e. about eps * 25 rad in
	// total, far inside that bound.
	const btScalar tolerance = btScalar(4 * kSteps) * SIMD_EPSILON;
	EXPECT_TRUE(rotationsNear(current.getRotation(), expected, tolerance));
	EXPECT_TRUE(caliber_test::matricesNear(current.getBasis(), btMatrix3x3(expected), tolerance));
	// The origin never moves with zero linear velocity.
	EXPECT_EQ(current.getOrigin(), start.getOrigin());
}

TEST(TransformUtilIntegrate, LinearPartIsExactAndIndependentOfRotation)
{
	// Dyadic values: x0 + v dt is exact in binary floating point, so the result must be bit-exact.
	btTransform start(btQuaternion(btVector3(0, 1, 0), btScalar(0.3)), btVector3(1, 2, -3));
	btTransform predicted;
	btTransformUtil::integrateTransform(start, btVector3(btScalar(0.5), btScalar(-0.25), 2), btVector3(3, 1, -2),
	                                    btScalar(0.125), predicted);
	EXPECT_EQ(predicted.getOrigin(), btVector3(btScalar(1.0625), btScalar(1.96875), btScalar(-2.75)));

	// Random values: the origin is x0 + v dt rounded per component exactly as written (one product, one
	// sum), whatever the rotation and the angular velocity are.
	Random rng(103);
	for (int i = 0; i < 200; ++i)
	{
		const btTransform t0 = randomTransform(rng, 10);
		const btVector3 v = rng.vector(20);
		const btScalar dt = rng.uniform(btScalar(1e-3), btScalar(0.1));
		btTransform withSpin, withoutSpin;
		btTransformUtil::integrateTransform(t0, v, rng.vector(30), dt, withSpin);
		btTransformUtil::integrateTransform(t0, v, btVector3(0, 0, 0), dt, withoutSpin);
		for (int axis = 0; axis < 3; ++axis)
		{
			const btScalar displacement = v[axis] * dt;
			const btScalar expected = t0.getOrigin()[axis] + displacement;
			EXPECT_EQ(withSpin.getOrigin()[axis], expected) << "case " << i << " axis " << axis;
		}
		EXPECT_EQ(withSpin.getOrigin(), withoutSpin.getOrigin()) << "case " << i;
	}
}

TEST(TransformUtilIntegrate, ZeroAngularVelocityKeepsRotation)
{
	Random rng(104);
	for (int i = 0; i < 100; ++i)
	{
		const btTransform t0 = randomTransform(rng, 5);
		btTransform t1;
		btTransformUtil::integrateTransform(t0, rng.vector(1), btVector3(0, 0, 0), btScalar(1.0 / 60), t1);
		// Only the matrix -> quaternion -> matrix round trip rounds: a few eps.
		EXPECT_TRUE(caliber_test::matricesNear(t1.getBasis(), t0.getBasis(), kTightTolerance)) << "case " << i;
	}
}

// A faster spin turns by exactly the threshold about the same axis (a clamp that scaled only the angle
// but not the axis part of the step quaternion would turn by up to a half turn instead).
TEST(TransformUtilIntegrate, FastSpinIsClampedToAngularMotionThreshold)
{
	Random rng(105);
	const btScalar dt = btScalar(1.0 / 60);
	const btScalar factors[] = {btScalar(1.01), btScalar(2), btScalar(10), btScalar(1000), btScalar(1e6)};
	for (btScalar factor : factors)
	{
		const btTransform start = randomTransform(rng, 1);
		const btVector3 axis = rng.unitVector();
		const btVector3 w = axis * (factor * kThreshold / dt);
		btTransform predicted;
		btTransformUtil::integrateTransform(start, btVector3(0, 0, 0), w, dt, predicted);
		// The applied rotation must be exactly the threshold angle about w's direction. The rounding is
		// that of one step (a few eps, see OneStepMatchesExactRotation) plus eps-relative rounding of the
		// clamped speed.
		const btQuaternion expected = exactRotation(axis, kThreshold) * start.getRotation();
		btVector3 appliedAxis;
		btScalar appliedAngle;
		btTransformUtil::calculateDiffAxisAngleQuaternion(start.getRotation(), predicted.getRotation(), appliedAxis,
		                                                  appliedAngle);
		EXPECT_TRUE(rotationsNear(predicted.getRotation(), expected, kTightTolerance))
		    << "|w| dt = " << factor << " x threshold: applied angle " << appliedAngle << " rad, expected "
		    << kThreshold;
	}
}

TEST(TransformUtilIntegrate, SpinJustBelowThresholdIsNotClamped)
{
	const btScalar dt = btScalar(1.0 / 60);
	const btVector3 w = btVector3(2, -1, 2) * (btScalar(0.999) * kThreshold / dt / btScalar(3));
	btTransform start;
	start.setIdentity();
	btTransform predicted;
	btTransformUtil::integrateTransform(start, btVector3(0, 0, 0), w, dt, predicted);
	// A single exact step: a few eps (see OneStepMatchesExactRotation).
	EXPECT_TRUE(rotationsNear(predicted.getRotation(), exactRotation(w, lengthInDouble(w) * dt), kTightTolerance));
}

TEST(TransformUtilIntegrate, TinyAngularVelocityGivesTinyAngle)
{
	// From the identity, the rotation's antisymmetric part holds sin(angle) * axis at full relative
	// precision, so a turn of 1e-9 rad/s * 1/60 s = 1.7e-11 rad is measurable. It is computed by the
	// series branch of integrateTransform.
	const btScalar dt = btScalar(1.0 / 60);
	const btVector3 axes[] = {btVector3(1, 0, 0), btVector3(0, 0, -1), btVector3(2, -1, 2) / btScalar(3)};
	for (const btVector3& axis : axes)
	{
		const btVector3 w = axis * btScalar(1e-9);
		btTransform start;
		start.setIdentity();
		btTransform predicted;
		btTransformUtil::integrateTransform(start, btVector3(0, 0, 0), w, dt, predicted);
		const double angle = 1e-9 * double(dt);
		const btVector3 expected = axis * btScalar(angle);
		// Relative: the quaternion and matrix entries are each rounded a few times: kTightTolerance.
		EXPECT_TRUE(vectorsNear(sinAngleTimesAxis(predicted.getBasis()), expected, kTightTolerance * btScalar(angle)))
		    << "expected angle " << angle;
		const btQuaternion q = predicted.getRotation();
		EXPECT_TRUE(
		    vectorsNear(btVector3(q.x(), q.y(), q.z()), expected * btScalar(0.5), kTightTolerance * btScalar(angle)));
		EXPECT_EQ(predicted.getBasis()[0][0], btScalar(1)) << "cos(1.7e-11) rounds to 1";
	}
}

TEST(TransformUtilIntegrate, SeriesAndExactBranchesAgreeNearTheSwitch)
{
	// The implementation switches formulas at half angle 1e-3; on both sides, and across several
	// decades, the tiny rotation must match sin(angle) * axis to a relative few eps (kTightTolerance).
	const btScalar dt = btScalar(1.0 / 60);
	const btVector3 axis = btVector3(-2, 2, 1) / btScalar(3);
	const double halfAngles[] = {1e-7, 1e-5, 9.9e-4, 9.999e-4, 1.0001e-3, 1.01e-3, 1e-2};
	for (double halfAngle : halfAngles)
	{
		const btVector3 w = axis * btScalar(2 * halfAngle / double(dt));
		btTransform start;
		start.setIdentity();
		btTransform predicted;
		btTransformUtil::integrateTransform(start, btVector3(0, 0, 0), w, dt, predicted);
		const double angle = lengthInDouble(w) * double(dt);
		const btVector3 expected = axis * btScalar(sin(angle));
		EXPECT_TRUE(vectorsNear(sinAngleTimesAxis(predicted.getBasis()), expected, kTightTolerance * btScalar(angle)))
		    << "half angle " << halfAngle;
	}
}

// ---- calculateVelocity / calculateVelocityQuaternion ---------------------------------------------

namespace
{
// One random case for the inversion tests: a transform, velocities and a step with |w| dt log-uniform in
// [1e-6, 1] * 0.99 threshold, from nearly at rest to just below the clamp.
struct MotionCase
{
	btTransform start;
	btVector3 linearVelocity;
	btVector3 angularVelocity;
	btScalar dt;
	btTransform end;
};

MotionCase randomMotion(Random& rng)
{
	MotionCase c;
	c.start = randomTransform(rng, 10);
	c.dt = rng.uniform(btScalar(1.0 / 240), btScalar(1.0 / 30));
	c.linearVelocity = rng.vector(20);
	const btScalar stepAngle = btScalar(0.99) * kThreshold * btScalar(pow(10.0, double(rng.uniform(-6, 0))));
	c.angularVelocity = rng.unitVector() * (stepAngle / c.dt);
	btTransformUtil::integrateTransform(c.start, c.linearVelocity, c.angularVelocity, c.dt, c.end);
	return c;
}

// Recovering v = (x1 - x0) / dt: x1 = x0 + v dt is rounded relative to |x1| and |v dt|, the difference
// and the division add a relative eps each; 2 eps on each term bounds it.
btScalar linearTolerance(const MotionCase& c)
{
	return btScalar(2) * SIMD_EPSILON *
	       ((c.start.getOrigin().length() + c.end.getOrigin().length()) / c.dt + c.linearVelocity.length());
}

// The end rotation carries a few eps of rounding (one integration step plus a matrix/quaternion round
// trip), so the angle between the rotations is known to within a few eps whatever its size:
// kTightTolerance radians, divided by dt.
btScalar angularTolerance(const MotionCase& c) { return kTightTolerance / c.dt; }
}  // namespace

TEST(TransformUtilVelocity, CalculateVelocityInvertsIntegrateTransform)
{
	Random rng(201);
	for (int i = 0; i < 1000; ++i)
	{
		const MotionCase c = randomMotion(rng);
		btVector3 linVel, angVel;
		btTransformUtil::calculateVelocity(c.start, c.end, c.dt, linVel, angVel);
		EXPECT_TRUE(vectorsNear(linVel, c.linearVelocity, linearTolerance(c))) << "case " << i;
		EXPECT_TRUE(vectorsNear(angVel, c.angularVelocity, angularTolerance(c))) << "case " << i << ", dt " << c.dt;
	}
}

TEST(TransformUtilVelocity, CalculateVelocityQuaternionInvertsIntegrateTransform)
{
	Random rng(202);
	for (int i = 0; i < 1000; ++i)
	{
		const MotionCase c = randomMotion(rng);
		const btQuaternion orn0 = c.start.getRotation();
		const btQuaternion orn1 = c.end.getRotation();
		btVector3 linVel, angVel;
		btTransformUtil::calculateVelocityQuaternion(c.start.getOrigin(), c.end.getOrigin(), orn0, orn1, c.dt, linVel,
		                                             angVel);
		EXPECT_TRUE(vectorsNear(linVel, c.linearVelocity, linearTolerance(c))) << "case " << i;
		EXPECT_TRUE(vectorsNear(angVel, c.angularVelocity, angularTolerance(c))) << "case " << i << ", dt " << c.dt;
		// q and -q are the same orientation: the velocity must not depend on the sign of either.
		btVector3 linVelNeg, angVelNeg;
		btTransformUtil::calculateVelocityQuaternion(c.start.getOrigin(), c.end.getOrigin(), -orn0, orn1, c.dt,
		                                             linVelNeg, angVelNeg);
		EXPECT_TRUE(vectorsNear(angVelNeg, c.angularVelocity, angularTolerance(c))) << "case " << i << " (-orn0)";
		btTransformUtil::calculateVelocityQuaternion(c.start.getOrigin(), c.end.getOrigin(), orn0, -orn1, c.dt,
		                                             linVelNeg, angVelNeg);
		EXPECT_TRUE(vectorsNear(angVelNeg, c.angularVelocity, angularTolerance(c))) << "case " << i << " (-orn1)";
	}
}

TEST(TransformUtilVelocity, IntegratingCalculatedVelocityReachesTarget)
{
	// The other direction: any target whose relative rotation is below the clamp is reached in one step.
	Random rng(203);
	for (int i = 0; i < 500; ++i)
	{
		const btTransform t0 = randomTransform(rng, 10);
		const btQuaternion turn(rng.unitVector(), rng.uniform(0, btScalar(0.99) * kThreshold));
		const btTransform t1(turn * t0.getRotation(), rng.vector(10));
		const btScalar dt = rng.uniform(btScalar(1.0 / 240), btScalar(1.0 / 30));
		btVector3 linVel, angVel;
		btTransformUtil::calculateVelocity(t0, t1, dt, linVel, angVel);
		btTransform reached;
		btTransformUtil::integrateTransform(t0, linVel, angVel, dt, reached);
		// Positions: (x1 - x0) / dt * dt + x0 rounds a few times relative to the coordinates (up to 20).
		EXPECT_TRUE(vectorsNear(reached.getOrigin(), t1.getOrigin(), kTightTolerance * 20)) << "case " << i;
		// Rotations: both directions are exact maps (well conditioned at every angle) rounded a few times.
		EXPECT_TRUE(rotationsNear(reached.getRotation(), t1.getRotation(), kTightTolerance)) << "case " << i;
	}
}

// The angle of a tiny rotation must come back to a few eps, like a large one: the rotation's entries are
// known to a few eps whatever its size. (Recovering it as 2 acos(w) would not: acos is flat at w = 1, so
// in single precision every turn below ~3e-4 rad would come back as 0, and in double below ~3e-8 rad.)
TEST(TransformUtilVelocity, RecoversSlowSpinToRounding)
{
	Random rng(204);
	const btScalar dt = btScalar(1.0 / 60);
	for (int decade = -9; decade <= 1; ++decade)
	{
		const btTransform t0 = randomTransform(rng, 1);
		const btVector3 w = rng.unitVector() * btScalar(pow(10.0, decade));
		btTransform t1;
		btTransformUtil::integrateTransform(t0, btVector3(0, 0, 0), w, dt, t1);
		btVector3 linVel, angVel, angVelQuaternion;
		btTransformUtil::calculateVelocity(t0, t1, dt, linVel, angVel);
		btTransformUtil::calculateVelocityQuaternion(t0.getOrigin(), t1.getOrigin(), t0.getRotation(), t1.getRotation(),
		                                             dt, linVel, angVelQuaternion);
		// The same bound as for fast spins: the rotations are known to a few eps, whatever their size.
		const btScalar tolerance = kTightTolerance / dt;
		EXPECT_TRUE(vectorsNear(angVel, w, tolerance)) << "calculateVelocity, |w| = 1e" << decade << " rad/s";
		EXPECT_TRUE(vectorsNear(angVelQuaternion, w, tolerance))
		    << "calculateVelocityQuaternion, |w| = 1e" << decade << " rad/s";
	}
}

TEST(TransformUtilVelocity, DiffAxisAngleTakesShortWayRound)
{
	Random rng(205);
	for (int i = 0; i < 100; ++i)
	{
		const btVector3 axis = rng.unitVector();
		const btQuaternion orn0 = rng.rotation();
		// A 270 degree turn about axis is a 90 degree turn about -axis.
		const btQuaternion orn1 = btQuaternion(axis, btScalar(1.5) * SIMD_PI) * orn0;
		const btQuaternion representations[] = {orn1, -orn1};
		for (const btQuaternion& q1 : representations)
		{
			btVector3 diffAxis;
			btScalar diffAngle;
			btTransformUtil::calculateDiffAxisAngleQuaternion(orn0, q1, diffAxis, diffAngle);
			// Values of order 1 through one product and an angle recovery at 90 degrees: a few eps.
			EXPECT_NEAR(diffAngle, SIMD_HALF_PI, kTightTolerance) << "case " << i;
			EXPECT_TRUE(vectorsNear(diffAxis, -axis, kTightTolerance)) << "case " << i;
		}
		btVector3 diffAxis;
		btScalar diffAngle;
		btTransformUtil::calculateDiffAxisAngle(btTransform(orn0), btTransform(orn1), diffAxis, diffAngle);
		EXPECT_NEAR(diffAngle, SIMD_HALF_PI, kTightTolerance) << "case " << i;
		EXPECT_TRUE(vectorsNear(diffAxis, -axis, kTightTolerance)) << "case " << i;

		const btScalar dt = btScalar(0.5);
		btVector3 linVel, angVel;
		btTransformUtil::calculateVelocity(btTransform(orn0), btTransform(orn1), dt, linVel, angVel);
		EXPECT_TRUE(vectorsNear(angVel, -axis * (SIMD_HALF_PI / dt), kTightTolerance / dt)) << "case " << i;
	}
}

TEST(TransformUtilVelocity, DiffAxisAngleOfEqualRotationsIsZeroWithUnitAxis)
{
	Random rng(206);
	for (int i = 0; i < 100; ++i)
	{
		const btQuaternion q = rng.rotation();
		btVector3 axis;
		btScalar angle;
		btTransformUtil::calculateDiffAxisAngleQuaternion(q, q, axis, angle);
		// q * q^-1 is the identity up to a few eps in x, y, z, so the angle is a few eps; the axis is
		// arbitrary but must be a unit vector (callers multiply it by the angle).
		EXPECT_NEAR(axis.length(), btScalar(1), kTightTolerance) << "case " << i;
		EXPECT_GE(angle, btScalar(0));
		EXPECT_LE(angle, kTightTolerance) << "case " << i;
		btTransformUtil::calculateDiffAxisAngle(btTransform(q), btTransform(q), axis, angle);
		EXPECT_NEAR(axis.length(), btScalar(1), kTightTolerance) << "case " << i;
		EXPECT_GE(angle, btScalar(0));
		EXPECT_LE(angle, kTightTolerance) << "case " << i;
	}
	btVector3 axis;
	btScalar angle = -1;
	btTransformUtil::calculateDiffAxisAngleQuaternion(btQuaternion::getIdentity(), btQuaternion::getIdentity(), axis,
	                                                  angle);
	EXPECT_EQ(angle, btScalar(0));
	EXPECT_EQ(axis.length2(), btScalar(1));
}

#if CALIBER_ASSERTS_ENABLED
TEST(TransformUtilDeathTest, NonPositiveTimeStepAsserts)
{
	const btTransform t0 = btTransform::getIdentity();
	const btTransform t1(btQuaternion(btVector3(0, 0, 1), btScalar(0.3)), btVector3(1, 2, 3));
	btVector3 linVel, angVel;
	EXPECT_DEATH(btTransformUtil::calculateVelocity(t0, t1, btScalar(0), linVel, angVel), "assertion failed");
	EXPECT_DEATH(btTransformUtil::calculateVelocity(t0, t1, btScalar(-1), linVel, angVel), "assertion failed");
	EXPECT_DEATH(btTransformUtil::calculateVelocityQuaternion(t0.getOrigin(), t1.getOrigin(), t0.getRotation(),
	                                                          t1.getRotation(), btScalar(0), linVel, angVel),
	             "assertion failed");
}
#else
TEST(TransformUtilVelocity, NonPositiveTimeStepGivesZeroVelocities)
{
	const btTransform t0 = btTransform::getIdentity();
	const btTransform t1(btQuaternion(btVector3(0, 0, 1), btScalar(0.3)), btVector3(1, 2, 3));
	const btScalar steps[] = {btScalar(0), btScalar(-1)};
	for (btScalar dt : steps)
	{
		btVector3 linVel(7, 7, 7), angVel(7, 7, 7);
		btTransformUtil::calculateVelocity(t0, t1, dt, linVel, angVel);
		EXPECT_EQ(linVel, btVector3(0, 0, 0)) << "dt " << dt;
		EXPECT_EQ(angVel, btVector3(0, 0, 0)) << "dt " << dt;
		linVel.setValue(7, 7, 7);
		angVel.setValue(7, 7, 7);
		btTransformUtil::calculateVelocityQuaternion(t0.getOrigin(), t1.getOrigin(), t0.getRotation(), t1.getRotation(),
		                                             dt, linVel, angVel);
		EXPECT_EQ(linVel, btVector3(0, 0, 0)) << "dt " << dt;
		EXPECT_EQ(angVel, btVector3(0, 0, 0)) << "dt " << dt;
	}
}
#endif

// ---- btAabbSupport -------------------------------------------------------------------------------

TEST(TransformUtilAabbSupport, PicksCornerBySignOfDirection)
{
	const btVector3 half(1, 2, 3);
	for (int signs = 0; signs < 8; ++signs)
	{
		const btVector3 dir((signs & 1) ? -0.5 : 0.5, (signs & 2) ? -4 : 4, (signs & 4) ? -0.1 : 0.1);
		const btVector3 expected((signs & 1) ? -1 : 1, (signs & 2) ? -2 : 2, (signs & 4) ? -3 : 3);
		EXPECT_EQ(btAabbSupport(half, dir), expected) << "signs " << signs;
	}
	// A zero component may pick either face; both give the same support value.
	const btVector3 support = btAabbSupport(half, btVector3(0, -1, 0));
	EXPECT_EQ(support.y(), btScalar(-2));
	EXPECT_EQ(btFabs(support.x()), btScalar(1));
	EXPECT_EQ(btFabs(support.z()), btScalar(3));
}

TEST(TransformUtilAabbSupport, MaximisesDotProductOverCorners)
{
	Random rng(301);
	for (int i = 0; i < 500; ++i)
	{
		const btVector3 half(rng.uniform(0, 3), rng.uniform(0, 3), rng.uniform(0, 3));
		const btVector3 dir = rng.vector(5);
		const btScalar supportValue = dir.dot(btAabbSupport(half, dir));
		for (int corner = 0; corner < 8; ++corner)
		{
			const btVector3 c((corner & 1) ? -half.x() : half.x(), (corner & 2) ? -half.y() : half.y(),
			                  (corner & 4) ? -half.z() : half.z());
			// Exact comparison: the support corner's products are the absolute values of the others'.
			EXPECT_GE(supportValue, dir.dot(c)) << "case " << i << " corner " << corner;
		}
	}
}

// ---- btConvexSeparatingDistanceUtil --------------------------------------------------------------

TEST(TransformUtilSeparatingDistance, DropsByApproachWhenBMovesTowardsAAlongNormal)
{
	// A above B, normal from B to A = +z. Dyadic values with identity rotations: exact arithmetic.
	btConvexSeparatingDistanceUtil util(btScalar(1), btScalar(2));
	btTransform transA(btQuaternion::getIdentity(), btVector3(0, 0, 5));
	btTransform transB(btQuaternion::getIdentity(), btVector3(0, 0, 0));
	util.initSeparatingDistance(btVector3(0, 0, 1), btScalar(2), transA, transB);
	EXPECT_EQ(util.getConservativeSeparatingDistance(), btScalar(2));

	transB.setOrigin(btVector3(0, 0, btScalar(0.25)));
	util.updateSeparatingDistance(transA, transB);
	EXPECT_EQ(util.getConservativeSeparatingDistance(), btScalar(1.75));

	// A moving towards B closes the gap too; a sideways part of the motion does not count.
	transA.setOrigin(btVector3(3, -1, btScalar(4.5)));
	util.updateSeparatingDistance(transA, transB);
	EXPECT_EQ(util.getConservativeSeparatingDistance(), btScalar(1.25));

	transB.setOrigin(btVector3(btScalar(-2), 0, btScalar(0.375)));
	util.updateSeparatingDistance(transA, transB);
	EXPECT_EQ(util.getConservativeSeparatingDistance(), btScalar(1.125));
}

TEST(TransformUtilSeparatingDistance, DropsByApproachAlongAGeneralNormal)
{
	Random rng(401);
	for (int i = 0; i < 200; ++i)
	{
		const btVector3 normal = rng.unitVector();
		const btTransform transA(rng.rotation(), rng.vector(5));
		btTransform transB(rng.rotation(), rng.vector(5));
		btConvexSeparatingDistanceUtil util(btScalar(1), btScalar(1));
		util.initSeparatingDistance(normal, btScalar(3), transA, transB);
		const btScalar approach = rng.uniform(btScalar(0.01), btScalar(2));
		transB.setOrigin(transB.getOrigin() + normal * approach);
		util.updateSeparatingDistance(transA, transB);
		// The displacement is rounded relative to the positions (up to ~10) and the dot product adds a
		// few eps relative to the approach: kTightTolerance per unit of position.
		EXPECT_NEAR(util.getConservativeSeparatingDistance(), btScalar(3) - approach, kTightTolerance * 10)
		    << "case " << i;
	}
}

TEST(TransformUtilSeparatingDistance, DoesNotDropWhenBMovesAwayOrSideways)
{
	Random rng(402);
	for (int i = 0; i < 200; ++i)
	{
		const btVector3 normal = rng.unitVector();
		const btTransform transA(rng.rotation(), rng.vector(5));
		btTransform transB(rng.rotation(), rng.vector(5));
		btConvexSeparatingDistanceUtil util(btScalar(1), btScalar(1));
		util.initSeparatingDistance(normal, btScalar(3), transA, transB);
		btVector3 sideways = rng.unitVector().cross(normal);
		// Away from A, plus any sideways component.
		transB.setOrigin(transB.getOrigin() - normal * rng.uniform(btScalar(0.01), btScalar(2)) + sideways);
		util.updateSeparatingDistance(transA, transB);
		// Also check that nothing moving means nothing drops. The orientations are unchanged, so an exact
		// implementation sees no rotation at all; rounding of the unchanged quaternion is at most a few eps.
		util.updateSeparatingDistance(transA, transB);
		EXPECT_NEAR(util.getConservativeSeparatingDistance(), btScalar(3), kTightTolerance) << "case " << i;
		EXPECT_LE(util.getConservativeSeparatingDistance(), btScalar(3)) << "case " << i;
	}
}

TEST(TransformUtilSeparatingDistance, DropsByRadiusTimesAngleUnderRotation)
{
	Random rng(403);
	for (int i = 0; i < 200; ++i)
	{
		const btScalar radiusA = rng.uniform(btScalar(0.1), btScalar(5));
		const btScalar radiusB = rng.uniform(btScalar(0.1), btScalar(5));
		btTransform transA(rng.rotation(), rng.vector(5));
		btTransform transB(rng.rotation(), rng.vector(5));
		btConvexSeparatingDistanceUtil util(radiusA, radiusB);
		const btScalar initial = btScalar(100);
		util.initSeparatingDistance(rng.unitVector(), initial, transA, transB);

		const btScalar angleA = rng.uniform(btScalar(0.1), btScalar(1));
		transA.setRotation(btQuaternion(rng.unitVector(), angleA) * transA.getRotation());
		util.updateSeparatingDistance(transA, transB);
		// An angle of order 1 recovered from rotations known to a few eps, times the radius, plus the
		// rounding of the bound (order 100): kTightTolerance * (radius + 100).
		EXPECT_NEAR(util.getConservativeSeparatingDistance(), initial - radiusA * angleA,
		            kTightTolerance * (radiusA + initial))
		    << "case " << i;

		const btScalar angleB = rng.uniform(btScalar(0.1), btScalar(1));
		transB.setRotation(btQuaternion(rng.unitVector(), angleB) * transB.getRotation());
		util.updateSeparatingDistance(transA, transB);
		EXPECT_NEAR(util.getConservativeSeparatingDistance(), initial - radiusA * angleA - radiusB * angleB,
		            kTightTolerance * (radiusA + radiusB + initial))
		    << "case " << i;
	}
}

TEST(TransformUtilSeparatingDistance, NonPositiveInitialDistanceStaysNonPositive)
{
	btConvexSeparatingDistanceUtil util(btScalar(1), btScalar(1));
	btTransform transA(btQuaternion::getIdentity(), btVector3(0, 0, 1));
	btTransform transB(btQuaternion::getIdentity(), btVector3(0, 0, 0));
	util.initSeparatingDistance(btVector3(0, 0, 1), btScalar(-0.5), transA, transB);
	EXPECT_LE(util.getConservativeSeparatingDistance(), btScalar(0));
	transB.setOrigin(btVector3(0, 0, -10));  // far apart now, but the bound was never established
	util.updateSeparatingDistance(transA, transB);
	EXPECT_LE(util.getConservativeSeparatingDistance(), btScalar(0));
}

namespace
{
// A sphere attached to a body at an offset from the body's origin, so that turning the body moves it.
struct OffsetSphere
{
	btTransform transform;
	btVector3 localCentre;
	btScalar radius;
	btScalar boundingRadius() const { return localCentre.length() + radius; }
	btVector3 centre() const { return transform(localCentre); }
};

btScalar sphereDistance(const OffsetSphere& a, const OffsetSphere& b)
{
	return (a.centre() - b.centre()).length() - a.radius - b.radius;
}
}  // namespace

// Slow turns must lower the bound too: a turn of 1e-4 rad per update, recovered as 0 by an inaccurate
// angle formula, would leave the bound at its initial value while the offset sphere swings into the other.
TEST(TransformUtilSeparatingDistance, SlowRotationStillLowersBound)
{
	OffsetSphere a{btTransform(btQuaternion::getIdentity(), btVector3(-9, 0, 3)), btVector3(9, 0, 0), btScalar(1)};
	OffsetSphere b{btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 0)), btVector3(0, 0, 0), btScalar(1)};
	btConvexSeparatingDistanceUtil util(a.boundingRadius(), b.boundingRadius());
	util.initSeparatingDistance(btVector3(0, 0, 1), sphereDistance(a, b), a.transform, b.transform);
	const btScalar stepAngle = btScalar(1e-4);
	btScalar worstExcess = -SIMD_INFINITY;
	int worstUpdate = -1;
	for (int update = 1; update <= 2000; ++update)
	{
		// A turns about +y through its origin: its sphere (9 units out along x) swings down towards B.
		a.transform.setRotation(btQuaternion(btVector3(0, 1, 0), stepAngle * btScalar(update)));
		util.updateSeparatingDistance(a.transform, b.transform);
		const btScalar excess = util.getConservativeSeparatingDistance() - sphereDistance(a, b);
		if (excess > worstExcess)
		{
			worstExcess = excess;
			worstUpdate = update;
		}
		if (util.getConservativeSeparatingDistance() <= 0) break;
	}
	// Allowance: an accurate implementation recovers each update's turn to a few eps (say 8 eps), which the
	// radius (10) turns into distance; over 2000 updates that is 2000 * 8 eps * 10 (0.02 in float).
	EXPECT_LE(worstExcess, btScalar(2000 * 8 * 10) * SIMD_EPSILON)
	    << "bound exceeded the true distance by " << worstExcess << " at update " << worstUpdate;
}

TEST(TransformUtilSeparatingDistance, BoundNeverExceedsTrueDistanceForRandomSmallMotions)
{
	Random rng(404);
	const int kTrials = 100;
	const int kUpdatesPerTrial = 200;
	int updatesChecked = 0;
	int violations = 0;
	// The worst case relative to its allowance, reported once (every update is checked).
	btScalar worstExcessOverAllowance = -SIMD_INFINITY;
	std::string worstCase = "none";
	for (int trial = 0; trial < kTrials; ++trial)
	{
		OffsetSphere a{randomTransform(rng, 3), rng.vector(btScalar(1.5)), rng.uniform(btScalar(0.2), btScalar(1))};
		OffsetSphere b{btTransform(rng.rotation()), rng.vector(btScalar(1.5)), rng.uniform(btScalar(0.2), btScalar(1))};
		// Place B's sphere a small gap away from A's in a random direction.
		const btVector3 towardsA = rng.unitVector();
		const btVector3 centreB = a.centre() - towardsA * (a.radius + b.radius + rng.uniform(btScalar(0.05), 1));
		b.transform.setOrigin(centreB - b.transform.getBasis() * b.localCentre);
		const btScalar initialDistance = sphereDistance(a, b);
		const btVector3 normal = (a.centre() - b.centre()).normalized();
		btConvexSeparatingDistanceUtil util(a.boundingRadius(), b.boundingRadius());
		util.initSeparatingDistance(normal, initialDistance, a.transform, b.transform);

		// A speed scale per trial, from nearly at rest to fast, so that slow motions are covered too:
		// per update, translations up to `scale` and turns up to `scale` radians.
		const btScalar scale = btScalar(pow(10.0, double(rng.uniform(-5, -1))));
		const btVector3 moveA = rng.vector(scale);
		const btVector3 moveB = rng.vector(scale) + normal * (scale * btScalar(0.5));  // B tends towards A
		const btQuaternion turnA(rng.unitVector(), rng.uniform(0, scale));
		const btQuaternion turnB(rng.unitVector(), rng.uniform(0, scale));
		btScalar pathLength = 0;
		for (int update = 0; update < kUpdatesPerTrial; ++update)
		{
			a.transform.setOrigin(a.transform.getOrigin() + moveA);
			a.transform.setRotation(turnA * a.transform.getRotation());
			b.transform.setOrigin(b.transform.getOrigin() + moveB);
			b.transform.setRotation(turnB * b.transform.getRotation());
			util.updateSeparatingDistance(a.transform, b.transform);
			pathLength += (moveA.length() + moveB.length() + scale * (a.boundingRadius() + b.boundingRadius()));
			const btScalar bound = util.getConservativeSeparatingDistance();
			if (bound <= 0) break;  // a narrowphase query would run now
			const btScalar trueDistance = sphereDistance(a, b);
			// Allowance: the true distance is computed from coordinates up to ~6 (a few eps each), and every
			// update's drop is computed from rotations and displacements known to a few eps each, i.e. a
			// relative kTightTolerance of that update's motion bound; summed, kTightTolerance * path.
			const btScalar allowance = kTightTolerance * (btScalar(6) + pathLength);
			const btScalar excess = bound - trueDistance;
			if (excess > allowance) ++violations;
			if (excess - allowance > worstExcessOverAllowance)
			{
				worstExcessOverAllowance = excess - allowance;
				worstCase = "trial " + std::to_string(trial) + " (scale " + std::to_string(double(scale)) +
				            "), update " + std::to_string(update) + ": bound " + std::to_string(double(bound)) +
				            ", true distance " + std::to_string(double(trueDistance)) + ", allowance " +
				            std::to_string(double(allowance));
			}
			++updatesChecked;
		}
	}
	EXPECT_EQ(violations, 0) << "of " << updatesChecked << " updates; worst: " << worstCase;
	EXPECT_GT(updatesChecked, kTrials * 20) << "too few updates kept a positive bound to test anything";
}
