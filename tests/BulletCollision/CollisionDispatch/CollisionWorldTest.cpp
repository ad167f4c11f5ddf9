// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCollisionWorld bookkeeping: objects and proxies, AABB updates (and overflow), the discrete step and
// debug drawing.

#include <gtest/gtest.h>

#include <limits>
#include <set>
#include <string>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "CollisionWorldTestUtil.h"
#include "LinearMath/btIDebugDraw.h"

using namespace caliber_world_test;

namespace
{
// Counts what the world draws.
class CountingDrawer : public btIDebugDraw
{
public:
	void drawLine(const btVector3&, const btVector3&, const btVector3&) override { m_lines++; }
	void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override
	{
		m_contacts++;
	}
	void reportErrorWarning(const char* warning) override { m_warnings.push_back(warning); }
	void draw3dText(const btVector3&, const char*) override {}
	void setDebugMode(int mode) override { m_mode = mode; }
	int getDebugMode() const override { return m_mode; }
	void drawAabb(const btVector3& from, const btVector3& to, const btVector3&) override
	{
		m_aabbs++;
		m_lastAabbMin = from;
		m_lastAabbMax = to;
	}

	int m_mode = 0;
	int m_lines = 0;
	int m_contacts = 0;
	int m_aabbs = 0;
	btVector3 m_lastAabbMin, m_lastAabbMax;
	std::vector<std::string> m_warnings;
};

void expectProxyBox(const btCollisionObject* object, const btVector3& expectedMin, const btVector3& expectedMax)
{
	// The shape's AABB grown by the contact breaking threshold; a few ulps of rounding.
	const btScalar tolerance = btScalar(1e-5);
	const btVector3 threshold(gContactBreakingThreshold, gContactBreakingThreshold, gContactBreakingThreshold);
	const btBroadphaseProxy* proxy = object->getBroadphaseHandle();
	ASSERT_NE(proxy, nullptr);
	EXPECT_LE((proxy->m_aabbMin - (expectedMin - threshold)).length(), tolerance);
	EXPECT_LE((proxy->m_aabbMax - (expectedMax + threshold)).length(), tolerance);
}
}  // namespace

TEST(CollisionWorld, AddedObjectGetsProxyWithFilterAndArrayIndex)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* a = f.add(sphere, at(btVector3(1, 2, 3)), 2, 5);
	btCollisionObject* b = f.add(sphere, at(btVector3(-4, 0, 0)));
	EXPECT_EQ(f.m_world.getNumCollisionObjects(), 2);
	EXPECT_EQ(a->getWorldArrayIndex(), 0);
	EXPECT_EQ(b->getWorldArrayIndex(), 1);
	EXPECT_EQ(f.m_broadphase.numProxies(), 2);
	ASSERT_NE(a->getBroadphaseHandle(), nullptr);
	EXPECT_EQ(a->getBroadphaseHandle()->m_collisionFilterGroup, 2);
	EXPECT_EQ(a->getBroadphaseHandle()->m_collisionFilterMask, 5);
	EXPECT_EQ(a->getBroadphaseHandle()->m_clientObject, a);
	EXPECT_EQ(b->getBroadphaseHandle()->m_collisionFilterGroup, int(btBroadphaseProxy::DefaultFilter));
	EXPECT_EQ(b->getBroadphaseHandle()->m_collisionFilterMask, int(btBroadphaseProxy::AllFilter));
	expectProxyBox(a, btVector3(0, 1, 2), btVector3(2, 3, 4));
}

TEST(CollisionWorld, AddingAnObjectTwiceAssertsAndIsIgnored)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* a = f.add(sphere, at(btVector3(0, 0, 0)));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.addCollisionObject(a), "assertion failed");
#else
	f.m_world.addCollisionObject(a, 4, 4);
	EXPECT_EQ(f.m_world.getNumCollisionObjects(), 1);
	EXPECT_EQ(a->getWorldArrayIndex(), 0);
	EXPECT_EQ(f.m_broadphase.numProxies(), 1);
	EXPECT_EQ(a->getBroadphaseHandle()->m_collisionFilterGroup, int(btBroadphaseProxy::DefaultFilter));
#endif
}

