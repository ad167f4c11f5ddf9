// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btTriangleMeshShape (brute-force base) and btConvexTriangleMeshShape against brute force over the
// mesh data: supports, AABBs, local scaling, mass properties of closed meshes, classification.

#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/TriangleMeshTestUtil.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletCollision/CollisionShapes/btTriangleMeshShape.h"

using namespace mesh_test;

namespace
{
// btTriangleMeshShape's constructor is protected, as in Bullet; this exposes the brute-force base.
class PlainTriangleMeshShape : public btTriangleMeshShape
{
public:
	explicit PlainTriangleMeshShape(btStridingMeshInterface* mesh) : btTriangleMeshShape(mesh) {}
};

// The vertex maximising dir over the mesh (first on ties), scaled.
btVector3 bruteSupport(const TestMesh& mesh, const btVector3& dir, const btVector3& scaling)
{
	btVector3 best(0, 0, 0);
	btScalar bestDot = 0;
	bool any = false;
	for (const TriangleKey& k : mesh.allTriangles())
	{
		btVector3 tri[3];
		mesh.triangle(k.first, k.second, scaling, tri);
		for (int v = 0; v < 3; ++v)
			if (!any || dir.dot(tri[v]) > bestDot)
			{
				any = true;
				bestDot = dir.dot(tri[v]);
				best = tri[v];
			}
	}
	return best;
}

// A closed box [-h, h] (12 outward-wound triangles) as a btTriangleMesh.
void addBox(btTriangleMesh& mesh, const btVector3& h, const btTransform& t)
{
	btVector3 c[8];
	for (int i = 0; i < 8; ++i)
		c[i] = t(btVector3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z()));
	const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
	for (const auto& f : faces)
	{
		mesh.addTriangle(c[f[0]], c[f[1]], c[f[2]]);
		mesh.addTriangle(c[f[0]], c[f[2]], c[f[3]]);
	}
}
}  // namespace

TEST(TriangleMeshShapeTest, BruteForceProcessAllTrianglesReturnsOverlappingTriangles)
{
	Random rng(61);
	TestMesh mesh;
	std::vector<btVector3> vertices;
	std::vector<int> indices;
	randomSoup(rng, 200, 8, 1, vertices, indices);
	mesh.addPart(vertices, indices, PHY_DOUBLE, 3, PHY_INTEGER);
	PlainTriangleMeshShape shape(&mesh.array());
	EXPECT_EQ(TRIANGLE_MESH_SHAPE_PROXYTYPE, shape.getShapeType());
	EXPECT_STREQ("TRIANGLEMESH", shape.getName());
	EXPECT_TRUE(shape.isConcave());
	for (int q = 0; q < 50; ++q)
	{
		const btVector3 centre = rng.vector(10), half(rng.uniform(0, 3), rng.uniform(0, 3), rng.uniform(0, 3));
		TriangleSet expected;
		for (const TriangleKey& k : mesh.allTriangles())
		{
			btVector3 tri[3], mn, mx;
			mesh.triangle(k.first, k.second, btVector3(1, 1, 1), tri);
			triangleBox(tri, mn, mx);
			if (boxesOverlap(mn, mx, centre - half, centre + half)) expected.insert(k);
		}
		Collector c;
		shape.processAllTriangles(&c, centre - half, centre + half);
		ASSERT_EQ(expected, c.keys) << "query " << q;
	}
	// Supports and the AABB, before and after local scaling (which lives in the mesh interface).
	for (const btVector3& scaling : {btVector3(1, 1, 1), btVector3(2, btScalar(0.5), -1)})
	{
		shape.setLocalScaling(scaling);
		EXPECT_EQ(scaling, shape.getLocalScaling());
		EXPECT_EQ(scaling, mesh.array().getScaling());
		for (int i = 0; i < 30; ++i)
		{
			const btVector3 dir = rng.unitVector();
			EXPECT_EQ(bruteSupport(mesh, dir, scaling), shape.localGetSupportingVertex(dir));
		}
		const btVector3 axes[3] = {btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)};
		for (int a = 0; a < 3; ++a)
		{
			EXPECT_EQ(bruteSupport(mesh, axes[a], scaling)[a], shape.getLocalAabbMax()[a]);
			EXPECT_EQ(bruteSupport(mesh, -axes[a], scaling)[a], shape.getLocalAabbMin()[a]);
		}
	}
	btVector3 inertia(1, 1, 1);
	shape.calculateLocalInertia(0, inertia);
	EXPECT_EQ(btVector3(0, 0, 0), inertia);
}

