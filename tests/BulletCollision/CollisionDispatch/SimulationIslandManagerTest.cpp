// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btLoneIslandSink.h"
#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"

namespace
{
struct RecordedIsland
{
	std::set<const btCollisionObject*> bodies;
	std::vector<btPersistentManifold*> manifolds;
	int id;
};

struct RecordingCallback : public btSimulationIslandManager::IslandCallback
{
	std::vector<RecordedIsland> islands;
	void processIsland(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                   int islandId) override
	{
		RecordedIsland island;
		island.id = islandId;
		for (int i = 0; i < numBodies; ++i) island.bodies.insert(bodies[i]);
		for (int i = 0; i < numManifolds; ++i) island.manifolds.push_back(manifolds[i]);
		islands.push_back(island);
	}
};

// Two stacks of three unit boxes (slightly interpenetrating so that every neighbour pair has contacts)
// standing apart on one static ground box, plus room for extra objects.
class TwoStacks
{
public:
	TwoStacks()
	    : m_dispatcher(&m_config),
	      m_groundShape(btVector3(20, 1, 20)),
	      m_boxShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)))
	{
		m_ground.setCollisionShape(&m_groundShape);
		m_ground.setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT);
		place(m_ground, btVector3(0, -1, 0));
		for (int s = 0; s < 2; ++s)
		{
			for (int level = 0; level < 3; ++level)
			{
				btCollisionObject& box = m_stack[s][level];
				box.setCollisionShape(&m_boxShape);
				box.setCollisionFlags(btCollisionObject::CF_DYNAMIC_OBJECT);
				// 0.98 apart: 2 cm of overlap, well inside the box-box contact range.
				place(box, btVector3(btScalar(s * 5), btScalar(0.49) + btScalar(0.98) * btScalar(level), 0));
			}
		}
		m_world.reset(new btCollisionWorld(&m_dispatcher, &m_broadphase, &m_config));
		m_world->addCollisionObject(&m_ground);
		for (int s = 0; s < 2; ++s)
			for (int level = 0; level < 3; ++level) m_world->addCollisionObject(&m_stack[s][level]);
	}
	~TwoStacks() { m_world.reset(); }

	static void place(btCollisionObject& object, const btVector3& origin)
	{
		btTransform t;
		t.setIdentity();
		t.setOrigin(origin);
		object.setWorldTransform(t);
	}

	// The order of a dynamics world's step: contacts, islands (with the tags stored), then callbacks.
	RecordingCallback step()
	{
		m_world->performDiscreteCollisionDetection();
		m_islands.updateActivationState(m_world.get(), &m_dispatcher);
		m_islands.storeIslandActivationState(m_world.get());
		RecordingCallback callback;
		m_islands.buildAndProcessIslands(&m_dispatcher, m_world.get(), &callback);
		return callback;
	}

	std::set<const btCollisionObject*> stackSet(int s) const
	{
		return std::set<const btCollisionObject*>{&m_stack[s][0], &m_stack[s][1], &m_stack[s][2]};
	}

	btDefaultCollisionConfiguration m_config;
	btCollisionDispatcher m_dispatcher;
	btDbvtBroadphase m_broadphase;
	btBoxShape m_groundShape;
	btBoxShape m_boxShape;
	btCollisionObject m_ground;
	btCollisionObject m_stack[2][3];
	btSimulationIslandManager m_islands;
	std::unique_ptr<btCollisionWorld> m_world;
};

int touchingManifolds(btDispatcher& dispatcher)
{
	int count = 0;
	for (int i = 0; i < dispatcher.getNumManifolds(); ++i)
		if (dispatcher.getManifoldByIndexInternal(i)->getNumContacts() > 0) ++count;
	return count;
}
}  // namespace

