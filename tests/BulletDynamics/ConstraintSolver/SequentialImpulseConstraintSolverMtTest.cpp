// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSequentialImpulseConstraintSolverMt's coloured solve: the colouring is valid (every contact row in
// one batch, no two batches of a colour sharing a moving body), it is used only for large solves, and
// a pyramid solved with it rests as it does with the serial solver, on any number of threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "LinearMath/btThreads.h"
#include "MtSolverTestUtil.h"
#include "TestThreadsUtil.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// Checks every coloured solve with btBatchedConstraints::validate and counts colours and rows.
class CheckedMtSolver : public btSequentialImpulseConstraintSolverMt
{
public:
	int colouredSolves = 0;
	int invalidSolves = 0;
	int mostColours = 0;
	int rowsMissed = 0;

protected:
	btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
	                                      int numManifolds, btTypedConstraint** constraints, int numConstraints,
	                                      const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override
	{
		const btScalar result = btSequentialImpulseConstraintSolverMt::solveGroupCacheFriendlySetup(
		    bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
		if (m_useBatching)
		{
			++colouredSolves;
			if (!m_batchedContactConstraints.validate(&m_tmpSolverContactConstraintPool, m_tmpSolverBodyPool))
				++invalidSolves;
			if (m_batchedContactConstraints.m_phases.size() > mostColours)
				mostColours = m_batchedContactConstraints.m_phases.size();
			rowsMissed +=
			    m_tmpSolverContactConstraintPool.size() - m_batchedContactConstraints.m_constraintIndices.size();
		}
		return result;
	}
};

// The Mt solver with the serial solver's contact setup: the yardstick for its parallel setup.
class SerialSetupMtSolver : public CheckedMtSolver
{
protected:
	void convertContacts(btPersistentManifold** manifolds, int numManifolds, const btContactSolverInfo& info) override
	{
		btSequentialImpulseConstraintSolver::convertContacts(manifolds, numManifolds, info);
	}
};

const btScalar kHalf = btScalar(0.5);
const int kLevels = 8;  // 36 boxes: 8 + 7 + ... + 1 in a 2-D pyramid, twice side by side in depth

// A pyramid of boxes on a ground box, in the Mt world (as Bullet's multithreaded examples build it) or
// in the plain world.
struct Pyramid
{
	explicit Pyramid(bool mt, bool serialSetup = false)
	{
		if (mt)
		{
			btDefaultCollisionConstructionInfo info;
			info.m_defaultMaxPersistentManifoldPoolSize = 4096;
			info.m_defaultMaxCollisionAlgorithmPoolSize = 4096;
			config.reset(new btDefaultCollisionConfiguration(info));
			dispatcher.reset(new btCollisionDispatcherMt(config.get(), 16));
			pool.reset(new btConstraintSolverPoolMt(BT_MAX_THREAD_COUNT));
			solverMt.reset(serialSetup ? new SerialSetupMtSolver() : new CheckedMtSolver());
			broadphase.reset(new btDbvtBroadphase());
			world.reset(new btDiscreteDynamicsWorldMt(dispatcher.get(), broadphase.get(), pool.get(), solverMt.get(),
			                                          config.get()));
		}
		else
		{
			config.reset(new btDefaultCollisionConfiguration());
			dispatcher.reset(new btCollisionDispatcher(config.get()));
			solver.reset(new btSequentialImpulseConstraintSolver());
			broadphase.reset(new btDbvtBroadphase());
			world.reset(new btDiscreteDynamicsWorld(dispatcher.get(), broadphase.get(), solver.get(), config.get()));
		}
		world->setGravity(btVector3(0, -10, 0));
		ground.reset(new btBoxShape(btVector3(20, 1, 20)));
		box.reset(new btBoxShape(btVector3(kHalf, kHalf, kHalf)));
		add(0, ground.get(), btVector3(0, -1, 0));
		for (int row = 0; row < 2; ++row)
			for (int level = 0; level < kLevels; ++level)
				for (int i = 0; i < kLevels - level; ++i)
					add(1, box.get(),
					    btVector3(btScalar(i - (kLevels - level - 1) * 0.5) * btScalar(1.02), kHalf + level * 1.0f,
					              btScalar(row) * 1.02f));
	}
	~Pyramid()
	{
		for (auto& body : bodies) world->removeRigidBody(body.get());
	}
	void add(btScalar mass, btCollisionShape* shape, const btVector3& at)
	{
		btVector3 inertia(0, 0, 0);
		if (mass != 0) shape->calculateLocalInertia(mass, inertia);
		motionStates.emplace_back(new btDefaultMotionState(btTransform(btQuaternion::getIdentity(), at)));
		btRigidBody::btRigidBodyConstructionInfo info(mass, motionStates.back().get(), shape, inertia);
		bodies.emplace_back(new btRigidBody(info));
		bodies.back()->setActivationState(DISABLE_DEACTIVATION);
		world->addRigidBody(bodies.back().get());
	}
	void step(int steps)
	{
		for (int i = 0; i < steps; ++i) world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	}
	// The largest distance a box moved from where it was put, and the fastest box.
	void motion(btScalar& maxShift, btScalar& maxSpeed) const
	{
		maxShift = maxSpeed = 0;
		for (size_t i = 1; i < bodies.size(); ++i)
		{
			btTransform start;
			motionStatesStart(i, start);
			maxShift = btMax(maxShift, (bodies[i]->getWorldTransform().getOrigin() - start.getOrigin()).length());
			maxSpeed = btMax(maxSpeed, bodies[i]->getLinearVelocity().length());
		}
	}
	// The bits of every box's pose and velocities.
	std::vector<btScalar> state() const { return caliber_test::bodyStateBits(bodies); }
	void motionStatesStart(size_t i, btTransform& start) const { start = motionStates[i]->m_startWorldTrans; }

