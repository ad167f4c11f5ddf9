// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSimpleBroadphase: a pool of proxies and the all-pairs overlap test.

#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"

#include <cstdio>
#include <new>

#include "BulletCollision/BroadphaseCollision/btPairCacheUtil.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btAabbUtil2.h"
#include "LinearMath/btAlignedAllocator.h"

namespace
{
// Removes the pairs whose AABBs no longer overlap.
struct SeparatedPairRemover : public btOverlapCallback
{
	bool processOverlap(btBroadphasePair& pair) override
	{
		return !btSimpleBroadphase::aabbOverlap(static_cast<btSimpleBroadphaseProxy*>(pair.m_pProxy0),
		                                        static_cast<btSimpleBroadphaseProxy*>(pair.m_pProxy1));
	}
};
}  // namespace

btSimpleBroadphase::btSimpleBroadphase(int maxProxies, btOverlappingPairCache* overlappingPairCache)
    : m_numHandles(0),
      m_maxHandles(maxProxies > 0 ? maxProxies : 1),
      m_LastHandleIndex(-1),
      m_pHandles(0),
      m_pHandlesRawPtr(0),
      m_firstFreeHandle(0),
      m_pairCache(overlappingPairCache),
      m_ownsPairCache(false),
      m_invalidPair(0)
{
	btAssert(maxProxies > 0 && "btSimpleBroadphase: maxProxies must be positive");
	if (!m_pairCache)
	{
		void* memory = btAlignedAlloc(sizeof(btHashedOverlappingPairCache), 16);
		m_pairCache = new (memory) btHashedOverlappingPairCache();
		m_ownsPairCache = true;
	}
	m_pHandlesRawPtr = btAlignedAlloc(sizeof(btSimpleBroadphaseProxy) * size_t(m_maxHandles), 16);
	m_pHandles = static_cast<btSimpleBroadphaseProxy*>(m_pHandlesRawPtr);
	for (int i = 0; i < m_maxHandles; ++i)
	{
		new (&m_pHandles[i]) btSimpleBroadphaseProxy();
		m_pHandles[i].SetNextFree(i + 1 < m_maxHandles ? i + 1 : -1);
		m_pHandles[i].m_uniqueId = i + 1;
	}
}

btSimpleBroadphase::~btSimpleBroadphase()
{
	for (int i = 0; i < m_maxHandles; ++i) m_pHandles[i].~btSimpleBroadphaseProxy();
	btAlignedFree(m_pHandlesRawPtr);
	if (m_ownsPairCache)
	{
		m_pairCache->~btOverlappingPairCache();
		btAlignedFree(m_pairCache);
	}
}

bool btSimpleBroadphase::aabbOverlap(btSimpleBroadphaseProxy* proxy0, btSimpleBroadphaseProxy* proxy1)
{
	return TestAabbAgainstAabb2(proxy0->m_aabbMin, proxy0->m_aabbMax, proxy1->m_aabbMin, proxy1->m_aabbMax);
}

int btSimpleBroadphase::allocHandle()
{
	if (m_firstFreeHandle < 0) return -1;
	const int index = m_firstFreeHandle;
	m_firstFreeHandle = m_pHandles[index].GetNextFree();
	m_pHandles[index].SetNextFree(kProxyInUse);
	++m_numHandles;
	if (index > m_LastHandleIndex) m_LastHandleIndex = index;
	return index;
}

void btSimpleBroadphase::freeHandle(btSimpleBroadphaseProxy* proxy)
{
	const int index = int(proxy - m_pHandles);
	proxy->SetNextFree(m_firstFreeHandle);
	proxy->m_clientObject = 0;
	m_firstFreeHandle = index;
	--m_numHandles;
}

btBroadphaseProxy* btSimpleBroadphase::createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int shapeType,
                                                   void* userPtr, int collisionFilterGroup, int collisionFilterMask,
                                                   btDispatcher* dispatcher)
{
	(void)dispatcher;
	const bool finite = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(finite && "btSimpleBroadphase::createProxy: non-finite AABB");
	if (!finite) return 0;
	const int index = allocHandle();
	btAssert(index >= 0 && "btSimpleBroadphase::createProxy: the proxy pool is full (raise maxProxies)");
	if (index < 0) return 0;
	btSimpleBroadphaseProxy* proxy = &m_pHandles[index];
	const int uniqueId = proxy->m_uniqueId;
	*proxy = btSimpleBroadphaseProxy(aabbMin, aabbMax, shapeType, userPtr, collisionFilterGroup, collisionFilterMask);
	proxy->m_uniqueId = uniqueId;
	proxy->SetNextFree(kProxyInUse);
	return proxy;
}

void btSimpleBroadphase::destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher)
{
	if (!proxy) return;
	btSimpleBroadphaseProxy* simple = getSimpleProxyFromProxy(proxy);
	const bool live =
	    simple >= m_pHandles && simple < m_pHandles + m_maxHandles && simple->GetNextFree() == kProxyInUse;
	btAssert(live && "btSimpleBroadphase::destroyProxy: not a live proxy of this broadphase");
	if (!live) return;
	m_pairCache->removeOverlappingPairsContainingProxy(proxy, dispatcher);
	freeHandle(simple);
}

