// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_CREATE_FUNC
#define BT_COLLISION_CREATE_FUNC

/// btCollisionAlgorithmCreateFunc: makes the algorithm of one pair of shape types.

#include "LinearMath/btAlignedObjectArray.h"

class btCollisionAlgorithm;
class btCollisionObject;
struct btCollisionObjectWrapper;
struct btCollisionAlgorithmConstructionInfo;

/// A factory of one kind of collision algorithm, registered in a collision configuration for a pair of
/// shape types. m_swapped marks the factory of the (B, A) order of an asymmetric algorithm.
struct btCollisionAlgorithmCreateFunc
{
	/// True when the algorithm expects its two bodies in the opposite order.
	bool m_swapped;

	/// A factory for the unswapped order.
	btCollisionAlgorithmCreateFunc() : m_swapped(false) {}
	/// Factories are deleted through base pointers.
	virtual ~btCollisionAlgorithmCreateFunc() {}

	/// A new algorithm for the pair, allocated with ci.m_dispatcher1->allocateCollisionAlgorithm (the
	/// base factory makes none).
	virtual btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo&,
	                                                       const btCollisionObjectWrapper* body0Wrap,
	                                                       const btCollisionObjectWrapper* body1Wrap)
	{
		(void)body0Wrap;
		(void)body1Wrap;
		return 0;
	}
};

#endif  // BT_COLLISION_CREATE_FUNC
