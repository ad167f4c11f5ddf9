// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDbvtBroadphase against an independent brute-force reference. The guarantee checked every frame:
// every pair whose AABBs overlap is in the cache, and the cache holds exactly the filtered pairs whose
// tree ("fat") boxes overlap; each fat box contains its AABB. Also filtering, the ghost callback, the
// queries, the fat-box rules (margin, prediction, forced updates), static proxies and bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "BroadphaseTestUtil.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"

namespace
{
using namespace broadphase_test;

const btScalar kRange = 20;

const btDbvtVolume& fatBox(const btBroadphaseProxy* proxy)
{
	return static_cast<const btDbvtProxy*>(proxy)->leaf->volume;
}

// The filtered pairs of live objects whose fat boxes overlap, by brute force over the leaves.
IdPairSet fatReferencePairs(MovingScene& scene, bool (*extraFilter)(int, int) = 0)
{
	IdPairSet result;
	std::vector<SceneObject>& objects = scene.objects();
	const int n = int(objects.size());
	for (int i = 0; i < n; ++i)
	{
		if (!objects[size_t(i)].alive) continue;
		const btDbvtVolume& a = fatBox(objects[size_t(i)].proxy);
		for (int j = i + 1; j < n; ++j)
		{
			if (!objects[size_t(j)].alive) continue;
			const btDbvtVolume& b = fatBox(objects[size_t(j)].proxy);
			if (!boxesOverlap(a.Mins(), a.Maxs(), b.Mins(), b.Maxs())) continue;
			const SceneObject& oa = objects[size_t(i)];
			const SceneObject& ob = objects[size_t(j)];
			if (extraFilter ? !extraFilter(i, j) : !groupMaskAccepts(oa.group, oa.mask, ob.group, ob.mask)) continue;
			result.insert(IdPair(i, j));
		}
	}
	return result;
}

bool boxIsFinite(const btDbvtVolume& box)
{
	for (int axis = 0; axis < 3; ++axis)
	{
		if (!std::isfinite(double(box.Mins()[axis])) || !std::isfinite(double(box.Maxs()[axis]))) return false;
	}
	return true;
}

bool isSubset(const IdPairSet& small, const IdPairSet& big)
{
	for (const IdPair& p : small)
	{
		if (!big.count(p)) return false;
	}
	return true;
}

// Every live proxy's fat box contains its AABB, which is the AABB the scene set.
void checkFatBoxesContainAabbs(MovingScene& scene, int frame)
{
	for (const SceneObject& object : scene.objects())
	{
		if (!object.alive) continue;
		ASSERT_EQ(object.proxy->m_aabbMin, object.aabbMin()) << "frame " << frame;
		ASSERT_EQ(object.proxy->m_aabbMax, object.aabbMax()) << "frame " << frame;
		const btDbvtVolume& box = fatBox(object.proxy);
		for (int axis = 0; axis < 3; ++axis)
		{
			ASSERT_LE(box.Mins()[axis], object.aabbMin()[axis]) << "frame " << frame;
			ASSERT_GE(box.Maxs()[axis], object.aabbMax()[axis]) << "frame " << frame;
		}
	}
}

void runScene(btOverlappingPairCache* cache, unsigned seed, btScalar prediction, int fullObjects, int fullFrames,
              btScalar range = kRange)
{
	const int objects = fullObjects / kScale;
	const int frames = fullFrames / kScale;
	MovingScene scene(seed, objects, range, 2, btScalar(0.3));
	scene.assignFilters(10, 7);
	btDbvtBroadphase broadphase(cache);
	broadphase.setVelocityPrediction(prediction);
	CountingDispatcher dispatcher;
	RecordingPairCallback ghost;
	broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&ghost);
	for (int i = 0; i < objects; ++i)
	{
		if (i % 5 != 4) scene.create(broadphase, i, &dispatcher);
	}
	broadphase.calculateOverlappingPairs(&dispatcher);
	size_t extraMax = 0, trueMax = 0;
	for (int frame = 0; frame < frames; ++frame)
	{
		const IdPairSet actual = cachePairs(broadphase.getOverlappingPairCache());
		const IdPairSet truePairs = scene.referencePairs();
		const IdPairSet fatPairs = fatReferencePairs(scene);
		ASSERT_TRUE(isSubset(truePairs, actual)) << "frame " << frame << describeDifference(truePairs, actual);
		ASSERT_EQ(actual, fatPairs) << "frame " << frame << describeDifference(fatPairs, actual);
		ASSERT_EQ(ghost.m_pairs, actual) << "frame " << frame;
		checkFatBoxesContainAabbs(scene, frame);
		extraMax = std::max(extraMax, actual.size() - truePairs.size());
		trueMax = std::max(trueMax, truePairs.size());
		// Give some pairs an algorithm, so that removals must free them.
		btBroadphasePairArray& pairs = broadphase.getOverlappingPairCache()->getOverlappingPairArray();
		for (int i = 0; i < pairs.size(); i += 7)
		{
			if (!pairs[i].m_algorithm) dispatcher.attachAlgorithm(pairs[i]);
		}
		scene.frame(broadphase, &dispatcher, objects / 50);
	}
	EXPECT_EQ(ghost.m_errors, 0);
	// Expected pairs grow as objects^2 / volume; the floor is far below that expectation.
	const double volumeRatio = std::pow(double(kRange / range), 3.0);
	EXPECT_GT(double(trueMax), double(objects) * double(objects) / 20000.0 * volumeRatio)
	    << "the scene is too sparse to test anything";
	// Fat boxes add some pairs, but far fewer than the true ones (margin 0.05, speed <= 0.3 per frame).
	EXPECT_LT(extraMax, trueMax) << "fat boxes much too large";
	broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(0);
	for (int i = 0; i < objects; ++i)
	{
		if (scene.objects()[size_t(i)].alive) scene.destroy(broadphase, i, &dispatcher);
	}
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
	EXPECT_EQ(dispatcher.freed, dispatcher.allocated);
	EXPECT_EQ(dispatcher.destroyed, dispatcher.allocated);
}

