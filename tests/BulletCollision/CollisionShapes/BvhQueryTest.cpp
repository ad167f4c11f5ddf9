// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btBvhTriangleMeshShape / btQuantizedBvh queries against brute force over every triangle: box queries,
// ray casts (Moller-Trumbore reference) and box casts, quantized and unquantized, on random meshes
// with several subparts of mixed formats (refit and scaling: BvhRefitTest.cpp).

#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/CollisionShapes/TriangleMeshTestUtil.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"

using namespace mesh_test;

namespace
{
// Three parts in different formats: float/int32/3 components, double/int16/4 components, float/uchar.
void buildMixedMesh(unsigned seed, TestMesh& mesh, int trianglesPerPart = 300)
{
	Random rng(seed);
	for (int p = 0; p < 3; ++p)
	{
		std::vector<btVector3> vertices;
		std::vector<int> indices;
		randomSoup(rng, p == 2 ? 80 : trianglesPerPart, btScalar(10), btScalar(1.5), vertices, indices);
		if (p == 0) mesh.addPart(vertices, indices, PHY_FLOAT, 3, PHY_INTEGER);
		if (p == 1) mesh.addPart(vertices, indices, PHY_DOUBLE, 4, PHY_SHORT);
		if (p == 2) mesh.addPart(vertices, indices, PHY_FLOAT, 4, PHY_UCHAR);
	}
}

// How far a quantized box may reach beyond the true one, per side and axis, in quantization steps:
// rounding down to an even value (or up to an odd one) moves a corner by less than 2 steps, plus the
// 1/16-step safety slack. Both the node box and the query box widen this way, so a reported triangle's
// true box overlaps the query box grown by 2 * 2.0625 steps; 4.25 leaves room for float rounding.
const btScalar kQuantizedReachSteps = btScalar(4.25);

btVector3 quantizationStep(const btBvhTriangleMeshShape& shape)
{
	const btVector3& q = caliber::bvhQuantization(*const_cast<btBvhTriangleMeshShape&>(shape).getOptimizedBvh());
	return btVector3(btScalar(1) / q.x(), btScalar(1) / q.y(), btScalar(1) / q.z());
}

// The ray tolerance of the BVH is 64 eps times the largest coordinate involved; the reference allows 4 times
// that so that the two slab implementations never disagree within rounding.
btScalar rayTolerance(btScalar largestCoordinate) { return btScalar(256) * SIMD_EPSILON * largestCoordinate; }

void checkReportedVertices(const TestMesh& mesh, const Collector& c, const btVector3& scaling)
{
	for (size_t i = 0; i < c.order.size(); ++i)
	{
		btVector3 expected[3];
		mesh.triangle(c.order[i].first, c.order[i].second, scaling, expected);
		for (int k = 0; k < 3; ++k) ASSERT_EQ(expected[k], c.vertices[3 * i + size_t(k)]) << "triangle " << i;
	}
}
}  // namespace

TEST(BvhQueryTest, UnquantizedBoxQueryReturnsExactlyOverlappingTriangles)
{
	for (unsigned seed = 1; seed <= 2; ++seed)
	{
		TestMesh mesh;
		buildMixedMesh(seed, mesh);
		btBvhTriangleMeshShape shape(&mesh.array(), false);
		ASSERT_FALSE(shape.getOptimizedBvh()->isQuantized());
		Random rng(100 + seed);
		for (int q = 0; q < 100; ++q)
		{
			const btVector3 centre = rng.vector(12);
			btVector3 half(rng.uniform(0, 4), rng.uniform(0, 4), rng.uniform(0, 4));
			if (q % 7 == 0) half.setValue(0, 0, 0);  // a point query
			const btVector3 qMin = centre - half, qMax = centre + half;
			TriangleSet expected;
			for (const TriangleKey& k : mesh.allTriangles())
			{
				btVector3 tri[3], tMin, tMax;
				mesh.triangle(k.first, k.second, btVector3(1, 1, 1), tri);
				triangleBox(tri, tMin, tMax);
				if (boxesOverlap(tMin, tMax, qMin, qMax)) expected.insert(k);
			}
			Collector c;
			shape.processAllTriangles(&c, qMin, qMax);
			EXPECT_EQ(0, c.duplicates);
			ASSERT_EQ(expected, c.keys) << "seed " << seed << " query " << q << ": missing"
			                            << describe(minus(expected, c.keys)) << ", extra"
			                            << describe(minus(c.keys, expected));
			checkReportedVertices(mesh, c, btVector3(1, 1, 1));
		}
	}
}

