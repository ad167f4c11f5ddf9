// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <vector>

#include "BulletCollision/CollisionDispatch/btUnionFind.h"
#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"

namespace
{
// Reference: connected components by depth-first search over an adjacency list; label = smallest vertex.
std::vector<int> componentsByDfs(int n, const std::vector<std::pair<int, int>>& edges)
{
	std::vector<std::vector<int>> adjacency(static_cast<size_t>(n));
	for (const auto& e : edges)
	{
		adjacency[size_t(e.first)].push_back(e.second);
		adjacency[size_t(e.second)].push_back(e.first);
	}
	std::vector<int> label(size_t(n), -1);
	for (int start = 0; start < n; ++start)
	{
		if (label[size_t(start)] >= 0) continue;
		std::vector<int> stack(1, start);
		label[size_t(start)] = start;
		while (!stack.empty())
		{
			const int v = stack.back();
			stack.pop_back();
			for (int w : adjacency[size_t(v)])
			{
				if (label[size_t(w)] >= 0) continue;
				label[size_t(w)] = start;
				stack.push_back(w);
			}
		}
	}
	return label;
}
}  // namespace

TEST(UnionFind, ResetMakesSingletons)
{
	btUnionFind uf;
	uf.reset(5);
	ASSERT_EQ(uf.getNumElements(), 5);
	for (int i = 0; i < 5; ++i)
	{
		EXPECT_TRUE(uf.isRoot(i));
		EXPECT_EQ(uf.find(i), i);
		EXPECT_EQ(uf.getElement(i).m_sz, 1);
	}
	EXPECT_EQ(uf.find(1, 2), 0);
	uf.unite(1, 2);
	EXPECT_EQ(uf.find(1, 2), 1);
	EXPECT_EQ(uf.getElement(uf.find(1)).m_sz, 2) << "the root holds the set size";
	uf.reset(3);
	EXPECT_EQ(uf.getNumElements(), 3);
	EXPECT_EQ(uf.find(1, 2), 0) << "reset forgets the unions";
	uf.Free();
	EXPECT_EQ(uf.getNumElements(), 0);
}

TEST(UnionFind, SetsMatchBruteForceComponentsOnRandomGraphs)
{
	std::mt19937 rng(20261122u);
	for (int trial = 0; trial < 50; ++trial)
	{
		const int n = 1 + int(rng() % 200);
		const int numEdges = int(rng() % (size_t(n) * 2));
		std::vector<std::pair<int, int>> edges;
		btUnionFind uf;
		uf.reset(n);
		for (int e = 0; e < numEdges; ++e)
		{
			const int a = int(rng() % size_t(n));
			const int b = int(rng() % size_t(n));
			edges.push_back(std::make_pair(a, b));
			uf.unite(a, b);
		}
		const std::vector<int> reference = componentsByDfs(n, edges);
		std::vector<int> sizes(size_t(n), 0);
		for (int i = 0; i < n; ++i) ++sizes[size_t(reference[size_t(i)])];
		for (int i = 0; i < n; ++i)
		{
			for (int j = i + 1; j < n; ++j)
			{
				const bool same = reference[size_t(i)] == reference[size_t(j)];
				ASSERT_EQ(uf.find(i) == uf.find(j), same) << "trial " << trial << " vertices " << i << ", " << j;
			}
			EXPECT_EQ(uf.getElement(uf.find(i)).m_sz, sizes[size_t(reference[size_t(i)])])
			    << "set size at the root, trial " << trial;
		}
	}
}

