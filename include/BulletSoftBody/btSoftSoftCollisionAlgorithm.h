// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFT_SOFT_COLLISION_ALGORITHM_H
#define BT_SOFT_SOFT_COLLISION_ALGORITHM_H

/// btSoftSoftCollisionAlgorithm: the algorithm of two soft bodies in the broadphase.

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"

class btSoftBody;
class btPersistentManifold;

/// Hands the pair to the first soft body, which records node-face contacts both ways (VF_SS) for the
/// solver (no manifold).
class btSoftSoftCollisionAlgorithm : public btCollisionAlgorithm
{
	btSoftBody* m_softBody0;
	btSoftBody* m_softBody1;

public:
	/// An algorithm for the pair of ci's dispatcher.
	btSoftSoftCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci)
	    : btCollisionAlgorithm(ci), m_softBody0(0), m_softBody1(0)
	{
	}
	/// An algorithm for the pair (Bullet's signature).
	btSoftSoftCollisionAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                             const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap);
	virtual ~btSoftSoftCollisionAlgorithm();

	/// Records the node-face contacts of the two bodies.
	virtual void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                              const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut);
	/// Always 1.
	virtual btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                                       const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut);
	/// Owns no manifold.
	virtual void getAllContactManifolds(btManifoldArray& manifoldArray) { (void)manifoldArray; }

	/// Factory.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		virtual btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                                       const btCollisionObjectWrapper* body0Wrap,
		                                                       const btCollisionObjectWrapper* body1Wrap)
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btSoftSoftCollisionAlgorithm));
			return new (mem) btSoftSoftCollisionAlgorithm(0, ci, body0Wrap, body1Wrap);
		}
	};
};

#endif  // BT_SOFT_SOFT_COLLISION_ALGORITHM_H
