// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btAlignedObjectArray.h"

#include <gtest/gtest.h>

#include <stdint.h>

#include <algorithm>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{
// Same shape as btVector3: four scalars, 16-byte aligned.
struct alignas(16) Vec4
{
	btScalar v[4];
};

struct alignas(64) CacheLine
{
	int value;
};

bool isAligned(const void* ptr, uintptr_t alignment) { return reinterpret_cast<uintptr_t>(ptr) % alignment == 0; }

// Counts every construction and destruction so tests can check that they balance.
struct Tracked
{
	static int s_constructed;
	static int s_destroyed;
	static int live() { return s_constructed - s_destroyed; }
	static void resetCounts() { s_constructed = s_destroyed = 0; }

	int value;
	// Set by every constructor and cleared by the destructor: reading a dead or never-built Tracked
	// shows up as a wrong magic.
	unsigned magic;

	Tracked() : value(0), magic(kAlive) { ++s_constructed; }
	Tracked(int v) : value(v), magic(kAlive) { ++s_constructed; }
	Tracked(const Tracked& other) : value(other.value), magic(kAlive)
	{
		EXPECT_EQ(other.magic, kAlive) << "copied from a dead element";
		++s_constructed;
	}
	Tracked& operator=(const Tracked& other)
	{
		EXPECT_EQ(magic, kAlive) << "assigned to a dead element";
		EXPECT_EQ(other.magic, kAlive) << "assigned from a dead element";
		value = other.value;
		return *this;
	}
	~Tracked()
	{
		EXPECT_EQ(magic, kAlive) << "destroyed twice or never constructed";
		magic = 0;
		++s_destroyed;
	}
	bool operator<(const Tracked& other) const { return value < other.value; }
	bool operator==(const Tracked& other) const { return value == other.value; }

	static constexpr unsigned kAlive = 0xA11CEu;
};
int Tracked::s_constructed = 0;
int Tracked::s_destroyed = 0;

std::vector<int> randomInts(int count, int maxValue, unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_int_distribution<int> dist(0, maxValue);
	std::vector<int> values(count);
	for (int& v : values) v = dist(rng);
	return values;
}

btAlignedObjectArray<int> toArray(const std::vector<int>& values)
{
	btAlignedObjectArray<int> array;
	for (int v : values) array.push_back(v);
	return array;
}

std::vector<int> toVector(const btAlignedObjectArray<int>& array)
{
	std::vector<int> values;
	for (int i = 0; i < array.size(); ++i) values.push_back(array[i]);
	return values;
}

struct Greater
{
	bool operator()(int a, int b) const { return a > b; }
};

// Counts allocations made through the aligned hooks while alive, then restores the defaults.
int g_allocCalls = 0;
int g_freeCalls = 0;
void* countingAlignedAlloc(size_t size, int alignment)
{
	++g_allocCalls;
	return aligned_alloc(size_t(alignment), (size + size_t(alignment) - 1) / size_t(alignment) * size_t(alignment));
}
void countingAlignedFree(void* ptr)
{
	++g_freeCalls;
	free(ptr);
}
struct ScopedCountingAllocator
{
	ScopedCountingAllocator()
	{
		g_allocCalls = g_freeCalls = 0;
		btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree);
	}
	~ScopedCountingAllocator() { btAlignedAllocSetCustomAligned(nullptr, nullptr); }
};
}  // namespace

TEST(AlignedObjectArray, EveryElementIs16ByteAligned)
{
	btAlignedObjectArray<Vec4> vectors;
	btAlignedObjectArray<char> bytes;
	for (int n = 0; n < 600; ++n)
	{
		vectors.push_back(Vec4{{btScalar(n), 0, 0, 0}});
		bytes.push_back(char(n));
		// Check every element after every growth step, not only the last one.
		for (int i = 0; i < vectors.size(); ++i)
			ASSERT_TRUE(isAligned(&vectors[i], 16))
			    << "element " << i << " of " << vectors.size() << " at " << static_cast<const void*>(&vectors[i]);
		ASSERT_TRUE(isAligned(&bytes[0], 16)) << "char storage at " << static_cast<const void*>(&bytes[0]);
	}
	for (int i = 0; i < vectors.size(); ++i) EXPECT_EQ(vectors[i].v[0], btScalar(i));
}

