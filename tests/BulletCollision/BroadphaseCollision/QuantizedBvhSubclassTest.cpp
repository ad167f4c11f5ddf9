// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btQuantizedBvh's protected helpers, called from a subclass as a Bullet user's would: a tree of the
// subclass's own leaf boxes built with buildTree (quantized and not), its structure (every leaf once,
// parents holding their children, escape indices, cache-sized subtree headers covering every leaf), each
// walk against brute force over the same leaf boxes, the split helpers' meaning, and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"
#include "LinearMath/btAabbUtil2.h"

namespace
{
struct Box
{
	btVector3 min, max;
};

// A leaf's payload: part ids 0..2 and the box's index, so that both fields of the payload are exercised.
int partOf(int leaf) { return leaf % 3; }

std::vector<Box> randomBoxes(unsigned seed, int count, btScalar worldHalf, btScalar maxSize)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<float> position(-float(worldHalf), float(worldHalf));
	std::uniform_real_distribution<float> size(0.0f, float(maxSize));
	std::vector<Box> boxes(count);
	for (Box& box : boxes)
	{
		box.min = btVector3(position(rng), position(rng), position(rng));
		box.max = box.min + btVector3(size(rng), size(rng), size(rng));
	}
	return boxes;
}

// Records the leaves a walk reports: (part, index) -> how many times.
struct Recorder : btNodeOverlapCallback
{
	std::map<std::pair<int, int>, int> hits;
	void processNode(int subPart, int triangleIndex) override { ++hits[std::make_pair(subPart, triangleIndex)]; }
};

// A subclass that builds a tree of its own boxes with Bullet's protected helpers (as Bullet's
// btOptimizedBvh::build does with triangles) and exposes the protected walks.
class BoxTree : public btQuantizedBvh
{
public:
	void build(const std::vector<Box>& boxes, bool quantized)
	{
		const int n = int(boxes.size());
		if (quantized)
		{
			btVector3 low = boxes[0].min, high = boxes[0].max;
			for (const Box& box : boxes)
			{
				low.setMin(box.min);
				high.setMax(box.max);
			}
			setQuantizationValues(low, high);
			for (int i = 0; i < n; ++i)
			{
				btQuantizedBvhNode leaf;
				quantize(leaf.m_quantizedAabbMin, boxes[i].min, 0);
				quantize(leaf.m_quantizedAabbMax, boxes[i].max, 1);
				leaf.m_escapeIndexOrTriangleIndex = (partOf(i) << (31 - MAX_NUM_PARTS_IN_BITS)) | i;
				m_quantizedLeafNodes.push_back(leaf);
			}
			m_quantizedContiguousNodes.resize(2 * n);
		}
		else
		{
			for (int i = 0; i < n; ++i)
			{
				btOptimizedBvhNode leaf;
				leaf.m_aabbMinOrg = boxes[i].min;
				leaf.m_aabbMaxOrg = boxes[i].max;
				leaf.m_escapeIndex = -1;
				leaf.m_subPart = partOf(i);
				leaf.m_triangleIndex = i;
				m_leafNodes.push_back(leaf);
			}
			m_contiguousNodes.resize(2 * n);
		}
		m_curNodeIndex = 0;
		buildTree(0, n);
		// A tree small enough to be one cache-sized subtree got no header below its root: the root's.
		if (quantized && m_SubtreeHeaders.size() == 0)
		{
			btBvhSubtreeInfo header;
			header.setAabbFromQuantizeNode(m_quantizedContiguousNodes[0]);
			header.m_rootNodeIndex = 0;
			header.m_subtreeSize =
			    m_quantizedContiguousNodes[0].isLeafNode() ? 1 : m_quantizedContiguousNodes[0].getEscapeIndex();
			m_SubtreeHeaders.push_back(header);
		}
		m_subtreeHeaderCount = m_SubtreeHeaders.size();
		m_quantizedLeafNodes.clear();
		m_leafNodes.clear();
	}

