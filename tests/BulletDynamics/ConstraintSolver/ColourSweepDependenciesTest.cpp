// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The Mt solver's coloured sweep without a wait per colour: each batch's dependencies are the batches a
// brute-force search of the sweep's order finds, and a world solved with it has, bit for bit, the states of
// the sweep with a wait at the end of every colour, at any thread count and with schedulers that run a
// loop's tasks one after another (backwards, or all in one call) without deadlock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <set>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btBatchDependencies.h"
#include "BulletDynamics/ConstraintSolver/btBatchedConstraints.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "LinearMath/btThreads.h"
#include "MtSolverTestUtil.h"
#include "TestThreadsUtil.h"
#include "btBulletDynamicsCommon.h"

namespace
{
using caliber::BatchDependencies;

// A random coloured island: manifolds between random bodies (body 0 is the fixed entry), coloured greedily
// (no moving body twice in a colour), each colour cut into batches of random sizes.
struct ColouredIsland
{
	std::vector<int> ends;           // two bodies per manifold
	std::vector<int> order;          // the manifolds colour by colour
	std::vector<int> manifoldBegin;  // per batch (and one past the last), in order
	std::vector<int> batchColour;
	int numBodies = 0;

	ColouredIsland(unsigned seed, int bodies, int manifolds)
	{
		std::mt19937 random(seed);
		numBodies = bodies;
		std::vector<int> colour(manifolds);
		std::vector<std::set<int>> taken;  // per colour, its moving bodies
		for (int m = 0; m < manifolds; ++m)
		{
			const int a = int(random() % unsigned(bodies));
			int b = int(random() % unsigned(bodies - 1)) + 1;
			if (b == a) b = (b % (bodies - 1)) + 1;
			ends.push_back(a);
			ends.push_back(b);
			int c = 0;
			while (c < int(taken.size()) && (taken[c].count(a) || taken[c].count(b))) ++c;
			if (c == int(taken.size())) taken.emplace_back();
			if (a != 0) taken[c].insert(a);
			taken[c].insert(b);
			colour[m] = c;
		}
		for (int c = 0; c < int(taken.size()); ++c)
		{
			std::vector<int> inColour;
			for (int m = 0; m < manifolds; ++m)
				if (colour[m] == c) inColour.push_back(m);
			std::shuffle(inColour.begin(), inColour.end(), random);
			for (size_t k = 0; k < inColour.size();)
			{
				manifoldBegin.push_back(int(order.size()));
				batchColour.push_back(c);
				const size_t size = 1 + random() % 4;
				for (size_t n = 0; n < size && k < inColour.size(); ++n, ++k) order.push_back(inColour[k]);
			}
		}
		manifoldBegin.push_back(int(order.size()));
	}
	int numBatches() const { return int(batchColour.size()); }
	std::set<int> movingBodies(int batch) const
	{
		std::set<int> bodies;
		for (int p = manifoldBegin[batch]; p < manifoldBegin[batch + 1]; ++p)
			for (int side = 0; side < 2; ++side)
				if (ends[2 * order[p] + side] != 0) bodies.insert(ends[2 * order[p] + side]);
		return bodies;
	}
};

// The items of a sweep in its order: the normal pass over the colours (forwards or backwards), then the
// friction pass; an item is pass * numBatches + batch.
std::vector<int> sweepOrder(const ColouredIsland& island, bool backward)
{
	std::vector<int> items;
	const int numColours = island.batchColour.empty() ? 0 : island.batchColour.back() + 1;
	for (int pass = 0; pass < 2; ++pass)
		for (int k = 0; k < numColours; ++k)
		{
			const int c = backward ? numColours - 1 - k : k;
			for (int b = 0; b < island.numBatches(); ++b)
				if (island.batchColour[b] == c) items.push_back(pass * island.numBatches() + b);
		}
	return items;
}
}  // namespace