	std::unique_ptr<btDefaultCollisionConfiguration> config;
	std::unique_ptr<btCollisionDispatcher> dispatcher;
	std::unique_ptr<btConstraintSolverPoolMt> pool;
	std::unique_ptr<CheckedMtSolver> solverMt;
	std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
	std::unique_ptr<btBroadphaseInterface> broadphase;
	std::unique_ptr<btDiscreteDynamicsWorld> world;
	std::unique_ptr<btCollisionShape> ground, box;
	std::vector<std::unique_ptr<btDefaultMotionState>> motionStates;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
};

// Every solve coloured, for the length of a test.
using ColourEverySolve = caliber_test::ScopedManifoldBatchingThreshold;
}  // namespace

TEST(SequentialImpulseConstraintSolverMt, ColouringPutsEveryContactRowInOneBatchAndNoMovingBodyInTwoBatchesOfAColour)
{
	ColourEverySolve colourAll;
	Pyramid pyramid(true);
	pyramid.step(30);
	EXPECT_EQ(pyramid.solverMt->colouredSolves, 30);
	EXPECT_EQ(pyramid.solverMt->invalidSolves, 0);
	EXPECT_EQ(pyramid.solverMt->rowsMissed, 0);
	// A box in the pyramid touches up to 6 others and the ground: more than one colour, and few.
	EXPECT_GT(pyramid.solverMt->mostColours, 1);
	EXPECT_LE(pyramid.solverMt->mostColours, 16);
}

TEST(SequentialImpulseConstraintSolverMt, SmallSolvesAreNotColoured)
{
	Pyramid pyramid(true);  // about 100 manifolds, below the default threshold of 250
	pyramid.step(10);
	EXPECT_EQ(pyramid.solverMt->colouredSolves, 0);
}

