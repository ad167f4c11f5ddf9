// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Triangle, simplex, point cloud, multi-sphere, Minkowski sum and uniform scaling shapes.
#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btConvexPointCloudShape.h"
#include "BulletCollision/CollisionShapes/btMinkowskiSumShape.h"
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletCollision/CollisionShapes/btTetrahedronShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/CollisionShapes/btUniformScalingShape.h"
#include "BulletCollision/CollisionShapes/PolyShapeTestUtil.h"

namespace
{
// Unit-sized coordinates through a handful of operations: a few dozen ulps.
const btScalar kTol = btScalar(64) * SIMD_EPSILON;

bool isFinite(const btVector3& v) { return btIsFinite(v.x()) && btIsFinite(v.y()) && btIsFinite(v.z()); }
}  // namespace

TEST(TriangleShape, SupportNormalPlaneAndIsInside)
{
	btTriangleShape tri(btVector3(0, 0, 0), btVector3(2, 0, 0), btVector3(0, 2, 0));
	EXPECT_EQ(tri.getShapeType(), TRIANGLE_SHAPE_PROXYTYPE);
	EXPECT_EQ(tri.localGetSupportingVertexWithoutMargin(btVector3(1, btScalar(0.1), 0)), btVector3(2, 0, 0));
	EXPECT_EQ(tri.localGetSupportingVertexWithoutMargin(btVector3(-1, -1, 0)), btVector3(0, 0, 0));
	btVector3 normal, support;
	tri.calcNormal(normal);
	EXPECT_NEAR((normal - btVector3(0, 0, 1)).length(), 0, kTol);
	tri.getPlane(normal, support, 0);
	EXPECT_EQ(support, btVector3(0, 0, 0));
	EXPECT_TRUE(tri.isInside(btVector3(btScalar(0.5), btScalar(0.5), 0), kTol));
	EXPECT_TRUE(tri.isInside(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.05)), btScalar(0.1)));
	EXPECT_FALSE(tri.isInside(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)), btScalar(0.1)));
	EXPECT_FALSE(tri.isInside(btVector3(2, 2, 0), btScalar(0.1)));
	EXPECT_FALSE(tri.isInside(btVector3(-1, btScalar(0.5), 0), btScalar(0.1)));
	btVector3 dir;
	tri.getPreferredPenetrationDirection(1, dir);
	EXPECT_NEAR((dir + btVector3(0, 0, 1)).length(), 0, kTol);
	btVector3 inertia(1, 1, 1);
	tri.calculateLocalInertia(5, inertia);
	EXPECT_EQ(inertia, btVector3(0, 0, 0));
	// The AABB holds the three corners grown by the margin.
	btVector3 aabbMin, aabbMax;
	tri.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	const btScalar m = tri.getMargin();
	EXPECT_NEAR((aabbMin - btVector3(-m, -m, -m)).length(), 0, kTol);
	EXPECT_NEAR((aabbMax - btVector3(2 + m, 2 + m, m)).length(), 0, kTol);
}