TEST(AlignedObjectArray, OverAlignedElementsKeepTheirAlignment)
{
	btAlignedObjectArray<CacheLine> lines;
	for (int n = 0; n < 100; ++n)
	{
		lines.push_back(CacheLine{n});
		ASSERT_TRUE(isAligned(&lines[0], 64)) << "storage at " << static_cast<const void*>(&lines[0]);
	}
	lines.resize(300);
	for (int i = 0; i < lines.size(); ++i) ASSERT_TRUE(isAligned(&lines[i], 64)) << "element " << i;
}

TEST(AlignedObjectArray, PushBackDoublesCapacityStartingAtOne)
{
	btAlignedObjectArray<int> array;
	EXPECT_EQ(array.size(), 0);
	EXPECT_EQ(array.capacity(), 0);
	std::vector<int> capacities;
	for (int i = 0; i < 65; ++i)
	{
		array.push_back(i);
		if (capacities.empty() || capacities.back() != array.capacity()) capacities.push_back(array.capacity());
	}
	const std::vector<int> expected = {1, 2, 4, 8, 16, 32, 64, 128};
	EXPECT_EQ(capacities, expected);
	EXPECT_EQ(array.size(), 65);
	for (int i = 0; i < 65; ++i) ASSERT_EQ(array[i], i);
}

TEST(AlignedObjectArray, ReserveThatFitsDoesNotAllocate)
{
	ScopedCountingAllocator counting;
	{
		btAlignedObjectArray<int> array;
		array.reserve(100);
		EXPECT_EQ(g_allocCalls, 1);
		EXPECT_EQ(array.capacity(), 100);
		const int* storage = &array.expandNonInitializing();
		for (int i = 1; i < 100; ++i) array.push_back(i);
		array.reserve(50);
		array.reserve(100);
		array.resize(10);
		array.resize(100, 7);
		array.resizeNoInitialize(60);
		EXPECT_EQ(g_allocCalls, 1) << "capacity " << array.capacity();
		EXPECT_EQ(&array[0], storage);
		array.push_back(1);
		EXPECT_EQ(g_allocCalls, 1);
		array.resize(101);
		EXPECT_EQ(g_allocCalls, 2);
		EXPECT_EQ(array.capacity(), 101) << "resize grows to exactly the requested size";
	}
	EXPECT_EQ(g_freeCalls, g_allocCalls);
}

TEST(AlignedObjectArray, ResizeKeepsCapacityAndClearFreesIt)
{
	btAlignedObjectArray<int> array;
	array.resize(40, 3);
	EXPECT_EQ(array.capacity(), 40);
	for (int i = 0; i < 40; ++i) ASSERT_EQ(array[i], 3);
	array.resize(5);
	EXPECT_EQ(array.size(), 5);
	EXPECT_EQ(array.capacity(), 40);
	array.clear();
	EXPECT_EQ(array.size(), 0);
	EXPECT_EQ(array.capacity(), 0);
}

TEST(AlignedObjectArray, ConstructorAndDestructorCountsBalance)
{
	Tracked::resetCounts();
	{
		btAlignedObjectArray<Tracked> array;
		for (int i = 0; i < 37; ++i) array.push_back(Tracked(i));
		EXPECT_EQ(Tracked::live(), 37);
		array.pop_back();
		array.pop_back();
		EXPECT_EQ(Tracked::live(), 35);
		array.resize(60, Tracked(-1));
		EXPECT_EQ(Tracked::live(), 60);
		array.resize(20);
		EXPECT_EQ(Tracked::live(), 20);
		array.resizeNoInitialize(30);
		EXPECT_EQ(Tracked::live(), 30);
		array.resizeNoInitialize(25);
		EXPECT_EQ(Tracked::live(), 25);
		array.expand(Tracked(99));
		array.expandNonInitializing();
		EXPECT_EQ(Tracked::live(), 27);
		array.remove(Tracked(5));
		array.removeAtIndex(0);
		array.swap(0, 3);
		EXPECT_EQ(Tracked::live(), 25);
		array.quickSort(btAlignedObjectArray<Tracked>::less());
		array.heapSort(btAlignedObjectArray<Tracked>::less());
		EXPECT_EQ(Tracked::live(), 25);
		{
			btAlignedObjectArray<Tracked> copy(array);
			EXPECT_EQ(Tracked::live(), 50);
			btAlignedObjectArray<Tracked> assigned;
			assigned.push_back(Tracked(1));
			assigned = array;
			EXPECT_EQ(Tracked::live(), 75);
			assigned.copyFromArray(copy);
			EXPECT_EQ(Tracked::live(), 75);
			// As in Bullet 2.89, which declares no move constructor: std::move copies, the source keeps its elements.
			btAlignedObjectArray<Tracked> moved(std::move(copy));
			EXPECT_EQ(Tracked::live(), 100);
			EXPECT_EQ(copy.size(), 25);
		}
		EXPECT_EQ(Tracked::live(), 25);
		array.clear();
		EXPECT_EQ(Tracked::live(), 0);
		for (int i = 0; i < 10; ++i) array.push_back(Tracked(i));
	}
	EXPECT_EQ(Tracked::live(), 0) << "constructed " << Tracked::s_constructed << ", destroyed " << Tracked::s_destroyed;
}

