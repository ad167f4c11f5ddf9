// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBodyConcaveCollisionAlgorithm: Bullet's algorithm for soft bodies against concave shapes, made by
// btSoftBodyRigidBodyCollisionConfiguration for (soft, mesh) pairs in either order.

#include <gtest/gtest.h>

#include "BulletSoftBody/btSoftBodyConcaveCollisionAlgorithm.h"
#include "SoftBodyTestUtil.h"

using caliber_test::SoftTestWorld;

TEST(SoftBodyConcaveAlgorithm, ConfigurationMakesItForSoftAndConcavePairsInEitherOrder)
{
	btSoftBodyRigidBodyCollisionConfiguration config;
	btCollisionAlgorithmCreateFunc* f =
	    config.getCollisionAlgorithmCreateFunc(SOFTBODY_SHAPE_PROXYTYPE, TRIANGLE_MESH_SHAPE_PROXYTYPE);
	EXPECT_NE(dynamic_cast<btSoftBodyConcaveCollisionAlgorithm::CreateFunc*>(f), nullptr);
	btCollisionAlgorithmCreateFunc* g =
	    config.getCollisionAlgorithmCreateFunc(TERRAIN_SHAPE_PROXYTYPE, SOFTBODY_SHAPE_PROXYTYPE);
	EXPECT_NE(dynamic_cast<btSoftBodyConcaveCollisionAlgorithm::SwappedCreateFunc*>(g), nullptr);
	// Convex shapes keep the soft-rigid algorithm.
	btCollisionAlgorithmCreateFunc* h =
	    config.getCollisionAlgorithmCreateFunc(SOFTBODY_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE);
	EXPECT_EQ(dynamic_cast<btSoftBodyConcaveCollisionAlgorithm::CreateFunc*>(h), nullptr);
}

TEST(SoftBodyConcaveAlgorithm, ClothRestsOnATriangleMeshGroundOfEitherWinding)
{
	// A cloth dropped 1 m onto a two-triangle static mesh (the pair goes through this algorithm): no node
	// ends below the mesh by more than one step's fall, g h^2 = 2.8 mm, whichever way the triangles face.
	// (A node resting on a triangle starts the step on its plane; taking the side from that start alone
	// once let the cloth fall through triangles wound downwards.)
	for (bool up : {true, false})
	{
		SoftTestWorld w;
		btTriangleMesh* mesh = new btTriangleMesh();
		const btVector3 a(-10, 0, -10), b(10, 0, -10), c(10, 0, 10), d(-10, 0, 10);
		if (up)
		{
			mesh->addTriangle(a, c, b);
			mesh->addTriangle(a, d, c);
		}
		else
		{
			mesh->addTriangle(a, b, c);
			mesh->addTriangle(a, c, d);
		}
		std::unique_ptr<btTriangleMesh> owner(mesh);
		w.addRigid(0, btVector3(0, 0, 0), w.shape<btBvhTriangleMeshShape>(mesh, true));
		btSoftBody* cloth =
		    w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-1, 1, -1), btVector3(1, 1, -1),
		                                             btVector3(-1, 1, 1), btVector3(1, 1, 1), 9, 9, 0, true));
		cloth->setTotalMass(1);
		w.step(90);
		EXPECT_GT(caliber_test::lowestNodeY(*cloth), -0.0028) << (up ? "up" : "down");
		EXPECT_LT(caliber_test::lowestNodeY(*cloth), 0.05) << (up ? "up" : "down");  // it did land on the mesh
	}
}
