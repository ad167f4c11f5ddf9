// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btHashedOverlappingPairCache: pairs contiguous in one array, indexed by an open-addressing table.
//
// The table holds pair indices, hashed by the pair's two proxy addresses, so that neither a probe nor
// the home slot of a stored pair ever dereferences a proxy (the pair itself holds both). Linear probing with
// backward-shift deletion keeps every chain gap-free without tombstones, so a long-running scene that
// adds and removes pairs forever never needs a cleanup rehash. The load factor stays at or below 1/2.

#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btPairCacheUtil.h"
#include "BulletCollision/NarrowPhaseCollision/ManifoldPrefetch.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"

#include <stdint.h>

namespace
{
const int kInitialTableSlots = 16;

// Multiplicative hashing: the golden-ratio constant spreads consecutive ids over the whole word, and
// folding the high half down lets a small power-of-two mask see all of it.
SIMD_FORCE_INLINE int homeSlot(unsigned long long key, int mask)
{
	unsigned long long h = key * 0x9E3779B97F4A7C15ULL;
	h ^= h >> 32;
	return static_cast<int>(h & static_cast<unsigned long long>(mask));
}

// The home slot of the ordered pair (proxy0, proxy1), from the two addresses (the table's layout only
// decides how fast a pair is found, never which pairs exist or their order).
SIMD_FORCE_INLINE int homeSlot(const btBroadphaseProxy* proxy0, const btBroadphaseProxy* proxy1, int mask)
{
	const unsigned long long a = static_cast<unsigned long long>(reinterpret_cast<uintptr_t>(proxy0));
	const unsigned long long b = static_cast<unsigned long long>(reinterpret_cast<uintptr_t>(proxy1));
	return homeSlot(a * 0xC2B2AE3D27D4EB4FULL + b, mask);
}

SIMD_FORCE_INLINE int homeSlot(const btBroadphasePair& pair, int mask)
{
	return homeSlot(pair.m_pProxy0, pair.m_pProxy1, mask);
}

// Fills table (at least minSlots slots, a power of two) with the indices of pairs.
void rebuildTable(btAlignedObjectArray<int>& table, const btBroadphasePairArray& pairs, int minSlots)
{
	int slots = kInitialTableSlots;
	while (slots < minSlots) slots <<= 1;
	table.resizeNoInitialize(slots);
	for (int i = 0; i < slots; ++i) table[i] = BT_NULL_PAIR;
	const int mask = slots - 1;
	for (int index = 0; index < pairs.size(); ++index)
	{
		int slot = homeSlot(pairs[index], mask);
		while (table[slot] != BT_NULL_PAIR) slot = (slot + 1) & mask;
		table[slot] = index;
	}
}

// The index of the ordered pair (proxy0, proxy1), or -1.
int findPairIndex(const btAlignedObjectArray<int>& table, const btBroadphasePairArray& pairs,
                  const btBroadphaseProxy* proxy0, const btBroadphaseProxy* proxy1)
{
	const int mask = table.size() - 1;
	for (int slot = homeSlot(proxy0, proxy1, mask);; slot = (slot + 1) & mask)
	{
		const int index = table[slot];
		if (index == BT_NULL_PAIR) return -1;
		if (pairs[index].m_pProxy0 == proxy0 && pairs[index].m_pProxy1 == proxy1) return index;
	}
}

// The slot that holds pair index pairIndex.
int findSlotOfPair(const btAlignedObjectArray<int>& table, const btBroadphasePairArray& pairs, int pairIndex)
{
	const int mask = table.size() - 1;
	int slot = homeSlot(pairs[pairIndex], mask);
	while (table[slot] != pairIndex) slot = (slot + 1) & mask;
	return slot;
}

// Removes pair index from the table and the array; the last pair takes its index.
void removePairAt(btAlignedObjectArray<int>& table, btBroadphasePairArray& pairs, int index)
{
	const int mask = table.size() - 1;
	// Backward-shift deletion: pull later entries of the probe run into the hole when their home slot
	// allows it, so that lookups never stop early at a gap.
	int hole = findSlotOfPair(table, pairs, index);
	for (int slot = (hole + 1) & mask; table[slot] != BT_NULL_PAIR; slot = (slot + 1) & mask)
	{
		const int home = homeSlot(pairs[table[slot]], mask);
		// The entry may move to the hole when its home is not cyclically inside (hole, slot].
		const bool homeInside = (hole <= slot) ? (home > hole && home <= slot) : (home > hole || home <= slot);
		if (!homeInside)
		{
			table[hole] = table[slot];
			hole = slot;
		}
	}
	table[hole] = BT_NULL_PAIR;

	const int last = pairs.size() - 1;
	if (index != last)
	{
		table[findSlotOfPair(table, pairs, last)] = index;
		pairs[index] = pairs[last];
	}
	pairs.pop_back();
}

// Ascending (proxy0 id, proxy1 id), the order sortOverlappingPairs promises.
struct PairIdLess
{
	bool operator()(const btBroadphasePair& a, const btBroadphasePair& b) const
	{
		return caliber::pairKey(a.m_pProxy0, a.m_pProxy1) < caliber::pairKey(b.m_pProxy0, b.m_pProxy1);
	}
};

// The first manifold an algorithm reports (the one its processCollision reads first), or 0. The pair loop
// asks through getAllContactManifolds, which every algorithm has, so that a prefetch needs nothing from
// the algorithm classes beyond Bullet's interface.
const btPersistentManifold* firstManifoldOf(btCollisionAlgorithm* algorithm, btManifoldArray& scratch)
{
	scratch.resize(0);
	algorithm->getAllContactManifolds(scratch);
	return scratch.size() ? scratch[0] : 0;
}
}  // namespace