TEST(CollisionWorld, RemovingAnObjectNotInTheWorldAssertsAndIsIgnored)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	f.add(sphere, at(btVector3(0, 0, 0)));
	btCollisionObject stranger;
	stranger.setCollisionShape(sphere);
	stranger.setWorldArrayIndex(0);  // an index that names another object must not fool the world
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.removeCollisionObject(&stranger), "assertion failed");
#else
	f.m_world.removeCollisionObject(&stranger);
	EXPECT_EQ(f.m_world.getNumCollisionObjects(), 1);
	EXPECT_EQ(f.m_broadphase.numProxies(), 1);
#endif
}

TEST(CollisionWorld, RemoveMovesLastObjectIntoTheGapAndDestroysTheProxy)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* a = f.add(sphere, at(btVector3(0, 0, 0)));
	btCollisionObject* b = f.add(sphere, at(btVector3(5, 0, 0)));
	btCollisionObject* c = f.add(sphere, at(btVector3(10, 0, 0)));
	f.m_world.removeCollisionObject(a);
	EXPECT_EQ(a->getBroadphaseHandle(), nullptr);
	EXPECT_EQ(a->getWorldArrayIndex(), -1);
	EXPECT_EQ(f.m_world.getNumCollisionObjects(), 2);
	EXPECT_EQ(f.m_broadphase.numProxies(), 2);
	EXPECT_EQ(f.m_world.getCollisionObjectArray()[0], c);
	EXPECT_EQ(c->getWorldArrayIndex(), 0);
	EXPECT_EQ(b->getWorldArrayIndex(), 1);
	// Re-adding after removal is allowed.
	f.m_world.addCollisionObject(a);
	EXPECT_EQ(a->getWorldArrayIndex(), 2);
	EXPECT_EQ(f.m_broadphase.numProxies(), 3);
}

TEST(CollisionWorld, DestructorRemovesProxiesAndKeepsObjects)
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	BruteForceBroadphase broadphase;
	btSphereShape sphere(1);
	btCollisionObject a, b;
	a.setCollisionShape(&sphere);
	b.setCollisionShape(&sphere);
	{
		btCollisionWorld world(&dispatcher, &broadphase, &config);
		world.addCollisionObject(&a);
		world.addCollisionObject(&b);
		world.performDiscreteCollisionDetection();  // overlapping: a pair with an algorithm
		EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 1);
	}
	EXPECT_EQ(broadphase.numProxies(), 0);
	EXPECT_EQ(broadphase.getOverlappingPairCache()->getNumOverlappingPairs(), 0);
	EXPECT_EQ(a.getBroadphaseHandle(), nullptr);
	EXPECT_EQ(b.getBroadphaseHandle(), nullptr);
}

TEST(CollisionWorld, UpdateAabbsFollowsActiveObjectsAndStaticOnlyWhenForced)
{
	WorldFixture f;
	btBoxShape* box = f.own(new btBoxShape(btVector3(1, 2, 3)));
	btCollisionObject* moving = f.add(box, at(btVector3(0, 0, 0)));
	moving->setCollisionFlags(0);
	btCollisionObject* fixed = f.add(box, at(btVector3(10, 0, 0)));
	fixed->setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT);
	btCollisionObject* sleeping = f.add(box, at(btVector3(20, 0, 0)));
	sleeping->setCollisionFlags(0);
	sleeping->forceActivationState(ISLAND_SLEEPING);

	f.m_world.setForceUpdateAllAabbs(false);
	moving->setWorldTransform(at(btVector3(0, 5, 0)));
	fixed->setWorldTransform(at(btVector3(10, 5, 0)));
	sleeping->setWorldTransform(at(btVector3(20, 5, 0)));
	f.m_world.updateAabbs();
	const btVector3 he = box->getHalfExtentsWithMargin();
	expectProxyBox(moving, btVector3(0, 5, 0) - he, btVector3(0, 5, 0) + he);
	expectProxyBox(fixed, btVector3(10, 0, 0) - he, btVector3(10, 0, 0) + he);
	expectProxyBox(sleeping, btVector3(20, 0, 0) - he, btVector3(20, 0, 0) + he);

	EXPECT_TRUE(f.m_world.getForceUpdateAllAabbs() == false);
	f.m_world.setForceUpdateAllAabbs(true);
	f.m_world.updateAabbs();
	expectProxyBox(fixed, btVector3(10, 5, 0) - he, btVector3(10, 5, 0) + he);
	expectProxyBox(sleeping, btVector3(20, 5, 0) - he, btVector3(20, 5, 0) + he);
}

