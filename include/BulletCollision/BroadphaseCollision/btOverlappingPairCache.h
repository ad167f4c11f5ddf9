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

/// The default pair cache: pairs contiguous in one array, found through an open-addressing hash table
/// keyed by the two proxies' unique ids. Add, find and remove are O(1) expected; removal moves the last
/// pair into the freed slot. Memory grows by doubling and is kept, so a steady scene allocates nothing.
class btHashedOverlappingPairCache : public btOverlappingPairCache
{
public:
	btHashedOverlappingPairCache();
	~btHashedOverlappingPairCache() override;

	/// Adds the pair unless the filter rejects it (returns 0) or it exists (returns the stored pair).
	btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override;
	/// Frees the pair's algorithm, forgets the pair and returns its m_internalInfo1 (0 when absent).
	void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1,
	                            btDispatcher* dispatcher) override;
	/// Removes every pair containing proxy (the ghost callback hears each removal).
	void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;

	/// The group/mask test both ways, or the user's filter when one is installed.
	bool needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override;

	/// Frees the algorithms of every pair containing proxy (the pairs stay).
	void cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;
	/// Visits every pair once and removes those the callback returns true for. The callback may also add or
	/// remove pairs through the cache (memory-safe; a pair moved into a slot it freed may then be skipped).
	void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher) override;
	/// As above, after sorting the pairs when dispatchInfo.m_deterministicOverlappingPairs is set.
	void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher,
	                                const btDispatcherInfo& dispatchInfo) override;

	/// First pair (0 when empty).
	btBroadphasePair* getOverlappingPairArrayPtr() override
	{
		return m_overlappingPairArray.size() ? &m_overlappingPairArray[0] : 0;
	}
	/// First pair (0 when empty).
	const btBroadphasePair* getOverlappingPairArrayPtr() const override
	{
		return m_overlappingPairArray.size() ? &m_overlappingPairArray[0] : 0;
	}
	/// The pair array (do not add or remove through it; edit m_algorithm and m_internalInfo1 freely).
	btBroadphasePairArray& getOverlappingPairArray() override { return m_overlappingPairArray; }
	/// The pair array.
	const btBroadphasePairArray& getOverlappingPairArray() const { return m_overlappingPairArray; }

	/// Destroys the pair's algorithm and returns its memory to the dispatcher (nothing without a dispatcher).
	void cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher) override;
	/// The stored pair of the two proxies (either order), or 0.
	btBroadphasePair* findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override;

	/// Number of pairs (Bullet's name).
	int GetCount() const { return m_overlappingPairArray.size(); }
	/// Number of pairs.
	int getNumOverlappingPairs() const override { return m_overlappingPairArray.size(); }

	/// The user's filter, or 0.
	btOverlapFilterCallback* getOverlapFilterCallback() override { return m_overlapFilterCallback; }
	/// Installs a user filter (0: group/mask test). Existing pairs are kept.
	void setOverlapFilterCallback(btOverlapFilterCallback* callback) override { m_overlapFilterCallback = callback; }
	/// Also tells ghostPairCallback about every pair added or removed (0 to stop).
	void setInternalGhostPairCallback(btOverlappingPairCallback* ghostPairCallback) override
	{
		m_ghostPairCallback = ghostPairCallback;
	}
	/// Reorders the pairs by increasing (proxy0 id, proxy1 id); algorithms and user info are kept.
	void sortOverlappingPairs(btDispatcher* dispatcher) override;
	/// False: pairs are removed the moment the broadphase asks.
	bool hasDeferredRemoval() override { return false; }

protected:
	/// The pairs, contiguous.
	btBroadphasePairArray m_overlappingPairArray;
	/// Open-addressing table (linear probing): pair index or BT_NULL_PAIR; size is a power of two.
	btAlignedObjectArray<int> m_hashTable;
	/// The user's filter, or 0.
	btOverlapFilterCallback* m_overlapFilterCallback;
	/// Told about every pair added or removed, or 0.
	btOverlappingPairCallback* m_ghostPairCallback;
};

/// A pair cache kept sorted by (proxy0 id, proxy1 id): iteration order is always deterministic, lookup
/// is a binary search, adding or removing shifts the pairs after it (O(n)). Reports deferred removal,
/// which tells a broadphase it may remove stale pairs in one pass per step (Caliber's broadphases do that
/// within the same calculateOverlappingPairs call, so the pair set is the same as with the hashed cache).
class btSortedOverlappingPairCache : public btOverlappingPairCache
{
public:
	btSortedOverlappingPairCache();
	~btSortedOverlappingPairCache() override;

