// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_PROXY_IDS_H
#define CALIBER_DBVT_PROXY_IDS_H

// Which of btDbvtBroadphase's two trees holds a proxy is written in the parity of its unique id: Bullet's
// btDbvtProxy declares no field for it, and the id is the one field the broadphase alone writes. Ids still
// grow with creation order (the pair cache orders a pair's proxies by id), so pairs keep their order.

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"

namespace caliber
{
/// btDbvtBroadphase::DYNAMIC_SET (even id) or FIXED_SET (odd id).
inline int dbvtTreeOf(const btBroadphaseProxy& proxy) { return proxy.m_uniqueId & 1; }

/// The id of the serial-th proxy made by a broadphase, for the given tree. Unsigned arithmetic: after 2^30
/// proxies the ids wrap (as Bullet's wrap after 2^31) instead of overflowing.
inline int dbvtProxyId(int serial, int tree) { return int((unsigned(serial) << 1) | unsigned(tree & 1)); }
}  // namespace caliber

#endif  // CALIBER_DBVT_PROXY_IDS_H