	int nodeCount() const { return m_curNodeIndex; }
	const QuantizedNodeArray& quantizedNodes() const { return m_quantizedContiguousNodes; }
	const NodeArray& nodes() const { return m_contiguousNodes; }
	const BvhSubtreeInfoArray& headers() const { return m_SubtreeHeaders; }

	void quantizeQuery(const Box& query, unsigned short* low, unsigned short* high) const
	{
		quantizeWithClamp(low, query.min, 0);
		quantizeWithClamp(high, query.max, 1);
	}
	void stackless(Recorder& out, const Box& query) const { walkStacklessTree(&out, query.min, query.max); }
	void stacklessQuantized(Recorder& out, const Box& query) const
	{
		unsigned short low[3], high[3];
		quantizeQuery(query, low, high);
		walkStacklessQuantizedTree(&out, low, high, 0, m_curNodeIndex);
	}
	void cacheFriendly(Recorder& out, const Box& query) const
	{
		unsigned short low[3], high[3];
		quantizeQuery(query, low, high);
		walkStacklessQuantizedTreeCacheFriendly(&out, low, high);
	}
	void recursive(Recorder& out, const Box& query) const
	{
		unsigned short low[3], high[3];
		quantizeQuery(query, low, high);
		walkRecursiveQuantizedTreeAgainstQueryAabb(&m_quantizedContiguousNodes[0], &out, low, high);
	}
	void treeAgainstItself(Recorder& out) const
	{
		walkRecursiveQuantizedTreeAgainstQuantizedTree(&m_quantizedContiguousNodes[0], &m_quantizedContiguousNodes[0],
		                                               &out);
	}
	void ray(Recorder& out, const btVector3& from, const btVector3& to) const
	{
		const btVector3 zero(0, 0, 0);
		if (m_useQuantization)
			walkStacklessQuantizedTreeAgainstRay(&out, from, to, zero, zero, 0, m_curNodeIndex);
		else
			walkStacklessTreeAgainstRay(&out, from, to, zero, zero, 0, m_curNodeIndex);
	}
	// The leaf box as the tree stores it (quantized trees: its quantized corners).
	void storedBox(int leaf, unsigned short* low, unsigned short* high, const Box& box) const
	{
		quantize(low, box.min, 0);
		quantize(high, box.max, 1);
		(void)leaf;
	}

	// The split helpers on leaves that stay in the leaf array.
	void setLeaves(const std::vector<Box>& boxes)
	{
		m_leafNodes.clear();
		for (int i = 0; i < int(boxes.size()); ++i)
		{
			btOptimizedBvhNode leaf;
			leaf.m_aabbMinOrg = boxes[i].min;
			leaf.m_aabbMaxOrg = boxes[i].max;
			leaf.m_escapeIndex = -1;
			leaf.m_subPart = 0;
			leaf.m_triangleIndex = i;
			m_leafNodes.push_back(leaf);
		}
	}
	int splittingAxis(int start, int end) { return calcSplittingAxis(start, end); }
	int split(int start, int end, int axis) { return sortAndCalcSplittingIndex(start, end, axis); }
	int leafIndexAt(int slot) const { return m_leafNodes[slot].m_triangleIndex; }
	btVector3 leafMin(int slot) const { return getAabbMin(slot); }
	btVector3 leafMax(int slot) const { return getAabbMax(slot); }
	void swapLeaves(int a, int b) { swapLeafNodes(a, b); }
	void buildRange(int start, int end) { buildTree(start, end); }
	void setEscape(int node, int escape) { setInternalNodeEscapeIndex(node, escape); }
	void setNodeBox(int node, const btVector3& low, const btVector3& high)
	{
		setInternalNodeAabbMin(node, low);
		setInternalNodeAabbMax(node, high);
	}
	void mergeNodeBox(int node, const btVector3& low, const btVector3& high) { mergeInternalNodeAabb(node, low, high); }
	void copyLeafToNode(int node, int leaf) { assignInternalNodeFromLeafNode(node, leaf); }
	void headersFor(int left, int right) { updateSubtreeHeaders(left, right); }
	void quantizeOn(const btVector3& low, const btVector3& high) { setQuantizationValues(low, high); }
	void useQuantizedLeaves(const std::vector<Box>& boxes)
	{
		m_quantizedLeafNodes.clear();
		for (int i = 0; i < int(boxes.size()); ++i)
		{
			btQuantizedBvhNode leaf;
			quantize(leaf.m_quantizedAabbMin, boxes[i].min, 0);
			quantize(leaf.m_quantizedAabbMax, boxes[i].max, 1);
			leaf.m_escapeIndexOrTriangleIndex = i;
			m_quantizedLeafNodes.push_back(leaf);
		}
	}
	void resizeTree(int nodes) { m_contiguousNodes.resize(nodes); }
};

