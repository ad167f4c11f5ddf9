// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "LinearMath/btVector3.h"
#include "MathTestUtil.h"

using caliber_test::kTightTolerance;
using caliber_test::Random;
using caliber_test::vectorsNear;

namespace
{
bool sameBits(btScalar a, btScalar b) { return std::memcmp(&a, &b, sizeof(btScalar)) == 0; }
}  // namespace

TEST(Vector3, LayoutIsFourScalarsAlignedTo16Bytes)
{
	EXPECT_EQ(sizeof(btVector3), 4 * sizeof(btScalar));
	EXPECT_EQ(alignof(btVector3), 16u);
	EXPECT_EQ(sizeof(btVector4), sizeof(btVector3));
#if defined(BT_USE_SSE)
	EXPECT_EQ(sizeof(btVector3), sizeof(__m128));
#endif
}

TEST(Vector3, ConstructorAndSetValueClearW)
{
	btVector3 v(1, 2, 3);
	EXPECT_EQ(v.w(), 0);
	v.setW(7);
	v.setValue(4, 5, 6);
	EXPECT_EQ(v.x(), 4);
	EXPECT_EQ(v.y(), 5);
	EXPECT_EQ(v.z(), 6);
	EXPECT_EQ(v.w(), 0);
	v.setX(9);
	v.setY(8);
	v.setZ(7);
	EXPECT_EQ(v.getX(), 9);
	EXPECT_EQ(v.getY(), 8);
	EXPECT_EQ(v.getZ(), 7);
	EXPECT_EQ(v[0], 9);  // raw access through operator btScalar*
}

TEST(Vector3, ArithmeticOperatorsMatchComponentFormulas)
{
	Random random(11);
	for (int i = 0; i < 200; ++i)
	{
		const btVector3 a = random.vector(10), b = random.vector(10);
		const btScalar s = random.uniform(-3, 3);
		for (int k = 0; k < 3; ++k)
		{
			EXPECT_TRUE(sameBits((a + b)[k], a[k] + b[k]));
			EXPECT_TRUE(sameBits((a - b)[k], a[k] - b[k]));
			EXPECT_TRUE(sameBits((a * b)[k], a[k] * b[k]));
			EXPECT_TRUE(sameBits((a * s)[k], a[k] * s));
			EXPECT_TRUE(sameBits((s * a)[k], a[k] * s));
			EXPECT_TRUE(sameBits((-a)[k], -a[k]));
			EXPECT_TRUE(sameBits((a / btScalar(3))[k], a[k] / btScalar(3)));
			EXPECT_TRUE(sameBits((a / btVector3(2, 4, 8))[k], a[k] / btVector3(2, 4, 8)[k]));
		}
		// Results of the operators keep the padding at zero.
		EXPECT_EQ((a + b).w(), 0);
		EXPECT_EQ((-a).w(), 0);
		EXPECT_EQ((a / btVector3(2, 4, 8)).w(), 0);
		btVector3 c = a;
		c += b;
		c -= b;
		c *= btScalar(2);
		c /= btScalar(2);
		EXPECT_TRUE(vectorsNear(c, a, kTightTolerance * 10));
	}
}

// The SIMD path promises the same operations in the same order as the scalar formula, so the bits
// agree; in scalar builds this checks the scalar code against the formula itself.
TEST(Vector3, DotAndCrossAreBitIdenticalToTheScalarFormula)
{
	Random random(12);
	for (int i = 0; i < 1000; ++i)
	{
		const btVector3 a = random.vector(100), b = random.vector(100);
		const btScalar dot = a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
		EXPECT_TRUE(sameBits(a.dot(b), dot)) << a.dot(b) << " vs " << dot;
		const btVector3 c = a.cross(b);
		EXPECT_TRUE(sameBits(c.x(), a.y() * b.z() - a.z() * b.y()));
		EXPECT_TRUE(sameBits(c.y(), a.z() * b.x() - a.x() * b.z()));
		EXPECT_TRUE(sameBits(c.z(), a.x() * b.y() - a.y() * b.x()));
		EXPECT_EQ(c.w(), 0);
	}
}

