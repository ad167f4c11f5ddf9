// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhCast.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhSweep.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhWalk.h"

#include "LinearMath/btAabbUtil2.h"

namespace
{
// Half the surface area of a box: the SAH cost weight of a child.
btScalar halfArea(const btVector3& mn, const btVector3& mx)
{
	const btVector3 e = mx - mn;
	if (!(e.x() >= 0) || !(e.y() >= 0) || !(e.z() >= 0)) return 0;
	return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
}

const int kNumBins = 16;

// The bin of a centroid coordinate; NaN and out-of-range values are clamped.
int binOf(btScalar c, btScalar cmin, btScalar binsPerLength)
{
	const btScalar f = (c - cmin) * binsPerLength;
	if (!(f >= 0)) return 0;
	if (!(f < btScalar(kNumBins))) return kNumBins - 1;
	return int(f);
}

struct BuildTask
{
	int node;
	int begin;
	int end;
};

}  // namespace

btQuantizedBvh::btQuantizedBvh()
    : m_bvhAabbMin(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT),
      m_bvhAabbMax(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT),
      m_bvhQuantization(1, 1, 1),
      m_bulletVersion(289),
      m_curNodeIndex(0),
      m_useQuantization(false),
      m_traversalMode(TRAVERSAL_STACKLESS),
      m_subtreeHeaderCount(0)
{
}

btQuantizedBvh::~btQuantizedBvh() {}

void btQuantizedBvh::setQuantizationValues(const btVector3& bvhAabbMin, const btVector3& bvhAabbMax,
                                           btScalar quantizationMargin)
{
	const bool valid = caliber::isFinite(bvhAabbMin) && caliber::isFinite(bvhAabbMax) &&
	                   bvhAabbMin.x() <= bvhAabbMax.x() && bvhAabbMin.y() <= bvhAabbMax.y() &&
	                   bvhAabbMin.z() <= bvhAabbMax.z();
	btAssert(valid && "setQuantizationValues: non-finite or inverted box");
	const btScalar margin =
	    (quantizationMargin > btScalar(0) && btIsFinite(quantizationMargin)) ? quantizationMargin : btScalar(0);
	const btVector3 grow(margin, margin, margin);
	m_bvhAabbMin = valid ? bvhAabbMin - grow : btVector3(-1, -1, -1);
	m_bvhAabbMax = valid ? bvhAabbMax + grow : btVector3(1, 1, 1);
	for (int a = 0; a < 3; ++a)
	{
		// A flat axis would divide by zero; give it unit extent.
		if (!(m_bvhAabbMax[a] - m_bvhAabbMin[a] > btScalar(0)) || !btIsFinite(m_bvhAabbMax[a] - m_bvhAabbMin[a]))
			m_bvhAabbMax[a] = m_bvhAabbMin[a] + btScalar(1);
		// 65533 leaves room for the max corner to round up to an odd value within 16 bits.
		m_bvhQuantization[a] = btScalar(65533) / (m_bvhAabbMax[a] - m_bvhAabbMin[a]);
	}
	m_bvhQuantization[3] = 0;
	m_useQuantization = true;
}

void btQuantizedBvh::buildInternal() { caliber::buildQuantizedBvhTree(*this); }

