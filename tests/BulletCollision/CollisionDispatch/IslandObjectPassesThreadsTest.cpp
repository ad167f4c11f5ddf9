// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The island manager's per-object passes on the task scheduler's threads (28 Nov, island14): the numbering
// of the simulated objects (updateActivationState), the islands' tags (storeIslandActivationState, whose finds
// on the threads leave the paths unhalved) and the sleeping decision of every island (buildIslands). Each
// chunk of objects or islands writes only its own objects, so the objects, the union-find after buildIslands
// and the islands handed to the callback must be those of the serial passes, at any thread count, with any
// split of the loops, when objects turn static or leave between calls (the chunks' cached starts are then
// wrong and the passes start over), and with two worlds of as many objects taking turns on one thread.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"

namespace
{
struct Island
{
	int id;
	std::vector<int> bodies;     // places in the world's object array
	std::vector<int> manifolds;  // places in the dispatcher's manifold array
	bool operator==(const Island& other) const
	{
		return id == other.id && bodies == other.bodies && manifolds == other.manifolds;
	}
};

// Records the islands by places, so that runs of different worlds compare.
struct RecordingCallback : public btSimulationIslandManager::IslandCallback
{
	btCollisionDispatcher* dispatcher = nullptr;
	std::vector<Island> islands;
	void processIsland(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                   int islandId) override
	{
		Island island;
		island.id = islandId;
		for (int i = 0; i < numBodies; ++i) island.bodies.push_back(bodies[i]->getWorldArrayIndex());
		for (int i = 0; i < numManifolds; ++i)
		{
			int place = -1;
			for (int m = 0; m < dispatcher->getNumManifolds() && place < 0; ++m)
				if (dispatcher->getManifoldByIndexInternal(m) == manifolds[i]) place = m;
			island.manifolds.push_back(place);
		}
		islands.push_back(island);
	}
};

// What the passes leave, per call of the island stage.
struct Record
{
	std::vector<int> tags, companions, states;
	std::vector<btScalar> hitFractions, deactivationTimes;
	std::vector<int> elements;  // (m_id, m_sz) of every element after buildIslands
	std::vector<Island> islands;
	bool operator==(const Record& o) const
	{
		return tags == o.tags && companions == o.companions && states == o.states && hitFractions == o.hitFractions &&
		       deactivationTimes == o.deactivationTimes && elements == o.elements && islands == o.islands;
	}
};

// A grid of 1300 small boxes on a static floor: most in rows of three touching boxes (islands of three through
// their contacts), some alone; every 13th static, every 17th kinematic (both belong to no island and merge
// none); whole rows asleep, rows with one sleeping box among awake ones (woken), boxes that want to sleep
// (their island sleeps when none must stay awake) and boxes that must never sleep.
class Grid
{
public:
	explicit Grid(int variant, bool withKinematic = true)
	    : m_dispatcher(&m_config), m_floorShape(btVector3(200, 1, 200)), m_boxShape(btVector3(btScalar(0.25), btScalar(0.25), btScalar(0.25)))
	{
		m_world.reset(new btCollisionWorld(&m_dispatcher, &m_broadphase, &m_config));
		m_floor.setCollisionShape(&m_floorShape);
		m_floor.setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT);
		place(m_floor, btVector3(0, -1, 0));
		m_world->addCollisionObject(&m_floor);
		m_boxes.resize(kBoxes);
		for (int i = 0; i < kBoxes; ++i)
		{
			btCollisionObject& box = m_boxes[i];
			box.setCollisionShape(&m_boxShape);
			const int row = i / 3, inRow = i % 3;
			// Rows of three 0.49 m apart (1 cm of overlap: touching); every fifth row spread 0.6 m apart (three
			// lone boxes).
			const btScalar spacing = row % 5 == 4 ? btScalar(0.6) : btScalar(0.49);
			place(box, btVector3(btScalar(row % 20) * 3 + btScalar(inRow) * spacing, btScalar(0.24),
			                     btScalar(row / 20) * 2));
			int flags = btCollisionObject::CF_DYNAMIC_OBJECT;
			if ((i + variant) % 13 == 5) flags = btCollisionObject::CF_STATIC_OBJECT;
			if (withKinematic && (i + variant) % 17 == 3) flags = btCollisionObject::CF_KINEMATIC_OBJECT;
			box.setCollisionFlags(flags);
			int state = ACTIVE_TAG;
			if (row % 7 == 2) state = ISLAND_SLEEPING;                   // a sleeping row
			if (row % 7 == 3 && inRow == 1) state = ISLAND_SLEEPING;     // one sleeper among awake boxes
			if (row % 7 == 1 || row % 7 == 4 || row % 7 == 6 || (row % 7 == 5 && inRow != 0)) state = WANTS_DEACTIVATION;
			if (row % 11 == 6 && inRow == 2) state = DISABLE_DEACTIVATION;
			box.forceActivationState(state);
			box.setDeactivationTime(btScalar(0.25) * btScalar(i % 4));
			m_world->addCollisionObject(&box);
		}
	}
	~Grid() { m_world.reset(); }