TEST(AlignedObjectArray, PushBackOfOwnElementSurvivesGrowth)
{
	btAlignedObjectArray<std::string> array;
	array.push_back("a fairly long string that lives on the heap");
	for (int i = 0; i < 20; ++i)
	{
		array.push_back(array[0]);  // array[0] lives in the block that push_back may replace
		ASSERT_EQ(array[array.size() - 1], array[0]) << "after " << i << " pushes, capacity " << array.capacity();
	}
	array.resize(100, array[3]);
	EXPECT_EQ(array[99], array[0]);
	array.expand(array[1]);
	EXPECT_EQ(array[100], array[0]);
}

TEST(AlignedObjectArray, QuickSortMatchesStdSort)
{
	const int sizes[] = {0, 1, 2, 3, 15, 16, 17, 100, 1000, 5000};
	unsigned seed = 1234;
	for (int size : sizes)
	{
		for (int maxValue : {3, 1000000})  // many duplicates, then mostly distinct
		{
			std::vector<int> expected = randomInts(size, maxValue, seed++);
			btAlignedObjectArray<int> array = toArray(expected);
			array.quickSort(btAlignedObjectArray<int>::less());
			std::sort(expected.begin(), expected.end());
			ASSERT_EQ(toVector(array), expected) << "size " << size << ", values in [0, " << maxValue << "]";

			array.quickSort(Greater());
			std::sort(expected.begin(), expected.end(), std::greater<int>());
			ASSERT_EQ(toVector(array), expected) << "descending, size " << size;
		}
	}
}

TEST(AlignedObjectArray, HeapSortMatchesStdSort)
{
	const int sizes[] = {0, 1, 2, 3, 15, 16, 17, 100, 1000, 5000};
	unsigned seed = 5678;
	for (int size : sizes)
	{
		for (int maxValue : {3, 1000000})
		{
			std::vector<int> expected = randomInts(size, maxValue, seed++);
			btAlignedObjectArray<int> array = toArray(expected);
			array.heapSort(btAlignedObjectArray<int>::less());
			std::sort(expected.begin(), expected.end());
			ASSERT_EQ(toVector(array), expected) << "size " << size << ", values in [0, " << maxValue << "]";

			array.heapSort(Greater());
			std::sort(expected.begin(), expected.end(), std::greater<int>());
			ASSERT_EQ(toVector(array), expected) << "descending, size " << size;
		}
	}
}

TEST(AlignedObjectArray, SortsHandleSortedReversedAndConstantInput)
{
	for (int pattern = 0; pattern < 3; ++pattern)
	{
		std::vector<int> values(20000);
		for (int i = 0; i < int(values.size()); ++i) values[i] = pattern == 0 ? i : (pattern == 1 ? -i : 42);
		std::vector<int> expected = values;
		std::sort(expected.begin(), expected.end());
		btAlignedObjectArray<int> quick = toArray(values);
		quick.quickSort(btAlignedObjectArray<int>::less());
		EXPECT_EQ(toVector(quick), expected) << "pattern " << pattern;
		btAlignedObjectArray<int> heap = toArray(values);
		heap.heapSort(btAlignedObjectArray<int>::less());
		EXPECT_EQ(toVector(heap), expected) << "pattern " << pattern;
	}
}