TEST(BvhQueryTest, QuantizedBoxQueryIsConservativeWithinQuantizationStep)
{
	for (unsigned seed = 1; seed <= 2; ++seed)
	{
		TestMesh mesh;
		buildMixedMesh(seed, mesh);
		btBvhTriangleMeshShape shape(&mesh.array(), true);
		ASSERT_TRUE(shape.getOptimizedBvh()->isQuantized());
		const btVector3 reach = kQuantizedReachSteps * quantizationStep(shape);
		Random rng(200 + seed);
		size_t extraTotal = 0, expectedTotal = 0;
		for (int q = 0; q < 100; ++q)
		{
			const btVector3 centre = rng.vector(14);
			btVector3 half(rng.uniform(0, 4), rng.uniform(0, 4), rng.uniform(0, 4));
			if (q % 7 == 0) half.setValue(0, 0, 0);
			const btVector3 qMin = centre - half, qMax = centre + half;
			TriangleSet mustReport, mayReport;
			for (const TriangleKey& k : mesh.allTriangles())
			{
				btVector3 tri[3], tMin, tMax;
				mesh.triangle(k.first, k.second, btVector3(1, 1, 1), tri);
				triangleBox(tri, tMin, tMax);
				if (boxesOverlap(tMin, tMax, qMin, qMax)) mustReport.insert(k);
				if (boxesOverlap(tMin, tMax, qMin, qMax, reach)) mayReport.insert(k);
			}
			Collector c;
			shape.processAllTriangles(&c, qMin, qMax);
			EXPECT_EQ(0, c.duplicates);
			ASSERT_TRUE(minus(mustReport, c.keys).empty())
			    << "seed " << seed << " query " << q << " missed" << describe(minus(mustReport, c.keys));
			ASSERT_TRUE(minus(c.keys, mayReport).empty())
			    << "seed " << seed << " query " << q << " reported beyond the quantization step"
			    << describe(minus(c.keys, mayReport));
			checkReportedVertices(mesh, c, btVector3(1, 1, 1));
			extraTotal += c.keys.size() - mustReport.size();
			expectedTotal += mustReport.size();
		}
		// Quantization adds only the few triangles near the query's faces.
		EXPECT_LT(extraTotal, expectedTotal / 10 + 5) << "seed " << seed;
	}
}

TEST(BvhQueryTest, RaycastReportsEveryTriangleTheRayHits)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		TestMesh mesh;
		buildMixedMesh(7, mesh, 250);
		// A wavy grid as a fourth part gives long rays many exact hits near shared edges and vertices.
		std::vector<btVector3> gridVertices;
		std::vector<int> gridIndices;
		heightGrid(
		    20, 20, [](btScalar x, btScalar y) { return btScalar(0.3) * btSin(x) * btCos(y) - btScalar(11); },
		    gridVertices, gridIndices);
		for (btVector3& v : gridVertices) v -= btVector3(10, 10, 0);
		mesh.addPart(gridVertices, gridIndices, PHY_FLOAT, 3, PHY_INTEGER);
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		const btVector3 step = quantized ? quantizationStep(shape) : btVector3(0, 0, 0);
		Random rng(31);
		int hitsTotal = 0;
		for (int r = 0; r < 120; ++r)
		{
			btVector3 from = rng.vector(14), to = rng.vector(14);
			if (r % 4 == 0)
			{
				// Vertical rays through grid vertices and edges (integer x or y).
				from.setValue(btScalar(int(rng.uniform(-10, 10))), rng.uniform(-10, 10), 5);
				to = from - btVector3(0, 0, 20);
			}
			if (r % 10 == 1) to = from;  // a zero-length ray
			btScalar scale = 14;
			const btVector3 grow = btVector3(1, 1, 1) * rayTolerance(scale) + btScalar(2.1) * step;
			TriangleSet mustReport, mayReport;
			for (const TriangleKey& k : mesh.allTriangles())
			{
				btVector3 tri[3], tMin, tMax;
				mesh.triangle(k.first, k.second, btVector3(1, 1, 1), tri);
				triangleBox(tri, tMin, tMax);
				if (segmentHitsTriangle(from, to, tri)) mustReport.insert(k);
				if (segmentTouchesBox(from, to, tMin - grow, tMax + grow)) mayReport.insert(k);
			}
			Collector c;
			shape.performRaycast(&c, from, to);
			EXPECT_EQ(0, c.duplicates);
			ASSERT_TRUE(minus(mustReport, c.keys).empty())
			    << "quantized " << quantized << " ray " << r << " missed" << describe(minus(mustReport, c.keys));
			ASSERT_TRUE(minus(c.keys, mayReport).empty())
			    << "quantized " << quantized << " ray " << r << " reported boxes the ray misses"
			    << describe(minus(c.keys, mayReport));
			hitsTotal += int(mustReport.size());
		}
		// The rays must actually hit something for the test to mean anything.
		EXPECT_GT(hitsTotal, 60) << "quantized " << quantized;
	}
}

