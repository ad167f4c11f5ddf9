// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The multithreaded dispatcher's first step: Bullet's interface over the serial narrowphase, so that a
// program set up for Bullet's multithreaded world runs unchanged (and gives the same state bits).
#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"

btCollisionDispatcherMt::btCollisionDispatcherMt(btCollisionConfiguration* config, int grainSize)
    : btCollisionDispatcher(config), m_batchUpdating(false), m_grainSize(grainSize < 1 ? 1 : grainSize)
{
}

btPersistentManifold* btCollisionDispatcherMt::getNewManifold(const btCollisionObject* body0,
                                                              const btCollisionObject* body1)
{
	return btCollisionDispatcher::getNewManifold(body0, body1);
}

void btCollisionDispatcherMt::releaseManifold(btPersistentManifold* manifold)
{
	btCollisionDispatcher::releaseManifold(manifold);
}

void btCollisionDispatcherMt::dispatchAllCollisionPairs(btOverlappingPairCache* pairCache, const btDispatcherInfo& info,
                                                        btDispatcher* dispatcher)
{
	btCollisionDispatcher::dispatchAllCollisionPairs(pairCache, info, dispatcher);
}
