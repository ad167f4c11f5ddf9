// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btAxisSweep3 and bt32BitAxisSweep3 against independent brute-force references. Sweep and prune decides
// overlap on its quantisation grid, so every frame the pairs must equal, exactly, the filtered pairs
// whose grid boxes overlap (computed here from the public quantize() of each box clamped to the world),
// and must contain every pair whose real boxes overlap (the grid only ever grows boxes). Also the
// deferred-removal cache, boxes leaving the world bounds, the queries, the user pair callback and bad
// input.

#include <gtest/gtest.h>

#include <iterator>
#include <limits>

#include "BroadphaseTestUtil.h"
#include "BulletCollision/BroadphaseCollision/btAxisSweep3.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "LinearMath/btWarningHook.h"

namespace
{
using namespace broadphase_test;

const btScalar kRange = 20;

struct GridBox
{
	unsigned long long lo[3];
	unsigned long long hi[3];
};

// The grid box of a live object: its AABB clamped to the world, quantised like the broadphase says it does.
template <typename Sweep, typename IntType>
GridBox gridBoxOf(const Sweep& sweep, const SceneObject& object, const btVector3& worldMin, const btVector3& worldMax)
{
	btVector3 lo = object.aabbMin(), hi = object.aabbMax();
	lo.setMax(worldMin);
	lo.setMin(worldMax);
	hi.setMin(worldMax);
	hi.setMax(worldMin);
	IntType qlo[3], qhi[3];
	sweep.quantize(qlo, lo, 0);
	sweep.quantize(qhi, hi, 1);
	GridBox box;
	for (int axis = 0; axis < 3; ++axis)
	{
		box.lo[axis] = qlo[axis];
		box.hi[axis] = qhi[axis];
	}
	return box;
}

// Filtered pairs whose grid boxes overlap. Min positions are even and max positions odd, so the strict
// test is the overlap of the closed grid boxes.
template <typename Sweep, typename IntType>
IdPairSet gridReferencePairs(const Sweep& sweep, MovingScene& scene, const btVector3& worldMin,
                             const btVector3& worldMax)
{
	std::vector<SceneObject>& objects = scene.objects();
	std::vector<GridBox> boxes(objects.size());
	for (size_t i = 0; i < objects.size(); ++i)
		if (objects[i].alive) boxes[i] = gridBoxOf<Sweep, IntType>(sweep, objects[i], worldMin, worldMax);
	IdPairSet result;
	for (size_t i = 0; i < objects.size(); ++i)
	{
		if (!objects[i].alive) continue;
		for (size_t j = i + 1; j < objects.size(); ++j)
		{
			if (!objects[j].alive) continue;
			bool overlap = true;
			for (int axis = 0; axis < 3 && overlap; ++axis)
				overlap = boxes[i].lo[axis] < boxes[j].hi[axis] && boxes[j].lo[axis] < boxes[i].hi[axis];
			if (!overlap) continue;
			if (!groupMaskAccepts(objects[i].group, objects[i].mask, objects[j].group, objects[j].mask)) continue;
			result.insert(IdPair(int(i), int(j)));
		}
	}
	return result;
}

bool isSubset(const IdPairSet& small, const IdPairSet& big)
{
	for (const IdPair& p : small)
		if (!big.count(p)) return false;
	return true;
}

// A moving scene in the world [-worldHalf, worldHalf]^3 (objects roam over +-sceneRange, so a scene
// range above worldHalf makes them cross the bounds), compared with the references every frame.
template <typename Sweep, typename IntType>
void runScene(btOverlappingPairCache* cache, unsigned seed, int fullObjects, int fullFrames, btScalar sceneRange,
              btScalar worldHalf)
{
	const int objects = fullObjects / kScale;
	const int frames = fullFrames / kScale;
	const btVector3 worldMin(-worldHalf, -worldHalf, -worldHalf), worldMax(worldHalf, worldHalf, worldHalf);
	MovingScene scene(seed, objects, sceneRange, 2, btScalar(0.3));
	scene.assignFilters(10, 7);
	Sweep sweep(worldMin, worldMax, IntType(objects + 8), cache);
	CountingDispatcher dispatcher;
	RecordingPairCallback ghost;
	sweep.getOverlappingPairCache()->setInternalGhostPairCallback(&ghost);
	for (int i = 0; i < objects; ++i)
		if (i % 5 != 4) scene.create(sweep, i, &dispatcher);
	sweep.calculateOverlappingPairs(&dispatcher);
	size_t trueMax = 0;
	for (int frame = 0; frame < frames; ++frame)
	{
		const IdPairSet actual = cachePairs(sweep.getOverlappingPairCache());
		const IdPairSet gridPairs = gridReferencePairs<Sweep, IntType>(sweep, scene, worldMin, worldMax);
		const IdPairSet truePairs = scene.referencePairs();
		ASSERT_EQ(actual, gridPairs) << "frame " << frame << describeDifference(gridPairs, actual);
		ASSERT_TRUE(isSubset(truePairs, actual)) << "frame " << frame << describeDifference(truePairs, actual);
		ASSERT_EQ(ghost.m_pairs, actual) << "frame " << frame;
		trueMax = std::max(trueMax, truePairs.size());
		// Give some pairs an algorithm, so that removals must free them.
		btBroadphasePairArray& pairs = sweep.getOverlappingPairCache()->getOverlappingPairArray();
		for (int i = 0; i < pairs.size(); i += 7)
			if (!pairs[i].m_algorithm) dispatcher.attachAlgorithm(pairs[i]);
		scene.frame(sweep, &dispatcher, objects / 50);
		ASSERT_EQ(int(sweep.getNumHandles()), int(std::count_if(scene.objects().begin(), scene.objects().end(),
		                                                        [](const SceneObject& o) { return o.alive; })));
	}
	EXPECT_EQ(ghost.m_errors, 0);
	EXPECT_GT(trueMax, size_t(objects) / 20) << "the scene is too sparse to test anything";
	sweep.getOverlappingPairCache()->setInternalGhostPairCallback(0);
	for (int i = 0; i < objects; ++i)
		if (scene.objects()[size_t(i)].alive) scene.destroy(sweep, i, &dispatcher);
	EXPECT_EQ(sweep.getNumHandles(), IntType(0));
	EXPECT_EQ(sweep.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
	EXPECT_EQ(dispatcher.freed, dispatcher.allocated);
	EXPECT_EQ(dispatcher.destroyed, dispatcher.allocated);
}
}  // namespace

TEST(AxisSweep3, PairsEqualGridOverlapsAndCoverTrueOverlapsEveryFrame)
{
	runScene<btAxisSweep3, unsigned short>(0, 1, 1000, 100, kRange, kRange + 5);
}

TEST(AxisSweep3, ThirtyTwoBitPairsEqualGridOverlapsEveryFrame)
{
	runScene<bt32BitAxisSweep3, unsigned int>(0, 2, 1000, 100, kRange, kRange + 5);
}

TEST(AxisSweep3, TenThousandMovingBoxesKeepExactPairs)
{
	// Same density as the 1,000-box scene (range grown by the cube root of 10); the reference is
	// quadratic, so only a few frames.
	runScene<btAxisSweep3, unsigned short>(0, 3, 10000, 8, kRange * btScalar(2.154), kRange * btScalar(2.154) + 5);
}

TEST(AxisSweep3, DeferredRemovalCacheDropsStalePairsInCalculateOverlappingPairs)
{
	btSortedOverlappingPairCache cache;
	runScene<btAxisSweep3, unsigned short>(&cache, 4, 500, 60, kRange, kRange + 5);
}

// Objects roam over +-20 in a world of +-12: they leave and re-enter it on every side. Outside, their
// boxes are clamped (flat on the boundary), and the pairs still equal the clamped grid boxes' overlaps.
TEST(AxisSweep3, BoxesCrossingTheWorldBoundsAreClampedToThem)
{
	runScene<btAxisSweep3, unsigned short>(0, 5, 600, 80, kRange, btScalar(12));
	runScene<bt32BitAxisSweep3, unsigned int>(0, 6, 600, 40, kRange, btScalar(12));
}

TEST(AxisSweep3, QuantisationKeepsTouchingBoxesTogetherAndOrderMonotonic)
{
	btAxisSweep3 sweep(btVector3(-10, -10, -10), btVector3(10, 10, 10), 16, 0, true);
	// Boxes that touch on a face overlap on the grid; boxes a grid cell apart or more may or may not, but
	// boxes 1 unit apart (about 3,300 cells) never do.
	btBroadphaseProxy* a = sweep.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	btBroadphaseProxy* touching = sweep.createProxy(btVector3(1, 0, 0), btVector3(2, 1, 1), 0, idToClient(1), 1, -1, 0);
	btBroadphaseProxy* apart = sweep.createProxy(btVector3(2, 0, 0), btVector3(3, 1, 1), 0, idToClient(2), 1, -1, 0);
	EXPECT_TRUE(sweep.testAabbOverlap(a, touching));
	EXPECT_FALSE(sweep.testAabbOverlap(a, apart));
	EXPECT_TRUE(sweep.getOverlappingPairCache()->findPair(a, touching) != 0);
	EXPECT_TRUE(sweep.getOverlappingPairCache()->findPair(a, apart) == 0);

	// quantize is monotonic, min positions even, max positions odd, clamped at the bounds.
	unsigned short previous[3] = {0, 0, 0};
	for (int i = 0; i <= 200; ++i)
	{
		const btScalar x = btScalar(-12) + btScalar(i) * btScalar(0.12);
		unsigned short lo[3], hi[3];
		sweep.quantize(lo, btVector3(x, x, x), 0);
		sweep.quantize(hi, btVector3(x, x, x), 1);
		for (int axis = 0; axis < 3; ++axis)
		{
			EXPECT_EQ(lo[axis] % 2, 0) << x;
			EXPECT_EQ(hi[axis] % 2, 1) << x;
			EXPECT_GT(hi[axis], lo[axis]) << x;
			EXPECT_GE(lo[axis], previous[axis]) << x;
			previous[axis] = lo[axis];
		}
	}
	unsigned short bottom[3], top[3];
	sweep.quantize(bottom, btVector3(-1000, -1000, -1000), 0);
	sweep.quantize(top, btVector3(1000, 1000, 1000), 1);
	EXPECT_EQ(bottom[0], 0);
	EXPECT_EQ(top[0], 0xffff);

	// unQuantize brackets the real box to within one cell (20 / 65,534 per axis).
	btVector3 lo, hi;
	sweep.unQuantize(a, lo, hi);
	const btScalar cell = btScalar(20.0 / 65534.0);
	for (int axis = 0; axis < 3; ++axis)
	{
		EXPECT_LE(lo[axis], btScalar(0) + btScalar(1e-6));
		EXPECT_GE(lo[axis], -cell * 2);
		EXPECT_NEAR(hi[axis], btScalar(1), cell * 2);
	}
	btVector3 worldMin, worldMax;
	sweep.getBroadphaseAabb(worldMin, worldMax);
	EXPECT_EQ(worldMin, btVector3(-10, -10, -10));
	EXPECT_EQ(worldMax, btVector3(10, 10, 10));
}

TEST(AxisSweep3, AabbAndRayQueriesMatchBruteForceWithAndWithoutAccelerator)
{
	for (int accelerated = 0; accelerated < 2; ++accelerated)
	{
		const int objects = 600 / kScale;
		MovingScene scene(7, objects, kRange, 2, btScalar(0.5));
		scene.assignFilters(8, 0);
		btAxisSweep3 sweep(btVector3(-30, -30, -30), btVector3(30, 30, 30), 1024, 0, accelerated == 0);
		for (int i = 0; i < objects; ++i)
			if (i % 4 != 3) scene.create(sweep, i, 0);
		for (int round = 0; round < 3; ++round)
		{
			checkAabbQueries(sweep, scene, 100 / kScale, kRange);
			checkRayQueries(sweep, scene, 100 / kScale, kRange);
			scene.frame(sweep, 0, objects / 20);
		}
	}
}

TEST(AxisSweep3, UserPairCallbackSeesEveryAddAndRemove)
{
	const int objects = 300 / kScale;
	MovingScene scene(9, objects, kRange, 2, btScalar(0.4));
	btAxisSweep3 sweep(btVector3(-25, -25, -25), btVector3(25, 25, 25), 512);
	// A callback that only mirrors adds and removes (the bulk removal of a destroyed proxy is mirrored
	// by dropping that proxy's pairs).
	struct Mirror : public btOverlappingPairCallback
	{
		IdPairSet pairs;
		btBroadphasePair* addOverlappingPair(btBroadphaseProxy* p0, btBroadphaseProxy* p1) override
		{
			pairs.insert(makeIdPair(clientToId(p0), clientToId(p1)));
			return 0;
		}
		void* removeOverlappingPair(btBroadphaseProxy* p0, btBroadphaseProxy* p1, btDispatcher*) override
		{
			pairs.erase(makeIdPair(clientToId(p0), clientToId(p1)));
			return 0;
		}
		void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher*) override
		{
			const int id = clientToId(proxy);
			for (IdPairSet::iterator it = pairs.begin(); it != pairs.end();)
				it = (it->first == id || it->second == id) ? pairs.erase(it) : std::next(it);
		}
	} mirror;
	sweep.setOverlappingPairUserCallback(&mirror);
	EXPECT_EQ(sweep.getOverlappingPairUserCallback(), &mirror);
	for (int i = 0; i < objects; ++i) scene.create(sweep, i, 0);
	for (int frame = 0; frame < 40 / kScale; ++frame)
	{
		// The user callback is told of every overlap of the grid boxes, unfiltered (as in Bullet).
		IdPairSet expected;
		for (int i = 0; i < objects; ++i)
		{
			if (!scene.objects()[size_t(i)].alive) continue;
			for (int j = i + 1; j < objects; ++j)
			{
				if (!scene.objects()[size_t(j)].alive) continue;
				if (sweep.testAabbOverlap(scene.objects()[size_t(i)].proxy, scene.objects()[size_t(j)].proxy))
					expected.insert(IdPair(i, j));
			}
		}
		ASSERT_EQ(mirror.pairs, expected) << "frame " << frame;
		scene.frame(sweep, 0, objects / 30);
	}
	sweep.setOverlappingPairUserCallback(0);
}