TEST(SequentialImpulseConstraintSolverMt, PyramidRestsWithTheColouredSolveOnAnyThreadCount)
{
	// The boxes start 2 cm apart sideways and touching vertically: at rest from the start, so after 2 s
	// no box should have moved by more than the contacts' settling (a few millimetres per level: the
	// solver's penetration slop), and none should be moving. The serial solver is the yardstick: the
	// coloured order may settle differently, but not by more than 1 cm more.
	Pyramid serial(false);
	serial.step(120);
	btScalar serialShift, serialSpeed;
	serial.motion(serialShift, serialSpeed);

	ColourEverySolve colourAll;
	// A library built without threads (CALIBER_THREADSAFE=OFF) has no pool: the sequential scheduler
	// stands in.
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	btITaskScheduler* scheduler = pool ? pool.get() : btGetSequentialTaskScheduler();
	btSetTaskScheduler(scheduler);
	for (int threads : {1, 2, 4})
	{
		scheduler->setNumThreads(threads);
		Pyramid pyramid(true);
		pyramid.step(120);
		btScalar shift, speed;
		pyramid.motion(shift, speed);
		EXPECT_GT(pyramid.solverMt->colouredSolves, 0);
		EXPECT_LT(shift, serialShift + btScalar(0.01)) << threads << " threads";
		EXPECT_LT(shift, btScalar(0.05)) << threads << " threads";
		// Resting: well below one step of gravity (10 m/s^2 / 60 Hz = 0.17 m/s).
		EXPECT_LT(speed, btScalar(0.02)) << threads << " threads";
	}
	btSetTaskScheduler(0);
}

TEST(SequentialImpulseConstraintSolverMt, ParallelContactSetupGivesTheSerialSetupsBits)
{
	// The rows of a large solve are filled on the threads and their warm starts applied in the serial
	// order: the same bits as the serial setup, so the two solvers give the same world, step after step.
	ColourEverySolve colourAll;
	// A library built without threads (CALIBER_THREADSAFE=OFF) has no pool: the sequential scheduler
	// stands in.
	caliber_test::ScopedTaskScheduler scheduler(2);
	Pyramid parallelSetup(true), serialSetup(true, true);
	parallelSetup.step(40);
	serialSetup.step(40);
	EXPECT_GT(parallelSetup.solverMt->colouredSolves, 0);
	const std::vector<btScalar> a = parallelSetup.state(), b = serialSetup.state();
	ASSERT_EQ(a.size(), b.size());
	EXPECT_EQ(0, std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)));
}

namespace
{
// The contact order a setup leaves for the split-impulse pass (the serial solver's sweeps use it too).
template <class Solver>
class SetupOnly : public Solver
{
public:
	std::vector<int> contactOrder(btDiscreteDynamicsWorld& world, bool* batched = nullptr)
	{
		btDispatcher* dispatcher = world.getDispatcher();
		btCollisionObjectArray& objects = world.getCollisionObjectArray();
		this->solveGroupCacheFriendlySetup(&objects[0], objects.size(), dispatcher->getInternalManifoldPointer(),
		                                   dispatcher->getNumManifolds(), nullptr, 0, world.getSolverInfo(), nullptr);
		if (batched) *batched = batchedSolve();
		std::vector<int> order;
		for (int i = 0; i < this->m_orderTmpConstraintPool.size(); ++i)
			order.push_back(this->m_orderTmpConstraintPool[i]);
		EXPECT_EQ(int(order.size()), this->m_tmpSolverContactConstraintPool.size());
		return order;
	}
	bool batchedSolve() const;
};
template <>
bool SetupOnly<btSequentialImpulseConstraintSolverMt>::batchedSolve() const
{
	return m_useBatching;
}
template <>
bool SetupOnly<btSequentialImpulseConstraintSolver>::batchedSolve() const
{
	return false;
}
}  // namespace

TEST(SequentialImpulseConstraintSolverMt, BatchedSetupGivesTheSplitImpulsePassTheSerialContactOrder)
{
	// A batched solve sweeps its own batches, so its setup skips the serial sweep orders and writes only the
	// contact order, which the split-impulse pass follows, on the threads: it must be the serial setup's
	// (the manifolds' points interleaved in blocks, each manifold's first point rotated by the solve count).
	ColourEverySolve colourAll;
	caliber_test::ScopedTaskScheduler scheduler(2);
	Pyramid pyramid(false);
	pyramid.step(3);
	ASSERT_TRUE(pyramid.world->getSolverInfo().m_splitImpulse);
	SetupOnly<btSequentialImpulseConstraintSolverMt> mt;
	SetupOnly<btSequentialImpulseConstraintSolver> serial;
	bool batched = false;
	const std::vector<int> batchedOrder = mt.contactOrder(*pyramid.world, &batched);
	const std::vector<int> serialOrder = serial.contactOrder(*pyramid.world);
	EXPECT_TRUE(batched);
	ASSERT_GT(serialOrder.size(), size_t(100));  // a few points for each of about 100 manifolds
	EXPECT_EQ(batchedOrder, serialOrder);
}

