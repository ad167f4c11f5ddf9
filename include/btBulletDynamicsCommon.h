// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BULLET_DYNAMICS_COMMON_H
#define BULLET_DYNAMICS_COMMON_H

/// Everything a rigid-body program needs, in one include (as with Bullet): the collision layer
/// plus the dynamics layer. For now that is LinearMath; the BulletDynamics issues add their headers
/// here (dynamics worlds, rigid bodies, constraint solver, constraints, vehicle) as they land.

#include "btBulletCollisionCommon.h"

#include "LinearMath/btVector3.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btDefaultMotionState.h"
#include "LinearMath/btAlignedObjectArray.h"

#endif  // BULLET_DYNAMICS_COMMON_H