TEST(AxisSweep3, BadInputIsRejectedAndTheBroadphaseKeepsWorking)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	btAxisSweep3 sweep(btVector3(-10, -10, -10), btVector3(10, 10, 10), 3);
	btBroadphaseProxy* a = sweep.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	btBroadphaseProxy* b = sweep.createProxy(btVector3(0.5, 0, 0), btVector3(2, 1, 1), 0, idToClient(1), 1, -1, 0);
	btBroadphaseProxy* c = sweep.createProxy(btVector3(5, 5, 5), btVector3(6, 6, 6), 0, idToClient(2), 1, -1, 0);
	ASSERT_TRUE(a && b && c);
	btSimpleBroadphase other;
	btBroadphaseProxy* foreign = other.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(9), 1, -1, 0);
	sweep.destroyProxy(0, 0);  // ignored, documented
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(sweep.createProxy(btVector3(nan, 0, 0), btVector3(1, 1, 1), 0, idToClient(3), 1, -1, 0),
	             "non-finite AABB");
	EXPECT_DEATH(sweep.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(3), 1, -1, 0),
	             "all handles are in use");
	EXPECT_DEATH(sweep.setAabb(a, btVector3(0, 0, 0), btVector3(nan, 1, 1), 0), "non-finite AABB");
	EXPECT_DEATH(sweep.destroyProxy(foreign, 0), "not a proxy of this broadphase");
	EXPECT_DEATH(sweep.setAabb(foreign, btVector3(0, 0, 0), btVector3(1, 1, 1), 0), "not a proxy of this broadphase");
	sweep.destroyProxy(c, 0);
	EXPECT_DEATH(sweep.destroyProxy(c, 0), "not in use");
	EXPECT_DEATH(sweep.setAabb(c, btVector3(0, 0, 0), btVector3(1, 1, 1), 0), "was destroyed");
	EXPECT_DEATH(btAxisSweep3(btVector3(1, 0, 0), btVector3(0, 1, 1)), "world bounds");
