// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <new>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "LinearMath/btPoolAllocator.h"
#include "DispatchTestUtil.h"

using caliber_dispatch_test::ArrayPairCache;
using caliber_dispatch_test::ProxyObject;

namespace
{
// Forwards to the default configuration's factory and records which table entry was used, so that
// the dispatcher's matrix can be checked without RTTI.
struct SpyCreateFunc : public btCollisionAlgorithmCreateFunc
{
	btCollisionAlgorithmCreateFunc* m_inner = 0;
	int m_type0 = -1;
	int m_type1 = -1;
	bool m_closestPoints = false;
	int* m_lastUsed = 0;

	btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
	                                               const btCollisionObjectWrapper* body0Wrap,
	                                               const btCollisionObjectWrapper* body1Wrap) override
	{
		m_lastUsed[0] = m_type0;
		m_lastUsed[1] = m_type1;
		m_lastUsed[2] = m_closestPoints ? 1 : 0;
		return m_inner->CreateCollisionAlgorithm(ci, body0Wrap, body1Wrap);
	}
};

// Wraps (rather than derives from) the default configuration, whose own lookups call each other.
class SpyConfiguration : public btCollisionConfiguration
{
public:
	SpyConfiguration()
	{
		for (int i = 0; i < MAX_BROADPHASE_COLLISION_TYPES; ++i)
		{
			for (int j = 0; j < MAX_BROADPHASE_COLLISION_TYPES; ++j)
			{
				setUp(m_contact[i][j], m_inner.getCollisionAlgorithmCreateFunc(i, j), i, j, false);
				setUp(m_closest[i][j], m_inner.getClosestPointsAlgorithmCreateFunc(i, j), i, j, true);
			}
		}
	}
	btPoolAllocator* getPersistentManifoldPool() override { return m_inner.getPersistentManifoldPool(); }
	btPoolAllocator* getCollisionAlgorithmPool() override { return m_inner.getCollisionAlgorithmPool(); }
	btCollisionAlgorithmCreateFunc* getCollisionAlgorithmCreateFunc(int type0, int type1) override
	{
		++m_contactQueries;
		return &m_contact[type0][type1];
	}
	btCollisionAlgorithmCreateFunc* getClosestPointsAlgorithmCreateFunc(int type0, int type1) override
	{
		++m_closestQueries;
		return &m_closest[type0][type1];
	}

	int m_lastUsed[3] = {-1, -1, -1};
	int m_contactQueries = 0;
	int m_closestQueries = 0;

private:
	btDefaultCollisionConfiguration m_inner;
	void setUp(SpyCreateFunc& spy, btCollisionAlgorithmCreateFunc* inner, int i, int j, bool closest)
	{
		spy.m_inner = inner;
		spy.m_type0 = i;
		spy.m_type1 = j;
		spy.m_closestPoints = closest;
		spy.m_lastUsed = m_lastUsed;
	}
	SpyCreateFunc m_contact[MAX_BROADPHASE_COLLISION_TYPES][MAX_BROADPHASE_COLLISION_TYPES];
	SpyCreateFunc m_closest[MAX_BROADPHASE_COLLISION_TYPES][MAX_BROADPHASE_COLLISION_TYPES];
};

void destroyAlgorithm(btDispatcher& dispatcher, btCollisionAlgorithm* algorithm)
{
	if (!algorithm) return;
	algorithm->~btCollisionAlgorithm();
	dispatcher.freeCollisionAlgorithm(algorithm);
}

btTransform at(const btVector3& origin)
{
	btTransform t;
	t.setIdentity();
	t.setOrigin(origin);
	return t;
}

// A user shape: a sphere that reports its own type, so that only a registered algorithm knows it.
class CustomShape : public btSphereShape
{
public:
	explicit CustomShape(btScalar radius) : btSphereShape(radius) { m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE; }
};

