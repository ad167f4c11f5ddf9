// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_UNITE_IN_ORDER_H
#define CALIBER_UNITE_IN_ORDER_H

#include "BulletCollision/CollisionDispatch/btUnionFind.h"

namespace caliber
{
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
		while (elements[rootP].m_id != rootP)
		{
			const int grandParent = elements[elements[rootP].m_id].m_id;
			elements[rootP].m_id = grandParent;
			rootP = grandParent;
		}
		while (elements[rootQ].m_id != rootQ)
		{
			const int grandParent = elements[elements[rootQ].m_id].m_id;
			elements[rootQ].m_id = grandParent;
			rootQ = grandParent;
		}
		if (rootP == rootQ) continue;
		if (elements[rootP].m_sz > elements[rootQ].m_sz) btSwap(rootP, rootQ);
		elements[rootP].m_id = rootQ;
		elements[rootQ].m_sz += elements[rootP].m_sz;
	}
}
}  // namespace caliber

#endif  // CALIBER_UNITE_IN_ORDER_H
