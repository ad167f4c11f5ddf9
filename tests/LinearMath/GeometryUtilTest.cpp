// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btGeometryUtil.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdint.h>

namespace
{
// Test tolerance, relative to the size of the shape: the library treats distances below 1e-5 of the
// size as zero, and its results are rounded once to btScalar (float: about 1e-7 of the size), so
// 1e-4 of the size bounds every error the algorithms are allowed to make, in either precision.
const btScalar kRelativeTolerance = btScalar(1e-4);

// A small portable generator (64-bit LCG), so that the point sets are the same on every platform.
class Lcg
{
public:
	explicit Lcg(uint64_t seed) : m_state(seed) {}
	// Uniform in [lo, hi).
	btScalar uniform(btScalar lo, btScalar hi)
	{
		m_state = m_state * 6364136223846793005ull + 1442695040888963407ull;
		const double unit = double(m_state >> 11) * (1.0 / 9007199254740992.0);
		return lo + btScalar(unit) * (hi - lo);
	}
	btVector3 inBox(btScalar halfExtent)
	{
		const btScalar x = uniform(-halfExtent, halfExtent);
		const btScalar y = uniform(-halfExtent, halfExtent);
		const btScalar z = uniform(-halfExtent, halfExtent);
		return btVector3(x, y, z);
	}
	btVector3 unitDirection()
	{
		for (;;)
		{
			const btVector3 v = inBox(btScalar(1));
			const btScalar len = v.length();
			if (len > btScalar(0.1) && len <= btScalar(1)) return v / len;
		}
	}

private:
	uint64_t m_state;
};

btAlignedObjectArray<btVector3> boxCorners(const btVector3& center, const btVector3& halfExtents)
{
	btAlignedObjectArray<btVector3> corners;
	for (int i = 0; i < 8; ++i)
	{
		const btScalar sx = (i & 1) ? btScalar(1) : btScalar(-1);
		const btScalar sy = (i & 2) ? btScalar(1) : btScalar(-1);
		const btScalar sz = (i & 4) ? btScalar(1) : btScalar(-1);
		corners.push_back(center + btVector3(sx * halfExtents.x(), sy * halfExtents.y(), sz * halfExtents.z()));
	}
	return corners;
}

btAlignedObjectArray<btVector3> boxPlanes(const btVector3& center, const btVector3& halfExtents)
{
	btAlignedObjectArray<btVector3> planes;
	for (int axis = 0; axis < 3; ++axis)
	{
		for (int sign = -1; sign <= 1; sign += 2)
		{
			btVector3 plane(0, 0, 0);
			plane[axis] = btScalar(sign);
			// The face passes through center + sign * halfExtent along axis: n.p + d = 0 there.
			plane.setW(-(btScalar(sign) * center[axis] + halfExtents[axis]));
			planes.push_back(plane);
		}
	}
	return planes;
}

// Index of the entry of points within tolerance of p, or -1.
int findPoint(const btAlignedObjectArray<btVector3>& points, const btVector3& p, btScalar tolerance)
{
	for (int i = 0; i < points.size(); ++i)
	{
		if (points[i].distance(p) <= tolerance) return i;
	}
	return -1;
}

// Index of the plane with the same normal and offset, or -1.
int findPlane(const btAlignedObjectArray<btVector3>& planes, const btVector3& plane, btScalar tolerance)
{
	for (int i = 0; i < planes.size(); ++i)
	{
		if (planes[i].distance(plane) <= tolerance && btFabs(planes[i][3] - plane[3]) <= tolerance) return i;
	}
	return -1;
}

// Checks that two point sets are equal up to order and tolerance, each point matched once.
void expectSamePointSets(const btAlignedObjectArray<btVector3>& actual, const btAlignedObjectArray<btVector3>& expected,
                         btScalar tolerance)
{
	ASSERT_EQ(actual.size(), expected.size());
	btAlignedObjectArray<btVector3> remaining;
	remaining.copyFromArray(expected);
	for (int i = 0; i < actual.size(); ++i)
	{
		const int found = findPoint(remaining, actual[i], tolerance);
		ASSERT_GE(found, 0) << "unexpected point (" << actual[i].x() << ", " << actual[i].y() << ", " << actual[i].z()
		                    << ")";
		remaining.removeAtIndex(found);
	}
}

btScalar maxDot(const btAlignedObjectArray<btVector3>& points, const btVector3& direction)
{
	btScalar best = -SIMD_INFINITY;
	for (int i = 0; i < points.size(); ++i) best = btMax(best, points[i].dot(direction));
	return best;
}
}  // namespace

