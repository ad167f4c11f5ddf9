// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include "../NarrowPhaseCollision/NarrowPhaseTestUtil.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "TestDispatcher.h"

using caliber_dispatch_test::PairFixture;
using caliber_dispatch_test::TestDispatcher;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// A brute-force concave shape for these tests (independent of the BVH meshes): a list of triangles,
// each reported when its AABB overlaps the query box. Counts the triangles it reports.
class TriangleSoupShape : public btConcaveShape
{
public:
	TriangleSoupShape() : m_scaling(1, 1, 1), m_reported(0) { m_shapeType = TRIANGLE_MESH_SHAPE_PROXYTYPE; }

	void addTriangle(const btVector3& a, const btVector3& b, const btVector3& c)
	{
		m_vertices.push_back(a);
		m_vertices.push_back(b);
		m_vertices.push_back(c);
	}

	void processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
	                         const btVector3& aabbMax) const override
	{
		for (int t = 0; t < m_vertices.size() / 3; ++t)
		{
			btVector3 triangle[3] = {m_vertices[3 * t], m_vertices[3 * t + 1], m_vertices[3 * t + 2]};
			btVector3 lo = triangle[0], hi = triangle[0];
			for (int i = 1; i < 3; ++i)
			{
				lo.setMin(triangle[i]);
				hi.setMax(triangle[i]);
			}
			bool overlaps = true;
			for (int i = 0; i < 3; ++i) overlaps = overlaps && lo[i] <= aabbMax[i] && hi[i] >= aabbMin[i];
			if (!overlaps) continue;
			++m_reported;
			callback->processTriangle(triangle, 0, t);
		}
	}
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override
	{
		aabbMin.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
		aabbMax = -aabbMin;
		for (int i = 0; i < m_vertices.size(); ++i)
		{
			aabbMin.setMin(t(m_vertices[i]));
			aabbMax.setMax(t(m_vertices[i]));
		}
	}
	void setLocalScaling(const btVector3& scaling) override { m_scaling = scaling; }
	const btVector3& getLocalScaling() const override { return m_scaling; }
	void calculateLocalInertia(btScalar, btVector3& inertia) const override { inertia.setValue(0, 0, 0); }
	const char* getName() const override { return "TriangleSoup"; }

	btAlignedObjectArray<btVector3> m_vertices;
	btVector3 m_scaling;
	mutable int m_reported;
};

// A 4 x 4 floor at y = 0 of two triangles, plus a far-away triangle that must never be visited.
void buildFloor(TriangleSoupShape& soup)
{
	soup.addTriangle(btVector3(-2, 0, -2), btVector3(-2, 0, 2), btVector3(2, 0, 2));
	soup.addTriangle(btVector3(-2, 0, -2), btVector3(2, 0, 2), btVector3(2, 0, -2));
	soup.addTriangle(btVector3(50, 0, 50), btVector3(51, 0, 50), btVector3(50, 0, 51));
}

// Float noise of GJK/EPA on unit-sized shapes.
const btScalar kTolerance = btScalar(1e-3);
}  // namespace

TEST(ConvexConcaveAlgorithm, SphereOnMeshTouchesTheRightTriangle)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	TriangleSoupShape floor;
	buildFloor(floor);
	btSphereShape sphere(btScalar(0.5));
	// Centre over triangle 0 (x < z side of the diagonal), 0.01 into the floor.
	const btTransform sphereTransform(btQuaternion::getIdentity(), btVector3(-1, btScalar(0.49), 1));
	for (int order = 0; order < 2; ++order)
	{
		floor.m_reported = 0;
		PairFixture pair(dispatcher, order == 0 ? static_cast<btCollisionShape*>(&sphere) : &floor,
		                 order == 0 ? sphereTransform : btTransform::getIdentity(),
		                 order == 0 ? static_cast<btCollisionShape*>(&floor) : &sphere,
		                 order == 0 ? btTransform::getIdentity() : sphereTransform);
		btPersistentManifold* manifold = pair.process();
		ASSERT_NE(manifold, nullptr);
		ASSERT_EQ(manifold->getNumContacts(), 1) << "order " << order;
		EXPECT_EQ(manifold->getBody0(), order == 0 ? &pair.m_object0 : &pair.m_object1) << "manifold is (convex, mesh)";
		const btManifoldPoint& pt = manifold->getContactPoint(0);
		EXPECT_NEAR(pt.getDistance(), -0.01, kTolerance);
		EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, btVector3(0, 1, 0), kTolerance));
		EXPECT_TRUE(vectorsNear(pt.getPositionWorldOnB(), btVector3(-1, 0, 1), kTolerance));
		EXPECT_EQ(pt.m_index1, 0) << "triangle index on the mesh side";
		EXPECT_EQ(pt.m_partId1, 0);
		EXPECT_LE(floor.m_reported, 2) << "the far triangle is outside the sphere's AABB";
	}
}

