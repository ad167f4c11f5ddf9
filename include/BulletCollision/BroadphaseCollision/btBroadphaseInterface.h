// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BROADPHASE_INTERFACE_H
#define BT_BROADPHASE_INTERFACE_H

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "LinearMath/btVector3.h"

class btDispatcher;
class btOverlappingPairCache;

/// Visited by btBroadphaseInterface::aabbTest for every proxy whose AABB overlaps the query box.
struct btBroadphaseAabbCallback
{
	virtual ~btBroadphaseAabbCallback() {}

	/// Called once per overlapping proxy; the return value is ignored by the broadphases (as in Bullet).
	virtual bool process(const btBroadphaseProxy* proxy) = 0;
};

/// Visited by btBroadphaseInterface::rayTest for every proxy whose AABB the ray may hit. The ray
/// stops at m_lambda_max (a fraction of rayTo - rayFrom), which a closest-hit callback may shrink as
/// it finds hits; m_rayDirectionInverse and m_signs are filled by the caller for slab tests.
struct btBroadphaseRayCallback : public btBroadphaseAabbCallback
{
	/// 1 / (rayTo - rayFrom) per axis (a huge value where the direction is 0).
	btVector3 m_rayDirectionInverse;
	/// 1 where m_rayDirectionInverse is negative, per axis.
	unsigned int m_signs[3];
	/// The ray is tested up to this fraction of its length.
	btScalar m_lambda_max;

	virtual ~btBroadphaseRayCallback() {}

protected:
	btBroadphaseRayCallback() : m_lambda_max(btScalar(1)) { m_signs[0] = m_signs[1] = m_signs[2] = 0; }
};

/// Keeps the AABBs of many objects and reports which pairs overlap, into its btOverlappingPairCache.
/// Implementations: btDbvtBroadphase (the default), btAxisSweep3 / bt32BitAxisSweep3, btSimpleBroadphase.
class btBroadphaseInterface
{
public:
	virtual ~btBroadphaseInterface() {}

	/// Adds an object with its AABB; returns its proxy (0 when the input is rejected: NaN bounds, full pool).
	virtual btBroadphaseProxy* createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int shapeType,
	                                       void* userPtr, int collisionFilterGroup, int collisionFilterMask,
	                                       btDispatcher* dispatcher) = 0;
	/// Removes the proxy and every pair that contains it.
	virtual void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) = 0;
	/// Moves the proxy's AABB; pairs are updated now or at the next calculateOverlappingPairs.
	virtual void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
	                     btDispatcher* dispatcher) = 0;
	/// The proxy's AABB as last set.
	virtual void getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const = 0;

	/// Calls rayCallback.process for every proxy whose AABB the ray from rayFrom to rayTo may hit.
	/// aabbMin/aabbMax, when not zero, grow each proxy's box (for swept shapes).
	virtual void rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
	                     const btVector3& aabbMin = btVector3(0, 0, 0),
	                     const btVector3& aabbMax = btVector3(0, 0, 0)) = 0;
	/// Calls callback.process for every proxy whose AABB overlaps [aabbMin, aabbMax].
	virtual void aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback) = 0;

	/// Brings the pair cache up to date with the AABBs set since the last call.
	virtual void calculateOverlappingPairs(btDispatcher* dispatcher) = 0;

	/// The cache that holds the overlapping pairs.
	virtual btOverlappingPairCache* getOverlappingPairCache() = 0;
	/// The cache that holds the overlapping pairs.
	virtual const btOverlappingPairCache* getOverlappingPairCache() const = 0;

	/// Bounds of everything in the broadphase (the world bounds for btAxisSweep3).
	virtual void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const = 0;

	/// Resets internal pools when the broadphase is empty (optional, as in Bullet).
	virtual void resetPool(btDispatcher* dispatcher) { (void)dispatcher; }

	/// Prints statistics (counts, tree depth) to stdout.
	virtual void printStats() = 0;
};

#endif  // BT_BROADPHASE_INTERFACE_H
