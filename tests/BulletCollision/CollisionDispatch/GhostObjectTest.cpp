// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <set>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "LinearMath/btAabbUtil2.h"

namespace
{
btTransform at(const btVector3& origin)
{
	btTransform t;
	t.setIdentity();
	t.setOrigin(origin);
	return t;
}

// A ghost box (2 x 2 x 2) and a row of unit spheres along x at 0, 3, 6, ..., 27, in a world whose pair
// cache reports to a btGhostPairCallback. btSimpleBroadphase pairs exactly the overlapping proxy boxes;
// btDbvtBroadphase may pair slightly earlier (its tree boxes are enlarged).
template <class Broadphase = btSimpleBroadphase, class Ghost = btGhostObject>
class GhostScene
{
public:
	static const int kSpheres = 10;

	GhostScene() : m_dispatcher(&m_config), m_ghostShape(btVector3(1, 1, 1)), m_sphere(btScalar(0.5))
	{
		m_world.reset(new btCollisionWorld(&m_dispatcher, &m_broadphase, &m_config));
		m_world->getPairCache()->setInternalGhostPairCallback(&m_ghostCallback);
		for (int i = 0; i < kSpheres; ++i)
		{
			m_spheres[i].setCollisionShape(&m_sphere);
			m_spheres[i].setWorldTransform(at(btVector3(btScalar(3 * i), 0, 0)));
			m_world->addCollisionObject(&m_spheres[i]);
		}
		m_ghost.setCollisionShape(&m_ghostShape);
		m_ghost.setCollisionFlags(btCollisionObject::CF_NO_CONTACT_RESPONSE);
		m_world->addCollisionObject(&m_ghost, btBroadphaseProxy::SensorTrigger, btBroadphaseProxy::AllFilter);
	}
	~GhostScene()
	{
		if (m_ghost.getBroadphaseHandle()) m_world->removeCollisionObject(&m_ghost);
		m_world.reset();
	}

	void moveGhost(const btVector3& origin)
	{
		m_ghost.setWorldTransform(at(origin));
		m_world->performDiscreteCollisionDetection();
	}

	// Reference: the objects whose broadphase boxes overlap the ghost's, found by testing every box.
	std::set<const btCollisionObject*> expectedOverlaps() const
	{
		std::set<const btCollisionObject*> result;
		const btBroadphaseProxy* ghostProxy = m_ghost.getBroadphaseHandle();
		for (const btCollisionObject& sphere : m_spheres)
		{
			const btBroadphaseProxy* proxy = sphere.getBroadphaseHandle();
			if (proxy &&
			    TestAabbAgainstAabb2(ghostProxy->m_aabbMin, ghostProxy->m_aabbMax, proxy->m_aabbMin, proxy->m_aabbMax))
				result.insert(&sphere);
		}
		return result;
	}

	// The objects the world's pair cache pairs with the ghost.
	std::set<const btCollisionObject*> pairedWithGhost()
	{
		std::set<const btCollisionObject*> result;
		btOverlappingPairCache* cache = m_world->getPairCache();
		const btBroadphaseProxy* ghostProxy = m_ghost.getBroadphaseHandle();
		for (int i = 0; i < cache->getNumOverlappingPairs(); ++i)
		{
			const btBroadphasePair& pair = cache->getOverlappingPairArray()[i];
			if (pair.m_pProxy0 == ghostProxy)
				result.insert(static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject));
			else if (pair.m_pProxy1 == ghostProxy)
				result.insert(static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject));
		}
		return result;
	}

	std::set<const btCollisionObject*> ghostOverlaps() const
	{
		std::set<const btCollisionObject*> result;
		for (int i = 0; i < m_ghost.getNumOverlappingObjects(); ++i) result.insert(m_ghost.getOverlappingObject(i));
		EXPECT_EQ(int(result.size()), m_ghost.getNumOverlappingObjects()) << "no duplicates";
		return result;
	}

	btDefaultCollisionConfiguration m_config;
	btCollisionDispatcher m_dispatcher;
	Broadphase m_broadphase;
	btGhostPairCallback m_ghostCallback;
	btBoxShape m_ghostShape;
	btSphereShape m_sphere;
	btCollisionObject m_spheres[kSpheres];
	Ghost m_ghost;
	std::unique_ptr<btCollisionWorld> m_world;
};
}  // namespace

TEST(GhostObject, UpcastRecognisesGhostsOnly)
{
	btGhostObject ghost;
	btCollisionObject plain;
	EXPECT_EQ(ghost.getInternalType(), int(btCollisionObject::CO_GHOST_OBJECT));
	EXPECT_EQ(btGhostObject::upcast(static_cast<btCollisionObject*>(&ghost)), &ghost);
	EXPECT_EQ(btGhostObject::upcast(static_cast<const btCollisionObject*>(&ghost)), &ghost);
	EXPECT_TRUE(btGhostObject::upcast(&plain) == 0);
	EXPECT_TRUE(btGhostObject::upcast(static_cast<btCollisionObject*>(0)) == 0);
	EXPECT_EQ(ghost.getNumOverlappingObjects(), 0);
}

