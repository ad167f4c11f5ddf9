// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btGrahamScan2dConvexHull.h"

#include <gtest/gtest.h>

#include <set>
#include <vector>

#include "MathTestUtil.h"

using caliber_test::Random;

namespace
{
// Points in a plane: origin + u * axisU + v * axisV, with (axisU, axisV, normal) right-handed.
struct Plane
{
	btVector3 normal, axisU, axisV, origin;
	btVector3 point(btScalar u, btScalar v) const { return origin + axisU * u + axisV * v; }
};

Plane randomPlane(Random& random)
{
	Plane plane;
	plane.normal = random.unitVector();
	btPlaneSpace1(plane.normal, plane.axisU, plane.axisV);
	plane.origin = random.vector(5);
	return plane;
}

btAlignedObjectArray<GrahamVector3> toGraham(const std::vector<btVector3>& points)
{
	btAlignedObjectArray<GrahamVector3> out;
	for (size_t i = 0; i < points.size(); ++i) out.push_back(GrahamVector3(points[i], int(i)));
	return out;
}

btAlignedObjectArray<GrahamVector3> hullOf(const std::vector<btVector3>& points, const btVector3& normal)
{
	btAlignedObjectArray<GrahamVector3> input = toGraham(points);
	btAlignedObjectArray<GrahamVector3> hull;
	GrahamScanConvexHull2D(input, hull, normal);
	return hull;
}

// Signed area of the parallelogram (b - a, c - a), seen from the normal's side.
btScalar turn(const btVector3& a, const btVector3& b, const btVector3& c, const btVector3& normal)
{
	return (b - a).cross(c - a).dot(normal);
}

// Points whose coordinates are O(10) carry rounding of about 10 SIMD_EPSILON after projection, and the
// scan treats turns within a few SIMD_EPSILON of straight as straight; a margin of 1024 SIMD_EPSILON
// times the squared size on areas (distance times edge length) leaves a wide safety factor.
const btScalar kSize = 10;
const btScalar kAreaTolerance = btScalar(1024) * SIMD_EPSILON * kSize * kSize;

// The hull is a convex polygon, counter-clockwise about normal with strictly convex corners, its
// points are input points with their indices, and every input point is inside or on it.
void expectConvexHullOf(const std::vector<btVector3>& points, const btAlignedObjectArray<GrahamVector3>& hull,
                        const btVector3& normal)
{
	const int n = hull.size();
	ASSERT_GE(n, 3);
	for (int i = 0; i < n; ++i)
	{
		ASSERT_GE(hull[i].m_orgIndex, 0);
		ASSERT_LT(hull[i].m_orgIndex, int(points.size()));
		EXPECT_TRUE(static_cast<const btVector3&>(hull[i]) == points[hull[i].m_orgIndex]);
		const btScalar t = turn(hull[i], hull[(i + 1) % n], hull[(i + 2) % n], normal);
		EXPECT_GT(t, 0) << "corner " << (i + 1) % n << " is not a strict left turn";
	}
	for (size_t p = 0; p < points.size(); ++p)
		for (int i = 0; i < n; ++i)
		{
			const btScalar t = turn(hull[i], hull[(i + 1) % n], points[p], normal);
			EXPECT_GE(t, -kAreaTolerance) << "point " << p << " is outside edge " << i;
		}
}

// Brute force: i -> j is a hull edge when every other point is strictly left of it (random points
// are in general position, so no point lies on an edge). The hull vertices are the edges' sources.
std::set<int> bruteForceHullIndices(const std::vector<btVector3>& points, const btVector3& normal)
{
	std::set<int> indices;
	const int count = int(points.size());
	for (int i = 0; i < count; ++i)
		for (int j = 0; j < count; ++j)
		{
			if (i == j) continue;
			bool allLeft = true;
			for (int k = 0; k < count && allLeft; ++k)
				if (k != i && k != j && turn(points[i], points[j], points[k], normal) <= 0) allLeft = false;
			if (allLeft) indices.insert(i);
		}
	return indices;
}

std::set<int> indicesOf(const btAlignedObjectArray<GrahamVector3>& hull)
{
	std::set<int> indices;
	for (int i = 0; i < hull.size(); ++i) indices.insert(hull[i].m_orgIndex);
	return indices;
}
}  // namespace

// Random planar clouds, on planes of random orientation and offset: the scan finds exactly the
// brute-force hull vertices, counter-clockwise and convex, with every point inside.
TEST(GrahamScan2d, RandomPlanarCloudsMatchBruteForceHull)
{
	Random random(4242);
	for (int trial = 0; trial < 40; ++trial)
	{
		const Plane plane = randomPlane(random);
		const int count = random.integer(3, 120);
		std::vector<btVector3> points;
		for (int i = 0; i < count; ++i)
			points.push_back(plane.point(random.uniform(-kSize, kSize), random.uniform(-kSize, kSize)));
		const btAlignedObjectArray<GrahamVector3> hull = hullOf(points, plane.normal);
		SCOPED_TRACE(trial);
		expectConvexHullOf(points, hull, plane.normal);
		EXPECT_EQ(indicesOf(hull), bruteForceHullIndices(points, plane.normal));
	}
}

// Points off the plane are projected along the normal: a 3D cloud gives the hull of its shadow.
TEST(GrahamScan2d, ProjectsAlongNormalAxis)
{
	Random random(99);
	const Plane plane = randomPlane(random);
	std::vector<btVector3> points;
	for (int i = 0; i < 80; ++i)
		points.push_back(plane.point(random.uniform(-kSize, kSize), random.uniform(-kSize, kSize)) +
		                 plane.normal * random.uniform(-kSize, kSize));
	const btAlignedObjectArray<GrahamVector3> hull = hullOf(points, plane.normal);
	expectConvexHullOf(points, hull, plane.normal);
	EXPECT_EQ(indicesOf(hull), bruteForceHullIndices(points, plane.normal));
	// The normal need not be unit length.
	EXPECT_EQ(indicesOf(hullOf(points, plane.normal * btScalar(7.5))), indicesOf(hull));
}

