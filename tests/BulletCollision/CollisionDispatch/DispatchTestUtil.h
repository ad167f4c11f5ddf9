// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_DISPATCH_TEST_UTIL_H
#define CALIBER_TESTS_DISPATCH_TEST_UTIL_H

// Helpers of the dispatcher tests: a minimal pair cache (a plain array, so that these tests do not
// depend on the broadphase's caches) and an object that owns its broadphase proxy.

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"

namespace caliber_dispatch_test
{
// Pairs in an array, in insertion order; the filter is the group/mask test or the user's callback.
class ArrayPairCache : public btOverlappingPairCache
{
public:
	btBroadphasePair* getOverlappingPairArrayPtr() override { return m_pairs.size() ? &m_pairs[0] : 0; }
	const btBroadphasePair* getOverlappingPairArrayPtr() const override { return m_pairs.size() ? &m_pairs[0] : 0; }
	btBroadphasePairArray& getOverlappingPairArray() override { return m_pairs; }
	void cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher) override
	{
		if (!pair.m_algorithm) return;
		pair.m_algorithm->~btCollisionAlgorithm();
		dispatcher->freeCollisionAlgorithm(pair.m_algorithm);
		pair.m_algorithm = 0;
	}
	int getNumOverlappingPairs() const override { return m_pairs.size(); }
	bool needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override
	{
		if (m_filter) return m_filter->needBroadphaseCollision(proxy0, proxy1);
		return (proxy0->m_collisionFilterGroup & proxy1->m_collisionFilterMask) != 0 &&
		       (proxy1->m_collisionFilterGroup & proxy0->m_collisionFilterMask) != 0;
	}
	btOverlapFilterCallback* getOverlapFilterCallback() override { return m_filter; }
	void cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override
	{
		for (int i = 0; i < m_pairs.size(); ++i)
			if (m_pairs[i].m_pProxy0 == proxy || m_pairs[i].m_pProxy1 == proxy)
				cleanOverlappingPair(m_pairs[i], dispatcher);
	}
	void setOverlapFilterCallback(btOverlapFilterCallback* callback) override { m_filter = callback; }
	void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher) override
	{
		for (int i = 0; i < m_pairs.size();)
		{
			if (callback->processOverlap(m_pairs[i]))
			{
				cleanOverlappingPair(m_pairs[i], dispatcher);
				m_pairs.removeAtIndex(i);
			}
			else
			{
				++i;
			}
		}
	}
	btBroadphasePair* findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override
	{
		for (int i = 0; i < m_pairs.size(); ++i)
		{
			if ((m_pairs[i].m_pProxy0 == proxy0 && m_pairs[i].m_pProxy1 == proxy1) ||
			    (m_pairs[i].m_pProxy0 == proxy1 && m_pairs[i].m_pProxy1 == proxy0))
				return &m_pairs[i];
		}
		return 0;
	}
	bool hasDeferredRemoval() override { return false; }
	void setInternalGhostPairCallback(btOverlappingPairCallback* ghostPairCallback) override
	{
		m_ghost = ghostPairCallback;
	}
	void sortOverlappingPairs(btDispatcher*) override {}

	btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override
	{
		if (!needsBroadphaseCollision(proxy0, proxy1)) return 0;
		if (btBroadphasePair* existing = findPair(proxy0, proxy1)) return existing;
		m_pairs.push_back(btBroadphasePair(*proxy0, *proxy1));
		if (m_ghost) m_ghost->addOverlappingPair(proxy0, proxy1);
		return &m_pairs[m_pairs.size() - 1];
	}
	void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1, btDispatcher* dispatcher) override
	{
		btBroadphasePair* pair = findPair(proxy0, proxy1);
		if (!pair) return 0;
		if (m_ghost) m_ghost->removeOverlappingPair(proxy0, proxy1, dispatcher);
		cleanOverlappingPair(*pair, dispatcher);
		m_pairs.removeAtIndex(int(pair - &m_pairs[0]));
		return 0;
	}
	void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override
	{
		for (int i = m_pairs.size() - 1; i >= 0; --i)
			if (m_pairs[i].m_pProxy0 == proxy || m_pairs[i].m_pProxy1 == proxy)
				removeOverlappingPair(m_pairs[i].m_pProxy0, m_pairs[i].m_pProxy1, dispatcher);
	}

	// Frees every pair's algorithm (call before the dispatcher goes away).
	void clear(btDispatcher* dispatcher)
	{
		for (int i = 0; i < m_pairs.size(); ++i) cleanOverlappingPair(m_pairs[i], dispatcher);
		m_pairs.clear();
	}

private:
	btBroadphasePairArray m_pairs;
	btOverlapFilterCallback* m_filter = 0;
	btOverlappingPairCallback* m_ghost = 0;
};

// A collision object with its own broadphase proxy (no broadphase needed).
class ProxyObject : public btCollisionObject
{
public:
	ProxyObject(btCollisionShape* shape, const btVector3& origin, int uniqueId, int flags = CF_DYNAMIC_OBJECT,
	            int group = btBroadphaseProxy::DefaultFilter, int mask = btBroadphaseProxy::AllFilter)
	{
		setCollisionShape(shape);
		setCollisionFlags(flags);
		btTransform t;
		t.setIdentity();
		t.setOrigin(origin);
		setWorldTransform(t);
		setInterpolationWorldTransform(t);
		m_proxy.m_clientObject = this;
		m_proxy.m_uniqueId = uniqueId;
		m_proxy.m_collisionFilterGroup = group;
		m_proxy.m_collisionFilterMask = mask;
		setBroadphaseHandle(&m_proxy);
	}
	btBroadphaseProxy m_proxy;
};
}  // namespace caliber_dispatch_test

#endif  // CALIBER_TESTS_DISPATCH_TEST_UTIL_H