TEST(AlignedObjectArray, SortsNonTrivialElements)
{
	std::mt19937 rng(99);
	btAlignedObjectArray<std::string> quick;
	std::vector<std::string> expected;
	for (int i = 0; i < 500; ++i)
	{
		std::string s = "key" + std::to_string(rng() % 200);
		quick.push_back(s);
		expected.push_back(s);
	}
	btAlignedObjectArray<std::string> heap(quick);
	std::sort(expected.begin(), expected.end());
	quick.quickSort(btAlignedObjectArray<std::string>::less());
	heap.heapSort(btAlignedObjectArray<std::string>::less());
	for (int i = 0; i < quick.size(); ++i)
	{
		ASSERT_EQ(quick[i], expected[i]) << "quickSort, index " << i;
		ASSERT_EQ(heap[i], expected[i]) << "heapSort, index " << i;
	}
}

TEST(AlignedObjectArray, FindBinarySearchMatchesStdLowerBound)
{
	std::vector<int> sorted = randomInts(2000, 3000, 42);
	std::sort(sorted.begin(), sorted.end());
	btAlignedObjectArray<int> array = toArray(sorted);
	for (int key = -5; key <= 3005; ++key)
	{
		const auto it = std::lower_bound(sorted.begin(), sorted.end(), key);
		const int expected = (it != sorted.end() && *it == key) ? int(it - sorted.begin()) : array.size();
		ASSERT_EQ(array.findBinarySearch(key), expected) << "key " << key;
	}
	btAlignedObjectArray<int> empty;
	EXPECT_EQ(empty.findBinarySearch(1), 0);
}

TEST(AlignedObjectArray, FindLinearSearchMatchesStdFind)
{
	const std::vector<int> values = randomInts(500, 800, 7);
	const btAlignedObjectArray<int> array = toArray(values);
	for (int key = -2; key <= 802; ++key)
	{
		const auto it = std::find(values.begin(), values.end(), key);
		const int index = int(it - values.begin());
		ASSERT_EQ(array.findLinearSearch(key), index) << "key " << key;
		ASSERT_EQ(array.findLinearSearch2(key), it == values.end() ? -1 : index) << "key " << key;
	}
}

TEST(AlignedObjectArray, RemoveAtIndexMovesLastElementIntoTheHole)
{
	btAlignedObjectArray<int> array = toArray({10, 11, 12, 13, 14});
	array.removeAtIndex(1);
	EXPECT_EQ(toVector(array), (std::vector<int>{10, 14, 12, 13}));
	array.removeAtIndex(3);
	EXPECT_EQ(toVector(array), (std::vector<int>{10, 14, 12}));
	array.removeAtIndex(array.size());  // the "not found" index of the searches is a silent no-op
	EXPECT_EQ(array.size(), 3);
}

TEST(AlignedObjectArray, RemoveDeletesFirstMatchOnlyAndIgnoresAbsentKeys)
{
	btAlignedObjectArray<int> array = toArray({5, 7, 5, 9});
	array.remove(5);
	EXPECT_EQ(toVector(array), (std::vector<int>{9, 7, 5}));
	array.remove(42);
	EXPECT_EQ(toVector(array), (std::vector<int>{9, 7, 5}));
}

TEST(AlignedObjectArray, SwapExchangesTwoElements)
{
	btAlignedObjectArray<int> array = toArray({1, 2, 3});
	array.swap(0, 2);
	EXPECT_EQ(toVector(array), (std::vector<int>{3, 2, 1}));
	array.swap(1, 1);
	EXPECT_EQ(toVector(array), (std::vector<int>{3, 2, 1}));
}

TEST(AlignedObjectArray, ExpandReturnsTheNewLastElement)
{
	btAlignedObjectArray<int> array;
	int& first = array.expand(4);
	EXPECT_EQ(first, 4);
	EXPECT_EQ(&first, &array[0]);
	int& second = array.expandNonInitializing();
	second = 8;
	EXPECT_EQ(array.size(), 2);
	EXPECT_EQ(array[1], 8);
	EXPECT_EQ(array.expand(), 0);
	EXPECT_EQ(array.at(2), 0);
}

