// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The manual's four ways of filtering collisions, each shown on two overlapping pairs of spheres: the
// filtered pair must get no contact points while the other pair still does.
#include <gtest/gtest.h>

#include <memory>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"

namespace
{
// User index that marks the objects of the pair to filter out.
const int kFilteredTag = 7;

// Four unit spheres: A and B overlap (the pair to filter), C and D overlap 10 m away (the control pair).
template <class Dispatcher>
class FilterScene
{
public:
	FilterScene() : m_dispatcher(&m_config), m_sphere(1)
	{
		const btVector3 origins[4] = {btVector3(0, 0, 0), btVector3(btScalar(1.5), 0, 0), btVector3(10, 0, 0),
		                              btVector3(btScalar(11.5), 0, 0)};
		for (int i = 0; i < 4; ++i)
		{
			btCollisionObject& object = m_objects[i];
			object.setCollisionShape(&m_sphere);
			object.setCollisionFlags(btCollisionObject::CF_DYNAMIC_OBJECT);
			btTransform t;
			t.setIdentity();
			t.setOrigin(origins[i]);
			object.setWorldTransform(t);
			object.setUserIndex(i < 2 ? kFilteredTag : 0);
		}
		m_world.reset(new btCollisionWorld(&m_dispatcher, &m_broadphase, &m_config));
	}
	~FilterScene() { m_world.reset(); }

	void addAll()
	{
		for (btCollisionObject& object : m_objects) m_world->addCollisionObject(&object);
	}

	// Number of contact points between objects i and j after the last collision detection.
	int contactsBetween(int i, int j)
	{
		int points = 0;
		for (int m = 0; m < m_dispatcher.getNumManifolds(); ++m)
		{
			const btPersistentManifold* manifold = m_dispatcher.getManifoldByIndexInternal(m);
			const bool same = (manifold->getBody0() == &m_objects[i] && manifold->getBody1() == &m_objects[j]) ||
			                  (manifold->getBody0() == &m_objects[j] && manifold->getBody1() == &m_objects[i]);
			if (same) points += manifold->getNumContacts();
		}
		return points;
	}

	void expectOnlyTheControlPairTouches(const char* way)
	{
		m_world->performDiscreteCollisionDetection();
		EXPECT_EQ(contactsBetween(0, 1), 0) << way << ": the filtered pair got contacts";
		EXPECT_GT(contactsBetween(2, 3), 0) << way << ": the control pair lost its contacts";
	}

	btDefaultCollisionConfiguration m_config;
	Dispatcher m_dispatcher;
	btDbvtBroadphase m_broadphase;
	btSphereShape m_sphere;
	btCollisionObject m_objects[4];
	std::unique_ptr<btCollisionWorld> m_world;
};

bool bothTagged(const btCollisionObject* a, const btCollisionObject* b)
{
	return a->getUserIndex() == kFilteredTag && b->getUserIndex() == kFilteredTag;
}

// Way 2: a broadphase filter that keeps the group/mask test and also rejects the tagged pair.
struct TagOverlapFilter : public btOverlapFilterCallback
{
	bool needBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override
	{
		const bool groupsAgree = (proxy0->m_collisionFilterGroup & proxy1->m_collisionFilterMask) != 0 &&
		                         (proxy1->m_collisionFilterGroup & proxy0->m_collisionFilterMask) != 0;
		const btCollisionObject* a = static_cast<const btCollisionObject*>(proxy0->m_clientObject);
		const btCollisionObject* b = static_cast<const btCollisionObject*>(proxy1->m_clientObject);
		return groupsAgree && !bothTagged(a, b);
	}
};

// Way 3: a near callback that skips the tagged pair and hands the rest to the default one.
void tagNearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info)
{
	const btCollisionObject* a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
	const btCollisionObject* b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
	if (bothTagged(a, b)) return;
	btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

// Way 4: a dispatcher whose needsCollision also rejects the tagged pair.
class TagDispatcher : public btCollisionDispatcher
{
public:
	explicit TagDispatcher(btCollisionConfiguration* config) : btCollisionDispatcher(config) {}
	bool needsCollision(const btCollisionObject* body0, const btCollisionObject* body1) override
	{
		if (bothTagged(body0, body1)) return false;
		return btCollisionDispatcher::needsCollision(body0, body1);
	}
};
}  // namespace

