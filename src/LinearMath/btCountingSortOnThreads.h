// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_COUNTING_SORT_ON_THREADS_H
#define CALIBER_COUNTING_SORT_ON_THREADS_H

// A stable counting sort of items by an integer key, in three parallel loops on the task scheduler's
// threads: the island stage's groupings (the union-find's elements by island, the joints and the manifolds
// by island) are such sorts, and each used to run whole on the calling thread.
//
// Item i of key k (0 <= k < numKeys; a negative key leaves the item out) goes to slot
// start(k) + (the items of key k before i), where start(k) is the count of kept items of smaller keys:
// the serial counting sort's slot, whatever the number of parts the loops cut the work into and whatever
// order their tasks run in. The parts are contiguous ranges of the items (loop 1 and 3) and of the keys
// (loop 2); each task writes only its own part's row of counts, its key range's slots of every row, or the
// slots its own items go to.

#include <cstring>

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMinMax.h"
#include "LinearMath/btScalar.h"
#include "LinearMath/btThreads.h"

namespace caliber
{
/// The sort's working arrays, kept by the caller between calls so that a step allocates nothing once they
/// have grown.
struct CountingSortScratch
{
	btAlignedObjectArray<int> keys;      // per item, its key (loop 1)
	btAlignedObjectArray<int> counts;    // numParts rows of numKeys: counts, then each part's next slot per key
	btAlignedObjectArray<int> rangeBase; // per key range, its first slot; numParts + 1 entries
};

/// Parts to cut a sort of numItems items into on the current scheduler: one per thread (at most 8, as the
/// counts cost numKeys per part), or 0 when the sort is not worth the loops (fewer than minItems items, one
/// thread, or already inside a parallel loop, where the loops would run on this thread anyway).
inline int countingSortParts(int numItems, int minItems)
{
	const btITaskScheduler* scheduler = btGetTaskScheduler();
	if (numItems < minItems || numItems <= 0 || !scheduler || btThreadsAreRunning()) return 0;
	const int threads = scheduler->getNumThreads();
	return threads > 1 ? btMin(threads, 8) : 0;
}

/// The sort. KeyOf: `int operator()(int item) const`, called once per item from the loop-1 tasks (so it may
/// read anything the sort does not write, and write the item's own slots of the caller's arrays); Place:
/// `void operator()(int item, int key, int slot) const`, called once per kept item from the loop-3 tasks
/// (it writes the item to its slot; keys[] holds every item's key by then). numParts >= 1 (see
/// countingSortParts). After place(), keyStart (when not null, numKeys + 1 entries) holds where each key's
/// items start, and keyStart[numKeys] the number kept; place() returns that number.
template <class KeyOf, class Place>
class CountingSortOnThreads
{
public:
	CountingSortOnThreads(CountingSortScratch& scratch, int numItems, int numKeys, int numParts)
	    : m_scratch(scratch), m_numItems(btMax(0, numItems)), m_numKeys(btMax(0, numKeys)), m_numParts(btMax(1, numParts))
	{
		// Key ranges of a power of two keys each (a shift finds a key's range), at most numParts of them.
		const int perPart = (m_numKeys + m_numParts - 1) / m_numParts;
		m_shift = 0;
		while ((1 << m_shift) < perPart) ++m_shift;
		m_numRanges = m_numKeys > 0 ? ((m_numKeys - 1) >> m_shift) + 1 : 0;
		m_scratch.keys.resizeNoInitialize(m_numItems);
		m_scratch.counts.resizeNoInitialize(m_numParts * m_numKeys);
		m_scratch.rangeBase.resizeNoInitialize(m_numRanges + 1);
	}

	/// Loop 1: every item's key and each part's count per key. May be followed by run(), or by nothing (the
	/// caller may give up after looking at what keyOf noted).
	void count(const KeyOf& keyOf)
	{
		CountLoop loop;
		loop.sort = this;
		loop.keyOf = &keyOf;
		btParallelFor(0, m_numParts, 1, loop);
	}

