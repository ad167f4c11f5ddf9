// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btQuantizedBvh's protected helpers, with Bullet's names and meaning, for subclasses that build and walk
// trees of their own leaves: node and leaf accessors, a top-down build (split at the mean centre along the
// axis where the centres vary most), the cache-sized subtree headers and the walks. Caliber's own build
// (binned surface area heuristic) and public queries are in btQuantizedBvh.cpp; both write the same
// depth-first layout, so either tree answers either kind of query.

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"

#include "BulletCollision/BroadphaseCollision/QuantizedBvhCast.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhWalk.h"
#include "LinearMath/btAabbUtil2.h"

namespace
{
bool inRange(int index, int size) { return index >= 0 && index < size; }

// Nodes a subtree rooted at node spans (1 for a leaf).
int subtreeSize(const btQuantizedBvhNode& node) { return node.isLeafNode() ? 1 : node.getEscapeIndex(); }

bool quantizedBoxesOverlap(const btQuantizedBvhNode& a, const btQuantizedBvhNode& b)
{
	return testQuantizedAabbAgainstQuantizedAabb(a.m_quantizedAabbMin, a.m_quantizedAabbMax, b.m_quantizedAabbMin,
	                                             b.m_quantizedAabbMax) != 0;
}
}  // namespace

void btQuantizedBvh::setInternalNodeAabbMin(int nodeIndex, const btVector3& aabbMin)
{
	if (m_useQuantization)
	{
		const bool valid = inRange(nodeIndex, m_quantizedContiguousNodes.size());
		btAssert(valid && "setInternalNodeAabbMin: node index out of range");
		if (valid) quantize(m_quantizedContiguousNodes[nodeIndex].m_quantizedAabbMin, aabbMin, 0);
		return;
	}
	const bool valid = inRange(nodeIndex, m_contiguousNodes.size());
	btAssert(valid && "setInternalNodeAabbMin: node index out of range");
	if (valid) m_contiguousNodes[nodeIndex].m_aabbMinOrg = aabbMin;
}

void btQuantizedBvh::setInternalNodeAabbMax(int nodeIndex, const btVector3& aabbMax)
{
	if (m_useQuantization)
	{
		const bool valid = inRange(nodeIndex, m_quantizedContiguousNodes.size());
		btAssert(valid && "setInternalNodeAabbMax: node index out of range");
		if (valid) quantize(m_quantizedContiguousNodes[nodeIndex].m_quantizedAabbMax, aabbMax, 1);
		return;
	}
	const bool valid = inRange(nodeIndex, m_contiguousNodes.size());
	btAssert(valid && "setInternalNodeAabbMax: node index out of range");
	if (valid) m_contiguousNodes[nodeIndex].m_aabbMaxOrg = aabbMax;
}

btVector3 btQuantizedBvh::getAabbMin(int nodeIndex) const
{
	const int numLeaves = m_useQuantization ? m_quantizedLeafNodes.size() : m_leafNodes.size();
	const bool valid = inRange(nodeIndex, numLeaves);
	btAssert(valid && "getAabbMin: leaf index out of range");
	if (!valid) return btVector3(0, 0, 0);
	return m_useQuantization ? unQuantize(m_quantizedLeafNodes[nodeIndex].m_quantizedAabbMin)
	                         : m_leafNodes[nodeIndex].m_aabbMinOrg;
}

btVector3 btQuantizedBvh::getAabbMax(int nodeIndex) const
{
	const int numLeaves = m_useQuantization ? m_quantizedLeafNodes.size() : m_leafNodes.size();
	const bool valid = inRange(nodeIndex, numLeaves);
	btAssert(valid && "getAabbMax: leaf index out of range");
	if (!valid) return btVector3(0, 0, 0);
	return m_useQuantization ? unQuantize(m_quantizedLeafNodes[nodeIndex].m_quantizedAabbMax)
	                         : m_leafNodes[nodeIndex].m_aabbMaxOrg;
}

void btQuantizedBvh::setInternalNodeEscapeIndex(int nodeIndex, int escapeIndex)
{
	const int numNodes = m_useQuantization ? m_quantizedContiguousNodes.size() : m_contiguousNodes.size();
	// A subtree holds at least its root: 0 or less would make a walk stand still or go back.
	const bool valid = inRange(nodeIndex, numNodes) && escapeIndex > 0;
	btAssert(valid && "setInternalNodeEscapeIndex: node index out of range or escape index not positive");
	if (!valid) return;
	if (m_useQuantization)
		m_quantizedContiguousNodes[nodeIndex].m_escapeIndexOrTriangleIndex = -escapeIndex;
	else
	{
		btOptimizedBvhNode& node = m_contiguousNodes[nodeIndex];
		node.m_escapeIndex = escapeIndex;
		node.m_subPart = -1;
		node.m_triangleIndex = -1;
	}
}

