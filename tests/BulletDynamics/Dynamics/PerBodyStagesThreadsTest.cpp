// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The per-body stages that run on the task scheduler's threads (sleeping bookkeeping, the finiteness
// check of the quarantine, the motion states' poses) give the same bits as without a scheduler, at
// any thread count, in worlds with enough bodies that each loop is cut into several tasks.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "DynamicsWorldTestUtil.h"
#include "TestThreadsUtil.h"
#include "LinearMath/btThreads.h"

using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
// What one body ends a run with: its pose and velocities, its sleeping state and timer, and the pose its
// motion state was told (bit for bit).
struct BodyRecord
{
	btScalar values[12 + 6 + 1 + 12];
	int activationState;
};

bool operator==(const BodyRecord& a, const BodyRecord& b)
{
	return std::memcmp(a.values, b.values, sizeof(a.values)) == 0 && a.activationState == b.activationState;
}

void copyTransform(const btTransform& t, btScalar* out)
{
	for (int r = 0; r < 3; ++r)
		for (int c = 0; c < 3; ++c) out[r * 3 + c] = t.getBasis()[r][c];
	for (int k = 0; k < 3; ++k) out[9 + k] = t.getOrigin()[k];
}

std::vector<BodyRecord> record(const TestWorld& w)
{
	std::vector<BodyRecord> records;
	for (const btRigidBody* body : w.bodies())
	{
		BodyRecord r;
		std::memset(&r, 0, sizeof(r));
		copyTransform(body->getWorldTransform(), r.values);
		for (int k = 0; k < 3; ++k)
		{
			r.values[12 + k] = body->getLinearVelocity()[k];
			r.values[15 + k] = body->getAngularVelocity()[k];
		}
		r.values[18] = body->getDeactivationTime();
		btTransform shown;
		shown.setIdentity();
		if (body->getMotionState()) body->getMotionState()->getWorldTransform(shown);
		copyTransform(shown, r.values + 19);
		r.activationState = body->getActivationState();
		records.push_back(r);
	}
	return records;
}

// Rows of boxes and spheres resting apart on the ground (one island each), every fifth without a motion
// state, and every seventh thrown sideways so that it keeps moving for a while.
void buildRestingRows(TestWorld& w)
{
	w.addGround();
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
	btCollisionShape* sphere = w.shape<btSphereShape>(btScalar(0.4));
	for (int i = 0; i < 300; ++i)
	{
		const btVector3 at(btScalar(i % 20) * 2 - 20, btScalar(0.45), btScalar(i / 20) * 2 - 15);
		btRigidBody* body = w.addBody(i % 3 ? box : sphere, 1, at, i % 5 != 0);
		if (i % 7 == 0) body->setLinearVelocity(btVector3(btScalar(3), 0, btScalar(1)));
	}
}

std::vector<BodyRecord> runRestingRows(btITaskScheduler* scheduler, int threads, int steps)
{
	btSetTaskScheduler(scheduler);
	if (scheduler) scheduler->setNumThreads(threads);
	TestWorld w;
	buildRestingRows(w);
	w.run(steps);
	std::vector<BodyRecord> result = record(w);
	btSetTaskScheduler(0);
	return result;
}
}  // namespace

TEST(PerBodyStagesThreads, SleepingAndMotionStatesAreTheSameAtAnyThreadCount)
{
	// 150 steps of 1/60 s: more than the 2 s a resting body waits before it may sleep (gDeactivationTime),
	// not enough for the thrown bodies to stop, so some islands sleep and some are awake.
	const int steps = 150;
	const std::vector<BodyRecord> reference = runRestingRows(0, 1, steps);
	int sleeping = 0, awake = 0;
	for (const BodyRecord& r : reference)
	{
		if (r.activationState == ISLAND_SLEEPING) ++sleeping;
		if (r.activationState == ACTIVE_TAG) ++awake;
	}
	ASSERT_GT(sleeping, 100) << "the scene must put islands to sleep for the test to check sleeping";
	ASSERT_GT(awake, 0) << "and keep some awake";
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	if (!pool) GTEST_SKIP() << "a library without threads";
	for (int threads : {1, 2, 3})
	{
		const std::vector<BodyRecord> run = runRestingRows(pool.get(), threads, steps);
		ASSERT_EQ(run.size(), reference.size());
		for (size_t i = 0; i < run.size(); ++i)
			EXPECT_TRUE(run[i] == reference[i]) << "body " << i << " at " << threads << " threads";
	}
}