namespace
{
// A body of the slab below: bouncy (restitution 0.6) and never put to sleep.
void addSlabBody(btDiscreteDynamicsWorld& world, std::vector<std::unique_ptr<btRigidBody>>& bodies, btScalar mass,
                 btCollisionShape* shape, const btVector3& at)
{
	btVector3 inertia(0, 0, 0);
	if (mass != 0) shape->calculateLocalInertia(mass, inertia);
	btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
	info.m_startWorldTransform.setOrigin(at);
	info.m_restitution = btScalar(0.6);
	bodies.emplace_back(new btRigidBody(info));
	bodies.back()->setActivationState(DISABLE_DEACTIVATION);
	world.addRigidBody(bodies.back().get());
}

// A slab of 12 x 12 columns of two boxes each, side by side (touching) on a ground box, in the plain world:
// about 800 manifolds and 3000 contact rows in one solve, so that the batched setup's loops over chunks of
// manifolds and rows have several chunks. Every other column is sunk 0.1 m into the ground and into
// itself (deeper than the split-impulse threshold of 0.04 m: those contacts get push rows), the others
// rest exactly; the boxes bounce (restitution 0.6, falling at 3 m/s after the first step) and every
// other column's top box is ten times heavier (a heavy-on-light contact).
struct Slab
{
	static const int kSide = 12;

	Slab()
	    : dispatcher(&config),
	      world(&dispatcher, &broadphase, &solver, &config),
	      ground(btVector3(40, 1, 40)),
	      box(btVector3(kHalf, kHalf, kHalf))
	{
		world.setGravity(btVector3(0, -10, 0));
		add(0, &ground, btVector3(0, -1, 0));
		for (int i = 0; i < kSide; ++i)
			for (int j = 0; j < kSide; ++j)
			{
				const bool sunk = (i + j) % 2 == 0;
				const btScalar sink = sunk ? btScalar(0.1) : btScalar(0);
				add(1, &box, btVector3(btScalar(i), kHalf - sink, btScalar(j)));
				add(sunk ? 10 : 1, &box, btVector3(btScalar(i), 3 * kHalf - 2 * sink, btScalar(j)));
			}
		world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
		for (size_t b = 1; b < bodies.size(); ++b) bodies[b]->setLinearVelocity(btVector3(0, -3, 0));
	}
	~Slab()
	{
		for (auto& body : bodies) world.removeRigidBody(body.get());
	}
	void add(btScalar mass, btCollisionShape* shape, const btVector3& at)
	{
		addSlabBody(world, bodies, mass, shape, at);
	}

	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher;
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world;
	btBoxShape ground, box;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
};

// Sets up one solve of every manifold of a world and keeps what the split-impulse pass and the
// restitution pass will read.
template <class Solver>
class SetupOf : public Solver
{
public:
	void setup(btDiscreteDynamicsWorld& world)
	{
		btDispatcher* dispatcher = world.getDispatcher();
		btCollisionObjectArray& objects = world.getCollisionObjectArray();
		this->solveGroupCacheFriendlySetup(&objects[0], objects.size(), dispatcher->getInternalManifoldPointer(),
		                                   dispatcher->getNumManifolds(), nullptr, 0, world.getSolverInfo(), nullptr);
	}
	caliber::SolverScratch& scratch() const { return caliber::solverScratchOf(*this); }
	const btConstraintArray& contacts() const { return this->m_tmpSolverContactConstraintPool; }
	const btAlignedObjectArray<int>& contactOrder() const { return this->m_orderTmpConstraintPool; }
	bool batched() const { return this->m_useBatching; }  // the Mt solver's only
};

// The bits of the bounce rows a setup listed.
std::vector<btScalar> bounceBits(const caliber::SolverScratch& scratch)
{
	std::vector<btScalar> bits;
	for (int k = 0; k < scratch.bounceRows.size(); ++k)
	{
		const caliber::SolverBounceRow& bounce = scratch.bounceRows[k];
		bits.push_back(btScalar(bounce.row));
		bits.push_back(bounce.startVelocity);
		bits.push_back(bounce.targetVelocity);
		bits.push_back(bounce.targetPushVelocity);
	}
	return bits;
}
}  // namespace