TEST(GhostObject, OverlappingObjectsFollowTheGhostAsItMoves)
{
	GhostScene<> scene;
	std::mt19937 rng(4242u);
	std::uniform_real_distribution<float> along(-3.0f, 30.0f);
	std::uniform_real_distribution<float> across(-1.5f, 1.5f);
	int nonEmpty = 0;
	int changes = 0;
	std::set<const btCollisionObject*> previous;
	for (int step = 0; step < 60; ++step)
	{
		scene.moveGhost(btVector3(btScalar(along(rng)), btScalar(across(rng)), btScalar(across(rng))));
		const std::set<const btCollisionObject*> expected = scene.expectedOverlaps();
		ASSERT_EQ(scene.ghostOverlaps(), expected) << "step " << step;
		if (!expected.empty()) ++nonEmpty;
		if (expected != previous) ++changes;
		previous = expected;
	}
	// The walk must actually exercise both additions and removals.
	EXPECT_GT(nonEmpty, 10);
	EXPECT_GT(changes, 20);
}

TEST(GhostObject, RemovingObjectsUpdatesTheOverlapList)
{
	GhostScene<> scene;
	scene.moveGhost(btVector3(btScalar(1.5), 0, 0));  // between spheres 0 and 1
	ASSERT_EQ(scene.m_ghost.getNumOverlappingObjects(), 2);
	scene.m_world->removeCollisionObject(&scene.m_spheres[1]);
	ASSERT_EQ(scene.m_ghost.getNumOverlappingObjects(), 1);
	EXPECT_EQ(scene.m_ghost.getOverlappingObject(0), &scene.m_spheres[0]);
	scene.m_world->removeCollisionObject(&scene.m_ghost);
	EXPECT_EQ(scene.m_ghost.getNumOverlappingObjects(), 0) << "a ghost leaving the world overlaps nothing";
	scene.m_world->addCollisionObject(&scene.m_spheres[1]);
}

TEST(GhostObject, OverlapListMirrorsTheDbvtBroadphasePairs)
{
	GhostScene<btDbvtBroadphase> scene;
	std::mt19937 rng(99u);
	std::uniform_real_distribution<float> along(-3.0f, 30.0f);
	int nonEmpty = 0;
	for (int step = 0; step < 40; ++step)
	{
		scene.moveGhost(btVector3(btScalar(along(rng)), 0, 0));
		const std::set<const btCollisionObject*> paired = scene.pairedWithGhost();
		ASSERT_EQ(scene.ghostOverlaps(), paired) << "step " << step;
		// Every exact overlap is paired (the tree's boxes only ever add pairs).
		for (const btCollisionObject* object : scene.expectedOverlaps()) EXPECT_EQ(paired.count(object), 1u);
		if (!paired.empty()) ++nonEmpty;
	}
	EXPECT_GT(nonEmpty, 10);
}

