// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BULLET_COLLISION_COMMON_H
#define BULLET_COLLISION_COMMON_H

/// Everything a collision-detection program needs, in one include (as with Bullet).
/// For now it brings the LinearMath layer; the BulletCollision issues add their headers here
/// (shapes, broadphases, dispatcher, collision world) as they land.

#include "LinearMath/btScalar.h"
#include "LinearMath/btVector3.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btDefaultMotionState.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btIDebugDraw.h"

#endif  // BULLET_COLLISION_COMMON_H