void btQuantizedBvh::mergeInternalNodeAabb(int nodeIndex, const btVector3& newAabbMin, const btVector3& newAabbMax)
{
	if (m_useQuantization)
	{
		const bool valid = inRange(nodeIndex, m_quantizedContiguousNodes.size());
		btAssert(valid && "mergeInternalNodeAabb: node index out of range");
		if (!valid) return;
		unsigned short low[3], high[3];
		quantize(low, newAabbMin, 0);
		quantize(high, newAabbMax, 1);
		btQuantizedBvhNode& node = m_quantizedContiguousNodes[nodeIndex];
		for (int axis = 0; axis < 3; ++axis)
		{
			node.m_quantizedAabbMin[axis] = btMin(node.m_quantizedAabbMin[axis], low[axis]);
			node.m_quantizedAabbMax[axis] = btMax(node.m_quantizedAabbMax[axis], high[axis]);
		}
		return;
	}
	const bool valid = inRange(nodeIndex, m_contiguousNodes.size());
	btAssert(valid && "mergeInternalNodeAabb: node index out of range");
	if (!valid) return;
	m_contiguousNodes[nodeIndex].m_aabbMinOrg.setMin(newAabbMin);
	m_contiguousNodes[nodeIndex].m_aabbMaxOrg.setMax(newAabbMax);
}

void btQuantizedBvh::swapLeafNodes(int firstIndex, int secondIndex)
{
	const int numLeaves = m_useQuantization ? m_quantizedLeafNodes.size() : m_leafNodes.size();
	const bool valid = inRange(firstIndex, numLeaves) && inRange(secondIndex, numLeaves);
	btAssert(valid && "swapLeafNodes: leaf index out of range");
	if (!valid) return;
	if (m_useQuantization)
		m_quantizedLeafNodes.swap(firstIndex, secondIndex);
	else
		m_leafNodes.swap(firstIndex, secondIndex);
}

void btQuantizedBvh::assignInternalNodeFromLeafNode(int internalNode, int leafNodeIndex)
{
	if (m_useQuantization)
	{
		const bool valid = inRange(internalNode, m_quantizedContiguousNodes.size()) &&
		                   inRange(leafNodeIndex, m_quantizedLeafNodes.size());
		btAssert(valid && "assignInternalNodeFromLeafNode: index out of range");
		if (valid) m_quantizedContiguousNodes[internalNode] = m_quantizedLeafNodes[leafNodeIndex];
		return;
	}
	const bool valid = inRange(internalNode, m_contiguousNodes.size()) && inRange(leafNodeIndex, m_leafNodes.size());
	btAssert(valid && "assignInternalNodeFromLeafNode: index out of range");
	if (valid) m_contiguousNodes[internalNode] = m_leafNodes[leafNodeIndex];
}

int btQuantizedBvh::calcSplittingAxis(int startIndex, int endIndex)
{
	const int numLeaves = m_useQuantization ? m_quantizedLeafNodes.size() : m_leafNodes.size();
	const bool valid = 0 <= startIndex && startIndex < endIndex && endIndex <= numLeaves;
	btAssert(valid && "calcSplittingAxis: empty or out-of-range leaf range");
	if (!valid) return 0;
	const btScalar count = btScalar(endIndex - startIndex);
	btVector3 mean(0, 0, 0);
	for (int i = startIndex; i < endIndex; ++i) mean += btScalar(0.5) * (getAabbMin(i) + getAabbMax(i));
	mean /= count;
	btVector3 spread(0, 0, 0);  // sum of squared offsets from the mean: the variance times the count
	for (int i = startIndex; i < endIndex; ++i)
	{
		const btVector3 offset = btScalar(0.5) * (getAabbMin(i) + getAabbMax(i)) - mean;
		spread += offset * offset;
	}
	return spread.maxAxis();
}