TEST(SimulationIslandManager, TwoStacksOnOneStaticGroundAreTwoIslands)
{
	TwoStacks scene;
	const RecordingCallback result = scene.step();
	ASSERT_EQ(touchingManifolds(scene.m_dispatcher), 6) << "3 contacts per stack: ground-box and box-box";
	ASSERT_EQ(result.islands.size(), 2u) << "the static ground must not merge the stacks";
	bool seen[2] = {false, false};
	for (const RecordedIsland& island : result.islands)
	{
		const int s = island.bodies == scene.stackSet(0) ? 0 : (island.bodies == scene.stackSet(1) ? 1 : -1);
		ASSERT_GE(s, 0) << "an island is exactly one stack";
		seen[s] = true;
		EXPECT_EQ(island.bodies.count(&scene.m_ground), 0u) << "static objects belong to no island";
		int withContacts = 0;
		for (btPersistentManifold* manifold : island.manifolds)
		{
			const bool mine = island.bodies.count(manifold->getBody0()) || island.bodies.count(manifold->getBody1());
			EXPECT_TRUE(mine) << "a manifold goes to the island of its dynamic body";
			if (manifold->getNumContacts() > 0) ++withContacts;
		}
		EXPECT_EQ(withContacts, 3) << "ground-bottom, bottom-middle, middle-top";
		for (const btCollisionObject* body : island.bodies) EXPECT_EQ(body->getIslandTag(), island.id);
	}
	EXPECT_TRUE(seen[0] && seen[1]);
	EXPECT_EQ(scene.m_ground.getIslandTag(), -1);
}

TEST(SimulationIslandManager, TouchingStacksMergeIntoOneIsland)
{
	TwoStacks scene;
	// Move stack 1 against stack 0: every box overlaps its neighbour in the other stack by 2 cm.
	for (int level = 0; level < 3; ++level)
	{
		btVector3 origin = scene.m_stack[1][level].getWorldTransform().getOrigin();
		origin.setX(btScalar(0.98));
		TwoStacks::place(scene.m_stack[1][level], origin);
	}
	const RecordingCallback result = scene.step();
	ASSERT_EQ(result.islands.size(), 1u);
	EXPECT_EQ(result.islands[0].bodies.size(), 6u);
}

// Steps another scene from inside its first island (as a program with two worlds might from a callback),
// then records as RecordingCallback does.
struct NestingCallback : public RecordingCallback
{
	TwoStacks* inner = nullptr;
	size_t innerIslands = 0;
	void processIsland(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                   int islandId) override
	{
		if (inner)
		{
			innerIslands = inner->step().islands.size();
			inner = nullptr;
		}
		RecordingCallback::processIsland(bodies, numBodies, manifolds, numManifolds, islandId);
	}
};

TEST(SimulationIslandManager, IslandsProcessedInsideAnotherManagersCallbackKeepBothGroupings)
{
	// The grouping of manifolds by island is per-thread scratch; a manager working inside another's
	// callback must not overwrite the outer grouping. The inner scene is one island of nine manifolds,
	// the outer two islands of three, so a shared grouping would hand the outer's second island a wrong range.
	TwoStacks outer, inner;
	for (int level = 0; level < 3; ++level)
	{
		btVector3 origin = inner.m_stack[1][level].getWorldTransform().getOrigin();
		origin.setX(btScalar(0.98));
		TwoStacks::place(inner.m_stack[1][level], origin);
	}
	outer.m_world->performDiscreteCollisionDetection();
	outer.m_islands.updateActivationState(outer.m_world.get(), &outer.m_dispatcher);
	outer.m_islands.storeIslandActivationState(outer.m_world.get());
	NestingCallback callback;
	callback.inner = &inner;
	outer.m_islands.buildAndProcessIslands(&outer.m_dispatcher, outer.m_world.get(), &callback);
	EXPECT_EQ(callback.innerIslands, 1u);
	ASSERT_EQ(callback.islands.size(), 2u);
	for (const RecordedIsland& island : callback.islands)
	{
		int withContacts = 0;
		for (btPersistentManifold* manifold : island.manifolds)
		{
			const bool mine = island.bodies.count(manifold->getBody0()) || island.bodies.count(manifold->getBody1());
			EXPECT_TRUE(mine) << "island " << island.id << " was given another island's manifold";
			if (manifold->getNumContacts() > 0) ++withContacts;
		}
		EXPECT_EQ(withContacts, 3) << "island " << island.id;
	}
}

