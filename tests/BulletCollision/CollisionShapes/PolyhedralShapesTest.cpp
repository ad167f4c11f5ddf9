// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <cstring>

#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/PolyShapeTestUtil.h"

namespace
{
// Support points are input points copied unchanged (times the scaling), so they match brute force
// exactly except when two points tie within rounding; comparing the dot products allows for that with
// a few ulps of the coordinates' size (<= 2 here).
const btScalar kDotTol = btScalar(16) * SIMD_EPSILON * btScalar(2);

btAlignedObjectArray<btVector3> randomCloud(polytest::Random& rng, int count, btScalar h)
{
	btAlignedObjectArray<btVector3> points;
	for (int i = 0; i < count; ++i) points.push_back(rng.point(h));
	return points;
}

btScalar bruteMaxDot(const btAlignedObjectArray<btVector3>& points, const btVector3& scaling, const btVector3& dir)
{
	btScalar best = -SIMD_INFINITY;
	for (int i = 0; i < points.size(); ++i) best = btMax(best, (points[i] * scaling).dot(dir));
	return best;
}

void addBoxCorners(btConvexHullShape& hull, const btVector3& half)
{
	for (int i = 0; i < 8; ++i)
		hull.addPoint(
		    btVector3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(), (i & 4) ? half.z() : -half.z()),
		    i == 7);
}
}  // namespace

TEST(ConvexHullShape, SupportMatchesBruteForceOverPoints)
{
	polytest::Random rng(42);
	const btAlignedObjectArray<btVector3> points = randomCloud(rng, 50, 2);
	btConvexHullShape hull(&points[0].x(), points.size());
	ASSERT_EQ(hull.getNumPoints(), 50);
	EXPECT_EQ(hull.getShapeType(), CONVEX_HULL_SHAPE_PROXYTYPE);
	for (int trial = 0; trial < 200; ++trial)
	{
		const btVector3 dir = rng.direction();
		const btVector3 s = hull.localGetSupportingVertexWithoutMargin(dir);
		EXPECT_NEAR(s.dot(dir), bruteMaxDot(points, btVector3(1, 1, 1), dir), kDotTol);
		// With margin: the core support pushed out by the margin along the unit direction.
		const btVector3 sm = hull.localGetSupportingVertex(dir * btScalar(3));
		EXPECT_NEAR(sm.dot(dir), s.dot(dir) + hull.getMargin(), kDotTol);
	}
	btVector3 dirs[3] = {rng.direction(), rng.direction(), rng.direction()};
	btVector3 out[3];
	hull.batchedUnitVectorGetSupportingVertexWithoutMargin(dirs, out, 3);
	for (int k = 0; k < 3; ++k) EXPECT_EQ(out[k], hull.localGetSupportingVertexWithoutMargin(dirs[k]));
}

