// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The BVH after the mesh changes (refitTree, partialRefitTree, updateBvhNodes, local scaling, shared
// trees) and on bad input (empty meshes, zero-area triangles, NaN vertices, bad indices, null mesh).

#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/CollisionShapes/TriangleMeshTestUtil.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"

using namespace mesh_test;

namespace
{
// See BvhQueryTest.cpp: a quantized node and the quantized query each reach < 2.0625 steps further.
const btScalar kQuantizedReachSteps = btScalar(4.25);

btVector3 reachOf(btBvhTriangleMeshShape& shape)
{
	if (!shape.usesQuantizedAabbCompression()) return btVector3(0, 0, 0);
	const btVector3& q = caliber::bvhQuantization(*shape.getOptimizedBvh());
	return kQuantizedReachSteps * btVector3(btScalar(1) / q.x(), btScalar(1) / q.y(), btScalar(1) / q.z());
}

// Checks shape's box queries against brute force over mesh (scaled by scaling): every overlapping
// triangle reported, nothing beyond the quantization reach (exact when unquantized).
::testing::AssertionResult queriesMatchBruteForce(const btConcaveShape& shape, const TestMesh& mesh,
                                                  const btVector3& scaling, const btVector3& reach, unsigned seed,
                                                  btScalar range = 14)
{
	Random rng(seed);
	for (int q = 0; q < 60; ++q)
	{
		const btVector3 centre = rng.vector(range);
		const btVector3 half(rng.uniform(0, 4), rng.uniform(0, 4), rng.uniform(0, 4));
		const btVector3 qMin = centre - half, qMax = centre + half;
		TriangleSet mustReport, mayReport;
		for (const TriangleKey& k : mesh.allTriangles())
		{
			btVector3 tri[3], tMin, tMax;
			mesh.triangle(k.first, k.second, scaling, tri);
			triangleBox(tri, tMin, tMax);
			if (boxesOverlap(tMin, tMax, qMin, qMax)) mustReport.insert(k);
			if (boxesOverlap(tMin, tMax, qMin, qMax, reach)) mayReport.insert(k);
		}
		Collector c;
		shape.processAllTriangles(&c, qMin, qMax);
		if (c.duplicates) return ::testing::AssertionFailure() << "query " << q << ": duplicates";
		if (!minus(mustReport, c.keys).empty())
			return ::testing::AssertionFailure() << "query " << q << " missed" << describe(minus(mustReport, c.keys));
		if (!minus(c.keys, mayReport).empty())
			return ::testing::AssertionFailure() << "query " << q << " extra" << describe(minus(c.keys, mayReport));
		for (size_t i = 0; i < c.order.size(); ++i)
		{
			btVector3 tri[3];
			mesh.triangle(c.order[i].first, c.order[i].second, scaling, tri);
			for (int k = 0; k < 3; ++k)
			{
				// The scaled shape multiplies twice (child scaling 1, then its own), same rounding as here.
				if ((tri[k] - c.vertices[3 * i + size_t(k)]).length() > btScalar(0))
					return ::testing::AssertionFailure() << "query " << q << ": wrong vertex for triangle " << i;
			}
		}
	}
	return ::testing::AssertionSuccess();
}

void buildSoupMesh(unsigned seed, TestMesh& mesh)
{
	Random rng(seed);
	std::vector<btVector3> vertices;
	std::vector<int> indices;
	randomSoup(rng, 400, 10, btScalar(1.5), vertices, indices);
	mesh.addPart(vertices, indices, PHY_FLOAT, 3, PHY_INTEGER);
	vertices.clear();
	indices.clear();
	randomSoup(rng, 200, 10, btScalar(1.5), vertices, indices);
	mesh.addPart(vertices, indices, PHY_DOUBLE, 3, PHY_SHORT);
}

void bruteForceBox(const TestMesh& mesh, btVector3& mn, btVector3& mx)
{
	bool first = true;
	for (const TriangleKey& k : mesh.allTriangles())
	{
		btVector3 tri[3], tMin, tMax;
		mesh.triangle(k.first, k.second, btVector3(1, 1, 1), tri);
		triangleBox(tri, tMin, tMax);
		if (first) mn = tMin, mx = tMax, first = false;
		mn.setMin(tMin);
		mx.setMax(tMax);
	}
}
}  // namespace

