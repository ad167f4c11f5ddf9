// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BOX_BOX__COLLISION_ALGORITHM_H
#define BT_BOX_BOX__COLLISION_ALGORITHM_H

/// btBoxBoxCollisionAlgorithm: the contact manifold of two boxes (via btBoxBoxDetector).

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"

class btPersistentManifold;

/// Up to 4 points per frame from btBoxBoxDetector (separating axes and face clipping), so a box
/// resting on another gets its full manifold in the first frame.
class btBoxBoxCollisionAlgorithm : public btActivatingCollisionAlgorithm
{
	bool m_ownManifold;
	btPersistentManifold* m_manifoldPtr;

public:
	/// An algorithm with no manifold (reports nothing).
	btBoxBoxCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci)
	    : btActivatingCollisionAlgorithm(ci), m_ownManifold(false), m_manifoldPtr(0)
	{
	}
	/// An algorithm filling mf, or its own manifold (made now) when mf is null.
	btBoxBoxCollisionAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                           const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap);
	/// Releases an owned manifold through the dispatcher.
	~btBoxBoxCollisionAlgorithm() override;

	/// Writes the contacts and refreshes an owned manifold.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the owned manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// Factory of btBoxBoxCollisionAlgorithm.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm sharing ci.m_manifold.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override;
	};
};

#endif  // BT_BOX_BOX__COLLISION_ALGORITHM_H
