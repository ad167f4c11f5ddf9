// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_MATH_TEST_UTIL_H
#define CALIBER_TESTS_MATH_TEST_UTIL_H

// Shared helpers for the LinearMath tests: seeded random values and vector comparisons.

#include <gtest/gtest.h>

#include <random>

#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

namespace caliber_test
{
// A few units of rounding: each tested expression chains at most a few dozen operations, each
// with relative error SIMD_EPSILON / 2, on values of order 1.
const btScalar kTightTolerance = btScalar(64) * SIMD_EPSILON;
// For results of longer chains (Euler angle extraction through asin/atan2, iterations).
const btScalar kLooseTolerance = btScalar(4096) * SIMD_EPSILON;

class Random
{
public:
	explicit Random(unsigned seed) : m_engine(seed) {}
	btScalar uniform(btScalar lo, btScalar hi) { return std::uniform_real_distribution<double>(lo, hi)(m_engine); }
	int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(m_engine); }
	btVector3 vector(btScalar range = 1)
	{
		return btVector3(uniform(-range, range), uniform(-range, range), uniform(-range, range));
	}
	btVector3 unitVector()
	{
		for (;;)
		{
			const btVector3 v = vector();
			const btScalar l2 = v.length2();
			if (l2 > btScalar(0.01) && l2 <= 1) return v / btSqrt(l2);
		}
	}
	btQuaternion rotation() { return btQuaternion(unitVector(), uniform(-SIMD_PI, SIMD_PI)); }

private:
	std::mt19937 m_engine;
};

inline ::testing::AssertionResult vectorsNear(const btVector3& a, const btVector3& b, btScalar tolerance)
{
	const btScalar d = (a - b).length();
	if (d <= tolerance) return ::testing::AssertionSuccess();
	return ::testing::AssertionFailure() << "(" << a.x() << ", " << a.y() << ", " << a.z() << ") vs (" << b.x() << ", "
	                                     << b.y() << ", " << b.z() << "): distance " << d << " > " << tolerance;
}

inline ::testing::AssertionResult matricesNear(const btMatrix3x3& a, const btMatrix3x3& b, btScalar tolerance)
{
	btScalar worst = 0;
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) worst = btMax(worst, btFabs(a[i][j] - b[i][j]));
	if (worst <= tolerance) return ::testing::AssertionSuccess();
	return ::testing::AssertionFailure() << "largest element difference " << worst << " > " << tolerance;
}

// Same rotation: q and -q both count.
inline ::testing::AssertionResult rotationsNear(const btQuaternion& a, const btQuaternion& b, btScalar tolerance)
{
	const btScalar d = btMin((a - b).length(), (a + b).length());
	if (d <= tolerance) return ::testing::AssertionSuccess();
	return ::testing::AssertionFailure() << "(" << a.x() << ", " << a.y() << ", " << a.z() << ", " << a.w() << ") vs ("
	                                     << b.x() << ", " << b.y() << ", " << b.z() << ", " << b.w() << "): distance "
	                                     << d << " > " << tolerance;
}
}  // namespace caliber_test

#endif