TEST(GhostObject, PairCachingGhostKeepsItsOwnPairs)
{
	GhostScene<btDbvtBroadphase, btPairCachingGhostObject> scene;
	for (int step = 0; step < 12; ++step)
	{
		scene.moveGhost(btVector3(btScalar(2.5 * step), 0, 0));
		btHashedOverlappingPairCache* own = scene.m_ghost.getOverlappingPairCache();
		ASSERT_EQ(own->getNumOverlappingPairs(), scene.m_ghost.getNumOverlappingObjects()) << "step " << step;
		std::set<const btCollisionObject*> inOwnCache;
		for (int i = 0; i < own->getNumOverlappingPairs(); ++i)
		{
			const btBroadphasePair& pair = own->getOverlappingPairArray()[i];
			const bool ghostIn0 = pair.m_pProxy0 == scene.m_ghost.getBroadphaseHandle();
			const bool ghostIn1 = pair.m_pProxy1 == scene.m_ghost.getBroadphaseHandle();
			ASSERT_TRUE(ghostIn0 != ghostIn1) << "every pair joins the ghost and one other object";
			inOwnCache.insert(
			    static_cast<const btCollisionObject*>((ghostIn0 ? pair.m_pProxy1 : pair.m_pProxy0)->m_clientObject));
		}
		EXPECT_EQ(inOwnCache, scene.ghostOverlaps()) << "step " << step;
	}
	scene.m_world->removeCollisionObject(&scene.m_ghost);
	EXPECT_EQ(scene.m_ghost.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
}

TEST(GhostObject, RayTestSeesOnlyOverlappingObjects)
{
	GhostScene<> scene;
	scene.moveGhost(btVector3(btScalar(4.5), 0, 0));  // overlaps spheres 1 (x = 3) and 2 (x = 6)
	ASSERT_EQ(scene.m_ghost.getNumOverlappingObjects(), 2);

	// A ray along x from x = -10 would hit sphere 0 first in the world; the ghost only knows 1 and 2.
	btCollisionWorld::ClosestRayResultCallback closest(btVector3(-10, 0, 0), btVector3(10, 0, 0));
	scene.m_ghost.rayTest(closest.m_rayFromWorld, closest.m_rayToWorld, closest);
	ASSERT_TRUE(closest.hasHit());
	EXPECT_EQ(closest.m_collisionObject, &scene.m_spheres[1]);
	// Sphere 1's surface at x = 2.5: fraction 12.5 / 20.
	EXPECT_NEAR(closest.m_closestHitFraction, btScalar(12.5 / 20.0), btScalar(1e-4));

	btCollisionWorld::ClosestRayResultCallback world(btVector3(-10, 0, 0), btVector3(10, 0, 0));
	scene.m_world->rayTest(world.m_rayFromWorld, world.m_rayToWorld, world);
	EXPECT_EQ(world.m_collisionObject, &scene.m_spheres[0]) << "the control: the world sees sphere 0";

	// The callback's group/mask is honoured.
	btCollisionWorld::ClosestRayResultCallback masked(btVector3(-10, 0, 0), btVector3(10, 0, 0));
	masked.m_collisionFilterMask = btBroadphaseProxy::StaticFilter;
	scene.m_ghost.rayTest(masked.m_rayFromWorld, masked.m_rayToWorld, masked);
	EXPECT_FALSE(masked.hasHit()) << "the spheres are in the default group only";
}

TEST(GhostObject, ConvexSweepTestSeesOnlyOverlappingObjects)
{
	GhostScene<> scene;
	scene.moveGhost(btVector3(btScalar(4.5), 0, 0));
	btSphereShape probe(btScalar(0.25));
	btCollisionWorld::ClosestConvexResultCallback closest(btVector3(-10, 0, 0), btVector3(10, 0, 0));
	scene.m_ghost.convexSweepTest(&probe, at(closest.m_convexFromWorld), at(closest.m_convexToWorld), closest);
	ASSERT_TRUE(closest.hasHit());
	EXPECT_EQ(closest.m_hitCollisionObject, &scene.m_spheres[1]);
	// The probe's centre touches sphere 1 at x = 3 - 0.5 - 0.25 = 2.25: fraction 12.25 / 20. The GJK cast
	// stops within its tolerance of the surface.
	EXPECT_NEAR(closest.m_closestHitFraction, btScalar(12.25 / 20.0), btScalar(1e-3));

	// A sweep that passes beside every overlapping object finds nothing.
	btCollisionWorld::ClosestConvexResultCallback beside(btVector3(-10, 5, 0), btVector3(10, 5, 0));
	scene.m_ghost.convexSweepTest(&probe, at(beside.m_convexFromWorld), at(beside.m_convexToWorld), beside);
	EXPECT_FALSE(beside.hasHit());
}

TEST(GhostObject, InternalAddAndRemoveKeepTheListUnique)
{
	btGhostObject ghost;
	btCollisionObject other;
	btBroadphaseProxy proxy;
	proxy.m_clientObject = &other;
	ghost.addOverlappingObjectInternal(&proxy);
	ghost.addOverlappingObjectInternal(&proxy);
	EXPECT_EQ(ghost.getNumOverlappingObjects(), 1) << "added once";
	EXPECT_EQ(ghost.getOverlappingPairs().size(), 1);
	ghost.removeOverlappingObjectInternal(&proxy, 0);
	ghost.removeOverlappingObjectInternal(&proxy, 0);
	EXPECT_EQ(ghost.getNumOverlappingObjects(), 0);

	btBroadphaseProxy empty;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(ghost.addOverlappingObjectInternal(&empty), "assertion failed");
	EXPECT_DEATH(ghost.addOverlappingObjectInternal(0), "assertion failed");
#else
	ghost.addOverlappingObjectInternal(&empty);
	ghost.addOverlappingObjectInternal(0);
	ghost.removeOverlappingObjectInternal(0, 0);
	EXPECT_EQ(ghost.getNumOverlappingObjects(), 0) << "documented: a proxy without an object is ignored";
#endif
}

TEST(GhostObject, GhostPairCallbackUpdatesBothGhostsOfAPair)
{
	btGhostObject ghost0, ghost1;
	btBroadphaseProxy proxy0, proxy1;
	proxy0.m_clientObject = &ghost0;
	proxy1.m_clientObject = &ghost1;
	btGhostPairCallback callback;
	EXPECT_TRUE(callback.addOverlappingPair(&proxy0, &proxy1) == 0) << "the callback stores no pair";
	ASSERT_EQ(ghost0.getNumOverlappingObjects(), 1);
	ASSERT_EQ(ghost1.getNumOverlappingObjects(), 1);
	EXPECT_EQ(ghost0.getOverlappingObject(0), &ghost1);
	EXPECT_EQ(ghost1.getOverlappingObject(0), &ghost0);
	callback.removeOverlappingPair(&proxy1, &proxy0, 0);
	EXPECT_EQ(ghost0.getNumOverlappingObjects(), 0);
	EXPECT_EQ(ghost1.getNumOverlappingObjects(), 0);
}
