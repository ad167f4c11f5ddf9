// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <cstring>

#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btQuaternion.h"
#include "MathTestUtil.h"

using caliber_test::kLooseTolerance;
using caliber_test::kTightTolerance;
using caliber_test::matricesNear;
using caliber_test::Random;
using caliber_test::rotationsNear;
using caliber_test::vectorsNear;

namespace
{
bool sameBits(btScalar a, btScalar b) { return std::memcmp(&a, &b, sizeof(btScalar)) == 0; }
}  // namespace

TEST(Quaternion, AxisAngleRoundTrip)
{
	Random random(21);
	for (int i = 0; i < 300; ++i)
	{
		const btVector3 axis = random.unitVector();
		const btScalar angle = random.uniform(btScalar(0.05), SIMD_PI - btScalar(0.05));
		const btQuaternion q(axis * random.uniform(btScalar(0.5), 3), angle);  // axis need not be unit
		EXPECT_NEAR(q.length(), 1, kTightTolerance);
		// getAngle goes through acos(w): near w = +-1 its slope amplifies rounding by 1/sin(angle/2).
		EXPECT_NEAR(q.getAngle(), angle, kTightTolerance / btSin(btScalar(0.025)));
		EXPECT_TRUE(vectorsNear(q.getAxis(), axis, kTightTolerance / btSin(btScalar(0.025))));
	}
	EXPECT_EQ(btQuaternion::getIdentity().getAxis(), btVector3(1, 0, 0));
	EXPECT_EQ(btQuaternion::getIdentity().getAngle(), 0);
}

TEST(Quaternion, ZeroAxisAssertsOrGivesIdentity)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btQuaternion(btVector3(0, 0, 0), 1), "assertion failed");
#else
	const btQuaternion q(btVector3(0, 0, 0), 1);
	EXPECT_EQ(q, btQuaternion::getIdentity());
#endif
}

TEST(Quaternion, ProductComposesRotationsLikeMatrices)
{
	Random random(22);
	for (int i = 0; i < 300; ++i)
	{
		const btQuaternion a = random.rotation(), b = random.rotation();
		EXPECT_TRUE(matricesNear(btMatrix3x3(a * b), btMatrix3x3(a) * btMatrix3x3(b), kTightTolerance));
		btQuaternion c = a;
		c *= b;
		EXPECT_EQ(c, a * b);
	}
}

// The SIMD product performs the scalar formula's operations in the same order, lane by lane.
TEST(Quaternion, ProductIsBitIdenticalToTheScalarFormula)
{
	Random random(23);
	for (int i = 0; i < 1000; ++i)
	{
		const btQuaternion a(random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-2, 2),
		                     random.uniform(-2, 2));
		const btQuaternion b(random.uniform(-2, 2), random.uniform(-2, 2), random.uniform(-2, 2),
		                     random.uniform(-2, 2));
		const btQuaternion p = a * b;
		EXPECT_TRUE(sameBits(p.x(), a.w() * b.x() + a.x() * b.w() + a.y() * b.z() - a.z() * b.y()));
		EXPECT_TRUE(sameBits(p.y(), a.w() * b.y() + a.y() * b.w() + a.z() * b.x() - a.x() * b.z()));
		EXPECT_TRUE(sameBits(p.z(), a.w() * b.z() + a.z() * b.w() + a.x() * b.y() - a.y() * b.x()));
		EXPECT_TRUE(sameBits(p.w(), a.w() * b.w() - a.x() * b.x() - a.y() * b.y() - a.z() * b.z()));
	}
}

TEST(Quaternion, RotateVectorAgreesWithMatrixAndSandwichProduct)
{
	Random random(24);
	for (int i = 0; i < 300; ++i)
	{
		const btQuaternion q = random.rotation();
		const btVector3 v = random.vector(5);
		const btVector3 byMatrix = btMatrix3x3(q) * v;
		const btQuaternion sandwich = q * v * q.inverse();
		EXPECT_TRUE(vectorsNear(quatRotate(q, v), byMatrix, 5 * kTightTolerance));
		EXPECT_TRUE(vectorsNear(btVector3(sandwich.x(), sandwich.y(), sandwich.z()), byMatrix, 5 * kTightTolerance));
		EXPECT_NEAR(sandwich.w(), 0, 5 * kTightTolerance);
	}
	// A quarter turn about z takes x to y.
	EXPECT_TRUE(vectorsNear(quatRotate(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI), btVector3(1, 0, 0)),
	                        btVector3(0, 1, 0), kTightTolerance));
}

