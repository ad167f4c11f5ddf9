// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_AABB_FAST_PATH_H
#define CALIBER_DBVT_AABB_FAST_PATH_H

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"

namespace caliber
{
/// The first half of btDbvtBroadphase::setAabb for a finite AABB of a live proxy: stores the AABB and
/// returns false when it still fits in the fat box; otherwise stores it too, writes the proxy's new tree
/// box (fat and stretched along the move, as setAabb makes it) to fatMin / fatMax (which may be aabbMin /
/// aabbMax) and returns true, and the caller passes that box to moveProxyToFatBox. It reads the broadphase
/// and writes only this proxy, so the collision world calls it for many objects at once on the task
/// scheduler's threads, and adds the calls to m_updates_call afterwards.
bool storeAabbOrFatBox(const btDbvtBroadphase& broadphase, btBroadphaseProxy* proxy, const btVector3& aabbMin,
                       const btVector3& aabbMax, btVector3& fatMin, btVector3& fatMax);

/// The second half of setAabb for a proxy that left its fat box (storeAabbOrFatBox returned true): moves
/// its leaf to the new tree box and queues its pair search; counts one update done. The caller calls it on
/// one thread, in the order the serial setAabb calls would come, and adds the calls to m_updates_call.
void moveProxyToFatBox(btDbvtBroadphase& broadphase, btBroadphaseProxy* proxy, const btVector3& fatMin,
                       const btVector3& fatMax);

/// A proxy that left its fat box and its new tree box (storeAabbOrFatBox's result).
struct DbvtProxyMove
{
	btVector3 fatMin, fatMax;
	btBroadphaseProxy* proxy;
};

/// moveProxyToFatBox for each move, in array order, with the same result (the tree node by node, the stage
/// lists, the counters). With a task scheduler of several threads and enough moves, the moves whose leaves
/// lie in different subtrees a few levels below the dynamic tree's root run on different threads, each
/// subtree's in order, and their steps on the nodes above the subtrees are replayed in move order on the
/// calling thread; a move that needs a node inside another subtree runs alone, in its place in the order.
/// Called by one thread, outside parallel loops, while nothing else uses the broadphase. Not yet called by
/// the collision world (docs/threading.md, "Eleventh session"). stats, when given, receives what happened.
struct DbvtParallelMoveStats
{
	int rounds = 0;          // parallel loops run
	int movesOnThreads = 0;  // moves kept from those loops
	int movesUndone = 0;     // moves a task made at or after its round's bound, undone
	int movesAlone = 0;      // moves made in order on the calling thread
	int topStops = 0;        // rounds ended by a move whose steps above the subtrees could not be replayed
};
void moveProxiesToFatBoxes(btDbvtBroadphase& broadphase, const DbvtProxyMove* moves, int count,
                           DbvtParallelMoveStats* stats = 0);
}  // namespace caliber

#endif  // CALIBER_DBVT_AABB_FAST_PATH_H