int btQuantizedBvh::sortAndCalcSplittingIndex(int startIndex, int endIndex, int splitAxis)
{
	const int numLeaves = m_useQuantization ? m_quantizedLeafNodes.size() : m_leafNodes.size();
	const bool valid =
	    0 <= startIndex && startIndex < endIndex && endIndex <= numLeaves && splitAxis >= 0 && splitAxis < 3;
	btAssert(valid && "sortAndCalcSplittingIndex: empty or out-of-range leaf range, or an axis other than 0, 1, 2");
	if (!valid) return startIndex;
	const int count = endIndex - startIndex;
	btScalar mean = 0;
	for (int i = startIndex; i < endIndex; ++i)
		mean += btScalar(0.5) * (getAabbMin(i)[splitAxis] + getAabbMax(i)[splitAxis]);
	mean /= btScalar(count);
	// Leaves above the mean move to the front, in one pass.
	int split = startIndex;
	for (int i = startIndex; i < endIndex; ++i)
	{
		if (btScalar(0.5) * (getAabbMin(i)[splitAxis] + getAabbMax(i)[splitAxis]) > mean)
		{
			if (i != split) swapLeafNodes(i, split);
			++split;
		}
	}
	// Clustered centres can leave one side nearly empty, and the tree as deep as it has leaves: then the
	// middle, which keeps the depth logarithmic (both sides of two or three leaves always take it).
	const int third = count / 3;
	if (split - startIndex <= third || endIndex - split <= third + 1) split = startIndex + count / 2;
	return split;
}

void btQuantizedBvh::buildTree(int startIndex, int endIndex)
{
	const int numLeaves = m_useQuantization ? m_quantizedLeafNodes.size() : m_leafNodes.size();
	const bool valid = 0 <= startIndex && startIndex < endIndex && endIndex <= numLeaves && m_curNodeIndex >= 0;
	btAssert(valid && "buildTree: empty or out-of-range leaf range");
	if (!valid) return;
	const int count = endIndex - startIndex;
	// Room for the whole subtree at once (the caller usually sized the array for all leaves already).
	const int needed = m_curNodeIndex + 2 * count - 1;
	if (m_useQuantization && m_quantizedContiguousNodes.size() < needed) m_quantizedContiguousNodes.resize(needed);
	if (!m_useQuantization && m_contiguousNodes.size() < needed) m_contiguousNodes.resize(needed);

	if (count == 1)
	{
		assignInternalNodeFromLeafNode(m_curNodeIndex, startIndex);
		++m_curNodeIndex;
		return;
	}
	const int split = sortAndCalcSplittingIndex(startIndex, endIndex, calcSplittingAxis(startIndex, endIndex));
	const int node = m_curNodeIndex;
	// The node's box is the union of its leaves' boxes; quantized leaves are merged as they are stored
	// (unquantizing and quantizing again would widen them by the rounding each time).
	if (m_useQuantization)
	{
		btQuantizedBvhNode& box = m_quantizedContiguousNodes[node];
		box = m_quantizedLeafNodes[startIndex];
		for (int i = startIndex + 1; i < endIndex; ++i)
		{
			const btQuantizedBvhNode& leaf = m_quantizedLeafNodes[i];
			for (int axis = 0; axis < 3; ++axis)
			{
				box.m_quantizedAabbMin[axis] = btMin(box.m_quantizedAabbMin[axis], leaf.m_quantizedAabbMin[axis]);
				box.m_quantizedAabbMax[axis] = btMax(box.m_quantizedAabbMax[axis], leaf.m_quantizedAabbMax[axis]);
			}
		}
	}
	else
	{
		m_contiguousNodes[node].m_aabbMinOrg = m_leafNodes[startIndex].m_aabbMinOrg;
		m_contiguousNodes[node].m_aabbMaxOrg = m_leafNodes[startIndex].m_aabbMaxOrg;
		for (int i = startIndex + 1; i < endIndex; ++i)
			mergeInternalNodeAabb(node, m_leafNodes[i].m_aabbMinOrg, m_leafNodes[i].m_aabbMaxOrg);
	}
	++m_curNodeIndex;
	const int leftChild = m_curNodeIndex;
	buildTree(startIndex, split);
	const int rightChild = m_curNodeIndex;
	buildTree(split, endIndex);
	const int escapeIndex = m_curNodeIndex - node;
	// A subtree too big to stay in cache hands its children's subtrees to the headers.
	if (m_useQuantization && escapeIndex * int(sizeof(btQuantizedBvhNode)) > MAX_SUBTREE_SIZE_IN_BYTES)
		updateSubtreeHeaders(leftChild, rightChild);
	setInternalNodeEscapeIndex(node, escapeIndex);
}

