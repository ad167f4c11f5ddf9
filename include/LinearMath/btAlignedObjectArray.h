// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_OBJECT_ARRAY_H
#define BT_OBJECT_ARRAY_H

/// btAlignedObjectArray: the growable array used throughout the API. Storage comes from
/// btAlignedAlloc and every element is at least 16-byte aligned, so btVector3 and friends can be
/// stored by value. Elements are constructed with placement new and destroyed explicitly, so
/// constructor and destructor calls always balance.
///
/// Checks: out-of-range indices fire btAssert when asserts are enabled. In release builds
/// operator[] and at() are unchecked (like std::vector::operator[]); swap, removeAtIndex and
/// pop_back with a bad index or on an empty array do nothing; negative sizes are treated as 0.

#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btScalar.h"

#include <limits.h>
#include <stdint.h>

#include <new>
#include <type_traits>
#include <utility>

namespace caliber
{
/// The alignment of a btAlignedObjectArray's elements: T's own, and at least 16 bytes. A function (not
/// a constant at class scope) so that an array can be a member of T itself.
template <typename T>
constexpr unsigned alignedArrayAlignment()
{
	return alignof(T) > 16 ? unsigned(alignof(T)) : 16u;
}

/// Moves count live elements from one block into raw storage and ends their lives in the old one.
template <typename T>
inline void moveArrayElements(T* from, int count, T* to)
{
	for (int i = 0; i < count; ++i)
	{
		new (&to[i]) T(std::move(from[i]));
		from[i].~T();
	}
}

/// Default-initialises slots [first, last) (no zeroing for plain data), so that a later destructor
/// call is matched.
template <typename T>
inline void defaultInitArrayElements(T* data, int first, int last)
{
	if constexpr (std::is_default_constructible<T>::value && !std::is_trivially_default_constructible<T>::value)
	{
		for (int i = first; i < last; ++i) new (&data[i]) T;
	}
	else
	{
		(void)data;
		(void)first;
		(void)last;
	}
}

/// Exchanges two elements by moves.
template <typename T>
inline void swapArrayElements(T& a, T& b)
{
	T tmp(std::move(a));
	a = std::move(b);
	b = std::move(tmp);
}
}  // namespace caliber

/// Growable array of T with aligned storage, Bullet's container.
template <typename T>
class btAlignedObjectArray
{
	int m_size;
	int m_capacity;
	T* m_data;
	// False after initializeFromBuffer: the storage belongs to the caller and is never freed here.
	bool m_ownsMemory;

	bool isValidIndex(int n) const { return n >= 0 && n < m_size; }

protected:
	/// Capacity to grow to when an array of the given size is full: doubling, starting at 1.
	int allocSize(int size) const
	{
		if (size <= 0) return 1;
		return size > INT_MAX / 2 ? INT_MAX : size * 2;
	}

	/// Copy-constructs elements [start, end) into dest, raw storage for end - start elements.
	void copy(int start, int end, T* dest) const
	{
		for (int i = start; i < end; ++i) new (&dest[i - start]) T(m_data[i]);
	}

	/// An empty array that owns no storage (forgets any storage it had: call deallocate first).
	void init()
	{
		m_size = 0;
		m_capacity = 0;
		m_data = nullptr;
		m_ownsMemory = true;
	}

	/// Ends the lives of elements [first, last); the size and the storage stay as they are.
	void destroy(int first, int last)
	{
		if constexpr (!std::is_trivially_destructible<T>::value)
		{
			for (int i = first; i < last; ++i) m_data[i].~T();
		}
		else
		{
			(void)first;
			(void)last;
		}
	}

	/// Raw aligned storage for size elements, or null for size <= 0. The caller owns it until it
	/// becomes the array's storage.
	void* allocate(int size)
	{
		if (size <= 0) return nullptr;
		T* block = btAlignedAllocator<T, caliber::alignedArrayAlignment<T>()>().allocate(size);
		btAssert(block != nullptr);
		return block;
	}

