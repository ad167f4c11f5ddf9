// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_NARROW_PHASE_TEST_UTIL_H
#define CALIBER_TESTS_NARROW_PHASE_TEST_UTIL_H

// Shared helpers for the narrowphase tests: seeded random placements and brute-force reference
// distances computed feature by feature, independently of GJK.

#include <gtest/gtest.h>

#include <random>

#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

namespace caliber_narrowphase_test
{
class Random
{
public:
	explicit Random(unsigned seed) : m_engine(seed) {}
	btScalar uniform(btScalar lo, btScalar hi)
	{
		return btScalar(std::uniform_real_distribution<double>(lo, hi)(m_engine));
	}
	btVector3 vector(btScalar range)
	{
		return btVector3(uniform(-range, range), uniform(-range, range), uniform(-range, range));
	}
	btVector3 unitVector()
	{
		for (;;)
		{
			const btVector3 v = vector(1);
			const btScalar l2 = v.length2();
			if (l2 > btScalar(0.01) && l2 <= 1) return v / btSqrt(l2);
		}
	}
	btQuaternion rotation() { return btQuaternion(unitVector(), uniform(-SIMD_PI, SIMD_PI)); }
	btTransform transform(btScalar range) { return btTransform(rotation(), vector(range)); }

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

inline bool isFinite(const btVector3& v) { return btIsFinite(v.x()) && btIsFinite(v.y()) && btIsFinite(v.z()); }

// Closest point of a box (half extents h, placed by t) to the world point p: clamp in the local frame.
inline btVector3 closestPointOnBox(const btVector3& h, const btTransform& t, const btVector3& p)
{
	btVector3 local = t.invXform(p);
	for (int i = 0; i < 3; ++i) local[i] = btMax(-h[i], btMin(h[i], local[i]));
	return t(local);
}

// Closest points of segments [p0, p1] and [q0, q1] (Ericson 5.1.9 style clamping, in double precision).
inline btScalar segmentSegmentDistance(const btVector3& p0, const btVector3& p1, const btVector3& q0,
                                       const btVector3& q1)
{
	const btVector3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
	const double a = d1.dot(d1), e = d2.dot(d2), f = d2.dot(r);
	double s = 0, t = 0;
	if (a <= 1e-20 && e <= 1e-20) return (p0 - q0).length();
	if (a <= 1e-20)
	{
		t = btMax(0.0, btMin(1.0, f / e));
	}
	else
	{
		const double c = d1.dot(r);
		if (e <= 1e-20)
		{
			s = btMax(0.0, btMin(1.0, -c / a));
		}
		else
		{
			const double b = d1.dot(d2), denom = a * e - b * b;
			s = denom > 1e-20 ? btMax(0.0, btMin(1.0, (b * f - c * e) / denom)) : 0.0;
			t = (b * s + f) / e;
			if (t < 0)
			{
				t = 0;
				s = btMax(0.0, btMin(1.0, -c / a));
			}
			else if (t > 1)
			{
				t = 1;
				s = btMax(0.0, btMin(1.0, (b - c) / a));
			}
		}
	}
	return ((p0 + d1 * btScalar(s)) - (q0 + d2 * btScalar(t))).length();
}

// The 8 corners of a box.
inline void boxCorners(const btVector3& h, const btTransform& t, btVector3* corners)
{
	for (int i = 0; i < 8; ++i)
		corners[i] = t(btVector3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
}

// Distance between two boxes, 0 when they overlap. Overlap by the separating axis test (3 + 3 face
// normals and 9 edge cross products); otherwise the minimum over vertex-to-box (covers vertex-face,
// -edge and -vertex) and edge-edge pairs, which between disjoint convex polyhedra holds the closest pair.
inline btScalar boxBoxDistance(const btVector3& ha, const btTransform& ta, const btVector3& hb, const btTransform& tb)
{
	btVector3 ca[8], cb[8];
	boxCorners(ha, ta, ca);
	boxCorners(hb, tb, cb);
	btVector3 axes[15];
	int numAxes = 0;
	for (int i = 0; i < 3; ++i)
	{
		axes[numAxes++] = ta.getBasis().getColumn(i);
		axes[numAxes++] = tb.getBasis().getColumn(i);
		for (int j = 0; j < 3; ++j)
		{
			const btVector3 c = ta.getBasis().getColumn(i).cross(tb.getBasis().getColumn(j));
			if (c.length2() > btScalar(1e-6)) axes[numAxes++] = c.normalized();
		}
	}
	bool separated = false;
	for (int k = 0; k < numAxes && !separated; ++k)
	{
		btScalar minA = BT_LARGE_FLOAT, maxA = -BT_LARGE_FLOAT, minB = BT_LARGE_FLOAT, maxB = -BT_LARGE_FLOAT;
		for (int i = 0; i < 8; ++i)
		{
			minA = btMin(minA, ca[i].dot(axes[k]));
			maxA = btMax(maxA, ca[i].dot(axes[k]));
			minB = btMin(minB, cb[i].dot(axes[k]));
			maxB = btMax(maxB, cb[i].dot(axes[k]));
		}
		separated = minA > maxB || minB > maxA;
	}
	if (!separated) return 0;
	btScalar best = BT_LARGE_FLOAT;
	for (int i = 0; i < 8; ++i)
	{
		best = btMin(best, (ca[i] - closestPointOnBox(hb, tb, ca[i])).length());
		best = btMin(best, (cb[i] - closestPointOnBox(ha, ta, cb[i])).length());
	}
	// Edges join corners that differ in one bit.
	for (int i = 0; i < 8; ++i)
		for (int bi = 1; bi < 8; bi <<= 1)
		{
			if (i & bi) continue;
			for (int j = 0; j < 8; ++j)
				for (int bj = 1; bj < 8; bj <<= 1)
				{
					if (j & bj) continue;
					best = btMin(best, segmentSegmentDistance(ca[i], ca[i | bi], cb[j], cb[j | bj]));
				}
		}
	return best;
}
// Penetration depth of two overlapping boxes: the smallest overlap of their projections over the 15
// separating-axis candidates. These are all the face normals of the Minkowski difference, so the
// minimum is the exact depth (0 or less when the boxes are apart).
inline btScalar boxBoxSatDepth(const btVector3& ha, const btTransform& ta, const btVector3& hb, const btTransform& tb)
{
	btVector3 ca[8], cb[8];
	boxCorners(ha, ta, ca);
	boxCorners(hb, tb, cb);
	btScalar depth = BT_LARGE_FLOAT;
	for (int i = 0; i < 3; ++i)
	{
		btVector3 axes[5] = {ta.getBasis().getColumn(i), tb.getBasis().getColumn(i)};
		int numAxes = 2;
		for (int j = 0; j < 3; ++j)
		{
			const btVector3 c = ta.getBasis().getColumn(i).cross(tb.getBasis().getColumn(j));
			if (c.length2() > btScalar(1e-6)) axes[numAxes++] = c.normalized();
		}
		for (int k = 0; k < numAxes; ++k)
		{
			btScalar minA = BT_LARGE_FLOAT, maxA = -BT_LARGE_FLOAT, minB = BT_LARGE_FLOAT, maxB = -BT_LARGE_FLOAT;
			for (int v = 0; v < 8; ++v)
			{
				minA = btMin(minA, ca[v].dot(axes[k]));
				maxA = btMax(maxA, ca[v].dot(axes[k]));
				minB = btMin(minB, cb[v].dot(axes[k]));
				maxB = btMax(maxB, cb[v].dot(axes[k]));
			}
			depth = btMin(depth, btMin(maxB - minA, maxA - minB));
		}
	}
	return depth;
}
}  // namespace caliber_narrowphase_test

#endif  // CALIBER_TESTS_NARROW_PHASE_TEST_UTIL_H
