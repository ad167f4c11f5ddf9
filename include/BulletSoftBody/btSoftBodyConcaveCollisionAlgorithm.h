// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOFT_BODY_CONCAVE_COLLISION_ALGORITHM_H
#define BT_SOFT_BODY_CONCAVE_COLLISION_ALGORITHM_H

/// btSoftBodyConcaveCollisionAlgorithm: the algorithm of a soft body and a concave rigid object (a
/// triangle mesh, a height field, a static plane) in the broadphase.

#include <new>

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"

class btSoftBody;
class btCollisionObject;

/// Hands the pair to the soft body, which finds its node contacts with the nearest triangles itself
/// (docs/soft-bodies.md, "Collision"); it keeps no manifold and no triangle cache.
class btSoftBodyConcaveCollisionAlgorithm : public btCollisionAlgorithm
{
	bool m_isSwapped;  ///< The soft body is the second object of the pair.

public:
	/// An algorithm for the pair; isSwapped when the soft body comes second.
	btSoftBodyConcaveCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
	                                    const btCollisionObjectWrapper* body0Wrap,
	                                    const btCollisionObjectWrapper* body1Wrap, bool isSwapped);
	virtual ~btSoftBodyConcaveCollisionAlgorithm();

	/// Records the soft body's node contacts with the concave object.
	virtual void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                              const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut);
	/// Always 1 (the soft body handles fast motion itself).
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut);
	/// Owns no manifold.
	virtual void getAllContactManifolds(btManifoldArray& manifoldArray) { (void)manifoldArray; }
	/// Nothing to clear: no triangles are cached between steps.
	void clearCache() {}

	/// Factory for (soft, concave) pairs.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		virtual btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                                       const btCollisionObjectWrapper* body0Wrap,
		                                                       const btCollisionObjectWrapper* body1Wrap)
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btSoftBodyConcaveCollisionAlgorithm));
			return new (mem) btSoftBodyConcaveCollisionAlgorithm(ci, body0Wrap, body1Wrap, false);
		}
	};
	/// Factory for (concave, soft) pairs.
	struct SwappedCreateFunc : public btCollisionAlgorithmCreateFunc
	{
		virtual btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                                       const btCollisionObjectWrapper* body0Wrap,
		                                                       const btCollisionObjectWrapper* body1Wrap)
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btSoftBodyConcaveCollisionAlgorithm));
			return new (mem) btSoftBodyConcaveCollisionAlgorithm(ci, body0Wrap, body1Wrap, true);
		}
	};
};

#endif  // BT_SOFT_BODY_CONCAVE_COLLISION_ALGORITHM_H