TEST(Vector3, CrossIsPerpendicularAndRightHanded)
{
	const btVector3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
	EXPECT_EQ(x.cross(y), z);
	EXPECT_EQ(y.cross(z), x);
	EXPECT_EQ(z.cross(x), y);
	Random random(13);
	for (int i = 0; i < 200; ++i)
	{
		const btVector3 a = random.vector(), b = random.vector();
		const btVector3 c = btCross(a, b);
		// |c . a| <= a few eps * |a|^2 |b|
		EXPECT_NEAR(c.dot(a), 0, kTightTolerance);
		EXPECT_NEAR(c.dot(b), 0, kTightTolerance);
		EXPECT_NEAR(btTriple(a, b, c), c.length2(), kTightTolerance);
	}
}

TEST(Vector3, LengthDistanceAndNormalize)
{
	const btVector3 v(3, 4, 12);
	EXPECT_EQ(v.length2(), 169);
	EXPECT_EQ(v.length(), 13);
	EXPECT_EQ(v.norm(), 13);
	EXPECT_EQ(v.safeNorm(), 13);
	EXPECT_EQ(btVector3(0, 0, 0).safeNorm(), 0);
	EXPECT_EQ(v.distance2(btVector3(0, 0, 0)), 169);
	EXPECT_EQ(btDistance(v, btVector3(3, 4, 0)), 12);
	EXPECT_EQ(btDistance2(v, btVector3(3, 4, 0)), 144);
	Random random(14);
	for (int i = 0; i < 500; ++i)
	{
		const btVector3 a = random.vector(50);
		EXPECT_NEAR(a.normalized().length(), 1, kTightTolerance);
		EXPECT_TRUE(vectorsNear(a.normalized() * a.length(), a, kTightTolerance * a.length()));
	}
}

TEST(Vector3, NormalizeRescalesTinyAndHugeVectors)
{
	// Squared lengths that underflow or overflow btScalar still give the exact direction.
	const btScalar tiny = std::numeric_limits<btScalar>::min() * btScalar(4);
	btVector3 small(tiny, 0, 0);
	small.normalize();
	EXPECT_TRUE(vectorsNear(small, btVector3(1, 0, 0), kTightTolerance));
	const btScalar huge = std::numeric_limits<btScalar>::max() / btScalar(4);
	btVector3 big(huge, huge, 0);
	big.normalize();
	EXPECT_TRUE(vectorsNear(big, btVector3(SIMDSQRT12, SIMDSQRT12, 0), kTightTolerance));
	btVector3 bigSafe(0, -huge, 0);
	bigSafe.safeNormalize();
	EXPECT_TRUE(vectorsNear(bigSafe, btVector3(0, -1, 0), kTightTolerance));
}

TEST(Vector3, SafeNormalizeOfZeroOrNaNGivesUnitX)
{
	btVector3 zero(0, 0, 0);
	zero.safeNormalize();
	EXPECT_EQ(zero, btVector3(1, 0, 0));
	btVector3 belowEpsilon(SIMD_EPSILON / 4, 0, 0);
	belowEpsilon.safeNormalize();
	EXPECT_EQ(belowEpsilon, btVector3(1, 0, 0));
	btVector3 nan(BT_NAN, 1, 0);
	nan.safeNormalize();
	EXPECT_EQ(nan, btVector3(1, 0, 0));
	btVector3 ok(0, 0, 2);
	ok.safeNormalize();
	EXPECT_EQ(ok, btVector3(0, 0, 1));
}