TEST(ConvexHullShape, SupportIsBitwiseTheFirstPointOfLargestDotAmongRepeatsAndTies)
{
	// The support scan keeps one copy of each point; the answer must still be exactly maxDot's over all
	// points (the first point of largest dot product), also where points tie: on the grid below, axis and
	// diagonal directions meet whole faces and edges. Sizes cover partial blocks of four and clouds
	// beyond the duplicate-check limit (128 distinct points).
	polytest::Random rng(7);
	const int sizes[] = {1, 2, 3, 4, 5, 7, 9, 13, 40, 150, 400};
	for (int size : sizes)
	{
		btAlignedObjectArray<btVector3> points;
		for (int i = 0; i < size; ++i)
		{
			// Grid points on a 3 x 3 x 3 lattice (many ties), and every third one repeated later.
			btVector3 p(btScalar(rng.uniform(0, 3) > 2     ? 1
			                     : rng.uniform(0, 3) > 1.5 ? 0
			                                               : -1),
			            btScalar(int(rng.uniform(0, 2.999)) - 1), btScalar(int(rng.uniform(0, 2.999)) - 1));
			if (i % 5 == 4) p = rng.point(1);
			points.push_back(p);
			if (i % 3 == 0) points.push_back(points[int(rng.uniform(0, btScalar(points.size()) - btScalar(0.001)))]);
		}
		// A negative zero next to a positive one: both are kept (they differ in their bits).
		points.push_back(btVector3(btScalar(-0.0), 1, 1));
		points.push_back(btVector3(0, 1, 1));
		btConvexHullShape hull;
		for (int i = 0; i < points.size(); ++i) hull.addPoint(points[i], i + 1 == points.size());
		const btVector3 scalings[] = {btVector3(1, 1, 1), btVector3(2, btScalar(0.5), 3)};
		for (const btVector3& scaling : scalings)
		{
			hull.setLocalScaling(scaling);
			for (int trial = 0; trial < 300; ++trial)
			{
				btVector3 dir = rng.direction();
				if (trial < 27)
					dir = btVector3(btScalar(trial % 3 - 1), btScalar(trial / 3 % 3 - 1), btScalar(trial / 9 - 1));
				const btConvexHullShape& constHull = hull;
				const btVector3 got = constHull.localGetSupportingVertexWithoutMargin(dir);
				btVector3 scaledDir = dir * scaling;
				if (scaledDir.length2() < SIMD_EPSILON * SIMD_EPSILON) scaledDir.setValue(-1, -1, -1);
				btScalar best;
				const long index = scaledDir.maxDot(&points[0], points.size(), best);
				ASSERT_GE(index, 0);
				const btVector3 expected = points[int(index)] * scaling;
				for (int k = 0; k < 3; ++k)
				{
					ASSERT_EQ(std::memcmp(&got[k], &expected[k], sizeof(btScalar)), 0)
					    << "size " << size << " trial " << trial << " axis " << k << ": got " << got[k]
					    << ", maxDot gives " << expected[k] << " (index " << index << ")";
				}
			}
		}
	}
}

TEST(ConvexHullShape, SupportSkipsOverflowingProductsAsMaxDotDoes)
{
	// Coordinates of 1e30 along directions of 1e10 overflow: products are +-inf and their sums may be
	// NaN. maxDot skips NaN and still takes -inf; the support must give the same point bitwise, down to
	// directions where every product is NaN or -inf (the first cloud along -(1, 1, 1): point 1 wins),
	// and where a NaN comes before the winner in the same lane of four (both clouds along (-1, 1, 1):
	// point 0 is NaN, point 4 is +inf, and in the second cloud point 6 is a finite runner-up).
	const btScalar big = btScalar(1e30);
	btAlignedObjectArray<btVector3> points;
	points.push_back(btVector3(big, -big, big));
	points.push_back(btVector3(big, big, big));
	points.push_back(btVector3(big, big, 0));
	points.push_back(btVector3(big, -big, 0));
	points.push_back(btVector3(-big, big, 0));
	points.push_back(btVector3(big, big, 0));
	points.push_back(btVector3(-big, -big, big));
	for (int cloud = 0; cloud < 2; ++cloud)
	{
		if (cloud == 1) points.push_back(btVector3(0, 0, 1));
		btConvexHullShape hull(&points[0].x(), points.size());
		polytest::Random rng(11);
		for (int trial = 0; trial < 200; ++trial)
		{
			btVector3 dir = rng.direction() * btScalar(1e10);
			if (trial < 27)
				dir = btVector3(btScalar(trial % 3 - 1), btScalar(trial / 3 % 3 - 1), btScalar(trial / 9 - 1)) *
				      btScalar(1e10);
			if (dir.length2() == 0) continue;
			btScalar best;
			const long index = dir.maxDot(&points[0], points.size(), best);
			const btConvexHullShape& constHull = hull;
			const btVector3 got = constHull.localGetSupportingVertexWithoutMargin(dir);
			const btVector3 expected = index >= 0 ? points[int(index)] : btVector3(0, 0, 0);
			for (int k = 0; k < 3; ++k)
				ASSERT_EQ(std::memcmp(&got[k], &expected[k], sizeof(btScalar)), 0)
				    << "cloud " << cloud << " trial " << trial << " axis " << k << ": got " << got[k]
				    << ", maxDot gives " << expected[k] << " (index " << index << ", dot " << best << ")";
		}
	}
}

