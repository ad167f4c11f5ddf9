// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_UNITE_IN_ORDER_H
#define CALIBER_UNITE_IN_ORDER_H

#include "BulletCollision/CollisionDispatch/btUnionFind.h"

namespace caliber
{
/// btUnionFind::find(x) on the union-find's elements (the same path halving), without the call and the
/// range check: x must be below the element count.
inline int findWithHalving(btElement* elements, int x)
{
	while (elements[x].m_id != x)
	{
		const int grandParent = elements[elements[x].m_id].m_id;
		elements[x].m_id = grandParent;
		x = grandParent;
	}
	return x;
}

/// btUnionFind::unite(tags[2 i], tags[2 i + 1]) for i = 0 .. count - 1 in that order, skipping the i with
/// tags[2 i] < 0: the same finds (path halving), the same unions (the smaller set below the larger, the
/// first below the second on a tie), so the same elements, in one loop without the per-call checks. Every
/// tag must be below unionFind.getNumElements() (the island stage's lists are made so).
inline void uniteInOrder(btUnionFind& unionFind, const int* tags, int count)
{
	if (count <= 0 || unionFind.getNumElements() == 0) return;
	btElement* elements = &unionFind.getElement(0);
	for (int i = 0; i < count; ++i)
	{
		int rootP = tags[2 * i];
		if (rootP < 0) continue;
		int rootQ = tags[2 * i + 1];
		btAssert(rootP < unionFind.getNumElements() && rootQ >= 0 && rootQ < unionFind.getNumElements());
		rootP = findWithHalving(elements, rootP);
		rootQ = findWithHalving(elements, rootQ);
		if (rootP == rootQ) continue;
		if (elements[rootP].m_sz > elements[rootQ].m_sz) btSwap(rootP, rootQ);
		elements[rootP].m_id = rootQ;
		elements[rootQ].m_sz += elements[rootP].m_sz;
	}
}
}  // namespace caliber

#endif  // CALIBER_UNITE_IN_ORDER_H