// A user algorithm that reports one fixed, recognisable point into its own manifold.
class CustomAlgorithm : public btCollisionAlgorithm
{
public:
	CustomAlgorithm(const btCollisionAlgorithmConstructionInfo& ci, const btCollisionObject* body0,
	                const btCollisionObject* body1)
	    : btCollisionAlgorithm(ci), m_manifold(ci.m_dispatcher1->getNewManifold(body0, body1))
	{
	}
	~CustomAlgorithm() override { m_dispatcher->releaseManifold(m_manifold); }
	void processCollision(const btCollisionObjectWrapper*, const btCollisionObjectWrapper*, const btDispatcherInfo&,
	                      btManifoldResult* resultOut) override
	{
		resultOut->setPersistentManifold(m_manifold);
		resultOut->addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), btScalar(-0.125));
	}
	btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
	                               btManifoldResult*) override
	{
		return btScalar(1);
	}
	void getAllContactManifolds(btManifoldArray& manifolds) override { manifolds.push_back(m_manifold); }

	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		int m_created = 0;
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			++m_created;
			void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(int(sizeof(CustomAlgorithm)));
			return new (memory) CustomAlgorithm(ci, body0Wrap->getCollisionObject(), body1Wrap->getCollisionObject());
		}
	};

private:
	btPersistentManifold* m_manifold;
};
}  // namespace

TEST(CollisionDispatcher, MatrixIsFilledFromTheConfigurationForEveryTypePair)
{
	SpyConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	const int cells = MAX_BROADPHASE_COLLISION_TYPES * MAX_BROADPHASE_COLLISION_TYPES;
	EXPECT_EQ(config.m_contactQueries, cells);
	EXPECT_EQ(config.m_closestQueries, cells);

	btSphereShape sphere(1);
	btBoxShape box(btVector3(1, 1, 1));
	btCapsuleShape capsule(btScalar(0.5), 1);
	btCylinderShape cylinder(btVector3(1, 1, 1));
	btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
	btCompoundShape compound;
	compound.addChildShape(at(btVector3(0, 0, 0)), &sphere);
	btCollisionShape* shapes[] = {&sphere, &box, &capsule, &cylinder, &plane, &compound};
	btCollisionObject object0, object1;
	for (btCollisionShape* shape0 : shapes)
	{
		for (btCollisionShape* shape1 : shapes)
		{
			object0.setCollisionShape(shape0);
			object1.setCollisionShape(shape1);
			btCollisionObjectWrapper wrap0(0, shape0, &object0, object0.getWorldTransform(), -1, -1);
			btCollisionObjectWrapper wrap1(0, shape1, &object1, object1.getWorldTransform(), -1, -1);
			for (int query = 0; query < 2; ++query)
			{
				const ebtDispatcherQueryType type = query ? BT_CLOSEST_POINT_ALGORITHMS : BT_CONTACT_POINT_ALGORITHMS;
				config.m_lastUsed[0] = config.m_lastUsed[1] = config.m_lastUsed[2] = -1;
				btCollisionAlgorithm* algorithm = dispatcher.findAlgorithm(&wrap0, &wrap1, 0, type);
				EXPECT_TRUE(algorithm != 0) << shape0->getName() << " / " << shape1->getName();
				EXPECT_EQ(config.m_lastUsed[0], shape0->getShapeType()) << shape0->getName();
				EXPECT_EQ(config.m_lastUsed[1], shape1->getShapeType()) << shape1->getName();
				EXPECT_EQ(config.m_lastUsed[2], query) << "table of the query type";
				destroyAlgorithm(dispatcher, algorithm);
			}
		}
	}
	EXPECT_EQ(dispatcher.getNumManifolds(), 0) << "every algorithm released its manifold";
}

TEST(CollisionDispatcher, RegisteredCustomShapeAlgorithmProducesTheContacts)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	CustomAlgorithm::CreateFunc customFactory;
	dispatcher.registerCollisionCreateFunc(CUSTOM_CONVEX_SHAPE_TYPE, SPHERE_SHAPE_PROXYTYPE, &customFactory);

	CustomShape custom(1);
	btSphereShape sphere(1);
	// Far apart: a sphere-sphere algorithm would report nothing, the custom one always reports its point.
	ProxyObject a(&custom, btVector3(0, 0, 0), 1);
	ProxyObject b(&sphere, btVector3(0, 100, 0), 2);
	ArrayPairCache cache;
	cache.addOverlappingPair(&a.m_proxy, &b.m_proxy);
	btDispatcherInfo info;
	dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
	dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);

	EXPECT_EQ(customFactory.m_created, 1) << "the algorithm is made once per pair";
	ASSERT_EQ(dispatcher.getNumManifolds(), 1);
	const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(0);
	ASSERT_EQ(manifold->getNumContacts(), 1);
	EXPECT_EQ(manifold->getContactPoint(0).getDistance(), btScalar(-0.125));
	cache.clear(&dispatcher);
	EXPECT_EQ(dispatcher.getNumManifolds(), 0);
}