TEST(GeometryUtilTest, CubeVerticesGiveItsSixFacePlanes)
{
	const btVector3 center(btScalar(1), btScalar(-3), btScalar(0.5));
	const btVector3 halfExtents(btScalar(2), btScalar(0.5), btScalar(1.5));
	btAlignedObjectArray<btVector3> corners = boxCorners(center, halfExtents);
	btAlignedObjectArray<btVector3> planes;
	btGeometryUtil::getPlaneEquationsFromVertices(corners, planes);

	const btAlignedObjectArray<btVector3> expected = boxPlanes(center, halfExtents);
	const btScalar tolerance = kRelativeTolerance * btScalar(10);  // size of the box ~ 4.5
	ASSERT_EQ(planes.size(), 6);
	for (int i = 0; i < expected.size(); ++i)
	{
		EXPECT_GE(findPlane(planes, expected[i], tolerance), 0)
		    << "missing plane " << i << ": (" << expected[i].x() << ", " << expected[i].y() << ", " << expected[i].z()
		    << ", " << expected[i][3] << ")";
	}
	for (int i = 0; i < planes.size(); ++i) EXPECT_NEAR(planes[i].length(), btScalar(1), tolerance);
}

TEST(GeometryUtilTest, CubePlanesGiveItsEightCorners)
{
	const btVector3 center(btScalar(-2), btScalar(4), btScalar(7));
	const btVector3 halfExtents(btScalar(1), btScalar(3), btScalar(0.25));
	const btAlignedObjectArray<btVector3> planes = boxPlanes(center, halfExtents);
	btAlignedObjectArray<btVector3> corners;
	btGeometryUtil::getVerticesFromPlaneEquations(planes, corners);
	expectSamePointSets(corners, boxCorners(center, halfExtents), kRelativeTolerance * btScalar(10));
}

TEST(GeometryUtilTest, CubeRoundTripReturnsTheSameCorners)
{
	const btVector3 center(btScalar(0.3), btScalar(0.2), btScalar(-0.1));
	const btVector3 halfExtents(btScalar(1), btScalar(1), btScalar(1));
	btAlignedObjectArray<btVector3> corners = boxCorners(center, halfExtents);
	btAlignedObjectArray<btVector3> planes, roundTrip;
	btGeometryUtil::getPlaneEquationsFromVertices(corners, planes);
	btGeometryUtil::getVerticesFromPlaneEquations(planes, roundTrip);
	expectSamePointSets(roundTrip, corners, kRelativeTolerance * btScalar(4));
}

TEST(GeometryUtilTest, ScaleDoesNotChangeTheFaceCount)
{
	// Tolerances are relative to the shape's size, so tiny and huge boxes behave alike.
	const btScalar scales[] = {btScalar(1e-3), btScalar(1), btScalar(1e3)};
	for (btScalar scale : scales)
	{
		btAlignedObjectArray<btVector3> corners =
		    boxCorners(btVector3(scale, 2 * scale, 0), btVector3(scale, scale * btScalar(0.5), scale * btScalar(2)));
		btAlignedObjectArray<btVector3> planes, roundTrip;
		btGeometryUtil::getPlaneEquationsFromVertices(corners, planes);
		EXPECT_EQ(planes.size(), 6) << "scale " << scale;
		btGeometryUtil::getVerticesFromPlaneEquations(planes, roundTrip);
		EXPECT_EQ(roundTrip.size(), 8) << "scale " << scale;
	}
}

TEST(GeometryUtilTest, OctahedronCornersWhereFourPlanesMeetAppearOnce)
{
	btAlignedObjectArray<btVector3> vertices;
	for (int axis = 0; axis < 3; ++axis)
	{
		for (int sign = -1; sign <= 1; sign += 2)
		{
			btVector3 v(0, 0, 0);
			v[axis] = btScalar(sign) * btScalar(2);
			vertices.push_back(v);
		}
	}
	btAlignedObjectArray<btVector3> planes, roundTrip;
	btGeometryUtil::getPlaneEquationsFromVertices(vertices, planes);
	ASSERT_EQ(planes.size(), 8);
	const btScalar expectedOffset = -btScalar(2) / btSqrt(btScalar(3));  // distance of a face from the centre
	for (int i = 0; i < planes.size(); ++i)
	{
		EXPECT_NEAR(planes[i][3], expectedOffset, kRelativeTolerance * 4);
		EXPECT_NEAR(btFabs(planes[i].x()), btScalar(1) / btSqrt(btScalar(3)), kRelativeTolerance);
	}
	btGeometryUtil::getVerticesFromPlaneEquations(planes, roundTrip);
	expectSamePointSets(roundTrip, vertices, kRelativeTolerance * 4);
}

