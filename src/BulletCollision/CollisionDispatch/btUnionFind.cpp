// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btUnionFind.h"

#include <cstring>

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

void btUnionFind::sortIslands()
{
	const int count = m_elements.size();
	if (count == 0) return;
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
