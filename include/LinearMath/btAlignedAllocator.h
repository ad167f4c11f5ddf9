// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_ALIGNED_ALLOCATOR
#define BT_ALIGNED_ALLOCATOR

/// Aligned heap allocation for the whole SDK, with hooks to route it through a user's allocator.

#include "LinearMath/btScalar.h"

/// Signature of a user allocator that honours an alignment.
typedef void*(btAlignedAllocFunc)(size_t size, int alignment);
/// Signature of the matching free.
typedef void(btAlignedFreeFunc)(void* memblock);
/// Signature of a plain (malloc-like) user allocator; Caliber aligns on top of it.
typedef void*(btAllocFunc)(size_t size);
/// Signature of the matching plain free.
typedef void(btFreeFunc)(void* memblock);

/// Allocates size bytes aligned to alignment (a power of two). Size 0 gives a unique minimal block (as operator new
/// must); returns null only when the underlying allocator fails.
void* btAlignedAllocInternal(size_t size, int alignment);
/// Frees memory from btAlignedAllocInternal; null is ignored.
void btAlignedFreeInternal(void* ptr);

/// The names Bullet programs call.
inline void* btAlignedAlloc(size_t size, int alignment) { return btAlignedAllocInternal(size, alignment); }
inline void btAlignedFree(void* ptr) { btAlignedFreeInternal(ptr); }

/// Routes allocations through a plain malloc/free pair (null restores the default). Call before
/// any allocation is made, or after all are freed: blocks must be freed by the allocator that made them.
void btAlignedAllocSetCustom(btAllocFunc* allocFunc, btFreeFunc* freeFunc);
/// Routes allocations through an aligned allocator pair (null restores the default).
void btAlignedAllocSetCustomAligned(btAlignedAllocFunc* allocFunc, btAlignedFreeFunc* freeFunc);

/// Standard-style allocator used by btAlignedObjectArray; every block is Alignment-aligned.
template <typename T, unsigned Alignment>
class btAlignedAllocator
{
	typedef btAlignedAllocator<T, Alignment> self_type;

public:
	btAlignedAllocator() {}
	template <typename Other>
	btAlignedAllocator(const btAlignedAllocator<Other, Alignment>&)
	{
	}

	typedef const T* const_pointer;
	typedef const T& const_reference;
	typedef T* pointer;
	typedef T& reference;
	typedef T value_type;

	pointer address(reference ref) const { return &ref; }
	const_pointer address(const_reference ref) const { return &ref; }
	/// Allocates room for n elements (not constructed). The hint is ignored.
	pointer allocate(int n, const_pointer* hint = 0)
	{
		(void)hint;
		return reinterpret_cast<pointer>(btAlignedAlloc(sizeof(value_type) * size_t(n), int(Alignment)));
	}
	void construct(pointer ptr, const value_type& value) { new (ptr) value_type(value); }
	void deallocate(pointer ptr) { btAlignedFree(reinterpret_cast<void*>(ptr)); }
	void destroy(pointer ptr) { ptr->~value_type(); }

	template <typename O>
	struct rebind
	{
		typedef btAlignedAllocator<O, Alignment> other;
	};
	template <typename O>
	self_type& operator=(const btAlignedAllocator<O, Alignment>&)
	{
		return *this;
	}

	friend bool operator==(const self_type&, const self_type&) { return true; }
};

#endif  // BT_ALIGNED_ALLOCATOR