TEST(Filtering, UnfilteredSceneHasContactsOnBothPairs)
{
	// The control for the four tests below: without a filter both pairs touch.
	FilterScene<btCollisionDispatcher> scene;
	scene.addAll();
	scene.m_world->performDiscreteCollisionDetection();
	EXPECT_GT(scene.contactsBetween(0, 1), 0);
	EXPECT_GT(scene.contactsBetween(2, 3), 0);
	EXPECT_EQ(scene.contactsBetween(0, 2), 0) << "the pairs are 10 m apart";
}

TEST(Filtering, GroupAndMaskBitsKeepPairsOutOfTheBroadphase)
{
	FilterScene<btCollisionDispatcher> scene;
	const int groupA = 1 << 6;
	const int groupB = 1 << 7;
	// A collides with everything except B's group; B collides with everything. One side saying no is enough.
	scene.m_world->addCollisionObject(&scene.m_objects[0], groupA, btBroadphaseProxy::AllFilter & ~groupB);
	scene.m_world->addCollisionObject(&scene.m_objects[1], groupB, btBroadphaseProxy::AllFilter);
	scene.m_world->addCollisionObject(&scene.m_objects[2], groupA, btBroadphaseProxy::AllFilter);
	scene.m_world->addCollisionObject(&scene.m_objects[3], groupB, btBroadphaseProxy::AllFilter);
	scene.expectOnlyTheControlPairTouches("group/mask");
	EXPECT_TRUE(scene.m_world->getPairCache()->findPair(scene.m_objects[0].getBroadphaseHandle(),
	                                                    scene.m_objects[1].getBroadphaseHandle()) == 0)
	    << "filtered in the broadphase: no pair at all";
}

TEST(Filtering, OverlapFilterCallbackOnThePairCache)
{
	FilterScene<btCollisionDispatcher> scene;
	TagOverlapFilter filter;
	scene.m_world->getPairCache()->setOverlapFilterCallback(&filter);
	EXPECT_EQ(scene.m_world->getPairCache()->getOverlapFilterCallback(), &filter);
	scene.addAll();
	scene.expectOnlyTheControlPairTouches("btOverlapFilterCallback");
	EXPECT_TRUE(scene.m_world->getPairCache()->findPair(scene.m_objects[0].getBroadphaseHandle(),
	                                                    scene.m_objects[1].getBroadphaseHandle()) == 0);
	scene.m_world->getPairCache()->setOverlapFilterCallback(0);
}

TEST(Filtering, CustomNearCallbackOnTheDispatcher)
{
	FilterScene<btCollisionDispatcher> scene;
	scene.m_dispatcher.setNearCallback(&tagNearCallback);
	scene.addAll();
	scene.expectOnlyTheControlPairTouches("near callback");
	EXPECT_TRUE(scene.m_world->getPairCache()->findPair(scene.m_objects[0].getBroadphaseHandle(),
	                                                    scene.m_objects[1].getBroadphaseHandle()) != 0)
	    << "the broadphase still reports the pair; only the narrowphase is skipped";
}

TEST(Filtering, DispatcherOverridingNeedsCollision)
{
	FilterScene<TagDispatcher> scene;
	scene.addAll();
	scene.expectOnlyTheControlPairTouches("derived dispatcher");
	EXPECT_TRUE(scene.m_dispatcher.needsCollision(&scene.m_objects[2], &scene.m_objects[3]));
	EXPECT_FALSE(scene.m_dispatcher.needsCollision(&scene.m_objects[0], &scene.m_objects[1]));
}

TEST(Filtering, IgnoreListSkipsOnePairOfObjects)
{
	// Not one of the manual's four, but the same contract: checkCollideWith in needsCollision.
	FilterScene<btCollisionDispatcher> scene;
	scene.m_objects[1].setIgnoreCollisionCheck(&scene.m_objects[0], true);
	scene.addAll();
	scene.expectOnlyTheControlPairTouches("setIgnoreCollisionCheck");
}
