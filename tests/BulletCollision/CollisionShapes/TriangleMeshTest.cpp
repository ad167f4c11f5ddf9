// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Mesh interfaces: btTriangleIndexVertexArray and btTriangleMesh read back what was stored in every
// vertex and index format, btTriangleMesh welds within its threshold, scaling and AABBs, and bad input.

#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/TriangleMeshTestUtil.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexMaterialArray.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"

using namespace mesh_test;

TEST(TriangleMeshTest, AllIndexAndVertexFormatsReadBackTheStoredTriangles)
{
	for (int use32 = 0; use32 < 2; ++use32)
		for (int use4 = 0; use4 < 2; ++use4)
		{
			SCOPED_TRACE(std::string(use32 ? "32-bit" : "16-bit") + (use4 ? ", 4 components" : ", 3 components"));
			btTriangleMesh mesh(use32 != 0, use4 != 0);
			EXPECT_EQ(use32 != 0, mesh.getUse32bitIndices());
			EXPECT_EQ(use4 != 0, mesh.getUse4componentVertices());
			Random rng(5);
			std::vector<btVector3> expected;
			for (int t = 0; t < 50; ++t)
			{
				const btVector3 a = rng.vector(5), b = rng.vector(5), c = rng.vector(5);
				mesh.addTriangle(a, b, c);
				expected.insert(expected.end(), {a, b, c});
			}
			EXPECT_EQ(50, mesh.getNumTriangles());
			IndexCollector collected;
			mesh.InternalProcessAllTriangles(&collected, btVector3(0, 0, 0), btVector3(0, 0, 0));
			ASSERT_EQ(50u, collected.order.size());
			for (int t = 0; t < 50; ++t)
			{
				EXPECT_EQ(TriangleKey(0, t), collected.order[size_t(t)]);
				for (int k = 0; k < 3; ++k)
					EXPECT_EQ(expected[size_t(3 * t + k)], collected.vertices[size_t(3 * t + k)]);
			}
			const unsigned char *vertexBase, *indexBase;
			int numVerts, vertexStride, indexStride, numFaces;
			PHY_ScalarType vertexType, indexType;
			mesh.getLockedReadOnlyVertexIndexBase(&vertexBase, numVerts, vertexType, vertexStride, &indexBase,
			                                      indexStride, numFaces, indexType, 0);
			EXPECT_EQ(150, numVerts);
			EXPECT_EQ(50, numFaces);
			EXPECT_EQ(use32 ? PHY_INTEGER : PHY_SHORT, indexType);
			EXPECT_EQ(sizeof(btScalar) == 8 ? PHY_DOUBLE : PHY_FLOAT, vertexType);
			EXPECT_EQ(int(use4 ? 4 : 3) * int(sizeof(btScalar)), vertexStride);
			EXPECT_EQ(use32 ? 12 : 6, indexStride);
			mesh.unLockReadOnlyVertexBase(0);
		}
}

