// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The island stage's shortcuts for lone bodies (one body, no manifold): the island manager hands runs of
// them to the worlds' callback at once, and decides a lone body's sleep in one pass. These tests check
// that the shortcuts keep the general path's batches and the general path's deactivation timing.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "BulletDynamics/Dynamics/btInplaceSolverIslandCallback.h"
#include "DynamicsWorldTestUtil.h"
#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "../ConstraintSolver/MtSolverTestUtil.h"
#include "TestThreadsUtil.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// The first step (1-based) after which body is ISLAND_SLEEPING, or 0 if it never is within maxSteps.
struct SleepSteps
{
	int lone = 0, jointed = 0, jointedPartner = 0;
	bool neverSleepingStayedAwake = true;
};

SleepSteps stepUntilAsleep(caliber_test::TestWorld& world, int maxSteps)
{
	btSphereShape* shape = world.shape<btSphereShape>(btScalar(0.5));
	// No gravity, no velocity: every body rests, so each sleeps once its resting time passes
	// gDeactivationTime, whatever island it is in.
	btRigidBody* lone = world.addBody(shape, 1, btVector3(0, 10, 0));
	btRigidBody* a = world.addBody(shape, 1, btVector3(10, 10, 0));
	btRigidBody* b = world.addBody(shape, 1, btVector3(12, 10, 0));
	world.addJoint<btPoint2PointConstraint>(true, *a, *b, btVector3(1, 0, 0), btVector3(-1, 0, 0));
	btRigidBody* awake = world.addBody(shape, 1, btVector3(-10, 10, 0));
	awake->setActivationState(DISABLE_DEACTIVATION);
	SleepSteps steps;
	for (int step = 1; step <= maxSteps; ++step)
	{
		world.run(1);
		if (!steps.lone && lone->getActivationState() == ISLAND_SLEEPING) steps.lone = step;
		if (!steps.jointed && a->getActivationState() == ISLAND_SLEEPING) steps.jointed = step;
		if (!steps.jointedPartner && b->getActivationState() == ISLAND_SLEEPING) steps.jointedPartner = step;
		if (awake->getActivationState() != DISABLE_DEACTIVATION) steps.neverSleepingStayedAwake = false;
	}
	return steps;
}

void expectLoneBodySleepsLikeAJointedOne(const SleepSteps& steps)
{
	// gDeactivationTime is 2 s: at 60 steps a second a resting body wants to sleep after about 120 steps
	// and its island sleeps at the next island stage; 110..135 leaves room for the float sum of 1/60.
	EXPECT_GE(steps.jointed, 110);
	EXPECT_LE(steps.jointed, 135);
	EXPECT_EQ(steps.jointedPartner, steps.jointed) << "an island sleeps as a whole";
	EXPECT_EQ(steps.lone, steps.jointed) << "a lone body (the one-pass decision) sleeps on the general path's step";
	EXPECT_TRUE(steps.neverSleepingStayedAwake);
}
}  // namespace

TEST(IslandStage, LoneBodySleepsOnTheStepOfABodyInAJointedIslandPlainWorld)
{
	caliber_test::TestWorld world(btVector3(0, 0, 0));
	expectLoneBodySleepsLikeAJointedOne(stepUntilAsleep(world, 200));
}

TEST(IslandStage, LoneBodySleepsOnTheStepOfABodyInAJointedIslandMtWorld)
{
	caliber_test::TestWorld world(caliber_test::TestWorld::Multithreaded(), 4, btVector3(0, 0, 0));
	expectLoneBodySleepsLikeAJointedOne(stepUntilAsleep(world, 200));
}