TEST(CollisionDispatcher, ManifoldsComeFromThePoolAndFallBackToTheHeap)
{
	btDefaultCollisionConstructionInfo ci;
	ci.m_defaultMaxPersistentManifoldPoolSize = 2;
	btDefaultCollisionConfiguration config(ci);
	btCollisionDispatcher dispatcher(&config);
	btPoolAllocator* pool = dispatcher.getInternalManifoldPool();
	ASSERT_EQ(pool, config.getPersistentManifoldPool());
	EXPECT_TRUE(dispatcher.getInternalManifoldPointer() == 0) << "no manifold yet";

	btSphereShape sphere(1);
	btCollisionObject a, b;
	a.setCollisionShape(&sphere);
	b.setCollisionShape(&sphere);
	btPersistentManifold* m0 = dispatcher.getNewManifold(&a, &b);
	btPersistentManifold* m1 = dispatcher.getNewManifold(&a, &b);
	btPersistentManifold* m2 = dispatcher.getNewManifold(&a, &b);
	EXPECT_TRUE(pool->validPtr(m0));
	EXPECT_TRUE(pool->validPtr(m1));
	EXPECT_FALSE(pool->validPtr(m2)) << "a full pool falls back to the heap";
	EXPECT_EQ(pool->getUsedCount(), 2);
	ASSERT_EQ(dispatcher.getNumManifolds(), 3);

	// Releasing the first swaps the last into its slot; every manifold's index stays its position.
	dispatcher.releaseManifold(m0);
	ASSERT_EQ(dispatcher.getNumManifolds(), 2);
	EXPECT_EQ(dispatcher.getManifoldByIndexInternal(0), m2);
	EXPECT_EQ(dispatcher.getManifoldByIndexInternal(1), m1);
	for (int i = 0; i < dispatcher.getNumManifolds(); ++i)
		EXPECT_EQ(dispatcher.getInternalManifoldPointer()[i]->m_index1a, i);
	EXPECT_EQ(pool->getUsedCount(), 1);

	btPersistentManifold* reused = dispatcher.getNewManifold(&a, &b);
	EXPECT_EQ(reused, m0) << "the freed pool element is reused";
	dispatcher.releaseManifold(m2);
	dispatcher.releaseManifold(reused);
	dispatcher.releaseManifold(m1);
	EXPECT_EQ(dispatcher.getNumManifolds(), 0);
	EXPECT_EQ(pool->getUsedCount(), 0);
}