// Every point repeated three times (in shuffled order): the hull has the same corner positions as
// without the repeats, each once.
TEST(GrahamScan2d, DuplicatePointsAppearOnce)
{
	Random random(7);
	const Plane plane = randomPlane(random);
	std::vector<btVector3> unique;
	for (int i = 0; i < 30; ++i)
		unique.push_back(plane.point(random.uniform(-kSize, kSize), random.uniform(-kSize, kSize)));
	std::vector<btVector3> repeated;
	for (int copy = 0; copy < 3; ++copy)
		for (int i = 0; i < 30; ++i) repeated.push_back(unique[(i * 7 + copy * 11) % 30]);
	const btAlignedObjectArray<GrahamVector3> hull = hullOf(repeated, plane.normal);
	expectConvexHullOf(repeated, hull, plane.normal);
	std::set<int> positions;  // indices into unique
	for (int i = 0; i < hull.size(); ++i)
		for (int j = 0; j < 30; ++j)
			if (static_cast<const btVector3&>(hull[i]) == unique[j]) positions.insert(j);
	EXPECT_EQ(int(positions.size()), hull.size()) << "a corner appears twice";
	EXPECT_EQ(positions, bruteForceHullIndices(unique, plane.normal));
}

// A grid of points on and inside an axis-aligned square: only the 4 corners remain, since points on
// the edges are collinear with them. Integer coordinates keep the collinearity exact.
TEST(GrahamScan2d, CollinearBoundaryPointsAreDropped)
{
	std::vector<btVector3> points;
	for (int x = 0; x <= 4; ++x)
		for (int y = 0; y <= 4; ++y) points.push_back(btVector3(btScalar(x), btScalar(y), btScalar((x * y) % 3)));
	const btAlignedObjectArray<GrahamVector3> hull = hullOf(points, btVector3(0, 0, 1));
	ASSERT_EQ(hull.size(), 4);
	expectConvexHullOf(points, hull, btVector3(0, 0, 1));
	for (int i = 0; i < 4; ++i)
	{
		EXPECT_TRUE(hull[i].x() == 0 || hull[i].x() == 4);
		EXPECT_TRUE(hull[i].y() == 0 || hull[i].y() == 4);
	}
}

// Points on one line, in shuffled order: the hull is the two end points. Integer coordinates make the
// points exactly collinear; the projection onto a random plane keeps them collinear up to rounding.
TEST(GrahamScan2d, CollinearInputGivesEndPoints)
{
	Random random(12);
	for (int trial = 0; trial < 20; ++trial)
	{
		const btVector3 normal = random.unitVector();
		const btVector3 origin(btScalar(random.integer(-5, 5)), btScalar(random.integer(-5, 5)),
		                       btScalar(random.integer(-5, 5)));
		const btVector3 direction(btScalar(random.integer(-3, 3)), btScalar(random.integer(-3, 3)),
		                          btScalar(random.integer(1, 3)));
		if (btFabs(direction.normalized().dot(normal)) > btScalar(0.9)) continue;  // shadow too short
		std::vector<btVector3> points;
		for (int i = 0; i < 12; ++i) points.push_back(origin + direction * btScalar((i * 5) % 12));
		const btAlignedObjectArray<GrahamVector3> hull = hullOf(points, normal);
		SCOPED_TRACE(trial);
		ASSERT_EQ(hull.size(), 2);
		EXPECT_EQ(indicesOf(hull), (std::set<int>{0, 7}));  // parameters 0 and 11
	}
}

// Fewer than 3 points are copied unchanged; 3 points come out counter-clockwise; identical points give
// one point; an empty input gives an empty hull.
TEST(GrahamScan2d, TinyInputs)
{
	const btVector3 normal(0, 0, 1);
	EXPECT_EQ(hullOf({}, normal).size(), 0);

	const btAlignedObjectArray<GrahamVector3> one = hullOf({btVector3(1, 2, 3)}, normal);
	ASSERT_EQ(one.size(), 1);
	EXPECT_EQ(one[0].m_orgIndex, 0);

	const btAlignedObjectArray<GrahamVector3> two = hullOf({btVector3(1, 2, 3), btVector3(1, 2, 3)}, normal);
	ASSERT_EQ(two.size(), 2);
	EXPECT_EQ(two[0].m_orgIndex, 0);
	EXPECT_EQ(two[1].m_orgIndex, 1);

	const std::vector<btVector3> clockwise = {btVector3(0, 0, 0), btVector3(0, 1, 0), btVector3(1, 0, 0)};
	const btAlignedObjectArray<GrahamVector3> triangle = hullOf(clockwise, normal);
	ASSERT_EQ(triangle.size(), 3);
	EXPECT_GT(turn(triangle[0], triangle[1], triangle[2], normal), 0);
	const btAlignedObjectArray<GrahamVector3> flipped = hullOf(clockwise, -normal);
	ASSERT_EQ(flipped.size(), 3);
	EXPECT_GT(turn(flipped[0], flipped[1], flipped[2], -normal), 0);

	const std::vector<btVector3> same(5, btVector3(1, 1, 1));
	EXPECT_EQ(hullOf(same, normal).size(), 1);

	const std::vector<btVector3> threeOnALine = {btVector3(0, 0, 0), btVector3(2, 2, 0), btVector3(1, 1, 0)};
	EXPECT_EQ(indicesOf(hullOf(threeOnALine, normal)), (std::set<int>{0, 1}));
}
