// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btConvexHull.h"

#include <gtest/gtest.h>

#include <math.h>

#include <map>
#include <utility>
#include <vector>

#include "MathTestUtil.h"

using caliber_test::Random;

namespace
{
// Coordinates are O(1); plane tests chain a cross product and a dot product, so their rounding is a
// few SIMD_EPSILON. 256 SIMD_EPSILON leaves a wide margin without hiding real errors.
const btScalar kPlaneTolerance = btScalar(256) * SIMD_EPSILON;

HullError buildHull(const std::vector<btVector3>& points, HullResult& result, unsigned int flags = QF_DEFAULT,
                    unsigned int maxVertices = 4096, unsigned int maxFaces = 4096)
{
	HullDesc desc(HullFlag(flags), unsigned(points.size()), points.empty() ? 0 : &points[0]);
	desc.mMaxVertices = maxVertices;
	desc.mMaxFaces = maxFaces;
	HullLibrary library;
	return library.CreateConvexHull(desc, result);
}

btVector3 centroidOf(const HullResult& result)
{
	btVector3 sum(0, 0, 0);
	for (int i = 0; i < result.m_OutputVertices.size(); ++i) sum += result.m_OutputVertices[i];
	return sum / btScalar(result.m_OutputVertices.size());
}

btVector3 triangleNormal(const HullResult& result, int t)
{
	const btVector3& a = result.m_OutputVertices[result.m_Indices[3 * t]];
	const btVector3& b = result.m_OutputVertices[result.m_Indices[3 * t + 1]];
	const btVector3& c = result.m_OutputVertices[result.m_Indices[3 * t + 2]];
	return (b - a).cross(c - a);
}

// A closed triangle mesh: counts agree, indices are in range, every directed edge appears once and
// its reverse once, and V - E + F = 2 (so mNumFaces == 2V - 4). Every triangle faces outwards (or
// inwards when reversed): its normal points away from the vertex centroid, which is inside the hull.
void expectClosedTriangleMesh(const HullResult& result, bool reversed)
{
	ASSERT_FALSE(result.mPolygons);
	ASSERT_EQ(result.mNumOutputVertices, unsigned(result.m_OutputVertices.size()));
	ASSERT_EQ(result.mNumIndices, unsigned(result.m_Indices.size()));
	ASSERT_EQ(result.mNumIndices, 3 * result.mNumFaces);
	const unsigned int vertexCount = result.mNumOutputVertices;
	for (int i = 0; i < result.m_Indices.size(); ++i) ASSERT_LT(result.m_Indices[i], vertexCount);
	EXPECT_EQ(result.mNumFaces, 2 * vertexCount - 4);

	std::map<std::pair<unsigned, unsigned>, int> edges;
	for (unsigned int t = 0; t < result.mNumFaces; ++t)
		for (int k = 0; k < 3; ++k) ++edges[{result.m_Indices[3 * t + k], result.m_Indices[3 * t + (k + 1) % 3]}];
	for (const auto& edge : edges)
	{
		EXPECT_EQ(edge.second, 1) << "edge " << edge.first.first << "-" << edge.first.second << " repeats";
		EXPECT_EQ(edges.count({edge.first.second, edge.first.first}), 1u) << "edge without reverse";
	}

	const btVector3 centroid = centroidOf(result);
	for (unsigned int t = 0; t < result.mNumFaces; ++t)
	{
		const btVector3 normal = triangleNormal(result, int(t));
		const btScalar outward = normal.dot(result.m_OutputVertices[result.m_Indices[3 * t]] - centroid);
		if (reversed)
			EXPECT_LT(outward, 0) << "triangle " << t << " faces outwards";
		else
			EXPECT_GT(outward, 0) << "triangle " << t << " faces inwards";
	}
}

// Largest distance of any point outside any triangle plane (0 when all are inside).
btScalar largestOutsideDistance(const HullResult& result, const std::vector<btVector3>& points)
{
	btScalar worst = 0;
	for (unsigned int t = 0; t < result.mNumFaces; ++t)
	{
		const btVector3 normal = triangleNormal(result, int(t)).normalized();
		const btVector3& a = result.m_OutputVertices[result.m_Indices[3 * t]];
		for (const btVector3& p : points) worst = btMax(worst, normal.dot(p - a));
	}
	return worst;
}

bool isInputPoint(const btVector3& v, const std::vector<btVector3>& points)
{
	for (const btVector3& p : points)
		if (p == v) return true;
	return false;
}

std::vector<btVector3> cubeWithInteriorPoints(Random& random)
{
	std::vector<btVector3> points;
	for (int i = 0; i < 60; ++i) points.push_back(random.vector(btScalar(0.9)));
	// Face centres and edge midpoints lie on the hull but are not corners.
	for (int axis = 0; axis < 3; ++axis)
		for (int sign = -1; sign <= 1; sign += 2)
		{
			const btScalar s = btScalar(sign);
			btVector3 faceCentre(0, 0, 0);
			faceCentre[axis] = s;
			points.push_back(faceCentre);
			btVector3 edgeMidpoint(s, s, s);
			edgeMidpoint[axis] = 0;
			points.push_back(edgeMidpoint);
		}
	for (int corner = 0; corner < 8; ++corner)
		points.push_back(btVector3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1));
	return points;
}