TEST(SequentialImpulseConstraintSolverMt, BatchedSetupListsThePushRowsTheSerialScanFinds)
{
	// The batched setup lists the split-impulse pass's rows (those with a push target, in the contact
	// order) chunk by chunk on the threads while it writes the order; the pass then skips its own scan.
	// The list must be the scan's: the rows of the order whose push target is not zero, in that order.
	for (int threads : {1, 2, 3})
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		Slab slab;
		ASSERT_TRUE(slab.world.getSolverInfo().m_splitImpulse);
		SetupOf<btSequentialImpulseConstraintSolverMt> mt;
		mt.setup(slab.world);
		ASSERT_TRUE(mt.batched());
		ASSERT_GT(slab.dispatcher.getNumManifolds(), 3 * 128);  // several chunks of 128 manifolds
		EXPECT_TRUE(mt.scratch().pushRowsListed);
		std::vector<int> expected, listed;
		for (int k = 0; k < mt.contactOrder().size(); ++k)
		{
			const int row = mt.contactOrder()[k];
			if (mt.contacts()[row].m_rhsPenetration != btScalar(0)) expected.push_back(row);
		}
		for (int k = 0; k < mt.scratch().pushRows.size(); ++k) listed.push_back(mt.scratch().pushRows[k]);
		// The sunk columns' contacts have push rows, the resting ones none.
		EXPECT_GT(expected.size(), size_t(100)) << threads << " threads";
		EXPECT_LT(expected.size(), size_t(mt.contacts().size())) << threads << " threads";
		EXPECT_EQ(listed, expected) << threads << " threads";
	}
}

TEST(SequentialImpulseConstraintSolverMt, PushPassScansItsRowsWhenTheSetupDidNotListThem)
{
	// A serial setup leaves the list to the pass (and clears what a batched setup of the same solver
	// listed before).
	caliber_test::ScopedTaskScheduler scheduler(2);
	Slab slab;
	SetupOf<btSequentialImpulseConstraintSolver> serial;
	serial.scratch().pushRowsListed = true;  // as a previous batched solve would have left it
	serial.setup(slab.world);
	EXPECT_FALSE(serial.scratch().pushRowsListed);
}

