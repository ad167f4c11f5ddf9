// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btHashedOverlappingPairCache and btSortedOverlappingPairCache against a std::set reference under random
// add/remove sequences; filtering, algorithm release, ghost callback, iteration with removal, sorting,
// steady-state memory, btNullPairCache and bad input.

#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "BroadphaseTestUtil.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"

namespace
{
using namespace broadphase_test;

// Proxies with shuffled unique ids, so that id order differs from creation order.
struct ProxySet
{
	explicit ProxySet(int count, unsigned seed = 7)
	{
		proxies.resize(size_t(count));
		std::vector<int> ids;
		for (int i = 0; i < count; ++i) ids.push_back(3 * i + 5);
		Random rng(seed);
		for (int i = count - 1; i > 0; --i)
			std::swap(ids[size_t(i)], ids[size_t(rng.uniform(0, btScalar(i) + btScalar(0.999)))]);
		for (int i = 0; i < count; ++i)
		{
			proxies[size_t(i)].m_clientObject = idToClient(i);
			proxies[size_t(i)].m_uniqueId = ids[size_t(i)];
			proxies[size_t(i)].m_collisionFilterGroup = btBroadphaseProxy::DefaultFilter;
			proxies[size_t(i)].m_collisionFilterMask = btBroadphaseProxy::AllFilter;
		}
	}
	btBroadphaseProxy* operator[](int i) { return &proxies[size_t(i)]; }
	std::vector<btBroadphaseProxy> proxies;
};

bool groupMaskAcceptsForTest(const btBroadphaseProxy* a, const btBroadphaseProxy* b)
{
	return groupMaskAccepts(a->m_collisionFilterGroup, a->m_collisionFilterMask, b->m_collisionFilterGroup,
	                        b->m_collisionFilterMask);
}

void* infoOf(const IdPair& p) { return reinterpret_cast<void*>(static_cast<size_t>(p.first * 100000 + p.second + 1)); }

template <typename Cache>
class PairCacheTest : public ::testing::Test
{
};

typedef ::testing::Types<btHashedOverlappingPairCache, btSortedOverlappingPairCache> CacheTypes;
TYPED_TEST_SUITE(PairCacheTest, CacheTypes);

TYPED_TEST(PairCacheTest, RandomAddRemoveMatchesReferenceSetAndReturnsUserInfo)
{
	const int proxyCount = 120;
	const int operations = 20000 / kScale;
	ProxySet proxies(proxyCount);
	TypeParam cache;
	RecordingPairCallback ghost;
	cache.setInternalGhostPairCallback(&ghost);
	IdPairSet reference;
	Random rng(11);
	for (int op = 0; op < operations; ++op)
	{
		const int a = int(rng.uniform(0, btScalar(proxyCount) - btScalar(0.001)));
		int b = int(rng.uniform(0, btScalar(proxyCount) - btScalar(0.001)));
		if (a == b) b = (b + 1) % proxyCount;
		const IdPair key = makeIdPair(a, b);
		// Adds slightly more often than removes, so the set grows to a few thousand pairs and shrinks.
		if (rng.uniform(0, 1) < btScalar(0.55))
		{
			btBroadphasePair* pair = cache.addOverlappingPair(proxies[a], proxies[b]);
			ASSERT_NE(pair, nullptr);
			if (reference.insert(key).second)
			{
				EXPECT_EQ(pair->m_algorithm, nullptr);
				EXPECT_EQ(pair->m_internalInfo1, nullptr);
				pair->m_internalInfo1 = infoOf(key);
			}
			else
			{
				EXPECT_EQ(pair->m_internalInfo1, infoOf(key)) << "a second add must return the stored pair";
			}
		}
		else
		{
			void* info = cache.removeOverlappingPair(proxies[b], proxies[a], 0);
			EXPECT_EQ(info, reference.erase(key) ? infoOf(key) : nullptr) << "op " << op;
		}
		// A random lookup in either order agrees with the reference.
		const int c = int(rng.uniform(0, btScalar(proxyCount) - btScalar(0.001)));
		const int d = (c + 1 + int(rng.uniform(0, btScalar(proxyCount) - btScalar(1.001)))) % proxyCount;
		btBroadphasePair* found = cache.findPair(proxies[d], proxies[c]);
		EXPECT_EQ(found != nullptr, reference.count(makeIdPair(c, d)) == 1u) << "op " << op;
		if (op % 997 == 0)
		{
			ASSERT_EQ(cachePairs(&cache), reference) << "op " << op;
		}
	}
	EXPECT_EQ(cachePairs(&cache), reference);
	EXPECT_EQ(ghost.m_pairs, reference);
	EXPECT_EQ(ghost.m_errors, 0);
	// Every stored pair still carries the info given when it was added.
	btBroadphasePairArray& pairs = cache.getOverlappingPairArray();
	for (int i = 0; i < pairs.size(); ++i)
	{
		const IdPair key = makeIdPair(clientToId(pairs[i].m_pProxy0), clientToId(pairs[i].m_pProxy1));
		EXPECT_EQ(pairs[i].m_internalInfo1, infoOf(key));
	}
}

TYPED_TEST(PairCacheTest, GroupMaskFilterRejectsPairsEitherWayAndUserFilterReplacesIt)
{
	ProxySet proxies(5);
	TypeParam cache;
	// 0: group 1 mask 2; 1: group 2 mask 1 -> accepted both ways.
	proxies[0]->m_collisionFilterGroup = 1;
	proxies[0]->m_collisionFilterMask = 2;
	proxies[1]->m_collisionFilterGroup = 2;
	proxies[1]->m_collisionFilterMask = 1;
	// 2: group 2 mask 4 -> 0 accepts 2's group, but 2 does not accept 0's group.
	proxies[2]->m_collisionFilterGroup = 2;
	proxies[2]->m_collisionFilterMask = 4;
	EXPECT_TRUE(cache.needsBroadphaseCollision(proxies[0], proxies[1]));
	EXPECT_FALSE(cache.needsBroadphaseCollision(proxies[0], proxies[2]));
	EXPECT_FALSE(cache.needsBroadphaseCollision(proxies[2], proxies[0]));
	EXPECT_NE(cache.addOverlappingPair(proxies[0], proxies[1]), nullptr);
	EXPECT_EQ(cache.addOverlappingPair(proxies[2], proxies[0]), nullptr);
	EXPECT_EQ(cache.getNumOverlappingPairs(), 1);

	struct OnlyWithThree : public btOverlapFilterCallback
	{
		bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override
		{
			return clientToId(a) == 3 || clientToId(b) == 3;
		}
	} filter;
	cache.setOverlapFilterCallback(&filter);
	EXPECT_EQ(cache.getOverlapFilterCallback(), &filter);
	// (1, 4): group/mask accepts (4 is group 1, mask all), the user filter rejects.
	EXPECT_TRUE(groupMaskAcceptsForTest(proxies[1], proxies[4]));
	EXPECT_EQ(cache.addOverlappingPair(proxies[1], proxies[4]), nullptr);
	// (2, 3): group/mask rejects (3 is group 1, 2's mask is 4), the user filter accepts.
	EXPECT_FALSE(groupMaskAcceptsForTest(proxies[2], proxies[3]));
	EXPECT_NE(cache.addOverlappingPair(proxies[2], proxies[3]), nullptr);
	EXPECT_EQ(cache.getNumOverlappingPairs(), 2);
	cache.setOverlapFilterCallback(0);
	EXPECT_TRUE(cache.needsBroadphaseCollision(proxies[0], proxies[1]));
	EXPECT_FALSE(cache.needsBroadphaseCollision(proxies[0], proxies[2]));
}

TYPED_TEST(PairCacheTest, RemovalFreesAlgorithmsThroughTheDispatcher)
{
	ProxySet proxies(6);
	TypeParam cache;
	CountingDispatcher dispatcher;
	RecordingPairCallback ghost;
	cache.setInternalGhostPairCallback(&ghost);
	for (int a = 0; a < 6; ++a)
		for (int b = a + 1; b < 6; ++b) dispatcher.attachAlgorithm(*cache.addOverlappingPair(proxies[a], proxies[b]));
	ASSERT_EQ(cache.getNumOverlappingPairs(), 15);

	cache.removeOverlappingPair(proxies[0], proxies[1], &dispatcher);
	EXPECT_EQ(dispatcher.destroyed, 1);
	EXPECT_EQ(dispatcher.freed, 1);

	// cleanProxyFromPairs frees the algorithms of proxy 2's 5 pairs but keeps the pairs.
	cache.cleanProxyFromPairs(proxies[2], &dispatcher);
	EXPECT_EQ(dispatcher.freed, 6);
	EXPECT_EQ(cache.getNumOverlappingPairs(), 14);
	EXPECT_EQ(cache.findPair(proxies[2], proxies[3])->m_algorithm, nullptr);
	EXPECT_NE(cache.findPair(proxies[3], proxies[4])->m_algorithm, nullptr);

	// Removing proxy 3's pairs: (0,3) (1,3) (2,3) (3,4) (3,5); (2,3) has no algorithm any more.
	cache.removeOverlappingPairsContainingProxy(proxies[3], &dispatcher);
	EXPECT_EQ(cache.getNumOverlappingPairs(), 9);
	EXPECT_EQ(dispatcher.freed, 10);
	for (int i = 0; i < 6; ++i) EXPECT_EQ(cache.findPair(proxies[3], proxies[i]), nullptr);
	EXPECT_EQ(ghost.m_pairs, cachePairs(&cache));
	EXPECT_EQ(ghost.m_errors, 0);

	// cleanOverlappingPair without a dispatcher cannot free, and leaves the algorithm in place.
	btBroadphasePair* pair = cache.findPair(proxies[4], proxies[5]);
	cache.cleanOverlappingPair(*pair, 0);
	EXPECT_NE(pair->m_algorithm, nullptr);
	cache.cleanOverlappingPair(*pair, &dispatcher);
	EXPECT_EQ(pair->m_algorithm, nullptr);
	EXPECT_EQ(dispatcher.freed, 11);

	// Free the rest so the test leaks nothing.
	cache.processAllOverlappingPairs(nullptr, &dispatcher);
	while (cache.getNumOverlappingPairs() > 0)
	{
		btBroadphasePair& first = cache.getOverlappingPairArray()[0];
		cache.removeOverlappingPair(first.m_pProxy0, first.m_pProxy1, &dispatcher);
	}
	EXPECT_EQ(dispatcher.freed, dispatcher.allocated);
	EXPECT_EQ(dispatcher.destroyed, dispatcher.allocated);
	EXPECT_TRUE(ghost.m_pairs.empty());
}

// Returns true (remove) for pairs whose id sum is odd; also removes, through the cache, the pair
// (a, a+1) of the visited pair's first object when it is still there.
struct RemovingCallback : public btOverlapCallback
{
	RemovingCallback(btOverlappingPairCache* cache, ProxySet* proxies, int count)
	    : m_cache(cache), m_proxies(proxies), m_count(count)
	{
	}
	bool processOverlap(btBroadphasePair& pair) override
	{
		const IdPair key = makeIdPair(clientToId(pair.m_pProxy0), clientToId(pair.m_pProxy1));
		++m_visits[key];
		if (m_removeOthers && key.first + 1 < m_count && key.second != key.first + 1)
		{
			m_cache->removeOverlappingPair((*m_proxies)[key.first], (*m_proxies)[key.first + 1], 0);
		}
		return (key.first + key.second) % 2 == 1;
	}
	btOverlappingPairCache* m_cache;
	ProxySet* m_proxies;
	int m_count;
	bool m_removeOthers = false;
	std::map<IdPair, int> m_visits;
};

TYPED_TEST(PairCacheTest, ProcessAllVisitsEachPairOnceAndRemovesThoseTheCallbackReturns)
{
	const int count = 40;
	ProxySet proxies(count);
	TypeParam cache;
	IdPairSet reference;
	for (int a = 0; a < count; ++a)
		for (int b = a + 1; b < count; b += 1 + (a % 3))
		{
			cache.addOverlappingPair(proxies[a], proxies[b]);
			reference.insert(IdPair(a, b));
		}
	RemovingCallback callback(&cache, &proxies, count);
	cache.processAllOverlappingPairs(&callback, 0);
	IdPairSet expected;
	for (const IdPair& p : reference)
	{
		EXPECT_EQ(callback.m_visits[p], 1) << p.first << "," << p.second;
		if ((p.first + p.second) % 2 == 0) expected.insert(p);
	}
	EXPECT_EQ(callback.m_visits.size(), reference.size());
	EXPECT_EQ(cachePairs(&cache), expected);
}

TYPED_TEST(PairCacheTest, CallbackRemovingOtherPairsDuringIterationLeavesAConsistentCache)
{
	const int count = 40;
	ProxySet proxies(count);
	TypeParam cache;
	RecordingPairCallback ghost;
	cache.setInternalGhostPairCallback(&ghost);
	for (int a = 0; a < count; ++a)
		for (int b = a + 1; b < count; ++b) cache.addOverlappingPair(proxies[a], proxies[b]);
	RemovingCallback callback(&cache, &proxies, count);
	callback.m_removeOthers = true;
	cache.processAllOverlappingPairs(&callback, 0);
	// Removing other pairs may make the cache skip a pair (the one moved into the freed slot) but never
	// crash or corrupt it: every visited odd pair is gone, every even pair stays, the ghost mirror agrees.
	const IdPairSet remaining = cachePairs(&cache);
	for (const IdPair& p : remaining)
	{
		if ((p.first + p.second) % 2 == 1)
		{
			EXPECT_EQ(callback.m_visits[p], 0) << p.first << "," << p.second;
		}
	}
	for (int a = 0; a + 1 < count; ++a) EXPECT_EQ(cache.findPair(proxies[a], proxies[a + 1]), nullptr);
	EXPECT_EQ(ghost.m_pairs, remaining);
	EXPECT_EQ(ghost.m_errors, 0);
	// Even pairs are never removed (the callback only removes odd ones).
	int even = 0;
	for (int a = 0; a < count; ++a)
		for (int b = a + 1; b < count; ++b) even += (a + b) % 2 == 0;
	int evenRemaining = 0;
	for (const IdPair& p : remaining) evenRemaining += (p.first + p.second) % 2 == 0;
	EXPECT_EQ(evenRemaining, even);
}

TYPED_TEST(PairCacheTest, SortOrdersByIdsAndKeepsAlgorithmsAndInfo)
{
	const int count = 30;
	ProxySet proxies(count, 3);
	TypeParam cache;
	CountingDispatcher dispatcher;
	Random rng(5);
	for (int i = 0; i < 200; ++i)
	{
		const int a = int(rng.uniform(0, btScalar(count) - btScalar(0.001)));
		const int b = (a + 1 + int(rng.uniform(0, btScalar(count) - btScalar(1.001)))) % count;
		btBroadphasePair* pair = cache.addOverlappingPair(proxies[a], proxies[b]);
		if (!pair->m_algorithm)
		{
			dispatcher.attachAlgorithm(*pair);
			pair->m_internalInfo1 = infoOf(makeIdPair(a, b));
		}
	}
	const IdPairSet before = cachePairs(&cache);
	cache.sortOverlappingPairs(&dispatcher);
	EXPECT_EQ(cachePairs(&cache), before);
	btBroadphasePairArray& pairs = cache.getOverlappingPairArray();
	for (int i = 0; i < pairs.size(); ++i)
	{
		EXPECT_NE(pairs[i].m_algorithm, nullptr);
		EXPECT_EQ(pairs[i].m_internalInfo1,
		          infoOf(makeIdPair(clientToId(pairs[i].m_pProxy0), clientToId(pairs[i].m_pProxy1))));
		EXPECT_EQ(cache.findPair(pairs[i].m_pProxy1, pairs[i].m_pProxy0), &pairs[i]);
		if (i == 0) continue;
		const int prev0 = pairs[i - 1].m_pProxy0->m_uniqueId, prev1 = pairs[i - 1].m_pProxy1->m_uniqueId;
		const int cur0 = pairs[i].m_pProxy0->m_uniqueId, cur1 = pairs[i].m_pProxy1->m_uniqueId;
		EXPECT_TRUE(prev0 < cur0 || (prev0 == cur0 && prev1 < cur1)) << "index " << i;
	}
	EXPECT_EQ(dispatcher.freed, 0);
	for (int i = 0; i < count; ++i) cache.removeOverlappingPairsContainingProxy(proxies[i], &dispatcher);
	EXPECT_EQ(dispatcher.freed, dispatcher.allocated);
}

TYPED_TEST(PairCacheTest, EmptyCacheHasNoArrayPointerAndNullOrSelfProxiesAreRejected)
{
	ProxySet proxies(2);
	TypeParam cache;
	EXPECT_EQ(cache.getOverlappingPairArrayPtr(), nullptr);
	EXPECT_EQ(cache.findPair(proxies[0], proxies[1]), nullptr);
	EXPECT_EQ(cache.removeOverlappingPair(proxies[0], proxies[1], 0), nullptr);
	cache.removeOverlappingPairsContainingProxy(0, 0);
	cache.cleanProxyFromPairs(0, 0);
	EXPECT_EQ(cache.findPair(0, proxies[1]), nullptr);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(cache.addOverlappingPair(0, proxies[1]), "assertion failed");
	EXPECT_DEATH(cache.addOverlappingPair(proxies[0], proxies[0]), "assertion failed");
	EXPECT_DEATH(cache.removeOverlappingPair(proxies[0], 0, 0), "assertion failed");
#else
	EXPECT_EQ(cache.addOverlappingPair(0, proxies[1]), nullptr);
	EXPECT_EQ(cache.addOverlappingPair(proxies[0], proxies[0]), nullptr);
	EXPECT_EQ(cache.removeOverlappingPair(proxies[0], 0, 0), nullptr);
	EXPECT_EQ(cache.getNumOverlappingPairs(), 0);
#endif
	cache.addOverlappingPair(proxies[0], proxies[1]);
	EXPECT_EQ(cache.getOverlappingPairArrayPtr(), &cache.getOverlappingPairArray()[0]);
	EXPECT_FALSE(cache.getOverlappingPairArrayPtr() == nullptr);
}

TEST(PairCacheHashed, SteadyStateAddRemoveReusesMemoryAndDefersNothing)
{
	const int count = 200;
	ProxySet proxies(count);
	btHashedOverlappingPairCache cache;
	EXPECT_FALSE(cache.hasDeferredRemoval());
	Random rng(21);
	// Warm up to the peak size, then churn: remove a random pair, add a random one.
	std::vector<IdPair> live;
	for (int i = 0; i < 3000; ++i)
	{
		const int a = int(rng.uniform(0, btScalar(count) - btScalar(0.001)));
		const int b = (a + 1 + int(rng.uniform(0, btScalar(count) - btScalar(1.001)))) % count;
		if (cache.findPair(proxies[a], proxies[b])) continue;
		cache.addOverlappingPair(proxies[a], proxies[b]);
		live.push_back(makeIdPair(a, b));
	}
	const btBroadphasePair* arrayBefore = cache.getOverlappingPairArrayPtr();
	const int capacityBefore = cache.getOverlappingPairArray().capacity();
	for (int i = 0; i < 20000 / kScale; ++i)
	{
		const size_t k = size_t(rng.uniform(0, btScalar(live.size()) - btScalar(0.001)));
		cache.removeOverlappingPair(proxies[live[k].first], proxies[live[k].second], 0);
		for (;;)
		{
			const int a = int(rng.uniform(0, btScalar(count) - btScalar(0.001)));
			const int b = (a + 1 + int(rng.uniform(0, btScalar(count) - btScalar(1.001)))) % count;
			if (cache.findPair(proxies[a], proxies[b])) continue;
			cache.addOverlappingPair(proxies[a], proxies[b]);
			live[k] = makeIdPair(a, b);
			break;
		}
	}
	EXPECT_EQ(cache.GetCount(), int(live.size()));
	EXPECT_EQ(cache.getOverlappingPairArray().capacity(), capacityBefore);
	EXPECT_EQ(cache.getOverlappingPairArrayPtr(), arrayBefore) << "the pair array was reallocated";
	EXPECT_EQ(cachePairs(&cache), IdPairSet(live.begin(), live.end()));
}

TEST(PairCacheHashed, DeterministicDispatchInfoSortsBeforeVisiting)
{
	ProxySet proxies(20);
	btHashedOverlappingPairCache cache;
	for (int a = 19; a >= 0; --a)
		for (int b = 0; b < a; b += 3) cache.addOverlappingPair(proxies[a], proxies[b]);
	struct OrderRecorder : public btOverlapCallback
	{
		bool processOverlap(btBroadphasePair& pair) override
		{
			keys.push_back((static_cast<long long>(pair.m_pProxy0->m_uniqueId) << 32) | pair.m_pProxy1->m_uniqueId);
			return false;
		}
		std::vector<long long> keys;
	} recorder;
	btDispatcherInfo info;
	info.m_deterministicOverlappingPairs = true;
	cache.processAllOverlappingPairs(&recorder, 0, info);
	ASSERT_EQ(int(recorder.keys.size()), cache.getNumOverlappingPairs());
	for (size_t i = 1; i < recorder.keys.size(); ++i) EXPECT_LT(recorder.keys[i - 1], recorder.keys[i]);
}

TEST(PairCacheSorted, ReportsDeferredRemovalAndKeepsIdOrderAfterEveryChange)
{
	ProxySet proxies(50);
	btSortedOverlappingPairCache cache;
	EXPECT_TRUE(cache.hasDeferredRemoval());
	Random rng(8);
	for (int i = 0; i < 2000 / kScale; ++i)
	{
		const int a = int(rng.uniform(0, btScalar(49.999)));
		const int b = (a + 1 + int(rng.uniform(0, btScalar(48.999)))) % 50;
		if (rng.uniform(0, 1) < btScalar(0.6))
			cache.addOverlappingPair(proxies[a], proxies[b]);
		else
			cache.removeOverlappingPair(proxies[a], proxies[b], 0);
		const btBroadphasePairArray& pairs = cache.getOverlappingPairArray();
		for (int k = 1; k < pairs.size(); ++k)
		{
			const long long prev =
			    (static_cast<long long>(pairs[k - 1].m_pProxy0->m_uniqueId) << 32) | pairs[k - 1].m_pProxy1->m_uniqueId;
			const long long cur =
			    (static_cast<long long>(pairs[k].m_pProxy0->m_uniqueId) << 32) | pairs[k].m_pProxy1->m_uniqueId;
			ASSERT_LT(prev, cur) << "operation " << i << " index " << k;
		}
	}
}

TEST(PairCacheNull, StoresNothing)
{
	ProxySet proxies(2);
	btNullPairCache cache;
	RecordingPairCallback ghost;
	cache.setInternalGhostPairCallback(&ghost);
	EXPECT_EQ(cache.addOverlappingPair(proxies[0], proxies[1]), nullptr);
	EXPECT_EQ(cache.getNumOverlappingPairs(), 0);
	EXPECT_EQ(cache.findPair(proxies[0], proxies[1]), nullptr);
	EXPECT_EQ(cache.getOverlappingPairArrayPtr(), nullptr);
	EXPECT_EQ(cache.removeOverlappingPair(proxies[0], proxies[1], 0), nullptr);
	EXPECT_TRUE(cache.hasDeferredRemoval());
	EXPECT_EQ(ghost.m_adds, 0);
}
}  // namespace
