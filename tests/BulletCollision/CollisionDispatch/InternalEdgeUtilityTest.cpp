// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "../NarrowPhaseCollision/NarrowPhaseTestUtil.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btInternalEdgeUtility.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "TestDispatcher.h"

using caliber_dispatch_test::PairFixture;
using caliber_dispatch_test::TestDispatcher;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// Normals are unit vectors rebuilt from a few float operations (atan2, cos, sin, a normalisation).
const btScalar kNormalTolerance = btScalar(1e-5);
// Angles come from atan2 of float dot products of unit vectors.
const btScalar kAngleTolerance = btScalar(1e-5);
// Contact points of GJK/EPA and the sphere-triangle detector carry float noise of unit-sized shapes.
const btScalar kPointTolerance = btScalar(1e-3);

const btVector3 kUp(0, 1, 0);

// An n x n grid of unit quads at y = 0 over [0, n] x [0, n] (x, z), each split along its (i, j)-(i+1, j+1)
// diagonal, faces up. Triangles 2 * (j * n + i) and 2 * (j * n + i) + 1; vertices are not shared (the
// utility must weld them), and jitter moves each copy by up to that much (deterministic pattern).
void addGrid(btTriangleMesh& mesh, int n, btScalar jitter = btScalar(0))
{
	int copy = 0;
	auto vertex = [&](int i, int j)
	{
		++copy;
		const btScalar dx = jitter * btScalar((copy * 7) % 5 - 2) / btScalar(2);
		const btScalar dz = jitter * btScalar((copy * 3) % 5 - 2) / btScalar(2);
		return btVector3(btScalar(i) + dx, btScalar(0), btScalar(j) + dz);
	};
	for (int j = 0; j < n; ++j)
		for (int i = 0; i < n; ++i)
		{
			mesh.addTriangle(vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1));
			mesh.addTriangle(vertex(i, j), vertex(i + 1, j + 1), vertex(i + 1, j));
		}
}

btScalar angleOf(const btTriangleInfo& info, int edge)
{
	return edge == 0 ? info.m_edgeV0V1Angle : edge == 1 ? info.m_edgeV1V2Angle : info.m_edgeV2V0Angle;
}

// True when the grid edge a-b lies on the border of [0, n]^2 (both ends on the same side of the square).
bool onGridBorder(const btVector3& a, const btVector3& b, int n)
{
	const btScalar size = btScalar(n);
	const btScalar eps = btScalar(1e-3);
	for (int axis = 0; axis < 3; axis += 2)
	{
		if (btFabs(a[axis]) < eps && btFabs(b[axis]) < eps) return true;
		if (btFabs(a[axis] - size) < eps && btFabs(b[axis] - size) < eps) return true;
	}
	return false;
}

// The vertices of triangle index of the only part of mesh, read back through the mesh interface.
void triangleVertices(btTriangleMesh& mesh, int index, btVector3* v)
{
	struct Finder : btInternalTriangleIndexCallback
	{
		int m_index;
		btVector3* m_out;
		void internalProcessTriangleIndex(btVector3* triangle, int, int triangleIndex) override
		{
			if (triangleIndex != m_index) return;
			for (int k = 0; k < 3; ++k) m_out[k] = triangle[k];
		}
	} finder;
	finder.m_index = index;
	finder.m_out = v;
	mesh.InternalProcessAllTriangles(&finder, btVector3(-1e6, -1e6, -1e6), btVector3(1e6, 1e6, 1e6));
}

// A contact on a mesh triangle built by hand, in the layout btManifoldResult writes: the mesh is body B
// (as the convex-concave algorithm stores it) unless meshIsA.
struct HandContact
{
	btCollisionObject m_meshObject;
	btCollisionObject m_otherObject;
	btSphereShape m_otherShape;
	btTriangleShape m_triangle;
	int m_index;

