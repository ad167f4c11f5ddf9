// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Every shape kind the format describes: written with serializeSingleShape, read back with
// btBulletWorldImporter, and compared field by field. The format stores shape dimensions as float:
// float builds compare exactly, double builds within float rounding (kShapeTolerance).
#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletWorldImporter/btBulletWorldImporter.h"
#include "Serialize/SerializeTestUtil.h"

using caliber_test::bytesOf;

namespace
{
#ifdef BT_USE_DOUBLE_PRECISION
// One float rounding of values of order 1..10.
const btScalar kShapeTolerance = 1e-5;
#else
const btScalar kShapeTolerance = 0;
#endif

void expectVectorNear(const btVector3& a, const btVector3& b, const char* what)
{
	for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], kShapeTolerance) << what << " axis " << i;
}

// Writes shape (named "shape") as a file of its own and reads it back.
class ShapeRoundTrip
{
public:
	explicit ShapeRoundTrip(const btCollisionShape* shape)
	{
		btDefaultSerializer s;
		s.registerNameForPointer(shape, "shape");
		s.startSerialization();
		shape->serializeSingleShape(&s);
		s.finishSerialization();
		m_file = bytesOf(s);
		m_ok = m_importer.loadFileFromMemory(m_file.data(), int(m_file.size()));
	}
	~ShapeRoundTrip() { m_importer.deleteAllData(); }
	template <class T>
	T* get()
	{
		EXPECT_TRUE(m_ok);
		btCollisionShape* s = m_importer.getCollisionShapeByName("shape");
		EXPECT_NE(s, nullptr) << "the shape or its name was lost";
		return static_cast<T*>(s);
	}
	btBulletWorldImporter& importer() { return m_importer; }

private:
	std::vector<char> m_file;
	btBulletWorldImporter m_importer{0};
	bool m_ok = false;
};
}  // namespace

TEST(ShapeRoundTrip, BoxKeepsHalfExtentsMarginAndScaling)
{
	btBoxShape box(btVector3(1, 2, 3));
	box.setMargin(0.02f);
	box.setLocalScaling(btVector3(1, 2, 0.5));
	ShapeRoundTrip rt(&box);
	btBoxShape* read = rt.get<btBoxShape>();
	ASSERT_TRUE(read);
	EXPECT_EQ(read->getShapeType(), BOX_SHAPE_PROXYTYPE);
	expectVectorNear(read->getHalfExtentsWithoutMargin(), box.getHalfExtentsWithoutMargin(), "half extents");
	expectVectorNear(read->getLocalScaling(), box.getLocalScaling(), "scaling");
	EXPECT_NEAR(read->getMargin(), box.getMargin(), kShapeTolerance);
}

TEST(ShapeRoundTrip, SphereKeepsRadiusAndScaling)
{
	btSphereShape sphere(0.75);
	sphere.setLocalScaling(btVector3(2, 2, 2));
	ShapeRoundTrip rt(&sphere);
	btSphereShape* read = rt.get<btSphereShape>();
	ASSERT_TRUE(read);
	EXPECT_NEAR(read->getRadius(), sphere.getRadius(), kShapeTolerance);
	expectVectorNear(read->getLocalScaling(), sphere.getLocalScaling(), "scaling");
}

TEST(ShapeRoundTrip, CapsulesOfEveryAxisKeepRadiusHalfHeightAndAxis)
{
	btCapsuleShapeX x(0.3, 1.5);
	btCapsuleShape y(0.4, 2.0);
	btCapsuleShapeZ z(0.5, 2.5);
	y.setLocalScaling(btVector3(1, 2, 1));
	for (btCapsuleShape* capsule : {static_cast<btCapsuleShape*>(&x), &y, static_cast<btCapsuleShape*>(&z)})
	{
		ShapeRoundTrip rt(capsule);
		btCapsuleShape* read = rt.get<btCapsuleShape>();
		ASSERT_TRUE(read);
		EXPECT_EQ(read->getUpAxis(), capsule->getUpAxis());
		EXPECT_NEAR(read->getRadius(), capsule->getRadius(), kShapeTolerance);
		EXPECT_NEAR(read->getHalfHeight(), capsule->getHalfHeight(), kShapeTolerance);
		expectVectorNear(read->getLocalScaling(), capsule->getLocalScaling(), "scaling");
	}
}

TEST(ShapeRoundTrip, CylindersOfEveryAxisKeepExtentsMarginAndAxis)
{
	btCylinderShapeX x(btVector3(1, 0.5, 0.5));
	btCylinderShape y(btVector3(0.6, 1.2, 0.6));
	btCylinderShapeZ z(btVector3(0.7, 0.7, 1.4));
	z.setMargin(0.01f);
	x.setLocalScaling(btVector3(2, 1, 1));
	for (btCylinderShape* cylinder : {static_cast<btCylinderShape*>(&x), &y, static_cast<btCylinderShape*>(&z)})
	{
		ShapeRoundTrip rt(cylinder);
		btCylinderShape* read = rt.get<btCylinderShape>();
		ASSERT_TRUE(read);
		EXPECT_EQ(read->getUpAxis(), cylinder->getUpAxis());
		expectVectorNear(read->getHalfExtentsWithoutMargin(), cylinder->getHalfExtentsWithoutMargin(), "half extents");
		EXPECT_NEAR(read->getMargin(), cylinder->getMargin(), kShapeTolerance);
		expectVectorNear(read->getLocalScaling(), cylinder->getLocalScaling(), "scaling");
	}
}

