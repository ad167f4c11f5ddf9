// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_OVERLAPPING_PAIR_CACHE_H
#define BT_OVERLAPPING_PAIR_CACHE_H

#include "BulletCollision/BroadphaseCollision/btBroadphaseInterface.h"
#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCallback.h"
#include "LinearMath/btAlignedObjectArray.h"

class btDispatcher;
struct btDispatcherInfo;

/// The contiguous array of pairs a cache stores.
typedef btAlignedObjectArray<btBroadphasePair> btBroadphasePairArray;

/// Visited by processAllOverlappingPairs; returning true removes the pair from the cache.
struct btOverlapCallback
{
	virtual ~btOverlapCallback() {}
	/// Called once per pair; return true to remove the pair.
	virtual bool processOverlap(btBroadphasePair& pair) = 0;
};

/// User filter for broadphase pairs (the manual's second way of filtering): replaces the group/mask test.
struct btOverlapFilterCallback
{
	virtual ~btOverlapFilterCallback() {}
	/// Returns true when the two proxies may form a pair.
	virtual bool needBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const = 0;
};

/// Marks an empty slot in the hashed cache's tables.
const int BT_NULL_PAIR = 0xffffffff;

/// Stores the overlapping pairs a broadphase finds, each with its collision algorithm. Implementations:
/// btHashedOverlappingPairCache (default), btSortedOverlappingPairCache, btNullPairCache.
class btOverlappingPairCache : public btOverlappingPairCallback
{
public:
	virtual ~btOverlappingPairCache() {}

	/// First element of the pair array (0 when empty).
	virtual btBroadphasePair* getOverlappingPairArrayPtr() = 0;
	/// First element of the pair array (0 when empty).
	virtual const btBroadphasePair* getOverlappingPairArrayPtr() const = 0;
	/// The pair array itself.
	virtual btBroadphasePairArray& getOverlappingPairArray() = 0;

	/// Frees the pair's collision algorithm through the dispatcher and clears it.
	virtual void cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher) = 0;

	/// Number of pairs stored.
	virtual int getNumOverlappingPairs() const = 0;

	/// The filter a pair must pass: the user's btOverlapFilterCallback, or group/mask bits both ways.
	virtual bool needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const = 0;

	/// The user's filter, or 0.
	virtual btOverlapFilterCallback* getOverlapFilterCallback() = 0;

	/// Frees the algorithms of every pair containing the proxy (the pairs stay).
	virtual void cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher) = 0;

	/// Installs a user filter (0 restores the group/mask test).
	virtual void setOverlapFilterCallback(btOverlapFilterCallback* callback) = 0;

	/// Visits every pair; pairs for which the callback returns true are removed.
	virtual void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher) = 0;

	/// As above; dispatchInfo lets implementations process pairs in parallel.
	virtual void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher,
	                                        const btDispatcherInfo& dispatchInfo)
	{
		(void)dispatchInfo;
		processAllOverlappingPairs(callback, dispatcher);
	}

	/// The stored pair of the two proxies (in either order), or 0.
	virtual btBroadphasePair* findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) = 0;

	/// True when the broadphase removes stale pairs itself, later (btDbvtBroadphase with a sorted cache).
	virtual bool hasDeferredRemoval() = 0;

	/// A second callback told about every pair added or removed (ghost objects use it).
	virtual void setInternalGhostPairCallback(btOverlappingPairCallback* ghostPairCallback) = 0;

	/// Sorts the pairs into a deterministic order (by proxy ids).
	virtual void sortOverlappingPairs(btDispatcher* dispatcher) = 0;
};

// The implementations (btHashedOverlappingPairCache, btSortedOverlappingPairCache, btNullPairCache)
// follow below, as in Bullet's header.

#endif  // BT_OVERLAPPING_PAIR_CACHE_H
