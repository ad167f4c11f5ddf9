// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// With a task scheduler, btCollisionWorld::updateAabbs computes the boxes on the threads and, for the dbvt
// broadphase itself, also stores there the boxes that still fit in their fat boxes (what setAabb would
// do) and the new tree boxes of those that left them; one task then moves the leaves in object order while
// the others compute the boxes of the objects after them (or, with caliber::setSubtreeMovesInWorld(true),
// each task moves the leaves of one subtree of the dynamic tree in object order, computing the boxes of the
// objects as it reaches them). The
// broadphase must end exactly as with the serial updates: every proxy's AABB, every fat box, the dynamic
// tree node by node, the update counters and the pairs; a user's subclass of the broadphase still gets
// every setAabb call, and a user's pair filter is still asked about every pair the search finds.

#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtAabbFastPath.h"
#include "BulletCollision/BroadphaseCollision/DbvtTreeSnapshot.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "TestThreadsUtil.h"

namespace
{
// Counts the calls that reach setAabb (a Bullet-style subclass that watches them).
struct CountingDbvtBroadphase : public btDbvtBroadphase
{
	int calls = 0;
	void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
	             btDispatcher* dispatcher) override
	{
		++calls;
		btDbvtBroadphase::setAabb(proxy, aabbMin, aabbMax, dispatcher);
	}
};

// Refuses the pairs of two objects whose indices (the user pointers) differ by a multiple of 7, and notes
// whether it was ever called off the thread that made it (a user's filter need not be thread-safe).
struct SevenFilter : public btOverlapFilterCallback
{
	std::thread::id owner = std::this_thread::get_id();
	int calls = 0;
	bool calledOffOwner = false;
	bool needBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override
	{
		SevenFilter* self = const_cast<SevenFilter*>(this);
		++self->calls;
		if (std::this_thread::get_id() != owner) self->calledOffOwner = true;
		const btCollisionObject* a = static_cast<const btCollisionObject*>(proxy0->m_clientObject);
		const btCollisionObject* b = static_cast<const btCollisionObject*>(proxy1->m_clientObject);
		return (a->getUserIndex() - b->getUserIndex()) % 7 != 0;
	}
};

struct Snapshot
{
	std::vector<btVector3> boxes;  // per object: AABB min, max, fat box min, max
	unsigned updatesCall = 0, updatesDone = 0;
	std::vector<std::pair<int, int>> pairs;
	// The dynamic tree depth first: per node its box and, for a leaf, its proxy's id (-1 for inner nodes).
	std::vector<btVector3> treeBoxes;
	std::vector<int> treeLeaves;
	int setAabbCalls = 0;
	int filterCalls = 0;
	bool filterCalledOffOwner = false;
	std::vector<int> activationStates;
};

