// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::setAabbChunkPrologue: the next updateAabbs of the world does the prologue's work exactly once,
// chunk by chunk (every object in exactly one chunk, each chunk before its own boxes) in the dbvt
// broadphase's box loop with threads when the last steps' tree moves outweigh the boxes, or by prepareAll
// before anything else otherwise and on every other path; a prologue set for another world, or forgotten,
// is not done.

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"
#include "BulletCollision/CollisionDispatch/btAabbChunkPrologue.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "TestThreadsUtil.h"

namespace
{
// Moves each object it prepares up (1 m unless told) and counts, per object, how often it did: the boxes
// computed after it must be those of the moved objects.
class LiftingPrologue : public caliber::AabbChunkPrologue
{
public:
	explicit LiftingPrologue(btCollisionWorld& world, btScalar lift = 1)
	    : m_world(&world), m_lift(lift), m_counts(new std::atomic<int>[size_t(world.getNumCollisionObjects())])
	{
		for (int i = 0; i < world.getNumCollisionObjects(); ++i) m_counts[size_t(i)].store(0);
	}
	void prepareObjects(int objectBegin, int objectEnd) const override
	{
		++m_chunkCalls;
		for (int i = objectBegin; i < objectEnd; ++i) lift(i);
	}
	void prepareAll() const override
	{
		++m_allCalls;
		for (int i = 0; i < m_world->getNumCollisionObjects(); ++i) lift(i);
	}
	int count(int i) const { return m_counts[size_t(i)].load(); }
	int chunkCalls() const { return m_chunkCalls.load(); }
	int allCalls() const { return m_allCalls.load(); }

private:
	void lift(int i) const
	{
		btCollisionObject* object = m_world->getCollisionObjectArray()[i];
		btTransform transform = object->getWorldTransform();
		transform.getOrigin() += btVector3(0, m_lift, 0);
		object->setWorldTransform(transform);
		m_counts[size_t(i)].fetch_add(1);
	}
	btCollisionWorld* m_world;
	btScalar m_lift;
	std::unique_ptr<std::atomic<int>[]> m_counts;
	mutable std::atomic<int> m_chunkCalls{0};
	mutable std::atomic<int> m_allCalls{0};
};

// A collision world of `count` unit boxes on a grid (400 is more than the 256 objects of the threaded path).
struct Scene
{
	explicit Scene(int count, bool simpleBroadphase = false)
	    : dispatcher(&configuration),
	      broadphase(simpleBroadphase ? static_cast<btBroadphaseInterface*>(new btSimpleBroadphase(1024))
	                                  : new btDbvtBroadphase),
	      world(&dispatcher, broadphase.get(), &configuration),
	      shape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)))
	{
		for (int i = 0; i < count; ++i)
		{
			objects.emplace_back(new btCollisionObject);
			btCollisionObject& object = *objects.back();
			object.setCollisionShape(&shape);
			object.setCollisionFlags(0);  // moving, so that updateAabbs updates it
			object.setWorldTransform(
			    btTransform(btQuaternion::getIdentity(), btVector3(btScalar(i % 20) * 3, 0, btScalar(i / 20) * 3)));
			world.addCollisionObject(&object);
		}
	}
	~Scene()
	{
		for (auto& object : objects) world.removeCollisionObject(object.get());
	}
	// Sends every object to another object's grid cell and updates the boxes, twice: each leaf leaves its
	// fat box and its tree neighbours, so both steps re-insert every leaf (the costly tree moves that make
	// the box loop take the prologue).
	void shuffleTwice()
	{
		const int count = static_cast<int>(objects.size());
		for (int step = 1; step <= 2; ++step)
		{
			for (int i = 0; i < count; ++i)
			{
				const int cell = (i + step * 157) % count;
				objects[size_t(i)]->setWorldTransform(btTransform(
				    btQuaternion::getIdentity(), btVector3(btScalar(cell % 20) * 3, 0, btScalar(cell / 20) * 3)));
			}
			world.updateAabbs();
		}
	}
	// True when every proxy's AABB contains the box of its object's current pose (the lifted one).
	bool boxesFollowTheObjects() const
	{
		for (const auto& object : objects)
		{
			btVector3 shapeMin, shapeMax, proxyMin, proxyMax;
			shape.getAabb(object->getWorldTransform(), shapeMin, shapeMax);
			broadphase->getAabb(object->getBroadphaseHandle(), proxyMin, proxyMax);
			for (int k = 0; k < 3; ++k)
				if (proxyMin[k] > shapeMin[k] || proxyMax[k] < shapeMax[k]) return false;
		}
		return true;
	}
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher;
	std::unique_ptr<btBroadphaseInterface> broadphase;
	btCollisionWorld world;
	btBoxShape shape;
	std::vector<std::unique_ptr<btCollisionObject>> objects;
};

void expectEachObjectOnce(const LiftingPrologue& prologue, int count)
{
	for (int i = 0; i < count; ++i) ASSERT_EQ(prologue.count(i), 1) << "object " << i;
}
}  // namespace