TEST(BvhQueryTest, ConvexcastReportsEveryTriangleTheSweptBoxTouches)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		TestMesh mesh;
		buildMixedMesh(11, mesh);
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		const btVector3 step = quantized ? quantizationStep(shape) : btVector3(0, 0, 0);
		Random rng(41);
		for (int r = 0; r < 100; ++r)
		{
			const btVector3 from = rng.vector(14), to = r % 9 == 0 ? from : rng.vector(14);
			const btVector3 half(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1));
			// An off-centre box: [boxMin, boxMax] need not be symmetric about the moving point.
			const btVector3 offset = btScalar(0.3) * rng.vector(1);
			const btVector3 boxMin = offset - half, boxMax = offset + half;
			const btVector3 grow = btVector3(1, 1, 1) * rayTolerance(16) + btScalar(2.1) * step;
			TriangleSet mustReport, mayReport;
			for (const TriangleKey& k : mesh.allTriangles())
			{
				btVector3 tri[3], tMin, tMax;
				mesh.triangle(k.first, k.second, btVector3(1, 1, 1), tri);
				triangleBox(tri, tMin, tMax);
				// The moving point's box touches the triangle box iff the point is in the box grown by it.
				if (segmentTouchesBox(from, to, tMin - boxMax, tMax - boxMin)) mustReport.insert(k);
				if (segmentTouchesBox(from, to, tMin - boxMax - grow, tMax - boxMin + grow)) mayReport.insert(k);
			}
			Collector c;
			shape.performConvexcast(&c, from, to, boxMin, boxMax);
			EXPECT_EQ(0, c.duplicates);
			ASSERT_TRUE(minus(mustReport, c.keys).empty())
			    << "quantized " << quantized << " cast " << r << " missed" << describe(minus(mustReport, c.keys));
			ASSERT_TRUE(minus(c.keys, mayReport).empty())
			    << "quantized " << quantized << " cast " << r << " extra" << describe(minus(c.keys, mayReport));
		}
	}
}

TEST(BvhQueryTest, TreeHasOneLeafPerTriangleAndParentsContainChildren)
{
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		TestMesh mesh;
		buildMixedMesh(5, mesh);
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		btOptimizedBvh* bvh = shape.getOptimizedBvh();
		const int numTriangles = int(mesh.allTriangles().size());
		ASSERT_EQ(2 * numTriangles - 1, caliber::bvhNodeCount(*bvh));
		TriangleSet leaves;
		int leafCount = 0;
		for (int i = 0; i < caliber::bvhNodeCount(*bvh); ++i)
		{
			if (quantized)
			{
				const btQuantizedBvhNode& n = bvh->getQuantizedNodeArray()[i];
				for (int a = 0; a < 3; ++a)
				{
					EXPECT_EQ(0, n.m_quantizedAabbMin[a] & 1) << "min corners are even";
					EXPECT_EQ(1, n.m_quantizedAabbMax[a] & 1) << "max corners are odd";
				}
				if (n.isLeafNode())
				{
					leaves.insert(TriangleKey(n.getPartId(), n.getTriangleIndex()));
					++leafCount;
					continue;
				}
				const int left = i + 1;
				const btQuantizedBvhNode& l = bvh->getQuantizedNodeArray()[left];
				const int right = left + (l.isLeafNode() ? 1 : l.getEscapeIndex());
				ASSERT_EQ(i + n.getEscapeIndex(), right + (bvh->getQuantizedNodeArray()[right].isLeafNode()
				                                               ? 1
				                                               : bvh->getQuantizedNodeArray()[right].getEscapeIndex()));
				for (int child : {left, right})
				{
					const btQuantizedBvhNode& c = bvh->getQuantizedNodeArray()[child];
					for (int a = 0; a < 3; ++a)
					{
						EXPECT_LE(n.m_quantizedAabbMin[a], c.m_quantizedAabbMin[a]);
						EXPECT_GE(n.m_quantizedAabbMax[a], c.m_quantizedAabbMax[a]);
					}
				}
			}
			else
			{
				const btOptimizedBvhNode& n = caliber::bvhNodeArray(*bvh)[i];
				if (n.m_escapeIndex < 0)
				{
					leaves.insert(TriangleKey(n.m_subPart, n.m_triangleIndex));
					++leafCount;
					continue;
				}
				const int left = i + 1;
				const btOptimizedBvhNode& l = caliber::bvhNodeArray(*bvh)[left];
				const int right = left + (l.m_escapeIndex < 0 ? 1 : l.m_escapeIndex);
				for (int child : {left, right})
				{
					const btOptimizedBvhNode& c = caliber::bvhNodeArray(*bvh)[child];
					for (int a = 0; a < 3; ++a)
					{
						EXPECT_LE(n.m_aabbMinOrg[a], c.m_aabbMinOrg[a]);
						EXPECT_GE(n.m_aabbMaxOrg[a], c.m_aabbMaxOrg[a]);
					}
				}
			}
		}
		EXPECT_EQ(numTriangles, leafCount);
		EXPECT_EQ(size_t(numTriangles), leaves.size());
		if (quantized)
		{
			// Every node lies in exactly one cache-sized subtree or above them.
			int covered = 0;
			for (int h = 0; h < bvh->getSubtreeInfoArray().size(); ++h)
			{
				const btBvhSubtreeInfo& info = bvh->getSubtreeInfoArray()[h];
				EXPECT_LE(info.m_subtreeSize * int(sizeof(btQuantizedBvhNode)), MAX_SUBTREE_SIZE_IN_BYTES);
				covered += info.m_subtreeSize;
			}
			EXPECT_LE(covered, caliber::bvhNodeCount(*bvh));
			EXPECT_GE(covered, numTriangles);
		}
	}
}