	HandContact(btCollisionShape* meshShape, const btVector3* v, int index, const btTransform& meshTransform)
	    : m_otherShape(btScalar(0.5)), m_triangle(v[0], v[1], v[2]), m_index(index)
	{
		m_meshObject.setCollisionShape(meshShape);
		m_meshObject.setWorldTransform(meshTransform);
		m_otherObject.setCollisionShape(&m_otherShape);
		m_otherObject.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(7, 5, 3)));
	}

	// A point with the mesh point meshPoint (world), the normal outOfMesh (world, from the mesh to the other
	// body) and signed distance distance.
	btManifoldPoint make(const btVector3& meshPoint, const btVector3& outOfMesh, btScalar distance, bool meshIsA) const
	{
		const btVector3 otherPoint = meshPoint + outOfMesh * distance;
		const btVector3 pointA = meshIsA ? meshPoint : otherPoint;
		const btVector3 pointB = meshIsA ? otherPoint : meshPoint;
		const btCollisionObject& objectA = meshIsA ? m_meshObject : m_otherObject;
		const btCollisionObject& objectB = meshIsA ? m_otherObject : m_meshObject;
		btManifoldPoint cp(objectA.getWorldTransform().invXform(pointA), objectB.getWorldTransform().invXform(pointB),
		                   meshIsA ? -outOfMesh : outOfMesh, distance);
		cp.m_positionWorldOnA = pointA;
		cp.m_positionWorldOnB = pointB;
		return cp;
	}

	// Runs the utility the way a gContactAddedCallback does; returns the corrected normal out of the mesh.
	btVector3 adjust(btManifoldPoint& cp, bool meshIsA, int flags = 0) const
	{
		btCollisionObjectWrapper meshWrap(0, m_meshObject.getCollisionShape(), &m_meshObject,
		                                  m_meshObject.getWorldTransform(), -1, -1);
		btCollisionObjectWrapper triangleWrap(&meshWrap, &m_triangle, &m_meshObject, m_meshObject.getWorldTransform(),
		                                      0, m_index);
		btCollisionObjectWrapper otherWrap(0, &m_otherShape, &m_otherObject, m_otherObject.getWorldTransform(), -1, -1);
		btAdjustInternalEdgeContacts(cp, &triangleWrap, &otherWrap, 0, m_index, flags);
		return meshIsA ? -cp.m_normalWorldOnB : cp.m_normalWorldOnB;
	}
};

// Point, normal and distance of a manifold point agree: A = B + normal * distance, and the local points map
// onto the world points.
void expectConsistent(const btManifoldPoint& cp, const btCollisionObject& a, const btCollisionObject& b)
{
	EXPECT_TRUE(vectorsNear(cp.m_positionWorldOnA, cp.m_positionWorldOnB + cp.m_normalWorldOnB * cp.m_distance1,
	                        btScalar(1e-5)));
	EXPECT_TRUE(vectorsNear(a.getWorldTransform()(cp.m_localPointA), cp.m_positionWorldOnA, btScalar(1e-5)));
	EXPECT_TRUE(vectorsNear(b.getWorldTransform()(cp.m_localPointB), cp.m_positionWorldOnB, btScalar(1e-5)));
	EXPECT_NEAR(cp.m_normalWorldOnB.length(), 1, kNormalTolerance);
}

// Installs a gContactAddedCallback that runs the utility on whichever side is the mesh, and restores the
// previous callback on destruction.
int g_adjustFlags = 0;
bool g_adjustEnabled = true;
bool adjustingCallback(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int partId0, int index0,
                       const btCollisionObjectWrapper* w1, int partId1, int index1)
{
	if (!g_adjustEnabled) return false;
	if (w0->getCollisionShape()->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE)
		btAdjustInternalEdgeContacts(cp, w0, w1, partId0, index0, g_adjustFlags);
	else
		btAdjustInternalEdgeContacts(cp, w1, w0, partId1, index1, g_adjustFlags);
	return true;
}
struct CallbackGuard
{
	ContactAddedCallback m_saved;
	CallbackGuard() : m_saved(gContactAddedCallback) { gContactAddedCallback = adjustingCallback; }
	~CallbackGuard() { gContactAddedCallback = m_saved; }
};

// Collides convex (at convexTransform) with the concave shape (identity) in both pair orders, with or without
// the utility, and returns every manifold point (normal out of the mesh, distance, mesh point).
struct MeshContact
{
	btVector3 m_normalOut;
	btScalar m_distance;
	btVector3 m_meshPoint;
};
std::vector<MeshContact> collide(btCollisionShape* convex, const btTransform& convexTransform,
                                 btCollisionShape* concave, bool adjust, int order)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	CallbackGuard guard;
	g_adjustEnabled = adjust;
	PairFixture pair(dispatcher, order == 0 ? convex : concave,
	                 order == 0 ? convexTransform : btTransform::getIdentity(), order == 0 ? concave : convex,
	                 order == 0 ? btTransform::getIdentity() : convexTransform);
	btCollisionObject& meshObject = order == 0 ? pair.m_object1 : pair.m_object0;
	meshObject.setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
	btPersistentManifold* manifold = pair.process();
	std::vector<MeshContact> out;
	if (!manifold) return out;
	const bool meshIsB = manifold->getBody1() == &meshObject;
	for (int i = 0; i < manifold->getNumContacts(); ++i)
	{
		const btManifoldPoint& cp = manifold->getContactPoint(i);
		expectConsistent(cp, *static_cast<const btCollisionObject*>(manifold->getBody0()),
		                 *static_cast<const btCollisionObject*>(manifold->getBody1()));
		MeshContact c;
		c.m_normalOut = meshIsB ? cp.m_normalWorldOnB : -cp.m_normalWorldOnB;
		c.m_distance = cp.m_distance1;
		c.m_meshPoint = meshIsB ? cp.m_positionWorldOnB : cp.m_positionWorldOnA;
		out.push_back(c);
	}
	g_adjustEnabled = true;
	return out;
}

