// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btTriangleBuffer keeps exactly the triangles a mesh query hands it (vertices, part and index), and
// btCollisionMargin.h's CONVEX_DISTANCE_MARGIN is the margin convex shapes get by default.

#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/btCollisionMargin.h"
#include "BulletCollision/CollisionShapes/btTriangleBuffer.h"
#include "btBulletCollisionCommon.h"

TEST(TriangleBuffer, KeepsTheTrianglesAMeshQueryReturns)
{
	btTriangleMesh mesh;
	// A row of 4 unit squares along x (8 triangles), in the plane y = 0.
	for (int i = 0; i < 4; ++i)
	{
		const btScalar x = btScalar(i);
		mesh.addTriangle(btVector3(x, 0, 0), btVector3(x, 0, 1), btVector3(x + 1, 0, 1));
		mesh.addTriangle(btVector3(x, 0, 0), btVector3(x + 1, 0, 1), btVector3(x + 1, 0, 0));
	}
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleBuffer buffer;
	// The box over the first two squares (x in [0.1, 1.9]) overlaps exactly their 4 triangles.
	shape.processAllTriangles(&buffer, btVector3(btScalar(0.1), -1, btScalar(0.1)), btVector3(btScalar(1.9), 1, btScalar(0.9)));
	ASSERT_EQ(buffer.getNumTriangles(), 4);
	for (int i = 0; i < buffer.getNumTriangles(); ++i)
	{
		const btTriangle& t = buffer.getTriangle(i);
		EXPECT_EQ(t.m_partId, 0);
		EXPECT_LT(t.m_triangleIndex, 4) << "only the first two squares' triangles";
		EXPECT_LE(btMax(t.m_vertex0.x(), btMax(t.m_vertex1.x(), t.m_vertex2.x())), 2);
		EXPECT_EQ(t.m_vertex0.y(), 0);
	}
	buffer.clearBuffer();
	EXPECT_EQ(buffer.getNumTriangles(), 0);
}

TEST(CollisionMargin, ConvexShapesGetTheDefaultMargin)
{
	btSphereShape sphere(1);  // a sphere's margin is its radius; a cylinder's is the default
	btCylinderShape cylinder(btVector3(1, 1, 1));
	EXPECT_FLOAT_EQ(CONVEX_DISTANCE_MARGIN, btScalar(0.04));
	EXPECT_FLOAT_EQ(cylinder.getMargin(), CONVEX_DISTANCE_MARGIN);
}