TEST(SimulationIslandManager, IslandSleepsOnlyWhenAllItsObjectsWantTo)
{
	TwoStacks scene;
	scene.step();
	for (int level = 0; level < 3; ++level)
	{
		scene.m_stack[0][level].setActivationState(WANTS_DEACTIVATION);
		scene.m_stack[1][level].setActivationState(WANTS_DEACTIVATION);
	}
	scene.m_stack[1][2].setActivationState(ACTIVE_TAG);  // one restless box in stack 1

	const RecordingCallback result = scene.step();
	for (int level = 0; level < 3; ++level)
	{
		EXPECT_EQ(scene.m_stack[0][level].getActivationState(), ISLAND_SLEEPING) << "level " << level;
		EXPECT_NE(scene.m_stack[1][level].getActivationState(), ISLAND_SLEEPING) << "level " << level;
	}
	ASSERT_EQ(result.islands.size(), 1u) << "a sleeping island gets no callback";
	EXPECT_EQ(result.islands[0].bodies, scene.stackSet(1));

	// Waking one box of the sleeping stack wakes its whole island: the sleepers become WANTS_DEACTIVATION
	// with their rest timer restarted.
	scene.m_stack[0][0].setDeactivationTime(btScalar(5));
	scene.m_stack[0][1].activate();
	const RecordingCallback woken = scene.step();
	EXPECT_EQ(woken.islands.size(), 2u);
	EXPECT_EQ(scene.m_stack[0][0].getActivationState(), WANTS_DEACTIVATION);
	EXPECT_EQ(scene.m_stack[0][0].getDeactivationTime(), btScalar(0));
	EXPECT_EQ(scene.m_stack[0][1].getActivationState(), ACTIVE_TAG);
}

TEST(SimulationIslandManager, DisableDeactivationKeepsTheIslandAwake)
{
	TwoStacks scene;
	for (int level = 0; level < 3; ++level) scene.m_stack[0][level].setActivationState(WANTS_DEACTIVATION);
	scene.m_stack[0][1].forceActivationState(DISABLE_DEACTIVATION);
	scene.step();
	EXPECT_EQ(scene.m_stack[0][0].getActivationState(), WANTS_DEACTIVATION);
	EXPECT_EQ(scene.m_stack[0][2].getActivationState(), WANTS_DEACTIVATION);
}

TEST(SimulationIslandManager, KinematicObjectsWakeWhatTheyTouchWithoutMergingIslands)
{
	TwoStacks scene;
	// A kinematic bar lying across both stacks' tops (top faces at y = 2.95; the bar sinks 2 cm).
	btBoxShape barShape(btVector3(4, btScalar(0.25), btScalar(0.5)));
	btCollisionObject bar;
	bar.setCollisionShape(&barShape);
	bar.setCollisionFlags(btCollisionObject::CF_KINEMATIC_OBJECT);
	TwoStacks::place(bar, btVector3(btScalar(2.5), btScalar(3.18), 0));
	scene.m_world->addCollisionObject(&bar);

	scene.step();
	for (int s = 0; s < 2; ++s)
		for (int level = 0; level < 3; ++level) scene.m_stack[s][level].forceActivationState(ISLAND_SLEEPING);
	const RecordingCallback result = scene.step();
	ASSERT_EQ(result.islands.size(), 2u) << "the kinematic bar does not merge the stacks";
	EXPECT_EQ(bar.getIslandTag(), -1);
	// The awake bar woke the top boxes, so both islands are processed.
	for (int s = 0; s < 2; ++s) EXPECT_EQ(scene.m_stack[s][2].getActivationState(), ACTIVE_TAG) << "stack " << s;
	scene.m_world->removeCollisionObject(&bar);
}

