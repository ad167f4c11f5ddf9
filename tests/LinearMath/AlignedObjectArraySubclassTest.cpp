// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// A user container derived from btAlignedObjectArray, written against Bullet 2.89's protected
// interface (allocSize, copy, init, destroy, allocate, deallocate): it must compile, and each member
// must do what its Bullet name says, with constructions and destructions balanced.
#include "LinearMath/btAlignedObjectArray.h"

#include <gtest/gtest.h>

#include <stdint.h>

namespace
{
// Counts live objects; a dead one is recognised by its cleared magic.
struct Counted
{
	static int s_live;
	int value;
	unsigned magic;

	explicit Counted(int v = 0) : value(v), magic(kAlive) { ++s_live; }
	Counted(const Counted& other) : value(other.value), magic(kAlive)
	{
		EXPECT_EQ(other.magic, kAlive) << "copied from a dead element";
		++s_live;
	}
	Counted& operator=(const Counted& other) = default;
	~Counted()
	{
		EXPECT_EQ(magic, kAlive) << "destroyed twice or never constructed";
		magic = 0;
		--s_live;
	}
	static constexpr unsigned kAlive = 0xC0FFEEu;
};
int Counted::s_live = 0;

template <typename T>
class UserArray : public btAlignedObjectArray<T>
{
public:
	// A copy of elements [start, end) in a raw block of the array's allocator.
	T* copyOut(int start, int end)
	{
		T* block = static_cast<T*>(this->allocate(end - start));
		this->copy(start, end, block);
		return block;
	}
	static void freeBlock(T* block, int count)
	{
		for (int i = 0; i < count; ++i) block[i].~T();
		btAlignedFree(block);
	}
	// What Bullet's clear does, through the protected members.
	void dropEverything()
	{
		this->destroy(0, this->size());
		this->deallocate();
		this->init();
	}
	int grownCapacity() { return this->allocSize(this->size()); }
	void* rawBlock(int count) { return this->allocate(count); }
};

int g_frees = 0;
void* countingAlloc(size_t size, int alignment)
{
	return aligned_alloc(size_t(alignment), (size + size_t(alignment) - 1) / size_t(alignment) * size_t(alignment));
}
void countingFree(void* ptr)
{
	++g_frees;
	free(ptr);
}
}  // namespace

TEST(AlignedObjectArraySubclass, CopyConstructsTheRangeIntoRawStorage)
{
	{
		UserArray<Counted> array;
		for (int i = 0; i < 5; ++i) array.push_back(Counted(10 * i));
		ASSERT_EQ(Counted::s_live, 5);
		Counted* block = array.copyOut(1, 4);
		EXPECT_EQ(Counted::s_live, 8) << "three copies constructed";
		EXPECT_EQ(block[0].value, 10);
		EXPECT_EQ(block[2].value, 30);
		EXPECT_EQ(reinterpret_cast<uintptr_t>(block) % 16, 0u) << "allocate gives the array's alignment";
		UserArray<Counted>::freeBlock(block, 3);
		EXPECT_EQ(array.size(), 5) << "copy leaves the array alone";
	}
	EXPECT_EQ(Counted::s_live, 0);
}

TEST(AlignedObjectArraySubclass, DestroyDeallocateInitEmptyTheArray)
{
	UserArray<Counted> array;
	for (int i = 0; i < 7; ++i) array.push_back(Counted(i));
	array.dropEverything();
	EXPECT_EQ(Counted::s_live, 0) << "destroy ended every element's life";
	EXPECT_EQ(array.size(), 0);
	EXPECT_EQ(array.capacity(), 0);
	array.push_back(Counted(3));
	EXPECT_EQ(array[0].value, 3) << "usable again after init";
	array.clear();
	EXPECT_EQ(Counted::s_live, 0);
}

TEST(AlignedObjectArraySubclass, DeallocateNeverFreesACallersBuffer)
{
	alignas(16) static int buffer[8] = {1, 2, 3, 4};
	btAlignedAllocSetCustomAligned(countingAlloc, countingFree);
	g_frees = 0;
	{
		UserArray<int> array;
		array.initializeFromBuffer(buffer, 4, 8);
		array.dropEverything();
		EXPECT_EQ(g_frees, 0) << "the buffer belongs to the caller";
		EXPECT_EQ(buffer[3], 4);
		array.push_back(9);
		EXPECT_EQ(array.capacity(), 1) << "after init the array owns its storage again";
		array.dropEverything();
		EXPECT_EQ(g_frees, 1) << "owned storage is freed";
	}
	btAlignedAllocSetCustomAligned(nullptr, nullptr);
}

TEST(AlignedObjectArraySubclass, AllocSizeDoublesAndAllocateOfNothingIsNull)
{
	UserArray<int> array;
	EXPECT_EQ(array.grownCapacity(), 1);
	for (int i = 0; i < 3; ++i) array.push_back(i);
	EXPECT_EQ(array.grownCapacity(), 6);
	EXPECT_EQ(array.rawBlock(0), nullptr);
	EXPECT_EQ(array.rawBlock(-4), nullptr) << "a nonsense size allocates nothing";
}
