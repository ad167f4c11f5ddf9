// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The island stage's per-item passes on the task scheduler's threads (eleventh session): the union
// pass's reading of the broadphase pairs (btSimulationIslandManager::findUnions), the joints' unions
// (calculateSimulationIslands), the joints' islands (caliber::sortConstraintsByIsland) and the joint
// correction's choice of joints and their islands (joint_correction::selectJoints). Each item writes its
// own slot and the calling thread reads the slots in order, so a world must end with the bits of a world
// without a scheduler, at any thread count and with a scheduler that cuts the loops unevenly. The scenes
// are large enough for every pass to take the threads (at least 1024 pairs and 512 joints).

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h"
#include "DynamicsWorldTestUtil.h"
#include "TestThreadsUtil.h"
#include "LinearMath/btThreads.h"

using caliber_test::TestWorld;

namespace
{
struct Outcome
{
	std::vector<btScalar> bits;
	std::vector<int> states;  // every body's activation state
	int pairs = 0;            // the broadphase pairs at the end
	int manifolds = 0;        // the dispatcher's manifolds at the end
	int joints = 0;
};

// Chains of four boxes joined by ball joints, lying on the ground in rows close enough that neighbouring
// chains touch (their islands merge through contacts) or far enough apart that they stay alone. Every
// tenth chain hangs from a static post by a joint to it, every fifteenth is pushed by a kinematic box that
// slides along the ground. At step 20 some joints are disabled and some removed; at step 75 a body is thrown
// into a chain that has fallen asleep, waking its island.
// Without pushers, no kinematic box: buildIslands' manifold filter then stays on the threads (a kinematic body
// that wakes another sends it to the serial loop).
Outcome runChains(btITaskScheduler* scheduler, int threads, bool multithreaded, bool oneIsland, bool pushers)
{
	btSetTaskScheduler(scheduler);
	if (scheduler && threads > 0) scheduler->setNumThreads(threads);
	// Bodies at rest may sleep after half a second instead of two, so that islands fall asleep in a short
	// run (which matters under ThreadSanitizer); restored below.
	const btScalar deactivationTime = gDeactivationTime;
	gDeactivationTime = btScalar(0.5);
	Outcome outcome;
	{
		std::unique_ptr<TestWorld> w(multithreaded ? new TestWorld(TestWorld::Multithreaded(), BT_MAX_THREAD_COUNT)
		                                           : new TestWorld());
		w->addGround();
		btCollisionShape* box = w->shape<btBoxShape>(btVector3(btScalar(0.2), btScalar(0.2), btScalar(0.2)));
		btCollisionShape* post = w->shape<btBoxShape>(btVector3(btScalar(0.1), btScalar(1), btScalar(0.1)));
		std::vector<btTypedConstraint*> joints;
		std::vector<btRigidBody*> kinematic;
		// Without pushers, 270 chains: enough manifolds (at least 1024) for the manifold passes on the threads.
		const int numChains = oneIsland ? 1 : (pushers ? 180 : 270);
		const int linksPerChain = oneIsland ? 540 : 4;
		for (int chain = 0; chain < numChains; ++chain)
		{
			// Rows 1 m apart along z; chains along x, 2.0 m long, every other row's chains end to end.
			const btScalar z = oneIsland ? btScalar(-30) : btScalar(chain / 12) * btScalar(1.2) - btScalar(9);
			const btScalar x0 = oneIsland ? btScalar(-45) : btScalar(chain % 12) * ((chain / 12) % 2 ? btScalar(1.6) : btScalar(2.5)) - btScalar(18);
			btRigidBody* previous = 0;
			for (int link = 0; link < linksPerChain; ++link)
			{
				const btScalar x = x0 + btScalar(link) * btScalar(oneIsland ? 0.16 : 0.42);
				const btScalar y = oneIsland ? btScalar(0.25) + btScalar(link % 2) * btScalar(0.1) : btScalar(0.21);
				btRigidBody* body = w->addBody(box, 1, btVector3(x, y, z), link % 3 != 0);
				if (previous)
				{
					const btVector3 pivot((previous->getWorldTransform().getOrigin() + body->getWorldTransform().getOrigin()) *
					                      btScalar(0.5));
					joints.push_back(w->addJoint<btPoint2PointConstraint>(
					    true, *previous, *body, previous->getWorldTransform().inverse() * pivot,
					    body->getWorldTransform().inverse() * pivot));
				}
				previous = body;
			}
			if (!oneIsland && chain % 10 == 3)
			{
				btRigidBody* fixed = w->addBody(post, 0, previous->getWorldTransform().getOrigin() + btVector3(0, 1.5, 0));
				const btVector3 pivot = previous->getWorldTransform().getOrigin() + btVector3(0, btScalar(0.3), 0);
				joints.push_back(w->addJoint<btPoint2PointConstraint>(true, *previous, *fixed,
				                                                      previous->getWorldTransform().inverse() * pivot,
				                                                      fixed->getWorldTransform().inverse() * pivot));
			}
			if (pushers && !oneIsland && chain % 15 == 7)
			{
				btRigidBody* pusher = w->addBody(box, 0, previous->getWorldTransform().getOrigin() + btVector3(0, 0, btScalar(-0.5)));
				pusher->setCollisionFlags(pusher->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
				pusher->setActivationState(DISABLE_DEACTIVATION);
				kinematic.push_back(pusher);
			}
		}
		std::vector<btTypedConstraint*> removed;
		const int steps = oneIsland ? 30 : 90;
		for (int step = 0; step < steps; ++step)
		{
			// The kinematic boxes slide into their chains for half a second, then stop.
			for (size_t k = 0; k < kinematic.size(); ++k)
			{
				btTransform pose = kinematic[k]->getWorldTransform();
				if (step < 30) pose.getOrigin() += btVector3(0, 0, btScalar(0.01));
				kinematic[k]->getMotionState()->setWorldTransform(pose);
			}
			if (step == 20)
			{
				for (size_t j = 5; j < joints.size(); j += 23) joints[j]->setEnabled(false);
				for (size_t j = 11; j < joints.size(); j += 31)
				{
					w->world()->removeConstraint(joints[j]);
					removed.push_back(joints[j]);
				}
			}
			// By now resting chains are asleep (0.5 s at rest); a thrown body wakes the first chain's island.
			if (step == 75) w->bodies()[1]->setLinearVelocity(btVector3(0, btScalar(4), 0)), w->bodies()[1]->activate();
			w->run(1);
		}
		for (const btRigidBody* body : w->bodies()) outcome.states.push_back(body->getActivationState());
		outcome.bits = caliber_test::bodyStateBits(w->bodies());
		outcome.pairs = w->world()->getPairCache()->getNumOverlappingPairs();
		outcome.manifolds = w->world()->getDispatcher()->getNumManifolds();
		outcome.joints = w->world()->getNumConstraints();
		for (btTypedConstraint* joint : removed) w->world()->addConstraint(joint, true);
	}
	gDeactivationTime = deactivationTime;
	btSetTaskScheduler(0);
	return outcome;
}

void expectSameAtAnyThreadCount(bool multithreaded, bool oneIsland, bool pushers = true)
{
	const Outcome reference = runChains(0, 0, multithreaded, oneIsland, pushers);
	// Large enough for every pass to run on the threads (else the test would compare the serial pass
	// with itself).
	ASSERT_GE(reference.pairs, 1024);
	ASSERT_GE(reference.joints, 512);
	if (!oneIsland)
	{
		int sleeping = 0, awake = 0;
		for (int state : reference.states)
		{
			if (state == ISLAND_SLEEPING) ++sleeping;
			if (state == ACTIVE_TAG) ++awake;
		}
		ASSERT_GT(sleeping, 0) << "some islands must sleep";
		ASSERT_GT(awake, 0) << "and some be awake";
	}
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	caliber_test::UnevenSplitScheduler uneven;
	for (int threads : {1, 2, 3, -1})  // -1: the uneven scheduler
	{
		if (threads > 0 && !pool) continue;
		btITaskScheduler* scheduler = threads > 0 ? pool.get() : &uneven;
		const Outcome run = runChains(scheduler, threads, multithreaded, oneIsland, pushers);
		ASSERT_EQ(run.bits.size(), reference.bits.size());
		EXPECT_TRUE(run.bits == reference.bits) << "threads " << threads << (multithreaded ? ", Mt world" : "");
		EXPECT_TRUE(run.states == reference.states) << "threads " << threads;
		EXPECT_EQ(run.pairs, reference.pairs);
	}
}
}  // namespace

TEST(IslandStageThreads, ChainsWithStaticKinematicSleepingAndRemovedJointsEndTheSameAtAnyThreadCount)
{
	expectSameAtAnyThreadCount(false, false);
}

TEST(IslandStageThreads, ChainsEndTheSameAtAnyThreadCountInTheMtWorld) { expectSameAtAnyThreadCount(true, false); }

TEST(IslandStageThreads, OneIslandOfManyJointsEndsTheSameAtAnyThreadCount) { expectSameAtAnyThreadCount(true, true); }

// buildIslands' manifold filter and processIslands' grouping of the manifolds on the threads (at least 1024
// manifolds, no kinematic body) and the joints' sort on the threads (at least 512 joints). (sortIslands on the
// threads needs 1024 elements: UnionFindTest.)
TEST(IslandStageThreads, ChainsWithoutKinematicBodiesEndTheSameAtAnyThreadCountInTheMtWorld)
{
	const Outcome reference = runChains(0, 0, true, false, false);
	ASSERT_GE(reference.manifolds, 1024) << "too few manifolds for the manifold passes on the threads";
	expectSameAtAnyThreadCount(true, false, false);
}

TEST(IslandStageThreads, AnEmptyWorldStepsWithThreads)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	if (!pool) GTEST_SKIP() << "a library without threads";
	btSetTaskScheduler(pool.get());
	pool->setNumThreads(2);
	{
		TestWorld w;
		w.run(3);
		EXPECT_EQ(w.world()->getNumCollisionObjects(), 0);
		TestWorld mt(TestWorld::Multithreaded(), BT_MAX_THREAD_COUNT);
		mt.run(3);
		EXPECT_EQ(mt.world()->getNumCollisionObjects(), 0);
	}
	btSetTaskScheduler(0);
}