// Largest angle (radians) between a contact normal and +y.
btScalar largestTilt(const std::vector<MeshContact>& contacts)
{
	btScalar tilt = 0;
	for (const MeshContact& c : contacts)
		tilt = btMax(tilt, btAcos(btClamped(c.m_normalOut.dot(kUp), btScalar(-1), btScalar(1))));
	return tilt;
}
}  // namespace

TEST(InternalEdgeUtility, KeysFollowBulletLayoutAndHeightfieldKeysAreUnique)
{
	EXPECT_EQ(btInternalEdgeMeshKey(0, 0), 0);
	EXPECT_EQ(btInternalEdgeMeshKey(3, 17), (3 << 21) | 17);
	EXPECT_EQ(btInternalEdgeMeshKey(1023, (1 << 21) - 1), 0x7fffffff);
	std::set<int> seen;
	// Wide grids (partId = 2 x + half up to 2 * 32767 + 1) against a sample of rows, including the last one.
	const int rows[] = {0, 1, 2, 3, 100, 4095, 32767};
	for (int row : rows)
		for (int part = 0; part < 65536; part += 7)
		{
			const int key = btInternalEdgeHeightfieldKey(part, row);
			EXPECT_GE(key, 0);
			EXPECT_TRUE(seen.insert(key).second) << "part " << part << " row " << row;
		}
}

TEST(InternalEdgeUtility, FlatGridHasPlanarInternalEdgesAndFreeBorders)
{
	const int n = 2;
	btTriangleMesh mesh;
	addGrid(mesh, n);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	EXPECT_EQ(shape.getTriangleInfoMap(), &map);
	ASSERT_EQ(map.size(), 2 * n * n);
	int paired = 0;
	for (int t = 0; t < 2 * n * n; ++t)
	{
		const btTriangleInfo* info = map.find(btHashInt((0 << 21) | t));
		ASSERT_NE(info, nullptr) << "triangle " << t;
		btVector3 v[3];
		triangleVertices(mesh, t, v);
		EXPECT_EQ(info->m_flags, 0) << "a flat grid has no convex edge and consistent winding";
		for (int k = 0; k < 3; ++k)
		{
			const btScalar angle = angleOf(*info, k);
			if (onGridBorder(v[k], v[(k + 1) % 3], n))
				EXPECT_EQ(angle, SIMD_2_PI) << "border edge " << k << " of triangle " << t;
			else
			{
				EXPECT_EQ(angle, btScalar(0)) << "internal edge " << k << " of triangle " << t;
				++paired;
			}
		}
	}
	// Internal edges of an n x n split grid: 2 n (n - 1) grid lines inside plus n^2 diagonals, two sides each.
	EXPECT_EQ(paired, 2 * (2 * n * (n - 1) + n * n));
}

TEST(InternalEdgeUtility, LargeJitteredGridPairsEveryInternalEdge)
{
	// 60 x 60 quads = 7200 triangles, each vertex copy moved by up to 2e-5 (within the default weld distance
	// 1e-4): a quadratic pairing would be slow here, and a position-exact one would pair nothing.
	const int n = 60;
	btTriangleMesh mesh;
	addGrid(mesh, n, btScalar(2e-5));
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	ASSERT_EQ(map.size(), 2 * n * n);
	int paired = 0, largeAngles = 0;
	for (int i = 0; i < map.size(); ++i)
		for (int k = 0; k < 3; ++k)
		{
			const btScalar angle = angleOf(*map.getAtIndex(i), k);
			if (angle == SIMD_2_PI) continue;
			++paired;
			// Jitter of 2e-5 over unit edges tilts a face by at most ~4e-5 rad.
			if (btFabs(angle) > btScalar(1e-3)) ++largeAngles;
		}
	EXPECT_EQ(paired, 2 * (2 * n * (n - 1) + n * n));
	EXPECT_EQ(largeAngles, 0);
}

TEST(InternalEdgeUtility, VerticesFartherThanTheWeldDistanceAreNotJoined)
{
	// Two coplanar triangles whose "shared" edge ends are 1e-3 apart (default weld distance 1e-4).
	btTriangleMesh mesh;
	const btScalar gap = btScalar(1e-3);
	mesh.addTriangle(btVector3(0, 0, 0), btVector3(0, 0, 1), btVector3(1, 0, 1));
	mesh.addTriangle(btVector3(gap, 0, 0), btVector3(1, 0, 1 + gap), btVector3(1, 0, 0));
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	for (int i = 0; i < map.size(); ++i)
		for (int k = 0; k < 3; ++k) EXPECT_EQ(angleOf(*map.getAtIndex(i), k), SIMD_2_PI);
	// The same mesh with a weld distance of 1e-2 pairs them.
	map.m_equalVertexThreshold = btScalar(1e-2) * btScalar(1e-2);
	btGenerateInternalEdgeInfo(&shape, &map);
	int paired = 0;
	for (int i = 0; i < map.size(); ++i)
		for (int k = 0; k < 3; ++k) paired += angleOf(*map.getAtIndex(i), k) != SIMD_2_PI;
	EXPECT_EQ(paired, 2);
}

