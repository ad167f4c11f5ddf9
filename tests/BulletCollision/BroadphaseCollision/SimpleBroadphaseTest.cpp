// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSimpleBroadphase against an independent brute-force reference: moving random scenes with proxies
// created and destroyed at any time, filtering, the ghost pair callback, queries and bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "BroadphaseTestUtil.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"

namespace
{
using namespace broadphase_test;

const btScalar kRange = 20;  // objects live in [-20, 20]^3: dense enough for hundreds of pairs

void runExactPairScene(btOverlappingPairCache* cache, unsigned seed, int fullObjects, int fullFrames)
{
	const int objects = fullObjects / kScale;
	const int frames = fullFrames / kScale;
	MovingScene scene(seed, objects, kRange, 2, btScalar(0.5));
	scene.assignFilters(10, 7);
	btSimpleBroadphase broadphase(objects, cache);
	CountingDispatcher dispatcher;
	RecordingPairCallback ghost;
	broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&ghost);
	for (int i = 0; i < objects; ++i)
	{
		if (i % 5 != 4) scene.create(broadphase, i, &dispatcher);  // the rest appear during the run
	}
	broadphase.calculateOverlappingPairs(&dispatcher);
	size_t maxPairs = 0;
	for (int frame = 0; frame < frames; ++frame)
	{
		const IdPairSet expected = scene.referencePairs();
		const IdPairSet actual = cachePairs(broadphase.getOverlappingPairCache());
		ASSERT_EQ(actual, expected) << "frame " << frame << describeDifference(expected, actual);
		ASSERT_EQ(ghost.m_pairs, actual) << "frame " << frame;
		maxPairs = std::max(maxPairs, expected.size());
		scene.frame(broadphase, &dispatcher, objects / 50);
	}
	EXPECT_EQ(ghost.m_errors, 0);
	EXPECT_GT(maxPairs, size_t(objects) * size_t(objects) / 20000) << "the scene is too sparse to test anything";
	broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(0);
}

// The full-size scene: 1000 objects, 100 frames; the sorted-cache variant runs a smaller one.
TEST(SimpleBroadphase, PairsEqualBruteForceEveryFrameWithHashedCache) { runExactPairScene(0, 1, 1000, 100); }

TEST(SimpleBroadphase, PairsEqualBruteForceEveryFrameWithSortedCache)
{
	btSortedOverlappingPairCache cache;
	runExactPairScene(&cache, 2, 500, 50);
}

bool rejectSumDivisibleByThree(int a, int b) { return (a + b) % 3 != 0; }

TEST(SimpleBroadphase, UserFilterCallbackDecidesWhichTouchingProxiesPair)
{
	struct SumFilter : public btOverlapFilterCallback
	{
		bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override
		{
			return rejectSumDivisibleByThree(clientToId(a), clientToId(b));
		}
	} filter;
	const int objects = 400 / kScale;
	MovingScene scene(3, objects, 12, 2, btScalar(0.4));
	scene.assignFilters(6, 5);  // group/mask settings are ignored while the user filter is installed
	btSimpleBroadphase broadphase(objects);
	broadphase.getOverlappingPairCache()->setOverlapFilterCallback(&filter);
	for (int i = 0; i < objects; ++i) scene.create(broadphase, i, 0);
	for (int frame = 0; frame < 20; ++frame)
	{
		broadphase.calculateOverlappingPairs(0);
		const IdPairSet expected = scene.referencePairs(rejectSumDivisibleByThree);
		const IdPairSet actual = cachePairs(broadphase.getOverlappingPairCache());
		ASSERT_EQ(actual, expected) << "frame " << frame << describeDifference(expected, actual);
		// Both kinds occur: touching pairs the filter rejects, and accepted ones.
		if (frame == 0)
		{
			const IdPairSet unfiltered = scene.referencePairs([](int, int) { return true; });
			EXPECT_GT(unfiltered.size(), expected.size());
			EXPECT_GT(expected.size(), 0u);
		}
		scene.step();
		for (int i = 0; i < objects; ++i)
			broadphase.setAabb(scene.objects()[size_t(i)].proxy, scene.objects()[size_t(i)].aabbMin(),
			                   scene.objects()[size_t(i)].aabbMax(), 0);
	}
}

