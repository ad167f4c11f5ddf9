// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btMultimaterialTriangleMeshShape: per-triangle material lookups through the mesh's material tables,
// the lookups a user makes from a ray hit, and bad input.

#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btMultimaterialTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexMaterialArray.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"

namespace
{
// Four unit squares' worth of floor at y = 0 along x: triangles 2k and 2k+1 cover x in [k, k+1].
struct MaterialFloor
{
	btScalar vertices[3 * 6];
	int indices[3 * 4];
	int triangleMaterial[4];
	btMaterial materials[2];
	btTriangleIndexVertexMaterialArray mesh;

	explicit MaterialFloor(const int (&materialOfTriangle)[4])
	    : vertices{0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 2, 0, 0, 2, 0, 1},
	      indices{0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5},
	      triangleMaterial{materialOfTriangle[0], materialOfTriangle[1], materialOfTriangle[2], materialOfTriangle[3]},
	      materials{btMaterial(btScalar(0.05), btScalar(0.1)), btMaterial(btScalar(0.9), btScalar(0.8))},
	      mesh(4, indices, 3 * int(sizeof(int)), 6, vertices, 3 * int(sizeof(btScalar)), 2,
	           reinterpret_cast<unsigned char*>(materials), int(sizeof(btMaterial)), triangleMaterial, int(sizeof(int)))
	{
	}
};

// Records the part and triangle of the closest hit.
struct TriangleRayCallback : public btCollisionWorld::RayResultCallback
{
	int m_part = -1;
	int m_triangle = -1;
	btScalar addSingleResult(btCollisionWorld::LocalRayResult& rayResult, bool) override
	{
		if (rayResult.m_hitFraction > m_closestHitFraction) return m_closestHitFraction;
		m_closestHitFraction = rayResult.m_hitFraction;
		m_collisionObject = rayResult.m_collisionObject;
		if (rayResult.m_localShapeInfo)
		{
			m_part = rayResult.m_localShapeInfo->m_shapePart;
			m_triangle = rayResult.m_localShapeInfo->m_triangleIndex;
		}
		return m_closestHitFraction;
	}
};
}  // namespace

TEST(MultimaterialTriangleMeshShape, EachTriangleReportsTheMaterialItsIndexNames)
{
	const int materialOfTriangle[4] = {0, 1, 1, 0};
	MaterialFloor floor(materialOfTriangle);
	btMultimaterialTriangleMeshShape shape(&floor.mesh, true);
	EXPECT_EQ(shape.getShapeType(), int(MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE));
	EXPECT_STREQ(shape.getName(), "MULTIMATERIALTRIANGLEMESH");
	EXPECT_TRUE(shape.isConcave());
	for (int t = 0; t < 4; ++t)
	{
		const btMaterial* material = shape.getMaterialProperties(0, t);
		ASSERT_TRUE(material != 0) << "triangle " << t;
		// The pointer is into the user's table: the very record the index names.
		EXPECT_EQ(material, &floor.materials[materialOfTriangle[t]]) << "triangle " << t;
	}
	EXPECT_EQ(shape.getMaterialProperties(0, 1)->m_friction, btScalar(0.9));
	EXPECT_EQ(shape.getMaterialProperties(0, 3)->m_restitution, btScalar(0.1));
}

TEST(MultimaterialTriangleMeshShape, ShortMaterialIndicesAreRead)
{
	const int unused[4] = {0, 0, 0, 0};
	MaterialFloor floor(unused);
	const short shortIndices[4] = {1, 0, 0, 1};
	btMaterialProperties table;
	table.m_numMaterials = 2;
	table.m_materialBase = reinterpret_cast<const unsigned char*>(floor.materials);
	table.m_materialStride = int(sizeof(btMaterial));
	table.m_numTriangles = 4;
	table.m_triangleMaterialsBase = reinterpret_cast<const unsigned char*>(shortIndices);
	table.m_triangleMaterialStride = int(sizeof(short));
	// A second subpart's table over the same triangles, with 16-bit indices.
	floor.mesh.addMaterialProperties(table, PHY_SHORT);
	btMultimaterialTriangleMeshShape shape(&floor.mesh, true);
	for (int t = 0; t < 4; ++t) EXPECT_EQ(shape.getMaterialProperties(1, t), &floor.materials[shortIndices[t]]);
}

