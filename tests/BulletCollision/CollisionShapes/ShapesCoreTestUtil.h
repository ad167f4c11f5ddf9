// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_SHAPES_CORE_TEST_UTIL_H
#define CALIBER_TESTS_SHAPES_CORE_TEST_UTIL_H

// Helpers for the shapes-core tests (ShapesCore*Test.cpp): a seeded generator and vector comparisons.

#include <gtest/gtest.h>

#include <random>

#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

namespace shapes_core_test
{
// A few dozen roundings of values of order 1 (each with relative error SIMD_EPSILON / 2).
const btScalar kRoundingTolerance = btScalar(64) * SIMD_EPSILON;

class Random
{
public:
	explicit Random(unsigned seed) : m_engine(seed) {}
	btScalar uniform(btScalar lo, btScalar hi)
	{
		return btScalar(std::uniform_real_distribution<double>(double(lo), double(hi))(m_engine));
	}
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
	btTransform transform(btScalar range = 5) { return btTransform(rotation(), vector(range)); }

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

inline bool isFiniteVector(const btVector3& v) { return btIsFinite(v.x()) && btIsFinite(v.y()) && btIsFinite(v.z()); }

}  // namespace shapes_core_test

#endif  // CALIBER_TESTS_SHAPES_CORE_TEST_UTIL_H