TEST(ConvexConcaveAlgorithm, BoxOnMeshRestsAtItsDepth)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	TriangleSoupShape floor;
	buildFloor(floor);
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	PairFixture pair(dispatcher, &box,
	                 btTransform(btQuaternion::getIdentity(), btVector3(btScalar(0.3), btScalar(0.49), btScalar(-0.8))),
	                 &floor, btTransform::getIdentity());
	btPersistentManifold* manifold = 0;
	for (int frame = 0; frame < 3; ++frame) manifold = pair.process();
	ASSERT_GE(manifold->getNumContacts(), 1);
	for (int i = 0; i < manifold->getNumContacts(); ++i)
	{
		EXPECT_NEAR(manifold->getContactPoint(i).getDistance(), -0.01, kTolerance);
		EXPECT_TRUE(vectorsNear(manifold->getContactPoint(i).m_normalWorldOnB, btVector3(0, 1, 0), kTolerance));
	}
}

TEST(ConvexConcaveAlgorithm, SeparatedConvexHasNoPointsAndAllocatesNothingPerFrame)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	TriangleSoupShape floor;
	buildFloor(floor);
	btSphereShape sphere(btScalar(0.5));
	PairFixture pair(dispatcher, &sphere, btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.49), 0)),
	                 &floor, btTransform::getIdentity());
	pair.process();
	const int freeAlgorithms = config.getCollisionAlgorithmPool()->getFreeCount();
	const int freeManifolds = config.getPersistentManifoldPool()->getFreeCount();
	for (int frame = 0; frame < 5; ++frame) pair.process();
	EXPECT_EQ(config.getCollisionAlgorithmPool()->getFreeCount(), freeAlgorithms);
	EXPECT_EQ(config.getPersistentManifoldPool()->getFreeCount(), freeManifolds);
	pair.m_object0.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 3, 0)));
	EXPECT_EQ(pair.process()->getNumContacts(), 0);
}

TEST(ConvexConcaveAlgorithm, HullNearATiltedTriangleIsFoundUpToTheReachOnEverySide)
{
	// GJK starts each triangle from its normal and stops once a lower bound on the distance exceeds
	// the reach (and a hull over the face is then clipped). A cube hull just inside the reach must still
	// be found wherever it is: above the face,
	// below it, beside an edge in the triangle's plane, and diagonally off that edge.
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	TriangleSoupShape mesh;
	// Normal +y in the mesh's frame; the edge from (-2, 0, 0) to (2, 0, 0) bounds it at z = 0.
	mesh.addTriangle(btVector3(-2, 0, 0), btVector3(0, 0, 3), btVector3(2, 0, 0));
	mesh.setMargin(btScalar(0.01));
	btConvexHullShape cube;
	for (int corner = 0; corner < 8; ++corner)
		cube.addPoint(btVector3(corner & 1 ? btScalar(0.5) : btScalar(-0.5),
		                        corner & 2 ? btScalar(0.5) : btScalar(-0.5),
		                        corner & 4 ? btScalar(0.5) : btScalar(-0.5)));
	cube.setMargin(btScalar(0.04));
	const btScalar margins = cube.getMargin() + mesh.getMargin();
	const btTransform meshTransform(btQuaternion(btVector3(1, 0, 1), btScalar(0.5)), btVector3(3, -1, 2));

	struct Placement
	{
		btVector3 direction;         // unit, in the mesh's frame: from the triangle towards the cube
		btVector3 cubeCentreAtZero;  // where the cube touches the triangle (zero distance)
	};
	const btScalar diagonal = btSqrt(btScalar(0.5));
	const Placement placements[] = {
	    {btVector3(0, 1, 0), btVector3(0, btScalar(0.5), 1)},
	    {btVector3(0, -1, 0), btVector3(0, btScalar(-0.5), 1)},
	    {btVector3(0, 0, -1), btVector3(0, 0, btScalar(-0.5))},
	    {btVector3(0, diagonal, -diagonal), btVector3(0, btScalar(0.5), btScalar(-0.5))},
	};
	// Coordinates of size ~5 after two rotations: a few ulps of 5 per operation, far below 1e-4.
	const btScalar tolerance = btScalar(1e-4);
	for (int p = 0; p < 4; ++p)
	{
		const Placement& placement = placements[p];
		PairFixture pair(dispatcher, &cube, btTransform::getIdentity(), &mesh, meshTransform);
		// The margins sit between the cores: a core gap of margins + d is a reported distance d.
		const auto placeAt = [&](btScalar distance)
		{
			const btVector3 local = placement.cubeCentreAtZero + placement.direction * (margins + distance);
			pair.m_object0.setWorldTransform(meshTransform * btTransform(btQuaternion::getIdentity(), local));
			return pair.process();
		};
		const btScalar reach = placeAt(btScalar(5))->getContactBreakingThreshold();
		ASSERT_GT(reach, btScalar(0.01));
		btPersistentManifold* manifold = placeAt(reach * btScalar(0.95));
		// Over the face (above or below it) the cube's face is clipped against the triangle: its 4
		// corners, all inside the triangle; beside the edge in the triangle's plane, the cube's side face
		// lies along the edge: the edge's part under that face, both ends; diagonally off the edge (the
		// cube's edge nearest), GJK's single point.
		const int expected[] = {4, 4, 2, 1};
		ASSERT_EQ(manifold->getNumContacts(), expected[p]) << "placement " << p << " reach " << reach;
		for (int i = 0; i < manifold->getNumContacts(); ++i)
		{
			const btManifoldPoint& point = manifold->getContactPoint(i);
			EXPECT_NEAR(point.getDistance(), reach * btScalar(0.95), tolerance) << "placement " << p;
			EXPECT_TRUE(vectorsNear(point.m_normalWorldOnB, meshTransform.getBasis() * placement.direction, tolerance))
			    << "placement " << p;
		}
		manifold->clearManifold();
		EXPECT_EQ(placeAt(reach * btScalar(1.05))->getNumContacts(), 0) << "placement " << p;
	}
}