void btQuantizedBvh::updateSubtreeHeaders(int leftChildNodexIndex, int rightChildNodexIndex)
{
	const bool valid = m_useQuantization && inRange(leftChildNodexIndex, m_quantizedContiguousNodes.size()) &&
	                   inRange(rightChildNodexIndex, m_quantizedContiguousNodes.size());
	btAssert(valid && "updateSubtreeHeaders: needs a quantized tree and node indices in range");
	if (!valid) return;
	const int maxNodes = MAX_SUBTREE_SIZE_IN_BYTES / int(sizeof(btQuantizedBvhNode));
	const int children[2] = {leftChildNodexIndex, rightChildNodexIndex};
	for (int c = 0; c < 2; ++c)
	{
		const btQuantizedBvhNode& child = m_quantizedContiguousNodes[children[c]];
		const int size = subtreeSize(child);
		if (size > maxNodes) continue;
		btBvhSubtreeInfo header;
		header.setAabbFromQuantizeNode(child);
		header.m_rootNodeIndex = children[c];
		header.m_subtreeSize = size;
		m_SubtreeHeaders.push_back(header);
	}
	m_subtreeHeaderCount = m_SubtreeHeaders.size();
}

void btQuantizedBvh::walkStacklessTree(btNodeOverlapCallback* nodeCallback, const btVector3& aabbMin,
                                       const btVector3& aabbMax) const
{
	const bool valid = nodeCallback && !m_useQuantization;
	btAssert(valid && "walkStacklessTree: needs a callback and an unquantized tree");
	if (!valid) return;
	const int numNodes = btMin(m_curNodeIndex, m_contiguousNodes.size());
	if (numNodes > 0) caliber::walkNodes(&m_contiguousNodes[0], numNodes, aabbMin, aabbMax, nodeCallback);
}

void btQuantizedBvh::walkStacklessQuantizedTree(btNodeOverlapCallback* nodeCallback,
                                                unsigned short int* quantizedQueryAabbMin,
                                                unsigned short int* quantizedQueryAabbMax, int startNodeIndex,
                                                int endNodeIndex) const
{
	const bool valid = nodeCallback && quantizedQueryAabbMin && quantizedQueryAabbMax && m_useQuantization;
	btAssert(valid && "walkStacklessQuantizedTree: needs a callback, a query box and a quantized tree");
	if (!valid) return;
	const int end = btMin(btMin(endNodeIndex, m_curNodeIndex), m_quantizedContiguousNodes.size());
	if (end <= 0) return;
	const unsigned short low[3] = {quantizedQueryAabbMin[0], quantizedQueryAabbMin[1], quantizedQueryAabbMin[2]};
	const unsigned short high[3] = {quantizedQueryAabbMax[0], quantizedQueryAabbMax[1], quantizedQueryAabbMax[2]};
	caliber::walkQuantizedNodes(&m_quantizedContiguousNodes[0], btMax(startNodeIndex, 0), end, low, high, nodeCallback);
}

void btQuantizedBvh::walkStacklessQuantizedTreeAgainstRay(btNodeOverlapCallback* nodeCallback,
                                                          const btVector3& raySource, const btVector3& rayTarget,
                                                          const btVector3& aabbMin, const btVector3& aabbMax,
                                                          int startNodeIndex, int endNodeIndex) const
{
	btAssert(m_useQuantization && "walkStacklessQuantizedTreeAgainstRay: needs a quantized tree");
	if (!m_useQuantization) return;
	caliber::reportBoxCastOverlappingNodesInRange(*this, nodeCallback, raySource, rayTarget, aabbMin, aabbMax, 0,
	                                              startNodeIndex, endNodeIndex);
}

void btQuantizedBvh::walkStacklessTreeAgainstRay(btNodeOverlapCallback* nodeCallback, const btVector3& raySource,
                                                 const btVector3& rayTarget, const btVector3& aabbMin,
                                                 const btVector3& aabbMax, int startNodeIndex, int endNodeIndex) const
{
	btAssert(!m_useQuantization && "walkStacklessTreeAgainstRay: needs an unquantized tree");
	if (m_useQuantization) return;
	caliber::reportBoxCastOverlappingNodesInRange(*this, nodeCallback, raySource, rayTarget, aabbMin, aabbMax, 0,
	                                              startNodeIndex, endNodeIndex);
}