TEST(CollisionDispatcher, DisabledDynamicAllocationGivesNoManifoldWhenThePoolIsFull)
{
	btDefaultCollisionConstructionInfo ci;
	ci.m_defaultMaxPersistentManifoldPoolSize = 1;
	btDefaultCollisionConfiguration config(ci);
	btCollisionDispatcher dispatcher(&config);
	dispatcher.setDispatcherFlags(dispatcher.getDispatcherFlags() |
	                              btCollisionDispatcher::CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION);
	btSphereShape sphere(1);
	btCollisionObject a, b;
	a.setCollisionShape(&sphere);
	b.setCollisionShape(&sphere);
	btPersistentManifold* first = dispatcher.getNewManifold(&a, &b);
	ASSERT_TRUE(first != 0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(dispatcher.getNewManifold(&a, &b), "assertion failed");
#else
	EXPECT_TRUE(dispatcher.getNewManifold(&a, &b) == 0) << "documented: null when the pool is exhausted";
	EXPECT_EQ(dispatcher.getNumManifolds(), 1);
#endif
	dispatcher.releaseManifold(first);
}

// Algorithms that make their own manifold must cope with the dispatcher giving none: the pair is
// skipped for the step and the pairs that did get a manifold keep their contacts.
TEST(CollisionDispatcher, PairsWithoutAManifoldFromAFullPoolAreSkippedSafely)
{
#if CALIBER_ASSERTS_ENABLED
	GTEST_SKIP() << "a full pool asserts in builds with btAssert; the release behaviour is checked without it";
#else
	btDefaultCollisionConstructionInfo ci;
	ci.m_defaultMaxPersistentManifoldPoolSize = 1;
	btDefaultCollisionConfiguration config(ci);
	btCollisionDispatcher dispatcher(&config);
	dispatcher.setDispatcherFlags(dispatcher.getDispatcherFlags() |
	                              btCollisionDispatcher::CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION);

	btSphereShape sphere(1);
	btCapsuleShape capsule(btScalar(0.5), 1);
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(-10, 0, -10), btVector3(10, 0, -10), btVector3(-10, 0, 10));
	mesh.addTriangle(btVector3(10, 0, -10), btVector3(10, 0, 10), btVector3(-10, 0, 10));
	btBvhTriangleMeshShape ground(&mesh, true);

	// Sphere pair first, so that it takes the pool's only manifold.
	ProxyObject s0(&sphere, btVector3(0, 20, 0), 1);
	ProxyObject s1(&sphere, btVector3(0, btScalar(21.5), 0), 2);
	ProxyObject c0(&capsule, btVector3(5, 1, 0), 3);
	ProxyObject c1(&capsule, btVector3(btScalar(5.5), 1, 0), 4);
	ProxyObject floor(&ground, btVector3(0, 0, 0), 5, btCollisionObject::CF_STATIC_OBJECT);
	ArrayPairCache cache;
	cache.addOverlappingPair(&s0.m_proxy, &s1.m_proxy);
	cache.addOverlappingPair(&c0.m_proxy, &c1.m_proxy);    // convex-convex
	cache.addOverlappingPair(&c0.m_proxy, &floor.m_proxy);  // convex-concave
	btDispatcherInfo info;
	for (int step = 0; step < 2; ++step) dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);

	ASSERT_EQ(dispatcher.getNumManifolds(), 1) << "no manifold beyond the pool";
	const btPersistentManifold* only = dispatcher.getManifoldByIndexInternal(0);
	EXPECT_EQ(only->getBody0(), &s0);
	ASSERT_EQ(only->getNumContacts(), 1);
	// Centres 1.5 apart, radii 1 and 1: 0.5 of overlap.
	EXPECT_NEAR(only->getContactPoint(0).getDistance(), btScalar(-0.5), btScalar(1e-5));
	cache.clear(&dispatcher);
	EXPECT_EQ(dispatcher.getNumManifolds(), 0);
#endif
}

TEST(CollisionDispatcher, ManifoldThresholdsAreTheSmallerOfThePair)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btSphereShape small(btScalar(0.1));
	btBoxShape large(btVector3(5, 5, 5));
	btCollisionObject a, b;
	a.setCollisionShape(&small);
	b.setCollisionShape(&large);
	a.setContactProcessingThreshold(btScalar(0.5));
	b.setContactProcessingThreshold(btScalar(0.25));

	const btScalar smallThreshold = small.getContactBreakingThreshold(gContactBreakingThreshold);
	const btScalar largeThreshold = large.getContactBreakingThreshold(gContactBreakingThreshold);
	ASSERT_LT(smallThreshold, largeThreshold) << "the shapes' relative thresholds must differ for this test";
	btPersistentManifold* relative = dispatcher.getNewManifold(&a, &b);
	EXPECT_EQ(relative->getContactBreakingThreshold(), smallThreshold);
	EXPECT_EQ(relative->getContactProcessingThreshold(), btScalar(0.25));

	dispatcher.setDispatcherFlags(0);
	btPersistentManifold* absolute = dispatcher.getNewManifold(&b, &a);
	EXPECT_EQ(absolute->getContactBreakingThreshold(), gContactBreakingThreshold)
	    << "without CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD the global threshold is used";
	dispatcher.releaseManifold(relative);
	dispatcher.releaseManifold(absolute);
}