TEST(ConvexConcaveAlgorithm, TurnedHullReachesTrianglesAtItsExtremesOnEveryAxis)
{
	// The mesh query box of a hull is its exact box in the mesh's frame (its supports along the axes,
	// plus its margin), tighter than its turned local box. A triangle facing the hull's extreme point
	// along each axis of the mesh, just inside the reach, must still be queried and give its contact.
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	// A barrel: octagons of radius 1.1, 1.8, 1.1 at heights -2, 0, 2.
	btConvexHullShape barrel;
	const btScalar radii[3] = {btScalar(1.1), btScalar(1.8), btScalar(1.1)};
	for (int ring = 0; ring < 3; ++ring)
		for (int k = 0; k < 8; ++k)
		{
			const btScalar angle = btScalar(k) * SIMD_PI / btScalar(4);
			barrel.addPoint(btVector3(radii[ring] * btCos(angle), btScalar(2 * ring - 2), radii[ring] * btSin(angle)),
			                k == 7 && ring == 2);
		}
	barrel.setMargin(btScalar(0.04));
	const btTransform meshTransform(btQuaternion(btVector3(1, 2, 0), btScalar(0.3)), btVector3(1, -2, 3));
	const btTransform barrelInMesh(btQuaternion(btVector3(btScalar(0.2), btScalar(-0.7), 1), btScalar(0.9)),
	                               btVector3(btScalar(0.5), 4, btScalar(-1)));
	// Coordinates of size ~5 after two rotations: a few ulps of 5 per operation, far below 1e-4.
	const btScalar tolerance = btScalar(1e-4);
	for (int direction = 0; direction < 6; ++direction)
	{
		const int axis = direction % 3;
		const btScalar sign = direction < 3 ? btScalar(1) : btScalar(-1);
		btVector3 outward(0, 0, 0);
		outward[axis] = sign;
		// The barrel's extreme point along the axis, in the mesh's frame.
		const btVector3 extreme =
		    barrelInMesh(barrel.localGetSupportingVertexWithoutMargin(outward * barrelInMesh.getBasis()));
		TriangleSoupShape mesh;
		mesh.setMargin(btScalar(0.01));
		PairFixture pair(dispatcher, &barrel, meshTransform * barrelInMesh, &mesh, meshTransform);
		const btScalar reach = pair.process()->getContactBreakingThreshold();
		ASSERT_GT(reach, btScalar(0.01));
		// A triangle across the axis, its plane at the reported distance 0.95 reach beyond the extreme
		// (the margins lie between the cores), covering the extreme point's neighbourhood.
		const btScalar distance = reach * btScalar(0.95);
		const btVector3 centre = extreme + outward * (barrel.getMargin() + mesh.getMargin() + distance);
		const int across1 = (axis + 1) % 3, across2 = (axis + 2) % 3;
		btVector3 corners[3] = {centre, centre, centre};
		corners[0][across1] -= 3;
		corners[0][across2] -= 3;
		corners[1][across1] += 6;
		corners[1][across2] -= 3;
		corners[2][across1] -= 3;
		corners[2][across2] += 6;
		mesh.addTriangle(corners[0], corners[1], corners[2]);
		btPersistentManifold* manifold = pair.process();
		ASSERT_EQ(mesh.m_reported, 1) << "direction " << direction << ": the triangle is in the query box";
		ASSERT_EQ(manifold->getNumContacts(), 1) << "direction " << direction;
		EXPECT_NEAR(manifold->getContactPoint(0).getDistance(), distance, tolerance) << "direction " << direction;
		EXPECT_TRUE(
		    vectorsNear(manifold->getContactPoint(0).m_normalWorldOnB, meshTransform.getBasis() * -outward, tolerance))
		    << "direction " << direction;
	}
}