// Brute force: every box overlapping the query, each once. Quantized trees compare their quantized boxes
// (the tree's own and conservative answer), unquantized ones the boxes themselves.
std::map<std::pair<int, int>, int> bruteForce(const BoxTree& tree, const std::vector<Box>& boxes, const Box& query,
                                              bool quantized)
{
	std::map<std::pair<int, int>, int> expected;
	unsigned short qLow[3], qHigh[3];
	if (quantized) tree.quantizeQuery(query, qLow, qHigh);
	for (int i = 0; i < int(boxes.size()); ++i)
	{
		bool overlap;
		if (quantized)
		{
			unsigned short low[3], high[3];
			tree.storedBox(i, low, high, boxes[i]);
			overlap = testQuantizedAabbAgainstQuantizedAabb(qLow, qHigh, low, high) != 0;
		}
		else
			overlap = TestAabbAgainstAabb2(query.min, query.max, boxes[i].min, boxes[i].max);
		if (overlap) expected[std::make_pair(partOf(i), i)] = 1;
	}
	return expected;
}

// Every leaf once, each internal node's box holding its children's, and escape indices adding up.
void expectWellFormed(const BoxTree& tree, int numLeaves, bool quantized)
{
	ASSERT_EQ(tree.nodeCount(), 2 * numLeaves - 1);
	std::vector<int> seen(numLeaves, 0);
	for (int i = 0; i < tree.nodeCount(); ++i)
	{
		if (quantized)
		{
			const btQuantizedBvhNode& node = tree.quantizedNodes()[i];
			if (node.isLeafNode())
			{
				ASSERT_GE(node.getTriangleIndex(), 0);
				ASSERT_LT(node.getTriangleIndex(), numLeaves);
				EXPECT_EQ(node.getPartId(), partOf(node.getTriangleIndex()));
				++seen[node.getTriangleIndex()];
				continue;
			}
			const btQuantizedBvhNode& left = tree.quantizedNodes()[i + 1];
			const int leftSize = left.isLeafNode() ? 1 : left.getEscapeIndex();
			const btQuantizedBvhNode& right = tree.quantizedNodes()[i + 1 + leftSize];
			const int rightSize = right.isLeafNode() ? 1 : right.getEscapeIndex();
			EXPECT_EQ(node.getEscapeIndex(), 1 + leftSize + rightSize) << "node " << i;
			for (int a = 0; a < 3; ++a)
			{
				EXPECT_LE(node.m_quantizedAabbMin[a], btMin(left.m_quantizedAabbMin[a], right.m_quantizedAabbMin[a]));
				EXPECT_GE(node.m_quantizedAabbMax[a], btMax(left.m_quantizedAabbMax[a], right.m_quantizedAabbMax[a]));
			}
		}
		else
		{
			const btOptimizedBvhNode& node = tree.nodes()[i];
			if (node.m_escapeIndex < 0)
			{
				ASSERT_GE(node.m_triangleIndex, 0);
				ASSERT_LT(node.m_triangleIndex, numLeaves);
				EXPECT_EQ(node.m_subPart, partOf(node.m_triangleIndex));
				++seen[node.m_triangleIndex];
				continue;
			}
			const btOptimizedBvhNode& left = tree.nodes()[i + 1];
			const int leftSize = left.m_escapeIndex < 0 ? 1 : left.m_escapeIndex;
			const btOptimizedBvhNode& right = tree.nodes()[i + 1 + leftSize];
			const int rightSize = right.m_escapeIndex < 0 ? 1 : right.m_escapeIndex;
			EXPECT_EQ(node.m_escapeIndex, 1 + leftSize + rightSize) << "node " << i;
			for (int a = 0; a < 3; ++a)
			{
				EXPECT_LE(node.m_aabbMinOrg[a], btMin(left.m_aabbMinOrg[a], right.m_aabbMinOrg[a]));
				EXPECT_GE(node.m_aabbMaxOrg[a], btMax(left.m_aabbMaxOrg[a], right.m_aabbMaxOrg[a]));
			}
		}
	}
	for (int i = 0; i < numLeaves; ++i) EXPECT_EQ(seen[i], 1) << "leaf " << i;
}

