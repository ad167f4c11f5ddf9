// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::moveProxiesToFatBoxes makes the dbvt broadphase's tree moves of one step on the task scheduler's
// threads, one task per subtree a few levels below the root, replaying the moves' steps above the subtrees in
// move order afterwards, and undoing what a task did past a move that needs a node inside another subtree. The broadphase must end exactly as with the serial moves
// (caliber::moveProxyToFatBox in order): the dynamic tree node by node (structure, boxes, leaf order), the
// queue of proxies to search, the update counter, and then the pairs in the cache's order, at any thread
// count and with schedulers that run a loop's tasks in any order or split it unevenly.

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtAabbFastPath.h"
#include "BulletCollision/BroadphaseCollision/DbvtTreeSnapshot.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"

namespace
{
struct Lcg
{
	unsigned state = 2024u;
	btScalar next()  // in [0, 1)
	{
		state = state * 1664525u + 1013904223u;
		return btScalar(state >> 8) / btScalar(1 << 24);
	}
};

enum class Motion
{
	None,      // nothing leaves its fat box
	One,       // one proxy a step
	All,       // every proxy, a short way
	Churn,     // most proxies, and proxies destroyed and created between steps
	Teleport,  // most proxies, some of them across the scene (moves that leave their subtrees)
	Sweep,     // the boxes of one half of the scene cross the other half, a few metres a step
	Split,     // four clusters; one cluster's boxes move away from the others, 10 m a step
};

struct Snapshot
{
	std::vector<btVector3> treeBoxes;  // depth first: each node's box
	std::vector<int> treeLeaves;       // depth first: a leaf's proxy id, -1 for an inner node
	std::vector<int> queued;           // the dynamic stage list before the pair search
	std::vector<std::pair<int, int>> pairs;
	int updatesDone = 0;
	caliber::DbvtParallelMoveStats stats;
};

// 700 unit boxes in a 40 m cube, 8 steps of `motion`; after each step's moves the tree and the queue are
// recorded, then the pairs are searched and recorded. parallel: the moves go through
// moveProxiesToFatBoxes (under the scheduler given by threads or userScheduler), else through
// moveProxyToFatBox one by one.
// The moves through caliber::DbvtMoveRound as the collision world makes them: a task per subtree makes its
// leaves' moves in order; the first move in no subtree, or one its task cannot make, ends the round, and
// the rest are made in order.
void moveInRound(btDbvtBroadphase& broadphase, const btAlignedObjectArray<caliber::DbvtProxyMove>& moves,
                 caliber::DbvtParallelMoveStats& stats)
{
	caliber::DbvtMoveRound round;
	int end = 0;
	if (round.begin(broadphase))
	{
		std::vector<int> subtreeOfMove(size_t(moves.size()), -1);
		for (int i = 0; i < moves.size(); ++i)
		{
			const btDbvtNode* node = static_cast<const btDbvtProxy*>(moves[i].proxy)->leaf;
			for (; node && subtreeOfMove[size_t(i)] < 0; node = node->parent)
				for (int k = 0; k < round.numSubtrees(); ++k)
					if (round.subtreeRoot(k) == node) subtreeOfMove[size_t(i)] = k;
		}
		std::atomic<int> bound(moves.size());
		struct Tasks : public btIParallelForBody
		{
			const caliber::DbvtMoveRound* round;
			const btAlignedObjectArray<caliber::DbvtProxyMove>* moves;
			const std::vector<int>* subtreeOfMove;
			std::atomic<int>* bound;
			void lower(int i) const
			{
				int current = bound->load();
				while (i < current && !bound->compare_exchange_weak(current, i))
				{
				}
			}
			void forLoop(int taskBegin, int taskEnd) const override
			{
				for (int task = taskBegin; task < taskEnd; ++task)
				{
					for (int i = 0; i < moves->size() && i < bound->load(); ++i)
					{
						const int subtree = (*subtreeOfMove)[size_t(i)];
						if (subtree < 0)
						{
							lower(i);
							break;
						}
						if (subtree != task) continue;
						const caliber::DbvtProxyMove& move = (*moves)[i];
						if (!round->moveWithin(task, i, move.proxy, move.fatMin, move.fatMax))
						{
							lower(i);
							break;
						}
					}
				}
			}
		} tasks;
		tasks.round = &round;
		tasks.moves = &moves;
		tasks.subtreeOfMove = &subtreeOfMove;
		tasks.bound = &bound;
		btParallelFor(0, round.numSubtrees(), 1, tasks);
		end = round.finish(bound.load(), &stats);
	}
	for (int k = end; k < moves.size(); ++k)
	{
		caliber::moveProxyToFatBox(broadphase, moves[k].proxy, moves[k].fatMin, moves[k].fatMax);
		++stats.movesAlone;
	}
}

std::vector<Snapshot> run(Motion motion, bool parallel, int threads, btITaskScheduler* userScheduler = 0,
                          bool inRound = false)
{
	caliber_test::ScopedTaskScheduler scheduler(userScheduler ? 0 : threads);
	if (userScheduler) btSetTaskScheduler(userScheduler);
	btDbvtBroadphase broadphase;
	Lcg random;
	const btVector3 half(btScalar(0.5), btScalar(0.5), btScalar(0.5));
	const int kBoxes = 700;
	std::vector<btBroadphaseProxy*> proxies;
	std::vector<btVector3> centres;
	for (int i = 0; i < kBoxes; ++i)
	{
		btVector3 centre(random.next() * 40, random.next() * 40, random.next() * 40);
		if (motion == Motion::Split)
		{
			// Four clusters of 8 m cubes along x, 20 m and 200 m apart.
			const int cluster = i % 4;
			centre = centre * btScalar(0.2) + btVector3(btScalar((cluster % 2) * 20 + (cluster / 2) * 200), 0, 0);
		}
		centres.push_back(centre);
		proxies.push_back(broadphase.createProxy(centre - half, centre + half, BOX_SHAPE_PROXYTYPE, 0, 1, -1, 0));
	}
	broadphase.calculateOverlappingPairs(0);
	std::vector<Snapshot> history;
	btAlignedObjectArray<caliber::DbvtProxyMove> moves;
	for (int step = 0; step < 8; ++step)
	{
		if (motion == Motion::Churn && step > 0)
		{
			// Every seventh proxy (shifted each step) is destroyed and a new one made elsewhere.
			for (size_t i = size_t(step) % 7; i < proxies.size(); i += 7)
			{
				broadphase.destroyProxy(proxies[i], 0);
				centres[i] = btVector3(random.next() * 40, random.next() * 40, random.next() * 40);
				proxies[i] = broadphase.createProxy(centres[i] - half, centres[i] + half, BOX_SHAPE_PROXYTYPE, 0, 1,
				                                    -1, 0);
			}
		}
		moves.resize(0);
		Snapshot snapshot;
		const unsigned doneBefore = broadphase.m_updates_done;
		for (size_t i = 0; i < proxies.size(); ++i)
		{
			btVector3 move(0, 0, 0);
			switch (motion)
			{
				case Motion::None:
					move = btVector3(step % 2 ? btScalar(-0.01) : btScalar(0.01), 0, 0);  // within the 0.05 m margin
					break;
				case Motion::One:
					if (i == size_t(step) * 37 % proxies.size()) move = btVector3(0, btScalar(-2), 0);
					break;
				case Motion::All:
					move = btVector3(0, btScalar(-0.3), 0);
					break;
				case Motion::Sweep:
					if (i % 2 == 0) move = btVector3(btScalar(4), random.next() - btScalar(0.5), 0);
					break;
				case Motion::Split:
					if (i % 4 == 1) move = btVector3(0, btScalar(10), 0);
					break;
				case Motion::Churn:
				case Motion::Teleport:
					move = btVector3(random.next() - btScalar(0.5), random.next() - btScalar(0.5),
					                 random.next() - btScalar(0.5));
					if (motion == Motion::Teleport && i % 23 == 0)
						move = btVector3(random.next() * 40, random.next() * 40, random.next() * 40) - centres[i];
					break;
			}
			centres[i] += move;
			caliber::DbvtProxyMove entry;
			if (!caliber::storeAabbOrFatBox(broadphase, proxies[i], centres[i] - half, centres[i] + half, entry.fatMin,
			                                entry.fatMax))
				continue;
			entry.proxy = proxies[i];
			moves.push_back(entry);
		}
		if (inRound)
		{
			moveInRound(broadphase, moves, snapshot.stats);
		}
		else if (parallel)
		{
			caliber::moveProxiesToFatBoxes(broadphase, moves.size() ? &moves[0] : 0, moves.size(), &snapshot.stats);
		}
		else
		{
			for (int k = 0; k < moves.size(); ++k)
				caliber::moveProxyToFatBox(broadphase, moves[k].proxy, moves[k].fatMin, moves[k].fatMax);
		}
		snapshot.updatesDone = int(broadphase.m_updates_done - doneBefore);
		dbvt_test::snapshotTree(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_root, snapshot.treeBoxes,
		                        snapshot.treeLeaves);
		for (const btDbvtProxy* proxy = broadphase.m_stageRoots[btDbvtBroadphase::DYNAMIC_SET]; proxy;
		     proxy = proxy->links[1])
			snapshot.queued.push_back(proxy->m_uniqueId);
		broadphase.calculateOverlappingPairs(0);
		const btBroadphasePairArray& pairs = broadphase.getOverlappingPairCache()->getOverlappingPairArray();
		for (int k = 0; k < pairs.size(); ++k)
			snapshot.pairs.push_back(std::make_pair(pairs[k].m_pProxy0->m_uniqueId, pairs[k].m_pProxy1->m_uniqueId));
		history.push_back(snapshot);
	}
	for (btBroadphaseProxy* proxy : proxies) broadphase.destroyProxy(proxy, 0);
	if (userScheduler) btSetTaskScheduler(0);
	return history;
}

// Sums a history's statistics.
caliber::DbvtParallelMoveStats total(const std::vector<Snapshot>& history)
{
	caliber::DbvtParallelMoveStats sum;
	for (const Snapshot& s : history)
	{
		sum.rounds += s.stats.rounds;
		sum.movesOnThreads += s.stats.movesOnThreads;
		sum.movesUndone += s.stats.movesUndone;
		sum.movesAlone += s.stats.movesAlone;
		sum.topStops += s.stats.topStops;
	}
	return sum;
}

void expectSame(const std::vector<Snapshot>& serial, const std::vector<Snapshot>& parallel)
{
	ASSERT_EQ(serial.size(), parallel.size());
	for (size_t step = 0; step < serial.size(); ++step)
	{
		SCOPED_TRACE(testing::Message() << "step " << step);
		EXPECT_TRUE(serial[step].treeLeaves == parallel[step].treeLeaves);
		EXPECT_TRUE(serial[step].treeBoxes == parallel[step].treeBoxes);
		EXPECT_TRUE(serial[step].queued == parallel[step].queued);
		EXPECT_TRUE(serial[step].pairs == parallel[step].pairs);
		EXPECT_EQ(serial[step].updatesDone, parallel[step].updatesDone);
	}
}

// The serial moves against moveProxiesToFatBoxes at 1, 2 and 3 threads and under the two user schedulers;
// returns the statistics of the last-first scheduler's run (and adds the top stops of every parallel run
// to allRuns).
caliber::DbvtParallelMoveStats checkEveryScheduler(Motion motion, caliber::DbvtParallelMoveStats* allRuns = 0)
{
	const std::vector<Snapshot> serial = run(motion, false, 0);
	expectSame(serial, run(motion, true, 1));
	const std::vector<Snapshot> two = run(motion, true, 2);
	expectSame(serial, two);
	const std::vector<Snapshot> three = run(motion, true, 3);
	expectSame(serial, three);
	caliber_test::UnevenSplitScheduler uneven;
	const std::vector<Snapshot> unevenRun = run(motion, true, 0, &uneven);
	expectSame(serial, unevenRun);
	caliber_test::LastFirstScheduler lastFirst;
	const std::vector<Snapshot> reversed = run(motion, true, 0, &lastFirst);
	expectSame(serial, reversed);
	if (allRuns)
	{
		for (const std::vector<Snapshot>* history : {&two, &three, &unevenRun, &reversed})
			allRuns->topStops += total(*history).topStops;
	}
	return total(reversed);
}
}  // namespace

