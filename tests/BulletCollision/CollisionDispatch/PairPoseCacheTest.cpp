// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The contact cache's shape test (src/BulletCollision/CollisionDispatch/btPairPoseCache.h): its SIMD
// comparison decides as btVector3's == on x, y and z of the four boxes, whatever the fourth lanes hold.

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "BulletCollision/CollisionDispatch/btPairPoseCache.h"

namespace
{
// The reference: the scalar comparisons the cache made before it compared four vectors at once.
bool referenceEqual(const caliber::PairShapes& a, const caliber::PairShapes& b)
{
	const btVector3* va[4] = {&a.min0, &a.max0, &a.min1, &a.max1};
	const btVector3* vb[4] = {&b.min0, &b.max0, &b.min1, &b.max1};
	for (int v = 0; v < 4; ++v)
		for (int c = 0; c < 3; ++c)
			if (!((*va[v])[c] == (*vb[v])[c])) return false;
	return true;
}

btVector3* field(caliber::PairShapes& s, int v)
{
	btVector3* fields[4] = {&s.min0, &s.max0, &s.min1, &s.max1};
	return fields[v];
}
}  // namespace

TEST(PairPoseCache, ShapeComparisonDecidesAsTheScalarComparisons)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btScalar inf = std::numeric_limits<btScalar>::infinity();
	const btScalar specials[] = {btScalar(0),
	                             btScalar(-0.0),
	                             btScalar(0.5),
	                             btScalar(-0.5),
	                             btScalar(1e30),
	                             btScalar(-1e30),
	                             std::numeric_limits<btScalar>::denorm_min(),
	                             nan,
	                             inf,
	                             -inf};
	const int numSpecials = int(sizeof(specials) / sizeof(specials[0]));
	std::mt19937 random(12);
	std::uniform_int_distribution<int> pick(0, numSpecials - 1), lane(0, 2), vector(0, 3), coin(0, 3);
	int equalCount = 0, differentCount = 0;
	for (int trial = 0; trial < 20000; ++trial)
	{
		caliber::PairShapes a, b;
		for (int v = 0; v < 4; ++v)
		{
			btVector3& x = *field(a, v);
			x.setValue(specials[pick(random)], specials[pick(random)], specials[pick(random)]);
			// The fourth lanes differ and may be NaN: they must not count.
			x.setW(specials[pick(random)]);
			btVector3& y = *field(b, v);
			y = x;
			y.setW(specials[pick(random)]);
		}
		// Mostly small changes: one lane of one vector replaced (often by -0 for 0, or by a NaN).
		const int changes = coin(random);
		for (int k = 0; k < changes; ++k) (*field(b, vector(random)))[lane(random)] = specials[pick(random)];
		const bool expected = referenceEqual(a, b);
		ASSERT_EQ(expected, a == b) << "trial " << trial;
		ASSERT_EQ(referenceEqual(b, a), b == a) << "trial " << trial;
		(expected ? equalCount : differentCount)++;
	}
	// Both answers occur often enough for the comparison to be tested both ways.
	EXPECT_GT(equalCount, 1000);
	EXPECT_GT(differentCount, 1000);
}

TEST(PairPoseCache, SignedZerosMatchAndNaNsNever)
{
	caliber::PairShapes a, b;
	a.min0.setValue(0, 1, 2);
	b.min0.setValue(btScalar(-0.0), 1, 2);
	EXPECT_TRUE(a == b);
	a.max1.setValue(std::numeric_limits<btScalar>::quiet_NaN(), 1, 1);
	b.max1 = a.max1;
	EXPECT_FALSE(a == b);
	EXPECT_FALSE(a == a);
}