btHashedOverlappingPairCache::btHashedOverlappingPairCache() : m_overlapFilterCallback(0), m_ghostPairCallback(0)
{
	rebuildTable(m_hashTable, m_overlappingPairArray, kInitialTableSlots);
}

btHashedOverlappingPairCache::~btHashedOverlappingPairCache() {}

bool btHashedOverlappingPairCache::needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const
{
	return caliber::needsBroadphaseCollision(m_overlapFilterCallback, proxy0, proxy1);
}

btBroadphasePair* btHashedOverlappingPairCache::addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1)
{
	btAssert(proxy0 && proxy1 && proxy0 != proxy1 && "addOverlappingPair: null or identical proxies");
	if (!proxy0 || !proxy1 || proxy0 == proxy1) return 0;
	if (!needsBroadphaseCollision(proxy0, proxy1)) return 0;
	caliber::orderPair(proxy0, proxy1);
	const int existing = findPairIndex(m_hashTable, m_overlappingPairArray, proxy0, proxy1);
	if (existing >= 0) return &m_overlappingPairArray[existing];

	if ((m_overlappingPairArray.size() + 1) * 2 > m_hashTable.size())
		rebuildTable(m_hashTable, m_overlappingPairArray, m_hashTable.size() * 2);
	const int index = m_overlappingPairArray.size();
	m_overlappingPairArray.push_back(btBroadphasePair(*proxy0, *proxy1));
	const int mask = m_hashTable.size() - 1;
	int slot = homeSlot(proxy0, proxy1, mask);
	while (m_hashTable[slot] != BT_NULL_PAIR) slot = (slot + 1) & mask;
	m_hashTable[slot] = index;

	if (m_ghostPairCallback) m_ghostPairCallback->addOverlappingPair(proxy0, proxy1);
	return &m_overlappingPairArray[index];
}

void* btHashedOverlappingPairCache::removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1,
                                                          btDispatcher* dispatcher)
{
	btAssert(proxy0 && proxy1 && "removeOverlappingPair: null proxy");
	if (!proxy0 || !proxy1 || proxy0 == proxy1) return 0;
	caliber::orderPair(proxy0, proxy1);
	const int index = findPairIndex(m_hashTable, m_overlappingPairArray, proxy0, proxy1);
	if (index < 0) return 0;
	caliber::releasePairAlgorithm(m_overlappingPairArray[index], dispatcher);
	void* userInfo = m_overlappingPairArray[index].m_internalInfo1;
	removePairAt(m_hashTable, m_overlappingPairArray, index);
	if (m_ghostPairCallback) m_ghostPairCallback->removeOverlappingPair(proxy0, proxy1, dispatcher);
	return userInfo;
}

void btHashedOverlappingPairCache::removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy,
                                                                         btDispatcher* dispatcher)
{
	if (!proxy) return;
	for (int i = 0; i < m_overlappingPairArray.size();)
	{
		if (caliber::pairContains(m_overlappingPairArray[i], proxy))
		{
			// The last pair moves into slot i, so i is examined again.
			removeOverlappingPair(m_overlappingPairArray[i].m_pProxy0, m_overlappingPairArray[i].m_pProxy1, dispatcher);
		}
		else
		{
			++i;
		}
	}
}

