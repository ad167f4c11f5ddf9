// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_ALGORITHM_H
#define BT_COLLISION_ALGORITHM_H

/// btCollisionAlgorithm: the narrowphase of one pair of collision objects.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

struct btBroadphaseProxy;
class btDispatcher;
class btManifoldResult;
class btCollisionObject;
struct btCollisionObjectWrapper;
struct btDispatcherInfo;
class btPersistentManifold;

/// The manifolds of an algorithm (see getAllContactManifolds).
typedef btAlignedObjectArray<btPersistentManifold*> btManifoldArray;

/// What a create function needs to build an algorithm: the dispatcher and an optional shared manifold.
struct btCollisionAlgorithmConstructionInfo
{
	/// No dispatcher, no manifold.
	btCollisionAlgorithmConstructionInfo() : m_dispatcher1(0), m_manifold(0) {}
	/// A dispatcher and no manifold (the int is unused, as in Bullet).
	btCollisionAlgorithmConstructionInfo(btDispatcher* dispatcher, int temp) : m_dispatcher1(dispatcher), m_manifold(0)
	{
		(void)temp;
	}

	/// The dispatcher that allocates the algorithm and its manifold.
	btDispatcher* m_dispatcher1;
	/// A manifold the algorithm should fill instead of creating its own (may be null).
	btPersistentManifold* m_manifold;
};

/// Computes contacts (processCollision) or a time of impact for one pair of objects. Algorithms are
/// allocated with btDispatcher::allocateCollisionAlgorithm and live as long as the pair overlaps.
class btCollisionAlgorithm
{
protected:
	/// The dispatcher that made the algorithm.
	btDispatcher* m_dispatcher;

public:
	/// An algorithm without a dispatcher.
	btCollisionAlgorithm() : m_dispatcher(0) {}
	/// An algorithm bound to ci's dispatcher.
	btCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci);
	/// Algorithms are destroyed through base pointers.
	virtual ~btCollisionAlgorithm() {}

	/// Computes the contacts of the pair at the current transforms and writes them to resultOut.
	virtual void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                              const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) = 0;

	/// The fraction of the step (from the current to the interpolation transforms) at which the pair
	/// first touches, or 1 when it does not.
	virtual btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                                       const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) = 0;

	/// Appends the manifolds the algorithm owns.
	virtual void getAllContactManifolds(btManifoldArray& manifoldArray) = 0;
};

#endif  // BT_COLLISION_ALGORITHM_H