	/// Frees the storage when the array owns it (not a caller's initializeFromBuffer block) and
	/// forgets it; the elements must have been destroyed first.
	void deallocate()
	{
		if (m_data && m_ownsMemory) btAlignedAllocator<T, caliber::alignedArrayAlignment<T>()>().deallocate(m_data);
		m_data = nullptr;
	}

public:
	/// Empty array; allocates nothing.
	btAlignedObjectArray() { init(); }

	/// Frees the elements and, when owned, the storage.
	~btAlignedObjectArray() { clear(); }

	/// Deep copy: copy-constructs every element into storage of exactly other.size().
	btAlignedObjectArray(const btAlignedObjectArray& otherArray)
	{
		init();
		copyFromArray(otherArray);
	}

	/// Deep copy assignment; same as copyFromArray.
	btAlignedObjectArray& operator=(const btAlignedObjectArray& otherArray)
	{
		copyFromArray(otherArray);
		return *this;
	}

	/// Number of elements.
	SIMD_FORCE_INLINE int size() const { return m_size; }

	/// Number of elements that fit without reallocating.
	SIMD_FORCE_INLINE int capacity() const { return m_capacity; }

	/// Element n; asserts 0 <= n < size(), unchecked in release.
	SIMD_FORCE_INLINE const T& at(int n) const
	{
		btAssert(isValidIndex(n));
		return m_data[n];
	}

	/// Element n; asserts 0 <= n < size(), unchecked in release.
	SIMD_FORCE_INLINE T& at(int n)
	{
		btAssert(isValidIndex(n));
		return m_data[n];
	}

	/// Element n; asserts 0 <= n < size(), unchecked in release.
	SIMD_FORCE_INLINE const T& operator[](int n) const
	{
		btAssert(isValidIndex(n));
		return m_data[n];
	}

	/// Element n; asserts 0 <= n < size(), unchecked in release.
	SIMD_FORCE_INLINE T& operator[](int n)
	{
		btAssert(isValidIndex(n));
		return m_data[n];
	}

	/// Destroys every element and frees the storage (capacity becomes 0).
	void clear()
	{
		destroy(0, m_size);
		deallocate();
		init();
	}

	/// Destroys the last element; asserts on an empty array, does nothing in release.
	void pop_back()
	{
		btAssert(m_size > 0);
		if (m_size <= 0) return;
		--m_size;
		m_data[m_size].~T();
	}

	/// Sets the size without copying a fill value: new elements are default-initialised (left
	/// uninitialised for plain data), removed ones are destroyed. Asserts newsize >= 0.
	void resizeNoInitialize(int newsize)
	{
		btAssert(newsize >= 0);
		if (newsize < 0) newsize = 0;
		if (newsize < m_size)
		{
			destroy(newsize, m_size);
		}
		else if (newsize > m_size)
		{
			reserve(newsize);
			caliber::defaultInitArrayElements(m_data, m_size, newsize);
		}
		m_size = newsize;
	}

	/// Sets the size; new elements are value-initialised (T(): zero for plain numbers, the default
	/// constructor for classes), removed ones are destroyed. Asserts newsize >= 0.
	void resize(int newsize)
	{
		btAssert(newsize >= 0);
		if (newsize < 0) newsize = 0;
		if (newsize < m_size)
		{
			destroy(newsize, m_size);
		}
		else if (newsize > m_size)
		{
			reserve(newsize);
			for (int i = m_size; i < newsize; ++i) new (&m_data[i]) T();
		}
		m_size = newsize;
	}

	/// Sets the size; new elements are copies of fillData (which may be an element of this array),
	/// removed ones are destroyed. Grows capacity to exactly newsize when needed. Asserts newsize >= 0.
	void resize(int newsize, const T& fillData)
	{
		btAssert(newsize >= 0);
		if (newsize < 0) newsize = 0;
		if (newsize < m_size)
		{
			destroy(newsize, m_size);
		}
		else if (newsize > m_capacity)
		{
			// Fill the new block first: fillData may live in the old one.
			T* newData = static_cast<T*>(allocate(newsize));
			for (int i = m_size; i < newsize; ++i) new (&newData[i]) T(fillData);
			caliber::moveArrayElements(m_data, m_size, newData);
			deallocate();
			m_data = newData;
			m_capacity = newsize;
			m_ownsMemory = true;
		}
		else
		{
			for (int i = m_size; i < newsize; ++i) new (&m_data[i]) T(fillData);
		}
		m_size = newsize;
	}

