// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SPHERE_SPHERE_COLLISION_ALGORITHM_H
#define BT_SPHERE_SPHERE_COLLISION_ALGORITHM_H

/// btSphereSphereCollisionAlgorithm: the exact contact of two spheres.

#include <new>

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"

class btPersistentManifold;

/// One point along the line of centres: normal from sphere B towards sphere A, the point on B's surface
/// and distance |cA - cB| - rA - rB. Concentric spheres use the normal (1, 0, 0).
class btSphereSphereCollisionAlgorithm : public btActivatingCollisionAlgorithm
{
	bool m_ownManifold;
	btPersistentManifold* m_manifoldPtr;

public:
	/// An algorithm filling mf, or its own manifold (made now) when mf is null.
	btSphereSphereCollisionAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                                 const btCollisionObjectWrapper* body0Wrap,
	                                 const btCollisionObjectWrapper* body1Wrap);
	/// An algorithm with no manifold (reports nothing).
	btSphereSphereCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci)
	    : btActivatingCollisionAlgorithm(ci), m_ownManifold(false), m_manifoldPtr(0)
	{
	}
	/// Releases an owned manifold through the dispatcher.
	~btSphereSphereCollisionAlgorithm() override;

	/// Writes the contact (or empties an owned manifold when the spheres are apart).
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the owned manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// Factory of btSphereSphereCollisionAlgorithm.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm sharing ci.m_manifold.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btSphereSphereCollisionAlgorithm));
			return new (mem) btSphereSphereCollisionAlgorithm(ci.m_manifold, ci, body0Wrap, body1Wrap);
		}
	};
};

#endif  // BT_SPHERE_SPHERE_COLLISION_ALGORITHM_H