TEST(CollisionDispatcher, NeedsCollisionSkipsSleepingPairsAndIgnoredObjects)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btCollisionObject a, b;
	EXPECT_TRUE(dispatcher.needsCollision(&a, &b)) << "two awake objects";

	// The dynamics world puts static objects to sleep, which is how static-static pairs are skipped.
	a.forceActivationState(ISLAND_SLEEPING);
	EXPECT_TRUE(dispatcher.needsCollision(&a, &b)) << "one awake object is enough";
	b.forceActivationState(ISLAND_SLEEPING);
	EXPECT_FALSE(dispatcher.needsCollision(&a, &b)) << "two sleeping objects";
	dispatcher.setDispatcherFlags(dispatcher.getDispatcherFlags() | btCollisionDispatcher::CD_STATIC_STATIC_REPORTED);
	EXPECT_TRUE(dispatcher.needsCollision(&a, &b)) << "CD_STATIC_STATIC_REPORTED keeps them";
	b.forceActivationState(DISABLE_SIMULATION);
	EXPECT_TRUE(dispatcher.needsCollision(&a, &b));
	dispatcher.setDispatcherFlags(0);
	EXPECT_FALSE(dispatcher.needsCollision(&a, &b)) << "DISABLE_SIMULATION is not active either";

	a.forceActivationState(ACTIVE_TAG);
	b.forceActivationState(ACTIVE_TAG);
	a.setIgnoreCollisionCheck(&b, true);
	EXPECT_FALSE(dispatcher.needsCollision(&a, &b));
	EXPECT_FALSE(dispatcher.needsCollision(&b, &a)) << "the ignore list is checked both ways";
	a.setIgnoreCollisionCheck(&b, false);
	EXPECT_TRUE(dispatcher.needsCollision(&b, &a));
}

TEST(CollisionDispatcher, NeedsResponseRequiresOneDynamicRespondingObject)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	const int kDynamic = btCollisionObject::CF_DYNAMIC_OBJECT;
	const int kStatic = btCollisionObject::CF_STATIC_OBJECT;
	const int kKinematic = btCollisionObject::CF_KINEMATIC_OBJECT;
	const int kTrigger = btCollisionObject::CF_NO_CONTACT_RESPONSE;
	struct Case
	{
		int flags0, flags1;
		bool expected;
	};
	const Case cases[] = {{kDynamic, kDynamic, true},
	                      {kDynamic, kStatic, true},
	                      {kKinematic, kDynamic, true},
	                      {kStatic, kStatic, false},
	                      {kStatic, kKinematic, false},
	                      {kKinematic, kKinematic, false},
	                      {kDynamic | kTrigger, kDynamic, false},
	                      {kDynamic, kStatic | kTrigger, false}};
	btCollisionObject a, b;
	for (const Case& c : cases)
	{
		a.setCollisionFlags(c.flags0);
		b.setCollisionFlags(c.flags1);
		EXPECT_EQ(dispatcher.needsResponse(&a, &b), c.expected) << "flags " << c.flags0 << " / " << c.flags1;
		EXPECT_EQ(dispatcher.needsResponse(&b, &a), c.expected) << "symmetric";
	}
}

TEST(CollisionDispatcher, DefaultNearCallbackFillsTheManifoldWithTheAnalyticDepth)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btSphereShape sphere0(1), sphere1(btScalar(0.5));
	ProxyObject a(&sphere0, btVector3(0, 0, 0), 1);
	ProxyObject b(&sphere1, btVector3(0, btScalar(1.25), 0), 2);
	ProxyObject far(&sphere1, btVector3(0, 10, 0), 3);
	ArrayPairCache cache;
	cache.addOverlappingPair(&a.m_proxy, &b.m_proxy);
	cache.addOverlappingPair(&a.m_proxy, &far.m_proxy);
	btDispatcherInfo info;
	dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);

	int touching = 0;
	for (int i = 0; i < dispatcher.getNumManifolds(); ++i)
	{
		const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(i);
		if (manifold->getNumContacts() == 0) continue;
		++touching;
		// Centres 1.25 apart, radii 1 and 0.5: 0.25 of overlap.
		EXPECT_NEAR(manifold->getContactPoint(0).getDistance(), btScalar(-0.25), btScalar(1e-5));
	}
	EXPECT_EQ(touching, 1) << "only the touching pair has a contact";
	btCollisionAlgorithm* first = cache.getOverlappingPairArray()[0].m_algorithm;
	dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
	EXPECT_EQ(cache.getOverlappingPairArray()[0].m_algorithm, first) << "the pair keeps its algorithm";
	cache.clear(&dispatcher);
	EXPECT_EQ(dispatcher.getNumManifolds(), 0);
}