	/// Appends a default-initialised element (uninitialised for plain data) and returns it.
	T& expandNonInitializing()
	{
		if (m_size == m_capacity) reserve(allocSize(m_size));
		caliber::defaultInitArrayElements(m_data, m_size, m_size + 1);
		++m_size;
		return m_data[m_size - 1];
	}

	/// Appends a value-initialised element (T()) and returns it.
	T& expand()
	{
		if (m_size == m_capacity) reserve(allocSize(m_size));
		new (&m_data[m_size]) T();
		++m_size;
		return m_data[m_size - 1];
	}

	/// Appends a copy of fillValue and returns it.
	T& expand(const T& fillValue)
	{
		push_back(fillValue);
		return m_data[m_size - 1];
	}

	/// Appends a copy of value; value may be an element of this array. Capacity doubles when full.
	void push_back(const T& value)
	{
		if (m_size == m_capacity)
		{
			// Construct the new element before moving the old ones: value may live in the old block.
			const int newCapacity = allocSize(m_size);
			T* newData = static_cast<T*>(allocate(newCapacity));
			new (&newData[m_size]) T(value);
			caliber::moveArrayElements(m_data, m_size, newData);
			deallocate();
			m_data = newData;
			m_capacity = newCapacity;
			m_ownsMemory = true;
		}
		else
		{
			new (&m_data[m_size]) T(value);
		}
		++m_size;
	}

	/// Makes room for at least count elements; allocates only when count > capacity().
	void reserve(int count)
	{
		if (count <= m_capacity) return;
		T* newData = static_cast<T*>(allocate(count));
		caliber::moveArrayElements(m_data, m_size, newData);
		deallocate();
		m_data = newData;
		m_capacity = count;
		m_ownsMemory = true;
	}

	/// Default ordering functor for the sorts: operator<.
	class less
	{
	public:
		/// True when a sorts before b.
		bool operator()(const T& a, const T& b) const { return a < b; }
	};

	/// Sorts the inclusive index range [lo, hi] with compare (a strict weak order); not stable.
	template <typename L>
	void quickSortInternal(const L& compare, int lo, int hi)
	{
		while (lo < hi)
		{
			if (hi - lo < 16)
			{
				// Short ranges: insertion sort beats further partitioning.
				for (int k = lo + 1; k <= hi; ++k)
				{
					T value(std::move(m_data[k]));
					int m = k;
					for (; m > lo && compare(value, m_data[m - 1]); --m) m_data[m] = std::move(m_data[m - 1]);
					m_data[m] = std::move(value);
				}
				return;
			}
			const T pivot(m_data[lo + (hi - lo) / 2]);
			int i = lo;
			int j = hi;
			while (i <= j)
			{
				while (compare(m_data[i], pivot)) ++i;
				while (compare(pivot, m_data[j])) --j;
				if (i <= j)
				{
					if (i != j) caliber::swapArrayElements(m_data[i], m_data[j]);
					++i;
					--j;
				}
			}
			// Recurse into the smaller part and loop on the larger one: stack depth stays O(log n).
			if (j - lo < hi - i)
			{
				quickSortInternal(compare, lo, j);
				lo = i;
			}
			else
			{
				quickSortInternal(compare, i, hi);
				hi = j;
			}
		}
	}

	/// Sorts the whole array with compare (a strict weak order, "a before b"); not stable.
	template <typename L>
	void quickSort(const L& compare)
	{
		if (m_size > 1) quickSortInternal(compare, 0, m_size - 1);
	}