// The worlds' callback gathers runs of lone islands into the batches that one processIsland call per island
// gives: same bodies and joints in the same order, cut at the same places, for several batch sizes, with a
// lone island that has a joint (to the fixed body) among them.
TEST(IslandStage, LoneIslandRunsGiveTheBatchesOfOneCallPerIsland)
{
	const int numIslands = 8;
	btSphereShape shape(btScalar(0.5));
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	for (int i = 0; i < numIslands; ++i)
		bodies.emplace_back(
		    new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(1, 0, &shape, btVector3(1, 1, 1))));
	btPoint2PointConstraint joint(*bodies[3], btVector3(0, 1, 0));
	btTypedConstraint* sortedJoints[1] = {&joint};
	const int jointStart[numIslands + 1] = {0, 0, 0, 0, 1, 1, 1, 1, 1};  // island 3 has the joint
	btCollisionObject* objects[numIslands];
	int ids[numIslands];
	for (int i = 0; i < numIslands; ++i)
	{
		objects[i] = bodies[i].get();
		ids[i] = i;
	}

	const int noJointStart[1] = {0};
	for (int batchSize : {1, 3, 5, 128})
	{
		for (bool withJoint : {true, false})
		{
			btContactSolverInfo info;
			info.m_minimumSolverBatchSize = batchSize;
			InplaceSolverIslandCallback perIsland(0, 0), runs(0, 0);
			for (InplaceSolverIslandCallback* callback : {&perIsland, &runs})
			{
				callback->setup(&info, 0);
				if (withJoint)
					callback->setConstraints(sortedJoints, 1, jointStart, numIslands);
				else
					callback->setConstraints(0, 0, noJointStart, 0);  // as the world passes a step without joints
			}
			for (int i = 0; i < numIslands; ++i) perIsland.processIsland(&objects[i], 1, 0, 0, i);
			runs.processLoneIslands(objects, ids, 4);  // two runs, cut inside a batch
			runs.processLoneIslands(objects + 4, ids + 4, numIslands - 4);
			perIsland.flush();
			runs.flush();

			SCOPED_TRACE(testing::Message() << "batch size " << batchSize << (withJoint ? ", a joint" : ", no joint"));
			ASSERT_EQ(runs.numBatches(), perIsland.numBatches());
			for (int b = 0; b < perIsland.numBatches(); ++b)
			{
				const InplaceSolverIslandCallback::Batch& x = perIsland.m_batches[b];
				const InplaceSolverIslandCallback::Batch& y = runs.m_batches[b];
				EXPECT_EQ(y.firstBody, x.firstBody);
				EXPECT_EQ(y.numBodies, x.numBodies);
				EXPECT_EQ(y.firstConstraint, x.firstConstraint);
				EXPECT_EQ(y.numConstraints, x.numConstraints);
				EXPECT_EQ(y.numManifolds, 0);
				EXPECT_EQ(x.numManifolds, 0);
			}
			ASSERT_EQ(runs.m_bodies.size(), numIslands);
			for (int i = 0; i < numIslands; ++i) EXPECT_EQ(runs.m_bodies[i], perIsland.m_bodies[i]);
			ASSERT_EQ(runs.m_gatheredConstraints.size(), withJoint ? 1 : 0);
			if (withJoint)
			{
				EXPECT_EQ(runs.m_gatheredConstraints[0], &joint);
			}
		}
	}
	// With batches of 3 items (bodies and joints): {0,1,2}, {3, its joint, 4}, {5,6,7}.
	btContactSolverInfo info;
	info.m_minimumSolverBatchSize = 3;
	InplaceSolverIslandCallback runs(0, 0);
	runs.setup(&info, 0);
	runs.setConstraints(sortedJoints, 1, jointStart, numIslands);
	runs.processLoneIslands(objects, ids, numIslands);
	runs.flush();
	ASSERT_EQ(runs.numBatches(), 3);
	EXPECT_EQ(runs.m_batches[0].numBodies, 3);
	EXPECT_EQ(runs.m_batches[1].numBodies, 2);
	EXPECT_EQ(runs.m_batches[1].numConstraints, 1);
	EXPECT_EQ(runs.m_batches[2].numBodies, 3);
}