// As the mesh scenes of the benchmark: bodies falling apart from each other, so that most leave their fat
// boxes every other step and their leaves are re-inserted (the tree moves run on one task while the other
// threads compute the boxes after them, btCollisionWorld::updateAabbs); three layers, so that the lower
// ones land and the upper ones land on them. Plain and Mt world, no scheduler, the pool at 1, 2 and 3
// threads and a scheduler that cuts the loops unevenly: the same bits.
TEST(PerBodyStagesThreads, FallingBodiesLeavingTheirFatBoxesEndTheSameAtAnyThreadCount)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	caliber_test::UnevenSplitScheduler uneven;
	for (bool multithreaded : {false, true})
	{
		std::vector<std::vector<BodyRecord>> runs;
		for (int threads : {0, 1, 2, 3, -1})  // 0: no scheduler; -1: the uneven scheduler
		{
			if (threads > 0 && !pool) continue;
			btITaskScheduler* scheduler = threads > 0 ? pool.get() : (threads < 0 ? &uneven : 0);
			btSetTaskScheduler(scheduler);
			if (threads > 0) pool->setNumThreads(threads);
			std::unique_ptr<TestWorld> w(multithreaded ? new TestWorld(TestWorld::Multithreaded(), BT_MAX_THREAD_COUNT)
			                                           : new TestWorld());
			w->addGround();
			btCollisionShape* shapes[3] = {
			    w->shape<btBoxShape>(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4))),
			    w->shape<btSphereShape>(btScalar(0.4)), w->shape<btCapsuleShape>(btScalar(0.3), btScalar(0.5))};
			for (int i = 0; i < 300; ++i)
			{
				const int layer = i / 100, k = i % 100;
				const btVector3 at(btScalar(k % 10) * 3 - 15 + btScalar(0.1) * layer, btScalar(2 + 2 * layer),
				                   btScalar(k / 10) * 3 - 15);
				w->addBody(shapes[(i * 7) % 3], 1, at, i % 4 != 0);
			}
			unsigned moved = 0;
			for (int step = 0; step < 90; ++step)
			{
				w->run(1);
				moved += static_cast<btDbvtBroadphase*>(w->world()->getBroadphase())->m_updates_ratio > btScalar(0.3);
			}
			EXPECT_GT(moved, 20u) << "the bodies must leave their fat boxes in many steps for the test to check them";
			runs.push_back(record(*w));
			w.reset();
			btSetTaskScheduler(0);
		}
		for (size_t r = 1; r < runs.size(); ++r)
		{
			ASSERT_EQ(runs[r].size(), runs[0].size());
			for (size_t i = 0; i < runs[0].size(); ++i)
				EXPECT_TRUE(runs[r][i] == runs[0][i]) << "body " << i << ", run " << r << ", Mt world " << multithreaded;
		}
	}
}

TEST(PerBodyStagesThreads, NonFiniteBodyIsQuarantinedTheSameAtAnyThreadCount)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	std::vector<std::vector<BodyRecord>> runs;
	for (int threads : {0, 1, 2, 3})  // 0: no scheduler
	{
		if (threads > 0 && !pool) break;
		WarningCounter warnings;
		btSetTaskScheduler(threads > 0 ? pool.get() : 0);
		if (threads > 0) pool->setNumThreads(threads);
		TestWorld w;
		buildRestingRows(w);
		w.run(5);
		// One body's state goes bad behind the API's back, in a late task of the per-body loops.
		btRigidBody* bad = w.bodies()[250];
		bad->getWorldTransform().getOrigin().setY(std::numeric_limits<btScalar>::quiet_NaN());
		w.run(20);
		btSetTaskScheduler(0);
		EXPECT_EQ(bad->getActivationState(), DISABLE_SIMULATION) << threads << " threads";
		EXPECT_EQ(bad->getBroadphaseHandle(), nullptr) << "it left the broadphase";
		EXPECT_EQ(warnings.count(), 1) << "one warning per world";
		runs.push_back(record(w));
	}
	for (size_t run = 1; run < runs.size(); ++run)
	{
		ASSERT_EQ(runs[run].size(), runs[0].size());
		for (size_t i = 0; i < runs[0].size(); ++i)
			EXPECT_TRUE(runs[run][i] == runs[0][i]) << "body " << i << ", run " << run;
	}
}
