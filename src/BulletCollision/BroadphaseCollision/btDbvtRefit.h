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

/// What a move within a subtree, made with moveLeafWithinSubtreeDeferringTop, leaves to the nodes above the
/// subtree's root: the steps the serial move would take there, replayed later in move order on one thread
/// (replayDbvtTopStep).
struct DbvtTopStep
{
	btDbvtVolume shrunk;     // the subtree root's box after the removal's shrink (when shrinks)
	btDbvtVolume grownBox;   // the box the growth above the subtree must contain (when grows)
	btDbvtVolume after;      // the subtree root's box after the move
	btDbvtVolume childs[2];  // its children's boxes after the move (a rotation above reads them)
	bool shrinks;            // the removal's shrink changed the subtree's root: the serial loop goes on above
	bool grows;              // the growth changed the subtree's root: the serial loop tests its parent next
	bool rotates;            // that growth rotates at each node (an insertion; a refit does not)
};

/// moveLeafWithinSubtree, except that the steps above the subtree's root (a shrink that goes on above it,
/// a growth that goes past it) are not a reason to stop: they are recorded in top, and the move reads and
/// changes no node outside the subtree (its parent's box included). It still stops (false, undone) when
/// its removal or insertion would replace the subtree's root or its re-insertion would start above it.
bool moveLeafWithinSubtreeDeferringTop(btDbvt& tree, const btDbvtNode* subtree, btDbvtNode* leaf,
                                       const btDbvtVolume& box, DbvtUndoLog& log, DbvtTopStep& top);

/// The nodes above a set of disjoint subtrees (the "top"), as the serial moves would leave them, followed
/// move by move: for each subtree root, its box and its children's boxes as of the last replayed move (the
/// live nodes of the subtrees already hold the round's last state).
struct DbvtTopView
{
	enum
	{
		kMaxSubtrees = 8
	};
	const btDbvtNode* roots[kMaxSubtrees];  // null entries hold no subtree
	btDbvtVolume boxes[kMaxSubtrees];
	btDbvtVolume childs[kMaxSubtrees][2];
	int count;

	/// Takes the subtree roots and their boxes as they are now.
	void start(const btDbvtNode* const* subtreeRoots, int numSubtrees);
};

/// The serial move's steps above subtree `index`'s root (top, recorded by
/// moveLeafWithinSubtreeDeferringTop), on the top's nodes, and the view updated to after the move. Each top
/// node is saved to topLog before it changes. Returns false, having made no change it did not log, when
/// the serial move would rotate a node above the subtrees by swapping a node inside a subtree: that move
/// cannot be replayed (the caller undoes it and makes it alone).
bool replayDbvtTopStep(DbvtTopView& view, int index, const DbvtTopStep& top, DbvtUndoLog& topLog);
}  // namespace caliber

#endif  // CALIBER_DBVT_REFIT_H