TEST(BvhRefitTest, RefitTreeAfterMovingVerticesMatchesBruteForce)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		TestMesh mesh;
		buildSoupMesh(21, mesh);
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		// Move every vertex, some well outside the original bounds (so quantization must be redone).
		Random rng(22);
		for (int p = 0; p < mesh.numParts(); ++p)
			for (int v = 0; v < mesh.part(p).numVertices; ++v)
				mesh.part(p).setVertex(v, mesh.part(p).vertex(v) * btScalar(1.3) + rng.vector(btScalar(0.5)));
		btVector3 mn, mx;
		bruteForceBox(mesh, mn, mx);
		shape.refitTree(mn, mx);
		EXPECT_TRUE(queriesMatchBruteForce(shape, mesh, btVector3(1, 1, 1), reachOf(shape), 23))
		    << "quantized " << quantized;
		EXPECT_EQ(mn, shape.getLocalAabbMin());
		EXPECT_EQ(mx, shape.getLocalAabbMax());
	}
}

TEST(BvhRefitTest, PartialRefitAfterLocalEditMatchesBruteForce)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		for (int outside = 0; outside < 2; ++outside)
		{
			// A terrain-like grid; a bump is raised inside a small region.
			TestMesh mesh;
			std::vector<btVector3> vertices;
			std::vector<int> indices;
			heightGrid(
			    24, 24, [](btScalar, btScalar) { return btScalar(0); }, vertices, indices);
			mesh.addPart(vertices, indices);
			btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
			// outside: the bump leaves the quantization box (which has margin 1), forcing a full refit.
			const btScalar height = outside ? btScalar(6) : btScalar(0.8);
			btVector3 regionMin(5, 5, 0), regionMax(9, 10, height);
			TestPart& part = mesh.part(0);
			for (int v = 0; v < part.numVertices; ++v)
			{
				const btVector3 p = part.vertex(v);
				if (p.x() >= 6 && p.x() <= 8 && p.y() >= 6 && p.y() <= 9)
					part.setVertex(v, btVector3(p.x(), p.y(), height * btScalar(0.5 + 0.1 * (v % 5))));
			}
			shape.partialRefitTree(regionMin, regionMax);
			SCOPED_TRACE(outside ? "bump leaves the quantization box" : "bump inside the quantization box");
			EXPECT_TRUE(queriesMatchBruteForce(shape, mesh, btVector3(1, 1, 1), reachOf(shape), 24, 12))
			    << "quantized " << quantized;
			// Queries aimed at the bump itself.
			Collector c;
			shape.processAllTriangles(&c, btVector3(6.5, 6.5, height * btScalar(0.45)), btVector3(7.5, 8.5, height));
			EXPECT_FALSE(c.keys.empty());
			EXPECT_GE(shape.getLocalAabbMax().z(), height * btScalar(0.9));
		}
	}
}

TEST(BvhRefitTest, UpdateBvhNodesOverWholeTreeEqualsRebuild)
{
	TestMesh mesh;
	buildSoupMesh(25, mesh);
	btBvhTriangleMeshShape shape(&mesh.array(), false);
	Random rng(26);
	for (int v = 0; v < mesh.part(1).numVertices; ++v)
		mesh.part(1).setVertex(v, mesh.part(1).vertex(v) + rng.vector(btScalar(0.7)));
	btOptimizedBvh* bvh = shape.getOptimizedBvh();
	bvh->updateBvhNodes(&mesh.array(), 0, caliber::bvhNodeCount(*bvh), 0);
	EXPECT_TRUE(queriesMatchBruteForce(shape, mesh, btVector3(1, 1, 1), btVector3(0, 0, 0), 27));
}