	/// Loops 2 and 3: the slots, and the placement. Returns the number of items kept.
	int place(const Place& placeItem, int* keyStart)
	{
		if (m_numRanges > 0)
		{
			SlotLoop slots;
			slots.sort = this;
			slots.keyStart = keyStart;
			btParallelFor(0, m_numRanges, 1, slots);
		}
		int* rangeBase = m_numRanges > 0 ? &m_scratch.rangeBase[0] : 0;
		int total = 0;
		for (int r = 0; r < m_numRanges; ++r)
		{
			const int size = rangeBase[r];
			rangeBase[r] = total;
			total += size;
		}
		if (m_numRanges > 0) rangeBase[m_numRanges] = total;
		PlaceLoop loop;
		loop.sort = this;
		loop.placeItem = &placeItem;
		loop.keyStart = keyStart;
		btParallelFor(0, m_numParts, 1, loop);
		if (keyStart) keyStart[m_numKeys] = total;
		return total;
	}

private:
	int partBegin(int part) const { return int((long long)m_numItems * part / m_numParts); }

	struct CountLoop : public btIParallelForBody
	{
		CountingSortOnThreads* sort;
		const KeyOf* keyOf;
		void forLoop(int iBegin, int iEnd) const override
		{
			const int numKeys = sort->m_numKeys;
			for (int part = iBegin; part < iEnd; ++part)
			{
				int* row = numKeys ? &sort->m_scratch.counts[part * numKeys] : 0;
				if (numKeys) std::memset(row, 0, sizeof(int) * size_t(numKeys));
				int* keys = sort->m_numItems ? &sort->m_scratch.keys[0] : 0;
				const int end = sort->partBegin(part + 1);
				for (int i = sort->partBegin(part); i < end; ++i)
				{
					int key = (*keyOf)(i);
					if (key >= numKeys) key = -1;  // out of range: left out, as a negative key
					keys[i] = key;
					if (key >= 0) ++row[key];
				}
			}
		}
	};

	// Key range r: each key's slot per part, counted from the range's start (items of smaller keys first, then
	// of the same key in part order), and the range's size in rangeBase[r]; where each key starts, counted from
	// the range's start, in keyStart when asked.
	struct SlotLoop : public btIParallelForBody
	{
		CountingSortOnThreads* sort;
		int* keyStart;
		void forLoop(int iBegin, int iEnd) const override
		{
			const int numKeys = sort->m_numKeys;
			const int numParts = sort->m_numParts;
			int* counts = &sort->m_scratch.counts[0];
			for (int r = iBegin; r < iEnd; ++r)
			{
				const int keyEnd = btMin(numKeys, (r + 1) << sort->m_shift);
				int running = 0;
				for (int key = r << sort->m_shift; key < keyEnd; ++key)
				{
					if (keyStart) keyStart[key] = running;
					for (int part = 0; part < numParts; ++part)
					{
						int& slot = counts[part * numKeys + key];
						const int count = slot;
						slot = running;
						running += count;
					}
				}
				sort->m_scratch.rangeBase[r] = running;
			}
		}
	};

	// Part p: its items to their slots, and (when asked) where the keys of range p start.
	struct PlaceLoop : public btIParallelForBody
	{
		CountingSortOnThreads* sort;
		const Place* placeItem;
		int* keyStart;
		void forLoop(int iBegin, int iEnd) const override
		{
			const int numKeys = sort->m_numKeys;
			const int shift = sort->m_shift;
			const int* rangeBase = sort->m_numRanges > 0 ? &sort->m_scratch.rangeBase[0] : 0;
			int* counts = numKeys ? &sort->m_scratch.counts[0] : 0;
			const int* keys = sort->m_numItems ? &sort->m_scratch.keys[0] : 0;
			for (int part = iBegin; part < iEnd; ++part)
			{
				if (keyStart && part < sort->m_numRanges)
				{
					// The keys of range p (as many ranges as parts at most) from the range's start to the sort's.
					const int keyEnd = btMin(numKeys, (part + 1) << shift);
					for (int key = part << shift; key < keyEnd; ++key) keyStart[key] += rangeBase[part];
				}
				int* row = numKeys ? counts + part * numKeys : 0;
				const int end = sort->partBegin(part + 1);
				for (int i = sort->partBegin(part); i < end; ++i)
				{
					const int key = keys[i];
					if (key < 0) continue;
					(*placeItem)(i, key, rangeBase[key >> shift] + row[key]++);
				}
			}
		}
	};

	CountingSortScratch& m_scratch;
	int m_numItems;
	int m_numKeys;
	int m_numParts;
	int m_shift;
	int m_numRanges;
};
}  // namespace caliber

#endif  // CALIBER_COUNTING_SORT_ON_THREADS_H