// 400 boxes on a grid (more than the 256 objects that start the threaded path); every step moves all of
// them, every third one far enough to leave its fat box, the others a millimetre (they stay inside).
// overflowAt >= 0: that object is a moving one (not static) with a box far too large for a moving object,
// so each update finds it overflowing. userScheduler: used instead of the thread pool when not null.
// jumps: every 37th object also jumps 12 m along x each step (across the grid: moves that leave their
// subtrees of the tree). rootInsertions: the dynamic tree re-inserts moved leaves from its root (m_lkhd -1),
// which no subtree can do alone.
Snapshot run(int threads, bool subclass, bool filter = false, int overflowAt = -1,
             btITaskScheduler* userScheduler = 0, bool jumps = false, bool rootInsertions = false)
{
	caliber_test::ScopedTaskScheduler scheduler(userScheduler ? 0 : threads);
	if (userScheduler) btSetTaskScheduler(userScheduler);
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	std::unique_ptr<btDbvtBroadphase> broadphase(subclass ? new CountingDbvtBroadphase : new btDbvtBroadphase);
	btCollisionWorld world(&dispatcher, broadphase.get(), &configuration);
	SevenFilter sevenFilter;
	if (filter) broadphase->getOverlappingPairCache()->setOverlapFilterCallback(&sevenFilter);
	btBoxShape shape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	btBoxShape hugeShape(btVector3(btScalar(1e7), btScalar(1e7), btScalar(1e7)));  // extent 2e7 m: overflow
	const int kObjects = 400;
	std::vector<std::unique_ptr<btCollisionObject>> objects;
	for (int i = 0; i < kObjects; ++i)
	{
		objects.emplace_back(new btCollisionObject);
		btCollisionObject& object = *objects.back();
		object.setCollisionShape(i == overflowAt ? static_cast<btCollisionShape*>(&hugeShape) : &shape);
		if (i == overflowAt) object.setCollisionFlags(0);
		object.setUserIndex(i);
		object.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(btScalar(i % 20) * btScalar(0.9), 0,
		                                                                            btScalar(i / 20) * btScalar(0.9))));
		world.addCollisionObject(&object);
	}
	if (subclass) static_cast<CountingDbvtBroadphase*>(broadphase.get())->calls = 0;
	if (rootInsertions) broadphase->m_sets[btDbvtBroadphase::DYNAMIC_SET].m_lkhd = -1;
	Snapshot result;
	for (int step = 1; step <= 3; ++step)
	{
		for (int i = 0; i < kObjects; ++i)
		{
			const btScalar move = i % 3 == 0 ? btScalar(0.3) : btScalar(0.001);
			btTransform transform = objects[size_t(i)]->getWorldTransform();
			transform.getOrigin() += btVector3(jumps && i % 37 == 0 ? btScalar(12) : btScalar(0), move, 0);
			objects[size_t(i)]->setWorldTransform(transform);
		}
		world.updateAabbs();
		result.updatesCall += broadphase->m_updates_call;
		result.updatesDone += broadphase->m_updates_done;
		broadphase->calculateOverlappingPairs(&dispatcher);
	}
	for (const std::unique_ptr<btCollisionObject>& object : objects)
	{
		const btDbvtProxy* proxy = static_cast<const btDbvtProxy*>(object->getBroadphaseHandle());
		result.boxes.push_back(proxy->m_aabbMin);
		result.boxes.push_back(proxy->m_aabbMax);
		result.boxes.push_back(proxy->leaf->volume.Mins());
		result.boxes.push_back(proxy->leaf->volume.Maxs());
	}
	const btBroadphasePairArray& pairs = broadphase->getOverlappingPairCache()->getOverlappingPairArray();
	for (int i = 0; i < pairs.size(); ++i)
		result.pairs.push_back(std::make_pair(pairs[i].m_pProxy0->m_uniqueId, pairs[i].m_pProxy1->m_uniqueId));
	dbvt_test::snapshotTree(broadphase->m_sets[btDbvtBroadphase::DYNAMIC_SET].m_root, result.treeBoxes,
	                        result.treeLeaves);
	if (subclass) result.setAabbCalls = static_cast<CountingDbvtBroadphase*>(broadphase.get())->calls;
	result.filterCalls = sevenFilter.calls;
	result.filterCalledOffOwner = sevenFilter.calledOffOwner;
	for (const std::unique_ptr<btCollisionObject>& object : objects)
		result.activationStates.push_back(object->getActivationState());
	for (const std::unique_ptr<btCollisionObject>& object : objects) world.removeCollisionObject(object.get());
	if (userScheduler) btSetTaskScheduler(0);
	return result;
}

void expectSame(const Snapshot& serial, const Snapshot& threaded)
{
	ASSERT_EQ(serial.boxes.size(), threaded.boxes.size());
	for (size_t i = 0; i < serial.boxes.size(); ++i) EXPECT_EQ(serial.boxes[i], threaded.boxes[i]) << "box value " << i;
	EXPECT_EQ(serial.updatesCall, threaded.updatesCall);
	EXPECT_EQ(serial.updatesDone, threaded.updatesDone);
	EXPECT_TRUE(serial.pairs == threaded.pairs);
	EXPECT_TRUE(serial.treeLeaves == threaded.treeLeaves);
	EXPECT_TRUE(serial.treeBoxes == threaded.treeBoxes);
	EXPECT_TRUE(serial.activationStates == threaded.activationStates);
}
}  // namespace

TEST(CollisionWorldThreadedAabbs, BroadphaseEndsAsWithSerialUpdates)
{
	const Snapshot serial = run(0, false);
	// Every object is updated each step (3 x 400 calls). The 134 objects moved 0.3 m leave their fat boxes
	// (margin 0.05 m) in steps 1 and 3; in step 2 they still fit, since the fat box made in step 1 reaches
	// one more displacement (0.3 m, m_prediction 1) ahead. The others move 1 mm and always fit.
	EXPECT_EQ(serial.updatesCall, 1200u);
	EXPECT_EQ(serial.updatesDone, 2u * 134u);
	EXPECT_GT(serial.pairs.size(), 100u);
	for (int threads : {1, 2, 4}) expectSame(serial, run(threads, false));
}

TEST(CollisionWorldThreadedAabbs, SubclassOfTheBroadphaseGetsEverySetAabbCall)
{
	const Snapshot serial = run(0, true);
	EXPECT_EQ(serial.setAabbCalls, 1200);
	const Snapshot threaded = run(2, true);
	EXPECT_EQ(threaded.setAabbCalls, 1200);
	expectSame(serial, threaded);
}

