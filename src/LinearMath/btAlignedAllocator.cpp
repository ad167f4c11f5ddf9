// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btAlignedAllocator.h"

#include <stdint.h>
#include <stdlib.h>

namespace
{
void* defaultPlainAlloc(size_t size) { return malloc(size); }
void defaultPlainFree(void* ptr) { free(ptr); }

// Aligns on top of a plain allocator: over-allocate, round up, and keep the original pointer in the
// word just below the block handed out.
btAllocFunc* g_plainAlloc = defaultPlainAlloc;
btFreeFunc* g_plainFree = defaultPlainFree;

void* alignOnTopOfPlainAlloc(size_t size, int alignment)
{
	const size_t extra = size_t(alignment) + sizeof(void*);
	if (size > SIZE_MAX - extra) return nullptr;
	char* raw = static_cast<char*>(g_plainAlloc(size + extra));
	if (!raw) return nullptr;
	const uintptr_t firstUsable = reinterpret_cast<uintptr_t>(raw) + sizeof(void*);
	const uintptr_t aligned = (firstUsable + uintptr_t(alignment) - 1) & ~(uintptr_t(alignment) - 1);
	void** slot = reinterpret_cast<void**>(aligned) - 1;
	*slot = raw;
	return reinterpret_cast<void*>(aligned);
}

void freeOnTopOfPlainAlloc(void* ptr)
{
	void* raw = *(static_cast<void**>(ptr) - 1);
	g_plainFree(raw);
}

btAlignedAllocFunc* g_alignedAlloc = alignOnTopOfPlainAlloc;
btAlignedFreeFunc* g_alignedFree = freeOnTopOfPlainAlloc;

bool isPowerOfTwo(int value) { return value > 0 && (value & (value - 1)) == 0; }
}  // namespace

void* btAlignedAllocInternal(size_t size, int alignment)
{
	btAssert(isPowerOfTwo(alignment));
	// Release builds: a bad alignment is raised to the next power of two of at least pointer size,
	// so the caller still receives usable, aligned memory.
	if (!isPowerOfTwo(alignment))
	{
		int fixed = int(sizeof(void*));
		while (fixed < alignment && fixed < (1 << 20)) fixed <<= 1;
		alignment = fixed;
	}
	// operator new (BT_DECLARE_ALIGNED_ALLOCATOR) must return a unique pointer even for 0 bytes.
	if (size == 0) size = 1;
	return g_alignedAlloc(size, alignment);
}

void btAlignedFreeInternal(void* ptr)
{
	if (!ptr) return;
	g_alignedFree(ptr);
}

void btAlignedAllocSetCustom(btAllocFunc* allocFunc, btFreeFunc* freeFunc)
{
	g_plainAlloc = allocFunc ? allocFunc : defaultPlainAlloc;
	g_plainFree = freeFunc ? freeFunc : defaultPlainFree;
}

void btAlignedAllocSetCustomAligned(btAlignedAllocFunc* allocFunc, btAlignedFreeFunc* freeFunc)
{
	g_alignedAlloc = allocFunc ? allocFunc : alignOnTopOfPlainAlloc;
	g_alignedFree = freeFunc ? freeFunc : freeOnTopOfPlainAlloc;
}