	/// Sifts node k down a max-heap of n nodes stored in pArr; k and n count from 1 (node k is pArr[k - 1]).
	template <typename L>
	void downHeap(T* pArr, int k, int n, const L& compare)
	{
		T value(std::move(pArr[k - 1]));
		while (k <= n / 2)
		{
			int child = 2 * k;
			if (child < n && compare(pArr[child - 1], pArr[child])) ++child;
			if (!compare(value, pArr[child - 1])) break;
			pArr[k - 1] = std::move(pArr[child - 1]);
			k = child;
		}
		pArr[k - 1] = std::move(value);
	}

	/// Swaps elements index0 and index1; asserts both are valid, does nothing in release if not.
	void swap(int index0, int index1)
	{
		btAssert(isValidIndex(index0) && isValidIndex(index1));
		if (!isValidIndex(index0) || !isValidIndex(index1) || index0 == index1) return;
		caliber::swapArrayElements(m_data[index0], m_data[index1]);
	}

	/// Sorts the whole array with compare in O(n log n) worst case; not stable.
	template <typename L>
	void heapSort(const L& compare)
	{
		int n = m_size;
		for (int k = n / 2; k > 0; --k) downHeap(m_data, k, n, compare);
		while (n > 1)
		{
			caliber::swapArrayElements(m_data[0], m_data[n - 1]);
			--n;
			downHeap(m_data, 1, n, compare);
		}
	}

	/// Index of the first element equal to key in an array sorted by operator<, or size() if absent.
	int findBinarySearch(const T& key) const
	{
		int first = 0;
		int count = m_size;
		while (count > 0)
		{
			const int step = count / 2;
			const int mid = first + step;
			if (m_data[mid] < key)
			{
				first = mid + 1;
				count -= step + 1;
			}
			else
			{
				count = step;
			}
		}
		return (first < m_size && !(key < m_data[first])) ? first : m_size;
	}

	/// Index of the first element == key, or size() if absent.
	int findLinearSearch(const T& key) const
	{
		for (int i = 0; i < m_size; ++i)
			if (m_data[i] == key) return i;
		return m_size;
	}

	/// Index of the first element == key, or -1 if absent.
	int findLinearSearch2(const T& key) const
	{
		for (int i = 0; i < m_size; ++i)
			if (m_data[i] == key) return i;
		return -1;
	}

	/// Removes element index by moving the last element into its place (order is not kept).
	/// index == size() (the "absent" result of the searches) is a silent no-op; other bad indices
	/// assert, and do nothing in release.
	void removeAtIndex(int index)
	{
		btAssert(index >= 0 && index <= m_size);
		if (!isValidIndex(index)) return;
		if (index != m_size - 1) caliber::swapArrayElements(m_data[index], m_data[m_size - 1]);
		pop_back();
	}

	/// Removes the first element == key (as removeAtIndex, order is not kept); no-op if absent.
	void remove(const T& key)
	{
		const int index = findLinearSearch(key);
		if (index < m_size) removeAtIndex(index);
	}

	/// Adopts caller-owned storage holding size constructed elements and room for capacity. The
	/// array destroys its elements when cleared but never frees buffer; growing past capacity moves
	/// the elements to owned storage. Asserts 0 <= size <= capacity and a suitably aligned buffer.
	void initializeFromBuffer(void* buffer, int size, int capacity)
	{
		clear();
		btAssert(size >= 0 && size <= capacity);
		btAssert(buffer != nullptr || capacity == 0);
		btAssert(reinterpret_cast<uintptr_t>(buffer) % alignof(T) == 0);
		m_ownsMemory = false;
		m_data = static_cast<T*>(buffer);
		m_size = size;
		m_capacity = capacity;
	}

	/// Replaces the contents with copies of otherArray's elements; keeps storage that is big enough.
	void copyFromArray(const btAlignedObjectArray& otherArray)
	{
		if (this == &otherArray) return;
		destroy(0, m_size);
		m_size = 0;
		reserve(otherArray.m_size);
		otherArray.copy(0, otherArray.m_size, m_data);
		m_size = otherArray.m_size;
	}
};

#endif  // BT_OBJECT_ARRAY_H
