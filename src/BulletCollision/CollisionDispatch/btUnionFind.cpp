// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btUnionFind.h"

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

void btUnionFind::sortIslands()
{
	const int count = m_elements.size();
	for (int i = 0; i < count; ++i) m_elements[i].m_id = find(i);
	m_elements.quickSort(IslandOrder());
}