namespace
{
// The builder's view of the leaves: boxes and centroids (quantized leaves unquantized), and the
// permutation of leaf indices that the splits reorder.
struct LeafSet
{
	btAlignedObjectArray<btVector3> min, max, centroid;
	btAlignedObjectArray<int> order;
};

void gatherLeaves(const btQuantizedBvh& bvh, const caliber::QuantizedBvhParts& p, int numLeaves, LeafSet& leaves)
{
	leaves.min.resize(numLeaves);
	leaves.max.resize(numLeaves);
	leaves.centroid.resize(numLeaves);
	leaves.order.resize(numLeaves);
	for (int i = 0; i < numLeaves; ++i)
	{
		if (p.useQuantization)
		{
			leaves.min[i] = bvh.unQuantize(p.quantizedLeafNodes[i].m_quantizedAabbMin);
			leaves.max[i] = bvh.unQuantize(p.quantizedLeafNodes[i].m_quantizedAabbMax);
		}
		else
		{
			leaves.min[i] = p.leafNodes[i].m_aabbMinOrg;
			leaves.max[i] = p.leafNodes[i].m_aabbMaxOrg;
		}
		leaves.centroid[i] = btScalar(0.5) * (leaves.min[i] + leaves.max[i]);
		leaves.order[i] = i;
	}
}

// The axis a task's leaves are binned along (the longest of their centroids' box) and the binning
// scale; binsPerLength is 0 (or not finite) when the centroids do not spread along it.
struct BinAxis
{
	int axis;
	btScalar origin;
	btScalar binsPerLength;
};

BinAxis chooseBinAxis(const LeafSet& leaves, const BuildTask& task)
{
	btVector3 cmin = leaves.centroid[leaves.order[task.begin]], cmax = cmin;
	for (int i = task.begin + 1; i < task.end; ++i)
	{
		cmin.setMin(leaves.centroid[leaves.order[i]]);
		cmax.setMax(leaves.centroid[leaves.order[i]]);
	}
	const btVector3 extent = cmax - cmin;
	BinAxis bins;
	bins.axis = extent.x() >= extent.y() ? (extent.x() >= extent.z() ? 0 : 2) : (extent.y() >= extent.z() ? 1 : 2);
	bins.origin = cmin[bins.axis];
	bins.binsPerLength = extent[bins.axis] > btScalar(0) ? btScalar(kNumBins) / extent[bins.axis] : btScalar(0);
	return bins;
}

int binOfLeaf(const LeafSet& leaves, int leaf, const BinAxis& bins)
{
	return binOf(leaves.centroid[leaf][bins.axis], bins.origin, bins.binsPerLength);
}

// The last bin of the left group in the cheapest binned SAH split (child count times half area),
// or -1 when every split leaves one side empty.
int cheapestBinSplit(const LeafSet& leaves, const BuildTask& task, const BinAxis& bins)
{
	int binCount[kNumBins];
	btVector3 binMin[kNumBins], binMax[kNumBins];
	for (int b = 0; b < kNumBins; ++b)
	{
		binCount[b] = 0;
		binMin[b].setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
		binMax[b].setValue(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
	}
	for (int i = task.begin; i < task.end; ++i)
	{
		const int leaf = leaves.order[i];
		const int b = binOfLeaf(leaves, leaf, bins);
		binCount[b]++;
		binMin[b].setMin(leaves.min[leaf]);
		binMax[b].setMax(leaves.max[leaf]);
	}
	// Sweep from the right to get the cost of every right-hand group, then from the left.
	btScalar rightCost[kNumBins];
	int rightCount = 0;
	btVector3 rMin(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), rMax = -rMin;
	for (int b = kNumBins - 1; b > 0; --b)
	{
		rightCount += binCount[b];
		rMin.setMin(binMin[b]);
		rMax.setMax(binMax[b]);
		rightCost[b] = btScalar(rightCount) * halfArea(rMin, rMax);
	}
	const int count = task.end - task.begin;
	int leftCount = 0, bestSplit = -1;
	btScalar bestCost = BT_LARGE_FLOAT;
	btVector3 lMin(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), lMax = -lMin;
	for (int b = 0; b < kNumBins - 1; ++b)
	{
		leftCount += binCount[b];
		lMin.setMin(binMin[b]);
		lMax.setMax(binMax[b]);
		if (leftCount == 0 || leftCount == count) continue;
		const btScalar cost = btScalar(leftCount) * halfArea(lMin, lMax) + rightCost[b + 1];
		if (bestSplit < 0 || cost < bestCost)
		{
			bestCost = cost;
			bestSplit = b;
		}
	}
	return bestSplit;
}

// Reorders the task's leaves so that those in bins <= lastLeftBin come first; returns the first of the rest.
int partitionAtBin(LeafSet& leaves, const BuildTask& task, const BinAxis& bins, int lastLeftBin)
{
	int lo = task.begin, hi = task.end - 1;
	while (lo <= hi)
	{
		if (binOfLeaf(leaves, leaves.order[lo], bins) <= lastLeftBin)
			++lo;
		else
		{
			btSwap(leaves.order[lo], leaves.order[hi]);
			--hi;
		}
	}
	return lo;
}

// Splits a task of two or more leaves: returns the first leaf of the right child (after reordering).
int splitTask(LeafSet& leaves, const BuildTask& task)
{
	const int count = task.end - task.begin;
	const BinAxis bins = chooseBinAxis(leaves, task);
	const int equalHalves = task.begin + count / 2;  // fallback: all centroids in one place
	if (!btIsFinite(bins.binsPerLength) || !(bins.binsPerLength > btScalar(0))) return equalHalves;
	const int lastLeftBin = cheapestBinSplit(leaves, task, bins);
	if (lastLeftBin < 0) return equalHalves;
	const int mid = partitionAtBin(leaves, task, bins, lastLeftBin);
	return mid > task.begin && mid < task.end ? mid : equalHalves;
}

// An interior node over count leaves: its escape index skips its 2 count - 1 node subtree.
void writeInteriorNode(const caliber::QuantizedBvhParts& p, int nodeIndex, int count)
{
	if (p.useQuantization)
		p.quantizedContiguousNodes[nodeIndex].m_escapeIndexOrTriangleIndex = -(2 * count - 1);
	else
	{
		btOptimizedBvhNode& node = p.contiguousNodes[nodeIndex];
		node.m_escapeIndex = 2 * count - 1;
		node.m_subPart = -1;
		node.m_triangleIndex = -1;
	}
}

void writeLeafNode(const caliber::QuantizedBvhParts& p, int nodeIndex, int leaf)
{
	if (p.useQuantization)
		p.quantizedContiguousNodes[nodeIndex] = p.quantizedLeafNodes[leaf];
	else
		p.contiguousNodes[nodeIndex] = p.leafNodes[leaf];
}
}  // namespace

// Binned SAH build, top-down with an explicit stack, written depth-first: a node is followed by its
// left subtree, then its right. Interior boxes are filled afterwards by the refit.
void caliber::buildQuantizedBvhTree(btQuantizedBvh& bvh)
{
	const QuantizedBvhParts p = QuantizedBvhAccess::parts(bvh);
	const int numLeaves = p.useQuantization ? p.quantizedLeafNodes.size() : p.leafNodes.size();
	p.contiguousNodes.resize(0);
	p.quantizedContiguousNodes.resize(0);
	p.subtreeHeaders.resize(0);
	p.subtreeHeaderCount = 0;
	p.curNodeIndex = 0;
	if (numLeaves == 0) return;

	LeafSet leaves;
	gatherLeaves(bvh, p, numLeaves, leaves);
	const int numNodes = 2 * numLeaves - 1;
	if (p.useQuantization)
		p.quantizedContiguousNodes.resize(numNodes);
	else
		p.contiguousNodes.resize(numNodes);

	btAlignedObjectArray<BuildTask> stack;
	stack.reserve(64);
	BuildTask root = {0, 0, numLeaves};
	stack.push_back(root);
	while (stack.size())
	{
		const BuildTask task = stack[stack.size() - 1];
		stack.pop_back();
		const int count = task.end - task.begin;
		if (count == 1)
		{
			writeLeafNode(p, task.node, leaves.order[task.begin]);
			continue;
		}
		const int mid = splitTask(leaves, task);
		writeInteriorNode(p, task.node, count);
		// The left subtree (2 leftLeaves - 1 nodes) follows the node, then the right.
		const int leftLeaves = mid - task.begin;
		BuildTask right = {task.node + 2 * leftLeaves, mid, task.end};
		BuildTask left = {task.node + 1, task.begin, mid};
		stack.push_back(right);
		stack.push_back(left);
	}
	p.curNodeIndex = numNodes;
	refitQuantizedBvhInternalNodes(bvh);
	updateQuantizedBvhSubtreeHeaders(bvh);
}

namespace
{
// Grows node nodeIndex's box by its child childIndex's (both in the tree's current format).
void mergeChildIntoNode(const caliber::QuantizedBvhParts& p, int nodeIndex, int childIndex)
{
	if (p.useQuantization)
	{
		btQuantizedBvhNode& node = p.quantizedContiguousNodes[nodeIndex];
		const btQuantizedBvhNode& child = p.quantizedContiguousNodes[childIndex];
		for (int a = 0; a < 3; ++a)
		{
			node.m_quantizedAabbMin[a] = btMin(node.m_quantizedAabbMin[a], child.m_quantizedAabbMin[a]);
			node.m_quantizedAabbMax[a] = btMax(node.m_quantizedAabbMax[a], child.m_quantizedAabbMax[a]);
		}
	}
	else
	{
		btOptimizedBvhNode& node = p.contiguousNodes[nodeIndex];
		const btOptimizedBvhNode& child = p.contiguousNodes[childIndex];
		node.m_aabbMinOrg.setMin(child.m_aabbMinOrg);
		node.m_aabbMaxOrg.setMax(child.m_aabbMaxOrg);
	}
}

}  // namespace

void caliber::setQuantizedBvhNodeFromChildren(btQuantizedBvh& bvh, int nodeIndex)
{
	const QuantizedBvhParts p = QuantizedBvhAccess::parts(bvh);
	const int left = nodeIndex + 1;
	int leftSize;
	if (p.useQuantization)
	{
		btQuantizedBvhNode& node = p.quantizedContiguousNodes[nodeIndex];
		// Start from the empty box (min above max) so that the merge is a plain union.
		for (int a = 0; a < 3; ++a)
		{
			node.m_quantizedAabbMin[a] = 0xFFFE;
			node.m_quantizedAabbMax[a] = 1;
		}
		const btQuantizedBvhNode& l = p.quantizedContiguousNodes[left];
		leftSize = l.isLeafNode() ? 1 : l.getEscapeIndex();
	}
	else
	{
		btOptimizedBvhNode& node = p.contiguousNodes[nodeIndex];
		node.m_aabbMinOrg.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
		node.m_aabbMaxOrg.setValue(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
		const btOptimizedBvhNode& l = p.contiguousNodes[left];
		leftSize = l.m_escapeIndex < 0 ? 1 : l.m_escapeIndex;
	}
	mergeChildIntoNode(p, nodeIndex, left);
	mergeChildIntoNode(p, nodeIndex, left + leftSize);
}

void caliber::refitQuantizedBvhInternalNodes(btQuantizedBvh& bvh)
{
	const QuantizedBvhParts p = QuantizedBvhAccess::parts(bvh);
	for (int i = p.curNodeIndex - 1; i >= 0; --i)
	{
		const bool leaf =
		    p.useQuantization ? p.quantizedContiguousNodes[i].isLeafNode() : p.contiguousNodes[i].m_escapeIndex < 0;
		if (!leaf) setQuantizedBvhNodeFromChildren(bvh, i);
	}
}

void caliber::updateQuantizedBvhSubtreeHeaders(btQuantizedBvh& bvh)
{
	const QuantizedBvhParts p = QuantizedBvhAccess::parts(bvh);
	p.subtreeHeaders.resize(0);
	if (p.useQuantization)
	{
		const int maxNodes = MAX_SUBTREE_SIZE_IN_BYTES / int(sizeof(btQuantizedBvhNode));
		int i = 0;
		while (i < p.curNodeIndex)
		{
			const btQuantizedBvhNode& node = p.quantizedContiguousNodes[i];
			const int size = node.isLeafNode() ? 1 : node.getEscapeIndex();
			if (size > maxNodes)
			{
				++i;  // too big: descend (the left child is next, the right child follows its subtree)
				continue;
			}
			btBvhSubtreeInfo header;
			header.setAabbFromQuantizeNode(node);
			header.m_rootNodeIndex = i;
			header.m_subtreeSize = size;
			p.subtreeHeaders.push_back(header);
			i += size;
		}
	}
	p.subtreeHeaderCount = p.subtreeHeaders.size();
}

void btQuantizedBvh::reportAabbOverlappingNodex(btNodeOverlapCallback* nodeCallback, const btVector3& aabbMin,
                                                const btVector3& aabbMax) const
{
	btAssert(nodeCallback != 0);
	const bool finite = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(finite && "reportAabbOverlappingNodex: non-finite box");
	if (!nodeCallback || !finite || m_curNodeIndex == 0) return;
	if (m_useQuantization)
	{
		// A box outside the quantization box would clamp onto its boundary and falsely touch nodes there.
		if (!TestAabbAgainstAabb2(aabbMin, aabbMax, m_bvhAabbMin, m_bvhAabbMax)) return;
		unsigned short qMin[3], qMax[3];
		quantizeWithClamp(qMin, aabbMin, 0);
		quantizeWithClamp(qMax, aabbMax, 1);
		caliber::walkQuantizedNodes(&m_quantizedContiguousNodes[0], 0, m_curNodeIndex, qMin, qMax, nodeCallback);
		return;
	}
	caliber::walkNodes(&m_contiguousNodes[0], m_curNodeIndex, aabbMin, aabbMax, nodeCallback);
}

void btQuantizedBvh::reportRayOverlappingNodex(btNodeOverlapCallback* nodeCallback, const btVector3& raySource,
                                               const btVector3& rayTarget) const
{
	const btVector3 zero(0, 0, 0);
	reportBoxCastOverlappingNodex(nodeCallback, raySource, rayTarget, zero, zero);
}

void btQuantizedBvh::reportBoxCastOverlappingNodex(btNodeOverlapCallback* nodeCallback, const btVector3& raySource,
                                                   const btVector3& rayTarget, const btVector3& aabbMin,
                                                   const btVector3& aabbMax) const
{
	caliber::reportBoxCastOverlappingNodes(*this, nodeCallback, raySource, rayTarget, aabbMin, aabbMax, 0);
}

void caliber::reportBoxCastOverlappingNodes(const btQuantizedBvh& bvh, btNodeOverlapCallback* nodeCallback,
                                            const btVector3& raySource, const btVector3& rayTarget,
                                            const btVector3& aabbMin, const btVector3& aabbMax,
                                            const btScalar* maxFraction)
{
	if (maxFraction)
	{
		reportBoxCastOverlappingNodesNearestFirst(bvh, nodeCallback, raySource, rayTarget, aabbMin, aabbMax,
		                                          maxFraction);
		return;
	}
	reportBoxCastOverlappingNodesInRange(bvh, nodeCallback, raySource, rayTarget, aabbMin, aabbMax, 0, 0,
	                                     caliber::bvhNodeCount(bvh));
}

void caliber::setUpBvhSweep(const btQuantizedBvh& bvh, const btVector3& raySource, const btVector3& rayTarget,
                            const btVector3& aabbMin, const btVector3& aabbMax, const btScalar* maxFraction,
                            BvhSweep& sweep)
{
	sweep.maxFraction = maxFraction;
	sweep.source = raySource;
	sweep.dir = rayTarget - raySource;
	for (int a = 0; a < 3; ++a) sweep.inv[a] = sweep.dir[a] != btScalar(0) ? btScalar(1) / sweep.dir[a] : btScalar(0);
	btVector3 rootMin, rootMax;
	if (bvh.isQuantized())
	{
		rootMin = caliber::bvhAabbMin(bvh);
		rootMax = caliber::bvhAabbMax(bvh);
	}
	else
	{
		rootMin = caliber::bvhNodeArray(bvh)[0].m_aabbMinOrg;
		rootMax = caliber::bvhNodeArray(bvh)[0].m_aabbMaxOrg;
	}
	btScalar scale = 0;
	const bool rootValid = rootMin.x() <= rootMax.x() && rootMin.y() <= rootMax.y() && rootMin.z() <= rootMax.z();
	const btVector3* scaled[] = {&raySource, &rayTarget, &aabbMin, &aabbMax, &rootMin, &rootMax};
	const int numScaled = rootValid ? 6 : 4;  // a tree of unreadable triangles has an empty (inverted) root
	for (int s = 0; s < numScaled; ++s)
		for (int a = 0; a < 3; ++a) scale = btMax(scale, btFabs((*scaled[s])[a]));
	const btScalar tolerance = btScalar(64) * SIMD_EPSILON * scale;
	const btVector3 tol(tolerance, tolerance, tolerance);
	sweep.growMin = aabbMax + tol;
	sweep.growMax = -aabbMin + tol;
	sweep.sweepMin = raySource;
	sweep.sweepMin.setMin(rayTarget);
	sweep.sweepMax = raySource;
	sweep.sweepMax.setMax(rayTarget);
	sweep.sweepMin += aabbMin - tol;
	sweep.sweepMax += aabbMax + tol;
}

void caliber::reportBoxCastOverlappingNodesInRange(const btQuantizedBvh& bvh, btNodeOverlapCallback* nodeCallback,
                                                   const btVector3& raySource, const btVector3& rayTarget,
                                                   const btVector3& aabbMin, const btVector3& aabbMax,
                                                   const btScalar* maxFraction, int startNode, int endNode)
{
	btAssert(nodeCallback != 0);
	const bool finite = caliber::isFinite(raySource) && caliber::isFinite(rayTarget) && caliber::isFinite(aabbMin) &&
	                    caliber::isFinite(aabbMax);
	btAssert(finite && "reportBoxCastOverlappingNodex: non-finite input");
	if (!nodeCallback || !finite || caliber::bvhNodeCount(bvh) == 0) return;
	const int numNodes = btMin(endNode, caliber::bvhNodeCount(bvh));
	if (startNode < 0) startNode = 0;

	caliber::BvhSweep sweep;
	caliber::setUpBvhSweep(bvh, raySource, rayTarget, aabbMin, aabbMax, maxFraction, sweep);

	if (bvh.isQuantized())
	{
		if (!TestAabbAgainstAabb2(sweep.sweepMin, sweep.sweepMax, caliber::bvhAabbMin(bvh), caliber::bvhAabbMax(bvh)))
			return;
		unsigned short qMin[3], qMax[3];
		bvh.quantizeWithClamp(qMin, sweep.sweepMin, 0);
		bvh.quantizeWithClamp(qMax, sweep.sweepMax, 1);
		// Multiplying by the inverse instead of dividing (unQuantize) rounds once more; the tolerance covers it.
		const btVector3& quantization = caliber::bvhQuantization(bvh);
		const btVector3 invQuantization(btScalar(1) / quantization.x(), btScalar(1) / quantization.y(),
		                                btScalar(1) / quantization.z());
		const btVector3 bvhMin = caliber::bvhAabbMin(bvh);
		// Bullet declares only a non-const accessor of the quantized nodes; they are only read here.
		const btQuantizedBvhNode* nodes = &const_cast<btQuantizedBvh&>(bvh).getQuantizedNodeArray()[0];
		int i = startNode;
		while (i < numNodes)
		{
			const btQuantizedBvhNode& node = nodes[i];
			bool overlap = testQuantizedAabbAgainstQuantizedAabb(qMin, qMax, node.m_quantizedAabbMin,
			                                                     node.m_quantizedAabbMax) != 0;
			if (overlap)
			{
				const unsigned short* lo = node.m_quantizedAabbMin;
				const unsigned short* hi = node.m_quantizedAabbMax;
				const btVector3 nodeMin =
				    btVector3(btScalar(lo[0]), btScalar(lo[1]), btScalar(lo[2])) * invQuantization + bvhMin;
				const btVector3 nodeMax =
				    btVector3(btScalar(hi[0]), btScalar(hi[1]), btScalar(hi[2])) * invQuantization + bvhMin;
				overlap = sweep.hits(nodeMin, nodeMax);
			}
			if (node.isLeafNode())
			{
				if (overlap) nodeCallback->processNode(node.getPartId(), node.getTriangleIndex());
				++i;
			}
			else
				i += overlap ? 1 : node.getEscapeIndex();
		}
		return;
	}
	const btOptimizedBvhNode* nodes = &caliber::bvhNodeArray(bvh)[0];
	int i = startNode;
	while (i < numNodes)
	{
		const btOptimizedBvhNode& node = nodes[i];
		bool overlap = TestAabbAgainstAabb2(sweep.sweepMin, sweep.sweepMax, node.m_aabbMinOrg, node.m_aabbMaxOrg);
		if (overlap) overlap = sweep.hits(node.m_aabbMinOrg, node.m_aabbMaxOrg);
		if (node.m_escapeIndex < 0)
		{
			if (overlap) nodeCallback->processNode(node.m_subPart, node.m_triangleIndex);
			++i;
		}
		else
			i += overlap ? 1 : node.m_escapeIndex;
	}
}
