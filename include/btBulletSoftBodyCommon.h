// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_BULLET_SOFT_BODY_COMMON_H
#define CALIBER_BULLET_SOFT_BODY_COMMON_H

/// Caliber's own umbrella header (Bullet has none): meant to be everything a soft-body program needs,
/// in one include. Soft bodies are not implemented yet (there is no BulletSoftBody library), so today it
/// is exactly btBulletDynamicsCommon.h; the soft-body headers join here when that layer lands.

#include "btBulletDynamicsCommon.h"

#endif  // CALIBER_BULLET_SOFT_BODY_COMMON_H