TEST(Vector3, NormalizeOfZeroVectorAssertsOrGivesUnitX)
{
	btVector3 zero(0, 0, 0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(zero.normalize(), "assertion failed");
	btVector3 infinite(BT_INFINITY, 0, 0);
	EXPECT_DEATH(infinite.normalize(), "assertion failed");
#else
	zero.normalize();
	EXPECT_EQ(zero, btVector3(1, 0, 0));
	btVector3 nan(BT_NAN, 0, 0);
	nan.normalize();
	EXPECT_EQ(nan, btVector3(1, 0, 0));
	btVector3 infinite(BT_INFINITY, 0, 0);
	infinite.normalize();
	EXPECT_EQ(infinite, btVector3(1, 0, 0));
#endif
}

TEST(Vector3, RotateTurnsAboutTheAxisAndKeepsLength)
{
	const btVector3 x(1, 0, 0), z(0, 0, 1);
	EXPECT_TRUE(vectorsNear(x.rotate(z, SIMD_HALF_PI), btVector3(0, 1, 0), kTightTolerance));
	Random random(15);
	for (int i = 0; i < 200; ++i)
	{
		const btVector3 axis = random.unitVector(), v = random.vector();
		const btScalar angle = random.uniform(-SIMD_PI, SIMD_PI);
		const btVector3 r = v.rotate(axis, angle);
		EXPECT_NEAR(r.length(), v.length(), kTightTolerance);
		EXPECT_NEAR(r.dot(axis), v.dot(axis), kTightTolerance);  // the axial part is untouched
		// The perpendicular parts turn by exactly the angle.
		const btVector3 before = v - axis * v.dot(axis), after = r - axis * r.dot(axis);
		if (before.length() > btScalar(0.1))
		{
			EXPECT_NEAR(before.angle(after), btFabs(angle), btScalar(1e-3)) << "acos near 0/pi amplifies rounding";
		}
	}
}

TEST(Vector3, AngleBetweenVectors)
{
	EXPECT_NEAR(btVector3(1, 0, 0).angle(btVector3(0, 5, 0)), SIMD_HALF_PI, kTightTolerance);
	EXPECT_NEAR(btAngle(btVector3(1, 1, 0), btVector3(2, 2, 0)), 0, btScalar(1e-3));
	EXPECT_NEAR(btVector3(1, 0, 0).angle(btVector3(-3, 0, 0)), SIMD_PI, kTightTolerance);
#if !CALIBER_ASSERTS_ENABLED
	EXPECT_EQ(btVector3(0, 0, 0).angle(btVector3(1, 0, 0)), 0);  // documented release result
#endif
}

TEST(Vector3, AxisQueriesAndAbsolute)
{
	const btVector3 v(-5, 2, 3);
	EXPECT_EQ(v.minAxis(), 0);
	EXPECT_EQ(v.maxAxis(), 2);
	EXPECT_EQ(v.absolute(), btVector3(5, 2, 3));
	EXPECT_EQ(v.closestAxis(), 0);   // largest magnitude
	EXPECT_EQ(v.furthestAxis(), 1);  // smallest magnitude
	EXPECT_EQ(btVector3(1, 9, 1).maxAxis(), 1);
	EXPECT_EQ(btVector3(1, -9, 1).minAxis(), 1);
	EXPECT_EQ(btVector3(0, 0, 0).absolute(), btVector3(0, 0, 0));
	EXPECT_EQ(btVector3(-0.0f, 0, 0).absolute().x(), 0);
}

TEST(Vector3, InterpolationEndpointsAndMidpoint)
{
	const btVector3 a(1, 2, 3), b(5, -2, 7);
	EXPECT_EQ(a.lerp(b, 0), a);
	EXPECT_EQ(lerp(a, b, 1), b);
	EXPECT_EQ(a.lerp(b, btScalar(0.5)), btVector3(3, 0, 5));
	btVector3 c;
	c.setInterpolate3(a, b, 0);
	EXPECT_EQ(c, a);
	c.setInterpolate3(a, b, 1);
	EXPECT_EQ(c, b);
	c.setInterpolate3(a, b, btScalar(0.25));
	EXPECT_TRUE(vectorsNear(c, btVector3(2, 1, 4), kTightTolerance));
}

TEST(Vector3, SetMinSetMaxAreComponentWise)
{
	btVector3 a(1, 5, -3), b(2, -1, -4);
	btVector3 lo = a, hi = a;
	lo.setMin(b);
	hi.setMax(b);
	EXPECT_EQ(lo, btVector3(1, -1, -4));
	EXPECT_EQ(hi, btVector3(2, 5, -3));
}

TEST(Vector3, ZeroQueries)
{
	btVector3 v(1, 2, 3);
	EXPECT_FALSE(v.isZero());
	EXPECT_FALSE(v.fuzzyZero());
	v.setZero();
	EXPECT_TRUE(v.isZero());
	EXPECT_EQ(v.w(), 0);
	EXPECT_TRUE(btVector3(SIMD_EPSILON / 2, 0, 0).fuzzyZero());
	EXPECT_FALSE(btVector3(SIMD_EPSILON / 2, 0, 0).isZero());
}

TEST(Vector3, EqualityIgnoresThePaddingComponent)
{
	btVector3 a(1, 2, 3), b(1, 2, 3);
	b.setW(42);
	EXPECT_TRUE(a == b);
	EXPECT_FALSE(a != b);
	EXPECT_TRUE(a != btVector3(1, 2, 4));
	const btVector4 c(1, 2, 3, 4), d(1, 2, 3, 5);
	EXPECT_TRUE(c != d);
	EXPECT_TRUE(c == btVector4(1, 2, 3, 4));
}

TEST(Vector3, SkewSymmetricMatrixReproducesTheCrossProduct)
{
	Random random(16);
	for (int i = 0; i < 50; ++i)
	{
		const btVector3 v = random.vector(), u = random.vector();
		btVector3 r0, r1, r2;
		v.getSkewSymmetricMatrix(&r0, &r1, &r2);
		EXPECT_TRUE(vectorsNear(btVector3(r0.dot(u), r1.dot(u), r2.dot(u)), v.cross(u), kTightTolerance));
	}
}

TEST(Vector3, Dot3AndTriple)
{
	const btVector3 v(1, 2, 3);
	EXPECT_EQ(v.dot3(btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)), v);
	// The triple product is the determinant of the three vectors.
	EXPECT_EQ(btVector3(1, 0, 0).triple(btVector3(0, 2, 0), btVector3(0, 0, 3)), 6);
	EXPECT_EQ(btVector3(0, 2, 0).triple(btVector3(1, 0, 0), btVector3(0, 0, 3)), -6);
}