TEST(GeometryUtilTest, RandomConvexPointSetsRoundTripThroughPlanes)
{
	Lcg rng(20260101u);
	for (int trial = 0; trial < 8; ++trial)
	{
		const btScalar halfExtent = rng.uniform(btScalar(0.5), btScalar(20));
		const btVector3 offset = rng.inBox(btScalar(10));
		const int count = 8 + trial * 4;
		btAlignedObjectArray<btVector3> points;
		for (int i = 0; i < count; ++i) points.push_back(offset + rng.inBox(halfExtent));
		// Absolute tolerance for this set: its size is at most 2*sqrt(3)*halfExtent plus the offset's
		// effect on float rounding.
		const btScalar tolerance = kRelativeTolerance * (btScalar(4) * halfExtent + offset.length());

		btAlignedObjectArray<btVector3> planes;
		btGeometryUtil::getPlaneEquationsFromVertices(points, planes);
		ASSERT_GE(planes.size(), 4) << "trial " << trial;

		for (int p = 0; p < planes.size(); ++p)
		{
			EXPECT_NEAR(planes[p].length(), btScalar(1), kRelativeTolerance);
			// Every plane is a face: all points inside, at least three on it.
			EXPECT_TRUE(btGeometryUtil::areVerticesBehindPlane(planes[p], points, tolerance));
			int onPlane = 0;
			for (int i = 0; i < count; ++i)
			{
				if (btFabs(planes[p].dot(points[i]) + planes[p][3]) <= tolerance) ++onPlane;
			}
			EXPECT_GE(onPlane, 3) << "trial " << trial << " plane " << p;
		}
		for (int i = 0; i < count; ++i) EXPECT_TRUE(btGeometryUtil::isPointInsidePlanes(planes, points[i], tolerance));

		// The polytope the planes bound is the hull of the points: its corners are input points, and
		// it reaches exactly as far as the points in every direction (a missing face would let it
		// reach further, a wrong face less far).
		btAlignedObjectArray<btVector3> corners;
		btGeometryUtil::getVerticesFromPlaneEquations(planes, corners);
		ASSERT_GE(corners.size(), 4);
		for (int c = 0; c < corners.size(); ++c)
		{
			EXPECT_GE(findPoint(points, corners[c], tolerance), 0) << "trial " << trial << " corner " << c;
			for (int other = c + 1; other < corners.size(); ++other)
			{
				EXPECT_GT(corners[c].distance(corners[other]), tolerance) << "duplicate corner";
			}
		}
		for (int d = 0; d < 200; ++d)
		{
			const btVector3 direction = rng.unitDirection();
			EXPECT_NEAR(maxDot(corners, direction), maxDot(points, direction), tolerance)
			    << "trial " << trial << " direction " << d;
		}
	}
}

TEST(GeometryUtilTest, PointInsideAndOutsideWithMargin)
{
	const btAlignedObjectArray<btVector3> planes = boxPlanes(btVector3(0, 0, 0), btVector3(1, 1, 1));
	EXPECT_TRUE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(0, 0, 0), 0));
	EXPECT_TRUE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(btScalar(0.99), btScalar(-0.99), 0), 0));
	EXPECT_TRUE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(1, 1, 1), 0));  // on the boundary
	EXPECT_FALSE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(btScalar(1.1), 0, 0), 0));
	EXPECT_FALSE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(0, 0, btScalar(-1.5)), 0));
	// A positive margin grows the region, a negative one shrinks it.
	EXPECT_TRUE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(btScalar(1.1), 0, 0), btScalar(0.2)));
	EXPECT_FALSE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(btScalar(0.9), 0, 0), btScalar(-0.2)));
	// NaN is never inside; no planes means everything is inside.
	EXPECT_FALSE(btGeometryUtil::isPointInsidePlanes(planes, btVector3(BT_NAN, 0, 0), 0));
	btAlignedObjectArray<btVector3> none;
	EXPECT_TRUE(btGeometryUtil::isPointInsidePlanes(none, btVector3(100, 0, 0), 0));
}