namespace
{
// Records, per solveGroup call, its first body and whether it ran inside a parallel loop on several threads.
struct RecordingSolver : public btConstraintSolver
{
	std::mutex mutex;
	std::vector<std::pair<const btCollisionObject*, bool>> calls;
	btScalar solveGroup(btCollisionObject** bodies, int numBodies, btPersistentManifold**, int, btTypedConstraint**, int,
	                    const btContactSolverInfo&, btIDebugDraw*, btDispatcher*) override
	{
		std::lock_guard<std::mutex> lock(mutex);
		calls.push_back(std::make_pair(numBodies ? bodies[0] : nullptr, btThreadsAreRunning()));
		return 0;
	}
	void reset() override {}
	btConstraintSolverType getSolverType() const override { return BT_SEQUENTIAL_IMPULSE_SOLVER; }
};
}  // namespace

// The batches that touch a kinematic body (through a joint, a manifold or as one of their bodies) are found on
// the threads when the batches are solved in parallel, and solved one after another on the calling thread,
// outside the parallel loop; every batch is solved once.
TEST(IslandStage, BatchesTouchingAKinematicBodyAreFoundOnTheThreadsAndSolvedAlone)
{
	caliber_test::ScopedTaskScheduler threads(2);
	btSphereShape shape(btScalar(0.5));
	const int numBodies = 40;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	for (int i = 0; i < numBodies; ++i)
		bodies.emplace_back(new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(1, 0, &shape, btVector3(1, 1, 1))));
	btRigidBody kinematic(btRigidBody::btRigidBodyConstructionInfo(0, 0, &shape));
	kinematic.setCollisionFlags(kinematic.getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
	// Island 5: a joint to the kinematic body; island 17: a manifold with it (as body 0); island 30: the
	// kinematic body among the island's bodies (as a caller that hands every object at once would).
	btPoint2PointConstraint joint(*bodies[5], kinematic, btVector3(0, 1, 0), btVector3(0, -1, 0));
	btTypedConstraint* sortedJoints[1] = {&joint};
	std::vector<int> jointStart(numBodies + 1, 0);
	for (int i = 6; i <= numBodies; ++i) jointStart[i] = 1;
	btPersistentManifold manifold(&kinematic, bodies[17].get(), 0, btScalar(0.02), btScalar(0.02));
	btPersistentManifold* manifolds[1] = {&manifold};

	RecordingSolver solver;
	btContactSolverInfo info;
	info.m_minimumSolverBatchSize = 1;  // every island a batch
	InplaceSolverIslandCallback callback(&solver, 0);
	callback.setup(&info, 0);
	callback.setConstraints(sortedJoints, 1, &jointStart[0], numBodies);
	for (int i = 0; i < numBodies; ++i)
	{
		btCollisionObject* island[2] = {bodies[i].get(), &kinematic};
		callback.processIsland(island, i == 30 ? 2 : 1, i == 17 ? manifolds : 0, i == 17 ? 1 : 0, i);
	}
	callback.solveBatches(true, 1);
	ASSERT_EQ(callback.numBatches(), numBodies);
	ASSERT_EQ(solver.calls.size(), size_t(numBodies));
	for (int b = 0; b < numBodies; ++b)
		EXPECT_EQ(callback.m_batches[b].touchesKinematic, b == 5 || b == 17 || b == 30) << "batch " << b;
	std::vector<int> solved(numBodies, 0);
	for (const std::pair<const btCollisionObject*, bool>& call : solver.calls)
	{
		int b = 0;
		while (b < numBodies && bodies[b].get() != call.first) ++b;
		ASSERT_LT(b, numBodies);
		++solved[b];
		if (b == 5 || b == 17 || b == 30)
		{
			EXPECT_FALSE(call.second) << "batch " << b << " solved beside others";
		}
	}
	for (int b = 0; b < numBodies; ++b) EXPECT_EQ(solved[b], 1) << "batch " << b;
}

