// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSortedOverlappingPairCache: pairs kept in increasing key order, found by binary search.

#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"

#include "BulletCollision/BroadphaseCollision/btPairCacheUtil.h"

btSortedOverlappingPairCache::btSortedOverlappingPairCache()
    : m_blockedForChanges(false), m_hasDeferredRemoval(true), m_overlapFilterCallback(0), m_ghostPairCallback(0)
{
}

btSortedOverlappingPairCache::~btSortedOverlappingPairCache() {}

bool btSortedOverlappingPairCache::needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const
{
	return caliber::needsBroadphaseCollision(m_overlapFilterCallback, proxy0, proxy1);
}

namespace
{
SIMD_FORCE_INLINE unsigned long long keyOf(const btBroadphasePair& pair)
{
	return caliber::pairKey(pair.m_pProxy0, pair.m_pProxy1);
}

// The first pair whose key is >= key (binary search).
int lowerBound(const btBroadphasePairArray& pairs, unsigned long long key)
{
	int lo = 0;
	int hi = pairs.size();
	while (lo < hi)
	{
		const int mid = (lo + hi) >> 1;
		if (keyOf(pairs[mid]) < key)
			lo = mid + 1;
		else
			hi = mid;
	}
	return lo;
}

// The index of the ordered pair (proxy0, proxy1) of the given key, or -1.
int findPairIndex(const btBroadphasePairArray& pairs, unsigned long long key, const btBroadphaseProxy* proxy0,
                  const btBroadphaseProxy* proxy1)
{
	// Equal keys (proxies of two broadphases sharing ids) sit side by side; the proxies tell them apart.
	for (int i = lowerBound(pairs, key); i < pairs.size() && keyOf(pairs[i]) == key; ++i)
	{
		if (pairs[i].m_pProxy0 == proxy0 && pairs[i].m_pProxy1 == proxy1) return i;
	}
	return -1;
}
}  // namespace

btBroadphasePair* btSortedOverlappingPairCache::addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1)
{
	btAssert(proxy0 && proxy1 && proxy0 != proxy1 && "addOverlappingPair: null or identical proxies");
	if (!proxy0 || !proxy1 || proxy0 == proxy1) return 0;
	if (!needsBroadphaseCollision(proxy0, proxy1)) return 0;
	caliber::orderPair(proxy0, proxy1);
	const unsigned long long key = caliber::pairKey(proxy0, proxy1);
	const int existing = findPairIndex(m_overlappingPairArray, key, proxy0, proxy1);
	if (existing >= 0) return &m_overlappingPairArray[existing];

	const int index = lowerBound(m_overlappingPairArray, key);
	const int count = m_overlappingPairArray.size();
	m_overlappingPairArray.push_back(btBroadphasePair());
	for (int i = count; i > index; --i) m_overlappingPairArray[i] = m_overlappingPairArray[i - 1];
	m_overlappingPairArray[index] = btBroadphasePair(*proxy0, *proxy1);

	if (m_ghostPairCallback) m_ghostPairCallback->addOverlappingPair(proxy0, proxy1);
	return &m_overlappingPairArray[index];
}

void* btSortedOverlappingPairCache::removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1,
                                                          btDispatcher* dispatcher)
{
	btAssert(proxy0 && proxy1 && "removeOverlappingPair: null proxy");
	if (!proxy0 || !proxy1 || proxy0 == proxy1) return 0;
	caliber::orderPair(proxy0, proxy1);
	const int index = findPairIndex(m_overlappingPairArray, caliber::pairKey(proxy0, proxy1), proxy0, proxy1);
	if (index < 0) return 0;
	caliber::releasePairAlgorithm(m_overlappingPairArray[index], dispatcher);
	void* userInfo = m_overlappingPairArray[index].m_internalInfo1;
	const int count = m_overlappingPairArray.size();
	for (int i = index + 1; i < count; ++i) m_overlappingPairArray[i - 1] = m_overlappingPairArray[i];
	m_overlappingPairArray.pop_back();
	if (m_ghostPairCallback) m_ghostPairCallback->removeOverlappingPair(proxy0, proxy1, dispatcher);
	return userInfo;
}

void btSortedOverlappingPairCache::removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy,
                                                                         btDispatcher* dispatcher)
{
	if (!proxy) return;
	// One compaction pass instead of one O(n) shift per removed pair. The ghost callback is told once
	// the kept pairs are compacted, while the removed ones still sit at the end (before the resize).
	int kept = 0;
	const int count = m_overlappingPairArray.size();
	for (int i = 0; i < count; ++i)
	{
		if (caliber::pairContains(m_overlappingPairArray[i], proxy))
		{
			caliber::releasePairAlgorithm(m_overlappingPairArray[i], dispatcher);
			continue;
		}
		if (kept != i) btSwap(m_overlappingPairArray[kept], m_overlappingPairArray[i]);
		++kept;
	}
	// Swapping (not copying) keeps the kept pairs in order and gathers the removed ones after them.
	for (int i = kept; i < count; ++i)
	{
		if (m_ghostPairCallback)
			m_ghostPairCallback->removeOverlappingPair(m_overlappingPairArray[i].m_pProxy0,
			                                           m_overlappingPairArray[i].m_pProxy1, dispatcher);
	}
	m_overlappingPairArray.resize(kept);
}

void btSortedOverlappingPairCache::cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher)
{
	caliber::releasePairAlgorithm(pair, dispatcher);
}

void btSortedOverlappingPairCache::cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher)
{
	if (!proxy) return;
	for (int i = 0; i < m_overlappingPairArray.size(); ++i)
	{
		if (caliber::pairContains(m_overlappingPairArray[i], proxy))
			caliber::releasePairAlgorithm(m_overlappingPairArray[i], dispatcher);
	}
}

btBroadphasePair* btSortedOverlappingPairCache::findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1)
{
	if (!proxy0 || !proxy1 || proxy0 == proxy1) return 0;
	caliber::orderPair(proxy0, proxy1);
	const int index = findPairIndex(m_overlappingPairArray, caliber::pairKey(proxy0, proxy1), proxy0, proxy1);
	return index >= 0 ? &m_overlappingPairArray[index] : 0;
}

void btSortedOverlappingPairCache::processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher)
{
	if (!callback) return;
	for (int i = 0; i < m_overlappingPairArray.size();)
	{
		// As in the hashed cache: the callback may change the array, so the pair is removed by identity
		// and index i is visited again when its pair left (the next pair shifted down into it).
		btBroadphaseProxy* proxy0 = m_overlappingPairArray[i].m_pProxy0;
		btBroadphaseProxy* proxy1 = m_overlappingPairArray[i].m_pProxy1;
		if (callback->processOverlap(m_overlappingPairArray[i])) removeOverlappingPair(proxy0, proxy1, dispatcher);
		if (i < m_overlappingPairArray.size() && m_overlappingPairArray[i].m_pProxy0 == proxy0 &&
		    m_overlappingPairArray[i].m_pProxy1 == proxy1)
			++i;
	}
}
