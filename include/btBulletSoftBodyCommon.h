// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_BULLET_SOFT_BODY_COMMON_H
#define CALIBER_BULLET_SOFT_BODY_COMMON_H

/// Caliber's own umbrella header (Bullet has none): everything a soft-body program needs, in one
/// include: the rigid-body layers plus the soft-body layer. For now that is LinearMath; the
/// BulletSoftBody issues add their headers here (soft bodies, helpers, soft-rigid world) as they land.

#include "btBulletDynamicsCommon.h"

#endif  // CALIBER_BULLET_SOFT_BODY_COMMON_H