TEST(ConvexHullShape, PointsEditedInPlaceAreSeenBySupport)
{
	btConvexHullShape hull;
	addBoxCorners(hull, btVector3(1, 1, 1));
	EXPECT_EQ(hull.localGetSupportingVertexWithoutMargin(btVector3(1, 1, 1)), btVector3(1, 1, 1));
	hull.getUnscaledPoints()[0] = btVector3(5, 5, 5);
	hull.recalcLocalAabb();
	EXPECT_EQ(hull.localGetSupportingVertexWithoutMargin(btVector3(1, 1, 1)), btVector3(5, 5, 5));
	EXPECT_EQ(hull.localGetSupportingVertexWithoutMargin(btVector3(-1, -1, -1)), btVector3(1, -1, -1))
	    << "the edited corner (-1, -1, -1) is gone: the first of the three next corners wins";
	// Adding a point afterwards keeps the edit.
	hull.addPoint(btVector3(-6, -6, -6));
	EXPECT_EQ(hull.localGetSupportingVertexWithoutMargin(btVector3(1, 1, 1)), btVector3(5, 5, 5));
	EXPECT_EQ(hull.localGetSupportingVertexWithoutMargin(btVector3(-1, -1, -1)), btVector3(-6, -6, -6));
	hull.optimizeConvexHull();
	EXPECT_EQ(hull.localGetSupportingVertexWithoutMargin(btVector3(1, 1, 1)), btVector3(5, 5, 5));
}

TEST(ConvexHullShape, StrideConstructorReadsInterleavedPoints)
{
	// x, y, z, then two unrelated scalars per record.
	const btScalar records[3][5] = {{1, 2, 3, 99, 99}, {-1, 0, 0, 99, 99}, {0, -5, 1, 99, 99}};
	btConvexHullShape hull(&records[0][0], 3, int(5 * sizeof(btScalar)));
	ASSERT_EQ(hull.getNumPoints(), 3);
	EXPECT_EQ(hull.getUnscaledPoints()[2], btVector3(0, -5, 1));
}

TEST(ConvexHullShape, AabbContainsAllPointsAndIsTight)
{
	polytest::Random rng(7);
	const btAlignedObjectArray<btVector3> points = randomCloud(rng, 30, 1);
	btConvexHullShape hull(&points[0].x(), points.size());
	hull.setMargin(btScalar(0.05));
	const btScalar margin = hull.getMargin();
	// Pure translation: the AABB is exactly the points' box grown by the margin.
	const btTransform shift(btQuaternion::getIdentity(), btVector3(3, -2, 1));
	btVector3 aabbMin, aabbMax;
	hull.getAabb(shift, aabbMin, aabbMax);
	btVector3 lo = points[0], hi = points[0];
	for (int i = 0; i < points.size(); ++i)
	{
		lo.setMin(points[i]);
		hi.setMax(points[i]);
	}
	const btScalar tol = btScalar(8) * SIMD_EPSILON * btScalar(4);
	for (int k = 0; k < 3; ++k)
	{
		EXPECT_NEAR(aabbMin[k], lo[k] + shift.getOrigin()[k] - margin, tol);
		EXPECT_NEAR(aabbMax[k], hi[k] + shift.getOrigin()[k] + margin, tol);
	}
	// Random rigid transforms: every point (with its margin ball) is inside, and the box is exactly the
	// box of the rotated local box grown by the margin: half extent |R| (localHalfExtents + margin).
	for (int trial = 0; trial < 50; ++trial)
	{
		const btTransform t = rng.transform(5);
		hull.getAabb(t, aabbMin, aabbMax);
		for (int i = 0; i < points.size(); ++i)
		{
			const btVector3 w = t(points[i]);
			for (int k = 0; k < 3; ++k)
			{
				EXPECT_LE(aabbMin[k], w[k] - margin + tol);
				EXPECT_GE(aabbMax[k], w[k] + margin - tol);
			}
		}
		const btVector3 bound =
		    t.getBasis().absolute() * ((hi - lo) * btScalar(0.5) + btVector3(margin, margin, margin));
		for (int k = 0; k < 3; ++k) EXPECT_NEAR(aabbMax[k] - aabbMin[k], 2 * bound[k], tol * 4);
	}
}