TEST(BvhRefitTest, SetLocalScalingRebuildsTreeForScaledTriangles)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		TestMesh mesh;
		buildSoupMesh(28, mesh);
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		const btVector3 scaling(2, -1, btScalar(0.5));
		shape.setLocalScaling(scaling);
		EXPECT_EQ(scaling, shape.getLocalScaling());
		EXPECT_EQ(scaling, mesh.array().getScaling());
		EXPECT_TRUE(queriesMatchBruteForce(shape, mesh, scaling, reachOf(shape), 29, 20)) << "quantized " << quantized;
	}
}

TEST(BvhRefitTest, SharedTreeViaSetOptimizedBvhGivesSameResults)
{
	TestMesh mesh;
	buildSoupMesh(30, mesh);
	btBvhTriangleMeshShape owner(&mesh.array(), true);
	EXPECT_TRUE(owner.getOwnsBvh());
	btBvhTriangleMeshShape user(&mesh.array(), true, false);
	EXPECT_EQ(nullptr, user.getOptimizedBvh());
	// Without a tree the shape answers by brute force, exactly.
	EXPECT_TRUE(queriesMatchBruteForce(user, mesh, btVector3(1, 1, 1), btVector3(0, 0, 0), 31));
	user.setOptimizedBvh(owner.getOptimizedBvh());
	EXPECT_FALSE(user.getOwnsBvh());
	EXPECT_TRUE(queriesMatchBruteForce(user, mesh, btVector3(1, 1, 1), reachOf(user), 31));
}

TEST(BvhRefitTest, ScaledBvhShapeQueryEqualsScaledBruteForce)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		TestMesh mesh;
		buildSoupMesh(32, mesh);
		btBvhTriangleMeshShape child(&mesh.array(), quantized != 0);
		const btVector3 scaling(btScalar(1.5), btScalar(-0.75), 2);
		btScaledBvhTriangleMeshShape scaled(&child, scaling);
		EXPECT_EQ(SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE, scaled.getShapeType());
		EXPECT_STREQ("SCALEDBVHTRIANGLEMESH", scaled.getName());
		// The child's reach is in child space; scaled space stretches it by |scaling|.
		const btVector3 reach = reachOf(child) * scaling.absolute();
		EXPECT_TRUE(queriesMatchBruteForce(scaled, mesh, scaling, reach, 33, 20)) << "quantized " << quantized;
		// AABB: the scaled brute-force box under the identity.
		btVector3 mn(0, 0, 0), mx(0, 0, 0);
		bool first = true;
		for (const TriangleKey& k : mesh.allTriangles())
		{
			btVector3 tri[3], tMin, tMax;
			mesh.triangle(k.first, k.second, scaling, tri);
			triangleBox(tri, tMin, tMax);
			if (first) mn = tMin, mx = tMax, first = false;
			mn.setMin(tMin);
			mx.setMax(tMax);
		}
		btTransform identity;
		identity.setIdentity();
		btVector3 aabbMin, aabbMax;
		scaled.getAabb(identity, aabbMin, aabbMax);
		// Only the centre/half-extent round trip of btTransformAabb rounds here.
		EXPECT_TRUE(shapes_core_test::vectorsNear(mn, aabbMin, btScalar(64) * SIMD_EPSILON * 20));
		EXPECT_TRUE(shapes_core_test::vectorsNear(mx, aabbMax, btScalar(64) * SIMD_EPSILON * 20));
	}
}

TEST(BvhRefitTest, ScaledBvhShapeWithZeroScalingFlattensMesh)
{
	TestMesh mesh;
	buildSoupMesh(34, mesh);
	btBvhTriangleMeshShape child(&mesh.array(), false);
	const btVector3 scaling(1, 0, 1);
	btScaledBvhTriangleMeshShape scaled(&child, scaling);
	// A box away from y = 0 finds nothing; one containing it behaves like the 2D brute force.
	Collector none;
	scaled.processAllTriangles(&none, btVector3(-20, 1, -20), btVector3(20, 2, 20));
	EXPECT_TRUE(none.keys.empty());
	EXPECT_TRUE(queriesMatchBruteForce(scaled, mesh, scaling, btVector3(0, 0, 0), 35));
	EXPECT_EQ(0, none.nonFinite);
}