TEST(Quaternion, InverseUndoesTheRotation)
{
	Random random(25);
	for (int i = 0; i < 100; ++i)
	{
		const btQuaternion q = random.rotation();
		EXPECT_TRUE(rotationsNear(q * q.inverse(), btQuaternion::getIdentity(), kTightTolerance));
		EXPECT_TRUE(rotationsNear(inverse(q) * q, btQuaternion::getIdentity(), kTightTolerance));
	}
}

TEST(Quaternion, SlerpHitsEndpointsStaysUnitAndMovesAtConstantRate)
{
	Random random(26);
	for (int i = 0; i < 200; ++i)
	{
		const btQuaternion a = random.rotation(), b = random.rotation();
		EXPECT_TRUE(rotationsNear(a.slerp(b, 0), a, kTightTolerance));
		EXPECT_TRUE(rotationsNear(slerp(a, b, 1), b, 10 * kTightTolerance));
		const btScalar total = a.angleShortestPath(b);
		for (int k = 1; k < 10; ++k)
		{
			const btScalar t = btScalar(k) / 10;
			const btQuaternion s = a.slerp(b, t);
			EXPECT_NEAR(s.length(), 1, 10 * kTightTolerance);
			// Angles through acos lose precision near 0: compare with a tolerance of sqrt(eps) scale.
			EXPECT_NEAR(a.angleShortestPath(s), t * total, btScalar(2e-3)) << "t " << t;
			EXPECT_NEAR(s.angleShortestPath(b), (1 - t) * total, btScalar(2e-3)) << "t " << t;
		}
	}
}

TEST(Quaternion, SlerpTakesTheShortestPath)
{
	const btQuaternion a = btQuaternion::getIdentity();
	const btQuaternion b = -btQuaternion(btVector3(0, 0, 1), btScalar(0.5));  // same rotation as +0.5, other sign
	const btQuaternion mid = a.slerp(b, btScalar(0.5));
	EXPECT_TRUE(rotationsNear(mid, btQuaternion(btVector3(0, 0, 1), btScalar(0.25)), kTightTolerance));
	// Nearly identical inputs fall back to linear weights without dividing by sin(0).
	const btQuaternion c = a.slerp(a, btScalar(0.3));
	EXPECT_TRUE(rotationsNear(c, a, kTightTolerance));
}

TEST(Quaternion, SetEulerIsYawAboutYThenPitchAboutXThenRollAboutZ)
{
	Random random(27);
	const btVector3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
	for (int i = 0; i < 100; ++i)
	{
		const btScalar yaw = random.uniform(-3, 3), pitch = random.uniform(-3, 3), roll = random.uniform(-3, 3);
		btQuaternion q;
		q.setEuler(yaw, pitch, roll);
		EXPECT_TRUE(
		    rotationsNear(q, btQuaternion(y, yaw) * btQuaternion(x, pitch) * btQuaternion(z, roll), kTightTolerance));
		EXPECT_TRUE(rotationsNear(btQuaternion(yaw, pitch, roll), q, kTightTolerance));
		btQuaternion zyx;
		zyx.setEulerZYX(yaw, pitch, roll);
		EXPECT_TRUE(
		    rotationsNear(zyx, btQuaternion(z, yaw) * btQuaternion(y, pitch) * btQuaternion(x, roll), kTightTolerance));
		// The matrix convention agrees: btMatrix3x3::setEulerZYX(x, y, z) == Rz Ry Rx.
		btMatrix3x3 m;
		m.setEulerZYX(roll, pitch, yaw);
		EXPECT_TRUE(matricesNear(m, btMatrix3x3(zyx), kTightTolerance));
	}
}

TEST(Quaternion, GetEulerZYXRoundTripsAwayFromGimbalLock)
{
	Random random(28);
	for (int i = 0; i < 300; ++i)
	{
		const btScalar yaw = random.uniform(-3, 3), pitch = random.uniform(-1.4, 1.4), roll = random.uniform(-3, 3);
		btQuaternion q;
		q.setEulerZYX(yaw, pitch, roll);
		btScalar y2, p2, r2;
		q.getEulerZYX(y2, p2, r2);
		EXPECT_NEAR(y2, yaw, kLooseTolerance);
		EXPECT_NEAR(p2, pitch, kLooseTolerance);
		EXPECT_NEAR(r2, roll, kLooseTolerance);
	}
}

TEST(Quaternion, GetEulerZYXAtGimbalLockReproducesTheRotation)
{
	for (btScalar pitch : {SIMD_HALF_PI, -SIMD_HALF_PI})
	{
		btQuaternion q;
		q.setEulerZYX(btScalar(0.7), pitch, btScalar(-0.4));
		btScalar y2, p2, r2;
		q.getEulerZYX(y2, p2, r2);
		EXPECT_EQ(r2, 0);
		EXPECT_NEAR(p2, pitch, kTightTolerance);
		btQuaternion back;
		back.setEulerZYX(y2, p2, r2);
		// At gimbal lock the angle extraction is ill-conditioned (asin near 1): sqrt(eps) accuracy.
		EXPECT_TRUE(rotationsNear(back, q, btScalar(1e-3)));
	}
}

