// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Stacks that must stand, a pyramid that must settle and fall asleep, and waking.

#include <gtest/gtest.h>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kHalf = btScalar(0.5);

// A tower of n unit cubes standing on the ground, stepped for seconds; returns the largest horizontal
// drift of any box from its starting column and checks each box's height.
btScalar towerDrift(int n, btScalar seconds, btScalar* worstHeightError, int extraSolverMode = 0)
{
	TestWorld w;
	w.world()->getSolverInfo().m_solverMode |= extraSolverMode;
	w.addGround(btScalar(0.8), btScalar(0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(kHalf, kHalf, kHalf));
	std::vector<btRigidBody*> tower;
	for (int i = 0; i < n; ++i) tower.push_back(w.addBody(box, 1, btVector3(0, kHalf + i, 0)));
	w.run(int(seconds * 60));
	btScalar drift = 0;
	btScalar heightError = 0;
	for (int i = 0; i < n; ++i)
	{
		const btVector3 p = tower[i]->getCenterOfMassPosition();
		drift = btMax(drift, btSqrt(p.x() * p.x() + p.z() * p.z()));
		heightError = btMax(heightError, btFabs(p.y() - (kHalf + i)));
	}
	*worstHeightError = heightError;
	return drift;
}
}  // namespace

TEST(StackingAndSleeping, TowerOfTenBoxesStandsForTwentySeconds)
{
	// Standing means every box stays in its column (drift well under a tenth of its size) and at its
	// height: the contacts of a tower compress by at most the solver's slop per contact, a few mm in all.
	btScalar heightError = 0;
	const btScalar drift = towerDrift(10, 20, &heightError);
	EXPECT_LT(drift, btScalar(0.1));
	EXPECT_LT(heightError, btScalar(0.05));
}

TEST(StackingAndSleeping, TowerOfTenBoxesStandsWithTwoFrictionDirectionsToo)
{
	btScalar heightError = 0;
	const btScalar drift = towerDrift(10, 20, &heightError, SOLVER_USE_2_FRICTION_DIRECTIONS);
	EXPECT_LT(drift, btScalar(0.1));
	EXPECT_LT(heightError, btScalar(0.05));
}

TEST(StackingAndSleeping, TowerOfTwentyBoxesStandsForTwentySeconds)
{
	btScalar heightError = 0;
	const btScalar drift = towerDrift(20, 20, &heightError);
	EXPECT_LT(drift, btScalar(0.1));
	EXPECT_LT(heightError, btScalar(0.1));
}

TEST(StackingAndSleeping, PyramidOfTenLevelsSettlesAndSleeps)
{
	TestWorld w;
	w.addGround(btScalar(0.8), btScalar(0));
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(kHalf, kHalf, kHalf));
	std::vector<btRigidBody*> boxes;
	std::vector<btVector3> start;
	const int levels = 10;
	for (int level = 0; level < levels; ++level)
	{
		for (int i = 0; i < levels - level; ++i)
		{
			const btVector3 p(btScalar(1.05) * (i - (levels - level - 1) * btScalar(0.5)), kHalf + level, 0);
			boxes.push_back(w.addBody(box, 1, p));
			start.push_back(p);
		}
	}
	int sleepingAfter = -1;
	for (int step = 0; step < 600 && sleepingAfter < 0; ++step)
	{
		w.run(1);
		bool allAsleep = true;
		for (btRigidBody* b : boxes) allAsleep = allAsleep && b->getActivationState() == ISLAND_SLEEPING;
		if (allAsleep) sleepingAfter = step;
	}
	ASSERT_GE(sleepingAfter, 0) << "the pyramid did not fall asleep within 10 s";
	// Asleep at rest, in shape: no box has slid sideways by a tenth of its size (the edge boxes of the upper
	// levels creep a few centimetres while the contacts below them settle), and none has sunk by more
	// than a tenth either.
	for (size_t i = 0; i < boxes.size(); ++i)
	{
		const btVector3 moved = boxes[i]->getCenterOfMassPosition() - start[i];
		EXPECT_LT(btSqrt(moved.x() * moved.x() + moved.z() * moved.z()), btScalar(0.1)) << "box " << i;
		EXPECT_LT(btFabs(moved.y()), btScalar(0.1)) << "box " << i;
		EXPECT_TRUE(boxes[i]->getLinearVelocity().fuzzyZero());
	}
	// Sleeping bodies do not move while the world steps.
	const btVector3 before = boxes.back()->getCenterOfMassPosition();
	w.run(60);
	EXPECT_EQ(boxes.back()->getCenterOfMassPosition(), before);
}

TEST(StackingAndSleeping, SleepingBodyWakesWhenHitAndWhenActivated)
{
	TestWorld w;
	w.addGround(btScalar(0.8), btScalar(0));
	btRigidBody* resting = w.addBody(w.shape<btBoxShape>(btVector3(kHalf, kHalf, kHalf)), 1, btVector3(0, kHalf, 0));
	w.run(240);
	ASSERT_EQ(resting->getActivationState(), ISLAND_SLEEPING);

	// A ball dropped on it wakes it.
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.3)), 5, btVector3(btScalar(0.3), 3, 0));
	bool woke = false;
	for (int i = 0; i < 120 && !woke; ++i)
	{
		w.run(1);
		woke = resting->getActivationState() != ISLAND_SLEEPING;
	}
	EXPECT_TRUE(woke);
	(void)ball;

	// Asleep again, an impulse after activate() moves it.
	w.run(400);
	w.world()->removeRigidBody(ball);
	w.run(300);
	ASSERT_EQ(resting->getActivationState(), ISLAND_SLEEPING);
	resting->activate();
	resting->applyCentralImpulse(btVector3(0, 5, 0));
	w.run(5);
	EXPECT_GT(resting->getCenterOfMassPosition().y(), kHalf + btScalar(0.1));
}

TEST(StackingAndSleeping, DisableDeactivationKeepsABodyAwake)
{
	TestWorld w;
	w.addGround();
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(kHalf, kHalf, kHalf)), 1, btVector3(0, kHalf, 0));
	body->setActivationState(DISABLE_DEACTIVATION);
	w.run(300);
	EXPECT_EQ(body->getActivationState(), DISABLE_DEACTIVATION);
}
