// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The colouring of the Mt solver's large solves (btContactColouring.h): valid (no two manifolds of a
// colour share a moving body, every manifold coloured, also for a body in more manifolds than there are
// colours), ordered up the stacks along gravity, and what that order is for: a pyramid in the Mt world
// comes to rest as in the plain world, with the same bits at any thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btContactColouring.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/ConstraintSolver/btWideContactRows.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "LinearMath/btThreads.h"
#include "MtSolverTestUtil.h"
#include "TestThreadsUtil.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// Solver bodies at given positions (body 0 is the fixed entry) and manifolds between them.
struct Graph
{
	std::vector<btSolverBody> bodies;
	std::vector<int> ends;  // two per manifold

	Graph()
	{
		bodies.resize(1);
		bodies[0].m_worldTransform.setIdentity();
		bodies[0].m_originalBody = nullptr;
	}
	int addBody(const btVector3& at)
	{
		btSolverBody body;
		body.m_worldTransform.setIdentity();
		body.m_worldTransform.setOrigin(at);
		body.m_originalBody = nullptr;
		bodies.push_back(body);
		return int(bodies.size()) - 1;
	}
	void addManifold(int a, int b)
	{
		ends.push_back(a);
		ends.push_back(b);
	}
	int numManifolds() const { return int(ends.size()) / 2; }
	void colour(caliber::ContactColouring& colouring, const btVector3& up) const
	{
		colouring.colour(ends.data(), 2, numManifolds(), bodies.data(), int(bodies.size()), 0, up);
	}
	// Every manifold coloured within range, and no moving body twice in a colour.
	bool valid(const caliber::ContactColouring& colouring) const
	{
		std::vector<std::vector<bool>> used(size_t(colouring.numColours()), std::vector<bool>(bodies.size(), false));
		for (int m = 0; m < numManifolds(); ++m)
		{
			const int c = colouring.manifoldColour()[m];
			if (c < 0 || c >= colouring.numColours()) return false;
			for (int e = 0; e < 2; ++e)
			{
				const int body = ends[size_t(2 * m + e)];
				if (body == 0) continue;  // the fixed entry joins any colour
				if (used[size_t(c)][size_t(body)]) return false;
				used[size_t(c)][size_t(body)] = true;
			}
		}
		return true;
	}
};

// A pyramid as in BenchmarkDemo's stack1000: levels of n x n boxes (half extent 1), each box on the four
// below it, given to the colouring top level first (the worst order for a greedy colouring), with the
// level of each manifold's upper box.
Graph pyramidGraph(int levels, std::vector<int>& manifoldLevel)
{
	Graph graph;
	std::vector<std::vector<int>> ids(static_cast<size_t>(levels));
	for (int level = 0; level < levels; ++level)
	{
		const int n = levels - level;
		for (int j = 0; j < n; ++j)
			for (int i = 0; i < n; ++i)
				ids[size_t(level)].push_back(graph.addBody(btVector3(
				    btScalar(i) * 2 + btScalar(level), 1 + 2 * btScalar(level), btScalar(j) * 2 + btScalar(level))));
	}
	for (int level = levels - 1; level >= 0; --level)
	{
		const int n = levels - level;
		for (int j = 0; j < n; ++j)
			for (int i = 0; i < n; ++i)
			{
				const int box = ids[size_t(level)][size_t(j * n + i)];
				if (level == 0)
				{
					graph.addManifold(box, 0);
					manifoldLevel.push_back(0);
					continue;
				}
				const int below = n + 1;
				for (int dj = 0; dj < 2; ++dj)
					for (int di = 0; di < 2; ++di)
					{
						graph.addManifold(ids[size_t(level - 1)][size_t((j + dj) * below + i + di)], box);
						manifoldLevel.push_back(level);
					}
			}
	}
	return graph;
}
}  // namespace

