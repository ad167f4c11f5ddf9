// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The per-body stages that run on the task scheduler's threads (sleeping bookkeeping, the finiteness
// check of the quarantine, the motion states' poses) give the same bits as without a scheduler, at
// any thread count, in worlds with enough bodies that each loop is cut into several tasks.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "DynamicsWorldTestUtil.h"
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
