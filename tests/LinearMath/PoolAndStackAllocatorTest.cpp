// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btPoolAllocator.h"
#include "LinearMath/btStackAlloc.h"

#include <gtest/gtest.h>

#include <stdint.h>
#include <string.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

namespace
{
bool isAligned16(const void* ptr) { return reinterpret_cast<uintptr_t>(ptr) % 16 == 0; }
}  // namespace

TEST(PoolAllocator, HandsOutEveryElementThenNull)
{
	btPoolAllocator pool(24, 10);
	EXPECT_EQ(pool.getMaxCount(), 10);
	EXPECT_EQ(pool.getElementSize(), 24);
	EXPECT_EQ(pool.getFreeCount(), 10);
	EXPECT_EQ(pool.getUsedCount(), 0);
	std::vector<void*> elements;
	for (int i = 0; i < 10; ++i)
	{
		void* element = pool.allocate(24);
		ASSERT_NE(element, nullptr) << "element " << i;
		elements.push_back(element);
	}
	EXPECT_EQ(pool.getFreeCount(), 0);
	EXPECT_EQ(pool.getUsedCount(), 10);
	EXPECT_EQ(pool.allocate(8), nullptr) << "a full pool returns null";
	EXPECT_EQ(elements[0], static_cast<void*>(pool.getPoolAddress()));

	for (void* element : elements) pool.freeMemory(element);
	EXPECT_EQ(pool.getFreeCount(), 10);
	EXPECT_EQ(pool.getUsedCount(), 0);
	EXPECT_NE(pool.allocate(1), nullptr) << "freed elements are reused";
}

TEST(PoolAllocator, ElementsAre16ByteAlignedAndDoNotOverlap)
{
	for (int elemSize : {1, 8, 17, 24, 100})
	{
		btPoolAllocator pool(elemSize, 33);
		std::vector<unsigned char*> elements;
		for (int i = 0; i < 33; ++i)
		{
			unsigned char* element = static_cast<unsigned char*>(pool.allocate(elemSize));
			ASSERT_NE(element, nullptr);
			ASSERT_TRUE(isAligned16(element)) << "element size " << elemSize << ", element " << i;
			memset(element, i, size_t(elemSize));
			elements.push_back(element);
		}
		for (int i = 0; i < 33; ++i)
			for (int b = 0; b < elemSize; ++b)
				ASSERT_EQ(elements[i][b], i) << "element " << i << " overwritten, element size " << elemSize;
		for (unsigned char* element : elements) pool.freeMemory(element);
	}
}

TEST(PoolAllocator, RequestLargerThanElementGivesNull)
{
	btPoolAllocator pool(32, 4);
	EXPECT_EQ(pool.allocate(33), nullptr);
	EXPECT_EQ(pool.getFreeCount(), 4);
	void* element = pool.allocate(0);
	EXPECT_NE(element, nullptr) << "size 0 still gets an element";
	pool.freeMemory(element);
}

TEST(PoolAllocator, ValidPtrAcceptsOnlyElementStarts)
{
	btPoolAllocator pool(20, 8);
	unsigned char* first = static_cast<unsigned char*>(pool.allocate(20));
	unsigned char* second = static_cast<unsigned char*>(pool.allocate(20));
	int outside = 0;
	EXPECT_TRUE(pool.validPtr(first));
	EXPECT_TRUE(pool.validPtr(second));
	EXPECT_TRUE(pool.validPtr(pool.getPoolAddress() + 7 * 32)) << "free elements are valid too";
	EXPECT_FALSE(pool.validPtr(first + 4)) << "interior pointer";
	EXPECT_FALSE(pool.validPtr(pool.getPoolAddress() + 8 * 32)) << "one past the end";
	EXPECT_FALSE(pool.validPtr(&outside));
	EXPECT_FALSE(pool.validPtr(nullptr));
	pool.freeMemory(nullptr);
	EXPECT_EQ(pool.getUsedCount(), 2);
	pool.freeMemory(first);
	pool.freeMemory(second);
}

TEST(PoolAllocator, EmptyPoolAlwaysReturnsNull)
{
	btPoolAllocator pool(16, 0);
	EXPECT_EQ(pool.allocate(16), nullptr);
	EXPECT_EQ(pool.getFreeCount(), 0);
	EXPECT_EQ(pool.getMaxCount(), 0);
}

TEST(PoolAllocator, ConcurrentAllocateAndFreeKeepCountsConsistent)
{
	btPoolAllocator pool(64, 256);
	std::atomic<int> failures(0);
	std::vector<std::thread> threads;
	for (int t = 0; t < 4; ++t)
	{
		threads.emplace_back(
		    [&pool, &failures, t]
		    {
			    std::vector<void*> mine;
			    for (int round = 0; round < 2000; ++round)
			    {
				    void* element = pool.allocate(64);
				    if (element)
				    {
					    *static_cast<int*>(element) = t;
					    mine.push_back(element);
				    }
				    if (mine.size() > 30 || (!element && !mine.empty()))
				    {
					    if (*static_cast<int*>(mine.back()) != t) ++failures;
					    pool.freeMemory(mine.back());
					    mine.pop_back();
				    }
			    }
			    for (void* element : mine) pool.freeMemory(element);
		    });
	}
	for (std::thread& thread : threads) thread.join();
	EXPECT_EQ(failures.load(), 0) << "an element was handed to two threads";
	EXPECT_EQ(pool.getFreeCount(), 256);
}