TEST(UnionFind, SortIslandsMakesEachSetOneContiguousRun)
{
	std::mt19937 rng(7u);
	const int n = 300;
	btUnionFind uf;
	uf.reset(n);
	std::vector<std::pair<int, int>> edges;
	for (int e = 0; e < 200; ++e)
	{
		const int a = int(rng() % n);
		const int b = int(rng() % n);
		edges.push_back(std::make_pair(a, b));
		uf.unite(a, b);
	}
	const std::vector<int> reference = componentsByDfs(n, edges);
	// As the island manager does: remember which vertex each element stands for in m_sz.
	std::vector<int> rootOf(static_cast<size_t>(n));
	for (int i = 0; i < n; ++i) rootOf[size_t(i)] = uf.find(i);
	for (int i = 0; i < n; ++i) uf.getElement(i).m_sz = i;
	uf.sortIslands();

	std::vector<bool> seenIsland(size_t(n), false);
	std::vector<bool> seenVertex(size_t(n), false);
	for (int start = 0, end = 0; start < n; start = end)
	{
		const int id = uf.getElement(start).m_id;
		ASSERT_FALSE(seenIsland[size_t(id)]) << "island " << id << " appears in two runs";
		seenIsland[size_t(id)] = true;
		for (end = start; end < n && uf.getElement(end).m_id == id; ++end)
		{
			const int vertex = uf.getElement(end).m_sz;
			EXPECT_FALSE(seenVertex[size_t(vertex)]);
			seenVertex[size_t(vertex)] = true;
			EXPECT_EQ(rootOf[size_t(vertex)], id) << "island id is the set's root";
			EXPECT_EQ(reference[size_t(vertex)], reference[size_t(uf.getElement(start).m_sz)]);
			if (end > start)
			{
				EXPECT_LT(uf.getElement(end - 1).m_sz, vertex) << "ordered inside an island";
			}
		}
	}
	for (int i = 0; i < n; ++i) EXPECT_TRUE(seenVertex[size_t(i)]);
}

// sortIslands orders the elements by (island id, m_sz), which fixes the result; it takes a linear
// counting sort when m_sz grows with the element index (as the island manager stores it), another when
// only each island's elements come in increasing m_sz, and a comparison sort otherwise. All must give
// exactly the reference order.
TEST(UnionFind, SortIslandsGivesTheOrderByIslandIdThenStoredValueWhateverTheStoredValues)
{
	std::mt19937 rng(11u);
	for (int trial = 0; trial < 80; ++trial)
	{
		// Every fourth trial is as large as the benchmark's 3000 falling boxes, and has no unions at all
		// (every island one element) or only a few.
		const int n = trial % 4 == 3 ? 3000 : 1 + int(rng() % 400);
		btUnionFind uf;
		uf.reset(n);
		const int unions = trial % 4 == 3 ? (trial % 8 == 3 ? 0 : 20) : n / 2;
		for (int e = 0; e < unions; ++e) uf.unite(int(rng() % size_t(n)), int(rng() % size_t(n)));
		std::vector<int> stored(static_cast<size_t>(n));
		for (int i = 0; i < n; ++i)
		{
			// Trials 0 and 3 (mod 4): values growing with the index (the first counting sort); 1: random
			// ones with repeats (the comparison sort); 2: growing within each island but not from one island
			// to the next (the second counting sort).
			const int mode = trial % 4;
			stored[size_t(i)] = mode == 1 ? int(rng() % size_t(n)) : (mode == 2 ? 3 * i - 4 * n * (uf.find(i) % 3) : 3 * i);
		}
		std::vector<std::pair<int, int>> reference;
		for (int i = 0; i < n; ++i)
		{
			reference.push_back(std::make_pair(uf.find(i), stored[size_t(i)]));
			uf.getElement(i).m_sz = stored[size_t(i)];
		}
		std::sort(reference.begin(), reference.end());
		uf.sortIslands();
		for (int i = 0; i < n; ++i)
		{
			ASSERT_EQ(uf.getElement(i).m_id, reference[size_t(i)].first) << "trial " << trial << " element " << i;
			ASSERT_EQ(uf.getElement(i).m_sz, reference[size_t(i)].second) << "trial " << trial << " element " << i;
		}
	}
}

namespace
{
// One random union-find of n elements as the island manager leaves it before sortIslands: shape 0 random
// unions, 1 one island (a chain of unions), 2 no unions (every element alone), 3 a few large islands;
// m_sz the index times three (growing: the sort on the threads) or, when increasing is false, random.
void makeIslands(btUnionFind& uf, int n, int shape, bool increasing, std::mt19937& rng)
{
	uf.reset(n);
	if (shape == 0)
		for (int e = 0; e < n / 2; ++e) uf.unite(int(rng() % size_t(n)), int(rng() % size_t(n)));
	if (shape == 1)
		for (int i = 1; i < n; ++i) uf.unite(int(rng() % size_t(i)), i);
	if (shape == 3)
		for (int i = 5; i < n; ++i) uf.unite(i, int(rng() % 5));
	for (int i = 0; i < n; ++i) uf.getElement(i).m_sz = increasing ? 3 * i : int(rng() % size_t(n));
}
}  // namespace

