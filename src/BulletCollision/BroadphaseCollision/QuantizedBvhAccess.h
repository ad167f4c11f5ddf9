// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_QUANTIZED_BVH_ACCESS_H
#define CALIBER_QUANTIZED_BVH_ACCESS_H

// Internal: reading the parts of a btQuantizedBvh that Bullet keeps protected (the unquantized nodes,
// the node count, the quantization box), for Caliber's own walks, tests and benchmarks, without adding
// accessors to Bullet's class.

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"

namespace caliber
{
/// References to a btQuantizedBvh's protected members, for Caliber's build and refit code.
struct QuantizedBvhParts
{
	int& curNodeIndex;
	bool& useQuantization;
	NodeArray& leafNodes;
	NodeArray& contiguousNodes;
	QuantizedNodeArray& quantizedLeafNodes;
	QuantizedNodeArray& quantizedContiguousNodes;
	BvhSubtreeInfoArray& subtreeHeaders;
	int& subtreeHeaderCount;
};

// A pointer to a protected member, formed in a derived class, may be applied to any btQuantizedBvh: the
// class is never instantiated, it only names the members.
struct QuantizedBvhAccess : btQuantizedBvh
{
	static const NodeArray& nodes(const btQuantizedBvh& bvh) { return bvh.*(&QuantizedBvhAccess::m_contiguousNodes); }
	static int nodeCount(const btQuantizedBvh& bvh) { return bvh.*(&QuantizedBvhAccess::m_curNodeIndex); }
	static const btVector3& aabbMin(const btQuantizedBvh& bvh) { return bvh.*(&QuantizedBvhAccess::m_bvhAabbMin); }
	static const btVector3& aabbMax(const btQuantizedBvh& bvh) { return bvh.*(&QuantizedBvhAccess::m_bvhAabbMax); }
	static const btVector3& quantization(const btQuantizedBvh& bvh)
	{
		return bvh.*(&QuantizedBvhAccess::m_bvhQuantization);
	}
	static QuantizedBvhParts parts(btQuantizedBvh& bvh);
};

/// The unquantized tree, depth-first (empty for quantized BVHs).
inline const NodeArray& bvhNodeArray(const btQuantizedBvh& bvh) { return QuantizedBvhAccess::nodes(bvh); }
/// Number of nodes in the tree (0 when empty; 2n - 1 for n leaves).
inline int bvhNodeCount(const btQuantizedBvh& bvh) { return QuantizedBvhAccess::nodeCount(bvh); }
/// Minimum corner of the quantization box.
inline const btVector3& bvhAabbMin(const btQuantizedBvh& bvh) { return QuantizedBvhAccess::aabbMin(bvh); }
/// Maximum corner of the quantization box.
inline const btVector3& bvhAabbMax(const btQuantizedBvh& bvh) { return QuantizedBvhAccess::aabbMax(bvh); }
/// Quantized units per length unit, per axis.
inline const btVector3& bvhQuantization(const btQuantizedBvh& bvh) { return QuantizedBvhAccess::quantization(bvh); }
inline QuantizedBvhParts QuantizedBvhAccess::parts(btQuantizedBvh& bvh)
{
	QuantizedBvhParts p = {
	    bvh.*(&QuantizedBvhAccess::m_curNodeIndex),       bvh.*(&QuantizedBvhAccess::m_useQuantization),
	    bvh.*(&QuantizedBvhAccess::m_leafNodes),          bvh.*(&QuantizedBvhAccess::m_contiguousNodes),
	    bvh.*(&QuantizedBvhAccess::m_quantizedLeafNodes), bvh.*(&QuantizedBvhAccess::m_quantizedContiguousNodes),
	    bvh.*(&QuantizedBvhAccess::m_SubtreeHeaders),     bvh.*(&QuantizedBvhAccess::m_subtreeHeaderCount)};
	return p;
}

/// Builds bvh's tree from the leaf array matching its quantization (the leaf order is not kept), then
/// its boxes and subtree headers.
void buildQuantizedBvhTree(btQuantizedBvh& bvh);
/// Recomputes the boxes of bvh's internal nodes from their children, from the last node to the first.
void refitQuantizedBvhInternalNodes(btQuantizedBvh& bvh);
/// Sets internal node nodeIndex's box to the union of its two children's.
void setQuantizedBvhNodeFromChildren(btQuantizedBvh& bvh, int nodeIndex);
/// Recomputes the headers of bvh's cache-sized subtrees (quantized trees).
void updateQuantizedBvhSubtreeHeaders(btQuantizedBvh& bvh);
}  // namespace caliber

#endif  // CALIBER_QUANTIZED_BVH_ACCESS_H
