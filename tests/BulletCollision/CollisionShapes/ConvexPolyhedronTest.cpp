// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"
#include "BulletCollision/CollisionShapes/ConvexHullMassProperties.h"
#include "LinearMath/btQuaternion.h"

namespace
{
// Hull vertices are input points copied unchanged and planes come from unit-size coordinates, so a
// few hundred float ulps cover every plane offset and normal component computed here.
const btScalar kGeomTol = btScalar(256) * SIMD_EPSILON;

void boxCorners(const btVector3& half, const btVector3& offset, btAlignedObjectArray<btVector3>& out)
{
	for (int i = 0; i < 8; ++i)
		out.push_back(offset + btVector3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
		                                 (i & 4) ? half.z() : -half.z()));
}
}  // namespace

TEST(ConvexPolyhedron, BoxHullHasSixFacesWithAxisPlanes)
{
	btAlignedObjectArray<btVector3> points;
	const btVector3 half(1, 2, 3);
	boxCorners(half, btVector3(0, 0, 0), points);
	points.push_back(btVector3(0.1f, 0.2f, 0.3f));  // interior point: not a vertex
	btConvexPolyhedron poly;
	ASSERT_TRUE(caliber::buildConvexPolyhedron(&points[0], points.size(), poly));
	EXPECT_EQ(poly.m_vertices.size(), 8);
	ASSERT_EQ(poly.m_faces.size(), 6);
	EXPECT_EQ(poly.m_uniqueEdges.size(), 3);
	for (int f = 0; f < poly.m_faces.size(); ++f)
	{
		const btFace& face = poly.m_faces[f];
		EXPECT_EQ(face.m_indices.size(), 4);
		const btVector3 n(face.m_plane[0], face.m_plane[1], face.m_plane[2]);
		EXPECT_NEAR(n.length(), 1, kGeomTol);
		const int axis = n.absolute().maxAxis();
		EXPECT_NEAR(btFabs(n[axis]), 1, kGeomTol);
		EXPECT_NEAR(face.m_plane[3], -half[axis], kGeomTol * half[axis]);
		for (int i = 0; i < face.m_indices.size(); ++i)
			EXPECT_NEAR(n.dot(poly.m_vertices[face.m_indices[i]]) + face.m_plane[3], 0, kGeomTol * 4);
	}
	EXPECT_NEAR(poly.m_localCenter.length(), 0, kGeomTol);
	EXPECT_NEAR(poly.m_radius, 1, kGeomTol);
	EXPECT_NEAR((poly.mE - half).length(), 0, kGeomTol);
	EXPECT_TRUE(poly.testContainment());
	// The inner box grows along each axis up to the faces (bisection to 2^-16 of the search range).
	EXPECT_NEAR(poly.m_extents.x(), 1, btScalar(1e-3));
	EXPECT_NEAR(poly.m_extents.z(), 3, btScalar(1e-2));
}

TEST(ConvexPolyhedron, FaceWindingIsCounterClockwiseFromOutside)
{
	btAlignedObjectArray<btVector3> points;
	boxCorners(btVector3(1, 1, 1), btVector3(5, -2, 1), points);
	btConvexPolyhedron poly;
	ASSERT_TRUE(caliber::buildConvexPolyhedron(&points[0], points.size(), poly));
	for (int f = 0; f < poly.m_faces.size(); ++f)
	{
		const btFace& face = poly.m_faces[f];
		const btVector3& a = poly.m_vertices[face.m_indices[0]];
		const btVector3& b = poly.m_vertices[face.m_indices[1]];
		const btVector3& c = poly.m_vertices[face.m_indices[2]];
		const btVector3 n(face.m_plane[0], face.m_plane[1], face.m_plane[2]);
		EXPECT_GT((b - a).cross(c - a).dot(n), 0);
	}
	EXPECT_NEAR((poly.m_localCenter - btVector3(5, -2, 1)).length(), 0, kGeomTol * 8);
}

TEST(ConvexPolyhedron, ProjectMatchesBruteForceUnderRandomTransforms)
{
	btAlignedObjectArray<btVector3> points;
	srand(1234);
	for (int i = 0; i < 40; ++i)
		points.push_back(
		    btVector3(btScalar(rand() % 2001 - 1000), btScalar(rand() % 2001 - 1000), btScalar(rand() % 2001 - 1000)) /
		    btScalar(1000));
	btConvexPolyhedron poly;
	ASSERT_TRUE(caliber::buildConvexPolyhedron(&points[0], points.size(), poly));
	for (int trial = 0; trial < 50; ++trial)
	{
		const btQuaternion q(btVector3(btScalar(rand() % 200 - 100), btScalar(rand() % 200 - 100), 1).normalized(),
		                     btScalar(rand() % 628) / 100);
		const btTransform t(q, btVector3(btScalar(rand() % 20 - 10), 3, -1));
		const btVector3 dir = btVector3(btScalar(rand() % 200 - 100), btScalar(rand() % 200 - 100), 7).normalized();
		btScalar minP, maxP;
		btVector3 wMin, wMax;
		poly.project(t, dir, minP, maxP, wMin, wMax);
		btScalar bruteMin = SIMD_INFINITY, bruteMax = -SIMD_INFINITY;
		for (int i = 0; i < points.size(); ++i)
		{
			const btScalar d = t(points[i]).dot(dir);
			bruteMin = btMin(bruteMin, d);
			bruteMax = btMax(bruteMax, d);
		}
		// Values of size ~10 through one rotation: a few ulps of 10 each.
		const btScalar tol = btScalar(64) * SIMD_EPSILON * btScalar(10);
		EXPECT_NEAR(minP, bruteMin, tol);
		EXPECT_NEAR(maxP, bruteMax, tol);
		EXPECT_NEAR(wMin.dot(dir), minP, tol);
		EXPECT_NEAR(wMax.dot(dir), maxP, tol);
	}
}