TEST(SimulationIslandManager, TriggersDoNotMergeIslandsNorJoinTheirManifolds)
{
	TwoStacks scene;
	btBoxShape triggerShape(btVector3(4, btScalar(0.25), btScalar(0.5)));
	btCollisionObject trigger;
	trigger.setCollisionShape(&triggerShape);
	trigger.setCollisionFlags(btCollisionObject::CF_NO_CONTACT_RESPONSE);
	TwoStacks::place(trigger, btVector3(btScalar(2.5), btScalar(3.18), 0));
	scene.m_world->addCollisionObject(&trigger);

	const RecordingCallback result = scene.step();
	int triggerContacts = 0;
	for (int i = 0; i < scene.m_dispatcher.getNumManifolds(); ++i)
	{
		const btPersistentManifold* manifold = scene.m_dispatcher.getManifoldByIndexInternal(i);
		if ((manifold->getBody0() == &trigger || manifold->getBody1() == &trigger) && manifold->getNumContacts() > 0)
			++triggerContacts;
	}
	ASSERT_EQ(triggerContacts, 2) << "the trigger overlaps both top boxes";
	int islandsOfStacks = 0;
	for (const RecordedIsland& island : result.islands)
	{
		if (island.bodies == scene.stackSet(0) || island.bodies == scene.stackSet(1)) ++islandsOfStacks;
		for (btPersistentManifold* manifold : island.manifolds)
			EXPECT_TRUE(manifold->getBody0() != &trigger && manifold->getBody1() != &trigger)
			    << "contacts with a trigger need no response";
	}
	EXPECT_EQ(islandsOfStacks, 2);
	EXPECT_EQ(result.islands.size(), 3u) << "the trigger is dynamic: an island of its own";
	scene.m_world->removeCollisionObject(&trigger);
}

TEST(SimulationIslandManager, UnsplitIslandsGiveOneCallbackWithEverything)
{
	TwoStacks scene;
	scene.m_islands.setSplitIslands(false);
	EXPECT_FALSE(scene.m_islands.getSplitIslands());
	const RecordingCallback result = scene.step();
	ASSERT_EQ(result.islands.size(), 1u);
	EXPECT_EQ(result.islands[0].id, -1);
	EXPECT_EQ(result.islands[0].bodies.size(), 7u) << "every object of the world, ground included";
	EXPECT_EQ(int(result.islands[0].manifolds.size()), scene.m_dispatcher.getNumManifolds());
}

TEST(SimulationIslandManager, NullArgumentsAreRejected)
{
	btSimulationIslandManager islands;
	RecordingCallback callback;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(islands.updateActivationState(0, 0), "assertion failed");
	EXPECT_DEATH(islands.buildAndProcessIslands(0, 0, &callback), "assertion failed");
#else
	islands.updateActivationState(0, 0);
	islands.storeIslandActivationState(0);
	islands.buildAndProcessIslands(0, 0, &callback);
	EXPECT_TRUE(callback.islands.empty());
#endif
	TwoStacks scene;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(scene.m_islands.processIslands(&scene.m_dispatcher, scene.m_world.get(), 0), "assertion failed");
#else
	scene.m_islands.processIslands(&scene.m_dispatcher, scene.m_world.get(), 0);
#endif
}

