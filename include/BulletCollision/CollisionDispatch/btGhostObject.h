// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GHOST_OBJECT_H
#define BT_GHOST_OBJECT_H

/// btGhostObject, btPairCachingGhostObject and btGhostPairCallback: collision objects that keep the list
/// of objects whose AABBs overlap theirs (triggers, character controllers, local queries).

#include "BulletCollision/BroadphaseCollision/btOverlappingPairCallback.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btAlignedObjectArray.h"

class btConvexShape;
class btDispatcher;
class btHashedOverlappingPairCache;

/// A collision object that records the objects its broadphase AABB overlaps, as reported through a
/// btGhostPairCallback installed on the world's pair cache. Ray and convex sweep queries against only
/// those objects are much cheaper than world queries. Remove it from the world before deleting it.
ATTRIBUTE_ALIGNED16(class)
btGhostObject : public btCollisionObject
{
protected:
	/// Objects whose AABBs overlap the ghost's (no duplicates, in no particular order).
	btAlignedObjectArray<btCollisionObject*> m_overlappingObjects;

public:
	/// A ghost (internal type CO_GHOST_OBJECT) that overlaps nothing yet.
	btGhostObject();
	/// Asserts that the ghost was removed from the world (its overlap list is empty).
	~btGhostObject() override;

	/// Sweeps castShape from convexFromWorld to convexToWorld against the overlapping objects that pass
	/// the callback's filter, reporting hits to resultCallback.
	void convexSweepTest(const btConvexShape* castShape, const btTransform& convexFromWorld,
	                     const btTransform& convexToWorld, btCollisionWorld::ConvexResultCallback& resultCallback,
	                     btScalar allowedCcdPenetration = btScalar(0)) const;

	/// Casts the ray against the overlapping objects that pass the callback's filter.
	void rayTest(const btVector3& rayFromWorld, const btVector3& rayToWorld,
	             btCollisionWorld::RayResultCallback& resultCallback) const;

	/// Adds otherProxy's object to the overlap list unless it is there already (called by btGhostPairCallback).
	virtual void addOverlappingObjectInternal(btBroadphaseProxy * otherProxy, btBroadphaseProxy* thisProxy = 0);
	/// Removes otherProxy's object from the overlap list (called by btGhostPairCallback).
	virtual void removeOverlappingObjectInternal(btBroadphaseProxy * otherProxy, btDispatcher * dispatcher,
	                                             btBroadphaseProxy* thisProxy = 0);

	/// Number of overlapping objects.
	int getNumOverlappingObjects() const { return m_overlappingObjects.size(); }
	/// Overlapping object at index.
	btCollisionObject* getOverlappingObject(int index) { return m_overlappingObjects[index]; }
	/// Overlapping object at index.
	const btCollisionObject* getOverlappingObject(int index) const { return m_overlappingObjects[index]; }
	/// The overlap list.
	btAlignedObjectArray<btCollisionObject*>& getOverlappingPairs() { return m_overlappingObjects; }
	/// The overlap list.
	const btAlignedObjectArray<btCollisionObject*>& getOverlappingPairs() const { return m_overlappingObjects; }

	/// colObj as a ghost object, or null when it is not one (or is null).
	static const btGhostObject* upcast(const btCollisionObject* colObj)
	{
		return (colObj && colObj->getInternalType() == CO_GHOST_OBJECT) ? static_cast<const btGhostObject*>(colObj) : 0;
	}
	/// colObj as a ghost object, or null when it is not one (or is null).
	static btGhostObject* upcast(btCollisionObject * colObj)
	{
		return (colObj && colObj->getInternalType() == CO_GHOST_OBJECT) ? static_cast<btGhostObject*>(colObj) : 0;
	}
};

/// A ghost object that also keeps its own pair cache of (ghost, other) pairs, so that the narrowphase
/// can be run on just its pairs (the character controller's recovery step does).
class btPairCachingGhostObject : public btGhostObject
{
	btHashedOverlappingPairCache* m_hashPairCache;

public:
	/// A ghost with an empty pair cache.
	btPairCachingGhostObject();
	/// Frees the pair cache (and the algorithms still attached to its pairs must be gone: remove the
	/// ghost from the world first).
	~btPairCachingGhostObject() override;

	/// Adds the object and the (ghost, other) pair; thisProxy defaults to the ghost's broadphase handle.
	void addOverlappingObjectInternal(btBroadphaseProxy* otherProxy, btBroadphaseProxy* thisProxy = 0) override;
	/// Removes the object and its pair (the pair's algorithm is freed through dispatcher).
	void removeOverlappingObjectInternal(btBroadphaseProxy* otherProxy, btDispatcher* dispatcher,
	                                     btBroadphaseProxy* thisProxy = 0) override;

	/// The ghost's own pair cache.
	btHashedOverlappingPairCache* getOverlappingPairCache() { return m_hashPairCache; }
};

/// Mirrors the world's pair additions and removals into the ghost objects involved. Install it with
/// world->getPairCache()->setInternalGhostPairCallback(new btGhostPairCallback()).
class btGhostPairCallback : public btOverlappingPairCallback
{
public:
	/// A stateless callback.
	btGhostPairCallback() {}
	~btGhostPairCallback() override {}

	/// Tells each ghost of the pair about the other object; returns null (the callback stores no pairs).
	btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override;

	/// Tells each ghost of the pair that the other object left; returns null.
	void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1,
	                            btDispatcher* dispatcher) override;

	/// Not used: the pair caches report removals pair by pair through removeOverlappingPair. Does nothing.
	void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;
};

#endif  // BT_GHOST_OBJECT_H
