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
}  // namespace caliber

#endif  // CALIBER_DBVT_REFIT_H