TEST(InternalEdgeUtility, RoofAndValleyGiveTheDihedralAngleWithConvexSign)
{
	for (int shapeKind = 0; shapeKind < 3; ++shapeKind)
	{
		// 0: roof (ridge up), 1: valley, 2: roof whose second triangle is wound the other way.
		const btScalar h = shapeKind == 1 ? btScalar(-0.5) : btScalar(0.5);
		btTriangleMesh mesh;
		mesh.addTriangle(btVector3(0, h, 0), btVector3(-1, 0, btScalar(0.5)), btVector3(0, h, 1));
		if (shapeKind == 2)
			mesh.addTriangle(btVector3(0, h, 0), btVector3(1, 0, btScalar(0.5)), btVector3(0, h, 1));
		else
			mesh.addTriangle(btVector3(0, h, 1), btVector3(1, 0, btScalar(0.5)), btVector3(0, h, 0));
		btBvhTriangleMeshShape shape(&mesh, true);
		btTriangleInfoMap map;
		btGenerateInternalEdgeInfo(&shape, &map);
		const btTriangleInfo* left = map.find(btHashInt(0));
		const btTriangleInfo* right = map.find(btHashInt(1));
		ASSERT_TRUE(left && right);
		// Each face leans atan(|h|) from the vertical, so the normals differ by 2 atan(|h|).
		const btScalar bend = btScalar(2) * btAtan(btFabs(h));
		const btScalar expectedLeft = shapeKind == 1 ? -bend : bend;
		EXPECT_NEAR(left->m_edgeV2V0Angle, expectedLeft, kAngleTolerance) << "kind " << shapeKind;
		EXPECT_EQ(left->m_edgeV0V1Angle, SIMD_2_PI);
		EXPECT_EQ(left->m_edgeV1V2Angle, SIMD_2_PI);
		const int leftConvex = shapeKind == 1 ? 0 : TRI_INFO_V2V0_CONVEX;
		const int swap = shapeKind == 2 ? TRI_INFO_V2V0_SWAP_NORMALB : 0;
		EXPECT_EQ(left->m_flags, leftConvex | swap) << "kind " << shapeKind;
		if (shapeKind == 2)
		{
			// The reversed triangle faces down: from below, the ridge is a valley.
			EXPECT_NEAR(right->m_edgeV2V0Angle, -bend, kAngleTolerance);
			EXPECT_EQ(right->m_flags, TRI_INFO_V2V0_SWAP_NORMALB);
		}
		else
		{
			EXPECT_NEAR(right->m_edgeV2V0Angle, expectedLeft, kAngleTolerance) << "kind " << shapeKind;
			EXPECT_EQ(right->m_flags, leftConvex);
		}
	}
}

TEST(InternalEdgeUtility, DegenerateTrianglesAreSkippedWithoutNaN)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	// A zero-area triangle along the grid's z = 0 border and a needle collapsing under the weld distance.
	mesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(2, 0, 0));
	mesh.addTriangle(btVector3(2, 0, 2), btVector3(2, 0, 2 + btScalar(1e-6)), btVector3(3, 0, 2));
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	EXPECT_EQ(map.size(), 8) << "only the grid's triangles get entries";
	EXPECT_EQ(map.find(btHashInt(8)), nullptr);
	EXPECT_EQ(map.find(btHashInt(9)), nullptr);
	int paired = 0;
	for (int i = 0; i < map.size(); ++i)
		for (int k = 0; k < 3; ++k)
		{
			const btScalar angle = angleOf(*map.getAtIndex(i), k);
			EXPECT_TRUE(btIsFinite(angle));
			paired += angle != SIMD_2_PI;
		}
	EXPECT_EQ(paired, 16) << "the degenerate triangle does not pair with the border";

	// A contact on a degenerate triangle is left alone (no normal to snap to), whatever the map says.
	btVector3 v[3] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(2, 0, 0)};
	map.insert(btHashInt(8), btTriangleInfo());
	map.find(btHashInt(8))->m_edgeV0V1Angle = 0;
	HandContact hand(&shape, v, 8, btTransform::getIdentity());
	btManifoldPoint cp =
	    hand.make(btVector3(btScalar(0.5), 0, 0), btVector3(0, 1, 1).normalized(), btScalar(-0.01), false);
	const btManifoldPoint before = cp;
	hand.adjust(cp, false);
	EXPECT_EQ(cp.m_normalWorldOnB, before.m_normalWorldOnB);
	EXPECT_EQ(cp.m_distance1, before.m_distance1);
}