TEST(Quaternion, ShortestArcTakesV0ToV1)
{
	Random random(29);
	for (int i = 0; i < 300; ++i)
	{
		const btVector3 a = random.unitVector(), b = random.unitVector();
		if (a.dot(b) < btScalar(-0.99)) continue;  // covered by the opposite-vectors case below
		const btQuaternion q = shortestArcQuat(a, b);
		EXPECT_NEAR(q.length(), 1, kTightTolerance);
		EXPECT_TRUE(vectorsNear(quatRotate(q, a), b, 20 * kTightTolerance));
		// Shortest: the axis is perpendicular to both vectors.
		EXPECT_NEAR(q.getAngle(), a.angle(b), btScalar(2e-3));
	}
	const btVector3 v(0, 0, 1);
	const btQuaternion half = shortestArcQuat(v, -v);
	EXPECT_TRUE(vectorsNear(quatRotate(half, v), -v, kTightTolerance));
	btVector3 a(3, 0, 0), b(0, 0, 5);
	const btQuaternion n = shortestArcQuatNormalize2(a, b);
	EXPECT_TRUE(vectorsNear(quatRotate(n, btVector3(1, 0, 0)), btVector3(0, 0, 1), kTightTolerance));
}

TEST(Quaternion, NormalizeAndSafeNormalize)
{
	btQuaternion q(1, 2, 3, 4);
	q.normalize();
	EXPECT_NEAR(q.length(), 1, kTightTolerance);
	EXPECT_NEAR(btQuaternion(0, 0, 0, 5).normalized().w(), 1, kTightTolerance);
	btQuaternion tiny(0, 0, 0, SIMD_EPSILON / 2);
	tiny.safeNormalize();  // below epsilon: left alone
	EXPECT_EQ(tiny.w(), SIMD_EPSILON / 2);
	btQuaternion zero(0, 0, 0, 0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(zero.normalize(), "assertion failed");
#else
	zero.normalize();
	EXPECT_EQ(zero, btQuaternion::getIdentity());
#endif
}

TEST(Quaternion, AnglesBetweenRotations)
{
	const btQuaternion a = btQuaternion::getIdentity();
	const btQuaternion b(btVector3(1, 0, 0), btScalar(0.8));
	EXPECT_NEAR(a.angle(b), btScalar(0.4), 1e-3) << "angle() is half the rotation angle, as in Bullet";
	EXPECT_NEAR(btAngle(a, b), btScalar(0.4), 1e-3);
	EXPECT_NEAR(a.angleShortestPath(-b), btScalar(0.8), 1e-3);
	EXPECT_NEAR((-b).getAngleShortestPath(), btScalar(0.8), 1e-3);
	EXPECT_NEAR((-b).getAngle(), 2 * SIMD_PI - btScalar(0.8), 1e-3);
	EXPECT_EQ(a.nearest(-b), b);
	EXPECT_EQ(a.farthest(b), -b);
	EXPECT_EQ(dot(a, b), b.w());
	EXPECT_NEAR(length(b), 1, kTightTolerance);
}

TEST(Quaternion, ArithmeticOperators)
{
	const btQuaternion a(1, 2, 3, 4), b(4, 3, 2, 1);
	EXPECT_EQ(a + b, btQuaternion(5, 5, 5, 5));
	EXPECT_EQ(a - b, btQuaternion(-3, -1, 1, 3));
	EXPECT_EQ(a * btScalar(2), btQuaternion(2, 4, 6, 8));
	EXPECT_EQ(a / btScalar(2), btQuaternion(0.5, 1, 1.5, 2));
	EXPECT_EQ(-a, btQuaternion(-1, -2, -3, -4));
	EXPECT_EQ(a.dot(b), 20);
	EXPECT_EQ(a.inverse(), btQuaternion(-1, -2, -3, 4));
	// (v, 0) products agree with promoting v to a quaternion.
	const btVector3 v(1, -1, 2);
	const btQuaternion vq(1, -1, 2, 0);
	EXPECT_EQ(a * v, a * vq);
	EXPECT_EQ(v * a, vq * a);
}

TEST(Quaternion, SerializationRoundTrips)
{
	const btQuaternion q(0.5, -0.25, 0.125, 2);
	btQuaternionFloatData f;
	btQuaternionDoubleData d;
	q.serializeFloat(f);
	q.serializeDouble(d);
	btQuaternion a, b;
	a.deSerializeFloat(f);
	b.deSerializeDouble(d);
	EXPECT_EQ(a, q);
	EXPECT_EQ(b, q);
}