// The pair search lists the pairs on the threads and leaves off those the cache already holds; with a
// user's filter it may not judge them there: the filter still sees every pair the search finds, on the
// calling thread, and the cache ends as with the serial search.
TEST(CollisionWorldThreadedAabbs, FilterCallbackSeesEveryFoundPairOnTheCallingThread)
{
	const Snapshot serial = run(0, false, true);
	EXPECT_GT(serial.filterCalls, 0);
	EXPECT_GT(serial.pairs.size(), 100u);
	for (int threads : {1, 2})
	{
		const Snapshot threaded = run(threads, false, true);
		expectSame(serial, threaded);
		EXPECT_EQ(serial.filterCalls, threaded.filterCalls);
		EXPECT_FALSE(threaded.filterCalledOffOwner);
	}
}

// The tree moves run in object order on one task while the other tasks compute the boxes of the objects
// after them; an object whose box overflows stops that task, and the calling thread goes on from it (its
// quarantine and warning, then the rest in order). The broadphase and the states end as with the serial
// updates at any thread count, and with chunks run last to first.
TEST(CollisionWorldThreadedAabbs, ObjectOverflowingMidwayEndsAsWithSerialUpdates)
{
	// In the fifth chunk of 32 objects (one moved 1 mm a step): after some tree moves, before others.
	const int overflowAt = 151;
	const Snapshot serial = run(0, false, false, overflowAt);
	ASSERT_EQ(serial.activationStates.size(), 400u);
	EXPECT_EQ(serial.activationStates[overflowAt], DISABLE_SIMULATION);
	EXPECT_EQ(serial.activationStates[overflowAt + 1], ACTIVE_TAG);
	// The 134 objects moved 0.3 m still leave their fat boxes in steps 1 and 3 (see above).
	EXPECT_EQ(serial.updatesDone, 2u * 134u);
	for (int threads : {1, 2, 3, 4}) expectSame(serial, run(threads, false, false, overflowAt));
	caliber_test::LastFirstScheduler reverse;
	expectSame(serial, run(0, false, false, overflowAt, &reverse));
	caliber_test::UnevenSplitScheduler uneven;
	expectSame(serial, run(0, false, false, overflowAt, &uneven));
	// The same with the tree moves of each subtree on its own task (caliber::DbvtMoveRound).
	caliber::setSubtreeMovesInWorld(true);
	for (int threads : {2, 3}) expectSame(serial, run(threads, false, false, overflowAt));
	expectSame(serial, run(0, false, false, overflowAt, &reverse));
	expectSame(serial, run(0, false, false, overflowAt, &uneven));
	caliber::setSubtreeMovesInWorld(false);
}

TEST(CollisionWorldThreadedAabbs, ChunksInAnyOrderOrSplitGiveTheSerialBroadphase)
{
	const Snapshot serial = run(0, false);
	caliber_test::LastFirstScheduler reverse;
	expectSame(serial, run(0, false, false, -1, &reverse));
	caliber_test::UnevenSplitScheduler uneven;
	expectSame(serial, run(0, false, false, -1, &uneven));
}

// With caliber::setSubtreeMovesInWorld(true) and several threads, the tree moves of the leaves in different
// subtrees of the dynamic tree run on different tasks (caliber::DbvtMoveRound); a move that leaves its
// subtree, or a tree that re-inserts from its root, sends the rest to the calling thread in order. Every thread count and
// the two odd schedulers end with the serial broadphase.
TEST(CollisionWorldThreadedAabbs, TreeMovesOfDifferentSubtreesOnTheThreadsGiveTheSerialBroadphase)
{
	struct SubtreeMovesOn
	{
		SubtreeMovesOn() { caliber::setSubtreeMovesInWorld(true); }
		~SubtreeMovesOn() { caliber::setSubtreeMovesInWorld(false); }
	} on;
	for (bool rootInsertions : {false, true})
	{
		SCOPED_TRACE(rootInsertions ? "re-insertion from the root" : "re-insertion from a few levels up");
		const Snapshot serial = run(0, false, false, -1, 0, true, rootInsertions);
		// The 134 objects moved 0.3 m leave their fat boxes in steps 1 and 3 (see above), and so do the 11
		// jumping objects (the fat box made in step 1 reaches one more jump ahead); 4 of them (0, 111, 222,
		// 333) are among the 134.
		EXPECT_EQ(serial.updatesDone, 2u * 134u + 2u * 11u - 2u * 4u);
		for (int threads : {1, 2, 3}) expectSame(serial, run(threads, false, false, -1, 0, true, rootInsertions));
		caliber_test::LastFirstScheduler reverse;
		expectSame(serial, run(0, false, false, -1, &reverse, true, rootInsertions));
		caliber_test::UnevenSplitScheduler uneven;
		expectSame(serial, run(0, false, false, -1, &uneven, true, rootInsertions));
	}
}