TEST(InternalEdgeUtility, SphereOverInternalEdgeOrVertexGetsTheFaceNormal)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	btSphereShape sphere(btScalar(0.5));
	// Centre 0.05 below touching height, 0.2 past the internal edge x = 1 (and, second, past the vertex
	// (1, 0, 1)): the neighbouring triangles' edges and vertex push back at about 24 degrees.
	const btVector3 centres[2] = {btVector3(btScalar(1.2), btScalar(0.45), btScalar(0.5)),
	                              btVector3(btScalar(1.15), btScalar(0.45), btScalar(1.2))};
	for (const btVector3& centre : centres)
		for (int order = 0; order < 2; ++order)
		{
			const btTransform at(btQuaternion::getIdentity(), centre);
			const std::vector<MeshContact> raw = collide(&sphere, at, &shape, false, order);
			ASSERT_GE(raw.size(), 2u);
			EXPECT_GT(largestTilt(raw), btScalar(0.3)) << "without the utility the edge/vertex contact is tilted";
			const std::vector<MeshContact> adjusted = collide(&sphere, at, &shape, true, order);
			ASSERT_EQ(adjusted.size(), raw.size());
			for (const MeshContact& c : adjusted)
			{
				EXPECT_TRUE(vectorsNear(c.m_normalOut, kUp, kNormalTolerance)) << "order " << order;
				EXPECT_NEAR(c.m_meshPoint.y(), 0, kPointTolerance) << "mesh point stays on the floor";
				// The true penetration is 0.05; corrected points keep the sphere point they had, which lies
				// no deeper than the sphere's lowest point (and a separated vertex contact stays separated,
				// within the breaking distance).
				EXPECT_GE(c.m_distance, btScalar(-0.05) - kPointTolerance);
				EXPECT_LE(c.m_distance, gContactBreakingThreshold);
			}
		}
}

TEST(InternalEdgeUtility, HeightfieldSphereOverInternalEdgeGetsTheFaceNormal)
{
	// 3 x 3 flat samples, y up: the same 2 x 2 cells as the grid, centred on the origin.
	const float heights[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
	btHeightfieldTerrainShape terrain(3, 3, heights, 1, -1, 1, 1, PHY_FLOAT, false);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&terrain, &map);
	EXPECT_EQ(terrain.getTriangleInfoMap(), &map);
	ASSERT_EQ(map.size(), 8);
	int paired = 0;
	for (int i = 0; i < map.size(); ++i)
		for (int k = 0; k < 3; ++k)
		{
			const btScalar angle = angleOf(*map.getAtIndex(i), k);
			if (angle != SIMD_2_PI)
			{
				EXPECT_EQ(angle, btScalar(0));
				++paired;
			}
		}
	EXPECT_EQ(paired, 16);
	btSphereShape sphere(btScalar(0.5));
	const btTransform at(btQuaternion::getIdentity(), btVector3(btScalar(0.2), btScalar(0.45), btScalar(-0.5)));
	const std::vector<MeshContact> raw = collide(&sphere, at, &terrain, false, 0);
	EXPECT_GT(largestTilt(raw), btScalar(0.3));
	const std::vector<MeshContact> adjusted = collide(&sphere, at, &terrain, true, 1);
	ASSERT_FALSE(adjusted.empty());
	for (const MeshContact& c : adjusted) EXPECT_TRUE(vectorsNear(c.m_normalOut, kUp, kNormalTolerance));
}

TEST(InternalEdgeUtility, BoxRestingAcrossAVertexKeepsItsContacts)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	btBoxShape box(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
	const btTransform at(btQuaternion::getIdentity(), btVector3(1, btScalar(0.39), 1));
	const std::vector<MeshContact> adjusted = collide(&box, at, &shape, true, 0);
	ASSERT_FALSE(adjusted.empty());
	for (const MeshContact& c : adjusted)
	{
		EXPECT_TRUE(vectorsNear(c.m_normalOut, kUp, kNormalTolerance));
		// Box margin 0.04 is inside the half extents: the resting depth is 0.01 whatever the algorithm.
		EXPECT_NEAR(c.m_distance, btScalar(-0.01), kPointTolerance);
	}
}

