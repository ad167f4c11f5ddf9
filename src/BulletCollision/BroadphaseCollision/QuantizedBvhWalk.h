// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_QUANTIZED_BVH_WALK_H
#define CALIBER_QUANTIZED_BVH_WALK_H

// Internal: the stackless box walks of a btQuantizedBvh's depth-first node array, shared by the public
// query (reportAabbOverlappingNodex) and Bullet's protected walks. Inlined into both: the mesh queries
// run them for every pair and frame, and a call with the query box behind pointers costs a few tenths of
// a percent of a mesh scene (the box is re-read after every opaque callback).

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"
#include "LinearMath/btAabbUtil2.h"

namespace caliber
{
/// Calls callback for every leaf among nodes [begin, end) (a whole subtree's range) whose quantized box
/// overlaps [queryMin, queryMax] (taken by value: kept in registers across the callback).
SIMD_FORCE_INLINE void walkQuantizedNodes(const btQuantizedBvhNode* nodes, int begin, int end,
                                          const unsigned short (&queryMin)[3], const unsigned short (&queryMax)[3],
                                          btNodeOverlapCallback* callback)
{
	const unsigned short low[3] = {queryMin[0], queryMin[1], queryMin[2]};
	const unsigned short high[3] = {queryMax[0], queryMax[1], queryMax[2]};
	int i = begin;
	while (i < end)
	{
		const btQuantizedBvhNode& node = nodes[i];
		const bool overlap =
		    testQuantizedAabbAgainstQuantizedAabb(low, high, node.m_quantizedAabbMin, node.m_quantizedAabbMax) != 0;
		if (node.isLeafNode())
		{
			if (overlap) callback->processNode(node.getPartId(), node.getTriangleIndex());
			++i;
		}
		else
			i += overlap ? 1 : node.getEscapeIndex();
	}
}

/// Calls callback for every leaf among the first numNodes unquantized nodes whose box overlaps
/// [aabbMin, aabbMax].
SIMD_FORCE_INLINE void walkNodes(const btOptimizedBvhNode* nodes, int numNodes, const btVector3& aabbMin,
                                 const btVector3& aabbMax, btNodeOverlapCallback* callback)
{
	const btVector3 low = aabbMin, high = aabbMax;
	int i = 0;
	while (i < numNodes)
	{
		const btOptimizedBvhNode& node = nodes[i];
		const bool overlap = TestAabbAgainstAabb2(low, high, node.m_aabbMinOrg, node.m_aabbMaxOrg);
		if (node.m_escapeIndex < 0)
		{
			if (overlap) callback->processNode(node.m_subPart, node.m_triangleIndex);
			++i;
		}
		else
			i += overlap ? 1 : node.m_escapeIndex;
	}
}
}  // namespace caliber

#endif  // CALIBER_QUANTIZED_BVH_WALK_H
