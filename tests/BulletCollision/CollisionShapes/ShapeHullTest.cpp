// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btShapeHull: the hull of sampled support points is closed, outward-facing, and has the expected corners.

#include <gtest/gtest.h>

#include <map>
#include <utility>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btShapeHull.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"

using namespace shapes_core_test;

namespace
{
// Support points are products of unit directions and sizes of order 1: a few roundings.
const btScalar kHullTolerance = btScalar(64) * SIMD_EPSILON;

// Indices valid, every directed edge used once and its reverse once (closed, consistently wound), every
// triangle facing away from the interior (all vertices on or behind its plane), Euler characteristic 2.
void expectClosedOutwardMesh(const btShapeHull& hull)
{
	ASSERT_GT(hull.numTriangles(), 0);
	ASSERT_EQ(hull.numTriangles() * 3, hull.numIndices());
	const btVector3* vertices = hull.getVertexPointer();
	const unsigned int* indices = hull.getIndexPointer();
	ASSERT_NE(nullptr, vertices);
	ASSERT_NE(nullptr, indices);
	std::map<std::pair<unsigned, unsigned>, int> directed;
	for (int i = 0; i < hull.numIndices(); ++i) ASSERT_LT(indices[i], unsigned(hull.numVertices()));
	for (int t = 0; t < hull.numTriangles(); ++t)
	{
		const unsigned* tri = indices + 3 * t;
		for (int e = 0; e < 3; ++e) ++directed[std::make_pair(tri[e], tri[(e + 1) % 3])];
		const btVector3 normal =
		    (vertices[tri[1]] - vertices[tri[0]]).cross(vertices[tri[2]] - vertices[tri[0]]).normalized();
		for (int v = 0; v < hull.numVertices(); ++v)
			EXPECT_LE(normal.dot(vertices[v] - vertices[tri[0]]), kHullTolerance)
			    << "vertex " << v << " in front of triangle " << t;
	}
	for (const auto& edge : directed)
	{
		EXPECT_EQ(1, edge.second) << "directed edge " << edge.first.first << "-" << edge.first.second;
		const auto reverse = directed.find(std::make_pair(edge.first.second, edge.first.first));
		EXPECT_TRUE(reverse != directed.end()) << "open edge " << edge.first.first << "-" << edge.first.second;
	}
	const int edges = int(directed.size()) / 2;
	EXPECT_EQ(2, hull.numVertices() - edges + hull.numTriangles());
}
}  // namespace

TEST(ShapeHullTest, BoxHullIsItsEightCorners)
{
	const btVector3 half(1, 2, btScalar(0.5));
	btBoxShape box(half);
	for (btScalar margin : {btScalar(0.04), btScalar(0.3)})
	{
		// The margin sits inside the box's outer size, so the corners stay at +-half whatever it is.
		box.setMargin(margin);
		btShapeHull hull(&box);
		ASSERT_TRUE(hull.buildHull(box.getMargin()));
		EXPECT_EQ(8, hull.numVertices());
		EXPECT_EQ(12, hull.numTriangles());
		int cornerMask = 0;
		for (int v = 0; v < hull.numVertices(); ++v)
		{
			const btVector3& p = hull.getVertexPointer()[v];
			const btVector3 corner(p.x() > 0 ? half.x() : -half.x(), p.y() > 0 ? half.y() : -half.y(),
			                       p.z() > 0 ? half.z() : -half.z());
			EXPECT_TRUE(vectorsNear(p, corner, kHullTolerance));
			cornerMask |= 1 << ((p.x() > 0) + 2 * (p.y() > 0) + 4 * (p.z() > 0));
		}
		EXPECT_EQ(0xff, cornerMask);
		expectClosedOutwardMesh(hull);
	}
}

TEST(ShapeHullTest, SphereHullVerticesLieOnTheRadius)
{
	const btScalar radius = btScalar(1.5);
	btSphereShape sphere(radius);
	for (int highres = 0; highres < 2; ++highres)
	{
		btShapeHull hull(&sphere);
		ASSERT_TRUE(hull.buildHull(sphere.getMargin(), highres));
		// 10 f^2 + 2 geodesic directions (frequency 2, or 4 for highres), each a distinct point on the sphere.
		EXPECT_EQ(highres ? 162 : 42, hull.numVertices());
		for (int v = 0; v < hull.numVertices(); ++v)
			EXPECT_NEAR(double(hull.getVertexPointer()[v].length()), double(radius), double(kHullTolerance));
		expectClosedOutwardMesh(hull);
	}
}

TEST(ShapeHullTest, RoundShapesGiveClosedHullsOfSupportPoints)
{
	btCapsuleShape capsule(btScalar(0.5), 2);
	btCylinderShape cylinder(btVector3(1, btScalar(0.7), 1));
	btConeShape cone(1, 2);
	const btConvexShape* shapes[] = {&capsule, &cylinder, &cone};
	for (const btConvexShape* shape : shapes)
	{
		SCOPED_TRACE(shape->getName());
		btShapeHull hull(shape);
		ASSERT_TRUE(hull.buildHull(shape->getMargin()));
		expectClosedOutwardMesh(hull);
		// Every hull vertex is a surface point: its support value along its own direction is not exceeded.
		for (int v = 0; v < hull.numVertices(); ++v)
		{
			const btVector3& p = hull.getVertexPointer()[v];
			const btVector3 support = shape->localGetSupportingVertex(p.normalized());
			EXPECT_LE(double(p.dot(p.normalized())), double(support.dot(p.normalized()) + kHullTolerance));
		}
	}
}

TEST(ShapeHullTest, DegenerateShapesGiveAnEmptyHull)
{
	btBoxShape point(btVector3(0, 0, 0));
	btBoxShape flat(btVector3(1, 1, 0));
	btSphereShape zeroSphere(0);
	const btConvexShape* shapes[] = {&point, &flat, &zeroSphere};
	for (const btConvexShape* shape : shapes)
	{
		SCOPED_TRACE(shape->getName());
		btShapeHull hull(shape);
		EXPECT_FALSE(hull.buildHull(0));
		EXPECT_EQ(0, hull.numTriangles());
		EXPECT_EQ(0, hull.numVertices());
		EXPECT_EQ(0, hull.numIndices());
		EXPECT_EQ(nullptr, hull.getVertexPointer());
		EXPECT_EQ(nullptr, hull.getIndexPointer());
	}
}

TEST(ShapeHullTest, RebuildReplacesThePreviousHull)
{
	btBoxShape box(btVector3(1, 1, 1));
	btShapeHull hull(&box);
	ASSERT_TRUE(hull.buildHull(0));
	ASSERT_TRUE(hull.buildHull(0, 1));
	EXPECT_EQ(8, hull.numVertices());
	EXPECT_EQ(36, hull.numIndices());
}

TEST(ShapeHullTest, NullShapeIsRejected)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btShapeHull(nullptr), "assertion failed");
#else
	btShapeHull hull(nullptr);
	EXPECT_FALSE(hull.buildHull(0));
	EXPECT_EQ(0, hull.numTriangles());
#endif
}