TEST(SequentialImpulseConstraintSolverMt, SolvesWithSeveralChunksOfManifoldsGiveTheBitsOfOneThreadAnySplit)
{
	// The places of the points and rows are counted chunk by chunk (256 manifolds) and the push rows listed
	// by chunk of the contact order: a world whose one solve has several chunks of each ends with the same
	// bits with the pool at 1, 2 and 3 threads, with a scheduler that cuts every loop unevenly, and with the
	// serial contact setup.
	ColourEverySolve colourAll;
	auto run = [](int threads, bool uneven, bool serialSetup) {
		caliber_test::UnevenSplitScheduler unevenScheduler;
		std::unique_ptr<caliber_test::ScopedTaskScheduler> pool;
		if (uneven)
			btSetTaskScheduler(&unevenScheduler);
		else
			pool.reset(new caliber_test::ScopedTaskScheduler(threads));
		std::vector<btScalar> bits;
		{
			btDefaultCollisionConfiguration config;
			// The Mt narrowphase too: its loop runs over chunk numbers, so a scheduler that ignores the grain
			// gives it the same pairs per chunk.
			btCollisionDispatcherMt dispatcher(&config, 40);
			btDbvtBroadphase broadphase;
			btConstraintSolverPoolMt solverPool(BT_MAX_THREAD_COUNT);
			std::unique_ptr<CheckedMtSolver> solver(serialSetup ? new SerialSetupMtSolver() : new CheckedMtSolver());
			btDiscreteDynamicsWorldMt world(&dispatcher, &broadphase, &solverPool, solver.get(), &config);
			world.setGravity(btVector3(0, -10, 0));
			btBoxShape ground(btVector3(40, 1, 40)), box(btVector3(kHalf, kHalf, kHalf));
			std::vector<std::unique_ptr<btRigidBody>> bodies;
			auto add = [&](btScalar mass, btCollisionShape* shape, const btVector3& at) {
				addSlabBody(world, bodies, mass, shape, at);
			};
			add(0, &ground, btVector3(0, -1, 0));
			for (int i = 0; i < Slab::kSide; ++i)
				for (int j = 0; j < Slab::kSide; ++j)
				{
					const btScalar sink = (i + j) % 2 == 0 ? btScalar(0.1) : btScalar(0);
					add(1, &box, btVector3(btScalar(i), kHalf - sink, btScalar(j)));
					add(1, &box, btVector3(btScalar(i), 3 * kHalf - 2 * sink, btScalar(j)));
				}
			for (int step = 0; step < 6; ++step) world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
			EXPECT_GT(solver->colouredSolves, 0);
			EXPECT_EQ(solver->invalidSolves, 0);
			bits = caliber_test::bodyStateBits(bodies);
			for (auto& body : bodies) world.removeRigidBody(body.get());
		}
		if (uneven) btSetTaskScheduler(0);
		return bits;
	};
	const std::vector<btScalar> reference = run(1, false, true);
	const struct
	{
		int threads;
		bool uneven;
	} cases[] = {{1, false}, {2, false}, {3, false}, {2, true}};
	for (const auto& c : cases)
	{
		const std::vector<btScalar> bits = run(c.threads, c.uneven, false);
		ASSERT_EQ(bits.size(), reference.size());
		EXPECT_EQ(0, std::memcmp(bits.data(), reference.data(), bits.size() * sizeof(btScalar)))
		    << c.threads << " threads" << (c.uneven ? ", uneven split" : "");
	}
}

TEST(SequentialImpulseConstraintSolverMt, BounceRowsAreTheSerialPassesForAnySplitOfTheLoop)
{
	// findBouncesAndMassRatios lists the bounce rows of chunks of 256 rows on the threads: each loop index is
	// one chunk, so a scheduler that ignores the grain (Bullet's interface allows it) still fills each
	// chunk's list once and the joined list is the serial pass's, bit for bit.
	std::vector<btScalar> serialBits;
	bool serialShock = false;
	{
		Slab slab;  // no scheduler: the serial pass
		SetupOf<btSequentialImpulseConstraintSolver> serial;
		serial.setup(slab.world);
		ASSERT_GT(serial.contacts().size(), 3 * 256);
		serialBits = bounceBits(serial.scratch());
		serialShock = serial.scratch().shockPropagationNeeded;
	}
	EXPECT_GT(serialBits.size(), size_t(4 * 100));  // the falling boxes bounce
	EXPECT_TRUE(serialShock);                       // the heavy top boxes
	caliber_test::UnevenSplitScheduler uneven;
	btSetTaskScheduler(&uneven);
	{
		Slab slab;
		SetupOf<btSequentialImpulseConstraintSolver> split;
		split.setup(slab.world);
		const std::vector<btScalar> bits = bounceBits(split.scratch());
		ASSERT_EQ(bits.size(), serialBits.size());
		EXPECT_EQ(0, std::memcmp(bits.data(), serialBits.data(), bits.size() * sizeof(btScalar)));
		EXPECT_EQ(split.scratch().shockPropagationNeeded, serialShock);
	}
	btSetTaskScheduler(0);
}