TEST(BatchDependencies, EveryBatchWaitsForTheLastEarlierBatchOfEachOfItsBodiesAsABruteForceSearchFinds)
{
	caliber_test::ScopedTaskScheduler scheduler(2);
	for (unsigned seed = 1; seed <= 20; ++seed)
	{
		const ColouredIsland island(seed, 4 + int(seed % 13), 10 + int(seed * 7 % 60));
		BatchDependencies dependencies;
		dependencies.build(island.manifoldBegin.data(), island.numBatches(), island.order.data(), island.ends.data(), 2,
		                   island.numBodies, 0);
		const int numBatches = island.numBatches();
		for (int s = 0; s < BatchDependencies::kNumSweeps; ++s)
		{
			const bool backward = s >= BatchDependencies::kBackwardNormal;
			const int pass = s % 2;
			const std::vector<int> items = sweepOrder(island, backward);
			for (size_t i = 0; i < items.size(); ++i)
			{
				if (items[i] / numBatches != pass) continue;
				const int batch = items[i] % numBatches;
				// Brute force: for each body, the last item before this one in the sweep that touches it.
				std::set<int> expected;
				for (int body : island.movingBodies(batch))
					for (size_t j = i; j-- > 0;)
						if (island.movingBodies(items[j] % numBatches).count(body))
						{
							expected.insert(items[j]);
							break;
						}
				const BatchDependencies::Sweep sweep = BatchDependencies::Sweep(s);
				std::vector<int> listed(dependencies.list(sweep, batch),
				                        dependencies.list(sweep, batch) + dependencies.count(sweep, batch));
				const size_t count = listed.size();
				std::sort(listed.begin(), listed.end());
				EXPECT_EQ(count, std::set<int>(listed.begin(), listed.end()).size()) << "an item listed twice";
				EXPECT_EQ(std::vector<int>(expected.begin(), expected.end()), listed)
				    << "seed " << seed << ", sweep " << s << ", batch " << batch;
			}
		}
	}
}

namespace
{
// A user's scheduler that reports `threads` threads and runs a loop's tasks on the calling thread, one after
// another, the last task first (or, oneCall, the whole range in one call): a task that waited for work of a
// task not yet started would never return.
class OneThreadScheduler : public btITaskScheduler
{
public:
	OneThreadScheduler(int threads, bool oneCall)
	    : btITaskScheduler("OneThread"), m_threads(threads), m_oneCall(oneCall)
	{
	}
	int getMaxNumThreads() const override { return m_threads; }
	int getNumThreads() const override { return m_threads; }
	void setNumThreads(int) override {}
	void parallelFor(int iBegin, int iEnd, int grain, const btIParallelForBody& body) override
	{
		++loops;
		if (m_oneCall || iBegin >= iEnd)
		{
			if (iBegin < iEnd) body.forLoop(iBegin, iEnd);
			return;
		}
		grain = btMax(1, grain);
		const int numTasks = (iEnd - iBegin + grain - 1) / grain;
		for (int t = numTasks - 1; t >= 0; --t) body.forLoop(iBegin + t * grain, btMin(iEnd, iBegin + (t + 1) * grain));
	}
	btScalar parallelSum(int iBegin, int iEnd, int, const btIParallelSumBody& body) override
	{
		return body.sumLoop(iBegin, iEnd);
	}
	int loops = 0;

private:
	int m_threads;
	bool m_oneCall;
};

// Counts the coloured solves and the colours with more than one batch (else the sweeps have little to
// order).
class CountingMtSolver : public btSequentialImpulseConstraintSolverMt
{
public:
	int colouredSolves = 0;
	int coloursOfSeveralBatches = 0;
	// The plain solver's contact rows (the same rows, made on this thread): the Mt set-up then plans the
	// sweep itself after the rows, instead of beside their fill.
	bool plainRows = false;

protected:
	void convertContacts(btPersistentManifold** manifolds, int numManifolds, const btContactSolverInfo& info) override
	{
		if (plainRows)
			btSequentialImpulseConstraintSolver::convertContacts(manifolds, numManifolds, info);
		else
			btSequentialImpulseConstraintSolverMt::convertContacts(manifolds, numManifolds, info);
	}

	btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
	                                      int numManifolds, btTypedConstraint** constraints, int numConstraints,
	                                      const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override
	{
		const btScalar result = btSequentialImpulseConstraintSolverMt::solveGroupCacheFriendlySetup(
		    bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
		if (m_useBatching)
		{
			++colouredSolves;
			for (int p = 0; p < m_batchedContactConstraints.m_phases.size(); ++p)
				if (m_batchedContactConstraints.m_phases[p].end - m_batchedContactConstraints.m_phases[p].begin > 1)
					++coloursOfSeveralBatches;
		}
		return result;
	}
};

// Puts the sweep switch and the Mt solver's batch size back at the end of a scope.
struct ScopedSweepSettings
{
	ScopedSweepSettings(bool barriers, int minBatchSize)
	{
		caliber::setColourSweepBarriers(barriers);
		btSequentialImpulseConstraintSolverMt::s_minBatchSize = minBatchSize;
	}
	~ScopedSweepSettings()
	{
		caliber::setColourSweepBarriers(false);
		btSequentialImpulseConstraintSolverMt::s_minBatchSize = m_minBatchSize;
	}
	int m_minBatchSize = btSequentialImpulseConstraintSolverMt::s_minBatchSize;
};

// A wall of bricks, 3 layers of 6 x 5, each layer offset by half a brick on the last, so that a brick rests
// on two or four below it: stacks whose colours have several batches that share bodies with the colours
// before and after. The layers start 1 cm apart and fall together, with friction and rolling contacts.
// hangBall: a ball hangs 2 m beside a top brick from a point-to-point joint, in the wall's island without a
// contact (a solver body that no batch holds).
std::vector<btScalar> wallBits(bool barriers, btITaskScheduler* scheduler, int steps, int* loops = nullptr,
                               bool plainRows = false, bool hangBall = false)
{
	caliber_test::ScopedManifoldBatchingThreshold colourAll;
	ScopedSweepSettings settings(barriers, 4);  // batches of a few rows: many per colour
	btSetTaskScheduler(scheduler);
	std::vector<btScalar> bits;
	{
		btDefaultCollisionConfiguration config;
		btCollisionDispatcherMt dispatcher(&config, 40);
		btDbvtBroadphase broadphase;
		btConstraintSolverPoolMt pool(BT_MAX_THREAD_COUNT);
		CountingMtSolver solver;
		solver.plainRows = plainRows;
		btDiscreteDynamicsWorldMt world(&dispatcher, &broadphase, &pool, &solver, &config);
		world.setGravity(btVector3(0, -10, 0));
		world.getSolverInfo().m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
		btBoxShape ground(btVector3(40, 1, 40)), brick(btVector3(btScalar(0.5), btScalar(0.25), btScalar(0.5)));
		std::vector<std::unique_ptr<btRigidBody>> bodies;
		auto add = [&](btScalar mass, btCollisionShape* shape, const btVector3& at)
		{
			btVector3 inertia(0, 0, 0);
			if (mass != 0) shape->calculateLocalInertia(mass, inertia);
			btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
			info.m_startWorldTransform.setOrigin(at);
			info.m_friction = btScalar(0.7);
			info.m_rollingFriction = btScalar(0.01);
			bodies.emplace_back(new btRigidBody(info));
			bodies.back()->setActivationState(DISABLE_DEACTIVATION);
			world.addRigidBody(bodies.back().get());
		};
		add(0, &ground, btVector3(0, -1, 0));
		for (int layer = 0; layer < 3; ++layer)
			for (int i = 0; i < 6; ++i)
				for (int j = 0; j < 5; ++j)
				{
					const btScalar offset = (layer % 2) * btScalar(0.5);
					add(1, &brick, btVector3(i + offset, btScalar(0.26) + layer * btScalar(0.51), j + offset));
				}
		btSphereShape ballShape(btScalar(0.2));
		std::unique_ptr<btPoint2PointConstraint> joint;
		if (hangBall)
		{
			btRigidBody* topBrick = bodies.back().get();
			add(1, &ballShape, topBrick->getWorldTransform().getOrigin() + btVector3(2, 0, 0));
			joint.reset(new btPoint2PointConstraint(*topBrick, *bodies.back(), btVector3(2, 0, 0), btVector3(0, 0, 0)));
			world.addConstraint(joint.get());
		}
		const int loopsBefore = loops ? *loops : 0;
		for (int step = 0; step < steps; ++step) world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
		if (loops) *loops -= loopsBefore;
		EXPECT_EQ(solver.colouredSolves, steps);
		EXPECT_GT(solver.coloursOfSeveralBatches, steps);
		bits = caliber_test::bodyStateBits(bodies);
		if (joint) world.removeConstraint(joint.get());
		for (auto& body : bodies) world.removeRigidBody(body.get());
	}
	btSetTaskScheduler(0);
	return bits;
}

bool sameBits(const std::vector<btScalar>& a, const std::vector<btScalar>& b)
{
	return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)) == 0;
}
}  // namespace