TEST(ConvexHullShape, LocalScalingScalesSupportAndAabb)
{
	polytest::Random rng(99);
	const btAlignedObjectArray<btVector3> points = randomCloud(rng, 25, 1);
	btConvexHullShape hull(&points[0].x(), points.size());
	const btVector3 scaling(2, btScalar(0.5), 3);
	hull.setLocalScaling(scaling);
	EXPECT_EQ(hull.getLocalScaling(), scaling);
	for (int trial = 0; trial < 100; ++trial)
	{
		const btVector3 dir = rng.direction();
		const btVector3 s = hull.localGetSupportingVertexWithoutMargin(dir);
		EXPECT_NEAR(s.dot(dir), bruteMaxDot(points, scaling, dir), kDotTol * 3);
	}
	EXPECT_EQ(hull.getScaledPoint(4), points[4] * scaling);
	btVector3 aabbMin, aabbMax;
	hull.setMargin(0);
	hull.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	btScalar maxX = -SIMD_INFINITY;
	for (int i = 0; i < points.size(); ++i) maxX = btMax(maxX, points[i].x() * scaling.x());
	EXPECT_EQ(aabbMax.x(), maxX);
}

TEST(ConvexHullShape, OptimizeConvexHullRemovesInteriorPoints)
{
	btConvexHullShape hull;
	addBoxCorners(hull, btVector3(1, 1, 1));
	polytest::Random rng(5);
	for (int i = 0; i < 40; ++i) hull.addPoint(rng.point(btScalar(0.9)), false);
	hull.addPoint(btVector3(1, 0, 0));  // on a face: not a vertex either
	ASSERT_EQ(hull.getNumPoints(), 49);
	hull.optimizeConvexHull();
	ASSERT_EQ(hull.getNumPoints(), 8);
	for (int i = 0; i < 8; ++i)
	{
		const btVector3 p = hull.getUnscaledPoints()[i];
		EXPECT_EQ(p.absolute(), btVector3(1, 1, 1));
	}
}

TEST(ConvexHullShape, PolyhedralFeaturesOfBoxHullHaveSixFaces)
{
	btConvexHullShape hull;
	addBoxCorners(hull, btVector3(1, 2, 3));
	hull.addPoint(btVector3(0, 0, 0));
	EXPECT_EQ(hull.getConvexPolyhedron(), nullptr);
	ASSERT_TRUE(hull.initializePolyhedralFeatures());
	const btConvexPolyhedron* poly = hull.getConvexPolyhedron();
	ASSERT_NE(poly, nullptr);
	EXPECT_EQ(poly->m_faces.size(), 6);
	EXPECT_EQ(poly->m_vertices.size(), 8);
	EXPECT_EQ(poly->m_uniqueEdges.size(), 3);
	// Shifted by the margin: each face plane moves out by exactly the margin.
	ASSERT_TRUE(hull.initializePolyhedralFeatures(1));
	poly = hull.getConvexPolyhedron();
	ASSERT_EQ(poly->m_faces.size(), 6);
	const btScalar tol = btScalar(64) * SIMD_EPSILON * btScalar(3);
	for (int f = 0; f < 6; ++f)
	{
		const btFace& face = poly->m_faces[f];
		const int axis = btVector3(face.m_plane[0], face.m_plane[1], face.m_plane[2]).absolute().maxAxis();
		EXPECT_NEAR(-face.m_plane[3], btVector3(1, 2, 3)[axis] + hull.getMargin(), tol);
	}
	// A copy owns its own polyhedron.
	btConvexHullShape copy(hull);
	ASSERT_NE(copy.getConvexPolyhedron(), nullptr);
	EXPECT_NE(copy.getConvexPolyhedron(), hull.getConvexPolyhedron());
	EXPECT_EQ(copy.getConvexPolyhedron()->m_faces.size(), 6);
}