TEST(BvhQueryTest, QuantizeRoundsMinDownAndMaxUpWithinTwoSteps)
{
	Random rng(3);
	for (int trial = 0; trial < 20; ++trial)
	{
		btQuantizedBvh bvh;
		const btVector3 lo = rng.vector(1000), size(rng.uniform(btScalar(0.01), 500), rng.uniform(btScalar(0.01), 500),
		                                            rng.uniform(btScalar(0.01), 500));
		bvh.setQuantizationValues(lo, lo + size, 0);
		ASSERT_TRUE(bvh.isQuantized());
		const btVector3 q = caliber::bvhQuantization(bvh);
		for (int i = 0; i < 200; ++i)
		{
			const btVector3 p = lo + btVector3(rng.uniform(0, 1) * size.x(), rng.uniform(0, 1) * size.y(),
			                                   rng.uniform(0, 1) * size.z());
			unsigned short qMin[3], qMax[3];
			bvh.quantize(qMin, p, 0);
			bvh.quantize(qMax, p, 1);
			// The exact quantized coordinate, in double precision: quantization must bracket it.
			for (int a = 0; a < 3; ++a)
			{
				const double exact = (double(p[a]) - double(caliber::bvhAabbMin(bvh)[a])) * double(q[a]);
				EXPECT_EQ(0, qMin[a] & 1);
				EXPECT_EQ(1, qMax[a] & 1);
				EXPECT_LE(double(qMin[a]), exact) << "axis " << a;
				EXPECT_GE(double(qMax[a]), exact) << "axis " << a;
				// Within 2 steps (parity) plus the 1/16 slack plus float rounding of the scaling (< 0.02).
				EXPECT_LE(exact - double(qMin[a]), 2.09) << "axis " << a;
				EXPECT_LE(double(qMax[a]) - exact, 2.09) << "axis " << a;
			}
			// Unquantizing is monotone: the corners bracket the point up to the rounding of the addition.
			const btVector3 down = bvh.unQuantize(qMin), up = bvh.unQuantize(qMax);
			for (int a = 0; a < 3; ++a)
			{
				const btScalar rounding = btScalar(4) * SIMD_EPSILON * btFabs(p[a]);
				EXPECT_LE(down[a], p[a] + rounding);
				EXPECT_GE(up[a], p[a] - rounding);
			}
		}
		// Points outside the box clamp to its faces with quantizeWithClamp.
		unsigned short qOut[3];
		bvh.quantizeWithClamp(qOut, lo - btVector3(5, 5, 5), 0);
		EXPECT_EQ(0, qOut[0]);
		bvh.quantizeWithClamp(qOut, lo + size + btVector3(5, 5, 5), 1);
		EXPECT_EQ(65535, qOut[2]);
	}
}

