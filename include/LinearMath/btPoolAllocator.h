// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_POOL_ALLOCATOR_H
#define BT_POOL_ALLOCATOR_H

/// btPoolAllocator: a fixed number of equal-sized, 16-byte-aligned elements carved from one block,
/// with a free list threaded through the unused elements. allocate and freeMemory are O(1) and
/// safe to call from several threads at once.
///
/// Bad input: allocate returns null when the pool is full or the request is larger than the
/// element size (callers fall back to btAlignedAlloc, as the collision dispatcher does).
/// freeMemory(null) is a no-op; freeing a pointer that is not an element of this pool asserts,
/// and is ignored in release builds.

#include "LinearMath/btScalar.h"

#include <mutex>

/// Fixed-capacity allocator of equal-sized elements.
class btPoolAllocator
{
	int m_elemSize;
	int m_maxElements;
	int m_stride;
	int m_freeCount;
	void* m_firstFree;
	unsigned char* m_pool;
	std::mutex m_mutex;

public:
	/// Reserves room for maxElements elements of elemSize bytes each (each rounded up to 16 bytes).
	btPoolAllocator(int elemSize, int maxElements);
	/// Frees the pool; elements still in use become invalid.
	~btPoolAllocator();

	btPoolAllocator(const btPoolAllocator&) = delete;
	btPoolAllocator& operator=(const btPoolAllocator&) = delete;

	/// Number of elements that can still be allocated.
	int getFreeCount() const { return m_freeCount; }
	/// Number of elements currently allocated.
	int getUsedCount() const { return m_maxElements - m_freeCount; }
	/// Number of elements the pool holds in total.
	int getMaxCount() const { return m_maxElements; }

	/// One free element (16-byte aligned), or null when the pool is full or size > getElementSize().
	void* allocate(int size);

	/// True when ptr is the start of an element of this pool (allocated or not).
	bool validPtr(void* ptr);

	/// Returns an element from allocate to the pool; null is ignored.
	void freeMemory(void* ptr);

	/// The element size given at construction.
	int getElementSize() const { return m_elemSize; }

	/// Start of the pool's block (element i is at i * (element size rounded up to 16)).
	unsigned char* getPoolAddress() { return m_pool; }
	/// Start of the pool's block.
	const unsigned char* getPoolAddress() const { return m_pool; }
};

#endif  // BT_POOL_ALLOCATOR_H
