// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDbvtBroadphase searches the pairs of many moved proxies on the task scheduler's threads; the pair
// cache must end exactly as with the serial search (same pairs, same order), at any thread count.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"

namespace
{
// A tiny deterministic generator (the test must not depend on the library's or the platform's).
struct Lcg
{
	unsigned state = 12345u;
	btScalar next()  // in [0, 1)
	{
		state = state * 1664525u + 1013904223u;
		return btScalar(state >> 8) / btScalar(1 << 24);
	}
};

// The pairs of a cache as (unique id, unique id), in the cache's order.
std::vector<std::pair<int, int> > pairsOf(btOverlappingPairCache* cache)
{
	std::vector<std::pair<int, int> > ids;
	const btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
	for (int i = 0; i < pairs.size(); ++i) ids.push_back(std::make_pair(pairs[i].m_pProxy0->m_uniqueId, pairs[i].m_pProxy1->m_uniqueId));
	return ids;
}

// 600 boxes in a 12 m cube (hundreds of pairs), moved by up to 0.4 m a step (most leave their fat
// boxes, so hundreds of proxies are searched each step), for 20 steps; returns the pairs after each step.
std::vector<std::vector<std::pair<int, int> > > run(int threads, btITaskScheduler* userScheduler = 0)
{
	caliber_test::ScopedTaskScheduler scheduler(userScheduler ? 0 : threads);
	if (userScheduler) btSetTaskScheduler(userScheduler);
	btDbvtBroadphase broadphase;
	Lcg random;
	const int kBoxes = 600;
	std::vector<btBroadphaseProxy*> proxies;
	std::vector<btVector3> centres;
	const btVector3 half(btScalar(0.5), btScalar(0.5), btScalar(0.5));
	for (int i = 0; i < kBoxes; ++i)
	{
		const btVector3 centre(random.next() * 12, random.next() * 12, random.next() * 12);
		centres.push_back(centre);
		proxies.push_back(broadphase.createProxy(centre - half, centre + half, BOX_SHAPE_PROXYTYPE, 0, 1, -1, 0));
	}
	std::vector<std::vector<std::pair<int, int> > > history;
	for (int step = 0; step < 20; ++step)
	{
		for (int i = 0; i < kBoxes; ++i)
		{
			centres[i] += btVector3(random.next() - btScalar(0.5), random.next() - btScalar(0.5), random.next() - btScalar(0.5)) *
			              btScalar(0.8);
			broadphase.setAabb(proxies[i], centres[i] - half, centres[i] + half, 0);
		}
		broadphase.calculateOverlappingPairs(0);
		history.push_back(pairsOf(broadphase.getOverlappingPairCache()));
	}
	for (btBroadphaseProxy* proxy : proxies) broadphase.destroyProxy(proxy, 0);
	if (userScheduler) btSetTaskScheduler(0);
	return history;
}
}  // namespace

TEST(DbvtBroadphaseParallelSearch, PairsAndTheirOrderAreTheSerialSearchsAtAnyThreadCount)
{
	const std::vector<std::vector<std::pair<int, int> > > serial = run(0);
	// The scene is busy enough to take the parallel path (at least 128 moved proxies) and finds pairs.
	ASSERT_GT(serial.back().size(), 100u);
	for (int threads : {1, 2, 4})
	{
		const std::vector<std::vector<std::pair<int, int> > > threaded = run(threads);
		ASSERT_EQ(serial.size(), threaded.size());
		for (size_t step = 0; step < serial.size(); ++step)
			EXPECT_EQ(serial[step], threaded[step]) << "step " << step << ", " << threads << " threads";
	}
}

TEST(DbvtBroadphaseParallelSearch, AUserSchedulerMaySplitLoopsAnywhere)
{
	const std::vector<std::vector<std::pair<int, int> > > serial = run(0);
	caliber_test::UnevenSplitScheduler uneven;
	const std::vector<std::vector<std::pair<int, int> > > split = run(0, &uneven);
	ASSERT_EQ(serial.size(), split.size());
	for (size_t step = 0; step < serial.size(); ++step) EXPECT_EQ(serial[step], split[step]) << "step " << step;
}
