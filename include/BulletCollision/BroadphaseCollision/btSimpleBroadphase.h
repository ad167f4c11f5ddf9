// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMPLE_BROADPHASE_H
#define BT_SIMPLE_BROADPHASE_H

#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"

/// A proxy of btSimpleBroadphase: a slot in its fixed pool.
struct btSimpleBroadphaseProxy : public btBroadphaseProxy
{
	/// Next free slot while this one is free; btSimpleBroadphase::kProxyInUse while it is in use.
	int m_nextFree;

	/// A free slot.
	btSimpleBroadphaseProxy() : m_nextFree(-1) {}

	/// A proxy for userPtr with the given AABB and filtering (shapeType is not stored, as in Bullet).
	btSimpleBroadphaseProxy(const btVector3& minpt, const btVector3& maxpt, int shapeType, void* userPtr,
	                        int collisionFilterGroup, int collisionFilterMask)
	    : btBroadphaseProxy(minpt, maxpt, userPtr, collisionFilterGroup, collisionFilterMask), m_nextFree(-1)
	{
		(void)shapeType;
	}

	/// Links a free slot to the next free one.
	SIMD_FORCE_INLINE void SetNextFree(int next) { m_nextFree = next; }
	/// The next free slot (-1: none).
	SIMD_FORCE_INLINE int GetNextFree() const { return m_nextFree; }
};

/// The reference broadphase: a fixed pool of proxies and an all-pairs test in calculateOverlappingPairs,
/// O(n^2) per step. Exact (pairs are precisely the filtered pairs whose AABBs overlap, touching included)
/// and simple, for small scenes and for checking the other broadphases.
class btSimpleBroadphase : public btBroadphaseInterface
{
public:
	/// m_nextFree of a slot in use.
	static const int kProxyInUse = -2;

	/// A pool of maxProxies slots. Uses overlappingPairCache when given (the caller keeps ownership),
	/// else creates and owns a btHashedOverlappingPairCache.
	btSimpleBroadphase(int maxProxies = 16384, btOverlappingPairCache* overlappingPairCache = 0);
	~btSimpleBroadphase() override;

	/// True when the two AABBs overlap or touch.
	static bool aabbOverlap(btSimpleBroadphaseProxy* proxy0, btSimpleBroadphaseProxy* proxy1);

	/// A new proxy; 0 (with an assert) when the pool is full or the AABB is not finite. An inverted box
	/// (min > max, e.g. an empty compound's) is accepted; it overlaps only boxes spanning [max, min].
	btBroadphaseProxy* createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int shapeType, void* userPtr,
	                               int collisionFilterGroup, int collisionFilterMask,
	                               btDispatcher* dispatcher) override;
	/// Removes the proxy's pairs and frees its slot. 0 is ignored; a proxy not live in this pool asserts
	/// and is ignored.
	void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;
	/// Stores the new AABB (pairs change at the next calculateOverlappingPairs). A non-finite AABB is
	/// ignored with an assert: the proxy keeps its previous box.
	void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
	             btDispatcher* dispatcher) override;
	/// The proxy's AABB.
	void getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Reports every proxy whose AABB, grown by [aabbMin, aabbMax], the ray hits within the callback's
	/// m_lambda_max (a slab test per proxy).
	void rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
	             const btVector3& aabbMin = btVector3(0, 0, 0), const btVector3& aabbMax = btVector3(0, 0, 0)) override;
	/// Reports every proxy whose AABB overlaps [aabbMin, aabbMax].
	void aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback) override;

	/// Removes pairs whose AABBs separated and adds pairs whose AABBs overlap (all pairs tested).
	void calculateOverlappingPairs(btDispatcher* dispatcher) override;

	/// The pair cache.
	btOverlappingPairCache* getOverlappingPairCache() override { return m_pairCache; }
	/// The pair cache.
	const btOverlappingPairCache* getOverlappingPairCache() const override { return m_pairCache; }

	/// True when the two proxies' AABBs overlap.
	bool testAabbOverlap(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1);

	/// Bullet's answer for an unbounded broadphase: [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3.
	void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Prints the pool use and pair count.
	void printStats() override;

protected:
	/// Takes a free slot (-1 when the pool is full).
	int allocHandle();
	/// Returns a slot to the free list.
	void freeHandle(btSimpleBroadphaseProxy* proxy);
	/// The proxy as a pool slot.
	SIMD_FORCE_INLINE btSimpleBroadphaseProxy* getSimpleProxyFromProxy(btBroadphaseProxy* proxy)
	{
		return static_cast<btSimpleBroadphaseProxy*>(proxy);
	}
	/// The proxy as a pool slot.
	SIMD_FORCE_INLINE const btSimpleBroadphaseProxy* getSimpleProxyFromProxy(btBroadphaseProxy* proxy) const
	{
		return static_cast<const btSimpleBroadphaseProxy*>(proxy);
	}
	/// Checks that every pair of the cache joins two live proxies (debug aid; asserts).
	void validate();

	/// Number of live proxies.
	int m_numHandles;
	/// Pool size.
	int m_maxHandles;
	/// Highest slot index ever used (slots above it were never handed out).
	int m_LastHandleIndex;
	/// The pool.
	btSimpleBroadphaseProxy* m_pHandles;
	/// The pool's raw allocation.
	void* m_pHandlesRawPtr;
	/// Head of the free list (-1: full).
	int m_firstFreeHandle;
	/// The pair cache (owned when m_ownsPairCache).
	btOverlappingPairCache* m_pairCache;
	/// True when the broadphase created the cache and deletes it.
	bool m_ownsPairCache;
	/// Kept for source compatibility (Bullet's count of invalidated pairs; always 0).
	int m_invalidPair;
};

#endif  // BT_SIMPLE_BROADPHASE_H