TEST(CollisionWorld, HugeAabbTakesMovingObjectOutOfSimulationWithOneWarning)
{
	WorldFixture f;
	CountingDrawer drawer;
	f.m_world.setDebugDrawer(&drawer);
	btSphereShape* small = f.own(new btSphereShape(1));
	// Diagonal 2e6 * sqrt(3): above the 1e6 limit on the AABB's diagonal.
	btSphereShape* huge = f.own(new btSphereShape(btScalar(1e6)));
	btCollisionObject* runaway1 = f.add(huge, at(btVector3(0, 0, 0)));
	btCollisionObject* runaway2 = f.add(huge, at(btVector3(0, 0, 0)));
	btCollisionObject* terrain = f.add(huge, at(btVector3(0, 0, 0)));
	btCollisionObject* ok = f.add(small, at(btVector3(3, 0, 0)));
	runaway1->setCollisionFlags(0);
	runaway2->setCollisionFlags(0);
	terrain->setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT);
	ok->setCollisionFlags(0);

	ok->setWorldTransform(at(btVector3(7, 0, 0)));
	f.m_world.updateAabbs();
	EXPECT_EQ(runaway1->getActivationState(), DISABLE_SIMULATION);
	EXPECT_EQ(runaway2->getActivationState(), DISABLE_SIMULATION);
	EXPECT_EQ(terrain->getActivationState(), ACTIVE_TAG);  // static objects may be as large as they like
	EXPECT_EQ(ok->getActivationState(), ACTIVE_TAG);
	expectProxyBox(ok, btVector3(6, -1, -1), btVector3(8, 1, 1));
	f.m_world.updateAabbs();
	EXPECT_EQ(drawer.m_warnings.size(), 1u);
}

TEST(CollisionWorld, NonFiniteTransformAssertsOrDisablesTheObject)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* bad = f.add(sphere, at(btVector3(0, 0, 0)));
	btCollisionObject* good = f.add(sphere, at(btVector3(5, 0, 0)));
	bad->setCollisionFlags(0);
	good->setCollisionFlags(0);
	// Written through the reference, bypassing setWorldTransform's check.
	bad->getWorldTransform().setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.updateAabbs(), "assertion failed");
	bad->getWorldTransform().setOrigin(btVector3(0, 0, 0));
#else
	CountingDrawer drawer;
	f.m_world.setDebugDrawer(&drawer);
	good->setWorldTransform(at(btVector3(6, 0, 0)));
	f.m_world.performDiscreteCollisionDetection();
	EXPECT_EQ(bad->getActivationState(), DISABLE_SIMULATION);
	expectProxyBox(bad, btVector3(-1, -1, -1), btVector3(1, 1, 1));  // the last finite box is kept
	expectProxyBox(good, btVector3(5, -1, -1), btVector3(7, 1, 1));
	EXPECT_EQ(drawer.m_warnings.size(), 1u);
	// Queries skip it rather than produce NaN.
	btCollisionWorld::ClosestRayResultCallback ray(btVector3(0, 10, 0), btVector3(0, -10, 0));
	f.m_world.rayTest(ray.m_rayFromWorld, ray.m_rayToWorld, ray);
	EXPECT_FALSE(ray.hasHit());
	bad->getWorldTransform().setOrigin(btVector3(0, 0, 0));
#endif
}