TEST(ContactColouring, PyramidIsColouredLevelByLevelFromTheBottomUp)
{
	// Five levels with four contacts under each box need 1 + 4 * 4 = 17 colours, fewer than the 32 of the
	// level sweep, so no level wraps around: every contact of a level must come after every contact of the
	// level below, whatever order the manifolds arrive in.
	std::vector<int> manifoldLevel;
	const Graph graph = pyramidGraph(5, manifoldLevel);
	caliber::ContactColouring colouring;
	graph.colour(colouring, btVector3(0, 10, 0));
	ASSERT_TRUE(graph.valid(colouring));
	std::vector<int> lowest(5, 1 << 30), highest(5, -1);
	for (int m = 0; m < graph.numManifolds(); ++m)
	{
		const int level = manifoldLevel[size_t(m)], c = colouring.manifoldColour()[m];
		lowest[size_t(level)] = std::min(lowest[size_t(level)], c);
		highest[size_t(level)] = std::max(highest[size_t(level)], c);
	}
	for (int level = 1; level < 5; ++level)
		EXPECT_GT(lowest[size_t(level)], highest[size_t(level - 1)]) << "level " << level;
	EXPECT_EQ(colouring.numColours(), 17);
}

TEST(ContactColouring, TheOrderFollowsGravityNotTheYAxis)
{
	// The same column of boxes with gravity pointing up (+y): it stands on a ceiling, so its contacts are
	// coloured from the top (largest y) down.
	Graph graph;
	int previous = 0;
	for (int k = 0; k < 10; ++k)
	{
		const int box = graph.addBody(btVector3(0, -1 - 2 * btScalar(k), 0));
		graph.addManifold(previous, box);
		previous = box;
	}
	caliber::ContactColouring colouring;
	graph.colour(colouring, btVector3(0, -10, 0));
	ASSERT_TRUE(graph.valid(colouring));
	for (int m = 1; m < graph.numManifolds(); ++m)
		EXPECT_GT(colouring.manifoldColour()[m], colouring.manifoldColour()[m - 1]) << "manifold " << m;
	// With the other gravity the column hangs: its lowest box is its base, and the colours run backwards.
	graph.colour(colouring, btVector3(0, 10, 0));
	ASSERT_TRUE(graph.valid(colouring));
	for (int m = 2; m < graph.numManifolds(); ++m)
		EXPECT_LT(colouring.manifoldColour()[m], colouring.manifoldColour()[m - 1]) << "manifold " << m;
}

TEST(ContactColouring, ABodyInMoreManifoldsThanColoursGetsFurtherColours)
{
	// A platform under 100 boxes is in 100 manifolds: more than the 32 colours of the level sweep. Every
	// manifold still gets a colour of its own at the platform, so it needs at least 100 colours.
	Graph graph;
	const int platform = graph.addBody(btVector3(0, 1, 0));
	graph.addManifold(0, platform);
	for (int k = 0; k < 100; ++k)
	{
		const int box = graph.addBody(btVector3(btScalar(k % 10) * 2, 3, btScalar(k / 10) * 2));
		graph.addManifold(platform, box);
		const int top = graph.addBody(btVector3(btScalar(k % 10) * 2, 5, btScalar(k / 10) * 2));
		graph.addManifold(box, top);
	}
	caliber::ContactColouring colouring;
	graph.colour(colouring, btVector3(0, 10, 0));
	EXPECT_TRUE(graph.valid(colouring));
	EXPECT_GE(colouring.numColours(), 101);
	// Without gravity there are no stacks, and the colouring is still valid.
	graph.colour(colouring, btVector3(0, 0, 0));
	EXPECT_TRUE(graph.valid(colouring));
	// Nor do non-finite positions break it.
	Graph broken = graph;
	broken.bodies[3].m_worldTransform.setOrigin(btVector3(0, std::numeric_limits<btScalar>::quiet_NaN(), 0));
	broken.colour(colouring, btVector3(0, 10, 0));
	EXPECT_TRUE(broken.valid(colouring));
}

