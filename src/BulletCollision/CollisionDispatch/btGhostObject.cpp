// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btGhostObject.h"

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "LinearMath/btAabbUtil2.h"

namespace
{
btCollisionObject* objectOf(btBroadphaseProxy* proxy)
{
	return proxy ? static_cast<btCollisionObject*>(proxy->m_clientObject) : 0;
}

// Removes object from list by moving the last entry into its place; returns false when it was not there.
bool removeUnordered(btAlignedObjectArray<btCollisionObject*>& list, btCollisionObject* object)
{
	const int index = list.findLinearSearch(object);
	if (index >= list.size()) return false;
	list[index] = list[list.size() - 1];
	list.pop_back();
	return true;
}
}  // namespace

btGhostObject::btGhostObject() { m_internalType = CO_GHOST_OBJECT; }

btGhostObject::~btGhostObject()
{
	// A ghost still in the world would leave dangling pointers in the broadphase and in other ghosts.
	btAssert(m_overlappingObjects.size() == 0 && "remove the ghost object from the world before deleting it");
}

void btGhostObject::addOverlappingObjectInternal(btBroadphaseProxy* otherProxy, btBroadphaseProxy* thisProxy)
{
	(void)thisProxy;
	btCollisionObject* other = objectOf(otherProxy);
	btAssert(other && "addOverlappingObjectInternal needs a proxy with a collision object");
	if (!other || other == this) return;
	// A ghost overlaps a handful of objects; a linear search beats hashing at that size.
	if (m_overlappingObjects.findLinearSearch(other) == m_overlappingObjects.size())
		m_overlappingObjects.push_back(other);
}

void btGhostObject::removeOverlappingObjectInternal(btBroadphaseProxy* otherProxy, btDispatcher* dispatcher,
                                                    btBroadphaseProxy* thisProxy)
{
	(void)dispatcher;
	(void)thisProxy;
	btCollisionObject* other = objectOf(otherProxy);
	btAssert(other && "removeOverlappingObjectInternal needs a proxy with a collision object");
	if (!other) return;
	removeUnordered(m_overlappingObjects, other);
}

void btGhostObject::rayTest(const btVector3& rayFromWorld, const btVector3& rayToWorld,
                            btCollisionWorld::RayResultCallback& resultCallback) const
{
	btTransform rayFrom;
	rayFrom.setIdentity();
	rayFrom.setOrigin(rayFromWorld);
	btTransform rayTo;
	rayTo.setIdentity();
	rayTo.setOrigin(rayToWorld);
	for (int i = 0; i < m_overlappingObjects.size(); ++i)
	{
		btCollisionObject* object = m_overlappingObjects[i];
		// Objects without a proxy are not in a world any more and cannot be filtered: skip them.
		if (!object->getBroadphaseHandle() || !object->getCollisionShape()) continue;
		if (!resultCallback.needsCollision(object->getBroadphaseHandle())) continue;
		btCollisionWorld::rayTestSingle(rayFrom, rayTo, object, object->getCollisionShape(),
		                                object->getWorldTransform(), resultCallback);
	}
}

void btGhostObject::convexSweepTest(const btConvexShape* castShape, const btTransform& convexFromWorld,
                                    const btTransform& convexToWorld,
                                    btCollisionWorld::ConvexResultCallback& resultCallback,
                                    btScalar allowedCcdPenetration) const
{
	btAssert(castShape);
	if (!castShape) return;
	// Box around everything the cast shape can cover: its bounding sphere about the transform's origin
	// (radius grown by the centre's offset, so any rotation stays inside) moved along the segment.
	btVector3 sphereCentre;
	btScalar sphereRadius;
	castShape->getBoundingSphere(sphereCentre, sphereRadius);
	const btScalar reach = sphereCentre.length() + sphereRadius;
	const btVector3 reachVector(reach, reach, reach);
	btVector3 sweepMin = convexFromWorld.getOrigin();
	btVector3 sweepMax = sweepMin;
	sweepMin.setMin(convexToWorld.getOrigin());
	sweepMax.setMax(convexToWorld.getOrigin());
	sweepMin -= reachVector;
	sweepMax += reachVector;

	for (int i = 0; i < m_overlappingObjects.size(); ++i)
	{
		btCollisionObject* object = m_overlappingObjects[i];
		if (!object->getBroadphaseHandle() || !object->getCollisionShape()) continue;
		if (!resultCallback.needsCollision(object->getBroadphaseHandle())) continue;
		btVector3 objectMin, objectMax;
		object->getCollisionShape()->getAabb(object->getWorldTransform(), objectMin, objectMax);
		if (!TestAabbAgainstAabb2(sweepMin, sweepMax, objectMin, objectMax)) continue;
		btCollisionWorld::objectQuerySingle(castShape, convexFromWorld, convexToWorld, object,
		                                    object->getCollisionShape(), object->getWorldTransform(), resultCallback,
		                                    allowedCcdPenetration);
	}
}

btBroadphasePair* btGhostPairCallback::addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1)
{
	btGhostObject* ghost0 = btGhostObject::upcast(objectOf(proxy0));
	btGhostObject* ghost1 = btGhostObject::upcast(objectOf(proxy1));
	if (ghost0) ghost0->addOverlappingObjectInternal(proxy1, proxy0);
	if (ghost1) ghost1->addOverlappingObjectInternal(proxy0, proxy1);
	return 0;
}

void* btGhostPairCallback::removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1,
                                                 btDispatcher* dispatcher)
{
	btGhostObject* ghost0 = btGhostObject::upcast(objectOf(proxy0));
	btGhostObject* ghost1 = btGhostObject::upcast(objectOf(proxy1));
	if (ghost0) ghost0->removeOverlappingObjectInternal(proxy1, dispatcher, proxy0);
	if (ghost1) ghost1->removeOverlappingObjectInternal(proxy0, dispatcher, proxy1);
	return 0;
}

void btGhostPairCallback::removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher)
{
	// The caches report every removed pair through removeOverlappingPair, which is all ghosts need.
	(void)proxy;
	(void)dispatcher;
}