TEST(TriangleMeshShapeTest, ConvexTriangleMeshSupportMatchesBruteForceOverVertices)
{
	Random rng(62);
	TestMesh mesh;
	std::vector<btVector3> vertices;
	std::vector<int> indices;
	randomSoup(rng, 60, 3, 1, vertices, indices);
	mesh.addPart(vertices, indices, PHY_FLOAT, 4, PHY_SHORT);
	vertices.clear();
	indices.clear();
	randomSoup(rng, 40, 3, 1, vertices, indices);
	mesh.addPart(vertices, indices, PHY_DOUBLE, 3, PHY_INTEGER);
	btConvexTriangleMeshShape shape(&mesh.array());
	EXPECT_EQ(CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE, shape.getShapeType());
	EXPECT_STREQ("ConvexTrimesh", shape.getName());
	EXPECT_TRUE(shape.isConvex());
	for (const btVector3& scaling : {btVector3(1, 1, 1), btVector3(btScalar(1.5), -2, btScalar(0.25))})
	{
		shape.setLocalScaling(scaling);
		EXPECT_EQ(scaling, shape.getLocalScaling());
		btVector3 dirs[16], batched[16];
		for (int i = 0; i < 16; ++i) dirs[i] = rng.unitVector();
		shape.batchedUnitVectorGetSupportingVertexWithoutMargin(dirs, batched, 16);
		for (int i = 0; i < 16; ++i)
		{
			const btVector3 expected = bruteSupport(mesh, dirs[i], scaling);
			EXPECT_EQ(expected, shape.localGetSupportingVertexWithoutMargin(dirs[i])) << "direction " << i;
			EXPECT_EQ(expected, batched[i]) << "direction " << i;
			// With the margin, the support moves out by margin along the unit direction.
			const btVector3 withMargin = shape.localGetSupportingVertex(dirs[i]);
			EXPECT_TRUE(shapes_core_test::vectorsNear(expected + shape.getMargin() * dirs[i], withMargin,
			                                          shapes_core_test::kRoundingTolerance * 8));
		}
		// The cached AABB (margin included) is the box of the scaled vertices grown by the margin.
		btTransform identity;
		identity.setIdentity();
		btVector3 aabbMin, aabbMax;
		shape.getAabb(identity, aabbMin, aabbMax);
		const btScalar m = shape.getMargin();
		for (int a = 0; a < 3; ++a)
		{
			btVector3 axis(0, 0, 0);
			axis[a] = 1;
			EXPECT_NEAR(double(bruteSupport(mesh, axis, scaling)[a] + m), double(aabbMax[a]), 1e-5);
			EXPECT_NEAR(double(bruteSupport(mesh, -axis, scaling)[a] - m), double(aabbMin[a]), 1e-5);
		}
	}
}

TEST(TriangleMeshShapeTest, PrincipalAxisTransformOfClosedBoxMeshIsAnalytic)
{
	// A closed box of sides 2a x 2b x 2c: volume 8abc, centre of mass at its centre, moments per unit mass
	// (b^2 + c^2) / 3 etc. along its own axes.
	const btVector3 h(1, 2, 3);
	const btTransform pose(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7)), btVector3(4, -1, 2));
	for (int inward = 0; inward < 2; ++inward)
	{
		btTriangleMesh mesh;
		addBox(mesh, h, pose);
		if (inward)
		{
			// Reverse the winding of every triangle: same solid.
			btTriangleMesh flipped;
			IndexCollector tris;
			mesh.InternalProcessAllTriangles(&tris, btVector3(0, 0, 0), btVector3(0, 0, 0));
			for (size_t i = 0; i < tris.vertices.size(); i += 3)
				flipped.addTriangle(tris.vertices[i], tris.vertices[i + 2], tris.vertices[i + 1]);
			mesh = flipped;
		}
		btConvexTriangleMeshShape shape(&mesh);
		btTransform principal;
		btVector3 inertia;
		btScalar volume;
		shape.calculatePrincipalAxisTransform(principal, inertia, volume);
		// Sums of 12 tetrahedra of size ~6: rounding of order 1e3 ulp at most.
		const double tol = 1e3 * double(SIMD_EPSILON) * 50;
		EXPECT_NEAR(48.0, double(volume), tol);
		EXPECT_TRUE(shapes_core_test::vectorsNear(pose.getOrigin(), principal.getOrigin(), btScalar(tol)));
		// Moments are a permutation of the box's; match each principal axis to the box axis it aligns with.
		const btScalar moments[3] = {(h.y() * h.y() + h.z() * h.z()) / 3, (h.x() * h.x() + h.z() * h.z()) / 3,
		                             (h.x() * h.x() + h.y() * h.y()) / 3};
		for (int i = 0; i < 3; ++i)
		{
			const btVector3 axis = principal.getBasis().getColumn(i);
			int best = 0;
			for (int j = 1; j < 3; ++j)
				if (btFabs(axis.dot(pose.getBasis().getColumn(j))) > btFabs(axis.dot(pose.getBasis().getColumn(best))))
					best = j;
			EXPECT_NEAR(1.0, double(btFabs(axis.dot(pose.getBasis().getColumn(best)))), 1e-3);
			EXPECT_NEAR(double(moments[best]), double(inertia[i]), 1e-3 * double(moments[best]));
		}
		// calculateLocalInertia: the solid hull about its centre, diagonal in local axes; the trace is
		// rotation invariant: mass * 2 (a^2 + b^2 + c^2) / 3.
		btVector3 localInertia;
		shape.calculateLocalInertia(2, localInertia);
		const double trace = double(localInertia.x() + localInertia.y() + localInertia.z());
		EXPECT_NEAR(2.0 * 2.0 * (1 + 4 + 9) / 3.0, trace, 1e-3 * trace);
	}
}