// The full-size scene: 1000 objects, 100 frames. The variants run smaller scenes to keep the file fast.
TEST(DbvtBroadphase, PairsCoverTrueOverlapsAndEqualFatOverlapsEveryFrame) { runScene(0, 1, 1, 1000, 100); }

// 10,000 objects at the same density (range grown by the cube root of 10); few frames, because the
// brute-force reference is quadratic.
TEST(DbvtBroadphase, PairsEqualFatOverlapsWithTenThousandMovingObjects)
{
	runScene(0, 3, 1, 10000, 8, kRange * btScalar(2.154));
}

TEST(DbvtBroadphase, PairsEqualFatOverlapsWithoutPrediction) { runScene(0, 2, 0, 500, 50); }

TEST(DbvtBroadphase, PairsEqualFatOverlapsWithSortedCache)
{
	btSortedOverlappingPairCache cache;
	runScene(&cache, 3, 1, 500, 50);
}

bool rejectSumDivisibleByThree(int a, int b) { return (a + b) % 3 != 0; }

TEST(DbvtBroadphase, UserFilterCallbackDecidesWhichTouchingProxiesPair)
{
	struct SumFilter : public btOverlapFilterCallback
	{
		bool needBroadphaseCollision(btBroadphaseProxy* a, btBroadphaseProxy* b) const override
		{
			return rejectSumDivisibleByThree(clientToId(a), clientToId(b));
		}
	} filter;
	const int objects = 400 / kScale;
	MovingScene scene(4, objects, 12, 2, btScalar(0.3));
	scene.assignFilters(6, 5);
	btDbvtBroadphase broadphase;
	broadphase.getOverlappingPairCache()->setOverlapFilterCallback(&filter);
	for (int i = 0; i < objects; ++i) scene.create(broadphase, i, 0);
	broadphase.calculateOverlappingPairs(0);
	for (int frame = 0; frame < 20; ++frame)
	{
		const IdPairSet actual = cachePairs(broadphase.getOverlappingPairCache());
		const IdPairSet truePairs = scene.referencePairs(rejectSumDivisibleByThree);
		const IdPairSet fatPairs = fatReferencePairs(scene, rejectSumDivisibleByThree);
		ASSERT_TRUE(isSubset(truePairs, actual)) << "frame " << frame << describeDifference(truePairs, actual);
		ASSERT_EQ(actual, fatPairs) << "frame " << frame << describeDifference(fatPairs, actual);
		if (frame == 0)
		{
			EXPECT_GT(scene.referencePairs([](int, int) { return true; }).size(), truePairs.size());
			EXPECT_GT(truePairs.size(), 0u);
		}
		scene.frame(broadphase, 0, 0);
	}
}