TEST(BvhQueryTest, LargeGridMeshQueriesMatchBruteForce)
{
	// 2 x 40 x 40 = 3200 triangles: deep enough for many subtree headers and long escape jumps.
	TestMesh mesh;
	std::vector<btVector3> vertices;
	std::vector<int> indices;
	heightGrid(
	    60, 60, [](btScalar x, btScalar y) { return btSin(btScalar(0.2) * x) + btCos(btScalar(0.3) * y); }, vertices,
	    indices);
	mesh.addPart(vertices, indices);
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		btBvhTriangleMeshShape shape(&mesh.array(), quantized != 0);
		const btVector3 reach = quantized ? kQuantizedReachSteps * quantizationStep(shape) : btVector3(0, 0, 0);
		Random rng(8);
		for (int q = 0; q < 20; ++q)
		{
			const btVector3 centre(rng.uniform(-2, 42), rng.uniform(-2, 42), rng.uniform(-3, 3));
			const btVector3 half(rng.uniform(0, 3), rng.uniform(0, 3), rng.uniform(0, 1));
			TriangleSet mustReport, mayReport;
			for (const TriangleKey& k : mesh.allTriangles())
			{
				btVector3 tri[3], tMin, tMax;
				mesh.triangle(k.first, k.second, btVector3(1, 1, 1), tri);
				triangleBox(tri, tMin, tMax);
				if (boxesOverlap(tMin, tMax, centre - half, centre + half)) mustReport.insert(k);
				if (boxesOverlap(tMin, tMax, centre - half, centre + half, reach)) mayReport.insert(k);
			}
			Collector c;
			shape.processAllTriangles(&c, centre - half, centre + half);
			ASSERT_TRUE(minus(mustReport, c.keys).empty()) << "query " << q;
			ASSERT_TRUE(minus(c.keys, mayReport).empty()) << "query " << q;
		}
	}
}

TEST(BvhQueryTest, BuildInternalFromUserLeavesMatchesQuantizedBruteForce)
{
	// btQuantizedBvh on its own: user-quantized leaves, queries compared with the same integer box test.
	struct Reporter : btNodeOverlapCallback
	{
		TriangleSet keys;
		void processNode(int subPart, int triangleIndex) override { keys.insert(TriangleKey(subPart, triangleIndex)); }
	};
	Random rng(77);
	btQuantizedBvh bvh;
	bvh.setQuantizationValues(btVector3(-50, -50, -50), btVector3(50, 50, 50));
	QuantizedNodeArray& leaves = bvh.getLeafNodeArray();
	const int numLeaves = 3000;
	std::vector<btQuantizedBvhNode> copies;
	for (int i = 0; i < numLeaves; ++i)
	{
		btQuantizedBvhNode leaf;
		const btVector3 c = rng.vector(45), h(rng.uniform(0, 2), rng.uniform(0, 2), rng.uniform(0, 2));
		bvh.quantize(leaf.m_quantizedAabbMin, c - h, 0);
		bvh.quantize(leaf.m_quantizedAabbMax, c + h, 1);
		leaf.m_escapeIndexOrTriangleIndex = ((i % 7) << (31 - MAX_NUM_PARTS_IN_BITS)) | i;
		leaves.push_back(leaf);
		copies.push_back(leaf);
	}
	bvh.buildInternal();
	ASSERT_EQ(2 * numLeaves - 1, caliber::bvhNodeCount(bvh));
	for (int q = 0; q < 100; ++q)
	{
		const btVector3 c = rng.vector(55), h(rng.uniform(0, 6), rng.uniform(0, 6), rng.uniform(0, 6));
		unsigned short qMin[3], qMax[3];
		bvh.quantizeWithClamp(qMin, c - h, 0);
		bvh.quantizeWithClamp(qMax, c + h, 1);
		const bool insideBounds = boxesOverlap(c - h, c + h, caliber::bvhAabbMin(bvh), caliber::bvhAabbMax(bvh));
		TriangleSet expected;
		for (const btQuantizedBvhNode& leaf : copies)
		{
			bool overlap = insideBounds;
			for (int a = 0; a < 3; ++a)
				overlap = overlap && leaf.m_quantizedAabbMin[a] <= qMax[a] && leaf.m_quantizedAabbMax[a] >= qMin[a];
			if (overlap) expected.insert(TriangleKey(leaf.getPartId(), leaf.getTriangleIndex()));
		}
		Reporter reporter;
		bvh.reportAabbOverlappingNodex(&reporter, c - h, c + h);
		ASSERT_EQ(expected, reporter.keys) << "query " << q;
	}
}
