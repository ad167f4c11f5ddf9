// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::moveProxiesToFatBoxes refits the dynamic tree on the task scheduler's threads, subtree by subtree,
// and must leave the broadphase exactly as setAabb called for each proxy in order: every node of the tree
// (shape, volumes, which leaf where), the order of the queued proxies, the counters and, after the pair
// search, the pairs in their order.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtAabbFastPath.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "TestThreadsUtil.h"

namespace
{
struct Lcg
{
	unsigned state = 777u;
	btScalar next()  // in [0, 1)
	{
		state = state * 1664525u + 1013904223u;
		return btScalar(state >> 8) / btScalar(1 << 24);
	}
};

// Everything about a broadphase that the moves may change, as plain values.
struct State
{
	std::vector<btScalar> nodes;  // depth first: per node its box and, for a leaf, its proxy's id (else -1)
	std::vector<int> queued;      // the dynamic stage list, head first
	unsigned updatesCall = 0, updatesDone = 0;
	std::vector<std::pair<int, int>> pairs;
	bool operator==(const State& other) const
	{
		return nodes == other.nodes && queued == other.queued && updatesCall == other.updatesCall &&
		       updatesDone == other.updatesDone && pairs == other.pairs;
	}
};

void addNodes(const btDbvtNode* node, std::vector<btScalar>& out)
{
	if (!node) return;
	for (int axis = 0; axis < 3; ++axis)
	{
		out.push_back(node->volume.Mins()[axis]);
		out.push_back(node->volume.Maxs()[axis]);
	}
	if (node->isleaf())
	{
		out.push_back(btScalar(static_cast<const btDbvtProxy*>(node->data)->m_uniqueId));
		return;
	}
	out.push_back(btScalar(-1));
	addNodes(node->childs[0], out);
	addNodes(node->childs[1], out);
}

State stateOf(btDbvtBroadphase& broadphase)
{
	State state;
	addNodes(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_root, state.nodes);
	for (btDbvtProxy* p = broadphase.m_stageRoots[btDbvtBroadphase::DYNAMIC_SET]; p; p = p->links[1])
		state.queued.push_back(p->m_uniqueId);
	state.updatesCall = unsigned(broadphase.m_updates_call);
	state.updatesDone = unsigned(broadphase.m_updates_done);
	return state;
}

// 1500 boxes on a 1 m grid (12 x 12 columns, touching neighbours) that fall faster each step (0.1 m more),
// with a little jitter: the boxes leave their fat boxes and are refitted next to their siblings, and the
// subtrees' boxes grow downwards (odd steps move nothing else). In even steps every 40th box jumps up to 3 m
// (re-inserted, sometimes far from its subtree); a few static boxes sit in the fixed tree. batched: the moves go
// through storeAabbOrFatBox and moveProxiesToFatBoxes, else through setAabb. Returns the state after each step's moves
// and after its pair search.
std::vector<State> run(bool batched, int& fewestMoves)
{
	btDbvtBroadphase broadphase;
	Lcg random;
	const int kBoxes = 1500;
	const btVector3 half(btScalar(0.45), btScalar(0.45), btScalar(0.45));
	std::vector<btBroadphaseProxy*> proxies;
	std::vector<btVector3> centres;
	for (int i = 0; i < kBoxes; ++i)
	{
		centres.push_back(btVector3(btScalar(i % 12), btScalar(i / 144), btScalar((i / 12) % 12)));
		proxies.push_back(
		    broadphase.createProxy(centres[i] - half, centres[i] + half, BOX_SHAPE_PROXYTYPE, 0, 1, -1, 0));
	}
	for (int i = 0; i < 20; ++i)
	{
		const btVector3 centre(random.next() * 12, btScalar(-2), random.next() * 12);
		broadphase.createProxy(centre - half, centre + half, BOX_SHAPE_PROXYTYPE, 0, btBroadphaseProxy::StaticFilter,
		                       btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter, 0);
	}
	broadphase.calculateOverlappingPairs(0);
	std::vector<State> history;
	std::vector<caliber::DbvtMove> moves;
	fewestMoves = kBoxes;
	for (int step = 0; step < 25; ++step)
	{
		moves.clear();
		for (int i = 0; i < kBoxes; ++i)
		{
			btVector3 shift(random.next() - btScalar(0.5), random.next() - btScalar(0.5),
			                random.next() - btScalar(0.5));
			shift *= i % 40 == 0 && step % 2 == 0 ? btScalar(6) : btScalar(0.05);
			centres[i] += shift + btVector3(0, btScalar(-0.1) * btScalar(step + 1), 0);
			const btVector3 aabbMin = centres[i] - half, aabbMax = centres[i] + half;
			if (!batched)
			{
				broadphase.setAabb(proxies[i], aabbMin, aabbMax, 0);
				continue;
			}
			++broadphase.m_updates_call;
			caliber::DbvtMove move;
			move.proxy = proxies[i];
			if (caliber::storeAabbOrFatBox(broadphase, proxies[i], aabbMin, aabbMax, move.fatMin, move.fatMax))
				moves.push_back(move);
		}
		if (batched)
		{
			fewestMoves = std::min(fewestMoves, int(moves.size()));
			if (!moves.empty()) caliber::moveProxiesToFatBoxes(broadphase, &moves[0], int(moves.size()));
		}
		history.push_back(stateOf(broadphase));
		broadphase.calculateOverlappingPairs(0);
		State afterSearch = stateOf(broadphase);
		const btBroadphasePairArray& pairs = broadphase.getOverlappingPairCache()->getOverlappingPairArray();
		for (int k = 0; k < pairs.size(); ++k)
			afterSearch.pairs.push_back(std::make_pair(pairs[k].m_pProxy0->m_uniqueId, pairs[k].m_pProxy1->m_uniqueId));
		history.push_back(afterSearch);
	}
	return history;
}

void expectSameHistory(const std::vector<State>& serial, const std::vector<State>& batched)
{
	ASSERT_EQ(serial.size(), batched.size());
	for (size_t i = 0; i < serial.size(); ++i)
	{
		EXPECT_TRUE(serial[i] == batched[i])
		    << "first difference after " << (i % 2 ? "the pair search of" : "the moves of") << " step " << i / 2;
		if (!(serial[i] == batched[i])) return;
	}
}
}  // namespace

TEST(DbvtBatchMove, TreeQueueAndPairsAreTheSerialUpdatesAtAnyThreadCount)
{
	int unused = 0;
	std::vector<State> serial;
	{
		caliber_test::ScopedTaskScheduler none(0);
		serial = run(false, unused);
	}
	ASSERT_GT(serial.back().pairs.size(), 100u);
	for (int threads : {1, 2, 3})
	{
		caliber_test::ScopedTaskScheduler scheduler(threads);
		int fewestMoves = 0;
		const std::vector<State> batched = run(true, fewestMoves);
		// The threaded path runs from 256 moves on; every step must take it.
		EXPECT_GE(fewestMoves, 256) << threads << " threads";
		expectSameHistory(serial, batched);
	}
}

TEST(DbvtBatchMove, AUserSchedulerMaySplitTheSubtreesAnywhere)
{
	int unused = 0;
	std::vector<State> serial;
	{
		caliber_test::ScopedTaskScheduler none(0);
		serial = run(false, unused);
	}
	caliber_test::UnevenSplitScheduler uneven;
	btSetTaskScheduler(&uneven);
	const std::vector<State> batched = run(true, unused);
	btSetTaskScheduler(0);
	expectSameHistory(serial, batched);
}