// sortIslands on the threads (at least 1024 elements and a scheduler with two threads or more: the roots found
// without changing the elements, then a counting sort in parts) must leave exactly the elements the serial
// sort leaves, for every shape of islands, on the pool and on schedulers that cut or order the loops oddly.
TEST(UnionFind, SortIslandsOnTheThreadsLeavesTheSerialElements)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	caliber_test::UnevenSplitScheduler uneven;
	caliber_test::LastFirstScheduler lastFirst;
	std::mt19937 rng(1128u);
	for (int trial = 0; trial < 40; ++trial)
	{
		const int sizes[] = {0, 1, 1023, 1024, 1500, 3000, 7001};
		const int n = sizes[trial % 7];
		const int shape = (trial / 7) % 4;
		const bool increasing = trial % 5 != 4;
		const unsigned seed = unsigned(rng());
		btUnionFind serial;
		std::mt19937 serialRng(seed);
		makeIslands(serial, n, shape, increasing, serialRng);
		serial.sortIslands();
		for (int schedulerIndex = 0; schedulerIndex < 4; ++schedulerIndex)
		{
			// The pool at 2 and at 3 threads, the uneven split, the last-first order.
			btITaskScheduler* scheduler = pool.get();
			if (schedulerIndex == 1) scheduler = &uneven;
			if (schedulerIndex == 2) scheduler = &lastFirst;
			if (!scheduler) continue;
			btSetTaskScheduler(scheduler);
			if (schedulerIndex == 0) scheduler->setNumThreads(2);
			if (schedulerIndex == 3) scheduler->setNumThreads(3);
			btUnionFind threaded;
			std::mt19937 threadedRng(seed);
			makeIslands(threaded, n, shape, increasing, threadedRng);
			threaded.sortIslands();
			btSetTaskScheduler(0);
			ASSERT_EQ(threaded.getNumElements(), n);
			for (int i = 0; i < n; ++i)
			{
				ASSERT_EQ(threaded.getElement(i).m_id, serial.getElement(i).m_id)
				    << "trial " << trial << " scheduler " << schedulerIndex << " element " << i;
				ASSERT_EQ(threaded.getElement(i).m_sz, serial.getElement(i).m_sz)
				    << "trial " << trial << " scheduler " << schedulerIndex << " element " << i;
			}
		}
	}
}

TEST(UnionFind, LongChainStaysShallow)
{
	// Uniting a chain in the worst order for naive linking; union by size plus path halving keep finds
	// short: after one find per element every element is at most a couple of hops from its root.
	const int n = 100000;
	btUnionFind uf;
	uf.reset(n);
	for (int i = 1; i < n; ++i) uf.unite(i - 1, i);
	const int root = uf.find(0);
	for (int i = 0; i < n; ++i) ASSERT_EQ(uf.find(i), root);
	int maxDepth = 0;
	for (int i = 0; i < n; ++i)
	{
		int depth = 0;
		for (int x = i; uf.getElement(x).m_id != x; x = uf.getElement(x).m_id) ++depth;
		maxDepth = depth > maxDepth ? depth : maxDepth;
	}
	EXPECT_LE(maxDepth, 2) << "max depth " << maxDepth;
}

TEST(UnionFind, OutOfRangeIndicesAreRejected)
{
	btUnionFind uf;
	uf.reset(3);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(uf.unite(0, 3), "assertion failed");
	EXPECT_DEATH(uf.find(-1), "assertion failed");
	EXPECT_DEATH(uf.reset(-2), "assertion failed");
#else
	uf.unite(0, 3);
	uf.unite(-1, 0);
	EXPECT_EQ(uf.find(7), 7) << "documented: an out-of-range index is returned unchanged";
	for (int i = 0; i < 3; ++i) EXPECT_TRUE(uf.isRoot(i)) << "nothing was united";
	uf.reset(-2);
	EXPECT_EQ(uf.getNumElements(), 0);
#endif
}