#else
	EXPECT_EQ(sweep.createProxy(btVector3(nan, 0, 0), btVector3(1, 1, 1), 0, idToClient(3), 1, -1, 0), nullptr);
	EXPECT_EQ(sweep.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(3), 1, -1, 0), nullptr)
	    << "pool full";
	sweep.setAabb(a, btVector3(0, 0, 0), btVector3(nan, 1, 1), 0);
	sweep.destroyProxy(foreign, 0);
	sweep.setAabb(foreign, btVector3(0, 0, 0), btVector3(1, 1, 1), 0);
	sweep.destroyProxy(c, 0);
	sweep.destroyProxy(c, 0);
	sweep.setAabb(c, btVector3(0, 0, 0), btVector3(1, 1, 1), 0);
	// Reversed bounds are swapped: the broadphase still works.
	btAxisSweep3 repaired(btVector3(1, 0, 0), btVector3(0, 1, 1));
	btVector3 boundsMin, boundsMax;
	repaired.getBroadphaseAabb(boundsMin, boundsMax);
	EXPECT_EQ(boundsMin, btVector3(0, 0, 0));
	EXPECT_EQ(boundsMax, btVector3(1, 1, 1));
#endif
	other.destroyProxy(foreign, 0);
	sweep.calculateOverlappingPairs(0);
	EXPECT_EQ(sweep.getNumHandles(), 2);
	btVector3 lo, hi;
	sweep.getAabb(a, lo, hi);
	EXPECT_EQ(hi, btVector3(1, 1, 1)) << "the rejected box left the old one";
	EXPECT_TRUE(sweep.getOverlappingPairCache()->findPair(a, b) != 0);
	EXPECT_EQ(sweep.getOverlappingPairCache()->getNumOverlappingPairs(), 1);
	// Far outside the bounds: clamped (one warning), still paired with a box at the same corner.
	sweep.setAabb(a, btVector3(1e6, 1e6, 1e6), btVector3(1e6 + 1, 1e6 + 1, 1e6 + 1), 0);
	sweep.setAabb(b, btVector3(9.5, 9.5, 9.5), btVector3(11, 11, 11), 0);
	EXPECT_TRUE(sweep.getOverlappingPairCache()->findPair(a, b) != 0);
	// The freed slot is reused and the pool is whole again once empty.
	btBroadphaseProxy* d = sweep.createProxy(btVector3(-1, -1, -1), btVector3(0, 0, 0), 0, idToClient(4), 1, -1, 0);
	EXPECT_TRUE(d != 0);
	sweep.destroyProxy(a, 0);
	sweep.destroyProxy(b, 0);
	sweep.destroyProxy(d, 0);
	sweep.resetPool(0);
	EXPECT_EQ(sweep.getNumHandles(), 0);
	EXPECT_EQ(sweep.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
}