TEST(ShapeRoundTrip, ConesOfEveryAxisKeepRadiusHeightAndAxis)
{
	btConeShapeX x(0.5, 2);
	btConeShape y(0.6, 1.5);
	btConeShapeZ z(0.7, 1.0);
	y.setLocalScaling(btVector3(2, 3, 2));
	for (btConeShape* cone : {static_cast<btConeShape*>(&x), &y, static_cast<btConeShape*>(&z)})
	{
		ShapeRoundTrip rt(cone);
		btConeShape* read = rt.get<btConeShape>();
		ASSERT_TRUE(read);
		EXPECT_EQ(read->getConeUpIndex(), cone->getConeUpIndex());
		EXPECT_NEAR(read->getRadius(), cone->getRadius(), kShapeTolerance);
		EXPECT_NEAR(read->getHeight(), cone->getHeight(), kShapeTolerance);
		EXPECT_NEAR(read->getMargin(), cone->getMargin(), kShapeTolerance);
		expectVectorNear(read->getLocalScaling(), cone->getLocalScaling(), "scaling");
	}
}

TEST(ShapeRoundTrip, MultiSphereKeepsEverySphere)
{
	const btVector3 positions[3] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 2, -1)};
	const btScalar radii[3] = {0.5, 0.25, 0.75};
	btMultiSphereShape shape(positions, radii, 3);
	ShapeRoundTrip rt(&shape);
	btMultiSphereShape* read = rt.get<btMultiSphereShape>();
	ASSERT_TRUE(read);
	ASSERT_EQ(read->getSphereCount(), 3);
	for (int i = 0; i < 3; ++i)
	{
		expectVectorNear(read->getSpherePosition(i), positions[i], "sphere position");
		EXPECT_NEAR(read->getSphereRadius(i), radii[i], kShapeTolerance);
	}
}

TEST(ShapeRoundTrip, ConvexHullKeepsItsPointsExactly)
{
	btConvexHullShape hull;
	const btVector3 points[5] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1),
	                             btVector3(0.1f, 0.2f, 0.3f)};
	for (const btVector3& p : points) hull.addPoint(p);
	hull.setMargin(0.03f);
	hull.setLocalScaling(btVector3(1, 1, 2));
	ShapeRoundTrip rt(&hull);
	btConvexHullShape* read = rt.get<btConvexHullShape>();
	ASSERT_TRUE(read);
	ASSERT_EQ(read->getNumPoints(), 5);
	// Points are stored in the build's own precision: exact in every build.
	for (int i = 0; i < 5; ++i)
		for (int k = 0; k < 3; ++k) EXPECT_EQ(read->getUnscaledPoints()[i][k], points[i][k]);
	EXPECT_NEAR(read->getMargin(), hull.getMargin(), kShapeTolerance);
	expectVectorNear(read->getLocalScaling(), hull.getLocalScaling(), "scaling");
}

TEST(ShapeRoundTrip, StaticPlaneKeepsNormalAndConstant)
{
	btStaticPlaneShape plane(btVector3(0, 1, 0), -2.5);
	ShapeRoundTrip rt(&plane);
	btStaticPlaneShape* read = rt.get<btStaticPlaneShape>();
	ASSERT_TRUE(read);
	expectVectorNear(read->getPlaneNormal(), plane.getPlaneNormal(), "normal");
	EXPECT_NEAR(read->getPlaneConstant(), plane.getPlaneConstant(), kShapeTolerance);
}

TEST(ShapeRoundTrip, NestedCompoundKeepsChildrenTransformsAndSharedChildren)
{
	btBoxShape box(btVector3(0.5, 0.5, 0.5));
	btSphereShape sphere(0.3);
	btCompoundShape inner;
	inner.addChildShape(btTransform(btQuaternion(btVector3(0, 0, 1), 0.5), btVector3(0, 1, 0)), &sphere);
	btCompoundShape outer;
	outer.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(1, 0, 0)), &box);
	outer.addChildShape(btTransform(btQuaternion(btVector3(1, 0, 0), 0.25), btVector3(-1, 0, 0)), &box);
	outer.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0, 0, 2)), &inner);
	ShapeRoundTrip rt(&outer);
	btCompoundShape* read = rt.get<btCompoundShape>();
	ASSERT_TRUE(read);
	ASSERT_EQ(read->getNumChildShapes(), 3);
	for (int i = 0; i < 3; ++i)
	{
		expectVectorNear(read->getChildTransform(i).getOrigin(), outer.getChildTransform(i).getOrigin(), "origin");
		for (int r = 0; r < 3; ++r)
			expectVectorNear(read->getChildTransform(i).getBasis()[r], outer.getChildTransform(i).getBasis()[r],
			                 "basis");
		EXPECT_EQ(read->getChildShape(i)->getShapeType(), outer.getChildShape(i)->getShapeType());
	}
	// The box used twice is one shape after reading, as before writing.
	EXPECT_EQ(read->getChildShape(0), read->getChildShape(1));
	btCompoundShape* readInner = static_cast<btCompoundShape*>(read->getChildShape(2));
	ASSERT_EQ(readInner->getNumChildShapes(), 1);
	EXPECT_NEAR(static_cast<btSphereShape*>(readInner->getChildShape(0))->getRadius(), sphere.getRadius(),
	            kShapeTolerance);
	EXPECT_EQ(rt.importer().getNumCollisionShapes(), 4);
}

