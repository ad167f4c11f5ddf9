// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_QUANTIZED_BVH_CAST_H
#define CALIBER_QUANTIZED_BVH_CAST_H

// Internal: the box-cast walk of a btQuantizedBvh with an optional upper bound on the fraction, for ray
// tests that keep only the closest hit.

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"

namespace caliber
{
// As btQuantizedBvh::reportBoxCastOverlappingNodex; with maxFraction, boxes the sweep only reaches beyond
// *maxFraction are skipped. The value is read at every box, so the node callback may lower it as it finds
// closer hits.
void reportBoxCastOverlappingNodes(const btQuantizedBvh& bvh, btNodeOverlapCallback* nodeCallback,
                                   const btVector3& raySource, const btVector3& rayTarget, const btVector3& aabbMin,
                                   const btVector3& aabbMax, const btScalar* maxFraction);

// As reportBoxCastOverlappingNodes with a fraction bound (maxFraction not null), walking the tree nearer
// child first (reportBoxCastOverlappingNodes calls it when given a bound). The nodes reported are those the
// sweep reaches within the bound as it stands when each is reached; only their order differs from the
// stackless walk's.
void reportBoxCastOverlappingNodesNearestFirst(const btQuantizedBvh& bvh, btNodeOverlapCallback* nodeCallback,
                                               const btVector3& raySource, const btVector3& rayTarget,
                                               const btVector3& aabbMin, const btVector3& aabbMax,
                                               const btScalar* maxFraction);

// As reportBoxCastOverlappingNodes over the nodes [startNode, endNode) only (a whole subtree's range, or
// the whole tree); the range is clamped to the tree.
void reportBoxCastOverlappingNodesInRange(const btQuantizedBvh& bvh, btNodeOverlapCallback* nodeCallback,
                                          const btVector3& raySource, const btVector3& rayTarget,
                                          const btVector3& aabbMin, const btVector3& aabbMax,
                                          const btScalar* maxFraction, int startNode, int endNode);
}  // namespace caliber

#endif  // CALIBER_QUANTIZED_BVH_CAST_H