TEST(TriangleMeshTest, SubpartsOfMixedFormatsReportTheirPartIds)
{
	Random rng(9);
	TestMesh mesh;
	const PHY_ScalarType vertexTypes[] = {PHY_FLOAT, PHY_DOUBLE, PHY_DOUBLE, PHY_FLOAT};
	const PHY_ScalarType indexTypes[] = {PHY_INTEGER, PHY_SHORT, PHY_UCHAR, PHY_SHORT};
	const int components[] = {3, 4, 3, 4};
	for (int p = 0; p < 4; ++p)
	{
		std::vector<btVector3> vertices;
		std::vector<int> indices;
		randomSoup(rng, 20 + p, 5, 1, vertices, indices);
		// Reuse vertices across triangles so indices are not just 0, 1, 2, ...
		for (size_t i = 0; i < indices.size(); i += 4) indices[i] = int(i / 4) % int(vertices.size());
		mesh.addPart(vertices, indices, vertexTypes[p], components[p], indexTypes[p]);
	}
	EXPECT_EQ(4, mesh.array().getNumSubParts());
	const btVector3 scaling(2, -3, btScalar(0.5));
	mesh.array().setScaling(scaling);
	IndexCollector collected;
	mesh.array().InternalProcessAllTriangles(&collected, btVector3(0, 0, 0), btVector3(0, 0, 0));
	const std::vector<TriangleKey> all = mesh.allTriangles();
	ASSERT_EQ(all, collected.order);
	for (size_t i = 0; i < all.size(); ++i)
	{
		btVector3 tri[3];
		mesh.triangle(all[i].first, all[i].second, scaling, tri);
		for (int k = 0; k < 3; ++k) EXPECT_EQ(tri[k], collected.vertices[3 * i + size_t(k)]) << "triangle " << i;
	}
	// The brute-force AABB is the box of the scaled vertices.
	btVector3 mn, mx, aabbMin, aabbMax;
	for (size_t i = 0; i < collected.vertices.size(); ++i)
	{
		if (i == 0) mn = mx = collected.vertices[0];
		mn.setMin(collected.vertices[i]);
		mx.setMax(collected.vertices[i]);
	}
	mesh.array().calculateAabbBruteForce(aabbMin, aabbMax);
	EXPECT_EQ(mn, aabbMin);
	EXPECT_EQ(mx, aabbMax);
}

TEST(TriangleMeshTest, WeldingMergesVerticesWithinThresholdOnly)
{
	// Reference: the lowest-index stored vertex within the threshold, found by scanning them all.
	for (int use4 = 0; use4 < 2; ++use4)
	{
		btTriangleMesh mesh(true, use4 != 0);
		mesh.m_weldingThreshold = btScalar(0.05);
		std::vector<btVector3> stored;
		Random rng(12);
		int merged = 0;
		for (int t = 0; t < 400; ++t)
		{
			btVector3 v[3];
			int expected[3];
			for (int k = 0; k < 3; ++k)
			{
				// Points on a coarse lattice plus jitter: many pairs closer than the threshold, many just beyond.
				v[k] =
				    btVector3(btScalar(int(rng.uniform(0, 6))), btScalar(int(rng.uniform(0, 6))), 0) * btScalar(0.5) +
				    rng.vector(btScalar(0.04));
			}
			for (int k = 0; k < 3; ++k)
			{
				expected[k] = -1;
				for (size_t i = 0; i < stored.size(); ++i)
					if ((stored[i] - v[k]).length() <= mesh.m_weldingThreshold)
					{
						expected[k] = int(i);
						break;
					}
				if (expected[k] < 0)
				{
					stored.push_back(v[k]);
					expected[k] = int(stored.size()) - 1;
				}
				else
					++merged;
			}
			mesh.addTriangle(v[0], v[1], v[2], true);
			const unsigned char *vertexBase, *indexBase;
			int numVerts, vertexStride, indexStride, numFaces;
			PHY_ScalarType vertexType, indexType;
			mesh.getLockedReadOnlyVertexIndexBase(&vertexBase, numVerts, vertexType, vertexStride, &indexBase,
			                                      indexStride, numFaces, indexType, 0);
			ASSERT_EQ(int(stored.size()), numVerts) << "triangle " << t;
			const unsigned int* indices = reinterpret_cast<const unsigned int*>(indexBase) + 3 * t;
			for (int k = 0; k < 3; ++k)
				ASSERT_EQ(unsigned(expected[k]), indices[k]) << "triangle " << t << " vertex " << k;
			mesh.unLockReadOnlyVertexBase(0);
		}
		EXPECT_GT(merged, 500);  // the data must exercise welding
	}
}

TEST(TriangleMeshTest, ZeroThresholdWeldsExactDuplicatesOnly)
{
	btTriangleMesh mesh(false, false);
	const btVector3 a(1, 2, 3), b(4, 5, 6), c(7, 8, 9);
	const btVector3 nearA = a + btVector3(btScalar(1e-3), 0, 0);
	mesh.addTriangle(a, b, c, true);
	mesh.addTriangle(c, b, a, true);
	EXPECT_EQ(3, mesh.getIndexedMeshArray()[0].m_numVertices);
	mesh.addTriangle(nearA, b, c, true);
	EXPECT_EQ(4, mesh.getIndexedMeshArray()[0].m_numVertices);
	mesh.addTriangle(a, b, c, false);  // no welding asked: three new vertices
	EXPECT_EQ(7, mesh.getIndexedMeshArray()[0].m_numVertices);
	EXPECT_EQ(4, mesh.getNumTriangles());
	EXPECT_EQ(1, mesh.findOrAddVertex(b, true));
}

