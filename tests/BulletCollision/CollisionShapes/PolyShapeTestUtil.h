// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_POLY_SHAPE_TEST_UTIL_H
#define CALIBER_POLY_SHAPE_TEST_UTIL_H

// Deterministic random helpers for the polyhedral shape tests (fixed seed per test).

#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"

#include <random>

namespace polytest
{
/// A small deterministic generator of scalars, directions and rigid transforms.
class Random
{
public:
	/// Seeded generator.
	explicit Random(unsigned seed) : m_engine(seed) {}
	/// Uniform in [lo, hi].
	btScalar uniform(btScalar lo, btScalar hi)
	{
		return lo + (hi - lo) * btScalar(std::uniform_real_distribution<double>(0, 1)(m_engine));
	}
	/// A point in the cube [-h, h]^3.
	btVector3 point(btScalar h) { return btVector3(uniform(-h, h), uniform(-h, h), uniform(-h, h)); }
	/// A unit direction.
	btVector3 direction()
	{
		for (;;)
		{
			const btVector3 v = point(1);
			if (v.length2() > btScalar(0.01) && v.length2() <= 1) return v.normalized();
		}
	}
	/// A random rotation and translation within [-h, h]^3.
	btTransform transform(btScalar h)
	{
		return btTransform(btQuaternion(direction(), uniform(0, SIMD_2_PI)), point(h));
	}

private:
	std::mt19937 m_engine;
};
}  // namespace polytest

#endif  // CALIBER_POLY_SHAPE_TEST_UTIL_H
