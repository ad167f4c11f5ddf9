// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence
// (see LICENSE.txt). btPairCachingGhostObject (declared in btGhostObject.h):
// kept apart because it needs the hashed pair cache.
#include <new>

#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "LinearMath/btAlignedAllocator.h"

namespace
{
btCollisionObject* objectOf(btBroadphaseProxy* proxy)
{
	return proxy ? static_cast<btCollisionObject*>(proxy->m_clientObject) : 0;
}
}  // namespace

btPairCachingGhostObject::btPairCachingGhostObject()
    : m_hashPairCache(new (btAlignedAlloc(sizeof(btHashedOverlappingPairCache), 16)) btHashedOverlappingPairCache())
{
}

btPairCachingGhostObject::~btPairCachingGhostObject()
{
	m_hashPairCache->~btHashedOverlappingPairCache();
	btAlignedFree(m_hashPairCache);
}

void btPairCachingGhostObject::addOverlappingObjectInternal(btBroadphaseProxy* otherProxy, btBroadphaseProxy* thisProxy)
{
	btBroadphaseProxy* ghostProxy = thisProxy ? thisProxy : getBroadphaseHandle();
	btCollisionObject* other = objectOf(otherProxy);
	btAssert(ghostProxy && other);
	if (!ghostProxy || !other || other == this) return;
	if (m_overlappingObjects.findLinearSearch(other) < m_overlappingObjects.size()) return;
	m_overlappingObjects.push_back(other);
	m_hashPairCache->addOverlappingPair(ghostProxy, otherProxy);
}

void btPairCachingGhostObject::removeOverlappingObjectInternal(btBroadphaseProxy* otherProxy, btDispatcher* dispatcher,
                                                               btBroadphaseProxy* thisProxy)
{
	btBroadphaseProxy* ghostProxy = thisProxy ? thisProxy : getBroadphaseHandle();
	btCollisionObject* other = objectOf(otherProxy);
	btAssert(ghostProxy && other);
	if (!ghostProxy || !other) return;
	const int index = m_overlappingObjects.findLinearSearch(other);
	if (index >= m_overlappingObjects.size()) return;
	m_overlappingObjects[index] = m_overlappingObjects[m_overlappingObjects.size() - 1];
	m_overlappingObjects.pop_back();
	m_hashPairCache->removeOverlappingPair(ghostProxy, otherProxy, dispatcher);
}
