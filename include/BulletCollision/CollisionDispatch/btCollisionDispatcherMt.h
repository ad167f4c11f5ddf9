// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_DISPATCHER_MT_H
#define BT_COLLISION_DISPATCHER_MT_H

#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "LinearMath/btThreads.h"

/// Bullet 2.89's multithreaded dispatcher: the narrowphase over pairs runs in chunks of at most grainSize pairs
/// on the task scheduler's threads (fewer pairs a chunk when that gives each thread 8 chunks of 4 pairs or
/// more, for balance), with the same results, bit for bit, as btCollisionDispatcher's serial
/// narrowphase (docs/threading.md). Near callbacks and contact callbacks are then called from those
/// threads, as in Bullet.
class btCollisionDispatcherMt : public btCollisionDispatcher
{
public:
	/// grainSize: the most pairs per task (below 1 counts as 1); with at most grainSize pairs the narrowphase
	/// runs on the calling thread.
	btCollisionDispatcherMt(btCollisionConfiguration* config, int grainSize = 40);

	/// A new manifold for the pair, as btCollisionDispatcher's.
	btPersistentManifold* getNewManifold(const btCollisionObject* body0, const btCollisionObject* body1) override;
	/// Releases a manifold, as btCollisionDispatcher's.
	void releaseManifold(btPersistentManifold* manifold) override;
	/// The narrowphase over every overlapping pair.
	void dispatchAllCollisionPairs(btOverlappingPairCache* pairCache, const btDispatcherInfo& info,
	                               btDispatcher* dispatcher) override;

protected:
	btAlignedObjectArray<btAlignedObjectArray<btPersistentManifold*> > m_batchManifoldsPtr;
	btAlignedObjectArray<btAlignedObjectArray<btPersistentManifold*> > m_batchReleasePtr;
	bool m_batchUpdating;
	int m_grainSize;
};

#endif  // BT_COLLISION_DISPATCHER_MT_H