TEST(TriangleMeshTest, AddIndexAndPreallocateBuildTrianglesByHand)
{
	btTriangleMesh mesh;
	mesh.preallocateVertices(4);
	mesh.preallocateIndices(6);
	const btVector3 quad[4] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(1, 1, 0), btVector3(0, 1, 0)};
	for (const btVector3& v : quad) mesh.findOrAddVertex(v, false);
	mesh.addTriangleIndices(0, 1, 2);
	mesh.addTriangleIndices(0, 2, 3);
	EXPECT_EQ(2, mesh.getNumTriangles());
	IndexCollector collected;
	mesh.InternalProcessAllTriangles(&collected, btVector3(0, 0, 0), btVector3(0, 0, 0));
	ASSERT_EQ(6u, collected.vertices.size());
	EXPECT_EQ(quad[3], collected.vertices[5]);
}

TEST(TriangleMeshTest, PremadeAabbRoundTripsAndEmptyMeshHasZeroAabb)
{
	btTriangleIndexVertexArray array;
	EXPECT_FALSE(array.hasPremadeAabb());
	btVector3 aabbMin(5, 5, 5), aabbMax(5, 5, 5);
	array.calculateAabbBruteForce(aabbMin, aabbMax);
	EXPECT_EQ(btVector3(0, 0, 0), aabbMin);
	EXPECT_EQ(btVector3(0, 0, 0), aabbMax);
	array.setPremadeAabb(btVector3(-1, -2, -3), btVector3(1, 2, 3));
	EXPECT_TRUE(array.hasPremadeAabb());
	array.getPremadeAabb(&aabbMin, &aabbMax);
	EXPECT_EQ(btVector3(-1, -2, -3), aabbMin);
	EXPECT_EQ(btVector3(1, 2, 3), aabbMax);
	IndexCollector none;
	array.InternalProcessAllTriangles(&none, aabbMin, aabbMax);
	EXPECT_TRUE(none.order.empty());
}

TEST(TriangleMeshTest, ConstructorOverUserArraysReadsIntegerIndices)
{
	int indices[6] = {0, 1, 2, 2, 1, 3};
	btScalar vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
	btTriangleIndexVertexArray array(2, indices, 3 * int(sizeof(int)), 4, vertices, 3 * int(sizeof(btScalar)));
	IndexCollector collected;
	array.InternalProcessAllTriangles(&collected, btVector3(0, 0, 0), btVector3(0, 0, 0));
	ASSERT_EQ(6u, collected.vertices.size());
	EXPECT_EQ(btVector3(1, 1, 1), collected.vertices[5]);
	EXPECT_EQ(TriangleKey(0, 1), collected.order[1]);
}