TEST(DbvtParallelMoves, ManyMovesEndAsTheSerialMovesAtAnyThreadCountAndScheduler)
{
	const caliber::DbvtParallelMoveStats stats = checkEveryScheduler(Motion::All);
	// 700 proxies moved 0.3 m down each step leave their fat boxes (margin 0.05 m) at least every other step.
	EXPECT_GT(stats.rounds, 0);
	EXPECT_GT(stats.movesOnThreads, 700);
	// Every subtree's lowest leaves fall out of its box: a round ending at each move that shrank or grew a
	// subtree's root made 133 rounds (and 129 moves alone) in these 8 steps under this scheduler; with those
	// steps replayed above the subtrees, a round ends only at a move that needs a node outside its subtree
	// (21 rounds).
	EXPECT_LT(stats.rounds, 40);
}

TEST(DbvtParallelMoves, MovesAcrossTheSceneAreUndoneAndMadeAloneInTheirPlace)
{
	caliber::DbvtParallelMoveStats allRuns;
	const caliber::DbvtParallelMoveStats stats = checkEveryScheduler(Motion::Teleport, &allRuns);
	// Some moves across the scene grow their subtree's root so much that the serial rotation above the
	// subtrees would swap a node out of a subtree: the replay stops there and the move is made alone.
	EXPECT_GT(allRuns.topStops, 0);
	// A proxy sent across the 40 m scene lands outside its subtree's box: its move grows nodes above the
	// subtree, so it runs alone; with the tasks run last to first, the later tasks' moves past it are undone.
	EXPECT_GT(stats.rounds, 8);
	EXPECT_GT(stats.movesAlone, 8);
	EXPECT_GT(stats.movesUndone, 0);
}

