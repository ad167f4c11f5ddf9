// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_MARGIN_HULL_SHAPE_H
#define CALIBER_EXTRAS_MARGIN_HULL_SHAPE_H

/// A btConvexHullShape whose surface (hull plus collision margin) is where the given corners say.

#include <memory>

#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// The hull of corners with its faces moved in by the collision margin, so that hull plus margin is the
/// hull of corners (with rounded edges). The margin is the default 0.04, or a quarter of the hull's inner
/// radius where that is less, so thin pieces (a cup's wall, a 1 cm plate) keep their thickness. Null for
/// fewer than 4 corners or a flat set.
std::unique_ptr<btConvexHullShape> makeMarginHullShape(const btAlignedObjectArray<btVector3>& corners);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_MARGIN_HULL_SHAPE_H