TEST(TriangleShape, DegenerateTriangleHasZeroNormalAndNothingInside)
{
	btTriangleShape tri(btVector3(0, 0, 0), btVector3(1, 1, 1), btVector3(2, 2, 2));
	btVector3 normal(5, 5, 5);
	tri.calcNormal(normal);
	EXPECT_EQ(normal, btVector3(0, 0, 0));
	EXPECT_FALSE(tri.isInside(btVector3(1, 1, 1), 1));
	btTriangleShape nanTri(btVector3(BT_NAN, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
	nanTri.calcNormal(normal);
	EXPECT_EQ(normal, btVector3(0, 0, 0));
}

TEST(TriangleShape, PolyhedralFeaturesAreTwoSidedTriangle)
{
	btTriangleShape tri(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
	ASSERT_TRUE(tri.initializePolyhedralFeatures());
	EXPECT_EQ(tri.getConvexPolyhedron()->m_faces.size(), 2);
	btTriangleShape copy = tri;
	EXPECT_NE(copy.getConvexPolyhedron(), tri.getConvexPolyhedron());
}

TEST(Simplex1to4, TetrahedronPlanesPointOutwardAndInertiaIsExact)
{
	btBU_Simplex1to4 tet(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 2, 0), btVector3(0, 0, 3));
	EXPECT_EQ(tet.getShapeType(), TETRAHEDRAL_SHAPE_PROXYTYPE);
	EXPECT_EQ(tet.getNumVertices(), 4);
	EXPECT_EQ(tet.getNumEdges(), 6);
	ASSERT_EQ(tet.getNumPlanes(), 4);
	const btVector3 centroid(btScalar(0.25), btScalar(0.5), btScalar(0.75));
	for (int i = 0; i < 4; ++i)
	{
		btVector3 n, p;
		tet.getPlane(n, p, i);
		EXPECT_NEAR(n.length(), 1, kTol);
		EXPECT_LT((centroid - p).dot(n), 0);
	}
	EXPECT_TRUE(tet.isInside(centroid, 0));
	EXPECT_FALSE(tet.isInside(btVector3(1, 1, 1), btScalar(0.01)));
	EXPECT_EQ(tet.localGetSupportingVertexWithoutMargin(btVector3(0, 0, 1)), btVector3(0, 0, 3));
	btVector3 inertia;
	const btScalar mass = 2;
	tet.calculateLocalInertia(mass, inertia);
	// Right-corner tetrahedron about its centroid: Ixx = 3 m (b^2 + c^2) / 80.
	EXPECT_NEAR(inertia.x(), 3 * mass * (4 + 9) / 80, kTol * 4);
	EXPECT_NEAR(inertia.z(), 3 * mass * (1 + 4) / 80, kTol * 4);
	btVector3 aabbMin, aabbMax;
	tet.setMargin(0);
	tet.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_EQ(aabbMin, btVector3(0, 0, 0));
	EXPECT_EQ(aabbMax, btVector3(1, 2, 3));
}

TEST(Simplex1to4, GrowsFromEmptyAndRejectsAFifthVertex)
{
	btBU_Simplex1to4 simplex;
	EXPECT_EQ(simplex.getNumVertices(), 0);
	EXPECT_EQ(simplex.localGetSupportingVertexWithoutMargin(btVector3(1, 0, 0)), btVector3(0, 0, 0));
	simplex.addVertex(btVector3(1, 0, 0));
	EXPECT_EQ(simplex.getNumEdges(), 0);
	simplex.addVertex(btVector3(-1, 0, 0));
	EXPECT_EQ(simplex.getNumEdges(), 1);
	simplex.addVertex(btVector3(0, 1, 0));
	EXPECT_EQ(simplex.getNumEdges(), 3);
	EXPECT_EQ(simplex.getNumPlanes(), 2);
	simplex.addVertex(btVector3(0, 0, 1));
	EXPECT_EQ(simplex.getNumVertices(), 4);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(simplex.addVertex(btVector3(5, 5, 5)), "assertion failed");
#else
	simplex.addVertex(btVector3(5, 5, 5));
	EXPECT_EQ(simplex.getNumVertices(), 4);
#endif
	simplex.reset();
	EXPECT_EQ(simplex.getNumVertices(), 0);
}

TEST(ConvexPointCloudShape, SupportMatchesBruteForceWithScaling)
{
	polytest::Random rng(321);
	btAlignedObjectArray<btVector3> points;
	for (int i = 0; i < 40; ++i) points.push_back(rng.point(2));
	const btVector3 scaling(1, 2, btScalar(0.5));
	btConvexPointCloudShape cloud(&points[0], points.size(), scaling);
	EXPECT_EQ(cloud.getShapeType(), CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE);
	for (int trial = 0; trial < 100; ++trial)
	{
		const btVector3 dir = rng.direction();
		btScalar best = -SIMD_INFINITY;
		for (int i = 0; i < points.size(); ++i) best = btMax(best, (points[i] * scaling).dot(dir));
		// Exact input points; ties within rounding of coordinates up to 4 in size.
		EXPECT_NEAR(cloud.localGetSupportingVertexWithoutMargin(dir).dot(dir), best, btScalar(64) * SIMD_EPSILON);
	}
	EXPECT_EQ(cloud.getScaledPoint(3), points[3] * scaling);
	// The cloud is not copied: moving a point and recomputing the AABB follows it.
	points[0] = btVector3(100, 0, 0);
	cloud.recalcLocalAabb();
	btVector3 aabbMin, aabbMax;
	cloud.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_NEAR(aabbMax.x(), 100 + cloud.getMargin(), kTol * 100);
}

TEST(ConvexPointCloudShape, NonFinitePointsAreNeverSupportPoints)
{
	btVector3 points[3] = {btVector3(1, 0, 0), btVector3(0, BT_INFINITY, 0), btVector3(BT_NAN, 0, 0)};
#if CALIBER_ASSERTS_ENABLED
	btConvexPointCloudShape cloud;
	EXPECT_DEATH(cloud.setPoints(points, 3), "assertion failed");
	EXPECT_DEATH(cloud.setPoints(0, 3), "assertion failed");
#else
	btConvexPointCloudShape cloud(points, 3, btVector3(1, 1, 1));
	EXPECT_EQ(cloud.localGetSupportingVertexWithoutMargin(btVector3(0, 1, 0)), btVector3(1, 0, 0));
	btVector3 aabbMin, aabbMax;
	cloud.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_TRUE(isFinite(aabbMin) && isFinite(aabbMax));
	cloud.setPoints(0, 3);
	EXPECT_EQ(cloud.getNumPoints(), 0);
#endif
	btConvexPointCloudShape empty;
	EXPECT_EQ(empty.localGetSupportingVertexWithoutMargin(btVector3(1, 1, 1)), btVector3(0, 0, 0));
}

TEST(MultiSphereShape, SupportIsFarthestSampledSpherePoint)
{
	const btVector3 centres[3] = {btVector3(0, 0, 0), btVector3(2, 0, 0), btVector3(0, 1, 1)};
	const btScalar radii[3] = {btScalar(0.5), btScalar(1), btScalar(0.25)};
	btMultiSphereShape shape(centres, radii, 3);
	EXPECT_EQ(shape.getShapeType(), MULTI_SPHERE_SHAPE_PROXYTYPE);
	EXPECT_EQ(shape.getSphereCount(), 3);
	polytest::Random rng(77);
	for (int trial = 0; trial < 100; ++trial)
	{
		const btVector3 dir = rng.direction();
		const btVector3 s = shape.localGetSupportingVertex(dir);
		// Brute force over points sampled on each sphere: the support reaches at least as far, and no
		// farther than the analytic max over spheres of c.d + r.
		btScalar sampled = -SIMD_INFINITY, analytic = -SIMD_INFINITY;
		for (int k = 0; k < 3; ++k)
		{
			analytic = btMax(analytic, centres[k].dot(dir) + radii[k]);
			for (int j = 0; j < 200; ++j) sampled = btMax(sampled, (centres[k] + radii[k] * rng.direction()).dot(dir));
		}
		EXPECT_GE(s.dot(dir), sampled - kTol);
		EXPECT_NEAR(s.dot(dir), analytic, kTol * 4);
	}
}

TEST(MultiSphereShape, InertiaOfOneSphereIsSolidSphere)
{
	const btVector3 centre(0, 0, 0);
	const btScalar radius = 2;
	btMultiSphereShape sphere(&centre, &radius, 1);
	btVector3 inertia;
	const btScalar mass = 3;
	sphere.calculateLocalInertia(mass, inertia);
	// Sampled polytope inscribed in the sphere with 400 vertices: faces ~0.5% of r inside, so the second
	// moment per unit mass is low by about 1%; allow 2%.
	const btScalar exact = btScalar(0.4) * mass * radius * radius;
	for (int k = 0; k < 3; ++k) EXPECT_NEAR(inertia[k], exact, btScalar(0.02) * exact);
}

TEST(MultiSphereShape, LocalScalingScalesCentresAndRadii)
{
	const btVector3 centres[2] = {btVector3(-1, 0, 0), btVector3(1, 0, 0)};
	const btScalar radii[2] = {btScalar(0.5), btScalar(0.5)};
	btMultiSphereShape capsule(centres, radii, 2);
	capsule.setLocalScaling(btVector3(2, 2, 2));
	const btVector3 s = capsule.localGetSupportingVertex(btVector3(1, 0, 0));
	EXPECT_NEAR(s.x(), 3, kTol * 4);
	btVector3 aabbMin, aabbMax;
	capsule.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_NEAR(aabbMax.x(), 3, kTol * 4);
	EXPECT_NEAR(aabbMax.y(), 1, kTol * 4);
}

TEST(MultiSphereShape, BadSpheresAreSanitized)
{
	const btVector3 centres[2] = {btVector3(0, 0, 0), btVector3(BT_NAN, 0, 0)};
	const btScalar radii[2] = {btScalar(-1), btScalar(1)};
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btMultiSphereShape(centres, radii, 2), "assertion failed");
#else
	btMultiSphereShape shape(centres, radii, 2);
	EXPECT_EQ(shape.getSphereCount(), 1);
	EXPECT_EQ(shape.getSphereRadius(0), btScalar(1));
	btVector3 inertia;
	shape.calculateLocalInertia(1, inertia);
	EXPECT_TRUE(isFinite(inertia));
#endif
	btMultiSphereShape empty(0, 0, 0);
	EXPECT_EQ(empty.getSphereCount(), 0);
	EXPECT_EQ(empty.localGetSupportingVertexWithoutMargin(btVector3(1, 0, 0)), btVector3(0, 0, 0));
	btVector3 emptyInertia;
	empty.calculateLocalInertia(1, emptyInertia);
	EXPECT_TRUE(isFinite(emptyInertia));
}

TEST(MinkowskiSumShape, SumOfTwoSpheresIsSphereOfSummedRadii)
{
	const btVector3 origin(0, 0, 0);
	const btScalar ra = btScalar(0.7), rb = btScalar(1.1);
	btMultiSphereShape a(&origin, &ra, 1), b(&origin, &rb, 1);
	btMinkowskiSumShape sum(&a, &b);
	EXPECT_EQ(sum.getShapeType(), MINKOWSKI_SUM_SHAPE_PROXYTYPE);
	EXPECT_NEAR(sum.getMargin(), a.getMargin() + b.getMargin(), kTol);
	polytest::Random rng(11);
	for (int trial = 0; trial < 100; ++trial)
	{
		const btVector3 dir = rng.direction();
		const btVector3 s = sum.localGetSupportingVertex(dir);
		EXPECT_NEAR((s - dir * (ra + rb)).length(), 0, kTol * 4);
	}
	// Placing the children translates the shape by A's offset minus B's (Bullet's A + (-B)).
	sum.setTransformA(btTransform(btQuaternion::getIdentity(), btVector3(1, 0, 0)));
	sum.setTransformB(btTransform(btQuaternion(btVector3(0, 0, 1), 1), btVector3(0, 2, 0)));
	const btVector3 s = sum.localGetSupportingVertex(btVector3(0, 0, 1));
	EXPECT_NEAR((s - btVector3(1, -2, ra + rb)).length(), 0, kTol * 4);
	btVector3 inertia;
	sum.calculateLocalInertia(1, inertia);
	const btScalar exact = btScalar(0.4) * (ra + rb) * (ra + rb);
	EXPECT_NEAR(inertia.x(), exact, btScalar(0.02) * exact);
}

TEST(MinkowskiSumShape, NullChildIsAPoint)
{
	const btVector3 origin(0, 0, 0);
	const btScalar r = 1;
	btMultiSphereShape a(&origin, &r, 1);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btMinkowskiSumShape(&a, 0), "assertion failed");
#else
	btMinkowskiSumShape sum(&a, 0);
	EXPECT_NEAR((sum.localGetSupportingVertex(btVector3(1, 0, 0)) - btVector3(1, 0, 0)).length(), 0, kTol * 4);
#endif
}

