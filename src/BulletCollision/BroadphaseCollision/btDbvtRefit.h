// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_REFIT_H
#define CALIBER_DBVT_REFIT_H

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "LinearMath/btAlignedObjectArray.h"

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

/// A node's volume before a change, and which move (an index chosen by the caller) changed it.
struct DbvtVolumeChange
{
	btDbvtNode* node;
	btDbvtVolume previous;
	int move;
};

/// What refitLeafInSubtree did.
enum DbvtSubtreeRefit
{
	kDbvtRefitNeedsReinsert,  ///< the leaf left its sibling: nothing changed, the caller re-inserts it
	kDbvtRefitInside,         ///< refitted; only nodes strictly inside the subtree changed
	kDbvtRefitThroughRoot     ///< refitted up to and including subtreeRoot; its ancestors are not yet grown
};

/// refitLeafNearSibling for a leaf strictly inside the subtree under subtreeRoot, stopping at subtreeRoot: the
/// same test, the same arithmetic, the same nodes in the same order, except that when subtreeRoot itself had to
/// grow, its ancestors are left to refitAncestorsAbove(subtreeRoot->parent, fitted). Reads and writes only
/// nodes of that subtree, so subtrees can be refitted on different threads. Every volume it changes is first
/// appended to changes (with move), and fitted receives the leaf's new volume.
DbvtSubtreeRefit refitLeafInSubtree(btDbvtNode* leaf, const btDbvtVolume& box, const btDbvtNode* subtreeRoot, int move,
                                    btAlignedObjectArray<DbvtVolumeChange>& changes, btDbvtVolume& fitted);

/// btDbvt::update(leaf, volume) of a leaf of a non-empty tree in two halves: detachLeafForUpdate unlinks the
/// leaf, gives it its new volume and returns the node its sibling search starts from; attachLeafUnder then
/// links it back under that node. Between the two a caller may look at what the insertion will touch.
btDbvtNode* detachLeafForUpdate(btDbvt& tree, btDbvtNode* leaf, const btDbvtVolume& volume);
void attachLeafUnder(btDbvt& tree, btDbvtNode* start, btDbvtNode* leaf);

/// The rest of a refit that grew a node below `node`: grows node and its ancestors, as refitLeafNearSibling
/// does, until one already contains fitted (the refitted leaf's volume).
void refitAncestorsAbove(btDbvtNode* node, const btDbvtVolume& fitted);
}  // namespace caliber

#endif  // CALIBER_DBVT_REFIT_H
