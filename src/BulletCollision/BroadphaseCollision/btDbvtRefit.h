// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_REFIT_H
#define CALIBER_DBVT_REFIT_H

#include "BulletCollision/BroadphaseCollision/btDbvt.h"

namespace caliber
{
/// How much larger than its two boxes apart the union of a moved leaf and its sibling may be for the
/// leaf to stay in place (see refitLeafNearSibling).
const btScalar kDbvtRefitSiblingSlack = btScalar(1.2);

/// Moves leaf to box in place, growing its ancestors until one already contains it, when the leaf is still
/// close to its sibling (the union of their boxes has at most kDbvtRefitSiblingSlack times the sum of their
/// half-areas): a few merges instead of a removal and a sibling search. Objects that move together (a
/// falling pile, a ragdoll's parts) mostly stay next to their siblings, so most moves take this path and
/// the tree keeps its quality; a leaf that left its sibling returns false and is re-inserted by the caller.
bool refitLeafNearSibling(btDbvtNode* leaf, const btDbvtVolume& box);

/// A node's contents before a move within a subtree changed them.
struct DbvtSavedNode
{
	btDbvtNode* node;
	btDbvtNode contents;
};

/// The nodes a thread's moves within a subtree changed, oldest first, to undo them.
typedef btAlignedObjectArray<DbvtSavedNode> DbvtUndoLog;

/// Moves a dynamic leaf to box as btDbvtBroadphase's serial move does (refitLeafNearSibling, else
/// btDbvt::update(leaf, box)), with the same result, when that move changes and reads only nodes of the
/// subtree under `subtree` (a node of the tree other than the root, above the leaf) and the box of
/// subtree's parent; each node is saved to log before it changes. Returns false, having undone its changes,
/// when the move needs a node outside the subtree: its removal or insertion would replace the subtree's root,
/// its re-insertion would start above it, or a box above it would change. Moves within different subtrees
/// touch different nodes, so they may run on different threads at once (while nothing else changes the
/// tree); moves within one subtree must come in the serial order.
bool moveLeafWithinSubtree(btDbvt& tree, const btDbvtNode* subtree, btDbvtNode* leaf, const btDbvtVolume& box,
                           DbvtUndoLog& log);

/// Restores the nodes saved in log from entry `mark` on, newest first, and shortens the log to mark.
void undoDbvtChanges(DbvtUndoLog& log, int mark);
}  // namespace caliber

#endif  // CALIBER_DBVT_REFIT_H