TEST(CollisionWorld, DiscreteCollisionDetectionFindsExactlyTheTouchingPairs)
{
	WorldFixture f;
	Random rng(7);
	std::vector<btCollisionObject*> objects;
	std::vector<btScalar> radii;
	for (int i = 0; i < 40; i++)
	{
		const btScalar r = rng.uniform(0.3, 1.0);
		btSphereShape* sphere = f.own(new btSphereShape(r));
		objects.push_back(f.add(sphere, at(rng.vector(4))));
		objects.back()->setCollisionFlags(0);
		radii.push_back(r);
	}
	f.m_world.performDiscreteCollisionDetection();

	std::set<std::pair<const void*, const void*>> expected, found;
	for (size_t i = 0; i < objects.size(); i++)
		for (size_t j = i + 1; j < objects.size(); j++)
		{
			const btScalar gap =
			    objects[i]->getWorldTransform().getOrigin().distance(objects[j]->getWorldTransform().getOrigin()) -
			    radii[i] - radii[j];
			// Pairs within 1e-3 of touching are ambiguous in float; keep them out of the comparison.
			if (btFabs(gap) < btScalar(1e-3)) continue;
			if (gap < 0)
				expected.insert(std::make_pair(std::min<const void*>(objects[i], objects[j]),
				                               std::max<const void*>(objects[i], objects[j])));
		}
	for (int m = 0; m < f.m_dispatcher.getNumManifolds(); m++)
	{
		const btPersistentManifold* manifold = f.m_dispatcher.getManifoldByIndexInternal(m);
		bool penetrating = false;
		for (int p = 0; p < manifold->getNumContacts(); p++)
			penetrating = penetrating || manifold->getContactPoint(p).getDistance() < btScalar(-1e-3);
		if (penetrating)
			found.insert(std::make_pair(std::min<const void*>(manifold->getBody0(), manifold->getBody1()),
			                            std::max<const void*>(manifold->getBody0(), manifold->getBody1())));
	}
	EXPECT_GT(expected.size(), 5u);
	EXPECT_EQ(found, expected);
}

TEST(CollisionWorld, RefreshBroadphaseProxyKeepsGroupAndMask)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btBoxShape* box = f.own(new btBoxShape(btVector3(2, 2, 2)));
	btCollisionObject* a = f.add(sphere, at(btVector3(0, 0, 0)), 8, 3);
	a->setCollisionShape(box);
	f.m_world.refreshBroadphaseProxy(a);
	ASSERT_NE(a->getBroadphaseHandle(), nullptr);
	EXPECT_EQ(a->getBroadphaseHandle()->m_collisionFilterGroup, 8);
	EXPECT_EQ(a->getBroadphaseHandle()->m_collisionFilterMask, 3);
	EXPECT_EQ(f.m_broadphase.numProxies(), 1);
	expectProxyBox(a, -box->getHalfExtentsWithMargin(), box->getHalfExtentsWithMargin());
}

TEST(CollisionWorld, DebugDrawWorldDrawsWireframesAabbsAndContacts)
{
	WorldFixture f;
	CountingDrawer drawer;
	f.m_world.setDebugDrawer(&drawer);
	EXPECT_EQ(f.m_world.getDebugDrawer(), &drawer);
	btBoxShape* box = f.own(new btBoxShape(btVector3(1, 1, 1)));
	btCollisionObject* a = f.add(box, at(btVector3(0, 0, 0)));
	f.add(box, at(btVector3(0, 1.9, 0)));
	btCollisionObject* hidden = f.add(box, at(btVector3(10, 0, 0)));
	hidden->setCollisionFlags(hidden->getCollisionFlags() | btCollisionObject::CF_DISABLE_VISUALIZE_OBJECT);
	a->setCollisionFlags(0);
	f.m_world.performDiscreteCollisionDetection();

	int numPoints = 0;
	for (int m = 0; m < f.m_dispatcher.getNumManifolds(); m++)
		numPoints += f.m_dispatcher.getManifoldByIndexInternal(m)->getNumContacts();
	EXPECT_GT(numPoints, 0);

	drawer.setDebugMode(btIDebugDraw::DBG_NoDebug);
	f.m_world.debugDrawWorld();
	EXPECT_EQ(drawer.m_lines + drawer.m_aabbs + drawer.m_contacts, 0);

	drawer.setDebugMode(btIDebugDraw::DBG_DrawWireframe);
	f.m_world.debugDrawWorld();
	EXPECT_EQ(drawer.m_lines, 2 * 12);  // two visible boxes of 12 edges

	drawer.setDebugMode(btIDebugDraw::DBG_DrawAabb | btIDebugDraw::DBG_DrawContactPoints);
	f.m_world.debugDrawWorld();
	EXPECT_EQ(drawer.m_aabbs, 2);
	EXPECT_EQ(drawer.m_contacts, numPoints);
}
