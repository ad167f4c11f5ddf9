// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_EMPTY_ALGORITH
#define BT_EMPTY_ALGORITH

/// btEmptyAlgorithm: the algorithm of pairs that never produce contacts.

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"

/// Does nothing: used for shape pairs without an algorithm (empty shapes, concave-concave, ...).
ATTRIBUTE_ALIGNED16(class)
btEmptyAlgorithm : public btCollisionAlgorithm
{
public:
	/// An algorithm bound to ci's dispatcher.
	btEmptyAlgorithm(const btCollisionAlgorithmConstructionInfo& ci);

	/// Adds nothing.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1 (no impact).
	btScalar calculateTimeOfImpact(btCollisionObject * body0, btCollisionObject * body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Owns no manifold.
	void getAllContactManifolds(btManifoldArray&) override {}

	/// Factory of btEmptyAlgorithm.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new btEmptyAlgorithm.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper*,
		                                               const btCollisionObjectWrapper*) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btEmptyAlgorithm));
			return new (mem) btEmptyAlgorithm(ci);
		}
	};
};

#endif  // BT_EMPTY_ALGORITH