TEST(CollisionDispatcher, ContinuousDispatchLowersTheTimeOfImpact)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btCylinderShape cylinder(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	ProxyObject mover(&cylinder, btVector3(-10, 0, 0), 1);
	ProxyObject target(&box, btVector3(0, 0, 0), 2);
	mover.setInterpolationWorldTransform(at(btVector3(10, 0, 0)));
	mover.setCcdMotionThreshold(btScalar(0.1));
	mover.setCcdSweptSphereRadius(btScalar(0.25));
	target.setCcdSweptSphereRadius(btScalar(0.25));
	ArrayPairCache cache;
	cache.addOverlappingPair(&mover.m_proxy, &target.m_proxy);

	btDispatcherInfo info;
	info.m_dispatchFunc = btDispatcherInfo::DISPATCH_CONTINUOUS;
	dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
	// Each shape meets the other's swept sphere (radius 0.25) when the centres are 0.5 + 0.25 apart:
	// at x = -0.75 of a sweep from -10 to 10, i.e. fraction 9.25 / 20. GJK's cast stops within its
	// tolerance of the surface (millimetres over 20 m).
	EXPECT_NEAR(info.m_timeOfImpact, btScalar(9.25 / 20.0), btScalar(2e-3));

	info.m_timeOfImpact = btScalar(0.1);
	dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
	EXPECT_EQ(info.m_timeOfImpact, btScalar(0.1)) << "a later impact never raises the minimum";
	cache.clear(&dispatcher);
}

TEST(CollisionDispatcher, NearCallbackCanBeReplacedAndRestored)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	EXPECT_EQ(dispatcher.getNearCallback(), &btCollisionDispatcher::defaultNearCallback);
	static int calls = 0;
	calls = 0;
	dispatcher.setNearCallback([](btBroadphasePair&, btCollisionDispatcher&, const btDispatcherInfo&) { ++calls; });
	btSphereShape sphere(1);
	ProxyObject a(&sphere, btVector3(0, 0, 0), 1);
	ProxyObject b(&sphere, btVector3(0, 1, 0), 2);
	ArrayPairCache cache;
	cache.addOverlappingPair(&a.m_proxy, &b.m_proxy);
	btDispatcherInfo info;
	dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
	EXPECT_EQ(calls, 1);
	EXPECT_EQ(dispatcher.getNumManifolds(), 0) << "the replacement made no algorithm";
	dispatcher.setNearCallback(0);
	EXPECT_EQ(dispatcher.getNearCallback(), &btCollisionDispatcher::defaultNearCallback) << "null restores the default";
	cache.clear(&dispatcher);
}

TEST(CollisionDispatcher, AlgorithmMemoryComesFromThePoolUntilItIsFull)
{
	btDefaultCollisionConstructionInfo ci;
	ci.m_defaultMaxCollisionAlgorithmPoolSize = 1;
	btDefaultCollisionConfiguration config(ci);
	btCollisionDispatcher dispatcher(&config);
	btPoolAllocator* pool = config.getCollisionAlgorithmPool();
	void* first = dispatcher.allocateCollisionAlgorithm(16);
	void* second = dispatcher.allocateCollisionAlgorithm(16);
	void* huge = dispatcher.allocateCollisionAlgorithm(pool->getElementSize() + 64);
	EXPECT_TRUE(pool->validPtr(first));
	EXPECT_FALSE(pool->validPtr(second)) << "full pool: heap";
	EXPECT_FALSE(pool->validPtr(huge)) << "larger than an element: heap";
	dispatcher.freeCollisionAlgorithm(first);
	dispatcher.freeCollisionAlgorithm(second);
	dispatcher.freeCollisionAlgorithm(huge);
	dispatcher.freeCollisionAlgorithm(0);
	EXPECT_EQ(pool->getUsedCount(), 0);
}

TEST(CollisionDispatcher, BadInputIsRejected)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btCollisionObject object;
	btCollisionObjectWrapper noShape(0, 0, &object, object.getWorldTransform(), -1, -1);
	CustomAlgorithm::CreateFunc factory;
	dispatcher.releaseManifold(0);  // documented no-op
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(dispatcher.getManifoldByIndexInternal(0), "assertion failed");
	EXPECT_DEATH(dispatcher.findAlgorithm(&noShape, &noShape, 0, BT_CONTACT_POINT_ALGORITHMS), "assertion failed");
	EXPECT_DEATH(dispatcher.registerCollisionCreateFunc(-1, 0, &factory), "assertion failed");
	EXPECT_DEATH(dispatcher.needsCollision(0, &object), "assertion failed");