TEST(DbvtBroadphase, GroupMaskFilterKeepsTouchingProxiesApart)
{
	btDbvtBroadphase broadphase;
	const btVector3 lo(0, 0, 0), hi(1, 1, 1);
	btBroadphaseProxy* s0 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(0), 2, -1 ^ 2, 0);
	btBroadphaseProxy* s1 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(1), 2, -1 ^ 2, 0);
	btBroadphaseProxy* d2 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(2), 8, -1 ^ 8, 0);
	btBroadphaseProxy* d3 = broadphase.createProxy(lo, hi, BOX_SHAPE_PROXYTYPE, idToClient(3), 8, -1 ^ 8, 0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0) << "pairs wait for the step";
	broadphase.calculateOverlappingPairs(0);
	btOverlappingPairCache* cache = broadphase.getOverlappingPairCache();
	EXPECT_EQ(cache->findPair(s0, s1), nullptr);
	EXPECT_EQ(cache->findPair(d2, d3), nullptr);
	EXPECT_NE(cache->findPair(s0, d2), nullptr);
	EXPECT_NE(cache->findPair(s1, d3), nullptr);
	EXPECT_EQ(cache->getNumOverlappingPairs(), 4);
	// The static ones live in the fixed tree.
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::FIXED_SET].m_leaves, 2);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_leaves, 2);
}

