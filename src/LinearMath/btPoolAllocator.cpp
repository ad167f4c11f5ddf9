// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btPoolAllocator.h"

#include "LinearMath/btAlignedAllocator.h"

#include <stddef.h>
#include <stdint.h>

namespace
{
const int kPoolAlignment = 16;

// The free list link lives in the first bytes of each unused element.
void*& nextFreeOf(void* element) { return *static_cast<void**>(element); }
}  // namespace

btPoolAllocator::btPoolAllocator(int elemSize, int maxElements)
    : m_elemSize(elemSize),
      m_maxElements(maxElements),
      m_stride(0),
      m_freeCount(0),
      m_firstFree(nullptr),
      m_pool(nullptr)
{
	btAssert(elemSize > 0 && maxElements >= 0);
	// Release builds: a non-positive element size behaves as 1 byte, a negative count as 0.
	if (m_elemSize <= 0) m_elemSize = 1;
	if (m_maxElements < 0) m_maxElements = 0;
	m_stride = (m_elemSize + kPoolAlignment - 1) & ~(kPoolAlignment - 1);
	if (m_maxElements == 0) return;

	m_pool = static_cast<unsigned char*>(btAlignedAlloc(size_t(m_stride) * size_t(m_maxElements), kPoolAlignment));
	btAssert(m_pool != nullptr);
	if (!m_pool)
	{
		m_maxElements = 0;
		return;
	}
	// Thread the free list in address order, so that a fresh pool hands out element 0, 1, 2, ...
	for (int i = 0; i < m_maxElements - 1; ++i)
		nextFreeOf(m_pool + size_t(i) * size_t(m_stride)) = m_pool + size_t(i + 1) * size_t(m_stride);
	nextFreeOf(m_pool + size_t(m_maxElements - 1) * size_t(m_stride)) = nullptr;
	m_firstFree = m_pool;
	m_freeCount = m_maxElements;
}

btPoolAllocator::~btPoolAllocator() { btAlignedFree(m_pool); }

void* btPoolAllocator::allocate(int size)
{
	if (size > m_elemSize) return nullptr;
	std::lock_guard<std::mutex> lock(m_mutex);
	if (!m_firstFree) return nullptr;
	void* element = m_firstFree;
	m_firstFree = nextFreeOf(element);
	--m_freeCount;
	return element;
}

bool btPoolAllocator::validPtr(void* ptr)
{
	if (!ptr || !m_pool) return false;
	const unsigned char* bytes = static_cast<const unsigned char*>(ptr);
	// Compare as integers: relational operators on unrelated pointers are unspecified.
	const uintptr_t address = reinterpret_cast<uintptr_t>(bytes);
	const uintptr_t begin = reinterpret_cast<uintptr_t>(m_pool);
	const uintptr_t end = begin + uintptr_t(m_stride) * uintptr_t(m_maxElements);
	if (address < begin || address >= end) return false;
	return (address - begin) % uintptr_t(m_stride) == 0;
}

void btPoolAllocator::freeMemory(void* ptr)
{
	if (!ptr) return;
	btAssert(validPtr(ptr));
	if (!validPtr(ptr)) return;
	std::lock_guard<std::mutex> lock(m_mutex);
	btAssert(m_freeCount < m_maxElements);
	if (m_freeCount >= m_maxElements) return;
	nextFreeOf(ptr) = m_firstFree;
	m_firstFree = ptr;
	++m_freeCount;
}