	static void place(btCollisionObject& object, const btVector3& origin)
	{
		btTransform t;
		t.setIdentity();
		t.setOrigin(origin);
		object.setWorldTransform(t);
	}

	// The island stage in a dynamics world's order: contacts, numbering and unions, tags, islands.
	Record step()
	{
		m_world->performDiscreteCollisionDetection();
		m_islands.updateActivationState(m_world.get(), &m_dispatcher);
		m_islands.storeIslandActivationState(m_world.get());
		return islands();
	}

	// buildAndProcessIslands and what the passes left.
	Record islands()
	{
		RecordingCallback callback;
		callback.dispatcher = &m_dispatcher;
		m_islands.buildAndProcessIslands(&m_dispatcher, m_world.get(), &callback);
		Record record;
		btCollisionObjectArray& objects = m_world->getCollisionObjectArray();
		for (int i = 0; i < objects.size(); ++i)
		{
			const btCollisionObject* object = objects[i];
			record.tags.push_back(object->getIslandTag());
			record.companions.push_back(object->getCompanionId());
			record.states.push_back(object->getActivationState());
			record.hitFractions.push_back(object->getHitFraction());
			record.deactivationTimes.push_back(object->getDeactivationTime());
		}
		btUnionFind& unionFind = m_islands.getUnionFind();
		for (int i = 0; i < unionFind.getNumElements(); ++i)
		{
			record.elements.push_back(unionFind.getElement(i).m_id);
			record.elements.push_back(unionFind.getElement(i).m_sz);
		}
		record.islands = callback.islands;
		return record;
	}

	static const int kBoxes = 1300;
	btDefaultCollisionConfiguration m_config;
	btCollisionDispatcher m_dispatcher;
	btDbvtBroadphase m_broadphase;
	btBoxShape m_floorShape;
	btBoxShape m_boxShape;
	btCollisionObject m_floor;
	std::vector<btCollisionObject> m_boxes;
	btSimulationIslandManager m_islands;
	std::unique_ptr<btCollisionWorld> m_world;
};

// Four calls of the island stage: as built; after a dynamic box turned static and a static one dynamic (the
// chunks' counts change); after a box left the world and another of the first chunk woke (the objects move
// down one place); and once more unchanged.
std::vector<Record> runGrid(int variant, bool withKinematic)
{
	Grid grid(variant, withKinematic);
	std::vector<Record> records;
	records.push_back(grid.step());
	grid.m_boxes[40].setCollisionFlags(btCollisionObject::CF_STATIC_OBJECT);
	for (int i = 0; i < Grid::kBoxes; ++i)
		if (grid.m_boxes[i].isStaticObject() && i > 700)
		{
			grid.m_boxes[i].setCollisionFlags(btCollisionObject::CF_DYNAMIC_OBJECT);
			break;
		}
	records.push_back(grid.step());
	grid.m_world->removeCollisionObject(&grid.m_boxes[3]);
	grid.m_boxes[7].activate(true);
	records.push_back(grid.step());
	records.push_back(grid.step());
	return records;
}

void expectSerialRecords(btITaskScheduler* scheduler, int threads, const char* what, bool withKinematic);

// The serial passes' records (no scheduler), and the same with a scheduler, with and without kinematic boxes.
void expectSerialRecords(btITaskScheduler* scheduler, int threads, const char* what)
{
	for (bool withKinematic : {true, false})
		expectSerialRecords(scheduler, threads, what, withKinematic);
}

// withKinematic: awake kinematic boxes touch dynamic ones and wake them after the sleeping pass (whose notes
// of which objects are awake processIslands must then not trust); without, processIslands reads the notes.
void expectSerialRecords(btITaskScheduler* scheduler, int threads, const char* what, bool withKinematic)
{
	btSetTaskScheduler(0);
	const std::vector<Record> serial = runGrid(0, withKinematic);
	// Enough objects for the passes to take the threads (4 chunks of 256), else the test compares the serial
	// passes with themselves.
	ASSERT_GE(Grid::kBoxes + 1, 1024);
	int sleeping = 0, lone = 0, larger = 0;
	for (int state : serial[0].states) sleeping += state == ISLAND_SLEEPING ? 1 : 0;
	for (const Island& island : serial[0].islands) (island.bodies.size() == 1 ? lone : larger) += 1;
	ASSERT_GT(sleeping, 0) << "some islands must sleep";
	ASSERT_GT(lone, 0);
	ASSERT_GT(larger, 0);
	btSetTaskScheduler(scheduler);
	if (threads > 0) scheduler->setNumThreads(threads);
	const std::vector<Record> run = runGrid(0, withKinematic);
	btSetTaskScheduler(0);
	ASSERT_EQ(run.size(), serial.size());
	for (size_t i = 0; i < run.size(); ++i)
		EXPECT_TRUE(run[i] == serial[i]) << what << ", call " << i << (withKinematic ? ", kinematic boxes" : "");
}
}  // namespace

