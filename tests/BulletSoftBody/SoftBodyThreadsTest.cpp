// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The soft-body stages on the task scheduler (docs/soft-bodies.md, "Threads"): the bodies' prediction and
// velocity update run one body per task, a large body's node loops and node contact search in chunks, its
// link sweeps in blocks of one colour at a time, and the cluster contacts with rigid shapes a cluster per
// task; the results are the same bits at any thread count.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "BulletSoftBody/btSoftBodyClusters.h"
#include "LinearMath/btThreads.h"
#include "SoftBodyTestUtil.h"

using caliber_test::hashNodes;
using caliber_test::SoftTestWorld;

namespace
{
// The sanitizers run the scene 25 to 50 times slower: fewer steps there keep their stages short (every
// stage above still runs from the first steps: the box touches the cloth, the clusters the ground).
#if defined(__SANITIZE_THREAD__) || defined(__SANITIZE_ADDRESS__)
const int kSteps = 10;
#else
const int kSteps = 40;
#endif

// A scene with a large pinned cloth (2500 nodes: its node loops and contact search are split in chunks of
// 1024, its 7000 links in blocks of 1024 whose colours hold several; btSoftBodyLinkColours.h), a box
// falling on it, three gas balls, a rope and two balls of clusters, stepped kSteps times on the current scheduler: each
// soft body's node positions, hashed.
std::vector<uint64_t> runScene()
{
	SoftTestWorld w;
	w.addGround();
	std::vector<btSoftBody*> bodies;
	btSoftBody* cloth =
	    w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-3, 4, -3), btVector3(3, 4, -3),
	                                             btVector3(-3, 4, 3), btVector3(3, 4, 3), 50, 50, 1 + 2 + 4 + 8, true));
	cloth->setTotalMass(2);
	cloth->m_cfg.piterations = 4;
	bodies.push_back(cloth);
	// Just above the cloth: its node contacts with the cloth are searched in chunks from the first steps.
	w.addRigid(1, btVector3(0.2, btScalar(4.45), 0.1), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
	for (int i = 0; i < 3; ++i)
	{
		btSoftBody* ball = w.addSoft(btSoftBodyHelpers::CreateEllipsoid(
		    w.info(), btVector3(btScalar(5 + 1.2 * i), btScalar(1 + 1.5 * i), 0), btVector3(0.5, 0.5, 0.5), 96));
		ball->setTotalMass(1, true);
		ball->m_cfg.kPR = 100;
		ball->m_cfg.collisions |= btSoftBody::fCollision::VF_SS;
		bodies.push_back(ball);
	}
	btSoftBody* rope =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(-6, 5, 0), btVector3(-4, 5, 0), 20, 1));
	rope->setTotalMass(btScalar(0.5));
	bodies.push_back(rope);
	// Two balls of 16 clusters, one dropped on the other (CL_RS, CL_SS): the clusters' contacts with the
	// ground are found on the task scheduler, a cluster per task.
	for (int i = 0; i < 2; ++i)
	{
		btSoftBody* ball = w.addSoft(btSoftBodyHelpers::CreateEllipsoid(
		    w.info(), btVector3(btScalar(8 + 0.3 * i), btScalar(1.2 + 2.2 * i), 4), btVector3(1, 1, 1), 128));
		ball->setTotalMass(1, true);
		ball->m_cfg.kPR = 100;
		ball->m_cfg.collisions = btSoftBody::fCollision::CL_RS | btSoftBody::fCollision::CL_SS;
		ball->generateClusters(16);
		bodies.push_back(ball);
	}
	w.step(kSteps);
	// The searches ran: the cloth's node contacts (with the box) and the lower ball's cluster contacts (with
	// the ground) of the last step.
	EXPECT_GT(cloth->m_rcontacts.size(), 0);
	EXPECT_GT(caliber::clusterState(*bodies.back()).contacts.size() +
	              caliber::clusterState(*bodies[bodies.size() - 2]).contacts.size(),
	          0);
	std::vector<uint64_t> hashes;
	for (const btSoftBody* b : bodies) hashes.push_back(hashNodes(*b));
	return hashes;
}
}  // namespace

TEST(SoftBodyThreads, NodePositionsHaveTheSameBitsAtOneTwoAndFourThreads)
{
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	btSetTaskScheduler(btGetSequentialTaskScheduler());
	const std::vector<uint64_t> reference = runScene();
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	ASSERT_NE(pool.get(), nullptr);
	for (int threads : {1, 2, 4})
	{
		pool->setNumThreads(threads);
		ASSERT_EQ(pool->getNumThreads(), btMin(threads, pool->getMaxNumThreads()));
		btSetTaskScheduler(pool.get());
		EXPECT_EQ(runScene(), reference) << threads << " threads";
		btSetTaskScheduler(0);
	}
#else
	// A single-threaded library has no thread pool: the stages run on the calling thread, with the same
	// bits with the sequential scheduler as with none.
	btSetTaskScheduler(0);
	const std::vector<uint64_t> reference = runScene();
	btSetTaskScheduler(btGetSequentialTaskScheduler());
	EXPECT_EQ(runScene(), reference);
	btSetTaskScheduler(0);
#endif
}