void expectEmpty(const HullResult& result)
{
	EXPECT_EQ(result.mNumOutputVertices, 0u);
	EXPECT_EQ(result.mNumFaces, 0u);
	EXPECT_EQ(result.mNumIndices, 0u);
	EXPECT_EQ(result.m_OutputVertices.size(), 0);
	EXPECT_EQ(result.m_Indices.size(), 0);
}
}  // namespace

// The 8 corners of a cube among interior points and points on faces and edges: the hull is exactly
// the 8 corners and 12 outward triangles, and contains every input point.
TEST(ConvexHullLibrary, CubeWithInteriorPointsGivesEightCornersAndTwelveTriangles)
{
	Random random(1);
	const std::vector<btVector3> points = cubeWithInteriorPoints(random);
	HullResult result;
	ASSERT_EQ(buildHull(points, result), QE_OK);
	EXPECT_EQ(result.mNumOutputVertices, 8u);
	EXPECT_EQ(result.mNumFaces, 12u);
	expectClosedTriangleMesh(result, false);
	for (int i = 0; i < result.m_OutputVertices.size(); ++i)
	{
		const btVector3& v = result.m_OutputVertices[i];
		EXPECT_TRUE(btFabs(v.x()) == 1 && btFabs(v.y()) == 1 && btFabs(v.z()) == 1);
	}
	EXPECT_LE(largestOutsideDistance(result, points), kPlaneTolerance);
}

// Random clouds: a closed outward mesh of input points containing every input point.
TEST(ConvexHullLibrary, RandomCloudHullIsClosedOutwardAndContainsAllPoints)
{
	Random random(2026);
	for (int trial = 0; trial < 20; ++trial)
	{
		std::vector<btVector3> points;
		const int count = random.integer(4, 300);
		for (int i = 0; i < count; ++i) points.push_back(random.vector());
		HullResult result;
		SCOPED_TRACE(trial);
		ASSERT_EQ(buildHull(points, result), QE_OK);
		expectClosedTriangleMesh(result, false);
		for (int i = 0; i < result.m_OutputVertices.size(); ++i)
			EXPECT_TRUE(isInputPoint(result.m_OutputVertices[i], points));
		EXPECT_LE(largestOutsideDistance(result, points), kPlaneTolerance);
	}
}

// 1000 points on the unit sphere are all hull corners; with mMaxVertices 32 the reduced hull has
// exactly 32 of them (points on a sphere are always corners of their hull) and stays close to the
// sphere: farthest-point selection spreads them, so no input point is more than 0.2 outside.
TEST(ConvexHullLibrary, SphereCloudRespectsMaxVertices)
{
	Random random(1000);
	std::vector<btVector3> points;
	for (int i = 0; i < 1000; ++i) points.push_back(random.unitVector());
	HullResult result;
	ASSERT_EQ(buildHull(points, result, QF_DEFAULT, 32), QE_OK);
	EXPECT_EQ(result.mNumOutputVertices, 32u);
	expectClosedTriangleMesh(result, false);
	for (int i = 0; i < result.m_OutputVertices.size(); ++i)
		EXPECT_TRUE(isInputPoint(result.m_OutputVertices[i], points));
	const btScalar outside = largestOutsideDistance(result, points);
	EXPECT_LT(outside, btScalar(0.2)) << "reduced hull is a poor fit: a point is " << outside << " outside";

	// Without a limit every point is a corner.
	HullResult full;
	ASSERT_EQ(buildHull(points, full), QE_OK);
	EXPECT_EQ(full.mNumOutputVertices, 1000u);
}