TEST(ConvexHullShape, InertiaIsExactSolidBoxAndTetrahedron)
{
	btConvexHullShape box;
	addBoxCorners(box, btVector3(1, 2, 3));
	const btScalar mass = 12;
	btVector3 inertia;
	box.calculateLocalInertia(mass, inertia);
	// Solid box with sides 2, 4, 6: I = m (b^2 + c^2) / 12; double accumulation of float inputs.
	const btScalar tol = btScalar(64) * SIMD_EPSILON * mass * btScalar(52) / 12;
	EXPECT_NEAR(inertia.x(), mass * (16 + 36) / 12, tol);
	EXPECT_NEAR(inertia.y(), mass * (4 + 36) / 12, tol);
	EXPECT_NEAR(inertia.z(), mass * (4 + 16) / 12, tol);

	// Right-corner tetrahedron (0, a e_x, b e_y, c e_z), about its centroid:
	// Ixx = 3 m (b^2 + c^2) / 80 (the standard result).
	btConvexHullShape tetra;
	tetra.addPoint(btVector3(0, 0, 0));
	tetra.addPoint(btVector3(1, 0, 0));
	tetra.addPoint(btVector3(0, 2, 0));
	tetra.addPoint(btVector3(0, 0, 3));
	tetra.calculateLocalInertia(mass, inertia);
	EXPECT_NEAR(inertia.x(), 3 * mass * (4 + 9) / 80, tol);
	EXPECT_NEAR(inertia.y(), 3 * mass * (1 + 9) / 80, tol);
	EXPECT_NEAR(inertia.z(), 3 * mass * (1 + 4) / 80, tol);

	// Local scaling scales the solid: the unit box scaled by (1, 2, 3) is the 2 x 4 x 6 box.
	btConvexHullShape unit;
	addBoxCorners(unit, btVector3(1, 1, 1));
	unit.setLocalScaling(btVector3(1, 2, 3));
	unit.calculateLocalInertia(mass, inertia);
	EXPECT_NEAR(inertia.x(), mass * (16 + 36) / 12, tol);
}