void btHashedOverlappingPairCache::cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher)
{
	caliber::releasePairAlgorithm(pair, dispatcher);
}

void btHashedOverlappingPairCache::cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher)
{
	if (!proxy) return;
	for (int i = 0; i < m_overlappingPairArray.size(); ++i)
	{
		if (caliber::pairContains(m_overlappingPairArray[i], proxy))
			caliber::releasePairAlgorithm(m_overlappingPairArray[i], dispatcher);
	}
}

btBroadphasePair* btHashedOverlappingPairCache::findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1)
{
	if (!proxy0 || !proxy1 || proxy0 == proxy1) return 0;
	caliber::orderPair(proxy0, proxy1);
	const int index = findPairIndex(m_hashTable, m_overlappingPairArray, proxy0, proxy1);
	return index >= 0 ? &m_overlappingPairArray[index] : 0;
}

void btHashedOverlappingPairCache::processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher)
{
	if (!callback) return;
	btManifoldArray aheadManifolds;  // scratch for firstManifoldOf
	for (int i = 0; i < m_overlappingPairArray.size();)
	{
		// The callback may add or remove pairs (reallocating or reordering the array), so nothing is held
		// across the call except the two proxies, and the pair is removed by identity, not by index.
		btBroadphasePair& pair = m_overlappingPairArray[i];
		btBroadphaseProxy* proxy0 = pair.m_pProxy0;
		btBroadphaseProxy* proxy1 = pair.m_pProxy1;
		// The narrowphase of a pair starts by reading its algorithm and the two objects, which live all
		// over the heap: ask for a pair a few places ahead while this one is processed.
#if defined(__GNUC__)
		// A three-stage pipeline: eight pairs ahead the pair's algorithm and proxies; four ahead (the
		// algorithm is in cache by then) the objects' transforms and the manifold's last line, which holds
		// its point count; two ahead the lines of the points it holds (an empty manifold needs none).
		if (i + 8 < m_overlappingPairArray.size())
		{
			const btBroadphasePair& ahead = m_overlappingPairArray[i + 8];
			if (ahead.m_algorithm) __builtin_prefetch(ahead.m_algorithm);
			__builtin_prefetch(ahead.m_pProxy0);
			__builtin_prefetch(ahead.m_pProxy1);
		}
		if (i + 4 < m_overlappingPairArray.size() && m_overlappingPairArray[i + 4].m_algorithm)
		{
			const btBroadphasePair& ahead = m_overlappingPairArray[i + 4];
			for (const btBroadphaseProxy* proxy : {ahead.m_pProxy0, ahead.m_pProxy1})
			{
				if (!proxy) continue;
				const char* object = static_cast<const char*>(proxy->m_clientObject);
				__builtin_prefetch(object);
				__builtin_prefetch(object + 64);
			}
			if (const btPersistentManifold* manifold = firstManifoldOf(ahead.m_algorithm, aheadManifolds))
				caliber::prefetchManifoldHeader(manifold);
		}
		if (i + 2 < m_overlappingPairArray.size() && m_overlappingPairArray[i + 2].m_algorithm)
		{
			if (const btPersistentManifold* manifold =
			        firstManifoldOf(m_overlappingPairArray[i + 2].m_algorithm, aheadManifolds))
				caliber::prefetchManifoldPoints(manifold);
		}
#endif
		if (callback->processOverlap(pair)) removeOverlappingPair(proxy0, proxy1, dispatcher);
		// Slot i holds an unvisited pair when this one left it (the last pair moved in); else move on.
		if (i < m_overlappingPairArray.size() && m_overlappingPairArray[i].m_pProxy0 == proxy0 &&
		    m_overlappingPairArray[i].m_pProxy1 == proxy1)
			++i;
	}
}

void btHashedOverlappingPairCache::processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher,
                                                              const btDispatcherInfo& dispatchInfo)
{
	if (dispatchInfo.m_deterministicOverlappingPairs) sortOverlappingPairs(dispatcher);
	processAllOverlappingPairs(callback, dispatcher);
}

void btHashedOverlappingPairCache::sortOverlappingPairs(btDispatcher* dispatcher)
{
	(void)dispatcher;
	// Sorting in place keeps each pair's algorithm and user info; only the index table changes.
	m_overlappingPairArray.quickSort(PairIdLess());
	rebuildTable(m_hashTable, m_overlappingPairArray, m_hashTable.size());
}