TEST(DbvtParallelMoves, HalfTheSceneCrossingTheOtherHalfEndsAsTheSerialMoves)
{
	const caliber::DbvtParallelMoveStats stats = checkEveryScheduler(Motion::Sweep);
	EXPECT_GT(stats.movesOnThreads, 0);
}

TEST(DbvtParallelMoves, AClusterLeavingTheOthersEndsAsTheSerialMoves)
{
	// A cluster's subtree grows by 10 m a step: its growth goes above the subtrees every step, where the
	// rotations may reorder the nodes above the subtrees.
	const caliber::DbvtParallelMoveStats stats = checkEveryScheduler(Motion::Split);
	EXPECT_GT(stats.movesOnThreads, 0);
}

TEST(DbvtParallelMoves, ProxiesDestroyedAndCreatedBetweenStepsEndAsTheSerialMoves)
{
	const caliber::DbvtParallelMoveStats stats = checkEveryScheduler(Motion::Churn);
	EXPECT_GT(stats.movesOnThreads, 0);
}

TEST(DbvtParallelMoves, NoMoveOrOneMoveAStepIsMadeInOrder)
{
	const std::vector<Snapshot> none = run(Motion::None, true, 2);
	for (const Snapshot& step : none)
	{
		EXPECT_EQ(step.updatesDone, 0);
		EXPECT_TRUE(step.queued.empty());
	}
	expectSame(run(Motion::None, false, 0), none);
	const caliber::DbvtParallelMoveStats one = checkEveryScheduler(Motion::One);
	// Fewer moves than a round needs (32) run in order on the calling thread.
	EXPECT_EQ(one.rounds, 0);
	EXPECT_EQ(one.movesAlone, 8);
}