TEST(DbvtBroadphase, AabbAndRayQueriesMatchBruteForce)
{
	const int objects = 600 / kScale;
	MovingScene scene(5, objects, kRange, 2, btScalar(0.5));
	scene.assignFilters(8, 0);
	btDbvtBroadphase broadphase;
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

TEST(DbvtBroadphase, RayLambdaMaxAndSweptBoxAreHonoured)
{
	btDbvtBroadphase broadphase;
	broadphase.createProxy(btVector3(4, -1, -1), btVector3(5, 1, 1), 0, idToClient(0), 1, -1, 0);
	broadphase.createProxy(btVector3(8, -1, -1), btVector3(9, 1, 1), 0, idToClient(1), 2, -1, 0);
	broadphase.createProxy(btVector3(4, 1.5, -1), btVector3(5, 3, 1), 0, idToClient(2), 1, -1, 0);
	CollectingRayCallback shortRay(btVector3(0, 0, 0), btVector3(10, 0, 0));
	shortRay.m_lambda_max = btScalar(0.6);  // reaches x = 6
	broadphase.rayTest(btVector3(0, 0, 0), btVector3(10, 0, 0), shortRay);
	ASSERT_EQ(shortRay.ids.size(), 1u);
	EXPECT_EQ(shortRay.ids[0], 0);
	CollectingRayCallback thin(btVector3(0, 0, 0), btVector3(10, 0, 0));
	broadphase.rayTest(btVector3(0, 0, 0), btVector3(10, 0, 0), thin);
	EXPECT_EQ(thin.ids.size(), 2u) << "the fat box of object 2 must not count";
	CollectingRayCallback swept(btVector3(0, 0, 0), btVector3(10, 0, 0));
	broadphase.rayTest(btVector3(0, 0, 0), btVector3(10, 0, 0), swept, btVector3(-1, -2, -1), btVector3(1, 2, 1));
	EXPECT_EQ(swept.ids.size(), 3u);
}

TEST(DbvtBroadphase, SmallMovesStayInsideTheFatBoxAndLargeOnesMoveIt)
{
	btDbvtBroadphase broadphase;
	broadphase.setVelocityPrediction(0);
	btBroadphaseProxy* proxy =
	    broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	const btDbvtVolume before = fatBox(proxy);
	// Created with the margin on every side.
	EXPECT_EQ(before.Mins(), btVector3(-gDbvtMargin, -gDbvtMargin, -gDbvtMargin));
	EXPECT_EQ(before.Maxs(), btVector3(1 + gDbvtMargin, 1 + gDbvtMargin, 1 + gDbvtMargin));
	broadphase.calculateOverlappingPairs(0);
	const btScalar small = gDbvtMargin * btScalar(0.5);
	broadphase.setAabb(proxy, btVector3(small, 0, 0), btVector3(1 + small, 1, 1), 0);
	EXPECT_EQ(fatBox(proxy).Mins(), before.Mins());
	EXPECT_EQ(fatBox(proxy).Maxs(), before.Maxs());
	EXPECT_FALSE(broadphase.m_needcleanup) << "a move inside the fat box queued a pair search";
	broadphase.setAabb(proxy, btVector3(2, 0, 0), btVector3(3, 1, 1), 0);
	EXPECT_EQ(fatBox(proxy).Mins(), btVector3(2 - gDbvtMargin, -gDbvtMargin, -gDbvtMargin));
	EXPECT_TRUE(broadphase.m_needcleanup);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.m_updates_ratio, btScalar(0.5)) << "one of the two setAabb calls moved the box";
}

TEST(DbvtBroadphase, VelocityPredictionGrowsTheBoxAheadOfTheMotion)
{
	btDbvtBroadphase broadphase;
	EXPECT_EQ(broadphase.getVelocityPrediction(), btScalar(1));
	broadphase.setVelocityPrediction(2);
	btBroadphaseProxy* proxy =
	    broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	// Moved by (1, -0.5, 0): the box grows 2 * 1 ahead in +x and 2 * 0.5 ahead in -y, margin elsewhere.
	broadphase.setAabb(proxy, btVector3(1, -0.5, 0), btVector3(2, 0.5, 1), 0);
	const btDbvtVolume& box = fatBox(proxy);
	const btScalar tolerance = btScalar(1e-5);  // float sums of values of order 1
	EXPECT_NEAR(box.Maxs().x(), 2 + gDbvtMargin + 2, tolerance);
	EXPECT_NEAR(box.Mins().x(), 1 - gDbvtMargin, tolerance);
	EXPECT_NEAR(box.Mins().y(), -0.5 - gDbvtMargin - 1, tolerance);
	EXPECT_NEAR(box.Maxs().y(), 0.5 + gDbvtMargin, tolerance);
	EXPECT_NEAR(box.Mins().z(), -gDbvtMargin, tolerance);
	EXPECT_NEAR(box.Maxs().z(), 1 + gDbvtMargin, tolerance);
	// The next move of the same size stays in the predicted box: the tree is not touched.
	broadphase.calculateOverlappingPairs(0);
	broadphase.setAabb(proxy, btVector3(2, -1, 0), btVector3(3, 0, 1), 0);
	EXPECT_FALSE(broadphase.m_needcleanup);
	broadphase.setVelocityPrediction(-3);
	EXPECT_EQ(broadphase.getVelocityPrediction(), btScalar(0));
}

