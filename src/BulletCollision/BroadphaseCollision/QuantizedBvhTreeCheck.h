// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_QUANTIZED_BVH_TREE_CHECK_H
#define CALIBER_QUANTIZED_BVH_TREE_CHECK_H

// Internal: the checks that a BVH read from untrusted bytes (a .bullet file, an in-place buffer) is a
// tree every walk and refit can use. Nodes is an adapter with isLeaf(i) and escape(i) (an internal
// node's subtree size); Header has m_rootNodeIndex and m_subtreeSize.

namespace caliber
{
// True when nodes [0, numNodes) form one depth-first tree: the root's subtree is the whole array and
// every internal node's size is one plus the sizes of its two children (the left one right after it,
// the right one after the left's subtree). By induction every escape then lands inside the array.
template <class Nodes>
bool wellFormedBvhTree(const Nodes& n, int numNodes)
{
	if (numNodes == 0) return true;
	const auto size = [&](int i) { return n.isLeaf(i) ? 1LL : n.escape(i); };
	if (size(0) != numNodes) return false;
	for (int i = 0; i < numNodes; ++i)
	{
		if (n.isLeaf(i)) continue;
		const long long e = n.escape(i);
		if (e < 3 || i + e > numNodes) return false;
		const long long left = size(i + 1);
		if (left < 1 || left > e - 2) return false;
		const long long right = size(int(i + 1 + left));
		if (right < 1 || 1 + left + right != e) return false;
	}
	return true;
}

template <class Nodes, class Header>
bool bvhSubtreeHeadersFit(const Nodes& n, int numNodes, const Header* headers, int numHeaders)
{
	for (int h = 0; h < numHeaders; ++h)
	{
		const long long root = headers[h].m_rootNodeIndex, count = headers[h].m_subtreeSize;
		if (root < 0 || root >= numNodes || count < 1 || root + count > numNodes) return false;
		if ((n.isLeaf(int(root)) ? 1LL : n.escape(int(root))) != count) return false;
	}
	return true;
}

}  // namespace caliber

#endif  // CALIBER_QUANTIZED_BVH_TREE_CHECK_H