TEST(IslandObjectPassesThreads, TheObjectsAndIslandsAreTheSerialPassesAtAnyThreadCount)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	if (!pool) GTEST_SKIP() << "a library without threads";
	expectSerialRecords(pool.get(), 1, "1 thread");
	expectSerialRecords(pool.get(), 2, "2 threads");
	expectSerialRecords(pool.get(), 3, "3 threads");
}

TEST(IslandObjectPassesThreads, AnySplitOrOrderOfTheLoopsGivesTheSerialPasses)
{
	caliber_test::UnevenSplitScheduler uneven;
	expectSerialRecords(&uneven, 0, "uneven split");
	caliber_test::LastFirstScheduler lastFirst;
	expectSerialRecords(&lastFirst, 0, "last chunk first");
}

TEST(IslandObjectPassesThreads, TwoWorldsOfAsManyObjectsTakingTurnsGetTheirOwnNumbering)
{
	// Two grids of 1301 objects whose static and kinematic boxes are at other places: the chunks' starts one
	// world's numbering leaves are wrong for the other's, every call.
	btSetTaskScheduler(0);
	std::vector<Record> serialA, serialB;
	{
		Grid a(0), b(6);
		for (int i = 0; i < 3; ++i)
		{
			serialA.push_back(a.step());
			serialB.push_back(b.step());
		}
	}
	ASSERT_FALSE(serialA[0].tags == serialB[0].tags);
	caliber_test::ScopedTaskScheduler threads(2);
	Grid a(0), b(6);
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_TRUE(a.step() == serialA[i]) << "world A, call " << i;
		EXPECT_TRUE(b.step() == serialB[i]) << "world B, call " << i;
	}
}

TEST(IslandObjectPassesThreads, TagsStoredAfterAnotherWorldsNumberingAreTheSerialTags)
{
	// Both worlds numbered, then both tagged: world A's tags are stored with the chunks' starts of world B's
	// numbering, which the chunks find wrong (the serial pass then stores them).
	std::vector<Record> serial, threaded;
	for (int threads : {0, 2})
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		Grid a(0), b(6);
		std::vector<Record>& records = threads ? threaded : serial;
		for (int i = 0; i < 2; ++i)
		{
			a.m_world->performDiscreteCollisionDetection();
			b.m_world->performDiscreteCollisionDetection();
			a.m_islands.updateActivationState(a.m_world.get(), &a.m_dispatcher);
			b.m_islands.updateActivationState(b.m_world.get(), &b.m_dispatcher);
			a.m_islands.storeIslandActivationState(a.m_world.get());
			b.m_islands.storeIslandActivationState(b.m_world.get());
			records.push_back(a.islands());
			records.push_back(b.islands());
		}
	}
	ASSERT_EQ(threaded.size(), serial.size());
	for (size_t i = 0; i < serial.size(); ++i) EXPECT_TRUE(threaded[i] == serial[i]) << "record " << i;
}

TEST(IslandObjectPassesThreads, ObjectsWokenBetweenBuildIslandsAndProcessIslandsAreProcessed)
{
	// A caller that runs the two halves of buildAndProcessIslands itself and wakes a sleeping row between them:
	// processIslands must see the woken row (it may not use what the sleeping pass noted).
	std::vector<std::vector<Island>> serial, threaded;
	for (int threads : {0, 2})
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		Grid grid(0, false);
		std::vector<std::vector<Island>>& islands = threads ? threaded : serial;
		for (int i = 0; i < 2; ++i)
		{
			grid.m_world->performDiscreteCollisionDetection();
			grid.m_islands.updateActivationState(grid.m_world.get(), &grid.m_dispatcher);
			grid.m_islands.storeIslandActivationState(grid.m_world.get());
			grid.m_islands.buildIslands(&grid.m_dispatcher, grid.m_world.get());
			// Row 9 (boxes 27-29) sleeps (9 % 7 == 2).
			ASSERT_EQ(grid.m_boxes[28].getActivationState(), ISLAND_SLEEPING);
			grid.m_boxes[28].activate(true);
			RecordingCallback callback;
			callback.dispatcher = &grid.m_dispatcher;
			grid.m_islands.processIslands(&grid.m_dispatcher, grid.m_world.get(), &callback);
			bool seen = false;
			for (const Island& island : callback.islands)
				for (int body : island.bodies) seen = seen || body == grid.m_boxes[28].getWorldArrayIndex();
			EXPECT_TRUE(seen) << "the woken box's island is processed, threads " << threads;
			islands.push_back(callback.islands);
			grid.m_boxes[28].forceActivationState(ISLAND_SLEEPING);
		}
	}
	EXPECT_TRUE(threaded == serial);
}