void btQuantizedBvh::walkStacklessQuantizedTreeCacheFriendly(btNodeOverlapCallback* nodeCallback,
                                                             unsigned short int* quantizedQueryAabbMin,
                                                             unsigned short int* quantizedQueryAabbMax) const
{
	const bool valid = nodeCallback && quantizedQueryAabbMin && quantizedQueryAabbMax && m_useQuantization;
	btAssert(valid && "walkStacklessQuantizedTreeCacheFriendly: needs a callback, a query box and a quantized tree");
	if (!valid) return;
	const int numHeaders = btMin(m_subtreeHeaderCount, m_SubtreeHeaders.size());
	for (int h = 0; h < numHeaders; ++h)
	{
		const btBvhSubtreeInfo& header = m_SubtreeHeaders[h];
		if (!testQuantizedAabbAgainstQuantizedAabb(quantizedQueryAabbMin, quantizedQueryAabbMax,
		                                           header.m_quantizedAabbMin, header.m_quantizedAabbMax))
			continue;
		walkStacklessQuantizedTree(nodeCallback, quantizedQueryAabbMin, quantizedQueryAabbMax, header.m_rootNodeIndex,
		                           header.m_rootNodeIndex + header.m_subtreeSize);
	}
}

void btQuantizedBvh::walkRecursiveQuantizedTreeAgainstQueryAabb(const btQuantizedBvhNode* currentNode,
                                                                btNodeOverlapCallback* nodeCallback,
                                                                unsigned short int* quantizedQueryAabbMin,
                                                                unsigned short int* quantizedQueryAabbMax) const
{
	const bool valid = currentNode && nodeCallback && quantizedQueryAabbMin && quantizedQueryAabbMax;
	btAssert(valid && "walkRecursiveQuantizedTreeAgainstQueryAabb: null node, callback or query box");
	if (!valid) return;
	if (!testQuantizedAabbAgainstQuantizedAabb(quantizedQueryAabbMin, quantizedQueryAabbMax,
	                                           currentNode->m_quantizedAabbMin, currentNode->m_quantizedAabbMax))
		return;
	if (currentNode->isLeafNode())
	{
		nodeCallback->processNode(currentNode->getPartId(), currentNode->getTriangleIndex());
		return;
	}
	// Depth-first: the left child follows its parent, the right child follows the left's subtree.
	const btQuantizedBvhNode* left = currentNode + 1;
	walkRecursiveQuantizedTreeAgainstQueryAabb(left, nodeCallback, quantizedQueryAabbMin, quantizedQueryAabbMax);
	walkRecursiveQuantizedTreeAgainstQueryAabb(left + subtreeSize(*left), nodeCallback, quantizedQueryAabbMin,
	                                           quantizedQueryAabbMax);
}

void btQuantizedBvh::walkRecursiveQuantizedTreeAgainstQuantizedTree(const btQuantizedBvhNode* treeNodeA,
                                                                    const btQuantizedBvhNode* treeNodeB,
                                                                    btNodeOverlapCallback* nodeCallback) const
{
	const bool valid = treeNodeA && treeNodeB && nodeCallback;
	btAssert(valid && "walkRecursiveQuantizedTreeAgainstQuantizedTree: null node or callback");
	if (!valid || !quantizedBoxesOverlap(*treeNodeA, *treeNodeB)) return;
	const bool leafA = treeNodeA->isLeafNode(), leafB = treeNodeB->isLeafNode();
	if (leafA && leafB)
	{
		nodeCallback->processNode(treeNodeA->getPartId(), treeNodeA->getTriangleIndex());
		return;
	}
	// Descend the bigger subtree (B's when A is a leaf), so that both shrink together.
	if (leafA || (!leafB && treeNodeB->getEscapeIndex() > treeNodeA->getEscapeIndex()))
	{
		const btQuantizedBvhNode* left = treeNodeB + 1;
		walkRecursiveQuantizedTreeAgainstQuantizedTree(treeNodeA, left, nodeCallback);
		walkRecursiveQuantizedTreeAgainstQuantizedTree(treeNodeA, left + subtreeSize(*left), nodeCallback);
		return;
	}
	const btQuantizedBvhNode* left = treeNodeA + 1;
	walkRecursiveQuantizedTreeAgainstQuantizedTree(left, treeNodeB, nodeCallback);
	walkRecursiveQuantizedTreeAgainstQuantizedTree(left + subtreeSize(*left), treeNodeB, nodeCallback);
}