namespace
{
// Columns of boxes (half extent 1, mass 1) 4 cm apart, as the boxes of BenchmarkDemo's stack1000, on a
// static ground box; 5 solver iterations and the benchmark's solver mode. In the Mt world, with every
// solve coloured (ColourEverySolve), or the plain world.
struct Stack
{
	Stack(bool mt, int levels, int columnsPerSide = 0)
	{
		btDefaultCollisionConstructionInfo info;
		info.m_defaultMaxPersistentManifoldPoolSize = 8192;
		info.m_defaultMaxCollisionAlgorithmPoolSize = 8192;
		config.reset(new btDefaultCollisionConfiguration(info));
		broadphase.reset(new btDbvtBroadphase());
		if (mt)
		{
			dispatcher.reset(new btCollisionDispatcherMt(config.get(), 16));
			pool.reset(new btConstraintSolverPoolMt(BT_MAX_THREAD_COUNT));
			solver.reset(new btSequentialImpulseConstraintSolverMt());
			world.reset(new btDiscreteDynamicsWorldMt(dispatcher.get(), broadphase.get(), pool.get(), solver.get(),
			                                          config.get()));
		}
		else
		{
			dispatcher.reset(new btCollisionDispatcher(config.get()));
			solver.reset(new btSequentialImpulseConstraintSolver());
			world.reset(new btDiscreteDynamicsWorld(dispatcher.get(), broadphase.get(), solver.get(), config.get()));
		}
		world->setGravity(btVector3(0, -10, 0));
		world->getSolverInfo().m_numIterations = 5;
		world->getSolverInfo().m_solverMode =
		    SOLVER_SIMD | SOLVER_USE_WARMSTARTING | SOLVER_ENABLE_FRICTION_DIRECTION_CACHING;
		ground.reset(new btBoxShape(btVector3(50, 50, 50)));
		box.reset(new btBoxShape(btVector3(1, 1, 1)));
		add(0, ground.get(), btVector3(0, -50, 0));
		const btScalar pitch = btScalar(2.04);
		for (int level = 0; level < levels; ++level)
			for (int j = 0; j < columnsPerSide; ++j)
				for (int i = 0; i < columnsPerSide; ++i)
					add(1, box.get(), btVector3(btScalar(i) * pitch, 1 + btScalar(level) * pitch, btScalar(j) * pitch));
	}
	~Stack()
	{
		for (auto& body : bodies) world->removeRigidBody(body.get());
	}
	void add(btScalar mass, btCollisionShape* shape, const btVector3& at)
	{
		btVector3 inertia(0, 0, 0);
		if (mass != 0) shape->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
		info.m_startWorldTransform.setOrigin(at);
		bodies.emplace_back(new btRigidBody(info));
		bodies.back()->setActivationState(DISABLE_DEACTIVATION);
		world->addRigidBody(bodies.back().get());
	}
	// Steps and returns the mean, over the steps from `from` on, of the fastest box's speed.
	btScalar meanFastestSpeed(int steps, int from)
	{
		btScalar sum = 0;
		for (int i = 0; i < steps; ++i)
		{
			world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
			if (i < from) continue;
			btScalar fastest = 0;
			for (size_t b = 1; b < bodies.size(); ++b)
				fastest = btMax(fastest, bodies[b]->getLinearVelocity().length());
			sum += fastest;
		}
		return sum / btScalar(steps - from);
	}
	std::vector<btScalar> state() const { return caliber_test::bodyStateBits(bodies); }

	std::unique_ptr<btDefaultCollisionConfiguration> config;
	std::unique_ptr<btCollisionDispatcher> dispatcher;
	std::unique_ptr<btConstraintSolverPoolMt> pool;
	std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
	std::unique_ptr<btBroadphaseInterface> broadphase;
	std::unique_ptr<btDiscreteDynamicsWorld> world;
	std::unique_ptr<btCollisionShape> ground, box;
	std::vector<std::unique_ptr<btCollisionShape>> extraShapes;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
};

// Every solve coloured, for the length of a test.
using ColourEverySolve = caliber_test::ScopedManifoldBatchingThreshold;
}  // namespace