TEST(SimpleBroadphase, GroupMaskFilterKeepsTouchingProxiesApart)
{
	btSimpleBroadphase broadphase(8);
	const btVector3 lo(0, 0, 0), hi(1, 1, 1);
	// Same box for all four; 0 and 1 are static (static ignores static), 2 is debris ignoring debris (3).
	btBroadphaseProxy* s0 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(0), 2, -1 ^ 2, 0);
	btBroadphaseProxy* s1 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(1), 2, -1 ^ 2, 0);
	btBroadphaseProxy* d2 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(2), 8, -1 ^ 8, 0);
	btBroadphaseProxy* d3 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(3), 8, -1 ^ 8, 0);
	broadphase.calculateOverlappingPairs(0);
	btOverlappingPairCache* cache = broadphase.getOverlappingPairCache();
	EXPECT_EQ(cache->findPair(s0, s1), nullptr);
	EXPECT_EQ(cache->findPair(d2, d3), nullptr);
	EXPECT_NE(cache->findPair(s0, d2), nullptr);
	EXPECT_NE(cache->findPair(s1, d3), nullptr);
	EXPECT_EQ(cache->getNumOverlappingPairs(), 4);
	EXPECT_TRUE(broadphase.testAabbOverlap(s0, s1));
}

TEST(SimpleBroadphase, TouchingBoxesPairAndSeparatedOnesLoseTheirPair)
{
	btSimpleBroadphase broadphase(4);
	CountingDispatcher dispatcher;
	btBroadphaseProxy* a = broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	btBroadphaseProxy* b = broadphase.createProxy(btVector3(1, 0, 0), btVector3(2, 1, 1), 0, idToClient(1), 1, -1, 0);
	broadphase.calculateOverlappingPairs(&dispatcher);
	ASSERT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1) << "touching faces count as overlap";
	dispatcher.attachAlgorithm(broadphase.getOverlappingPairCache()->getOverlappingPairArray()[0]);
	// One float step apart: separated, the pair goes and its algorithm is freed.
	const btScalar gapStart = std::nextafter(btScalar(1), btScalar(2));
	broadphase.setAabb(b, btVector3(gapStart, 0, 0), btVector3(2, 1, 1), &dispatcher);
	broadphase.calculateOverlappingPairs(&dispatcher);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
	EXPECT_EQ(dispatcher.freed, 1);
	btVector3 lo, hi;
	broadphase.getAabb(b, lo, hi);
	EXPECT_EQ(lo.x(), gapStart);
	broadphase.destroyProxy(a, &dispatcher);
	broadphase.destroyProxy(b, &dispatcher);
}

TEST(SimpleBroadphase, AabbAndRayQueriesMatchBruteForce)
{
	const int objects = 600 / kScale;
	MovingScene scene(4, objects, kRange, 2, btScalar(0.5));
	btSimpleBroadphase broadphase(objects);
	for (int i = 0; i < objects; ++i)
	{
		if (i % 4 != 3) scene.create(broadphase, i, 0);
	}
	for (int round = 0; round < 3; ++round)
	{
		checkAabbQueries(broadphase, scene, 100 / kScale, kRange);
		checkRayQueries(broadphase, scene, 100 / kScale, kRange);
		scene.frame(broadphase, 0, objects / 20);
	}
}

