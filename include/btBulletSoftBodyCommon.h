// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_BULLET_SOFT_BODY_COMMON_H
#define CALIBER_BULLET_SOFT_BODY_COMMON_H

/// Caliber's own umbrella header (Bullet has none): everything a soft-body program needs, in one
/// include: the rigid-body API and the soft-body layer.

#include "btBulletDynamicsCommon.h"
#include "BulletSoftBody/btDefaultSoftBodySolver.h"
#include "BulletSoftBody/btSoftBody.h"
#include "BulletSoftBody/btSoftBodyHelpers.h"
#include "BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h"
#include "BulletSoftBody/btSoftRigidDynamicsWorld.h"

#endif  // CALIBER_BULLET_SOFT_BODY_COMMON_H