TEST(DbvtBroadphase, ForcedUpdateMakesTheBoxExactAndRemovesStalePairs)
{
	btDbvtBroadphase broadphase;
	CountingDispatcher dispatcher;
	btBroadphaseProxy* a = broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	btBroadphaseProxy* b =
	    broadphase.createProxy(btVector3(1.02f, 0, 0), btVector3(2, 1, 1), 0, idToClient(1), 1, -1, 0);
	broadphase.calculateOverlappingPairs(&dispatcher);
	// 0.02 apart, but the margins (0.05 each) overlap: a pair of fat boxes only.
	ASSERT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1);
	dispatcher.attachAlgorithm(broadphase.getOverlappingPairCache()->getOverlappingPairArray()[0]);
	broadphase.setAabbForceUpdate(a, btVector3(0, 0, 0), btVector3(1, 1, 1), &dispatcher);
	broadphase.setAabbForceUpdate(b, btVector3(1.02f, 0, 0), btVector3(2, 1, 1), &dispatcher);
	EXPECT_EQ(fatBox(a).Maxs(), btVector3(1, 1, 1));
	broadphase.calculateOverlappingPairs(&dispatcher);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
	EXPECT_EQ(dispatcher.freed, 1);
}

TEST(DbvtBroadphase, MovingAStaticProxyUpdatesItsPairs)
{
	btDbvtBroadphase broadphase;
	btBroadphaseProxy* ground =
	    broadphase.createProxy(btVector3(-10, -1, -10), btVector3(10, 0, 10), 0, idToClient(0),
	                           btBroadphaseProxy::StaticFilter, -1 ^ btBroadphaseProxy::StaticFilter, 0);
	btBroadphaseProxy* box = broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(1), 1, -1, 0);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_NE(broadphase.getOverlappingPairCache()->findPair(ground, box), nullptr);
	broadphase.setAabb(ground, btVector3(-10, -11, -10), btVector3(10, -10, 10), 0);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
	broadphase.setAabb(ground, btVector3(-10, -1, -10), btVector3(10, 0.5f, 10), 0);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_NE(broadphase.getOverlappingPairCache()->findPair(ground, box), nullptr);
}

TEST(DbvtBroadphase, TreesStayShallowUnderMotionAndAfterOptimize)
{
	const int objects = 1000 / kScale;
	MovingScene scene(6, objects, kRange, 1, btScalar(0.5));
	btDbvtBroadphase broadphase;
	for (int i = 0; i < objects; ++i) scene.create(broadphase, i, 0);
	for (int frame = 0; frame < 60 / kScale; ++frame) scene.frame(broadphase, 0, 0);
	// A balanced tree of n leaves has depth log2(n) + 1 (11 for 1000); allow 3x for insertion order.
	const int bound = 3 * (int(std::log2(double(objects))) + 1);
	const int depth = btDbvt::maxdepth(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_root);
	EXPECT_LE(depth, bound);
	broadphase.optimize();
	EXPECT_LE(btDbvt::maxdepth(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_root), bound);
	// Optimising changes no box, so the pairs stay exact.
	scene.frame(broadphase, 0, 0);
	EXPECT_EQ(cachePairs(broadphase.getOverlappingPairCache()), fatReferencePairs(scene));
	btVector3 lo, hi;
	broadphase.getBroadphaseAabb(lo, hi);
	for (const SceneObject& object : scene.objects())
	{
		EXPECT_TRUE(boxesOverlap(lo, hi, object.aabbMin(), object.aabbMax()));
		for (int axis = 0; axis < 3; ++axis) EXPECT_LE(lo[axis], object.aabbMin()[axis]);
	}
}