void btSimpleBroadphase::setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
                                 btDispatcher* dispatcher)
{
	(void)dispatcher;
	btAssert(proxy && "btSimpleBroadphase::setAabb: null proxy");
	if (!proxy) return;
	const bool finite = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
	btAssert(finite && "btSimpleBroadphase::setAabb: non-finite AABB");
	if (!finite) return;
	proxy->m_aabbMin = aabbMin;
	proxy->m_aabbMax = aabbMax;
}

void btSimpleBroadphase::getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const
{
	btAssert(proxy && "btSimpleBroadphase::getAabb: null proxy");
	if (!proxy)
	{
		aabbMin.setValue(0, 0, 0);
		aabbMax.setValue(0, 0, 0);
		return;
	}
	aabbMin = proxy->m_aabbMin;
	aabbMax = proxy->m_aabbMax;
}

void btSimpleBroadphase::rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
                                 const btVector3& aabbMin, const btVector3& aabbMax)
{
	(void)rayTo;  // the callback carries the direction (m_rayDirectionInverse) and the length (m_lambda_max)
	for (int i = 0; i <= m_LastHandleIndex; ++i)
	{
		btSimpleBroadphaseProxy* proxy = &m_pHandles[i];
		if (proxy->GetNextFree() != kProxyInUse) continue;
		// Growing the box by the swept box turns the box cast into a ray cast.
		const btVector3 bounds[2] = {proxy->m_aabbMin - aabbMax, proxy->m_aabbMax - aabbMin};
		btScalar tmin;
		if (btRayAabb2(rayFrom, rayCallback.m_rayDirectionInverse, rayCallback.m_signs, bounds, tmin, btScalar(0),
		               rayCallback.m_lambda_max))
		{
			rayCallback.process(proxy);
		}
	}
}

void btSimpleBroadphase::aabbTest(const btVector3& aabbMin, const btVector3& aabbMax,
                                  btBroadphaseAabbCallback& callback)
{
	for (int i = 0; i <= m_LastHandleIndex; ++i)
	{
		btSimpleBroadphaseProxy* proxy = &m_pHandles[i];
		if (proxy->GetNextFree() != kProxyInUse) continue;
		if (TestAabbAgainstAabb2(aabbMin, aabbMax, proxy->m_aabbMin, proxy->m_aabbMax)) callback.process(proxy);
	}
}

void btSimpleBroadphase::calculateOverlappingPairs(btDispatcher* dispatcher)
{
	// Stale pairs first, in one pass over the cache, so that the all-pairs loop only has to add.
	if (m_pairCache->getNumOverlappingPairs() > 0)
	{
		SeparatedPairRemover remover;
		m_pairCache->processAllOverlappingPairs(&remover, dispatcher);
	}
	for (int i = 0; i <= m_LastHandleIndex; ++i)
	{
		btSimpleBroadphaseProxy* proxy0 = &m_pHandles[i];
		if (proxy0->GetNextFree() != kProxyInUse) continue;
		for (int j = i + 1; j <= m_LastHandleIndex; ++j)
		{
			btSimpleBroadphaseProxy* proxy1 = &m_pHandles[j];
			if (proxy1->GetNextFree() != kProxyInUse || !aabbOverlap(proxy0, proxy1)) continue;
			// The lookup first: a cache is not required to ignore a second add of the same pair.
			if (!m_pairCache->findPair(proxy0, proxy1)) m_pairCache->addOverlappingPair(proxy0, proxy1);
		}
	}
}

bool btSimpleBroadphase::testAabbOverlap(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1)
{
	if (!proxy0 || !proxy1) return false;
	return aabbOverlap(getSimpleProxyFromProxy(proxy0), getSimpleProxyFromProxy(proxy1));
}

void btSimpleBroadphase::getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const
{
	aabbMin.setValue(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
	aabbMax.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
}

void btSimpleBroadphase::validate()
{
	const btBroadphasePairArray& pairs = m_pairCache->getOverlappingPairArray();
	for (int i = 0; i < pairs.size(); ++i)
	{
		const btSimpleBroadphaseProxy* proxy0 = static_cast<const btSimpleBroadphaseProxy*>(pairs[i].m_pProxy0);
		const btSimpleBroadphaseProxy* proxy1 = static_cast<const btSimpleBroadphaseProxy*>(pairs[i].m_pProxy1);
		btAssert(proxy0->GetNextFree() == kProxyInUse && proxy1->GetNextFree() == kProxyInUse);
		(void)proxy0;
		(void)proxy1;
	}
}

void btSimpleBroadphase::printStats()
{
	std::printf("btSimpleBroadphase: %d of %d proxies, %d pairs\n", m_numHandles, m_maxHandles,
	            m_pairCache->getNumOverlappingPairs());
}
