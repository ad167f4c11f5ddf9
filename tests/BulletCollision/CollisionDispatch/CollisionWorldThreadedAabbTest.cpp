// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// With a task scheduler, btCollisionWorld::updateAabbs computes the boxes on the threads and, for the dbvt
// broadphase itself, also stores there the boxes that still fit in their fat boxes (what setAabb would
// do). The broadphase must end exactly as with the serial updates: every proxy's AABB, every fat box, the
// update counters and the pairs; and a user's subclass of the broadphase still gets every setAabb call.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

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

struct Snapshot
{
	std::vector<btVector3> boxes;  // per object: AABB min, max, fat box min, max
	unsigned updatesCall = 0, updatesDone = 0;
	std::vector<std::pair<int, int> > pairs;
	int setAabbCalls = 0;
};

// 400 boxes on a grid (more than the 256 objects that start the threaded path); every step moves all of
// them, every third one far enough to leave its fat box, the others a millimetre (they stay inside).
Snapshot run(int threads, bool subclass)
{
	caliber_test::ScopedTaskScheduler scheduler(threads);
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	std::unique_ptr<btDbvtBroadphase> broadphase(subclass ? new CountingDbvtBroadphase : new btDbvtBroadphase);
	btCollisionWorld world(&dispatcher, broadphase.get(), &configuration);
	btBoxShape shape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	const int kObjects = 400;
	std::vector<std::unique_ptr<btCollisionObject> > objects;
	for (int i = 0; i < kObjects; ++i)
	{
		objects.emplace_back(new btCollisionObject);
		btCollisionObject& object = *objects.back();
		object.setCollisionShape(&shape);
		object.setWorldTransform(btTransform(btQuaternion::getIdentity(),
		                                     btVector3(btScalar(i % 20) * btScalar(0.9), 0, btScalar(i / 20) * btScalar(0.9))));
		world.addCollisionObject(&object);
	}
	if (subclass) static_cast<CountingDbvtBroadphase*>(broadphase.get())->calls = 0;
	Snapshot result;
	for (int step = 1; step <= 3; ++step)
	{
		for (int i = 0; i < kObjects; ++i)
		{
			const btScalar move = i % 3 == 0 ? btScalar(0.3) : btScalar(0.001);
			btTransform transform = objects[size_t(i)]->getWorldTransform();
			transform.getOrigin() += btVector3(0, move, 0);
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
	if (subclass) result.setAabbCalls = static_cast<CountingDbvtBroadphase*>(broadphase.get())->calls;
	for (const std::unique_ptr<btCollisionObject>& object : objects) world.removeCollisionObject(object.get());
	return result;
}

void expectSame(const Snapshot& serial, const Snapshot& threaded)
{
	ASSERT_EQ(serial.boxes.size(), threaded.boxes.size());
	for (size_t i = 0; i < serial.boxes.size(); ++i) EXPECT_EQ(serial.boxes[i], threaded.boxes[i]) << "box value " << i;
	EXPECT_EQ(serial.updatesCall, threaded.updatesCall);
	EXPECT_EQ(serial.updatesDone, threaded.updatesDone);
	EXPECT_TRUE(serial.pairs == threaded.pairs);
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