TEST(ColourSweep, WithoutAWaitPerColourGivesTheBitsOfTheSweepWithOneOnAnyScheduler)
{
	const int kSteps = 12;
	const std::vector<btScalar> reference = wallBits(true, btGetSequentialTaskScheduler(), kSteps);
	EXPECT_TRUE(sameBits(wallBits(false, btGetSequentialTaskScheduler(), kSteps), reference)) << "sequential";
	for (int threads : {1, 2, 3})
	{
		std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
		if (!pool) break;  // a library without threads
		pool->setNumThreads(threads);
		EXPECT_TRUE(sameBits(wallBits(false, pool.get(), kSteps), reference)) << threads << " threads";
		EXPECT_TRUE(sameBits(wallBits(true, pool.get(), kSteps), reference)) << threads << " threads, barriers";
	}
	for (bool oneCall : {false, true})
	{
		OneThreadScheduler oneThread(3, oneCall);
		EXPECT_TRUE(sameBits(wallBits(false, &oneThread, kSteps), reference))
		    << (oneCall ? "one call" : "tasks backwards");
	}
}

TEST(ColourSweep, PostsOneLoopPerIterationInsteadOfTwoPerColour)
{
	// The loops of the whole step (set-up, write-back, the other stages) are counted; the sweep's own
	// loops are the difference: 10 iterations of two passes over several colours before, one loop each now.
	const int kSteps = 3;
	OneThreadScheduler counter(2, false);
	int loopsWithBarriers = 0, loopsWithout = 0;
	counter.loops = 0;
	wallBits(true, &counter, kSteps, &counter.loops);
	loopsWithBarriers = counter.loops;
	counter.loops = 0;
	wallBits(false, &counter, kSteps, &counter.loops);
	loopsWithout = counter.loops;
	std::printf("loops in %d steps: %d with a wait per colour, %d without\n", kSteps, loopsWithBarriers, loopsWithout);
	const int iterations = btContactSolverInfo().m_numIterations;
	// At least two colours per solve: at least 2 * 2 * iterations loops per step before, iterations + 1 now
	// (the dependencies are listed in one more loop per solve).
	EXPECT_GE(loopsWithBarriers - loopsWithout, kSteps * (4 * iterations - iterations - 1));
}