	/// Adds the pair unless the filter rejects it (returns 0) or it exists (returns the stored pair).
	btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override;
	/// Frees the pair's algorithm, forgets the pair and returns its m_internalInfo1 (0 when absent).
	void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1,
	                            btDispatcher* dispatcher) override;
	/// Removes every pair containing proxy (one compaction pass; the ghost callback hears each removal).
	void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;

	/// The group/mask test both ways, or the user's filter when one is installed.
	bool needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override;

	/// Frees the algorithms of every pair containing proxy (the pairs stay).
	void cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;
	/// Visits every pair in id order; the callback may add or remove pairs itself (memory-safe; a pair added
	/// during the pass before the current one may cause the current one to be visited again).
	void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher) override;
	using btOverlappingPairCache::processAllOverlappingPairs;

	/// First pair (0 when empty).
	btBroadphasePair* getOverlappingPairArrayPtr() override
	{
		return m_overlappingPairArray.size() ? &m_overlappingPairArray[0] : 0;
	}
	/// First pair (0 when empty).
	const btBroadphasePair* getOverlappingPairArrayPtr() const override
	{
		return m_overlappingPairArray.size() ? &m_overlappingPairArray[0] : 0;
	}
	/// The pair array (do not add, remove or reorder through it).
	btBroadphasePairArray& getOverlappingPairArray() override { return m_overlappingPairArray; }
	/// The pair array.
	const btBroadphasePairArray& getOverlappingPairArray() const { return m_overlappingPairArray; }

	/// Destroys the pair's algorithm and returns its memory to the dispatcher (nothing without a dispatcher).
	void cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher) override;
	/// The stored pair of the two proxies (either order), or 0.
	btBroadphasePair* findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override;

	/// Number of pairs.
	int getNumOverlappingPairs() const override { return m_overlappingPairArray.size(); }
	/// The user's filter, or 0.
	btOverlapFilterCallback* getOverlapFilterCallback() override { return m_overlapFilterCallback; }
	/// Installs a user filter (0: group/mask test). Existing pairs are kept.
	void setOverlapFilterCallback(btOverlapFilterCallback* callback) override { m_overlapFilterCallback = callback; }
	/// Also tells ghostPairCallback about every pair added or removed (0 to stop).
	void setInternalGhostPairCallback(btOverlappingPairCallback* ghostPairCallback) override
	{
		m_ghostPairCallback = ghostPairCallback;
	}
	/// Nothing to do: the pairs are always sorted.
	void sortOverlappingPairs(btDispatcher* dispatcher) override { (void)dispatcher; }
	/// True (see the class comment).
	bool hasDeferredRemoval() override { return m_hasDeferredRemoval; }

protected:
	/// The pairs, sorted by (proxy0 id, proxy1 id).
	btBroadphasePairArray m_overlappingPairArray;
	/// Kept for source compatibility (Bullet's flag; never set by Caliber).
	bool m_blockedForChanges;
	/// Always true.
	bool m_hasDeferredRemoval;
	/// The user's filter, or 0.
	btOverlapFilterCallback* m_overlapFilterCallback;
	/// Told about every pair added or removed, or 0.
	btOverlappingPairCallback* m_ghostPairCallback;
};

/// A cache that stores nothing: for broadphases used only for queries (rayTest, aabbTest).
class btNullPairCache : public btOverlappingPairCache
{
public:
	/// 0 (there are no pairs).
	btBroadphasePair* getOverlappingPairArrayPtr() override { return 0; }
	/// 0 (there are no pairs).
	const btBroadphasePair* getOverlappingPairArrayPtr() const override { return 0; }
	/// An always empty array.
	btBroadphasePairArray& getOverlappingPairArray() override { return m_overlappingPairArray; }
	/// Nothing to clean.
	void cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher) override
	{
		(void)pair;
		(void)dispatcher;
	}
	/// 0.
	int getNumOverlappingPairs() const override { return 0; }
	/// Nothing to clean.
	void cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override
	{
		(void)proxy;
		(void)dispatcher;
	}
	/// True: a broadphase must not count on this cache to remove anything.
	bool needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override
	{
		(void)proxy0;
		(void)proxy1;
		return true;
	}
	/// 0 (no filter).
	btOverlapFilterCallback* getOverlapFilterCallback() override { return 0; }
	/// Ignored.
	void setOverlapFilterCallback(btOverlapFilterCallback* callback) override { (void)callback; }
	/// Visits nothing.
	void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher) override
	{
		(void)callback;
		(void)dispatcher;
	}
	using btOverlappingPairCache::processAllOverlappingPairs;
	/// 0.
	btBroadphasePair* findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override
	{
		(void)proxy0;
		(void)proxy1;
		return 0;
	}
	/// True (nothing is ever stored, so nothing needs removing).
	bool hasDeferredRemoval() override { return true; }
	/// Ignored (no pair is ever added).
	void setInternalGhostPairCallback(btOverlappingPairCallback* ghostPairCallback) override
	{
		(void)ghostPairCallback;
	}
	/// Stores nothing; returns 0.
	btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override
	{
		(void)proxy0;
		(void)proxy1;
		return 0;
	}
	/// Returns 0.
	void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1, btDispatcher* dispatcher) override
	{
		(void)proxy0;
		(void)proxy1;
		(void)dispatcher;
		return 0;
	}
	/// Nothing to remove.
	void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override
	{
		(void)proxy;
		(void)dispatcher;
	}
	/// Nothing to sort.
	void sortOverlappingPairs(btDispatcher* dispatcher) override { (void)dispatcher; }

private:
	btBroadphasePairArray m_overlappingPairArray;
};

#endif  // BT_OVERLAPPING_PAIR_CACHE_H
