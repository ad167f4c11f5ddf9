// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The parts of a large solve's set-up that run on the task scheduler's threads (the bounces and mass
// ratios of the contact rows, the places of the points and rows, the warm starts by body) give the bits
// of the one-thread set-up: a bouncing block of boxes ends bit for bit the same at 1, 2 and 4 threads,
// in the plain world and in the Mt world.

#include <gtest/gtest.h>

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
// A 10 x 10 x 3 block of touching boxes (one island of about 1300 contact rows at rest) thrown down
// onto the ground at 2 m/s with restitution 0.5: the ground contacts bounce (their rows are bounce rows)
// and every contact is in one large solve.
struct BouncingBlock
{
	explicit BouncingBlock(bool mt)
	{
		if (mt)
		{
			btDefaultCollisionConstructionInfo info;
			info.m_defaultMaxPersistentManifoldPoolSize = 4096;
			info.m_defaultMaxCollisionAlgorithmPoolSize = 4096;
			config.reset(new btDefaultCollisionConfiguration(info));
			dispatcher.reset(new btCollisionDispatcherMt(config.get(), 16));
			pool.reset(new btConstraintSolverPoolMt(BT_MAX_THREAD_COUNT));
			solverMt.reset(new btSequentialImpulseConstraintSolverMt());
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
		box.reset(new btBoxShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5))));
		add(0, ground.get(), btVector3(0, -1, 0));
		for (int y = 0; y < 3; ++y)
			for (int x = 0; x < 10; ++x)
				for (int z = 0; z < 10; ++z)
				{
					btRigidBody* body = add(1, box.get(), btVector3(btScalar(x) - 5, btScalar(0.55) + btScalar(y), btScalar(z) - 5));
					body->setLinearVelocity(btVector3(0, -2, 0));
				}
	}
	~BouncingBlock()
	{
		for (auto& body : bodies) world->removeRigidBody(body.get());
	}
	btRigidBody* add(btScalar mass, btCollisionShape* shape, const btVector3& at)
	{
		btVector3 inertia(0, 0, 0);
		if (mass != 0) shape->calculateLocalInertia(mass, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(mass, 0, shape, inertia);
		info.m_startWorldTransform.setOrigin(at);
		info.m_restitution = btScalar(0.5);
		bodies.emplace_back(new btRigidBody(info));
		bodies.back()->setActivationState(DISABLE_DEACTIVATION);
		world->addRigidBody(bodies.back().get());
		return bodies.back().get();
	}
	std::vector<btScalar> state() const { return caliber_test::bodyStateBits(bodies); }
	// The fastest upward speed of a box of the bottom layer (the first 100 boxes after the ground: the
	// layers are added bottom first).
	btScalar fastestRise() const
	{
		btScalar fastest = 0;
		for (size_t i = 1; i <= 100; ++i) fastest = btMax(fastest, bodies[i]->getLinearVelocity().y());
		return fastest;
	}

	std::unique_ptr<btDefaultCollisionConfiguration> config;
	std::unique_ptr<btCollisionDispatcher> dispatcher;
	std::unique_ptr<btConstraintSolverPoolMt> pool;
	std::unique_ptr<btSequentialImpulseConstraintSolverMt> solverMt;
	std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
	std::unique_ptr<btBroadphaseInterface> broadphase;
	std::unique_ptr<btDiscreteDynamicsWorld> world;
	std::unique_ptr<btCollisionShape> ground, box;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
};

// The state after 12 steps (the impact is in the first) with the scheduler at `threads` (0: none).
std::vector<btScalar> run(bool mt, int threads, btScalar* rise = nullptr)
{
	caliber_test::ScopedTaskScheduler scheduler(threads);
	if (threads <= 0 && mt) btSetTaskScheduler(btGetSequentialTaskScheduler());
	std::vector<btScalar> bits;
	{
		BouncingBlock block(mt);
		btScalar fastest = 0;
		for (int i = 0; i < 12; ++i)
		{
			block.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
			fastest = btMax(fastest, block.fastestRise());
		}
		if (rise) *rise = fastest;
		bits = block.state();
	}
	return bits;
}
}  // namespace

TEST(ParallelSolverSetup, BouncingBlockEndsWithTheOneThreadBitsInThePlainWorld)
{
	btScalar rise = 0;
	const std::vector<btScalar> serial = run(false, 0, &rise);
	// The bottom layer rebounded: the set-up found bounce rows (restitution 0.5 of a 2 m/s impact is 1 m/s,
	// less what the layers above take).
	EXPECT_GT(rise, btScalar(0.1));
	for (int threads : {2, 4})
	{
		const std::vector<btScalar> threaded = run(false, threads);
		ASSERT_EQ(serial.size(), threaded.size());
		EXPECT_EQ(0, std::memcmp(serial.data(), threaded.data(), serial.size() * sizeof(btScalar))) << threads << " threads";
	}
}

TEST(ParallelSolverSetup, BouncingBlockEndsWithTheOneThreadBitsInTheMtWorld)
{
	const std::vector<btScalar> one = run(true, 1);
	for (int threads : {2, 4})
	{
		const std::vector<btScalar> threaded = run(true, threads);
		ASSERT_EQ(one.size(), threaded.size());
		EXPECT_EQ(0, std::memcmp(one.data(), threaded.data(), one.size() * sizeof(btScalar))) << threads << " threads";
	}
}
