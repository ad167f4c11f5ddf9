// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_TEST_DISPATCHER_H
#define CALIBER_TESTS_TEST_DISPATCHER_H

// A minimal btDispatcher for the algorithm tests (btCollisionDispatcher is another issue): algorithms
// come from the configuration's tables, manifolds and algorithms from its pools. Plus PairFixture,
// which owns two collision objects and the algorithm between them.

#include <gtest/gtest.h>

#include <new>

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btPoolAllocator.h"

namespace caliber_dispatch_test
{
class TestDispatcher : public btDispatcher
{
public:
	explicit TestDispatcher(btCollisionConfiguration* config) : m_config(config) {}
	~TestDispatcher() override
	{
		while (m_manifolds.size()) releaseManifold(m_manifolds[m_manifolds.size() - 1]);
	}

	btCollisionAlgorithm* findAlgorithm(const btCollisionObjectWrapper* body0Wrap,
	                                    const btCollisionObjectWrapper* body1Wrap, btPersistentManifold* sharedManifold,
	                                    ebtDispatcherQueryType queryType) override
	{
		btCollisionAlgorithmConstructionInfo ci;
		ci.m_dispatcher1 = this;
		ci.m_manifold = sharedManifold;
		const int type0 = body0Wrap->getCollisionShape()->getShapeType();
		const int type1 = body1Wrap->getCollisionShape()->getShapeType();
		btCollisionAlgorithmCreateFunc* factory = queryType == BT_CONTACT_POINT_ALGORITHMS
		                                              ? m_config->getCollisionAlgorithmCreateFunc(type0, type1)
		                                              : m_config->getClosestPointsAlgorithmCreateFunc(type0, type1);
		return factory->CreateCollisionAlgorithm(ci, body0Wrap, body1Wrap);
	}

	btPersistentManifold* getNewManifold(const btCollisionObject* b0, const btCollisionObject* b1) override
	{
		// Same thresholds as Bullet's dispatcher: relative to the shapes' size, processing from the objects.
		const btScalar breaking =
		    btMin(b0->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold),
		          b1->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold));
		const btScalar processing = btMin(b0->getContactProcessingThreshold(), b1->getContactProcessingThreshold());
		void* mem = m_config->getPersistentManifoldPool()->allocate(int(sizeof(btPersistentManifold)));
		if (!mem) mem = btAlignedAlloc(sizeof(btPersistentManifold), 16);
		btPersistentManifold* manifold = new (mem) btPersistentManifold(b0, b1, 0, breaking, processing);
		manifold->m_index1a = m_manifolds.size();
		m_manifolds.push_back(manifold);
		return manifold;
	}

	void releaseManifold(btPersistentManifold* manifold) override
	{
		clearManifold(manifold);
		const int index = manifold->m_index1a;
		m_manifolds.swap(index, m_manifolds.size() - 1);
		m_manifolds[index]->m_index1a = index;
		m_manifolds.pop_back();
		manifold->~btPersistentManifold();
		btPoolAllocator* pool = m_config->getPersistentManifoldPool();
		if (pool->validPtr(manifold))
			pool->freeMemory(manifold);
		else
			btAlignedFree(manifold);
	}

	void clearManifold(btPersistentManifold* manifold) override { manifold->clearManifold(); }

	bool needsCollision(const btCollisionObject* body0, const btCollisionObject* body1) override
	{
		return body0 && body1 && body0->checkCollideWith(body1) && body1->checkCollideWith(body0);
	}
	bool needsResponse(const btCollisionObject* body0, const btCollisionObject* body1) override
	{
		return body0->hasContactResponse() && body1->hasContactResponse() &&
		       !(body0->isStaticOrKinematicObject() && body1->isStaticOrKinematicObject());
	}
	void dispatchAllCollisionPairs(btOverlappingPairCache*, const btDispatcherInfo&, btDispatcher*) override {}

	int getNumManifolds() const override { return m_manifolds.size(); }
	btPersistentManifold* getManifoldByIndexInternal(int index) override { return m_manifolds[index]; }
	btPersistentManifold** getInternalManifoldPointer() override { return m_manifolds.size() ? &m_manifolds[0] : 0; }
	btPoolAllocator* getInternalManifoldPool() override { return m_config->getPersistentManifoldPool(); }
	const btPoolAllocator* getInternalManifoldPool() const override { return m_config->getPersistentManifoldPool(); }

	void* allocateCollisionAlgorithm(int size) override
	{
		void* mem = m_config->getCollisionAlgorithmPool()->allocate(size);
		return mem ? mem : btAlignedAlloc(size_t(size), 16);
	}
	void freeCollisionAlgorithm(void* ptr) override
	{
		btPoolAllocator* pool = m_config->getCollisionAlgorithmPool();
		if (pool->validPtr(ptr))
			pool->freeMemory(ptr);
		else
			btAlignedFree(ptr);
	}

	void destroyAlgorithm(btCollisionAlgorithm* algorithm)
	{
		if (!algorithm) return;
		algorithm->~btCollisionAlgorithm();
		freeCollisionAlgorithm(algorithm);
	}

private:
	btCollisionConfiguration* m_config;
	btAlignedObjectArray<btPersistentManifold*> m_manifolds;
};

// Two dynamic objects with the given shapes and the algorithm the dispatcher picks for them.
class PairFixture
{
public:
	PairFixture(TestDispatcher& dispatcher, btCollisionShape* shape0, const btTransform& t0, btCollisionShape* shape1,
	            const btTransform& t1, ebtDispatcherQueryType queryType = BT_CONTACT_POINT_ALGORITHMS)
	    : m_dispatcher(dispatcher), m_algorithm(0)
	{
		m_object0.setCollisionShape(shape0);
		m_object1.setCollisionShape(shape1);
		m_object0.setCollisionFlags(0);
		m_object1.setCollisionFlags(0);
		m_object0.setWorldTransform(t0);
		m_object1.setWorldTransform(t1);
		btCollisionObjectWrapper w0(0, shape0, &m_object0, m_object0.getWorldTransform(), -1, -1);
		btCollisionObjectWrapper w1(0, shape1, &m_object1, m_object1.getWorldTransform(), -1, -1);
		m_algorithm = dispatcher.findAlgorithm(&w0, &w1, 0, queryType);
	}
	~PairFixture() { m_dispatcher.destroyAlgorithm(m_algorithm); }

	// Runs the algorithm once at the current transforms and returns the manifold it filled (or null).
	btPersistentManifold* process()
	{
		btCollisionObjectWrapper w0(0, m_object0.getCollisionShape(), &m_object0, m_object0.getWorldTransform(), -1,
		                            -1);
		btCollisionObjectWrapper w1(0, m_object1.getCollisionShape(), &m_object1, m_object1.getWorldTransform(), -1,
		                            -1);
		btManifoldResult result(&w0, &w1);
		btDispatcherInfo info;
		info.m_enableSatConvex = m_enableSat;
		m_algorithm->processCollision(&w0, &w1, info, &result);
		return result.getPersistentManifold();
	}

	btCollisionObject m_object0;
	btCollisionObject m_object1;
	TestDispatcher& m_dispatcher;
	btCollisionAlgorithm* m_algorithm;
	bool m_enableSat = false;
};
}  // namespace caliber_dispatch_test

#endif  // CALIBER_TESTS_TEST_DISPATCHER_H