TEST(ColourSweep, ThePlanMadeBesideTheContactRowsIsThePlanMadeAfterThemOnAnyScheduler)
{
	// The Mt solver colours the manifolds, orders them, cuts the batches and sorts the dependencies by body
	// in the first task of the contact rows' fill. With the plain solver's rows (a subclass's convertContacts)
	// the set-up makes that plan itself after the rows, on the calling thread: the worlds must agree bit for
	// bit, with the pool, with the sequential scheduler, and with a scheduler that runs the fill's tasks last
	// first or in one call (the plan then runs after, or before, every row).
	const int kSteps = 12;
	const std::vector<btScalar> reference = wallBits(false, btGetSequentialTaskScheduler(), kSteps, nullptr, true);
	EXPECT_TRUE(sameBits(wallBits(false, btGetSequentialTaskScheduler(), kSteps), reference)) << "sequential";
	for (int threads : {2, 3})
	{
		std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
		if (!pool) break;  // a library without threads
		pool->setNumThreads(threads);
		EXPECT_TRUE(sameBits(wallBits(false, pool.get(), kSteps), reference)) << threads << " threads";
		EXPECT_TRUE(sameBits(wallBits(false, pool.get(), kSteps, nullptr, true), reference))
		    << threads << " threads, plain rows";
		EXPECT_TRUE(sameBits(wallBits(true, pool.get(), kSteps), reference)) << threads << " threads, barriers";
	}
	for (bool oneCall : {false, true})
	{
		OneThreadScheduler oneThread(3, oneCall);
		EXPECT_TRUE(sameBits(wallBits(false, &oneThread, kSteps), reference))
		    << (oneCall ? "one call" : "tasks backwards");
	}
}

TEST(ColourSweep, WarmStartsAndBodyWriteBackByTheSweepsRunsGiveTheBitsOfOneThread)
{
	// At more than one thread the Mt solver warms and writes back the solver bodies in the sweep's runs
	// (each body with the run of its first batch; a body in no batch, here the fixed entry and a ball hung
	// from a joint, with its share of the index range), slice by slice: every body must be warmed and
	// written back exactly once (a body missed or done twice changes its velocity), whichever thread takes
	// a slice and in whatever order, so the world ends with the bits of no threads.
	const int kSteps = 12;
	const std::vector<btScalar> reference =
	    wallBits(false, btGetSequentialTaskScheduler(), kSteps, nullptr, false, true);
	for (int threads : {2, 3, 4})
	{
		std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
		if (!pool) break;  // a library without threads
		pool->setNumThreads(threads);
		EXPECT_TRUE(sameBits(wallBits(false, pool.get(), kSteps, nullptr, false, true), reference))
		    << threads << " threads";
		EXPECT_TRUE(sameBits(wallBits(true, pool.get(), kSteps, nullptr, false, true), reference))
		    << threads << " threads, barriers";
	}
	for (bool oneCall : {false, true})
	{
		OneThreadScheduler oneThread(3, oneCall);
		EXPECT_TRUE(sameBits(wallBits(false, &oneThread, kSteps, nullptr, false, true), reference))
		    << (oneCall ? "one call" : "tasks backwards");
	}
}

namespace
{
// Colours of the given batch sizes (rows), in order, as the Mt solver's plan lays them out.
btBatchedConstraints batchesOf(const std::vector<std::vector<int>>& colours)
{
	btBatchedConstraints batched;
	int row = 0;
	for (const std::vector<int>& colour : colours)
	{
		const int first = batched.m_batches.size();
		for (int rows : colour)
		{
			batched.m_batches.push_back(btBatchedConstraints::Range(row, row + rows));
			row += rows;
		}
		batched.m_phaseOrder.push_back(batched.m_phases.size());
		batched.m_phases.push_back(btBatchedConstraints::Range(first, batched.m_batches.size()));
	}
	return batched;
}

std::vector<long long> rowsPerTask(const btBatchedConstraints& batched, const btAlignedObjectArray<caliber::SweepItem>& items,
                                   int tasks)
{
	std::vector<long long> rows(tasks, 0);
	for (int i = 0; i < items.size(); ++i)
		for (int b = items[i].batchBegin; b < items[i].batchEnd; ++b)
			rows[items[i].run] += batched.m_batches[b].end - batched.m_batches[b].begin;
	return rows;
}

// Random colours: 1 to 12 batches of 4 to 64 rows each.
std::vector<std::vector<int>> randomColours(unsigned seed, int numColours)
{
	std::mt19937 random(seed);
	std::vector<std::vector<int>> colours(numColours);
	for (std::vector<int>& colour : colours)
	{
		colour.resize(1 + random() % 12);
		for (int& rows : colour) rows = 4 + int(random() % 61);
	}
	return colours;
}
}  // namespace