TEST(Vector3, PlaneSpaceGivesARightHandedOrthonormalBasis)
{
	Random random(17);
	std::vector<btVector3> normals = {btVector3(0, 0, 1), btVector3(0, 0, -1), btVector3(1, 0, 0), btVector3(0, 1, 0),
	                                  btVector3(SIMDSQRT12, 0, SIMDSQRT12)};
	for (int i = 0; i < 300; ++i) normals.push_back(random.unitVector());
	for (const btVector3& n : normals)
	{
		btVector3 p, q;
		btPlaneSpace1(n, p, q);
		EXPECT_NEAR(p.length(), 1, kTightTolerance);
		EXPECT_NEAR(q.length(), 1, kTightTolerance);
		EXPECT_NEAR(p.dot(n), 0, kTightTolerance);
		EXPECT_NEAR(q.dot(n), 0, kTightTolerance);
		EXPECT_NEAR(p.dot(q), 0, kTightTolerance);
		EXPECT_TRUE(vectorsNear(n.cross(p), q, kTightTolerance));  // right-handed (n, p, q)
	}
}

TEST(Vector3, MaxDotAndMinDotAgreeWithBruteForce)
{
	Random random(18);
	for (int count = 0; count < 70; ++count)
	{
		std::vector<btVector3> points(count > 0 ? count : 1);
		for (int i = 0; i < count; ++i) points[i] = random.vector(10);
		const btVector3 direction = random.vector();
		long expectedMax = -1, expectedMin = -1;
		btScalar bestMax = 0, bestMin = 0;
		for (int i = 0; i < count; ++i)
		{
			const btScalar d = direction.dot(points[i]);
			if (expectedMax < 0 || d > bestMax) bestMax = d, expectedMax = i;
			if (expectedMin < 0 || d < bestMin) bestMin = d, expectedMin = i;
		}
		btScalar dotOut = 0;
		EXPECT_EQ(direction.maxDot(points.data(), count, dotOut), expectedMax) << "count " << count;
		if (count > 0)
		{
			EXPECT_TRUE(sameBits(dotOut, bestMax));
		}
		EXPECT_EQ(direction.minDot(points.data(), count, dotOut), expectedMin) << "count " << count;
		if (count > 0)
		{
			EXPECT_TRUE(sameBits(dotOut, bestMin));
		}
	}
}