namespace
{
// Records, per solveGroup call, its first body and whether it ran as a task of a parallel loop (also when
// the scheduler runs the loop on one thread).
struct TaskRecordingSolver : public btConstraintSolver
{
	std::mutex mutex;
	std::vector<std::pair<const btCollisionObject*, bool>> calls;
	btScalar solveGroup(btCollisionObject** bodies, int numBodies, btPersistentManifold**, int, btTypedConstraint**,
	                    int, const btContactSolverInfo&, btIDebugDraw*, btDispatcher*) override
	{
		std::lock_guard<std::mutex> lock(mutex);
		calls.push_back(std::make_pair(numBodies ? bodies[0] : nullptr, caliber::insideParallelBody()));
		return 0;
	}
	void reset() override {}
	btConstraintSolverType getSolverType() const override { return BT_SEQUENTIAL_IMPULSE_SOLVER; }
};

// Islands of one body and some manifolds for the island callback, and the solver that records its calls.
struct LargeAndSmallBatches
{
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	std::vector<std::unique_ptr<btPersistentManifold>> manifolds;
	btSphereShape shape{btScalar(0.5)};
	TaskRecordingSolver solver;
	btContactSolverInfo info;

	btRigidBody* body()
	{
		bodies.emplace_back(
		    new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(1, 0, &shape, btVector3(1, 1, 1))));
		return bodies.back().get();
	}
	// An island of one body and numManifolds manifolds (with a partner body of its own: the callback only
	// counts manifolds and reads their bodies' kinds).
	void addIsland(InplaceSolverIslandCallback& callback, int numManifolds, int islandId)
	{
		btCollisionObject* island[1] = {body()};
		btRigidBody* partner = body();
		std::vector<btPersistentManifold*> list;
		for (int m = 0; m < numManifolds; ++m)
		{
			manifolds.emplace_back(new btPersistentManifold(island[0], partner, 0, btScalar(0.02), btScalar(0.02)));
			list.push_back(manifolds.back().get());
		}
		callback.processIsland(island, 1, numManifolds ? &list[0] : 0, numManifolds, islandId);
	}
	// Where the batch starting with body was solved: its index in the calls (-1 if not solved exactly once)
	// and whether beside other batches.
	int callOf(const btCollisionObject* first, bool& besideOthers)
	{
		int found = -1;
		for (size_t c = 0; c < solver.calls.size(); ++c)
			if (solver.calls[c].first == first)
			{
				if (found >= 0) return -1;
				found = int(c);
				besideOthers = solver.calls[c].second;
			}
		return found;
	}
};
}  // namespace

// In a parallel solve, the large batches (those the Mt solver colours and spreads over the threads itself)
// that add up, cheapest first, to no more than the small batches' cost (bodies, and 8 per manifold and per
// joint) are solved whole as one item of the parallel loop, beside the small batches; the others are spread
// one after another before the loop. Every batch is solved once.
TEST(IslandStage, CheapLargeBatchesAreSolvedWholeBesideTheSmallBatchesAndTheOthersSpreadBefore)
{
	caliber_test::ScopedTaskScheduler threads(2);
	for (bool withSmall : {true, false})
	{
		SCOPED_TRACE(withSmall ? "small batches" : "no small batch");
		LargeAndSmallBatches scene;
		scene.info.m_minimumSolverBatchSize = 1;  // every island a batch
		InplaceSolverIslandCallback callback(&scene.solver, 0);
		callback.setup(&scene.info, 0);
		callback.m_largeBatchSolver = &scene.solver;
		callback.m_largeBatchManifolds = 3;
		const int noJointStart[1] = {0};
		callback.setConstraints(0, 0, noJointStart, 0);
		// Large: 10 manifolds (cost 81), 3 manifolds (cost 25), 4 manifolds (cost 33); small: ten islands of
		// one manifold (cost 9 each, 90 in all). Cheapest first: 25, then 25 + 33 = 58, then 58 + 81 = 139 > 90.
		int island = 0;
		scene.addIsland(callback, 10, island++);
		const btCollisionObject* expensive = scene.bodies[0].get();
		scene.addIsland(callback, 3, island++);
		const btCollisionObject* cheapest = scene.bodies[2].get();
		if (withSmall)
			for (int i = 0; i < 10; ++i) scene.addIsland(callback, 1, island++);
		scene.addIsland(callback, 4, island++);
		const btCollisionObject* cheap = scene.bodies[scene.bodies.size() - 2].get();
		callback.solveBatches(true, 1);
		ASSERT_EQ(callback.numBatches(), island);
		ASSERT_EQ(scene.solver.calls.size(), size_t(island));
		bool beside = true;
		EXPECT_EQ(scene.callOf(expensive, beside), 0) << "spread first";
		EXPECT_FALSE(beside);
		if (withSmall)
		{
			EXPECT_GT(scene.callOf(cheapest, beside), 0);
			EXPECT_TRUE(beside) << "the cheapest large batch is solved in the loop";
			EXPECT_GT(scene.callOf(cheap, beside), 0);
			EXPECT_TRUE(beside) << "the next cheapest fits too";
			for (int i = 0; i < 10; ++i)
			{
				EXPECT_GT(scene.callOf(scene.bodies[4 + 2 * i].get(), beside), 0) << "small batch " << i;
				EXPECT_TRUE(beside) << "small batch " << i;
			}
		}
		else
		{
			// Nothing to solve beside them: every large batch spread, in batch order.
			EXPECT_EQ(scene.callOf(cheapest, beside), 1);
			EXPECT_FALSE(beside);
			EXPECT_EQ(scene.callOf(cheap, beside), 2);
			EXPECT_FALSE(beside);
		}
	}
}