TEST(ConvexPolyhedron, EmptyPolyhedronProjectsToTheOrigin)
{
	btConvexPolyhedron poly;
	poly.initialize();
	EXPECT_EQ(poly.m_uniqueEdges.size(), 0);
	EXPECT_EQ(poly.m_radius, 0);
	const btTransform t(btQuaternion::getIdentity(), btVector3(1, 2, 3));
	btScalar minP = 0, maxP = 0;
	btVector3 wMin, wMax;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(poly.project(t, btVector3(0, 0, 1), minP, maxP, wMin, wMax), "assertion failed");
#else
	poly.project(t, btVector3(0, 0, 1), minP, maxP, wMin, wMax);
	EXPECT_EQ(minP, btScalar(3));
	EXPECT_EQ(maxP, btScalar(3));
	EXPECT_EQ(wMin, t.getOrigin());
	EXPECT_EQ(wMax, t.getOrigin());
#endif
}

TEST(ConvexPolyhedron, DegenerateCloudsGiveNoSolid)
{
	btConvexPolyhedron poly;
	EXPECT_FALSE(caliber::buildConvexPolyhedron(0, 0, poly));
	EXPECT_EQ(poly.m_faces.size(), 0);
	btVector3 two[2] = {btVector3(0, 0, 0), btVector3(1, 0, 0)};
	EXPECT_FALSE(caliber::buildConvexPolyhedron(two, 2, poly));
	EXPECT_EQ(poly.m_vertices.size(), 0);
	// Coplanar points: a flat polygon seen from both sides, no volume, so no solid inertia.
	btVector3 square[4] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(1, 1, 0), btVector3(0, 1, 0)};
	EXPECT_TRUE(caliber::buildConvexPolyhedron(square, 4, poly));
	EXPECT_EQ(poly.m_faces.size(), 2);
	EXPECT_EQ(poly.m_radius, 0);
	EXPECT_NEAR((poly.m_localCenter - btVector3(0.5f, 0.5f, 0)).length(), 0, kGeomTol);
	btVector3 inertia(7, 7, 7);
	EXPECT_FALSE(caliber::solidPolyhedronInertia(poly, 1, inertia));
	EXPECT_EQ(inertia, btVector3(7, 7, 7));
	// NaN points are ignored by the hull.
	btVector3 withNan[5] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1),
	                        btVector3(BT_NAN, 0, 0)};
	EXPECT_TRUE(caliber::buildConvexPolyhedron(withNan, 5, poly));
	EXPECT_EQ(poly.m_vertices.size(), 4);
}

TEST(ConvexPolyhedron, SolidInertiaMatchesAnalyticBoxAndTetrahedron)
{
	// Box with sides a, b, c: Ixx = m (b^2 + c^2) / 12.
	btAlignedObjectArray<btVector3> points;
	boxCorners(btVector3(0.5f, 1, 1.5f), btVector3(3, 4, 5), points);
	btVector3 inertia;
	const btScalar mass = 6;
	ASSERT_TRUE(caliber::solidHullInertia(&points[0], points.size(), mass, inertia));
	// Accumulated in double from float inputs: the result carries the float rounding of the inputs.
	const btScalar tol = btScalar(64) * SIMD_EPSILON * mass * btScalar(13) / 12;
	EXPECT_NEAR(inertia.x(), mass * (4 + 9) / 12, tol);
	EXPECT_NEAR(inertia.y(), mass * (1 + 9) / 12, tol);
	EXPECT_NEAR(inertia.z(), mass * (1 + 4) / 12, tol);

	// Regular tetrahedron with edge L (alternate corners of a cube of side s = L / sqrt 2): every
	// central moment is m L^2 / 20 (isotropic by symmetry).
	btVector3 tetra[4] = {btVector3(1, 1, 1), btVector3(1, -1, -1), btVector3(-1, 1, -1), btVector3(-1, -1, 1)};
	ASSERT_TRUE(caliber::solidHullInertia(tetra, 4, mass, inertia));
	const btScalar edge2 = 8;
	for (int k = 0; k < 3; ++k) EXPECT_NEAR(inertia[k], mass * edge2 / 20, tol);
}