TEST(UniformScalingShape, ScalesSupportsAabbAndInertia)
{
	btConvexHullShape hull;
	polytest::Random rng(8);
	for (int i = 0; i < 20; ++i) hull.addPoint(rng.point(1));
	const btScalar factor = btScalar(2.5);
	btUniformScalingShape scaled(&hull, factor);
	EXPECT_EQ(scaled.getShapeType(), UNIFORM_SCALING_SHAPE_PROXYTYPE);
	EXPECT_NEAR(scaled.getMargin(), hull.getMargin() * factor, kTol);
	for (int trial = 0; trial < 50; ++trial)
	{
		const btVector3 dir = rng.direction();
		EXPECT_NEAR((scaled.localGetSupportingVertexWithoutMargin(dir) -
		             hull.localGetSupportingVertexWithoutMargin(dir) * factor)
		                .length(),
		            0, kTol * 4);
		EXPECT_NEAR((scaled.localGetSupportingVertex(dir) - hull.localGetSupportingVertex(dir) * factor).length(), 0,
		            kTol * 4);
	}
	const btTransform t = rng.transform(3);
	btVector3 aabbMin, aabbMax;
	scaled.getAabb(t, aabbMin, aabbMax);
	for (int i = 0; i < hull.getNumPoints(); ++i)
	{
		const btVector3 w = t(hull.getUnscaledPoints()[i] * factor);
		for (int k = 0; k < 3; ++k)
		{
			EXPECT_LE(aabbMin[k], w[k] + kTol * 8);
			EXPECT_GE(aabbMax[k], w[k] - kTol * 8);
		}
	}
	btVector3 childInertia, inertia;
	hull.calculateLocalInertia(2, childInertia);
	scaled.calculateLocalInertia(2, inertia);
	EXPECT_NEAR((inertia - childInertia * factor * factor).length(), 0, kTol * childInertia.length() * 8);
}

TEST(UniformScalingShape, BadFactorAndNullChild)
{
	btConvexHullShape hull;
	hull.addPoint(btVector3(1, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btUniformScalingShape(&hull, -2), "assertion failed");
	EXPECT_DEATH(btUniformScalingShape(0, 1), "assertion failed");
#else
	btUniformScalingShape negative(&hull, -2);
	EXPECT_EQ(negative.getUniformScalingFactor(), btScalar(2));
	btUniformScalingShape notANumber(&hull, BT_NAN);
	EXPECT_EQ(notANumber.getUniformScalingFactor(), btScalar(0));
	btUniformScalingShape none(0, 1);
	EXPECT_EQ(none.localGetSupportingVertex(btVector3(1, 0, 0)), btVector3(0, 0, 0));
	btVector3 aabbMin, aabbMax;
	none.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_EQ(aabbMin, btVector3(0, 0, 0));
#endif
}