TEST(SweepItems, EveryBatchIsInOneItemOfItsColourInTheSweepsOrderWithTheTasksInOrderWithinAColour)
{
	for (unsigned seed = 1; seed <= 20; ++seed)
		for (int tasks : {1, 2, 3, 5})
			for (bool reverse : {false, true})
			{
				const btBatchedConstraints batched = batchesOf(randomColours(seed, 30));
				const int numBatches = batched.m_batches.size(), numPhases = batched.m_phases.size();
				btAlignedObjectArray<caliber::SweepItem> items;
				btAlignedObjectArray<int> itemOfBatch;
				caliber::listSweepItems(batched, reverse, tasks, items, itemOfBatch);
				ASSERT_EQ(itemOfBatch.size(), 2 * numBatches);
				// The items, read in order, walk pass by pass and colour by colour in the sweep's order, each
				// colour's batches once, in runs whose tasks rise (a task keeps one end of the bodies' order).
				int i = 0;
				for (int pass = 0; pass < 2; ++pass)
					for (int k = 0; k < numPhases; ++k)
					{
						const btBatchedConstraints::Range& phase =
						    batched.m_phases[batched.m_phaseOrder[reverse ? numPhases - 1 - k : k]];
						int next = phase.begin, lastTask = -1;
						const bool fewerThanTasks = phase.end - phase.begin < tasks;
						while (next < phase.end)
						{
							ASSERT_LT(i, items.size());
							const caliber::SweepItem& item = items[i];
							EXPECT_EQ(item.pass, pass);
							EXPECT_EQ(item.batchBegin, next);
							EXPECT_GT(item.batchEnd, item.batchBegin);
							EXPECT_GE(item.run, 0);
							EXPECT_LT(item.run, tasks);
							if (!fewerThanTasks)
							{
								EXPECT_GT(item.run, lastTask) << "seed " << seed;
							}
							lastTask = item.run;
							for (int b = item.batchBegin; b < item.batchEnd; ++b) EXPECT_EQ(itemOfBatch[pass * numBatches + b], i);
							next = item.batchEnd;
							++i;
						}
						EXPECT_EQ(next, phase.end);
					}
				EXPECT_EQ(i, items.size());
			}
}

TEST(SweepItems, EachTaskGetsAnEvenShareOfTheRowsWhereCuttingByCountGaveTheFirstTwoThirds)
{
	// Colours of three equal batches: cut by count, the first of two tasks took two batches of each.
	{
		const btBatchedConstraints batched = batchesOf(std::vector<std::vector<int>>(20, std::vector<int>{10, 10, 10}));
		btAlignedObjectArray<caliber::SweepItem> items;
		btAlignedObjectArray<int> itemOfBatch;
		caliber::listSweepItems(batched, false, 2, items, itemOfBatch);
		const std::vector<long long> rows = rowsPerTask(batched, items, 2);
		// 600 rows in each pass: within one batch of 600 each over the two passes.
		EXPECT_LE(std::llabs(rows[0] - 600), 10);
		EXPECT_LE(std::llabs(rows[1] - 600), 10);
	}
	// Random colours: no task more than one batch per task away from the even share (the greedy cut leaves
	// each task but the last within half a batch of its share after every colour).
	for (unsigned seed = 1; seed <= 20; ++seed)
		for (int tasks : {2, 3, 4})
		{
			const btBatchedConstraints batched = batchesOf(randomColours(seed, 40));
			btAlignedObjectArray<caliber::SweepItem> items;
			btAlignedObjectArray<int> itemOfBatch;
			caliber::listSweepItems(batched, seed % 2 == 1, tasks, items, itemOfBatch);
			const std::vector<long long> rows = rowsPerTask(batched, items, tasks);
			long long total = 0;
			for (long long r : rows) total += r;
			for (int t = 0; t < tasks; ++t)
				EXPECT_LE(std::llabs(rows[t] * tasks - total), static_cast<long long>(tasks) * tasks * 64)
				    << "seed " << seed << ", " << tasks << " tasks, task " << t;
		}
}

