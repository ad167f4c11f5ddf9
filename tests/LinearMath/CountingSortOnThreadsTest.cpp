// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::CountingSortOnThreads (the island stage's groupings on the threads): for random keys, any part
// count and any scheduler (the pool, one that cuts loops unevenly, one that runs chunks last first), the
// order and key starts must be those of a stable sort by key made here with std::stable_sort, with the
// negative and out-of-range keys left out.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "LinearMath/btCountingSortOnThreads.h"
#include "LinearMath/btThreads.h"
#include "TestThreadsUtil.h"

namespace
{
struct KeyFromList
{
	const int* keys;
	int operator()(int i) const { return keys[i]; }
};

struct PlaceIntoList
{
	int* out;  // the item index at each slot
	void operator()(int i, int, int slot) const { out[slot] = i; }
};

struct Sorted
{
	std::vector<int> order;  // item indices, slot by slot
	std::vector<int> keyStart;
	int kept = 0;
};

Sorted sortOnThreads(const std::vector<int>& keys, int numKeys, int numParts)
{
	caliber::CountingSortScratch scratch;
	Sorted result;
	result.order.assign(keys.size(), -7);
	result.keyStart.assign(size_t(numKeys > 0 ? numKeys : 0) + 1, -7);
	KeyFromList keyOf;
	keyOf.keys = keys.empty() ? 0 : &keys[0];
	PlaceIntoList place;
	place.out = result.order.empty() ? 0 : &result.order[0];
	caliber::CountingSortOnThreads<KeyFromList, PlaceIntoList> sort(scratch, int(keys.size()), numKeys, numParts);
	sort.count(keyOf);
	result.kept = sort.place(place, &result.keyStart[0]);
	result.order.resize(size_t(result.kept));
	return result;
}

// The reference: a stable sort of the kept items by key, and each key's first slot by counting.
Sorted sortReference(const std::vector<int>& keys, int numKeys)
{
	Sorted result;
	std::vector<std::pair<int, int>> kept;
	for (size_t i = 0; i < keys.size(); ++i)
		if (keys[i] >= 0 && keys[i] < numKeys) kept.push_back(std::make_pair(keys[i], int(i)));
	std::stable_sort(kept.begin(), kept.end(),
	                 [](const std::pair<int, int>& a, const std::pair<int, int>& b) { return a.first < b.first; });
	for (const auto& item : kept) result.order.push_back(item.second);
	const int keyCount = numKeys > 0 ? numKeys : 0;
	result.keyStart.assign(size_t(keyCount) + 1, 0);
	for (const auto& item : kept) ++result.keyStart[size_t(item.first) + 1];
	for (int k = 0; k < keyCount; ++k) result.keyStart[size_t(k) + 1] += result.keyStart[size_t(k)];
	result.kept = int(kept.size());
	return result;
}

void expectSameAsReference(const std::vector<int>& keys, int numKeys, int numParts, const char* what)
{
	const Sorted reference = sortReference(keys, numKeys);
	const Sorted sorted = sortOnThreads(keys, numKeys, numParts);
	EXPECT_EQ(sorted.kept, reference.kept) << what << ", " << keys.size() << " items, " << numKeys << " keys, "
	                                       << numParts << " parts";
	EXPECT_TRUE(sorted.order == reference.order) << what << ", " << keys.size() << " items, " << numKeys
	                                             << " keys, " << numParts << " parts";
	EXPECT_TRUE(sorted.keyStart == reference.keyStart) << what << ", " << keys.size() << " items, " << numKeys
	                                                   << " keys, " << numParts << " parts";
}

// Random inputs: no items, one item, one key, all keys left out, few keys for many items (long runs), as many
// keys as items (mostly singletons, as a scene of lone bodies), keys out of range, and part counts from 1 to
// more than there are keys or items.
void runRandomCases(const char* what)
{
	std::mt19937 rng(20261128u);
	expectSameAsReference(std::vector<int>(), 5, 2, what);
	expectSameAsReference(std::vector<int>(), 0, 3, what);
	expectSameAsReference(std::vector<int>(1, 0), 1, 2, what);
	expectSameAsReference(std::vector<int>(1, -1), 1, 2, what);
	expectSameAsReference(std::vector<int>(3000, 0), 1, 2, what);
	expectSameAsReference(std::vector<int>(3000, -1), 10, 3, what);
	for (int trial = 0; trial < 60; ++trial)
	{
		const int numItems = trial % 5 == 0 ? int(rng() % 8) : 1 + int(rng() % 5000);
		const int numKeys = trial % 3 == 0 ? numItems + 1 : 1 + int(rng() % 300);
		std::vector<int> keys(size_t(numItems), 0);
		for (int& key : keys)
		{
			const unsigned roll = rng() % 20;
			key = roll == 0 ? -1 - int(rng() % 3) : (roll == 1 ? numKeys + int(rng() % 3) : int(rng() % size_t(numKeys)));
		}
		const int numParts = 1 + trial % 9;
		expectSameAsReference(keys, numKeys, numParts, what);
	}
}
}  // namespace