TEST(AabbChunkPrologue, TheDbvtBoxLoopPreparesEveryObjectOnceChunkByChunkBeforeItsBoxes)
{
	for (int threads = 2; threads <= 3; ++threads)
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		if (btGetTaskScheduler()->getNumThreads() < 2) GTEST_SKIP() << "a library without threads";
		Scene scene(400);
		scene.shuffleTwice();
		LiftingPrologue prologue(scene.world);
		caliber::setAabbChunkPrologue(&scene.world, &prologue);
		scene.world.updateAabbs();
		EXPECT_TRUE(caliber::takeAabbChunkPrologueDone(&scene.world));
		expectEachObjectOnce(prologue, 400);
		EXPECT_EQ(prologue.allCalls(), 0);
		EXPECT_GE(prologue.chunkCalls(), 2) << "the work was not cut into chunks";
		EXPECT_TRUE(scene.boxesFollowTheObjects());
		// Taken once: the next update does nothing of it.
		scene.world.updateAabbs();
		expectEachObjectOnce(prologue, 400);
	}
}

TEST(AabbChunkPrologue, UsersSchedulersThatSplitOrOrderLoopsTheirOwnWayStillPrepareEveryObjectOnce)
{
	caliber_test::UnevenSplitScheduler uneven;
	caliber_test::LastFirstScheduler lastFirst;
	btITaskScheduler* schedulers[] = {&uneven, &lastFirst};
	for (btITaskScheduler* user : schedulers)
	{
		btSetTaskScheduler(user);
		{
			Scene scene(400);
			scene.shuffleTwice();
			LiftingPrologue prologue(scene.world);
			caliber::setAabbChunkPrologue(&scene.world, &prologue);
			scene.world.updateAabbs();
			EXPECT_TRUE(caliber::takeAabbChunkPrologueDone(&scene.world));
			expectEachObjectOnce(prologue, 400);
			EXPECT_EQ(prologue.allCalls(), 0);
			EXPECT_TRUE(scene.boxesFollowTheObjects());
		}
		btSetTaskScheduler(0);
	}
}

TEST(AabbChunkPrologue, PathsWithoutChunksPrepareEverythingFirst)
{
	struct Case
	{
		int threads, objects;
		bool simple;
	} cases[] = {{0, 400, false}, {1, 400, false}, {2, 100, false}, {2, 400, true}};
	for (const Case& c : cases)
	{
		caliber_test::ScopedTaskScheduler scheduler(c.threads);
		Scene scene(c.objects, c.simple);
		LiftingPrologue prologue(scene.world);
		caliber::setAabbChunkPrologue(&scene.world, &prologue);
		scene.world.updateAabbs();
		EXPECT_TRUE(caliber::takeAabbChunkPrologueDone(&scene.world));
		EXPECT_EQ(prologue.allCalls(), 1);
		EXPECT_EQ(prologue.chunkCalls(), 0);
		expectEachObjectOnce(prologue, c.objects);
		EXPECT_TRUE(scene.boxesFollowTheObjects());
	}
}

TEST(AabbChunkPrologue, WithFewTreeMovesTheBoxLoopLeavesThePrologueToItsOwnLoopFirst)
{
	// The dbvt box loop with threads, but the leaves did not move in the last steps (a first update, or
	// boxes that stayed in their fat boxes): the boxes' side is the loop's longer one, so the prologue is
	// not added to it. The leaves re-inserted once, two steps ago and not since, still count; three steps
	// ago no longer do.
	for (int threads = 2; threads <= 3; ++threads)
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		if (btGetTaskScheduler()->getNumThreads() < 2) GTEST_SKIP() << "a library without threads";
		Scene scene(400);
		for (int step = 0; step < 5; ++step)
		{
			// Before step 1: two updates that re-insert every leaf.
			if (step == 1) scene.shuffleTwice();
			LiftingPrologue prologue(scene.world, 0);  // a quiet update: no box leaves its fat box
			caliber::setAabbChunkPrologue(&scene.world, &prologue);
			scene.world.updateAabbs();
			EXPECT_TRUE(caliber::takeAabbChunkPrologueDone(&scene.world));
			expectEachObjectOnce(prologue, 400);
			EXPECT_TRUE(scene.boxesFollowTheObjects());
			// Step 0: nothing moved before. Step 1 follows two re-inserting updates (shuffleTwice), step 2 one
			// of them and a quiet one; step 3 and 4: two quiet updates.
			const bool handedOver = step == 1 || step == 2;
			EXPECT_EQ(prologue.allCalls(), handedOver ? 0 : 1) << "step " << step << ", " << threads << " threads";
			EXPECT_EQ(prologue.chunkCalls() > 0, handedOver) << "step " << step << ", " << threads << " threads";
		}
	}
}

TEST(AabbChunkPrologue, APrologueForgottenOrSetForAnotherWorldIsNotDone)
{
	caliber_test::ScopedTaskScheduler scheduler(2);
	Scene first(400), second(300);
	LiftingPrologue prologue(first.world);
	// Set for the first world: the second world's update leaves it alone.
	caliber::setAabbChunkPrologue(&first.world, &prologue);
	second.world.updateAabbs();
	EXPECT_FALSE(caliber::takeAabbChunkPrologueDone(&second.world));
	// The check above cleared it (takeAabbChunkPrologueDone forgets what was set either way).
	first.world.updateAabbs();
	EXPECT_FALSE(caliber::takeAabbChunkPrologueDone(&first.world));
	// Set, then forgotten with null.
	caliber::setAabbChunkPrologue(&first.world, &prologue);
	caliber::setAabbChunkPrologue(&first.world, 0);
	first.world.updateAabbs();
	EXPECT_FALSE(caliber::takeAabbChunkPrologueDone(&first.world));
	EXPECT_EQ(prologue.allCalls() + prologue.chunkCalls(), 0);
	for (int i = 0; i < 400; ++i) EXPECT_EQ(prologue.count(i), 0);
}