TEST(AlignedObjectArray, InitializeFromBufferUsesButNeverFreesTheBuffer)
{
	alignas(16) int buffer[8] = {1, 2, 3, 0, 0, 0, 0, 0};
	{
		btAlignedObjectArray<int> array;
		array.push_back(99);  // owned storage, must be freed by initializeFromBuffer
		array.initializeFromBuffer(buffer, 3, 8);
		EXPECT_EQ(array.size(), 3);
		EXPECT_EQ(array.capacity(), 8);
		EXPECT_EQ(&array[0], buffer);
		array.push_back(4);
		EXPECT_EQ(buffer[3], 4) << "push_back within capacity writes into the caller's buffer";
		for (int i = 5; i <= 9; ++i) array.push_back(i);
		EXPECT_NE(&array[0], buffer) << "growing past capacity moves to owned storage";
		EXPECT_EQ(toVector(array), (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9}));
	}  // destruction frees the owned block only (ASan would flag freeing the stack buffer)
	{
		btAlignedObjectArray<int> array;
		array.initializeFromBuffer(buffer, 2, 8);
		array.clear();
		EXPECT_EQ(array.capacity(), 0);
	}
	EXPECT_EQ(buffer[0], 1);
}

TEST(AlignedObjectArray, CopyFromArrayMakesAnIndependentDeepCopy)
{
	btAlignedObjectArray<std::string> source;
	for (int i = 0; i < 10; ++i) source.push_back("item" + std::to_string(i));
	btAlignedObjectArray<std::string> target;
	target.reserve(64);
	target.push_back("old");
	const std::string* storage = &target[0];
	target.copyFromArray(source);
	EXPECT_EQ(target.size(), 10);
	EXPECT_EQ(&target[0], storage) << "a copy that fits reuses the storage";
	source[0] = "changed";
	EXPECT_EQ(target[0], "item0");
	for (int i = 1; i < 10; ++i) EXPECT_EQ(target[i], source[i]);
	target.copyFromArray(target);
	EXPECT_EQ(target.size(), 10);

	btAlignedObjectArray<std::string> copy(target);
	btAlignedObjectArray<std::string> assigned;
	assigned = target;
	for (int i = 0; i < 10; ++i)
	{
		EXPECT_EQ(copy[i], target[i]);
		EXPECT_EQ(assigned[i], target[i]);
	}
}

TEST(AlignedObjectArray, ArrayOfArraysGrowsWithoutLosingContents)
{
	btAlignedObjectArray<btAlignedObjectArray<int>> rows;
	for (int r = 0; r < 50; ++r)
	{
		rows.expand();
		for (int c = 0; c <= r; ++c) rows[r].push_back(r * 100 + c);
	}
	for (int r = 0; r < 50; ++r)
	{
		ASSERT_EQ(rows[r].size(), r + 1);
		for (int c = 0; c <= r; ++c) ASSERT_EQ(rows[r][c], r * 100 + c);
	}
}

#if CALIBER_ASSERTS_ENABLED
TEST(AlignedObjectArrayDeathTest, OutOfRangeIndexAsserts)
{
	btAlignedObjectArray<int> array = toArray({1, 2, 3});
	const btAlignedObjectArray<int>& constArray = array;
	EXPECT_DEATH(array[3] = 0, "assertion failed");
	EXPECT_DEATH((void)constArray[-1], "assertion failed");
	EXPECT_DEATH((void)array.at(7), "assertion failed");
	EXPECT_DEATH(array.swap(0, 3), "assertion failed");
	EXPECT_DEATH(array.removeAtIndex(-1), "assertion failed");
	EXPECT_DEATH(array.removeAtIndex(4), "assertion failed");
	EXPECT_DEATH(array.resize(-1), "assertion failed");
	btAlignedObjectArray<int> empty;
	EXPECT_DEATH(empty.pop_back(), "assertion failed");
}
#else
TEST(AlignedObjectArray, BadIndicesAreNoOpsInRelease)
{
	btAlignedObjectArray<int> array = toArray({1, 2, 3});
	array.swap(0, 3);
	array.swap(-1, 1);
	array.removeAtIndex(-1);
	array.removeAtIndex(4);
	EXPECT_EQ(toVector(array), (std::vector<int>{1, 2, 3}));
	btAlignedObjectArray<int> empty;
	empty.pop_back();
	EXPECT_EQ(empty.size(), 0);
	array.resize(-1);
	EXPECT_EQ(array.size(), 0) << "a negative size is treated as 0";
}
#endif