// The same inputs give the same pair array, in the same order, every frame.
std::vector<IdPair> runAndRecordPairOrder(unsigned seed)
{
	const int objects = 300 / kScale;
	MovingScene scene(seed, objects, 12, 2, btScalar(0.3));
	scene.assignFilters(10, 0);
	btDbvtBroadphase broadphase;
	for (int i = 0; i < objects; ++i) scene.create(broadphase, i, 0);
	std::vector<IdPair> order;
	for (int frame = 0; frame < 20; ++frame)
	{
		scene.frame(broadphase, 0, objects / 30);
		const btBroadphasePairArray& pairs = broadphase.getOverlappingPairCache()->getOverlappingPairArray();
		for (int i = 0; i < pairs.size(); ++i)
			order.push_back(IdPair(clientToId(pairs[i].m_pProxy0), clientToId(pairs[i].m_pProxy1)));
		order.push_back(IdPair(-1, frame));
	}
	return order;
}

TEST(DbvtBroadphase, SameInputsGiveTheSamePairOrder)
{
	const std::vector<IdPair> first = runAndRecordPairOrder(9);
	const std::vector<IdPair> second = runAndRecordPairOrder(9);
	EXPECT_GT(first.size(), 100u);
	EXPECT_TRUE(first == second);
}

TEST(DbvtBroadphase, ResetPoolRestartsIdsOnlyWhenEmpty)
{
	btDbvtBroadphase broadphase;
	btBroadphaseProxy* a = broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	btBroadphaseProxy* b = broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(1), 1, -1, 0);
	broadphase.destroyProxy(a, 0);
	broadphase.resetPool(0);
	EXPECT_EQ(broadphase.m_gid, 2) << "reset with a live proxy";
	broadphase.destroyProxy(b, 0);
	broadphase.resetPool(0);
	EXPECT_EQ(broadphase.m_gid, 0);
	btVector3 lo, hi;
	broadphase.getBroadphaseAabb(lo, hi);
	EXPECT_EQ(lo, btVector3(0, 0, 0));
	EXPECT_EQ(hi, btVector3(0, 0, 0));
	// Proxies left alive are freed by the destructor (the ASan build checks for leaks).
	broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(2), 1, -1, 0);
}

// The tree of a proxy is fixed at creation by the StaticFilter bit and written in its id's parity (Bullet's
// btDbvtProxy has no field for it): ids grow with creation order, a recycled proxy gets a fresh id for its
// new tree, and a filter group changed later does not move the proxy.
TEST(DbvtBroadphase, ProxyTreeFollowsTheFilterGroupAtCreation)
{
	btDbvtBroadphase broadphase;
	const int staticGroup = btBroadphaseProxy::StaticFilter;
	btBroadphaseProxy* moving = broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	btBroadphaseProxy* fixed =
	    broadphase.createProxy(btVector3(0, -1, 0), btVector3(9, 0, 9), 0, idToClient(1), staticGroup, -1, 0);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_leaves, 1);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::FIXED_SET].m_leaves, 1);
	EXPECT_EQ(moving->getUid() % 2, 0);
	EXPECT_EQ(fixed->getUid() % 2, 1);
	EXPECT_LT(moving->getUid(), fixed->getUid()) << "ids follow creation order";

	// A group changed after creation leaves the proxy where it is; moving and destroying it still work.
	moving->m_collisionFilterGroup = staticGroup;
	broadphase.setAabb(moving, btVector3(5, 5, 5), btVector3(6, 6, 6), 0);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_leaves, 1);
	broadphase.destroyProxy(moving, 0);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_leaves, 0);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::FIXED_SET].m_leaves, 1);

	// The destroyed proxy's memory comes back for a static proxy, now in the fixed tree with a new odd id.
	btBroadphaseProxy* recycled =
	    broadphase.createProxy(btVector3(2, -1, 2), btVector3(3, 0, 3), 0, idToClient(2), staticGroup, -1, 0);
	EXPECT_EQ(recycled, moving);
	EXPECT_EQ(recycled->getUid() % 2, 1);
	EXPECT_GT(recycled->getUid(), fixed->getUid());
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::FIXED_SET].m_leaves, 2);
	broadphase.destroyProxy(recycled, 0);
	broadphase.destroyProxy(fixed, 0);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::FIXED_SET].m_leaves, 0);
}