TEST(StackAlloc, AllocationsAre16ByteAligned)
{
	btStackAlloc stack(4096);
	for (unsigned int size : {1u, 3u, 16u, 17u, 33u, 0u, 7u})
	{
		unsigned char* block = stack.allocate(size);
		ASSERT_NE(block, nullptr) << "size " << size;
		EXPECT_TRUE(isAligned16(block)) << "size " << size << " at " << static_cast<void*>(block);
	}
}

TEST(StackAlloc, ReturnsNullWhenOutOfSpace)
{
	btStackAlloc stack(256);
	EXPECT_EQ(stack.getAvailableMemory(), 256);
	unsigned char* whole = stack.allocate(200);
	ASSERT_NE(whole, nullptr);
	EXPECT_EQ(stack.getAvailableMemory(), 56);
	EXPECT_EQ(stack.allocate(57), nullptr);
	EXPECT_EQ(stack.getAvailableMemory(), 56) << "a failed request uses nothing";
	EXPECT_NE(stack.allocate(40), nullptr) << "200 rounds up to 208, leaving 48";
	EXPECT_EQ(stack.allocate(0xffffffffu), nullptr);
}

TEST(StackAlloc, EndBlockReleasesEverythingSinceBeginBlock)
{
	btStackAlloc stack(1024);
	ASSERT_NE(stack.allocate(10), nullptr);
	const int availableBefore = stack.getAvailableMemory();
	btBlock* outer = stack.beginBlock();
	ASSERT_NE(outer, nullptr);
	unsigned char* a = stack.allocate(100);
	btBlock* inner = stack.beginBlock();
	ASSERT_NE(inner, nullptr);
	EXPECT_EQ(inner->previous, outer);
	unsigned char* b = stack.allocate(200);
	ASSERT_NE(b, nullptr);
	const int availableInInner = stack.getAvailableMemory();
	stack.endBlock(inner);
	EXPECT_GT(stack.getAvailableMemory(), availableInInner);
	EXPECT_EQ(stack.allocate(200), reinterpret_cast<unsigned char*>(inner))
	    << "the inner block's space (record included) is handed out again";
	stack.endBlock(outer);
	EXPECT_EQ(stack.getAvailableMemory(), availableBefore);
	EXPECT_EQ(reinterpret_cast<unsigned char*>(outer), stack.allocate(1));
	EXPECT_NE(a, nullptr);
}

TEST(StackAlloc, BeginBlockFailsCleanlyWhenFull)
{
	btStackAlloc stack(64);
	ASSERT_NE(stack.allocate(64), nullptr);
	btBlock* block = stack.beginBlock();
	EXPECT_EQ(block, nullptr);
	stack.endBlock(block);
	EXPECT_EQ(stack.getAvailableMemory(), 0);
}

TEST(StackAlloc, CreateReplacesTheBuffer)
{
	btStackAlloc stack(64);
	stack.allocate(32);
	stack.create(512);
	EXPECT_EQ(stack.getAvailableMemory(), 512);
	stack.destroy();
	EXPECT_EQ(stack.getAvailableMemory(), 0);
	EXPECT_EQ(stack.allocate(1), nullptr);
	EXPECT_EQ(stack.beginBlock(), nullptr);
}

#if CALIBER_ASSERTS_ENABLED
TEST(PoolAllocatorDeathTest, FreeingForeignPointerAsserts)
{
	btPoolAllocator pool(16, 4);
	int outside = 0;
	EXPECT_DEATH(pool.freeMemory(&outside), "assertion failed");
}

TEST(StackAllocDeathTest, EndingAnOuterBlockFirstAsserts)
{
	btStackAlloc stack(1024);
	btBlock* outer = stack.beginBlock();
	stack.beginBlock();
	EXPECT_DEATH(stack.endBlock(outer), "assertion failed");
}
#else
TEST(PoolAllocator, FreeingForeignPointerIsIgnoredInRelease)
{
	btPoolAllocator pool(16, 4);
	void* element = pool.allocate(16);
	int outside = 0;
	pool.freeMemory(&outside);
	pool.freeMemory(static_cast<unsigned char*>(element) + 4);
	EXPECT_EQ(pool.getUsedCount(), 1);
	pool.freeMemory(element);
	EXPECT_EQ(pool.getUsedCount(), 0);
}

TEST(StackAlloc, EndingAnOuterBlockClosesInnerOnesInRelease)
{
	btStackAlloc stack(1024);
	const int available = stack.getAvailableMemory();
	btBlock* outer = stack.beginBlock();
	btBlock* inner = stack.beginBlock();
	stack.allocate(100);
	stack.endBlock(outer);
	EXPECT_EQ(stack.getAvailableMemory(), available);
	stack.endBlock(inner);  // already closed: ignored
	EXPECT_EQ(stack.getAvailableMemory(), available);
}
#endif