#else
	EXPECT_TRUE(dispatcher.getManifoldByIndexInternal(0) == 0) << "documented: null out of range";
	EXPECT_TRUE(static_cast<const btCollisionDispatcher&>(dispatcher).getManifoldByIndexInternal(-1) == 0);
	EXPECT_TRUE(dispatcher.findAlgorithm(&noShape, &noShape, 0, BT_CONTACT_POINT_ALGORITHMS) == 0);
	dispatcher.registerCollisionCreateFunc(-1, 0, &factory);
	dispatcher.registerCollisionCreateFunc(0, MAX_BROADPHASE_COLLISION_TYPES, &factory);
	EXPECT_FALSE(dispatcher.needsCollision(0, &object));
	EXPECT_FALSE(dispatcher.needsResponse(&object, 0));
#endif
	// A manifold of another dispatcher is not released by this one.
	btCollisionDispatcher other(&config);
	btSphereShape sphere(1);
	object.setCollisionShape(&sphere);
	btPersistentManifold* foreign = other.getNewManifold(&object, &object);
	btPersistentManifold* own = dispatcher.getNewManifold(&object, &object);
	(void)own;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(dispatcher.releaseManifold(foreign), "assertion failed");
#else
	dispatcher.releaseManifold(foreign);
	EXPECT_EQ(dispatcher.getNumManifolds(), 1) << "a foreign manifold leaves the array alone";
	EXPECT_EQ(other.getNumManifolds(), 1);
#endif
	other.releaseManifold(foreign);
	// The dispatcher's destructor releases `own`.
}

// A fast body dropping through a thin triangle mesh: its swept sphere meets the mesh plane first
// when the centre is one sphere radius above it. Both pair orders (convex first, mesh first) work.
TEST(CollisionDispatcher, ContinuousDispatchFindsTheImpactOfAFastBodyOnAMesh)
{
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(-10, 0, -10), btVector3(10, 0, -10), btVector3(-10, 0, 10));
	mesh.addTriangle(btVector3(10, 0, -10), btVector3(10, 0, 10), btVector3(-10, 0, 10));
	btBvhTriangleMeshShape ground(&mesh, true);
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));

	for (int order = 0; order < 2; ++order)
	{
		btDefaultCollisionConfiguration config;
		btCollisionDispatcher dispatcher(&config);
		ProxyObject mover(&box, btVector3(1, 5, 2), 1);
		ProxyObject floor(&ground, btVector3(0, 0, 0), 2, btCollisionObject::CF_STATIC_OBJECT);
		mover.setInterpolationWorldTransform(at(btVector3(1, -5, 2)));
		mover.setCcdMotionThreshold(btScalar(0.1));
		mover.setCcdSweptSphereRadius(btScalar(0.2));
		ArrayPairCache cache;
		if (order == 0)
			cache.addOverlappingPair(&mover.m_proxy, &floor.m_proxy);
		else
			cache.addOverlappingPair(&floor.m_proxy, &mover.m_proxy);

		btDispatcherInfo info;
		info.m_dispatchFunc = btDispatcherInfo::DISPATCH_CONTINUOUS;
		dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
		// Centre from y = 5 to y = -5; the sphere of radius 0.2 touches y = 0 at y = 0.2: fraction
		// 4.8 / 10. GJK's cast stops within its tolerance of the surface (millimetres over 10 m).
		EXPECT_NEAR(info.m_timeOfImpact, btScalar(0.48), btScalar(2e-3)) << "order " << order;
		EXPECT_NEAR(mover.getHitFraction(), btScalar(0.48), btScalar(2e-3)) << "the convex body keeps it";

		// The same motion beside the mesh (x = 15) never reaches a triangle.
		mover.setHitFraction(1);
		mover.setWorldTransform(at(btVector3(15, 5, 2)));
		mover.setInterpolationWorldTransform(at(btVector3(15, -5, 2)));
		info.m_timeOfImpact = 1;
		dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
		EXPECT_EQ(info.m_timeOfImpact, btScalar(1)) << "order " << order;

		// A slow body (motion below its threshold) is left to the discrete step.
		mover.setWorldTransform(at(btVector3(1, btScalar(0.3), 2)));
		mover.setInterpolationWorldTransform(at(btVector3(1, btScalar(0.25), 2)));
		dispatcher.dispatchAllCollisionPairs(&cache, info, &dispatcher);
		EXPECT_EQ(info.m_timeOfImpact, btScalar(1)) << "order " << order;
		cache.clear(&dispatcher);
	}
}