// The usual use: a ray hit names the part and triangle, and the shape gives its material.
TEST(MultimaterialTriangleMeshShape, RayHitsInTheWorldLeadToTheHitTrianglesMaterial)
{
	const int materialOfTriangle[4] = {1, 1, 0, 0};
	MaterialFloor floor(materialOfTriangle);
	btMultimaterialTriangleMeshShape shape(&floor.mesh, true);
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btCollisionWorld world(&dispatcher, &broadphase, &configuration);
	btCollisionObject object;
	object.setCollisionShape(&shape);
	world.addCollisionObject(&object);

	const btScalar xs[2] = {btScalar(0.5), btScalar(1.5)};
	for (btScalar x : xs)
	{
		TriangleRayCallback callback;
		world.rayTest(btVector3(x, 1, btScalar(0.3)), btVector3(x, -1, btScalar(0.3)), callback);
		ASSERT_TRUE(callback.hasHit());
		EXPECT_NEAR(callback.m_closestHitFraction, btScalar(0.5), btScalar(1e-5)) << "the floor is halfway";
		ASSERT_GE(callback.m_triangle, 0);
		const btMaterial* material = shape.getMaterialProperties(callback.m_part, callback.m_triangle);
		ASSERT_TRUE(material != 0);
		const btScalar expectedFriction = x < 1 ? btScalar(0.9) : btScalar(0.05);
		EXPECT_EQ(material->m_friction, expectedFriction) << "x = " << x;
	}

	// A sphere resting on the floor touches it through the convex-concave algorithm like any mesh.
	btSphereShape sphere(btScalar(0.5));
	btCollisionObject ball;
	ball.setCollisionShape(&sphere);
	btTransform pose;
	pose.setIdentity();
	pose.setOrigin(btVector3(btScalar(0.5), btScalar(0.45), btScalar(0.5)));
	ball.setWorldTransform(pose);
	world.addCollisionObject(&ball);
	world.performDiscreteCollisionDetection();
	ASSERT_EQ(dispatcher.getNumManifolds(), 1);
	const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(0);
	ASSERT_GE(manifold->getNumContacts(), 1);
	// Centre 0.45 above the floor, radius 0.5: 0.05 deep.
	EXPECT_NEAR(manifold->getContactPoint(0).getDistance(), btScalar(-0.05), btScalar(1e-4));
	world.removeCollisionObject(&ball);
	world.removeCollisionObject(&object);
}

TEST(MultimaterialTriangleMeshShape, BadLookupsGiveNull)
{
	const int badIndices[4] = {0, 1, 7, -1};
	MaterialFloor floor(badIndices);
	btMultimaterialTriangleMeshShape shape(&floor.mesh, true);
	btTriangleMesh plainMesh;
	plainMesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1));
	btMultimaterialTriangleMeshShape noTables(&plainMesh, true);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(shape.getMaterialProperties(0, 2), "material index is out of range");
	EXPECT_DEATH(shape.getMaterialProperties(0, 3), "material index is out of range");
	EXPECT_DEATH(shape.getMaterialProperties(0, 4), "triangle index out of range");
	EXPECT_DEATH(shape.getMaterialProperties(1, 0), "part id out of range");
	EXPECT_DEATH(noTables.getMaterialProperties(0, 0), "no material tables");
#else
	EXPECT_TRUE(shape.getMaterialProperties(0, 2) == 0) << "stored index past the table";
	EXPECT_TRUE(shape.getMaterialProperties(0, 3) == 0) << "negative stored index";
	EXPECT_TRUE(shape.getMaterialProperties(0, 4) == 0) << "triangle past the mesh";
	EXPECT_TRUE(shape.getMaterialProperties(0, -1) == 0) << "negative triangle";
	EXPECT_TRUE(shape.getMaterialProperties(1, 0) == 0) << "part without a table";
	EXPECT_TRUE(noTables.getMaterialProperties(0, 0) == 0) << "mesh without tables";
#endif
	EXPECT_EQ(shape.getMaterialProperties(0, 1), &floor.materials[1]) << "good entries still work";
}