void expectSame(const Recorder& walk, const std::map<std::pair<int, int>, int>& expected, const char* name)
{
	EXPECT_EQ(walk.hits, expected) << name << ": " << walk.hits.size() << " leaves reported, " << expected.size()
	                               << " expected";
}

// Queries of mixed sizes: small (a few leaves), large (many), and one beyond every box.
std::vector<Box> queries(unsigned seed)
{
	std::vector<Box> result = randomBoxes(seed, 40, btScalar(60), btScalar(15));
	std::vector<Box> large = randomBoxes(seed + 1, 5, btScalar(30), btScalar(80));
	result.insert(result.end(), large.begin(), large.end());
	result.push_back(Box{btVector3(500, 500, 500), btVector3(501, 501, 501)});
	return result;
}
}  // namespace

TEST(QuantizedBvhSubclass, UnquantizedTreeBuiltWithBuildTreeIsWellFormedAndEveryWalkMatchesBruteForce)
{
	const std::vector<Box> boxes = randomBoxes(7, 700, btScalar(50), btScalar(4));
	BoxTree tree;
	tree.build(boxes, false);
	expectWellFormed(tree, int(boxes.size()), false);
	for (const Box& query : queries(11))
	{
		const std::map<std::pair<int, int>, int> expected = bruteForce(tree, boxes, query, false);
		Recorder stackless, reported;
		tree.stackless(stackless, query);
		tree.reportAabbOverlappingNodex(&reported, query.min, query.max);
		expectSame(stackless, expected, "walkStacklessTree");
		expectSame(reported, expected, "reportAabbOverlappingNodex");
	}
}

TEST(QuantizedBvhSubclass, QuantizedTreeBuiltWithBuildTreeIsWellFormedAndEveryWalkMatchesBruteForce)
{
	const std::vector<Box> boxes = randomBoxes(3, 1000, btScalar(50), btScalar(4));
	BoxTree tree;
	tree.build(boxes, true);
	expectWellFormed(tree, int(boxes.size()), true);
	for (const Box& query : queries(5))
	{
		const std::map<std::pair<int, int>, int> expected = bruteForce(tree, boxes, query, true);
		Recorder stackless, cacheFriendly, recursive, reported;
		tree.stacklessQuantized(stackless, query);
		tree.cacheFriendly(cacheFriendly, query);
		tree.recursive(recursive, query);
		tree.reportAabbOverlappingNodex(&reported, query.min, query.max);
		expectSame(stackless, expected, "walkStacklessQuantizedTree");
		expectSame(cacheFriendly, expected, "walkStacklessQuantizedTreeCacheFriendly");
		expectSame(recursive, expected, "walkRecursiveQuantizedTreeAgainstQueryAabb");
		// The public query also rejects boxes outside the quantization box before quantizing; inside it,
		// the same leaves.
		if (TestAabbAgainstAabb2(query.min, query.max, btVector3(-60, -60, -60), btVector3(60, 60, 60)))
			expectSame(reported, expected, "reportAabbOverlappingNodex");
	}
}