// A world with a coloured island (the Mt solver's threshold lowered to 40 manifolds) and many small
// islands whose cost outweighs it, so that at two and three threads the coloured island is solved whole in a
// task of the island loop (its own loops then run on that thread) beside the small batches: every body ends
// with the bits of no scheduler and of one thread.
TEST(IslandStage, AColouredIslandSolvedBesideTheSmallBatchesEndsTheSameAtAnyThreadCount)
{
	caliber_test::ScopedManifoldBatchingThreshold colourFrom(40);
	std::vector<std::vector<btScalar>> results;
	for (int threads : {0, 1, 2, 3})
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		caliber_test::TestWorld world(caliber_test::TestWorld::Multithreaded(), BT_MAX_THREAD_COUNT);
		world.addGround();
		// Small batches of two columns (8 bodies and manifolds), below the colouring threshold (a batch of
		// 128 items, 32 columns, would hold 64 manifolds and be coloured too).
		world.world()->getSolverInfo().m_minimumSolverBatchSize = 8;
		btBoxShape* box = world.shape<btBoxShape>(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
		// A block of 4 x 4 x 3 touching boxes (one island: 16 ground manifolds, 32 between layers, 72 between
		// side neighbours and the pairs whose fat boxes merely overlap, at most 48 x 26 / 2 = 624) and 300
		// columns of two boxes well apart (each its own island of two manifolds). The small batches cost
		// 300 x 18 = 5400, more than the block's at most 8 x 624 + 48 = 5040, so at two threads the block is
		// solved beside them (at three, when it has at most 331 manifolds).
		for (int y = 0; y < 3; ++y)
			for (int x = 0; x < 4; ++x)
				for (int z = 0; z < 4; ++z)
					world.addBody(box, 1,
					              btVector3(btScalar(x) * btScalar(1.0), btScalar(0.5) + btScalar(y), btScalar(z)));
		for (int c = 0; c < 300; ++c)
			for (int y = 0; y < 2; ++y)
				world.addBody(
				    box, 1,
				    btVector3(btScalar(10 + 3 * (c % 20)), btScalar(0.5) + btScalar(y), btScalar(10 + 3 * (c / 20))));
		world.run(20);
		results.push_back(caliber_test::bodyStateBits(world.bodies()));
	}
	for (size_t r = 1; r < results.size(); ++r)
	{
		ASSERT_EQ(results[r].size(), results[0].size());
		EXPECT_EQ(memcmp(&results[r][0], &results[0][0], results[0].size() * sizeof(btScalar)), 0) << "run " << r;
	}
}
