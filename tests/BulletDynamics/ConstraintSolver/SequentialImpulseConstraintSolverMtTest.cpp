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
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "LinearMath/btThreads.h"
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

// Sets the threshold for the length of a test (the pyramid has about 100 manifolds).
struct ColourEverySolve
{
	int saved = btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching;
	ColourEverySolve() { btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = 1; }
	~ColourEverySolve() { btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = saved; }
};
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
