// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// A dynamic tree written out depth first, so that two trees can be compared node for node (the parallel
// tree-move tests and the threaded box-update tests).

#ifndef CALIBER_DBVT_TREE_SNAPSHOT_H
#define CALIBER_DBVT_TREE_SNAPSHOT_H

#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"

namespace dbvt_test
{
/// Appends, depth first from node, each node's box (min, max) to boxes and, per node, its leaf's proxy id
/// (-1 for an inner node) to leaves.
inline void snapshotTree(const btDbvtNode* node, std::vector<btVector3>& boxes, std::vector<int>& leaves)
{
	if (!node) return;
	boxes.push_back(node->volume.Mins());
	boxes.push_back(node->volume.Maxs());
	if (node->isleaf())
	{
		leaves.push_back(static_cast<const btDbvtProxy*>(node->data)->m_uniqueId);
		return;
	}
	leaves.push_back(-1);
	snapshotTree(node->childs[0], boxes, leaves);
	snapshotTree(node->childs[1], boxes, leaves);
}
}  // namespace dbvt_test

#endif  // CALIBER_DBVT_TREE_SNAPSHOT_H