TEST(QuantizedBvhSubclass, LargeQuantizedTreeHasCacheSizedSubtreeHeadersThatCoverEveryLeafOnce)
{
	const std::vector<Box> boxes = randomBoxes(9, 1000, btScalar(50), btScalar(4));
	BoxTree tree;
	tree.build(boxes, true);
	// 1999 nodes of 16 bytes do not fit in one 2048-byte subtree: several headers, each at most 128 nodes.
	ASSERT_GT(tree.headers().size(), 1);
	std::vector<int> covered(boxes.size(), 0);
	for (int h = 0; h < tree.headers().size(); ++h)
	{
		const btBvhSubtreeInfo& header = tree.headers()[h];
		EXPECT_LE(header.m_subtreeSize * int(sizeof(btQuantizedBvhNode)), MAX_SUBTREE_SIZE_IN_BYTES);
		const btQuantizedBvhNode& root = tree.quantizedNodes()[header.m_rootNodeIndex];
		EXPECT_EQ(header.m_subtreeSize, root.isLeafNode() ? 1 : root.getEscapeIndex());
		for (int a = 0; a < 3; ++a)
		{
			EXPECT_EQ(header.m_quantizedAabbMin[a], root.m_quantizedAabbMin[a]);
			EXPECT_EQ(header.m_quantizedAabbMax[a], root.m_quantizedAabbMax[a]);
		}
		for (int i = header.m_rootNodeIndex; i < header.m_rootNodeIndex + header.m_subtreeSize; ++i)
			if (tree.quantizedNodes()[i].isLeafNode()) ++covered[tree.quantizedNodes()[i].getTriangleIndex()];
	}
	for (int i = 0; i < int(boxes.size()); ++i) EXPECT_EQ(covered[i], 1) << "leaf " << i;
}

TEST(QuantizedBvhSubclass, RayWalksReportEveryBoxTheSegmentCrossesAndAgreeWithThePublicRayQuery)
{
	const std::vector<Box> boxes = randomBoxes(21, 500, btScalar(50), btScalar(6));
	std::mt19937 rng(4);
	std::uniform_real_distribution<float> position(-70.0f, 70.0f);
	for (int quantized = 0; quantized < 2; ++quantized)
	{
		BoxTree tree;
		tree.build(boxes, quantized != 0);
		for (int r = 0; r < 30; ++r)
		{
			const btVector3 from(position(rng), position(rng), position(rng));
			const btVector3 to(position(rng), position(rng), position(rng));
			Recorder walk, reported;
			tree.ray(walk, from, to);
			tree.reportRayOverlappingNodex(&reported, from, to);
			EXPECT_EQ(walk.hits, reported.hits);
			// A box the segment crosses well inside (its box shrunk by 1 mm still hit) must be reported.
			for (int i = 0; i < int(boxes.size()); ++i)
			{
				btScalar lambda = 1;
				btVector3 normal;
				const btVector3 shrink(btScalar(1e-3), btScalar(1e-3), btScalar(1e-3));
				if (btRayAabb(from, to, boxes[i].min + shrink, boxes[i].max - shrink, lambda, normal))
				{
					EXPECT_EQ(walk.hits.count(std::make_pair(partOf(i), i)), 1u)
					    << "box " << i << " quantized " << quantized;
				}
			}
		}
	}
}

TEST(QuantizedBvhSubclass, TreeAgainstItselfReportsEachLeafOncePerOverlappingLeaf)
{
	const std::vector<Box> boxes = randomBoxes(13, 300, btScalar(20), btScalar(4));
	BoxTree tree;
	tree.build(boxes, true);
	Recorder pairs;
	tree.treeAgainstItself(pairs);
	std::map<std::pair<int, int>, int> expected;
	for (int a = 0; a < int(boxes.size()); ++a)
	{
		unsigned short lowA[3], highA[3];
		tree.storedBox(a, lowA, highA, boxes[a]);
		for (int b = 0; b < int(boxes.size()); ++b)
		{
			unsigned short lowB[3], highB[3];
			tree.storedBox(b, lowB, highB, boxes[b]);
			if (testQuantizedAabbAgainstQuantizedAabb(lowA, highA, lowB, highB))
				++expected[std::make_pair(partOf(a), a)];
		}
	}
	EXPECT_EQ(pairs.hits, expected);
}