TEST(CountingSortOnThreads, MatchesAStableSortWithoutAScheduler) { runRandomCases("no scheduler"); }

TEST(CountingSortOnThreads, MatchesAStableSortOnThePoolAndOnUnevenAndLastFirstSchedulers)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	for (int threads : {2, 3})
	{
		if (!pool) break;
		btSetTaskScheduler(pool.get());
		pool->setNumThreads(threads);
		runRandomCases(threads == 2 ? "pool, 2 threads" : "pool, 3 threads");
		btSetTaskScheduler(0);
	}
	caliber_test::UnevenSplitScheduler uneven;
	btSetTaskScheduler(&uneven);
	runRandomCases("uneven split");
	btSetTaskScheduler(0);
	caliber_test::LastFirstScheduler lastFirst;
	btSetTaskScheduler(&lastFirst);
	runRandomCases("last first");
	btSetTaskScheduler(0);
}

// Misuse: a part count below one is taken as one, a negative key or item count as none (every item left out).
TEST(CountingSortOnThreads, BadCountsAreClampedNotFollowed)
{
	const std::vector<int> keys = {2, 0, 1, 0, 2};
	const Sorted reference = sortReference(keys, 3);
	for (int parts : {0, -4})
	{
		const Sorted sorted = sortOnThreads(keys, 3, parts);
		EXPECT_TRUE(sorted.order == reference.order) << parts << " parts";
		EXPECT_TRUE(sorted.keyStart == reference.keyStart) << parts << " parts";
	}
	const Sorted noKeys = sortOnThreads(keys, -2, 2);
	EXPECT_EQ(noKeys.kept, 0);
	ASSERT_EQ(noKeys.keyStart.size(), 1u);
	EXPECT_EQ(noKeys.keyStart[0], 0);
	caliber::CountingSortScratch scratch;
	KeyFromList keyOf;
	keyOf.keys = &keys[0];
	PlaceIntoList place;
	place.out = 0;
	caliber::CountingSortOnThreads<KeyFromList, PlaceIntoList> sort(scratch, -3, 3, 2);
	sort.count(keyOf);
	EXPECT_EQ(sort.place(place, 0), 0) << "a negative item count sorts nothing";
}

// The part count: none (the serial way) with no scheduler's threads, below the item threshold, or inside a
// parallel loop; one per thread, at most 8, otherwise.
TEST(CountingSortOnThreads, PartsFollowTheSchedulerAndTheThreshold)
{
	EXPECT_EQ(caliber::countingSortParts(5000, 1024), 0) << "the sequential scheduler has one thread";
	caliber_test::UnevenSplitScheduler uneven;  // reports two threads
	btSetTaskScheduler(&uneven);
	EXPECT_EQ(caliber::countingSortParts(5000, 1024), 2);
	EXPECT_EQ(caliber::countingSortParts(1000, 1024), 0);
	EXPECT_EQ(caliber::countingSortParts(0, 0), 0);
	EXPECT_EQ(caliber::countingSortParts(-5, 0), 0);
	btSetTaskScheduler(0);
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	if (!pool) return;
	btSetTaskScheduler(pool.get());
	pool->setNumThreads(pool->getMaxNumThreads());
	EXPECT_EQ(caliber::countingSortParts(5000, 1024), btMin(8, pool->getNumThreads() > 1 ? pool->getNumThreads() : 0));
	struct Nested : public btIParallelForBody
	{
		int* parts;
		void forLoop(int iBegin, int iEnd) const override
		{
			for (int i = iBegin; i < iEnd; ++i) parts[i] = caliber::countingSortParts(5000, 1024);
		}
	};
	int parts[2] = {-1, -1};
	Nested nested;
	nested.parts = parts;
	btParallelFor(0, 2, 1, nested);
	if (pool->getNumThreads() > 1)
	{
		EXPECT_EQ(parts[0], 0) << "inside a parallel loop the sort stays on its thread";
		EXPECT_EQ(parts[1], 0);
	}
	btSetTaskScheduler(0);
}