TEST(InternalEdgeUtility, ContactsInTheMiddleOfAFaceAreUntouched)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	btVector3 v[3];
	triangleVertices(mesh, 0, v);
	const btVector3 centroid = (v[0] + v[1] + v[2]) / btScalar(3);
	HandContact hand(&shape, v, 0, btTransform::getIdentity());
	// A strongly tilted normal (as EPA may give for a deep contact) 0.24 from every edge: not an edge bump.
	for (int meshIsA = 0; meshIsA < 2; ++meshIsA)
	{
		btManifoldPoint cp = hand.make(centroid, btVector3(1, 1, 0).normalized(), btScalar(-0.02), meshIsA != 0);
		const btManifoldPoint before = cp;
		hand.adjust(cp, meshIsA != 0);
		EXPECT_EQ(cp.m_normalWorldOnB, before.m_normalWorldOnB);
		EXPECT_EQ(cp.m_distance1, before.m_distance1);
		EXPECT_EQ(cp.m_positionWorldOnB, before.m_positionWorldOnB);
		EXPECT_EQ(cp.m_positionWorldOnA, before.m_positionWorldOnA);
	}
}

TEST(InternalEdgeUtility, HandContactOverEdgeIsSnappedInEitherBodyOrderAndMeshPose)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	// Triangle 1 = (0,0,0), (1,0,1), (1,0,0): its edge V1V2 is the internal edge x = 1 (z in [0, 1]).
	btVector3 v[3];
	triangleVertices(mesh, 1, v);
	const btTransform poses[2] = {
	    btTransform::getIdentity(),
	    btTransform(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7)), btVector3(5, -2, 4))};
	for (const btTransform& pose : poses)
		for (int meshIsA = 0; meshIsA < 2; ++meshIsA)
		{
			HandContact hand(&shape, v, 1, pose);
			const btVector3 tilted(btScalar(0.4), btScalar(0.9), btScalar(0));
			btManifoldPoint cp = hand.make(pose(btVector3(1, 0, btScalar(0.5))), pose.getBasis() * tilted.normalized(),
			                               btScalar(-0.01), meshIsA != 0);
			const btVector3 otherPoint = meshIsA ? cp.m_positionWorldOnB : cp.m_positionWorldOnA;
			const btVector3 out = hand.adjust(cp, meshIsA != 0);
			EXPECT_TRUE(vectorsNear(out, pose.getBasis() * kUp, kNormalTolerance)) << "meshIsA " << meshIsA;
			// The other body's point stays; the distance is its height over the face plane.
			EXPECT_EQ(meshIsA ? cp.m_positionWorldOnB : cp.m_positionWorldOnA, otherPoint);
			const btScalar height = (pose.invXform(otherPoint)).y();
			EXPECT_NEAR(cp.m_distance1, height, kNormalTolerance);
			expectConsistent(cp, meshIsA ? hand.m_meshObject : hand.m_otherObject,
			                 meshIsA ? hand.m_otherObject : hand.m_meshObject);
		}
}

TEST(InternalEdgeUtility, ConvexRidgeKeepsNormalsInsideItsCone)
{
	const btScalar h = btScalar(0.5);
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(0, h, 0), btVector3(-1, 0, btScalar(0.5)), btVector3(0, h, 1));
	mesh.addTriangle(btVector3(0, h, 1), btVector3(1, 0, btScalar(0.5)), btVector3(0, h, 0));
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	btVector3 v[3];
	triangleVertices(mesh, 0, v);
	HandContact hand(&shape, v, 0, btTransform::getIdentity());
	const btVector3 leftNormal = btVector3(-h, 1, 0).normalized();
	const btVector3 rightNormal = btVector3(h, 1, 0).normalized();
	const btVector3 ridgePoint(0, h, btScalar(0.5));

	// Inside the cone between the two faces (straight up, or the right face's own normal): unchanged.
	const btVector3 inside[3] = {kUp, rightNormal, (leftNormal + rightNormal * btScalar(3)).normalized()};
	for (const btVector3& n : inside)
	{
		btManifoldPoint cp = hand.make(ridgePoint, n, btScalar(0.01), false);
		EXPECT_TRUE(vectorsNear(hand.adjust(cp, false), n, kNormalTolerance));
	}
	// Past the right face's normal (leaning further right, even below horizontal): clamped to that normal.
	const btVector3 beyond[2] = {btVector3(1, btScalar(0.2), 0).normalized(),
	                             btVector3(1, btScalar(-0.1), 0).normalized()};
	for (const btVector3& n : beyond)
	{
		btManifoldPoint cp = hand.make(ridgePoint, n, btScalar(0.01), false);
		EXPECT_TRUE(vectorsNear(hand.adjust(cp, false), rightNormal, kNormalTolerance));
		expectConsistent(cp, hand.m_otherObject, hand.m_meshObject);
	}
	// An along-ridge component survives the clamp (only the tilt across the edge is bounded).
	btManifoldPoint cp =
	    hand.make(ridgePoint, btVector3(1, btScalar(0.2), btScalar(0.3)).normalized(), btScalar(0.01), false);
	const btVector3 out = hand.adjust(cp, false);
	EXPECT_NEAR(btAtan2(out.dot(btVector3(1, 0, 0)), out.dot(kUp)), btAtan2(h, btScalar(1)), kAngleTolerance);
	EXPECT_GT(out.z(), btScalar(0.2));
}