TEST(QuantizedBvhSubclass, SplitHelpersPickTheAxisOfMostSpreadAndPartitionAtTheMean)
{
	BoxTree tree;
	// Centres spread along y (x and z nearly fixed): y is the splitting axis.
	std::vector<Box> boxes;
	for (int i = 0; i < 8; ++i)
	{
		const btVector3 centre(btScalar(i % 2) * btScalar(0.1), btScalar(i), btScalar(0.05) * btScalar(i % 3));
		boxes.push_back(Box{centre - btVector3(0.5, 0.5, 0.5), centre + btVector3(0.5, 0.5, 0.5)});
	}
	tree.setLeaves(boxes);
	EXPECT_EQ(tree.splittingAxis(0, 8), 1);
	// Mean centre y = 3.5: the four above it (4..7) come first, the split is at 4.
	const int split = tree.split(0, 8, 1);
	EXPECT_EQ(split, 4);
	for (int slot = 0; slot < 8; ++slot)
		EXPECT_EQ(tree.leafIndexAt(slot) >= 4, slot < split)
		    << "slot " << slot << " holds leaf " << tree.leafIndexAt(slot);
	// Nine leaves at the origin and one far away: only one above the mean, which would leave a side with
	// less than a third; the middle instead.
	std::vector<Box> clustered(9, Box{btVector3(-1, -1, -1), btVector3(1, 1, 1)});
	clustered.push_back(Box{btVector3(99, -1, -1), btVector3(101, 1, 1)});
	tree.setLeaves(clustered);
	EXPECT_EQ(tree.splittingAxis(0, 10), 0);
	EXPECT_EQ(tree.split(0, 10, 0), 5);
	// The far leaf, the only one above the mean, was moved to the front; its corners read back as stored.
	EXPECT_EQ(tree.leafIndexAt(0), 9);
	EXPECT_EQ(tree.leafMin(0), clustered[9].min);
	EXPECT_EQ(tree.leafMax(0), clustered[9].max);
}

TEST(QuantizedBvhSubclass, NodeSettersWriteBoxesEscapeIndicesAndLeafCopies)
{
	BoxTree tree;
	const std::vector<Box> boxes = {Box{btVector3(0, 0, 0), btVector3(1, 1, 1)},
	                                Box{btVector3(2, 2, 2), btVector3(3, 3, 3)}};
	tree.setLeaves(boxes);
	tree.resizeTree(3);
	tree.setNodeBox(0, btVector3(0, 0, 0), btVector3(1, 1, 1));
	tree.mergeNodeBox(0, btVector3(-1, 2, 0), btVector3(0, 5, 0));
	EXPECT_EQ(tree.nodes()[0].m_aabbMinOrg, btVector3(-1, 0, 0));
	EXPECT_EQ(tree.nodes()[0].m_aabbMaxOrg, btVector3(1, 5, 1));
	tree.setEscape(0, 3);
	EXPECT_EQ(tree.nodes()[0].m_escapeIndex, 3);
	tree.copyLeafToNode(2, 1);
	EXPECT_EQ(tree.nodes()[2].m_aabbMinOrg, boxes[1].min);
	EXPECT_EQ(tree.nodes()[2].m_triangleIndex, 1);
	tree.swapLeaves(0, 1);
	EXPECT_EQ(tree.leafMin(0), boxes[1].min);
	EXPECT_EQ(tree.leafIndexAt(1), 0);

	// Quantized: corners round outwards (min down to an even value, max up to an odd one), by less than
	// two quantization steps plus the 1/16-step slack (2.1 steps leaves room for float rounding).
	BoxTree quantized;
	quantized.quantizeOn(btVector3(-10, -10, -10), btVector3(10, 10, 10));
	quantized.useQuantizedLeaves(boxes);
	const btScalar step = btScalar(22) / btScalar(65533);  // the box grown by the default margin 1
	for (int a = 0; a < 3; ++a)
	{
		EXPECT_LE(quantized.leafMin(1)[a], boxes[1].min[a]);
		EXPECT_GT(quantized.leafMin(1)[a], boxes[1].min[a] - btScalar(2.1) * step);
		EXPECT_GE(quantized.leafMax(1)[a], boxes[1].max[a]);
		EXPECT_LT(quantized.leafMax(1)[a], boxes[1].max[a] + btScalar(2.1) * step);
	}
}

