// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_BOX_WALK_H
#define CALIBER_DBVT_BOX_WALK_H

#include "BulletCollision/BroadphaseCollision/btDbvt.h"

namespace caliber
{
/// The leaves under root whose boxes touch box, given to policy.Process(leaf) in the order
/// btDbvt::collideTVNoStackAlloc gives them (a depth-first walk that opens childs[1]'s subtree first): the
/// broadphase's pair search, where that order is the order of the pairs it adds (docs/broadphases.md).
/// collideTVNoStackAlloc pushes both children of every node it opens and tests a node's box when it pops
/// it; this tests the children's boxes first, goes straight on into the first that touches and pushes the
/// other only when it touches too. Every node is tested once either way, so the same leaves come in the
/// same order, with a push and a pop only where the walk forks. The stack holds one entry per fork on the
/// path, in an array of InlineCapacity entries on the C++ stack (trees deeper than that go on the heap).
template <int InlineCapacity, class Policy>
void collideTVInTreeOrder(const btDbvtNode* root, const btDbvtVolume& box, Policy& policy)
{
	if (!root || !Intersect(root->volume, box)) return;
	DbvtLocalStack<const btDbvtNode*, InlineCapacity> forks;
	const btDbvtNode* node = root;  // a node whose box touches box
	for (;;)
	{
		if (node->isleaf())
			policy.Process(node);
		else
		{
			const btDbvtNode* first = node->childs[1];
			const btDbvtNode* second = node->childs[0];
			const bool touchesFirst = Intersect(first->volume, box);
			const bool touchesSecond = Intersect(second->volume, box);
			if (touchesFirst)
			{
				if (touchesSecond) forks.push(second);
				node = first;
				continue;
			}
			if (touchesSecond)
			{
				node = second;
				continue;
			}
		}
		if (forks.empty()) return;
		node = forks.pop();
	}
}
}  // namespace caliber

#endif  // CALIBER_DBVT_BOX_WALK_H