TEST(ContactColouring, ColumnsOfTwelveBoxesComeToRestWithTheSameBitsAtAnyThreadCount)
{
	// Four columns of twelve boxes, 4 cm apart, on the ground, solved with 5 iterations. Every step gravity
	// gives each box g dt = 10 / 60 = 0.17 m/s downwards, and the step's solve must take it back through the
	// whole column. A sweep that meets a column's contacts from the bottom up carries the support to the top
	// in its first pass, and the passes after it only trim; the greedy colouring met every other level first
	// and carried the support about two levels per pass, ten in five iterations, so the top boxes kept most of
	// g dt step after step (0.150 m/s on average, against 0.050 now and 0.081 in the plain world). Supported
	// boxes must move slower than half of g dt.
	const int kLevels = 12, kColumnsPerSide = 2, kSteps = 240, kFrom = 120;
	const btScalar kHalfGravityStep = btScalar(10) / 60 / 2;
	Stack plain(false, kLevels, kColumnsPerSide);
	const btScalar plainSpeed = plain.meanFastestSpeed(kSteps, kFrom);
	ColourEverySolve colourAll;
	std::vector<btScalar> oneThread;
	for (int threads : {1, 2, 3})
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		Stack mt(true, kLevels, kColumnsPerSide);
		const btScalar speed = mt.meanFastestSpeed(kSteps, kFrom);
		EXPECT_LT(speed, kHalfGravityStep) << threads << " threads; the plain world: " << plainSpeed;
		if (threads == 1)
		{
			oneThread = mt.state();
			continue;
		}
		const std::vector<btScalar> bits = mt.state();
		ASSERT_EQ(bits.size(), oneThread.size());
		EXPECT_EQ(0, std::memcmp(bits.data(), oneThread.data(), bits.size() * sizeof(btScalar)))
		    << threads << " threads";
	}
}

TEST(ContactColouring, APlatformUnderMoreBoxesThanColoursIsSweptWideWithTheRowByRowBits)
{
	// A dynamic platform carrying 49 boxes is in 50 manifolds, more than the 32 level colours. Before, the
	// manifolds left over went to one last batch that shared the platform, and the wide sweep, which loads
	// each lane's bodies once per group, lost all but one lane's impulses on it; now they get colours of
	// their own, and the wide sweep must give the bits of the row-by-row sweep.
	ColourEverySolve colourAll;
	const bool savedWide = caliber::wideContactRowsEnabled();
	for (int threads : {1, 2})
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		std::vector<btScalar> bits[2];
		btScalar platformDrop = 0;
		for (int wide = 0; wide < 2; ++wide)
		{
			caliber::setWideContactRowsEnabled(wide != 0);
			Stack world(true, 0);
			btCollisionShape* platformShape = new btBoxShape(btVector3(8, btScalar(0.5), 8));
			world.extraShapes.emplace_back(platformShape);
			world.add(20, platformShape, btVector3(0, btScalar(0.5), 0));
			for (int j = 0; j < 7; ++j)
				for (int i = 0; i < 7; ++i)
					world.add(1, world.box.get(),
					          btVector3(btScalar(i - 3) * btScalar(2.1), 2, btScalar(j - 3) * btScalar(2.1)));
			for (int step = 0; step < 60; ++step) world.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
			bits[wide] = world.state();
			platformDrop = btScalar(0.5) - world.bodies[1]->getWorldTransform().getOrigin().y();
		}
		ASSERT_EQ(bits[0].size(), bits[1].size());
		EXPECT_EQ(0, std::memcmp(bits[0].data(), bits[1].data(), bits[0].size() * sizeof(btScalar))) << threads;
		// Resting on the ground: sunk by no more than the contacts' slop (a few millimetres).
		EXPECT_LT(btFabs(platformDrop), btScalar(0.01)) << threads;
	}
	caliber::setWideContactRowsEnabled(savedWide);
}