TEST(SimpleBroadphase, RayLambdaMaxShortensTheRay)
{
	btSimpleBroadphase broadphase(4);
	broadphase.createProxy(btVector3(4, -1, -1), btVector3(5, 1, 1), 0, idToClient(0), 1, -1, 0);
	broadphase.createProxy(btVector3(8, -1, -1), btVector3(9, 1, 1), 0, idToClient(1), 1, -1, 0);
	CollectingRayCallback callback(btVector3(0, 0, 0), btVector3(10, 0, 0));
	callback.m_lambda_max = btScalar(0.6);  // reaches x = 6
	broadphase.rayTest(btVector3(0, 0, 0), btVector3(10, 0, 0), callback);
	ASSERT_EQ(callback.ids.size(), 1u);
	EXPECT_EQ(callback.ids[0], 0);
	// A swept box of half-size 2 in y reaches a box 1.5 off the ray's line; the thin ray does not.
	broadphase.createProxy(btVector3(4, 1.5, -1), btVector3(5, 3, 1), 0, idToClient(2), 1, -1, 0);
	CollectingRayCallback swept(btVector3(0, 0, 0), btVector3(10, 0, 0));
	broadphase.rayTest(btVector3(0, 0, 0), btVector3(10, 0, 0), swept, btVector3(-1, -2, -1), btVector3(1, 2, 1));
	EXPECT_EQ(swept.ids.size(), 3u);
	CollectingRayCallback thin(btVector3(0, 0, 0), btVector3(10, 0, 0));
	broadphase.rayTest(btVector3(0, 0, 0), btVector3(10, 0, 0), thin);
	EXPECT_EQ(thin.ids.size(), 2u);
}

TEST(SimpleBroadphase, ProxySlotsAreReusedAndAFullPoolReturnsNull)
{
	btSimpleBroadphase broadphase(3);
	btBroadphaseProxy* p[3];
	for (int i = 0; i < 3; ++i)
		p[i] = broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(i), 1, -1, 0);
	EXPECT_NE(p[0]->getUid(), p[1]->getUid());
	EXPECT_NE(p[1]->getUid(), p[2]->getUid());
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 3);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(3), 1, -1, 0),
	             "assertion failed");
#else
	EXPECT_EQ(broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(3), 1, -1, 0), nullptr);
#endif
	broadphase.destroyProxy(p[1], 0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1);
	btBroadphaseProxy* again =
	    broadphase.createProxy(btVector3(5, 5, 5), btVector3(6, 6, 6), 0, idToClient(4), 1, -1, 0);
	EXPECT_EQ(again, p[1]) << "the freed slot is reused";
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1);
}

TEST(SimpleBroadphase, BadInputIsRejectedWithoutTouchingState)
{
	btSimpleBroadphase broadphase(4);
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btScalar inf = std::numeric_limits<btScalar>::infinity();
	btBroadphaseProxy* good =
	    broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	broadphase.destroyProxy(0, 0);  // ignored, documented
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(broadphase.createProxy(btVector3(nan, 0, 0), btVector3(1, 1, 1), 0, idToClient(1), 1, -1, 0),
	             "assertion failed");
	EXPECT_DEATH(broadphase.setAabb(good, btVector3(0, 0, 0), btVector3(inf, 1, 1), 0), "assertion failed");
#else
	EXPECT_EQ(broadphase.createProxy(btVector3(nan, 0, 0), btVector3(1, 1, 1), 0, idToClient(1), 1, -1, 0), nullptr);
	EXPECT_EQ(broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, -inf, 1), 0, idToClient(1), 1, -1, 0), nullptr);
	broadphase.setAabb(good, btVector3(0, 0, 0), btVector3(inf, 1, 1), 0);
	broadphase.setAabb(good, btVector3(nan, 0, 0), btVector3(1, 1, 1), 0);
#endif
	btVector3 lo, hi;
	broadphase.getAabb(good, lo, hi);
	EXPECT_EQ(lo, btVector3(0, 0, 0));
	EXPECT_EQ(hi, btVector3(1, 1, 1));
	// An inverted box (an empty compound's) is accepted; it overlaps only boxes spanning its inverted range.
	btBroadphaseProxy* inverted =
	    broadphase.createProxy(btVector3(1, 1, 1), btVector3(-1, -1, -1), 0, idToClient(2), 1, -1, 0);
	ASSERT_NE(inverted, nullptr);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
	CollectingAabbCallback spanning;
	broadphase.aabbTest(btVector3(-10, -10, -10), btVector3(10, 10, 10), spanning);
	EXPECT_EQ(spanning.ids.size(), 2u);
	CollectingAabbCallback inside;
	broadphase.aabbTest(btVector3(0.25, 0.25, 0.25), btVector3(0.5, 0.5, 0.5), inside);
	ASSERT_EQ(inside.ids.size(), 1u);
	EXPECT_EQ(inside.ids[0], 0);
}
}  // namespace