TEST(TriangleMeshShapeTest, OpenOrEmptyMeshHasNoVolume)
{
	btTriangleMesh open;
	open.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
	btTriangleMesh empty;
	for (btTriangleMesh* mesh : {&open, &empty})
	{
		btConvexTriangleMeshShape shape(mesh);
		btTransform principal;
		btVector3 inertia;
		btScalar volume;
		shape.calculatePrincipalAxisTransform(principal, inertia, volume);
		EXPECT_EQ(btScalar(0), volume);
		EXPECT_EQ(btVector3(0, 0, 0), inertia);
		EXPECT_TRUE(shapes_core_test::isFiniteVector(principal.getOrigin()));
		btVector3 localInertia;
		shape.calculateLocalInertia(1, localInertia);
		EXPECT_TRUE(shapes_core_test::isFiniteVector(localInertia));
		const btVector3 support = shape.localGetSupportingVertexWithoutMargin(btVector3(1, 1, 1));
		EXPECT_TRUE(shapes_core_test::isFiniteVector(support));
	}
	btConvexTriangleMeshShape emptyShape(&empty);
	EXPECT_EQ(btVector3(0, 0, 0), emptyShape.localGetSupportingVertexWithoutMargin(btVector3(1, 0, 0)));
}

TEST(TriangleMeshShapeTest, NullMeshInterfaceGivesEmptyShapes)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btConvexTriangleMeshShape(nullptr), "assertion failed");
	EXPECT_DEATH(PlainTriangleMeshShape(nullptr), "assertion failed");
#else
	btConvexTriangleMeshShape convex(nullptr);
	EXPECT_EQ(btVector3(0, 0, 0), convex.localGetSupportingVertexWithoutMargin(btVector3(1, 2, 3)));
	EXPECT_EQ(btVector3(1, 1, 1), convex.getLocalScaling());
	PlainTriangleMeshShape plain(nullptr);
	Collector c;
	plain.processAllTriangles(&c, btVector3(-1, -1, -1), btVector3(1, 1, 1));
	EXPECT_TRUE(c.keys.empty());
	EXPECT_EQ(btVector3(0, 0, 0), plain.localGetSupportingVertex(btVector3(1, 0, 0)));
	plain.setLocalScaling(btVector3(2, 2, 2));
	EXPECT_EQ(btVector3(1, 1, 1), plain.getLocalScaling());
#endif
}

TEST(TriangleMeshShapeTest, ShapeNamesAndTypesFollowBullet)
{
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
	btBvhTriangleMeshShape bvh(&mesh, true);
	EXPECT_EQ(TRIANGLE_MESH_SHAPE_PROXYTYPE, bvh.getShapeType());
	EXPECT_STREQ("BVHTRIANGLEMESH", bvh.getName());
	EXPECT_TRUE(bvh.usesQuantizedAabbCompression());
	EXPECT_EQ(nullptr, bvh.getTriangleInfoMap());
	EXPECT_EQ(&mesh, bvh.getMeshInterface());
}