// mMaxFaces limits the triangle count through the vertex count (2V - 4 triangles).
TEST(ConvexHullLibrary, MaxFacesLimitsTriangles)
{
	Random random(3);
	std::vector<btVector3> points;
	for (int i = 0; i < 500; ++i) points.push_back(random.unitVector());
	HullResult result;
	ASSERT_EQ(buildHull(points, result, QF_DEFAULT, 4096, 21), QE_OK);
	EXPECT_LE(result.mNumFaces, 21u);
	EXPECT_EQ(result.mNumOutputVertices, 12u);  // (21 + 4) / 2 rounded down
	expectClosedTriangleMesh(result, false);
}

// QF_REVERSE_ORDER gives the same vertices and triangles with the opposite winding.
TEST(ConvexHullLibrary, ReverseOrderFlipsWinding)
{
	Random random(4);
	std::vector<btVector3> points;
	for (int i = 0; i < 100; ++i) points.push_back(random.vector());
	HullResult forward, reversed;
	ASSERT_EQ(buildHull(points, forward), QE_OK);
	ASSERT_EQ(buildHull(points, reversed, QF_TRIANGLES | QF_REVERSE_ORDER), QE_OK);
	expectClosedTriangleMesh(reversed, true);
	ASSERT_EQ(forward.mNumFaces, reversed.mNumFaces);
	ASSERT_EQ(forward.mNumOutputVertices, reversed.mNumOutputVertices);
	for (unsigned int t = 0; t < forward.mNumFaces; ++t)
	{
		EXPECT_EQ(forward.m_Indices[3 * t], reversed.m_Indices[3 * t]);
		EXPECT_EQ(forward.m_Indices[3 * t + 1], reversed.m_Indices[3 * t + 2]);
		EXPECT_EQ(forward.m_Indices[3 * t + 2], reversed.m_Indices[3 * t + 1]);
	}
}

// Without QF_TRIANGLES the faces come as counted polygons: a cube gives 6 quads.
TEST(ConvexHullLibrary, PolygonOutputWithoutTrianglesFlag)
{
	Random random(5);
	const std::vector<btVector3> points = cubeWithInteriorPoints(random);
	HullResult result;
	ASSERT_EQ(buildHull(points, result, 0), QE_OK);
	EXPECT_TRUE(result.mPolygons);
	EXPECT_EQ(result.mNumFaces, 6u);
	ASSERT_EQ(result.mNumIndices, 30u);
	ASSERT_EQ(result.m_Indices.size(), 30);
	for (int f = 0; f < 6; ++f)
	{
		EXPECT_EQ(result.m_Indices[5 * f], 4u);
		// All four corners share one coordinate: the face's axis.
		const btVector3& first = result.m_OutputVertices[result.m_Indices[5 * f + 1]];
		int sharedAxes = 0;
		for (int axis = 0; axis < 3; ++axis)
		{
			bool shared = true;
			for (int k = 2; k <= 4; ++k)
				if (result.m_OutputVertices[result.m_Indices[5 * f + k]][axis] != first[axis]) shared = false;
			sharedAxes += shared ? 1 : 0;
		}
		EXPECT_EQ(sharedAxes, 1);
	}
}

// Points read through a stride larger than a btVector3 (interleaved with other data).
TEST(ConvexHullLibrary, StrideSkipsInterleavedData)
{
	struct Vertex
	{
		btScalar position[3];
		btScalar colour[2];
	};
	Random random(6);
	std::vector<Vertex> vertices;
	std::vector<btVector3> points;
	for (int i = 0; i < 50; ++i)
	{
		const btVector3 p = random.vector();
		vertices.push_back(Vertex{{p.x(), p.y(), p.z()}, {btScalar(1e30), btScalar(-1e30)}});
		points.push_back(p);
	}
	HullDesc desc(QF_DEFAULT, 50, reinterpret_cast<const btVector3*>(&vertices[0]), sizeof(Vertex));
	HullResult strided, packed;
	HullLibrary library;
	ASSERT_EQ(library.CreateConvexHull(desc, strided), QE_OK);
	ASSERT_EQ(buildHull(points, packed), QE_OK);
	ASSERT_EQ(strided.mNumOutputVertices, packed.mNumOutputVertices);
	for (int i = 0; i < strided.m_OutputVertices.size(); ++i)
		EXPECT_TRUE(strided.m_OutputVertices[i] == packed.m_OutputVertices[i]);
	ASSERT_EQ(strided.m_Indices.size(), packed.m_Indices.size());
	for (int i = 0; i < strided.m_Indices.size(); ++i) EXPECT_EQ(strided.m_Indices[i], packed.m_Indices[i]);
}