// In a collision world: spheres resting on each other are paired through the sweep, rays find them
// through the accelerator, and an object the full pool refuses stays in the world without a proxy.
TEST(AxisSweep3, CollisionWorldRunsOnTheSweepAndSurvivesAFullPool)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btAxisSweep3 sweep(btVector3(-50, -50, -50), btVector3(50, 50, 50), 2);
	btCollisionWorld world(&dispatcher, &sweep, &configuration);
	btSphereShape sphere(1);
	btCollisionObject objects[3];
	for (int i = 0; i < 3; ++i)
	{
		objects[i].setCollisionShape(&sphere);
		btTransform pose;
		pose.setIdentity();
		pose.setOrigin(btVector3(btScalar(1.5) * btScalar(i), 0, 0));
		objects[i].setWorldTransform(pose);
	}
	world.addCollisionObject(&objects[0]);
	world.addCollisionObject(&objects[1]);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(world.addCollisionObject(&objects[2]), "all handles are in use");
#else
	world.addCollisionObject(&objects[2]);
	EXPECT_EQ(world.getNumCollisionObjects(), 3);
	EXPECT_TRUE(objects[2].getBroadphaseHandle() == 0);
	EXPECT_EQ(objects[2].getActivationState(), DISABLE_SIMULATION);
#endif
	world.performDiscreteCollisionDetection();
	ASSERT_EQ(dispatcher.getNumManifolds(), 1);
	// Centres 1.5 apart, radii 1: 0.5 deep.
	ASSERT_EQ(dispatcher.getManifoldByIndexInternal(0)->getNumContacts(), 1);
	EXPECT_NEAR(dispatcher.getManifoldByIndexInternal(0)->getContactPoint(0).getDistance(), btScalar(-0.5),
	            btScalar(1e-5));
	btCollisionWorld::ClosestRayResultCallback ray(btVector3(-10, 0, 0), btVector3(10, 0, 0));
	world.rayTest(btVector3(-10, 0, 0), btVector3(10, 0, 0), ray);
	ASSERT_TRUE(ray.hasHit());
	EXPECT_EQ(ray.m_collisionObject, &objects[0]);
	EXPECT_NEAR(ray.m_closestHitFraction, btScalar(9.0 / 20.0), btScalar(1e-5));