TEST(InternalEdgeUtility, ConcaveValleyTurnsOutwardNormalsToTheFace)
{
	const btScalar h = btScalar(-0.5);
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(0, h, 0), btVector3(-1, 0, btScalar(0.5)), btVector3(0, h, 1));
	mesh.addTriangle(btVector3(0, h, 1), btVector3(1, 0, btScalar(0.5)), btVector3(0, h, 0));
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	btVector3 v[3];
	triangleVertices(mesh, 0, v);
	HandContact hand(&shape, v, 0, btTransform::getIdentity());
	const btVector3 leftNormal = btVector3(-h, 1, 0).normalized();
	btManifoldPoint cp =
	    hand.make(btVector3(0, h, btScalar(0.5)), btVector3(1, btScalar(0.2), 0).normalized(), btScalar(-0.01), false);
	EXPECT_TRUE(vectorsNear(hand.adjust(cp, false), leftNormal, kNormalTolerance));
	// Leaning back over the left face is what the face itself reports: unchanged.
	const btVector3 back = btVector3(-1, 1, 0).normalized();
	cp = hand.make(btVector3(0, h, btScalar(0.5)), back, btScalar(-0.01), false);
	EXPECT_TRUE(vectorsNear(hand.adjust(cp, false), back, kNormalTolerance));
}

TEST(InternalEdgeUtility, BackFacesNeedTheirFlags)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	btVector3 v[3];
	triangleVertices(mesh, 1, v);
	HandContact hand(&shape, v, 1, btTransform::getIdentity());
	const btVector3 underTilted = btVector3(btScalar(0.4), btScalar(-0.9), 0).normalized();
	const btVector3 down(0, -1, 0);
	// Default: the back of a single-sided mesh is left alone.
	btManifoldPoint cp = hand.make(btVector3(1, 0, btScalar(0.5)), underTilted, btScalar(-0.01), false);
	EXPECT_TRUE(vectorsNear(hand.adjust(cp, false), underTilted, kNormalTolerance));
	// The back is the outside in backface mode, and either side is corrected at planar edges when double-sided.
	const int flags[2] = {BT_TRIANGLE_CONVEX_BACKFACE_MODE, BT_TRIANGLE_CONCAVE_DOUBLE_SIDED};
	for (int f : flags)
	{
		cp = hand.make(btVector3(1, 0, btScalar(0.5)), underTilted, btScalar(-0.01), false);
		EXPECT_TRUE(vectorsNear(hand.adjust(cp, false, f), down, kNormalTolerance)) << "flags " << f;
	}
	// Planar edges are not convex edges: the convex double-sided flag alone leaves the back alone.
	cp = hand.make(btVector3(1, 0, btScalar(0.5)), underTilted, btScalar(-0.01), false);
	EXPECT_TRUE(vectorsNear(hand.adjust(cp, false, BT_TRIANGLE_CONVEX_DOUBLE_SIDED), underTilted, kNormalTolerance));
}

TEST(InternalEdgeUtility, WithoutAnInfoMapContactsAreLeftAlone)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	btBvhTriangleMeshShape shape(&mesh, true);
	ASSERT_EQ(shape.getTriangleInfoMap(), nullptr);
	btVector3 v[3];
	triangleVertices(mesh, 1, v);
	HandContact hand(&shape, v, 1, btTransform::getIdentity());
	const btVector3 tilted = btVector3(btScalar(0.4), btScalar(0.9), 0).normalized();
	btManifoldPoint cp = hand.make(btVector3(1, 0, btScalar(0.5)), tilted, btScalar(-0.01), false);
	EXPECT_TRUE(vectorsNear(hand.adjust(cp, false), tilted, btScalar(0)));
	// Through the algorithm: the sphere past the edge keeps its tilted contact.
	btSphereShape sphere(btScalar(0.5));
	const btTransform at(btQuaternion::getIdentity(), btVector3(btScalar(1.2), btScalar(0.45), btScalar(0.5)));
	EXPECT_GT(largestTilt(collide(&sphere, at, &shape, true, 0)), btScalar(0.3));
}

