// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The joint position correction sweeps the joints of short articulations island by island on the task
// scheduler's threads; each island's joints keep their order, so the world ends with the bits of the
// one-thread sweep at any thread count.

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "DynamicsWorldTestUtil.h"
#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"

namespace
{
// 24 separate swinging chains of 5 boxes on ball joints (120 joints, each chain its own island and too
// short for the exact tree solve), the first box of each hung from the world, released sideways.
struct Chains
{
	Chains()
	{
		btBoxShape* box = scene.shape<btBoxShape>(btVector3(btScalar(0.2), btScalar(0.2), btScalar(0.2)));
		for (int chain = 0; chain < 24; ++chain)
		{
			btRigidBody* previous = 0;
			for (int link = 0; link < 5; ++link)
			{
				// Links laid out sideways, so the chain swings down under gravity.
				btRigidBody* body = scene.addBody(
				    box, 1, btVector3(btScalar(link) * btScalar(0.5), 10, btScalar(chain) * btScalar(2)), false);
				body->setActivationState(DISABLE_DEACTIVATION);
				if (!previous)
					joints.push_back(
					    scene.addJoint<btPoint2PointConstraint>(true, *body, btVector3(btScalar(-0.25), 0, 0)));
				else
					joints.push_back(scene.addJoint<btPoint2PointConstraint>(
					    true, *previous, *body, btVector3(btScalar(0.25), 0, 0), btVector3(btScalar(-0.25), 0, 0)));
				previous = body;
			}
		}
	}
	std::vector<btScalar> state() const { return caliber_test::bodyStateBits(scene.bodies()); }
	// The largest gap between the pivots of a joint.
	btScalar largestPivotGap() const
	{
		btScalar largest = 0;
		for (const btPoint2PointConstraint* joint : joints)
		{
			const btVector3 a = joint->getRigidBodyA().getWorldTransform() * joint->getPivotInA();
			const btVector3 b = joint->getRigidBodyB().getWorldTransform() * joint->getPivotInB();
			largest = btMax(largest, (a - b).length());
		}
		return largest;
	}

	caliber_test::TestWorld scene;
	std::vector<btPoint2PointConstraint*> joints;
};

std::vector<btScalar> run(int threads, btScalar* gap = nullptr)
{
	caliber_test::ScopedTaskScheduler scheduler(threads);
	std::vector<btScalar> bits;
	{
		Chains chains;
		chains.scene.run(60);
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
		EXPECT_EQ(0, std::memcmp(serial.data(), threaded.data(), serial.size() * sizeof(btScalar)))
		    << threads << " threads";
	}
}