namespace
{
// An island as a callback receives it: id, bodies in the order given, manifolds in the order given.
struct OrderedIsland
{
	int id;
	std::vector<const btCollisionObject*> bodies;
	std::vector<btPersistentManifold*> manifolds;
	bool operator==(const OrderedIsland& other) const
	{
		return id == other.id && bodies == other.bodies && manifolds == other.manifolds;
	}
};

struct OrderedRecorder : public btSimulationIslandManager::IslandCallback
{
	std::vector<OrderedIsland> islands;
	void processIsland(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                   int islandId) override
	{
		OrderedIsland island;
		island.id = islandId;
		island.bodies.assign(bodies, bodies + numBodies);
		island.manifolds.assign(manifolds, manifolds + numManifolds);
		islands.push_back(island);
	}
};

// The same recorder, also taking runs of lone islands as the worlds' own callback does.
struct OrderedSinkRecorder : public OrderedRecorder, public caliber::LoneIslandSink
{
	int loneIslands = 0;
	void processLoneIslands(btCollisionObject** bodies, const int* islandIds, int count) override
	{
		for (int i = 0; i < count; ++i)
		{
			OrderedIsland island;
			island.id = islandIds[i];
			island.bodies.push_back(bodies[i]);
			islands.push_back(island);
		}
		loneIslands += count;
	}
};
}  // namespace

// The lone-island runs are an internal shortcut: a callback taking them must see the islands a plain
// callback sees, in the same order, lone bodies (awake, asleep, resting on the ground with a manifold)
// mixed with touching stacks.
TEST(SimulationIslandManager, LoneIslandRunsGiveTheIslandsAndOrderOfOneCallPerIsland)
{
	TwoStacks scene;
	btBoxShape shape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	// Lone boxes before and after the stacks in the object array: in the air (no manifold), one asleep,
	// and one resting on the ground (a lone body with a manifold, which is not a run's).
	const btVector3 places[6] = {btVector3(-10, 5, 0), btVector3(-12, 5, 0), btVector3(10, 5, 0),
	                             btVector3(12, 5, 0),  btVector3(14, 5, 0),  btVector3(-14, btScalar(0.49), 0)};
	btCollisionObject lone[6];
	for (int i = 0; i < 6; ++i)
	{
		lone[i].setCollisionShape(&shape);
		lone[i].setCollisionFlags(btCollisionObject::CF_DYNAMIC_OBJECT);
		TwoStacks::place(lone[i], places[i]);
	}
	lone[3].setActivationState(ISLAND_SLEEPING);
	scene.m_world->removeCollisionObject(&scene.m_stack[1][0]);
	scene.m_world->removeCollisionObject(&scene.m_stack[1][1]);
	scene.m_world->removeCollisionObject(&scene.m_stack[1][2]);
	scene.m_world->addCollisionObject(&lone[0]);
	scene.m_world->addCollisionObject(&lone[1]);
	for (int level = 0; level < 3; ++level) scene.m_world->addCollisionObject(&scene.m_stack[1][level]);
	for (int i = 2; i < 6; ++i) scene.m_world->addCollisionObject(&lone[i]);

	scene.m_world->performDiscreteCollisionDetection();
	scene.m_islands.updateActivationState(scene.m_world.get(), &scene.m_dispatcher);
	scene.m_islands.storeIslandActivationState(scene.m_world.get());
	scene.m_islands.buildIslands(&scene.m_dispatcher, scene.m_world.get());
	OrderedRecorder plain;
	scene.m_islands.processIslands(&scene.m_dispatcher, scene.m_world.get(), &plain);
	OrderedSinkRecorder withRuns;
	scene.m_islands.processIslands(&scene.m_dispatcher, scene.m_world.get(), &withRuns);

	ASSERT_EQ(plain.islands.size(), 2u + 5u) << "two stacks, five awake lone boxes (the sixth is asleep)";
	EXPECT_EQ(withRuns.loneIslands, 4) << "the awake boxes in the air; the one on the ground has a manifold";
	ASSERT_EQ(withRuns.islands.size(), plain.islands.size());
	for (size_t i = 0; i < plain.islands.size(); ++i) EXPECT_TRUE(withRuns.islands[i] == plain.islands[i]) << i;
	for (const OrderedIsland& island : plain.islands)
		EXPECT_EQ(std::find(island.bodies.begin(), island.bodies.end(), &lone[3]), island.bodies.end())
		    << "the sleeping box is in no island";
	for (int i = 0; i < 6; ++i) scene.m_world->removeCollisionObject(&lone[i]);
}
