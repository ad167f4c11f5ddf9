// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_AABB_FAST_PATH_H
#define CALIBER_DBVT_AABB_FAST_PATH_H

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"

namespace caliber
{
/// What btDbvtBroadphase::setAabb does for a finite AABB that still fits in the proxy's fat box: stores it
/// and returns true (the tree and the pairs are untouched). False, with nothing changed, when the box left
/// the fat box or the proxy was destroyed: the caller then calls setAabb. It touches only this proxy, so
/// the collision world calls it for many objects at once on the task scheduler's threads, and adds the
/// calls to m_updates_call afterwards.
bool storeAabbIfInsideFatBox(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax);
}  // namespace caliber

#endif  // CALIBER_DBVT_AABB_FAST_PATH_H
