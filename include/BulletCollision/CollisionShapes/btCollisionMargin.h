// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_MARGIN_H
#define BT_COLLISION_MARGIN_H

#include "LinearMath/btScalar.h"

/// The collision margin convex shapes get by default (0.04 length units, as in Bullet): a thin shell
/// around the shape that keeps GJK away from its degenerate touching case. See btConvexInternalShape.
#ifndef CONVEX_DISTANCE_MARGIN
#define CONVEX_DISTANCE_MARGIN btScalar(0.04)
#endif

#endif  // BT_COLLISION_MARGIN_H
