// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_PAIR_CACHE_UTIL_H
#define CALIBER_PAIR_CACHE_UTIL_H

// Internal helpers shared by the pair caches: the pair key, the default filter, algorithm release.

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"

namespace caliber
{

/// Puts the two proxies in the order btBroadphasePair stores them (lower unique id first).
SIMD_FORCE_INLINE void orderPair(btBroadphaseProxy*& proxy0, btBroadphaseProxy*& proxy1)
{
	if (!(proxy0->m_uniqueId < proxy1->m_uniqueId)) btSwap(proxy0, proxy1);
}

/// The 64-bit key of an ordered pair: the two ids side by side, so that sorting keys sorts by (id0, id1).
SIMD_FORCE_INLINE unsigned long long pairKey(const btBroadphaseProxy* proxy0, const btBroadphaseProxy* proxy1)
{
	return (static_cast<unsigned long long>(static_cast<unsigned int>(proxy0->m_uniqueId)) << 32) |
	       static_cast<unsigned long long>(static_cast<unsigned int>(proxy1->m_uniqueId));
}

/// Bullet's default filter: each proxy's group is in the other's mask.
SIMD_FORCE_INLINE bool groupMaskAccepts(const btBroadphaseProxy* proxy0, const btBroadphaseProxy* proxy1)
{
	return (proxy0->m_collisionFilterGroup & proxy1->m_collisionFilterMask) != 0 &&
	       (proxy1->m_collisionFilterGroup & proxy0->m_collisionFilterMask) != 0;
}

/// The filter of a cache: the user's callback when installed, else the group/mask test.
SIMD_FORCE_INLINE bool needsBroadphaseCollision(const btOverlapFilterCallback* filter, btBroadphaseProxy* proxy0,
                                                btBroadphaseProxy* proxy1)
{
	if (filter) return filter->needBroadphaseCollision(proxy0, proxy1);
	return groupMaskAccepts(proxy0, proxy1);
}

/// Destroys the pair's algorithm and hands its memory back to the dispatcher that allocated it. Without a
/// dispatcher the algorithm cannot be freed, so it is left in place (as in Bullet).
SIMD_FORCE_INLINE void releasePairAlgorithm(btBroadphasePair& pair, btDispatcher* dispatcher)
{
	if (!pair.m_algorithm || !dispatcher) return;
	btCollisionAlgorithm* algorithm = pair.m_algorithm;
	pair.m_algorithm = 0;
	algorithm->~btCollisionAlgorithm();
	dispatcher->freeCollisionAlgorithm(algorithm);
}

/// True when the pair joins proxy.
SIMD_FORCE_INLINE bool pairContains(const btBroadphasePair& pair, const btBroadphaseProxy* proxy)
{
	return pair.m_pProxy0 == proxy || pair.m_pProxy1 == proxy;
}

}  // namespace caliber

#endif  // CALIBER_PAIR_CACHE_UTIL_H