// Bad or degenerate input returns QE_FAIL and leaves the result empty, even when it held a hull.
TEST(ConvexHullLibrary, DegenerateInputFailsWithEmptyResult)
{
	Random random(7);
	std::vector<btVector3> good;
	for (int i = 0; i < 20; ++i) good.push_back(random.vector());

	std::vector<btVector3> coplanar, collinear, identical(10, btVector3(1, 2, 3)), three, withNaN = good,
	                                                                                      withInfinity = good;
	for (int i = 0; i < 50; ++i) coplanar.push_back(btVector3(random.uniform(-1, 1), random.uniform(-1, 1), 2));
	for (int i = 0; i < 10; ++i) collinear.push_back(btVector3(1, 2, 3) * btScalar(i));
	three.assign(good.begin(), good.begin() + 3);
	withNaN[7].setY(btScalar(NAN));
	withInfinity[3].setZ(SIMD_INFINITY * 2);

	const std::vector<btVector3>* badInputs[] = {&coplanar, &collinear, &identical, &three, &withNaN, &withInfinity};
	HullLibrary library;
	for (const std::vector<btVector3>* input : badInputs)
	{
		HullResult result;
		ASSERT_EQ(buildHull(good, result), QE_OK);
		EXPECT_EQ(buildHull(*input, result), QE_FAIL) << input->size() << " points";
		expectEmpty(result);
	}

	HullResult result;
	ASSERT_EQ(buildHull(good, result), QE_OK);
	EXPECT_EQ(buildHull(std::vector<btVector3>(), result), QE_FAIL);  // no points (null pointer)
	expectEmpty(result);

	HullDesc nullVertices(QF_DEFAULT, 20, 0);
	EXPECT_EQ(library.CreateConvexHull(nullVertices, result), QE_FAIL);
	expectEmpty(result);

	HullDesc zeroCount(QF_DEFAULT, 0, &good[0]);
	EXPECT_EQ(library.CreateConvexHull(zeroCount, result), QE_FAIL);

	HullDesc shortStride(QF_DEFAULT, 20, &good[0], 2 * sizeof(btScalar));
	EXPECT_EQ(library.CreateConvexHull(shortStride, result), QE_FAIL);

	EXPECT_EQ(buildHull(good, result, QF_DEFAULT, 3), QE_FAIL);        // a solid needs 4 vertices
	EXPECT_EQ(buildHull(good, result, QF_DEFAULT, 4096, 3), QE_FAIL);  // and 4 triangles
	expectEmpty(result);
}

// ReleaseResult empties a result; releasing an empty one is harmless.
TEST(ConvexHullLibrary, ReleaseResultEmptiesResult)
{
	Random random(8);
	std::vector<btVector3> points;
	for (int i = 0; i < 40; ++i) points.push_back(random.vector());
	HullResult result;
	ASSERT_EQ(buildHull(points, result), QE_OK);
	ASSERT_GT(result.mNumFaces, 0u);
	HullLibrary library;
	EXPECT_EQ(library.ReleaseResult(result), QE_OK);
	expectEmpty(result);
	EXPECT_EQ(library.ReleaseResult(result), QE_OK);
	expectEmpty(result);
}

// HullDesc flag helpers and defaults.
TEST(ConvexHullLibrary, HullDescFlagsAndDefaults)
{
	HullDesc desc;
	EXPECT_TRUE(desc.HasHullFlag(QF_TRIANGLES));
	EXPECT_FALSE(desc.HasHullFlag(QF_REVERSE_ORDER));
	desc.SetHullFlag(QF_REVERSE_ORDER);
	EXPECT_TRUE(desc.HasHullFlag(QF_REVERSE_ORDER));
	desc.ClearHullFlag(QF_TRIANGLES);
	EXPECT_FALSE(desc.HasHullFlag(QF_TRIANGLES));
	EXPECT_TRUE(desc.HasHullFlag(QF_REVERSE_ORDER));
	EXPECT_EQ(desc.mVcount, 0u);
	EXPECT_EQ(desc.mVertexStride, unsigned(sizeof(btVector3)));
	EXPECT_EQ(desc.mMaxVertices, 4096u);
	EXPECT_EQ(desc.mMaxFaces, 4096u);
	EXPECT_NEAR(desc.mNormalEpsilon, 0.001, 1e-9);
}