// ---- bad input -------------------------------------------------------------------------------------

TEST(BvhRefitTest, EmptyMeshHasNoNodesAndReportsNothing)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		btTriangleMesh emptyMesh;
		btTriangleIndexVertexArray noParts;
		btStridingMeshInterface* meshes[] = {&emptyMesh, &noParts};
		for (btStridingMeshInterface* m : meshes)
		{
			btBvhTriangleMeshShape shape(m, quantized != 0);
			EXPECT_EQ(0, caliber::bvhNodeCount(*shape.getOptimizedBvh()));
			EXPECT_EQ(btVector3(0, 0, 0), shape.getLocalAabbMin());
			EXPECT_EQ(btVector3(0, 0, 0), shape.getLocalAabbMax());
			Collector c;
			shape.processAllTriangles(&c, btVector3(-1e6, -1e6, -1e6), btVector3(1e6, 1e6, 1e6));
			shape.performRaycast(&c, btVector3(-5, 0, 0), btVector3(5, 0, 0));
			shape.performConvexcast(&c, btVector3(-5, 0, 0), btVector3(5, 0, 0), btVector3(-1, -1, -1),
			                        btVector3(1, 1, 1));
			EXPECT_TRUE(c.keys.empty());
			shape.refitTree(btVector3(0, 0, 0), btVector3(0, 0, 0));
			shape.partialRefitTree(btVector3(-1, -1, -1), btVector3(1, 1, 1));
			shape.setLocalScaling(btVector3(2, 2, 2));
			EXPECT_EQ(0, caliber::bvhNodeCount(*shape.getOptimizedBvh()));
			btTransform t(btQuaternion(btVector3(0, 0, 1), 1), btVector3(1, 2, 3));
			btVector3 aabbMin, aabbMax;
			shape.getAabb(t, aabbMin, aabbMax);
			EXPECT_TRUE(shapes_core_test::vectorsNear(btVector3(1, 2, 3), aabbMin, btScalar(1e-5)));
			EXPECT_TRUE(shapes_core_test::vectorsNear(btVector3(1, 2, 3), aabbMax, btScalar(1e-5)));
		}
	}
}

TEST(BvhRefitTest, ZeroAreaTrianglesAreKeptAndReported)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		btTriangleMesh mesh;
		mesh.addTriangle(btVector3(1, 1, 1), btVector3(1, 1, 1), btVector3(1, 1, 1));  // a point
		mesh.addTriangle(btVector3(0, 0, 0), btVector3(2, 0, 0), btVector3(1, 0, 0));  // a segment
		mesh.addTriangle(btVector3(0, 3, 0), btVector3(0, 3, 0), btVector3(0, 3, 2));  // a segment
		btBvhTriangleMeshShape shape(&mesh, quantized != 0);
		EXPECT_EQ(5, caliber::bvhNodeCount(*shape.getOptimizedBvh()));
		Collector all;
		shape.processAllTriangles(&all, btVector3(-1, -1, -1), btVector3(3, 4, 3));
		EXPECT_EQ(3u, all.keys.size());
		EXPECT_EQ(0, all.nonFinite);
		// A ray along the x axis runs through the segment triangle's (flat) box; a box cast touches the point.
		Collector ray;
		shape.performRaycast(&ray, btVector3(-1, 0, 0), btVector3(3, 0, 0));
		EXPECT_EQ(1u, ray.keys.count(TriangleKey(0, 1)));
		Collector cast;
		shape.performConvexcast(&cast, btVector3(1, 1, -3), btVector3(1, 1, 3), btVector3(-0.1, -0.1, -0.1),
		                        btVector3(0.1, 0.1, 0.1));
		EXPECT_EQ(1u, cast.keys.count(TriangleKey(0, 0)));
		EXPECT_EQ(0, cast.nonFinite);
	}
}