TEST(DbvtBroadphase, BadInputIsRejectedWithoutTouchingState)
{
	btDbvtBroadphase broadphase;
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btScalar inf = std::numeric_limits<btScalar>::infinity();
	btBroadphaseProxy* good =
	    broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	btBroadphaseProxy* other =
	    broadphase.createProxy(btVector3(0.5, 0, 0), btVector3(2, 1, 1), 0, idToClient(1), 1, -1, 0);
	broadphase.destroyProxy(0, 0);  // ignored, documented
	broadphase.calculateOverlappingPairs(0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(broadphase.createProxy(btVector3(nan, 0, 0), btVector3(1, 1, 1), 0, idToClient(2), 1, -1, 0),
	             "assertion failed");
	EXPECT_DEATH(broadphase.setAabb(good, btVector3(0, 0, 0), btVector3(inf, 1, 1), 0), "assertion failed");
	EXPECT_DEATH(broadphase.setAabbForceUpdate(good, btVector3(nan, 0, 0), btVector3(1, 1, 1), 0), "assertion failed");
#else
	EXPECT_EQ(broadphase.createProxy(btVector3(nan, 0, 0), btVector3(1, 1, 1), 0, idToClient(2), 1, -1, 0), nullptr);
	EXPECT_EQ(broadphase.createProxy(btVector3(0, 0, 0), btVector3(inf, 1, 1), 0, idToClient(2), 1, -1, 0), nullptr);
	broadphase.setAabb(good, btVector3(0, 0, 0), btVector3(inf, 1, 1), 0);
	broadphase.setAabb(good, btVector3(nan, nan, nan), btVector3(nan, nan, nan), 0);
	broadphase.setAabbForceUpdate(good, btVector3(nan, 0, 0), btVector3(1, 1, 1), 0);
	broadphase.setAabb(0, btVector3(0, 0, 0), btVector3(1, 1, 1), 0);
#endif
	broadphase.calculateOverlappingPairs(0);
	btVector3 lo, hi;
	broadphase.getAabb(good, lo, hi);
	EXPECT_EQ(lo, btVector3(0, 0, 0));
	EXPECT_EQ(hi, btVector3(1, 1, 1));
	EXPECT_TRUE(boxIsFinite(fatBox(good)));
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_leaves, 2);
	EXPECT_NE(broadphase.getOverlappingPairCache()->findPair(good, other), nullptr);
	// Huge finite boxes (a static plane's) are fine.
	btBroadphaseProxy* plane =
	    broadphase.createProxy(btVector3(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT),
	                           btVector3(BT_LARGE_FLOAT, 0, BT_LARGE_FLOAT), 0, idToClient(3), 1, -1, 0);
	ASSERT_NE(plane, nullptr);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 3);

	// A destroyed proxy is kept for reuse, so using it again is caught rather than touching freed memory.
	broadphase.destroyProxy(plane, 0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(broadphase.destroyProxy(plane, 0), "already destroyed");
	EXPECT_DEATH(broadphase.setAabb(plane, btVector3(0, 0, 0), btVector3(1, 1, 1), 0), "was destroyed");
#else
	broadphase.destroyProxy(plane, 0);
	broadphase.setAabb(plane, btVector3(0, 0, 0), btVector3(1, 1, 1), 0);
	broadphase.setAabbForceUpdate(plane, btVector3(0, 0, 0), btVector3(1, 1, 1), 0);
#endif
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_leaves, 2) << "the destroyed proxy stays out";
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1);
	// The next proxy reuses the destroyed one's memory and works normally.
	btBroadphaseProxy* reused =
	    broadphase.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(4), 1, -1, 0);
	EXPECT_EQ(reused, plane);
	broadphase.calculateOverlappingPairs(0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 3);
}
}  // namespace
