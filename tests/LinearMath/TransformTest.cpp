// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <limits>

#include "LinearMath/btTransform.h"
#include "MathTestUtil.h"

using caliber_test::kTightTolerance;
using caliber_test::matricesNear;
using caliber_test::Random;
using caliber_test::rotationsNear;
using caliber_test::vectorsNear;

namespace
{
btTransform randomTransform(Random& random) { return btTransform(random.rotation(), random.vector(10)); }
}  // namespace

TEST(Transform, CompositionAppliesTheRightOperandFirst)
{
	Random random(51);
	for (int i = 0; i < 200; ++i)
	{
		const btTransform a = randomTransform(random), b = randomTransform(random);
		const btVector3 p = random.vector(5);
		// Points of size ~15 after two transforms: tolerance scales with magnitude.
		EXPECT_TRUE(vectorsNear((a * b)(p), a(b(p)), kTightTolerance * 20));
		btTransform c = a;
		c *= b;
		EXPECT_TRUE(vectorsNear(c(p), a(b(p)), kTightTolerance * 20));
		btTransform m;
		m.mult(a, b);
		EXPECT_TRUE(vectorsNear(m * p, a * (b * p), kTightTolerance * 20));
		EXPECT_TRUE(rotationsNear(a * b.getRotation(), a.getRotation() * b.getRotation(), kTightTolerance));
	}
}

TEST(Transform, InverseUndoesTheTransform)
{
	Random random(52);
	for (int i = 0; i < 200; ++i)
	{
		const btTransform t = randomTransform(random), u = randomTransform(random);
		const btVector3 p = random.vector(5);
		EXPECT_TRUE(vectorsNear(t.inverse()(t(p)), p, kTightTolerance * 20));
		EXPECT_TRUE(vectorsNear(t.invXform(t(p)), p, kTightTolerance * 20));
		const btTransform expected = t.inverse() * u;
		const btTransform actual = t.inverseTimes(u);
		EXPECT_TRUE(matricesNear(actual.getBasis(), expected.getBasis(), kTightTolerance));
		EXPECT_TRUE(vectorsNear(actual.getOrigin(), expected.getOrigin(), kTightTolerance * 20));
	}
}

TEST(Transform, OpenGLMatrixIsColumnMajorWithTranslationLast)
{
	btTransform t(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI), btVector3(1, 2, 3));
	btScalar gl[16];
	t.getOpenGLMatrix(gl);
	EXPECT_EQ(gl[12], 1);
	EXPECT_EQ(gl[13], 2);
	EXPECT_EQ(gl[14], 3);
	EXPECT_EQ(gl[15], 1);
	EXPECT_EQ(gl[3], 0);
	// Column 0 is the image of x: a quarter turn about z takes x to y.
	EXPECT_NEAR(gl[0], 0, kTightTolerance);
	EXPECT_NEAR(gl[1], 1, kTightTolerance);
	btTransform back;
	back.setFromOpenGLMatrix(gl);
	EXPECT_TRUE(back == t);
}

TEST(Transform, AccessorsAndIdentity)
{
	btTransform t;
	t.setIdentity();
	EXPECT_TRUE(t == btTransform::getIdentity());
	const btVector3 p(1, 2, 3);
	EXPECT_EQ(t(p), p);
	t.setOrigin(btVector3(5, 0, 0));
	t.setRotation(btQuaternion(btVector3(1, 0, 0), SIMD_PI));
	EXPECT_TRUE(vectorsNear(t(p), btVector3(6, -2, -3), kTightTolerance * 4));
	EXPECT_TRUE(rotationsNear(t.getRotation(), btQuaternion(btVector3(1, 0, 0), SIMD_PI), kTightTolerance));
	t.setBasis(btMatrix3x3::getIdentity());
	EXPECT_EQ(t.getBasis(), btMatrix3x3::getIdentity());
	t.getOrigin().setY(7);
	EXPECT_EQ(t.getOrigin(), btVector3(5, 7, 0));
	const btTransform fromBasis(btMatrix3x3::getIdentity());
	EXPECT_EQ(fromBasis.getOrigin(), btVector3(0, 0, 0));
}

TEST(Transform, SerializationRoundTrips)
{
	// A quarter turn about y with exactly representable entries, so the float form is exact too.
	const btTransform t(btMatrix3x3(0, 0, 1, 0, 1, 0, -1, 0, 0), btVector3(1, 2.5, 3));
	btTransformData native;
	t.serialize(native);
	btTransform back;
	back.deSerialize(native);
	EXPECT_TRUE(back == t);
	btTransformFloatData f;
	t.serializeFloat(f);
	back.setIdentity();
	back.deSerializeFloat(f);
	EXPECT_TRUE(back == t);
}

// caliber::isFinite sums x - x over the components (0 when finite, NaN otherwise): each of the twelve
// entries of a transform, set alone to NaN or an infinity, must make the vector, basis and transform
// tests fail, while the largest, smallest and denormal finite values, and -0, must pass.
TEST(Transform, IsFiniteRejectsAnyNonFiniteEntryAndAcceptsEveryFiniteOne)
{
	// A finite transform with entry (0-8: the basis row by row, 9-11: the origin) set to value.
	const auto withEntry = [](int entry, btScalar value) {
		btTransform t(btMatrix3x3(1, 2, 3, 4, 5, 6, 7, 8, 9), btVector3(10, 11, 12));
		if (entry < 9)
			t.getBasis()[entry / 3][entry % 3] = value;
		else
			t.getOrigin()[entry - 9] = value;
		return t;
	};
	const btScalar nonFinite[] = {std::numeric_limits<btScalar>::quiet_NaN(),
	                              std::numeric_limits<btScalar>::infinity(),
	                              -std::numeric_limits<btScalar>::infinity()};
	const btScalar finite[] = {std::numeric_limits<btScalar>::max(), -std::numeric_limits<btScalar>::max(),
	                           std::numeric_limits<btScalar>::min(), std::numeric_limits<btScalar>::denorm_min(),
	                           btScalar(-0.0), btScalar(1)};
	for (int entry = 0; entry < 12; ++entry)
	{
		for (btScalar value : nonFinite)
		{
			const btTransform t = withEntry(entry, value);
			EXPECT_FALSE(caliber::isFinite(t)) << entry << " " << value;
			const btVector3& row = entry < 9 ? t.getBasis()[entry / 3] : t.getOrigin();
			EXPECT_FALSE(caliber::isFinite(row)) << entry << " " << value;
			if (entry < 9)
			{
				EXPECT_FALSE(caliber::isFinite(t.getBasis())) << entry << " " << value;
			}
		}
		for (btScalar value : finite)
		{
			const btTransform t = withEntry(entry, value);
			EXPECT_TRUE(caliber::isFinite(t)) << entry << " " << value;
			EXPECT_TRUE(caliber::isFinite(t.getBasis())) << entry << " " << value;
			EXPECT_TRUE(caliber::isFinite(t.getOrigin())) << entry << " " << value;
		}
	}
	// The unused fourth lane is not read: a NaN there leaves the vector finite.
	btVector3 v(1, 2, 3);
	v.setW(std::numeric_limits<btScalar>::quiet_NaN());
	EXPECT_TRUE(caliber::isFinite(v));
}