// caliber::DbvtMoveRound (the collision world's tree moves inside its box loop, when
// caliber::setSubtreeMovesInWorld is on): the same tree, queue, counters and pairs as the serial moves at
// 1, 2 and 3 threads and under the two odd schedulers, for every motion.
TEST(DbvtParallelMoves, MovesOfARoundInsideALoopEndAsTheSerialMoves)
{
	for (Motion motion : {Motion::None, Motion::One, Motion::All, Motion::Churn, Motion::Teleport, Motion::Sweep,
	                      Motion::Split})
	{
		SCOPED_TRACE(testing::Message() << "motion " << int(motion));
		const std::vector<Snapshot> serial = run(motion, false, 0);
		for (int threads : {1, 2, 3}) expectSame(serial, run(motion, false, threads, 0, true));
		caliber_test::UnevenSplitScheduler uneven;
		expectSame(serial, run(motion, false, 0, &uneven, true));
		caliber_test::LastFirstScheduler lastFirst;
		const std::vector<Snapshot> reversed = run(motion, false, 0, &lastFirst, true);
		expectSame(serial, reversed);
		if (motion == Motion::All)
		{
			// Some of the 700 falling boxes' moves are kept from the rounds (a round's first stop sends the rest of
			// the step's moves to the calling thread, in this small tree about six moves in seven).
			const caliber::DbvtParallelMoveStats stats = total(reversed);
			EXPECT_GT(stats.movesOnThreads, 0);
			EXPECT_GT(stats.rounds, 0);
		}
	}
}