TEST(InternalEdgeUtility, NullArgumentsAreRejected)
{
	btTriangleMesh mesh;
	addGrid(mesh, 1);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btVector3 v[3];
	triangleVertices(mesh, 1, v);
	HandContact hand(&shape, v, 1, btTransform::getIdentity());
	btManifoldPoint cp = hand.make(btVector3(1, 0, btScalar(0.5)), kUp, btScalar(-0.01), false);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btGenerateInternalEdgeInfo(&shape, static_cast<btTriangleInfoMap*>(0)), "assertion failed");
	EXPECT_DEATH(btGenerateInternalEdgeInfo(static_cast<btBvhTriangleMeshShape*>(0), &map), "assertion failed");
	EXPECT_DEATH(btAdjustInternalEdgeContacts(cp, 0, 0, 0, 1), "assertion failed");
#else
	// Release: nothing happens; the shape keeps no map and the point is unchanged.
	btGenerateInternalEdgeInfo(&shape, static_cast<btTriangleInfoMap*>(0));
	btGenerateInternalEdgeInfo(static_cast<btBvhTriangleMeshShape*>(0), &map);
	btGenerateInternalEdgeInfo(static_cast<btHeightfieldTerrainShape*>(0), &map);
	EXPECT_EQ(shape.getTriangleInfoMap(), nullptr);
	EXPECT_EQ(map.size(), 0);
	const btManifoldPoint before = cp;
	btAdjustInternalEdgeContacts(cp, 0, 0, 0, 1);
	EXPECT_EQ(cp.m_normalWorldOnB, before.m_normalWorldOnB);
	EXPECT_EQ(cp.m_distance1, before.m_distance1);
#endif
}

TEST(InternalEdgeUtility, SphereSlidingAcrossTheGridNeverSeesATiltedNormal)
{
	// A sphere pressed 0.05 into a 4 x 4 grid slides diagonally across internal edges and vertices; one
	// algorithm (and manifold) for the whole path, as in a simulation.
	btTriangleMesh mesh;
	addGrid(mesh, 4);
	btBvhTriangleMeshShape shape(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&shape, &map);
	btSphereShape sphere(btScalar(0.5));
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	CallbackGuard guard;
	PairFixture pair(dispatcher, &sphere, btTransform::getIdentity(), &shape, btTransform::getIdentity());
	pair.m_object1.setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT |
	                                 btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
	// The same path without the callback flag: the convex-concave algorithm drops the points of internal
	// edges and vertices itself (they continue faces the sphere lies on), so no normal leans there either.
	PairFixture rawPair(dispatcher, &sphere, btTransform::getIdentity(), &shape, btTransform::getIdentity());
	int contacts = 0, rawTilted = 0;
	for (int step = 0; step <= 200; ++step)
	{
		const btScalar s = btScalar(0.6) + btScalar(2.8) * btScalar(step) / btScalar(200);
		const btTransform at(btQuaternion::getIdentity(),
		                     btVector3(s, btScalar(0.45), s * btScalar(0.7) + btScalar(0.3)));
		pair.m_object0.setWorldTransform(at);
		rawPair.m_object0.setWorldTransform(at);
		btPersistentManifold* manifold = pair.process();
		ASSERT_NE(manifold, nullptr);
		for (int i = 0; i < manifold->getNumContacts(); ++i, ++contacts)
			EXPECT_TRUE(vectorsNear(manifold->getContactPoint(i).m_normalWorldOnB, kUp, kNormalTolerance))
			    << "step " << step << " point " << i;
		btPersistentManifold* raw = rawPair.process();
		ASSERT_NE(raw, nullptr);
		for (int i = 0; i < raw->getNumContacts(); ++i)
			rawTilted += raw->getContactPoint(i).m_normalWorldOnB.dot(kUp) < btCos(btScalar(0.1));
	}
	EXPECT_GT(contacts, 200);
	EXPECT_EQ(rawTilted, 0) << "points on internal edges lean without the utility unless the algorithm drops them";
}

TEST(InternalEdgeUtility, ScaledMeshUsesItsChildMap)
{
	btTriangleMesh mesh;
	addGrid(mesh, 2);
	btBvhTriangleMeshShape child(&mesh, true);
	btTriangleInfoMap map;
	btGenerateInternalEdgeInfo(&child, &map);
	// Scaled 2x along x and z: the internal edge x = 1 moves to x = 2; angles of a flat grid stay 0.
	btScaledBvhTriangleMeshShape scaled(&child, btVector3(2, 1, 2));
	btSphereShape sphere(btScalar(0.5));
	const btTransform at(btQuaternion::getIdentity(), btVector3(btScalar(2.2), btScalar(0.45), btScalar(1)));
	EXPECT_GT(largestTilt(collide(&sphere, at, &scaled, false, 0)), btScalar(0.3));
	const std::vector<MeshContact> adjusted = collide(&sphere, at, &scaled, true, 0);
	ASSERT_FALSE(adjusted.empty());
	for (const MeshContact& c : adjusted) EXPECT_TRUE(vectorsNear(c.m_normalOut, kUp, kNormalTolerance));
}
