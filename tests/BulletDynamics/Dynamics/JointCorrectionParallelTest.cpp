// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The joint position correction sweeps the joints of short articulations island by island on the task
// scheduler's threads; each island's joints keep their order, so the world ends with the bits of the
// one-thread sweep at any thread count.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// 24 separate swinging chains of 5 boxes on ball joints (120 joints, each chain its own island and too
// short for the exact tree solve), the first box of each hung from the world, released sideways.
struct Chains
{
	Chains()
	{
		config.reset(new btDefaultCollisionConfiguration());
		dispatcher.reset(new btCollisionDispatcher(config.get()));
		solver.reset(new btSequentialImpulseConstraintSolver());
		broadphase.reset(new btDbvtBroadphase());
		world.reset(new btDiscreteDynamicsWorld(dispatcher.get(), broadphase.get(), solver.get(), config.get()));
		world->setGravity(btVector3(0, -10, 0));
		box.reset(new btBoxShape(btVector3(btScalar(0.2), btScalar(0.2), btScalar(0.2))));
		btVector3 inertia;
		box->calculateLocalInertia(1, inertia);
		for (int chain = 0; chain < 24; ++chain)
		{
			btRigidBody* previous = 0;
			for (int link = 0; link < 5; ++link)
			{
				btRigidBody::btRigidBodyConstructionInfo info(1, 0, box.get(), inertia);
				// Links laid out sideways, so the chain swings down under gravity.
				info.m_startWorldTransform.setOrigin(
				    btVector3(btScalar(link) * btScalar(0.5), 10, btScalar(chain) * btScalar(2)));
				bodies.emplace_back(new btRigidBody(info));
				btRigidBody* body = bodies.back().get();
				body->setActivationState(DISABLE_DEACTIVATION);
				world->addRigidBody(body);
				if (!previous)
					joints.emplace_back(new btPoint2PointConstraint(*body, btVector3(btScalar(-0.25), 0, 0)));
				else
					joints.emplace_back(new btPoint2PointConstraint(*previous, *body, btVector3(btScalar(0.25), 0, 0),
					                                                btVector3(btScalar(-0.25), 0, 0)));
				world->addConstraint(joints.back().get(), true);
				previous = body;
			}
		}
	}
	~Chains()
	{
		for (auto& joint : joints) world->removeConstraint(joint.get());
		for (auto& body : bodies) world->removeRigidBody(body.get());
	}
	std::vector<btScalar> state() const { return caliber_test::bodyStateBits(bodies); }
	// The largest gap between the pivots of a joint.
	btScalar largestPivotGap() const
	{
		btScalar largest = 0;
		for (const auto& joint : joints)
		{
			const btVector3 a = joint->getRigidBodyA().getWorldTransform() * joint->getPivotInA();
			const btVector3 b = joint->getRigidBodyB().getWorldTransform() * joint->getPivotInB();
			largest = btMax(largest, (a - b).length());
		}
		return largest;
	}

	std::unique_ptr<btDefaultCollisionConfiguration> config;
	std::unique_ptr<btCollisionDispatcher> dispatcher;
	std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
	std::unique_ptr<btBroadphaseInterface> broadphase;
	std::unique_ptr<btDiscreteDynamicsWorld> world;
	std::unique_ptr<btCollisionShape> box;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	std::vector<std::unique_ptr<btPoint2PointConstraint>> joints;
};

std::vector<btScalar> run(int threads, btScalar* gap = nullptr)
{
	caliber_test::ScopedTaskScheduler scheduler(threads);
	std::vector<btScalar> bits;
	{
		Chains chains;
		for (int i = 0; i < 60; ++i) chains.world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
		if (gap) *gap = chains.largestPivotGap();
		bits = chains.state();
	}
	return bits;
}
}  // namespace

TEST(JointCorrectionParallel, SwingingChainsEndWithTheOneThreadBitsAtAnyThreadCount)
{
	btScalar gap = 1;
	const std::vector<btScalar> serial = run(0, &gap);
	// The correction holds the chains together: after a second of swinging, pivots within 1 mm (a
	// step's worth of the swing's speed, about 3 m/s, would open them by 5 cm without it).
	EXPECT_LT(gap, btScalar(1e-3));
	for (int threads : {1, 2, 4})
	{
		const std::vector<btScalar> threaded = run(threads);
		ASSERT_EQ(serial.size(), threaded.size());
		EXPECT_EQ(0, std::memcmp(serial.data(), threaded.data(), serial.size() * sizeof(btScalar))) << threads << " threads";
	}
}
