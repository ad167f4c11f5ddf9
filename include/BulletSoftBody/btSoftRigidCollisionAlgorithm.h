// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFT_RIGID_COLLISION_ALGORITHM_H
#define BT_SOFT_RIGID_COLLISION_ALGORITHM_H

/// btSoftRigidCollisionAlgorithm: the algorithm of a soft body and a rigid object in the broadphase.

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"

class btSoftBody;
class btPersistentManifold;

/// Hands the pair to the soft body, which records node contacts for its own solver (no manifold).
class btSoftRigidCollisionAlgorithm : public btCollisionAlgorithm
{
	btSoftBody* m_softBody;
	btCollisionObject* m_rigidCollisionObject;
	bool m_isSwapped;  ///< The soft body is the second object of the pair.

public:
	/// An algorithm for the pair; isSwapped when the soft body comes second.
	btSoftRigidCollisionAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                              const btCollisionObjectWrapper* col0, const btCollisionObjectWrapper* col1Wrap,
	                              bool isSwapped);
	virtual ~btSoftRigidCollisionAlgorithm();

	/// Records the soft body's node contacts with the rigid object.
	virtual void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                              const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut);
	/// Always 1 (the soft body handles fast motion itself).
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
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btSoftRigidCollisionAlgorithm));
			return new (mem) btSoftRigidCollisionAlgorithm(0, ci, body0Wrap, body1Wrap, m_swapped);
		}
	};
};

#endif  // BT_SOFT_RIGID_COLLISION_ALGORITHM_H
