// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ALIGNED_OBJECT_H
#define CALIBER_ALIGNED_OBJECT_H

// Single objects and arrays in 16-byte aligned memory from btAlignedAlloc, made and released in one call
// each, so that an owner's constructor and destructor read as the list of what it owns.

#include <new>
#include <stddef.h>
#include <utility>

#include "LinearMath/btAlignedAllocator.h"

namespace caliber
{
/// Constructs a T in aligned memory.
template <class T, class... Args>
T* alignedNew(Args&&... args)
{
	return new (btAlignedAlloc(sizeof(T), 16)) T(std::forward<Args>(args)...);
}

/// Destroys an object made by alignedNew (through T's destructor, virtual or not); null is ignored.
template <class T>
void alignedDelete(T* object)
{
	if (!object) return;
	object->~T();
	btAlignedFree(object);
}

/// Constructs count default Ts in one aligned block.
template <class T>
T* alignedNewArray(size_t count)
{
	T* block = static_cast<T*>(btAlignedAlloc(sizeof(T) * count, 16));
	for (size_t i = 0; i < count; ++i) new (&block[i]) T();
	return block;
}

/// Destroys an array made by alignedNewArray with the same count; null is ignored.
template <class T>
void alignedDeleteArray(T* block, size_t count)
{
	if (!block) return;
	for (size_t i = 0; i < count; ++i) block[i].~T();
	btAlignedFree(block);
}
}  // namespace caliber

#endif  // CALIBER_ALIGNED_OBJECT_H