TEST(GeometryUtilTest, VerticesBehindPlaneAndIsInsideAgree)
{
	btAlignedObjectArray<btVector3> vertices = boxCorners(btVector3(0, 0, 0), btVector3(1, 1, 1));
	btVector3 top(0, 0, 1);
	top.setW(btScalar(-1));  // z = 1
	EXPECT_TRUE(btGeometryUtil::areVerticesBehindPlane(top, vertices, 0));
	EXPECT_TRUE(btGeometryUtil::isInside(vertices, top, 0));
	top.setW(btScalar(-0.5));  // z = 0.5 cuts the box
	EXPECT_FALSE(btGeometryUtil::areVerticesBehindPlane(top, vertices, 0));
	EXPECT_FALSE(btGeometryUtil::isInside(vertices, top, 0));
	EXPECT_TRUE(btGeometryUtil::areVerticesBehindPlane(top, vertices, btScalar(0.5)));
	EXPECT_TRUE(btGeometryUtil::isInside(vertices, top, btScalar(0.5)));
}

TEST(GeometryUtilTest, DegenerateInputsGiveNoFacesOrCorners)
{
	btAlignedObjectArray<btVector3> planes;
	btAlignedObjectArray<btVector3> vertices;
	btGeometryUtil::getPlaneEquationsFromVertices(vertices, planes);
	EXPECT_EQ(planes.size(), 0);

	vertices.push_back(btVector3(1, 2, 3));
	vertices.push_back(btVector3(1, 2, 3));
	vertices.push_back(btVector3(1, 2, 3));
	btGeometryUtil::getPlaneEquationsFromVertices(vertices, planes);
	EXPECT_EQ(planes.size(), 0) << "one repeated point";

	vertices.clear();
	for (int i = 0; i < 5; ++i) vertices.push_back(btVector3(btScalar(i), btScalar(2 * i), btScalar(-i)));
	btGeometryUtil::getPlaneEquationsFromVertices(vertices, planes);
	EXPECT_EQ(planes.size(), 0) << "collinear points";

	vertices.clear();
	vertices.push_back(btVector3(BT_NAN, 0, 0));
	vertices.push_back(btVector3(1, 0, 0));
	vertices.push_back(btVector3(0, 1, 0));
	vertices.push_back(btVector3(0, 0, 1));
	btGeometryUtil::getPlaneEquationsFromVertices(vertices, planes);
	EXPECT_EQ(planes.size(), 0) << "non-finite input";

	// Parallel planes (a slab) have no corners, and fewer than three planes cannot have any.
	btAlignedObjectArray<btVector3> corners;
	const btAlignedObjectArray<btVector3> box = boxPlanes(btVector3(0, 0, 0), btVector3(1, 1, 1));
	btAlignedObjectArray<btVector3> slab;
	slab.push_back(box[0]);
	slab.push_back(box[1]);
	btGeometryUtil::getVerticesFromPlaneEquations(slab, corners);
	EXPECT_EQ(corners.size(), 0);
	slab.push_back(slab[0]);
	slab.push_back(slab[1]);
	btGeometryUtil::getVerticesFromPlaneEquations(slab, corners);
	EXPECT_EQ(corners.size(), 0);
}

TEST(GeometryUtilTest, FlatPointSetGivesBothSidesOfItsPlane)
{
	btAlignedObjectArray<btVector3> square;
	square.push_back(btVector3(0, 0, 2));
	square.push_back(btVector3(1, 0, 2));
	square.push_back(btVector3(1, 1, 2));
	square.push_back(btVector3(0, 1, 2));
	btAlignedObjectArray<btVector3> planes;
	btGeometryUtil::getPlaneEquationsFromVertices(square, planes);
	ASSERT_EQ(planes.size(), 2);
	btVector3 up(0, 0, 1), down(0, 0, -1);
	up.setW(btScalar(-2));
	down.setW(btScalar(2));
	EXPECT_GE(findPlane(planes, up, kRelativeTolerance), 0);
	EXPECT_GE(findPlane(planes, down, kRelativeTolerance), 0);
}

TEST(GeometryUtilTest, ResultsAreAppendedToExistingEntries)
{
	btAlignedObjectArray<btVector3> corners = boxCorners(btVector3(0, 0, 0), btVector3(1, 1, 1));
	btAlignedObjectArray<btVector3> planes;
	planes.push_back(btVector3(7, 7, 7));
	btGeometryUtil::getPlaneEquationsFromVertices(corners, planes);
	ASSERT_EQ(planes.size(), 7);
	EXPECT_EQ(planes[0], btVector3(7, 7, 7));

	btAlignedObjectArray<btVector3> out;
	out.push_back(btVector3(5, 5, 5));
	btGeometryUtil::getVerticesFromPlaneEquations(boxPlanes(btVector3(0, 0, 0), btVector3(1, 1, 1)), out);
	ASSERT_EQ(out.size(), 9);
	EXPECT_EQ(out[0], btVector3(5, 5, 5));
}