TEST(SweepItems, ABatchOfAColourOfFewerBatchesThanTasksGoesToTheTaskWithTheFewestRows)
{
	// A colour of five batches, then colours of one batch each: the second task holds fewer rows after the
	// first colour's cut (30 of 50 to the first: 10 + 20 lie below the share of 25 by their middles), and
	// takes the single batches until it has caught up.
	const btBatchedConstraints batched = batchesOf({{10, 20, 5, 10, 5}, {8}, {8}, {8}});
	btAlignedObjectArray<caliber::SweepItem> items;
	btAlignedObjectArray<int> itemOfBatch;
	caliber::listSweepItems(batched, false, 2, items, itemOfBatch);
	ASSERT_EQ(items.size(), 2 * 5);
	EXPECT_EQ(items[0].run, 0);
	EXPECT_EQ(items[0].batchEnd, 2);  // 10 + 20 rows
	EXPECT_EQ(items[1].run, 1);       // 20 rows
	EXPECT_EQ(items[2].run, 1);       // 28
	EXPECT_EQ(items[3].run, 1);       // 36 (ties go to the first task; 28 < 30 still)
	EXPECT_EQ(items[4].run, 0);       // 30 < 36: the first task
}

TEST(SweepItems, ABatchHasTheSameTaskInBothPassesAndBothDirections)
{
	// A batch's rows and bodies stay in one thread's cache through a solve only if every sweep gives the batch
	// to the same task.
	for (unsigned seed = 1; seed <= 20; ++seed)
		for (int tasks : {2, 3, 4})
		{
			const btBatchedConstraints batched = batchesOf(randomColours(seed, 30));
			const int numBatches = batched.m_batches.size();
			btAlignedObjectArray<caliber::SweepItem> forward, backward;
			btAlignedObjectArray<int> forwardItem, backwardItem;
			caliber::listSweepItems(batched, false, tasks, forward, forwardItem);
			caliber::listSweepItems(batched, true, tasks, backward, backwardItem);
			for (int b = 0; b < numBatches; ++b)
			{
				const int task = forward[forwardItem[b]].run;
				EXPECT_EQ(forward[forwardItem[numBatches + b]].run, task) << "seed " << seed << ", batch " << b;
				EXPECT_EQ(backward[backwardItem[b]].run, task) << "seed " << seed << ", batch " << b;
				EXPECT_EQ(backward[backwardItem[numBatches + b]].run, task) << "seed " << seed << ", batch " << b;
			}
		}
}

TEST(SweepItems, AThreadCountOutOfRangeIsClampedAndNoBatchesGiveNoItems)
{
	const btBatchedConstraints batched = batchesOf(randomColours(7, 10));
	btAlignedObjectArray<caliber::SweepItem> one, zero, negative, many, most;
	btAlignedObjectArray<int> itemOfBatch;
	caliber::listSweepItems(batched, false, 1, one, itemOfBatch);
	caliber::listSweepItems(batched, false, 0, zero, itemOfBatch);
	caliber::listSweepItems(batched, false, -3, negative, itemOfBatch);
	for (const btAlignedObjectArray<caliber::SweepItem>* items : {&zero, &negative})
	{
		ASSERT_EQ(items->size(), one.size());
		for (int i = 0; i < one.size(); ++i)
		{
			EXPECT_EQ((*items)[i].batchBegin, one[i].batchBegin);
			EXPECT_EQ((*items)[i].run, 0);
		}
	}
	caliber::listSweepItems(batched, false, 100000, many, itemOfBatch);
	caliber::listSweepItems(batched, false, BT_MAX_THREAD_COUNT, most, itemOfBatch);
	ASSERT_EQ(many.size(), most.size());
	for (int i = 0; i < many.size(); ++i) EXPECT_EQ(many[i].run, most[i].run);
	btAlignedObjectArray<caliber::SweepItem> none;
	caliber::listSweepItems(btBatchedConstraints(), true, 2, none, itemOfBatch);
	EXPECT_EQ(none.size(), 0);
	EXPECT_EQ(itemOfBatch.size(), 0);
}