TEST(BvhRefitTest, NanVertexTriangleIsSkippedAndExcludedFromAabb)
{
	std::vector<btVector3> vertices = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0),
	                                   btVector3(SIMD_INFINITY * 2, 0, 0), btVector3(btScalar(NAN), 5, 5)};
	std::vector<int> indices = {0, 1, 2, 0, 1, 3, 4, 1, 2};
	TestMesh mesh;
	mesh.addPart(vertices, indices);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btBvhTriangleMeshShape(&mesh.array(), true), "assertion failed");
#else
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		EXPECT_EQ(1, caliber::bvhNodeCount(*shape.getOptimizedBvh()));
		EXPECT_EQ(btVector3(0, 0, 0), shape.getLocalAabbMin());
		EXPECT_EQ(btVector3(1, 1, 0), shape.getLocalAabbMax());
		Collector c;
		shape.processAllTriangles(&c, btVector3(-1e3, -1e3, -1e3), btVector3(1e3, 1e3, 1e3));
		shape.performRaycast(&c, btVector3(0.2, 0.2, 1), btVector3(0.2, 0.2, -1));
		EXPECT_EQ(TriangleSet({TriangleKey(0, 0)}), c.keys);
		EXPECT_EQ(0, c.nonFinite);
	}
#endif
}

TEST(BvhRefitTest, OutOfRangeIndexTriangleIsSkipped)
{
	std::vector<btVector3> vertices = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0)};
	std::vector<int> indices = {0, 1, 2, 0, 1, 7, 0, -1, 2};
	TestMesh mesh;
	mesh.addPart(vertices, indices);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btBvhTriangleMeshShape(&mesh.array(), false), "assertion failed");
#else
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		Collector c;
		shape.processAllTriangles(&c, btVector3(-10, -10, -10), btVector3(10, 10, 10));
		EXPECT_EQ(TriangleSet({TriangleKey(0, 0)}), c.keys);
	}
#endif
}

TEST(BvhRefitTest, NullMeshInterfaceGivesEmptyShape)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btBvhTriangleMeshShape(nullptr, true), "assertion failed");
#else
	btBvhTriangleMeshShape shape(nullptr, true);
	EXPECT_EQ(0, caliber::bvhNodeCount(*shape.getOptimizedBvh()));
	Collector c;
	shape.processAllTriangles(&c, btVector3(-10, -10, -10), btVector3(10, 10, 10));
	shape.performRaycast(&c, btVector3(-5, 0, 0), btVector3(5, 0, 0));
	EXPECT_TRUE(c.keys.empty());
	EXPECT_EQ(btVector3(1, 1, 1), shape.getLocalScaling());
	btTransform t;
	t.setIdentity();
	btVector3 aabbMin, aabbMax;
	shape.getAabb(t, aabbMin, aabbMax);
	EXPECT_EQ(btVector3(0, 0, 0), aabbMin);
	EXPECT_EQ(btVector3(0, 0, 0), aabbMax);
#endif
}

TEST(BvhRefitTest, NonFiniteQueriesReportNothing)
{
	TestMesh mesh;
	buildSoupMesh(36, mesh);
	btBvhTriangleMeshShape shape(&mesh.array(), true);
	const btVector3 nan(btScalar(NAN), 0, 0);
	Collector c;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(shape.processAllTriangles(&c, nan, btVector3(1, 1, 1)), "assertion failed");
	EXPECT_DEATH(shape.performRaycast(&c, nan, btVector3(1, 1, 1)), "assertion failed");
#else
	shape.processAllTriangles(&c, nan, btVector3(1, 1, 1));
	shape.performRaycast(&c, nan, btVector3(1, 1, 1));
	shape.performConvexcast(&c, btVector3(0, 0, 0), btVector3(1, 1, 1), nan, btVector3(1, 1, 1));
	EXPECT_TRUE(c.keys.empty());
#endif
}