#if CALIBER_ASSERTS_ENABLED
TEST(QuantizedBvhSubclassDeathTest, BadRangesIndicesAndWrongKindsOfTreeAssert)
{
	BoxTree tree;
	tree.setLeaves(randomBoxes(1, 4, btScalar(10), btScalar(1)));
	tree.resizeTree(7);
	EXPECT_DEATH(tree.buildRange(0, 0), "assertion failed");
	EXPECT_DEATH(tree.buildRange(2, 5), "assertion failed");
	EXPECT_DEATH(tree.split(0, 4, 3), "assertion failed");
	EXPECT_DEATH(tree.splittingAxis(3, 2), "assertion failed");
	EXPECT_DEATH(tree.leafMin(4), "assertion failed");
	EXPECT_DEATH(tree.swapLeaves(-1, 0), "assertion failed");
	EXPECT_DEATH(tree.setEscape(0, 0), "assertion failed");
	EXPECT_DEATH(tree.setEscape(7, 3), "assertion failed");
	EXPECT_DEATH(tree.copyLeafToNode(0, 9), "assertion failed");
	EXPECT_DEATH(tree.headersFor(1, 2), "assertion failed");  // an unquantized tree has no headers
	Recorder out;
	BoxTree quantized;
	quantized.build(randomBoxes(2, 10, btScalar(10), btScalar(1)), true);
	const Box query{btVector3(-1, -1, -1), btVector3(1, 1, 1)};
	EXPECT_DEATH(quantized.stackless(out, query), "assertion failed");  // the unquantized walk
}
#else
TEST(QuantizedBvhSubclass, BadRangesIndicesAndWrongKindsOfTreeChangeNothingInRelease)
{
	const std::vector<Box> boxes = randomBoxes(1, 4, btScalar(10), btScalar(1));
	BoxTree tree;
	tree.setLeaves(boxes);
	tree.resizeTree(7);
	tree.buildRange(0, 0);
	tree.buildRange(2, 5);
	EXPECT_EQ(tree.nodeCount(), 0) << "nothing built";
	EXPECT_EQ(tree.split(0, 4, 3), 0) << "the range's start";
	EXPECT_EQ(tree.splittingAxis(3, 2), 0);
	EXPECT_EQ(tree.leafMin(4), btVector3(0, 0, 0));
	tree.swapLeaves(-1, 0);
	for (int i = 0; i < 4; ++i) EXPECT_EQ(tree.leafIndexAt(i), i) << "no leaf moved";
	const int escapeBefore = tree.nodes()[0].m_escapeIndex;
	tree.setEscape(0, 0);
	tree.setEscape(7, 3);
	EXPECT_EQ(tree.nodes()[0].m_escapeIndex, escapeBefore);
	tree.copyLeafToNode(0, 9);
	tree.headersFor(1, 2);
	EXPECT_EQ(tree.headers().size(), 0);
	Recorder out;
	BoxTree quantized;
	quantized.build(randomBoxes(2, 10, btScalar(10), btScalar(1)), true);
	quantized.stackless(out, Box{btVector3(-1, -1, -1), btVector3(1, 1, 1)});
	EXPECT_TRUE(out.hits.empty()) << "the unquantized walk reports nothing on a quantized tree";
}
#endif
