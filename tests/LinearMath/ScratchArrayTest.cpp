// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The per-step scratch arrays' sizing (src/LinearMath/btScratchArray.h): a scratch array that grows a
// little every step must not be reallocated every step, and its contents must survive the growth.
#include <gtest/gtest.h>

#include "LinearMath/btScratchArray.h"

TEST(ScratchArray, GrowingByOneEachStepReallocatesLogarithmicallyOften)
{
	// btAlignedObjectArray::resizeNoInitialize reserves exactly: 1000 steps growing by one would be 1000
	// reallocations. Doubling allows at most log2(1000) + 1 of them.
	btAlignedObjectArray<int> array;
	int reallocations = 0;
	const int* data = 0;
	for (int size = 1; size <= 1000; ++size)
	{
		caliber::resizeScratch(array, size);
		ASSERT_EQ(array.size(), size);
		if (&array[0] != data) ++reallocations;
		data = &array[0];
	}
	EXPECT_LE(reallocations, 11);
	EXPECT_GE(array.capacity(), 1000);
}

TEST(ScratchArray, ResizeKeepsTheElementsItKeeps)
{
	btAlignedObjectArray<int> array;
	caliber::resizeScratch(array, 5);
	for (int i = 0; i < 5; ++i) array[i] = 10 * i;
	caliber::resizeScratch(array, 300);
	for (int i = 0; i < 5; ++i) EXPECT_EQ(array[i], 10 * i);
	caliber::resizeScratch(array, 3);
	EXPECT_EQ(array.size(), 3);
	EXPECT_EQ(array[2], 20);
	EXPECT_GE(array.capacity(), 300);  // shrinking keeps the room
}

TEST(ScratchArray, AssignSetsEveryElementAndConvertsTheFill)
{
	btAlignedObjectArray<unsigned int> array;
	caliber::assignScratch(array, 4, 7);
	caliber::assignScratch(array, 10, 0);  // an int fill for an unsigned array
	ASSERT_EQ(array.size(), 10);
	for (int i = 0; i < 10; ++i) EXPECT_EQ(array[i], 0u);
	caliber::assignScratch(array, 0, 1);
	EXPECT_EQ(array.size(), 0);
}

TEST(ScratchArray, NegativeCountsLeaveAnEmptyArray)
{
	// resizeNoInitialize asserts on a negative size and clamps it in release; reserveScratch never
	// shrinks. Only release behaviour can be checked here without tripping the assert.
	btAlignedObjectArray<int> array;
	caliber::reserveScratch(array, -5);
	EXPECT_EQ(array.size(), 0);
	EXPECT_EQ(array.capacity(), 0);
}