namespace
{
// A 3x3-vertex grid of two-triangle cells, with the index width given.
struct Grid
{
	btVector3 vertices[9];
	int indices32[24];
	short indices16[24];
	Grid()
	{
		for (int z = 0; z < 3; ++z)
			for (int x = 0; x < 3; ++x)
				vertices[z * 3 + x] = btVector3(btScalar(x), btScalar(0.1 * x * z), btScalar(z));
		int t = 0;
		for (int z = 0; z < 2; ++z)
			for (int x = 0; x < 2; ++x)
			{
				const int a = z * 3 + x, b = a + 1, c = a + 3, d = a + 4;
				const int tri[6] = {a, c, b, b, c, d};
				for (int k = 0; k < 6; ++k) indices32[t * 6 + k] = tri[k];
				++t;
			}
		for (int i = 0; i < 24; ++i) indices16[i] = short(indices32[i]);
	}
};

// Every triangle of a mesh interface, as world points.
std::vector<btVector3> trianglesOf(const btStridingMeshInterface& mesh)
{
	struct Collect : btInternalTriangleIndexCallback
	{
		std::vector<btVector3> points;
		void internalProcessTriangleIndex(btVector3* triangle, int, int) override
		{
			for (int k = 0; k < 3; ++k) points.push_back(triangle[k]);
		}
	} collect;
	const btScalar big = 1e6;
	mesh.InternalProcessAllTriangles(&collect, btVector3(-big, -big, -big), btVector3(big, big, big));
	return collect.points;
}
}  // namespace

TEST(ShapeRoundTrip, TriangleMeshesWith32And16BitIndicesKeepEveryTriangle)
{
	Grid grid;
	for (int width : {32, 16})
	{
		btTriangleIndexVertexArray mesh;
		btIndexedMesh part;
		part.m_numTriangles = 8;
		part.m_numVertices = 9;
		part.m_vertexBase = reinterpret_cast<const unsigned char*>(&grid.vertices[0]);
		part.m_vertexStride = sizeof(btVector3);
#ifdef BT_USE_DOUBLE_PRECISION
		part.m_vertexType = PHY_DOUBLE;
#else
		part.m_vertexType = PHY_FLOAT;
#endif
		if (width == 32)
		{
			part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(grid.indices32);
			part.m_triangleIndexStride = 3 * sizeof(int);
			mesh.addIndexedMesh(part, PHY_INTEGER);
		}
		else
		{
			part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(grid.indices16);
			part.m_triangleIndexStride = 3 * sizeof(short);
			mesh.addIndexedMesh(part, PHY_SHORT);
		}
		btBvhTriangleMeshShape shape(&mesh, true);
		ShapeRoundTrip rt(&shape);
		btBvhTriangleMeshShape* read = rt.get<btBvhTriangleMeshShape>();
		ASSERT_TRUE(read);
		EXPECT_NEAR(read->getMargin(), shape.getMargin(), kShapeTolerance);
		EXPECT_TRUE(read->getOptimizedBvh() != nullptr) << "the BVH is rebuilt on reading";
		const std::vector<btVector3> before = trianglesOf(mesh), after = trianglesOf(*read->getMeshInterface());
		ASSERT_EQ(before.size(), after.size());
		for (size_t i = 0; i < before.size(); ++i) expectVectorNear(after[i], before[i], "vertex");
	}
}

TEST(ShapeRoundTrip, ScaledTriangleMeshKeepsScalingAndMesh)
{
	Grid grid;
	btTriangleIndexVertexArray mesh(8, grid.indices32, 3 * sizeof(int), 9, &grid.vertices[0][0], sizeof(btVector3));
	btBvhTriangleMeshShape child(&mesh, true);
	btScaledBvhTriangleMeshShape scaled(&child, btVector3(2, 1, 0.5));
	ShapeRoundTrip rt(&scaled);
	btCollisionShape* read = rt.importer().getCollisionShapeByIndex(rt.importer().getNumCollisionShapes() - 1);
	ASSERT_TRUE(read);
	ASSERT_EQ(read->getShapeType(), SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE);
	btScaledBvhTriangleMeshShape* readScaled = static_cast<btScaledBvhTriangleMeshShape*>(read);
	expectVectorNear(readScaled->getLocalScaling(), scaled.getLocalScaling(), "scaling");
	EXPECT_EQ(trianglesOf(*readScaled->getChildShape()->getMeshInterface()).size(), trianglesOf(mesh).size());
}
