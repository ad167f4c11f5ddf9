// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btAlignedObjectArray.h"

#include <gtest/gtest.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <vector>

namespace
{
bool isAligned(const void* ptr, uintptr_t alignment) { return reinterpret_cast<uintptr_t>(ptr) % alignment == 0; }

int g_plainAllocCalls = 0;
int g_plainFreeCalls = 0;
void* countingMalloc(size_t size)
{
	++g_plainAllocCalls;
	return malloc(size);
}
void countingFree(void* ptr)
{
	++g_plainFreeCalls;
	free(ptr);
}

int g_alignedAllocCalls = 0;
int g_alignedFreeCalls = 0;
int g_lastAlignment = 0;
void* countingAlignedAlloc(size_t size, int alignment)
{
	++g_alignedAllocCalls;
	g_lastAlignment = alignment;
	return aligned_alloc(size_t(alignment), (size + size_t(alignment) - 1) / size_t(alignment) * size_t(alignment));
}
void countingAlignedFree(void* ptr)
{
	++g_alignedFreeCalls;
	free(ptr);
}

// Restores the default allocator even when an assertion returns early.
struct RestoreDefaultAllocators
{
	~RestoreDefaultAllocators()
	{
		btAlignedAllocSetCustom(nullptr, nullptr);
		btAlignedAllocSetCustomAligned(nullptr, nullptr);
	}
};
}  // namespace

TEST(AlignedAlloc, HonoursAlignments16To128)
{
	for (int alignment : {16, 32, 64, 128})
	{
		std::vector<void*> blocks;
		for (size_t size : {size_t(1), size_t(7), size_t(16), size_t(100), size_t(4096), size_t(100000)})
		{
			void* block = btAlignedAlloc(size, alignment);
			ASSERT_NE(block, nullptr);
			EXPECT_TRUE(isAligned(block, uintptr_t(alignment)))
			    << "alignment " << alignment << ", size " << size << ", address " << block;
			memset(block, 0xab, size);  // the whole block is usable (ASan checks the bounds)
			blocks.push_back(block);
		}
		for (void* block : blocks) btAlignedFree(block);
	}
}

// operator new of BT_DECLARE_ALIGNED_ALLOCATOR classes relies on this: new T[0] must give a
// unique, non-null pointer.
TEST(AlignedAlloc, ZeroSizeGivesDistinctAlignedBlocksAndFreeingNullIsHarmless)
{
	void* a = btAlignedAlloc(0, 16);
	void* b = btAlignedAlloc(0, 16);
	ASSERT_NE(a, nullptr);
	ASSERT_NE(b, nullptr);
	EXPECT_NE(a, b);
	EXPECT_EQ(reinterpret_cast<uintptr_t>(a) % 16, 0u);
	btAlignedFree(a);
	btAlignedFree(b);
	btAlignedFree(nullptr);
}

TEST(AlignedAlloc, CustomPlainAllocatorIsUsedAndRestored)
{
	RestoreDefaultAllocators restore;
	g_plainAllocCalls = g_plainFreeCalls = 0;
	btAlignedAllocSetCustom(countingMalloc, countingFree);
	std::vector<void*> blocks;
	for (int alignment : {16, 32, 64, 128})
	{
		void* block = btAlignedAlloc(40, alignment);
		ASSERT_NE(block, nullptr);
		EXPECT_TRUE(isAligned(block, uintptr_t(alignment))) << "alignment " << alignment;
		blocks.push_back(block);
	}
	EXPECT_EQ(g_plainAllocCalls, 4);
	for (void* block : blocks) btAlignedFree(block);
	EXPECT_EQ(g_plainFreeCalls, 4);

	btAlignedAllocSetCustom(nullptr, nullptr);
	void* block = btAlignedAlloc(40, 16);
	btAlignedFree(block);
	EXPECT_EQ(g_plainAllocCalls, 4) << "the default allocator is back";
	EXPECT_EQ(g_plainFreeCalls, 4);
}

TEST(AlignedAlloc, CustomAlignedAllocatorReceivesTheAlignment)
{
	RestoreDefaultAllocators restore;
	g_alignedAllocCalls = g_alignedFreeCalls = 0;
	btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree);
	for (int alignment : {16, 32, 64, 128})
	{
		void* block = btAlignedAlloc(10, alignment);
		ASSERT_NE(block, nullptr);
		EXPECT_EQ(g_lastAlignment, alignment);
		EXPECT_TRUE(isAligned(block, uintptr_t(alignment)));
		btAlignedFree(block);
	}
	EXPECT_EQ(g_alignedAllocCalls, 4);
	EXPECT_EQ(g_alignedFreeCalls, 4);

	btAlignedAllocSetCustomAligned(nullptr, nullptr);
	btAlignedFree(btAlignedAlloc(10, 16));
	EXPECT_EQ(g_alignedAllocCalls, 4) << "the default allocator is back";
}

TEST(AlignedAlloc, ObjectArrayStorageGoesThroughTheHooksAndBalances)
{
	RestoreDefaultAllocators restore;
	g_alignedAllocCalls = g_alignedFreeCalls = 0;
	btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree);
	{
		btAlignedObjectArray<int> array;
		for (int i = 0; i < 1000; ++i) array.push_back(i);
		EXPECT_EQ(g_alignedAllocCalls, 11) << "capacities 1, 2, 4, ..., 1024";
		EXPECT_EQ(g_lastAlignment, 16);
	}
	EXPECT_EQ(g_alignedFreeCalls, g_alignedAllocCalls);
}

TEST(AlignedAlloc, AlignedAllocatorTemplateAllocatesAlignedBlocks)
{
	btAlignedAllocator<double, 64> allocator;
	double* block = allocator.allocate(5);
	ASSERT_NE(block, nullptr);
	EXPECT_TRUE(isAligned(block, 64));
	allocator.construct(block, 2.5);
	EXPECT_EQ(block[0], 2.5);
	allocator.destroy(block);
	allocator.deallocate(block);
}

#if CALIBER_ASSERTS_ENABLED
TEST(AlignedAllocDeathTest, NonPowerOfTwoAlignmentAsserts)
{
	EXPECT_DEATH(btAlignedFree(btAlignedAlloc(16, 24)), "assertion failed");
}
#else
TEST(AlignedAlloc, NonPowerOfTwoAlignmentIsRaisedInRelease)
{
	void* block = btAlignedAlloc(16, 24);
	ASSERT_NE(block, nullptr);
	EXPECT_TRUE(isAligned(block, 32)) << "24 is raised to the next power of two, address " << block;
	btAlignedFree(block);
}
#endif