#if !CALIBER_ASSERTS_ENABLED
	world.removeCollisionObject(&objects[2]);
#endif
	world.removeCollisionObject(&objects[1]);
	world.removeCollisionObject(&objects[0]);
	EXPECT_EQ(sweep.getNumHandles(), 0);
}

// A box beyond the world bounds is clamped onto them (not an error: the object stays in the simulation),
// and the broadphase says so once, since pairs near the bounds may then be reported without touching.
TEST(AxisSweep3, ABoxOutsideTheWorldBoundsIsClampedWithOneWarning)
{
	int warnings = 0;
	btSetWarningHook([](const char*, void* count) { ++*static_cast<int*>(count); }, &warnings);
	btAxisSweep3 sweep(btVector3(-10, -10, -10), btVector3(10, 10, 10), 16, 0, true);
	btBroadphaseProxy* inside = sweep.createProxy(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, idToClient(0), 1, -1, 0);
	EXPECT_EQ(warnings, 0) << "a box inside the bounds is not reported";
	// Both boxes lie beyond x = 10, 5 units apart: clamped, they share the flat box on the boundary.
	btBroadphaseProxy* a = sweep.createProxy(btVector3(20, 0, 0), btVector3(21, 1, 1), 0, idToClient(1), 1, -1, 0);
	btBroadphaseProxy* b = sweep.createProxy(btVector3(26, 0, 0), btVector3(27, 1, 1), 0, idToClient(2), 1, -1, 0);
	ASSERT_NE(a, nullptr);
	ASSERT_NE(b, nullptr);
	EXPECT_EQ(warnings, 1) << "one warning per broadphase";
	EXPECT_TRUE(sweep.testAabbOverlap(a, b)) << "clamped onto the same boundary";
	EXPECT_FALSE(sweep.testAabbOverlap(a, inside));
	btSetWarningHook(0, 0);
}