TEST(ConvexHullShape, EmptyHullBehavesAsPointAtOrigin)
{
	btConvexHullShape hull;
	EXPECT_EQ(hull.getNumPoints(), 0);
	EXPECT_EQ(hull.localGetSupportingVertexWithoutMargin(btVector3(1, 2, 3)), btVector3(0, 0, 0));
	btVector3 aabbMin, aabbMax;
	hull.getAabb(btTransform(btQuaternion::getIdentity(), btVector3(1, 1, 1)), aabbMin, aabbMax);
	const btScalar m = hull.getMargin();
	EXPECT_EQ(aabbMin, btVector3(1 - m, 1 - m, 1 - m));
	EXPECT_EQ(aabbMax, btVector3(1 + m, 1 + m, 1 + m));
	btVector3 inertia;
	hull.calculateLocalInertia(1, inertia);
	// No volume: Bullet's box of the AABB grown by the margin (a cube of side 2m).
	EXPECT_NEAR(inertia.x(), (8 * m * m) / 12, SIMD_EPSILON);
	hull.optimizeConvexHull();
	EXPECT_EQ(hull.getNumPoints(), 0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(hull.initializePolyhedralFeatures(), "assertion failed");
#else
	EXPECT_FALSE(hull.initializePolyhedralFeatures());
	EXPECT_EQ(hull.getConvexPolyhedron(), nullptr);
#endif
}

TEST(ConvexHullShape, OneAndTwoPointHullsAreAPointAndASegment)
{
	btConvexHullShape one;
	one.addPoint(btVector3(1, 2, 3));
	EXPECT_EQ(one.localGetSupportingVertexWithoutMargin(btVector3(-1, 0, 0)), btVector3(1, 2, 3));
	btVector3 inertia;
	one.calculateLocalInertia(2, inertia);
	EXPECT_TRUE(btIsFinite(inertia.x()) && inertia.x() > 0);

	btConvexHullShape two;
	two.addPoint(btVector3(-1, 0, 0));
	two.addPoint(btVector3(1, 0, 0));
	EXPECT_EQ(two.localGetSupportingVertexWithoutMargin(btVector3(1, btScalar(0.1), 0)), btVector3(1, 0, 0));
	EXPECT_EQ(two.localGetSupportingVertexWithoutMargin(btVector3(-1, 5, 0)), btVector3(-1, 0, 0));
	// A zero direction is replaced by (-1, -1, -1): a finite point of the shape.
	EXPECT_EQ(two.localGetSupportingVertexWithoutMargin(btVector3(0, 0, 0)), btVector3(-1, 0, 0));
	two.optimizeConvexHull();
	EXPECT_EQ(two.getNumPoints(), 2);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(two.initializePolyhedralFeatures(), "assertion failed");
#else
	EXPECT_FALSE(two.initializePolyhedralFeatures());
#endif
}

TEST(ConvexHullShape, CoplanarHullIsFlatPolygonWithBoxInertiaFallback)
{
	btConvexHullShape flat;
	flat.addPoint(btVector3(0, 0, 0));
	flat.addPoint(btVector3(2, 0, 0));
	flat.addPoint(btVector3(2, 2, 0));
	flat.addPoint(btVector3(0, 2, 0));
	flat.addPoint(btVector3(1, 1, 0));
	ASSERT_TRUE(flat.initializePolyhedralFeatures());
	EXPECT_EQ(flat.getConvexPolyhedron()->m_faces.size(), 2);
	btVector3 inertia;
	const btScalar m = flat.getMargin();
	flat.calculateLocalInertia(3, inertia);
	// Box 2 x 2 x 0 grown by the margin on each side.
	const btScalar sx = 2 + 2 * m, sz = 2 * m;
	EXPECT_NEAR(inertia.x(), 3 * (sx * sx + sz * sz) / 12, btScalar(64) * SIMD_EPSILON);
	EXPECT_NEAR(inertia.z(), 3 * (sx * sx + sx * sx) / 12, btScalar(64) * SIMD_EPSILON);
	flat.optimizeConvexHull();
	EXPECT_EQ(flat.getNumPoints(), 4);
}

TEST(ConvexHullShape, NonFinitePointsAreRejected)
{
	btConvexHullShape hull;
	hull.addPoint(btVector3(1, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(hull.addPoint(btVector3(BT_NAN, 0, 0)), "assertion failed");
	EXPECT_DEATH(btConvexHullShape(0, 3), "assertion failed");
#else
	hull.addPoint(btVector3(BT_NAN, 0, 0));
	hull.addPoint(btVector3(0, BT_INFINITY, 0));
	EXPECT_EQ(hull.getNumPoints(), 1);
	const btVector3 s = hull.localGetSupportingVertex(btVector3(0, 1, 0));
	EXPECT_TRUE(btIsFinite(s.x()) && btIsFinite(s.y()) && btIsFinite(s.z()));
	btConvexHullShape fromNull(0, 3);
	EXPECT_EQ(fromNull.getNumPoints(), 0);
#endif
	// A NaN direction gives a finite support point.
	const btVector3 s2 = hull.localGetSupportingVertexWithoutMargin(btVector3(BT_NAN, 0, 0));
	EXPECT_EQ(s2, btVector3(1, 0, 0));
}

TEST(ConvexHullShape, NonFiniteTransformGivesOverflowAabb)
{
	btConvexHullShape hull;
	addBoxCorners(hull, btVector3(1, 1, 1));
	btTransform bad(btQuaternion::getIdentity(), btVector3(BT_NAN, 0, 0));
	btVector3 aabbMin, aabbMax;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(hull.getAabb(bad, aabbMin, aabbMax), "assertion failed");
#else
	hull.getAabb(bad, aabbMin, aabbMax);
	EXPECT_EQ(aabbMin, btVector3(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT));
	EXPECT_EQ(aabbMax, btVector3(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT));
#endif
}