TEST(Vector3, MaxDotPicksTheFirstOfTiesAndSkipsNaN)
{
	std::vector<btVector3> points(37, btVector3(1, 0, 0));
	points[0] = btVector3(BT_NAN, 0, 0);
	points[5] = btVector3(3, 0, 0);
	points[9] = btVector3(3, 0, 0);
	points[30] = btVector3(3, 0, 0);
	btScalar dotOut = 0;
	EXPECT_EQ(btVector3(1, 0, 0).maxDot(points.data(), long(points.size()), dotOut), 5);
	EXPECT_EQ(dotOut, 3);
	EXPECT_EQ(btVector3(-1, 0, 0).minDot(points.data(), long(points.size()), dotOut), 5);
	EXPECT_EQ(dotOut, -3);
	// Only NaN products: no valid index.
	std::vector<btVector3> nans(9, btVector3(BT_NAN, 0, 0));
	EXPECT_EQ(btVector3(1, 0, 0).maxDot(nans.data(), long(nans.size()), dotOut), -1);
	EXPECT_EQ(btVector3(1, 0, 0).maxDot(nans.data(), 0, dotOut), -1);
	EXPECT_EQ(dotOut, -SIMD_INFINITY);
}

TEST(Vector4, AxisQueriesUseAllFourComponents)
{
	btVector4 v(1, -7, 3, 5);
	EXPECT_EQ(v.maxAxis4(), 3);
	EXPECT_EQ(v.minAxis4(), 1);
	EXPECT_EQ(v.closestAxis4(), 1);
	EXPECT_EQ(v.absolute4(), btVector4(1, 7, 3, 5));
	EXPECT_EQ(v.getW(), 5);
	v.setValue(0, 0, 0, -9);
	EXPECT_EQ(v.w(), -9);
	EXPECT_EQ(v.minAxis4(), 3);
}

TEST(Vector3, SerializationRoundTripsInBothPrecisions)
{
	const btVector3 v(1.5, -2.25, 1e3);
	btVector3FloatData f;
	btVector3DoubleData d;
	v.serializeFloat(f);
	v.serializeDouble(d);
	btVector3 a, b;
	a.deSerializeFloat(f);
	b.deSerializeDouble(d);
	EXPECT_EQ(a, v);
	EXPECT_EQ(b, v);
	btVector3Data native;
	v.serialize(native);
	btVector3 c;
	c.deSerialize(native);
	EXPECT_EQ(c, v);
}

TEST(Vector3, EndianSwapTwiceIsIdentity)
{
	const btVector3 v(1.5, -2.25, 1e3);
	btVector3 swapped;
	btSwapVector3Endian(v, swapped);
	EXPECT_NE(swapped, v);
	btUnSwapVector3Endian(swapped);
	EXPECT_EQ(swapped, v);
}
