// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_STACK_ALLOC_H
#define BT_STACK_ALLOC_H

/// btStackAlloc: a bump allocator over one 16-byte-aligned block, with nested blocks (beginBlock /
/// endBlock) that release everything allocated since the matching beginBlock in one step.
///
/// Bad input: allocate returns null when the request does not fit (no assert), and beginBlock then
/// returns null too; endBlock(null) is a no-op. Ending a block other than the innermost open one
/// asserts; in release builds it also closes the blocks opened after it when it is still open,
/// and is ignored otherwise.

#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btScalar.h"

/// Record of an open block, stored on the stack itself.
struct btBlock
{
	/// The block that was innermost when this one was opened, or null.
	btBlock* previous;
	/// Top of the stack when this block was opened; endBlock returns the stack to it.
	unsigned char* address;
};

/// Stack (bump) allocator with nested blocks.
class btStackAlloc
{
	unsigned char* m_data;
	unsigned int m_totalSize;
	unsigned int m_usedSize;
	btBlock* m_current;

	static unsigned int alignUp(unsigned int offset) { return (offset + 15u) & ~15u; }

public:
	/// Allocates a block of size bytes (16-byte aligned).
	explicit btStackAlloc(unsigned int size) : m_data(nullptr), m_totalSize(0), m_usedSize(0), m_current(nullptr)
	{
		create(size);
	}
	/// Frees the block.
	~btStackAlloc() { destroy(); }

	btStackAlloc(const btStackAlloc&) = delete;
	btStackAlloc& operator=(const btStackAlloc&) = delete;

	/// Replaces the block with a new empty one of size bytes; earlier allocations become invalid.
	void create(unsigned int size)
	{
		destroy();
		m_data = static_cast<unsigned char*>(btAlignedAlloc(size, 16));
		m_totalSize = m_data ? size : 0;
	}

	/// Frees the block and forgets every allocation and open block.
	void destroy()
	{
		btAlignedFree(m_data);
		m_data = nullptr;
		m_totalSize = 0;
		m_usedSize = 0;
		m_current = nullptr;
	}

	/// Bytes left above the top of the stack (alignment padding of the next request not counted).
	int getAvailableMemory() const { return static_cast<int>(m_totalSize - m_usedSize); }

	/// size bytes at a 16-byte-aligned address, or null when they do not fit.
	unsigned char* allocate(unsigned int size)
	{
		const unsigned int start = alignUp(m_usedSize);
		if (start > m_totalSize || size > m_totalSize - start) return nullptr;
		m_usedSize = start + size;
		return m_data + start;
	}

	/// Opens a block: everything allocated until the matching endBlock is released by it. Null
	/// when the stack has no room for the block record.
	btBlock* beginBlock()
	{
		unsigned char* top = m_data + m_usedSize;
		btBlock* block = reinterpret_cast<btBlock*>(allocate(sizeof(btBlock)));
		if (!block) return nullptr;
		block->previous = m_current;
		block->address = top;
		m_current = block;
		return block;
	}

	/// Closes block (the innermost open one) and returns the stack to where it was at beginBlock.
	void endBlock(btBlock* block)
	{
		if (!block) return;
		btAssert(block == m_current);
		btBlock* open = m_current;
		while (open && open != block) open = open->previous;
		if (!open) return;
		m_current = block->previous;
		m_usedSize = static_cast<unsigned int>(block->address - m_data);
	}
};

#endif  // BT_STACK_ALLOC_H
