// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btUnionFind.h"

#include <atomic>
#include <cstring>

#include "LinearMath/btCountingSortOnThreads.h"

namespace
{
// Groups elements by island; the stored m_sz (an object index for the island manager) breaks ties so
// that the order inside an island does not depend on the sort's pivots.
struct IslandOrder
{
	bool operator()(const btElement& a, const btElement& b) const
	{
		if (a.m_id != b.m_id) return a.m_id < b.m_id;
		return a.m_sz < b.m_sz;
	}
};
}  // namespace

btUnionFind::btUnionFind() {}

btUnionFind::~btUnionFind() { Free(); }

void btUnionFind::allocate(int N)
{
	btAssert(N >= 0);
	m_elements.resize(N > 0 ? N : 0);
}

void btUnionFind::Free() { m_elements.clear(); }

void btUnionFind::reset(int N)
{
	allocate(N);
	const int count = m_elements.size();
	for (int i = 0; i < count; ++i)
	{
		m_elements[i].m_id = i;
		m_elements[i].m_sz = 1;
	}
}

int btUnionFind::find(int x)
{
	const int count = m_elements.size();
	btAssert(x >= 0 && x < count);
	if (x < 0 || x >= count) return x;
	// Path halving: every visited element skips to its grandparent, which flattens the tree as much
	// as full compression over repeated finds, in one pass and without recursion.
	while (m_elements[x].m_id != x)
	{
		const int parent = m_elements[x].m_id;
		const int grandParent = m_elements[parent].m_id;
		m_elements[x].m_id = grandParent;
		x = grandParent;
	}
	return x;
}

void btUnionFind::unite(int p, int q)
{
	const int count = m_elements.size();
	btAssert(p >= 0 && p < count && q >= 0 && q < count);
	if (p < 0 || p >= count || q < 0 || q >= count) return;
	int rootP = find(p);
	int rootQ = find(q);
	if (rootP == rootQ) return;
	// Hanging the smaller tree below the larger keeps every tree O(log n) deep even before compression.
	if (m_elements[rootP].m_sz > m_elements[rootQ].m_sz) btSwap(rootP, rootQ);
	m_elements[rootP].m_id = rootQ;
	m_elements[rootQ].m_sz += m_elements[rootP].m_sz;
}

namespace
{
// The counting sort's scratch, one per thread (btUnionFind declares Bullet's members only), kept from call
// to call so that a world's step allocates nothing once its largest island count has been seen.
struct SortScratch
{
	btAlignedObjectArray<int> start;         // per island id, where its elements begin
	btAlignedObjectArray<int> cursor;        // per island id, where its next element goes
	btAlignedObjectArray<btElement> sorted;  // the sorted elements
	// The sort on the threads: its working arrays, and each element's m_sz while the elements are rewritten.
	caliber::CountingSortScratch threads;
	btAlignedObjectArray<int> sizes;
};
SortScratch& sortScratch()
{
	static thread_local SortScratch scratch;
	return scratch;
}

// Sorts elements (whose m_id are roots, in [0, count)) by (m_id, m_sz) with a counting sort by m_id, which
// keeps each island's elements in their order; that is the sort's order when they come in increasing m_sz
// (the island manager stores the object index there, which grows with the element index). False, having
// changed nothing, when they do not.
bool countingSortByIsland(btAlignedObjectArray<btElement>& elements)
{
	const int count = elements.size();
	SortScratch& scratch = sortScratch();
	btAlignedObjectArray<int>& start = scratch.start;
	start.resize(0);
	start.resize(count + 1, 0);
	for (int i = 0; i < count; ++i)
	{
		const int id = elements[i].m_id;
		if (id < 0 || id >= count) return false;
		++start[id + 1];
	}
	for (int id = 0; id < count; ++id) start[id + 1] += start[id];
	btAlignedObjectArray<int>& cursor = scratch.cursor;
	cursor.resizeNoInitialize(count);
	for (int id = 0; id < count; ++id) cursor[id] = start[id];
	btAlignedObjectArray<btElement>& sorted = scratch.sorted;
	sorted.resizeNoInitialize(count);
	for (int i = 0; i < count; ++i)
	{
		const btElement& element = elements[i];
		const int slot = cursor[element.m_id]++;
		if (slot > start[element.m_id] && element.m_sz < sorted[slot - 1].m_sz) return false;
		sorted[slot] = element;
	}
	for (int i = 0; i < count; ++i) elements[i] = sorted[i];
	return true;
}
}  // namespace