TEST(TriangleMeshTest, MaterialArrayReturnsPerTriangleMaterials)
{
	int indices[6] = {0, 1, 2, 2, 1, 3};
	btScalar vertices[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
	struct Material
	{
		float friction;
		float restitution;
	};
	Material materials[2] = {{0.5f, 0.1f}, {0.9f, 0.7f}};
	int triangleMaterials[2] = {1, 0};
	btTriangleIndexVertexMaterialArray array(2, indices, 3 * int(sizeof(int)), 4, vertices, 3 * int(sizeof(btScalar)),
	                                         2, reinterpret_cast<unsigned char*>(materials), int(sizeof(Material)),
	                                         triangleMaterials, int(sizeof(int)));
	EXPECT_EQ(1, array.getNumMaterialSubParts());
	const unsigned char *materialBase, *triangleBase;
	int numMaterials, materialStride, numTriangles, triangleStride;
	PHY_ScalarType materialType, triangleType;
	array.getLockedReadOnlyMaterialBase(&materialBase, numMaterials, materialType, materialStride, &triangleBase,
	                                    numTriangles, triangleStride, triangleType, 0);
	EXPECT_EQ(2, numMaterials);
	EXPECT_EQ(2, numTriangles);
	EXPECT_EQ(PHY_INTEGER, triangleType);
	const int materialOfTriangle0 = *reinterpret_cast<const int*>(triangleBase);
	const Material* m = reinterpret_cast<const Material*>(materialBase + materialOfTriangle0 * materialStride);
	EXPECT_EQ(0.9f, m->friction);
	// The mesh part itself is an ordinary subpart.
	IndexCollector collected;
	array.InternalProcessAllTriangles(&collected, btVector3(0, 0, 0), btVector3(0, 0, 0));
	EXPECT_EQ(2u, collected.order.size());
}

// ---- bad input -------------------------------------------------------------------------------------

TEST(TriangleMeshTest, SixteenBitOverflowIsRejected)
{
	btTriangleMesh mesh(false, true);
	mesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(mesh.addTriangleIndices(0, 1, 70000), "assertion failed");
	EXPECT_DEATH(mesh.addIndex(-1), "assertion failed");
#else
	mesh.addTriangleIndices(0, 1, 70000);
	EXPECT_EQ(1, mesh.getNumTriangles());
#endif
}

TEST(TriangleMeshTest, BadSubpartAndUnsupportedTypesReadAsEmpty)
{
	btTriangleIndexVertexArray array;
	btIndexedMesh bad;
	float vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
	unsigned int indices[3] = {0, 1, 2};
	bad.m_numTriangles = 1;
	bad.m_numVertices = 3;
	bad.m_vertexBase = reinterpret_cast<const unsigned char*>(vertices);
	bad.m_vertexStride = 4;  // too small for three floats
	bad.m_vertexType = PHY_FLOAT;
	bad.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices);
	bad.m_triangleIndexStride = 12;
	array.addIndexedMesh(bad, PHY_INTEGER);
	IndexCollector collected;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(array.InternalProcessAllTriangles(&collected, btVector3(0, 0, 0), btVector3(0, 0, 0)),
	             "assertion failed");
	const unsigned char *vb, *ib;
	int nv, vs, is, nf;
	PHY_ScalarType vt, it;
	EXPECT_DEATH(array.getLockedReadOnlyVertexIndexBase(&vb, nv, vt, vs, &ib, is, nf, it, 3), "assertion failed");
#else
	array.InternalProcessAllTriangles(&collected, btVector3(0, 0, 0), btVector3(0, 0, 0));
	EXPECT_TRUE(collected.order.empty());
	const unsigned char *vb, *ib;
	int nv, vs, is, nf;
	PHY_ScalarType vt, it;
	array.getLockedReadOnlyVertexIndexBase(&vb, nv, vt, vs, &ib, is, nf, it, 3);
	EXPECT_EQ(0, nf);
	EXPECT_EQ(nullptr, vb);
#endif
}

TEST(TriangleMeshTest, NanVertexIsExcludedFromBruteForceAabb)
{
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0));
	mesh.addTriangle(btVector3(0, 0, 0), btVector3(btScalar(NAN), 0, 0), btVector3(0, 9, 0));
	btVector3 aabbMin, aabbMax;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(mesh.calculateAabbBruteForce(aabbMin, aabbMax), "assertion failed");
#else
	mesh.calculateAabbBruteForce(aabbMin, aabbMax);
	EXPECT_EQ(btVector3(0, 0, 0), aabbMin);
	EXPECT_EQ(btVector3(1, 1, 0), aabbMax);
#endif
	// A NaN scaling is refused.
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(mesh.setScaling(btVector3(btScalar(NAN), 1, 1)), "assertion failed");
#else
	mesh.setScaling(btVector3(btScalar(NAN), 1, 1));
	EXPECT_EQ(btVector3(1, 1, 1), mesh.getScaling());
#endif
}