namespace
{
// Elements worth sorting on the threads (three parallel loops); fewer go the serial way.
const int kMinElementsOnThreads = 1024;

// Loop 1 of the sort on the threads: element i's root, found without changing the elements (other tasks walk
// the same paths; the serial finds' halving only shortens paths, so the roots are the same), and its m_sz
// kept aside; notes when m_sz does not grow with the element index (the serial path then sorts instead).
struct RootOfElement
{
	const btElement* elements;
	int* sizes;
	std::atomic<int>* notIncreasing;
	int operator()(int i) const
	{
		int x = i;
		while (elements[x].m_id != x) x = elements[x].m_id;
		sizes[i] = elements[i].m_sz;
		if (i > 0 && elements[i].m_sz <= elements[i - 1].m_sz) notIncreasing->store(1, std::memory_order_relaxed);
		return x;
	}
};

// Loop 3: the element to its slot, as the serial sort leaves it (m_id its root, m_sz its own).
struct PlaceElement
{
	btElement* elements;
	const int* sizes;
	void operator()(int i, int root, int slot) const
	{
		elements[slot].m_id = root;
		elements[slot].m_sz = sizes[i];
	}
};

// The sort on the threads when m_sz grows with the element index (the island manager's use): the elements by
// root, each island's in element order, which is (root, m_sz) order. False, with the elements unchanged, when
// the sort is not worth the loops or m_sz does not grow.
bool sortIslandsOnThreads(btAlignedObjectArray<btElement>& elements)
{
	const int count = elements.size();
	const int parts = caliber::countingSortParts(count, kMinElementsOnThreads);
	if (parts == 0) return false;
	SortScratch& scratch = sortScratch();
	scratch.sizes.resizeNoInitialize(count);
	std::atomic<int> notIncreasing(0);
	RootOfElement rootOf;
	rootOf.elements = &elements[0];
	rootOf.sizes = &scratch.sizes[0];
	rootOf.notIncreasing = &notIncreasing;
	caliber::CountingSortOnThreads<RootOfElement, PlaceElement> sort(scratch.threads, count, count, parts);
	sort.count(rootOf);
	if (notIncreasing.load()) return false;
	PlaceElement place;
	place.elements = &elements[0];
	place.sizes = &scratch.sizes[0];
	const int placed = sort.place(place, 0);
	btAssert(placed == count);
	(void)placed;
	return true;
}
}  // namespace

void btUnionFind::sortIslands()
{
	const int count = m_elements.size();
	if (count == 0) return;
	if (sortIslandsOnThreads(m_elements)) return;
	// find(i) for every element in order (the same path halving), without a call and range check each;
	// in the same pass, the counting sort's count of each island (two places up: see below) and whether
	// m_sz grows with the element index (the island manager's object indices do).
	btElement* elements = &m_elements[0];
	SortScratch& scratch = sortScratch();
	btAlignedObjectArray<int>& start = scratch.start;
	start.resize(0);
	start.resize(count + 2, 0);
	int* counts = &start[0];
	bool increasing = true;
	for (int i = 0; i < count; ++i)
	{
		int x = i;
		while (elements[x].m_id != x)
		{
			const int grandParent = elements[elements[x].m_id].m_id;
			elements[x].m_id = grandParent;
			x = grandParent;
		}
		elements[i].m_id = x;
		++counts[x + 2];
		if (i > 0 && elements[i].m_sz <= elements[i - 1].m_sz) increasing = false;
	}
	// The order is (island id, m_sz), which fixes the result (equal keys are equal elements).
	if (increasing)
	{
		// A stable counting sort by island id keeps each island's elements in element order, which is
		// m_sz order. After the prefix sum counts[id + 1] is island id's first slot; the placement
		// advances it.
		for (int id = 2; id < count + 2; ++id) counts[id] += counts[id - 1];
		btAlignedObjectArray<btElement>& sorted = scratch.sorted;
		sorted.resizeNoInitialize(count);
		btElement* out = &sorted[0];
		for (int i = 0; i < count; ++i) out[counts[elements[i].m_id + 1]++] = elements[i];
		std::memcpy(elements, out, sizeof(btElement) * size_t(count));
		return;
	}
	// Otherwise the counting sort when each island's elements come in m_sz order, the comparison sort
	// when they do not.
	if (!countingSortByIsland(m_elements)) m_elements.quickSort(IslandOrder());
}
