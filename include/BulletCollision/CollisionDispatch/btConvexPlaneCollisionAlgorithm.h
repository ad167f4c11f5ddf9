// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_PLANE_COLLISION_ALGORITHM_H
#define BT_CONVEX_PLANE_COLLISION_ALGORITHM_H

/// btConvexPlaneCollisionAlgorithm: contacts of a convex shape with a btStaticPlaneShape.

#include <new>

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"
#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "LinearMath/btQuaternion.h"

class btPersistentManifold;

/// A full manifold in one frame: for polyhedral shapes every vertex (pushed out by the margin, boxes at
/// their full size) within the breaking threshold of the plane is a candidate, so a resting box gets
/// its 4 corners at once; for other convex shapes the deepest support point plus support points of
/// slightly tilted copies (the multipoint perturbation, for shapes like cylinders; never for spheres)
/// while the manifold has fewer than m_minimumPointsPerturbationThreshold points.
/// The normal is the plane's; swapped means body 0 is the plane.
class btConvexPlaneCollisionAlgorithm : public btCollisionAlgorithm
{
	bool m_ownManifold;
	btPersistentManifold* m_manifoldPtr;
	bool m_isSwapped;
	int m_numPerturbationIterations;
	int m_minimumPointsPerturbationThreshold;

public:
	/// An algorithm filling mf, or its own manifold (made now) when mf is null.
	btConvexPlaneCollisionAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                                const btCollisionObjectWrapper* body0Wrap,
	                                const btCollisionObjectWrapper* body1Wrap, bool isSwapped,
	                                int numPerturbationIterations, int minimumPointsPerturbationThreshold);
	/// Releases an owned manifold through the dispatcher.
	~btConvexPlaneCollisionAlgorithm() override;

	/// Writes the contacts and refreshes an owned manifold.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Adds the support point of the convex shape rotated by perturbeRot (identity: the deepest point),
	/// evaluated at its unrotated position, when it is within the breaking threshold of the plane.
	void collideSingleContact(const btQuaternion& perturbeRot, const btCollisionObjectWrapper* body0Wrap,
	                          const btCollisionObjectWrapper* body1Wrap, const btDispatcherInfo& dispatchInfo,
	                          btManifoldResult* resultOut);
	/// Always 1: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the owned manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// Factory of btConvexPlaneCollisionAlgorithm (m_swapped for the plane-convex order).
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// Number of tilted copies tried for non-polyhedral shapes.
		int m_numPerturbationIterations;
		/// Tilted copies are tried only while the manifold has fewer points than this.
		int m_minimumPointsPerturbationThreshold;

		/// Bullet's defaults (1, 0): no tilted copies unless setPlaneConvexMultipointIterations asks.
		CreateFunc() : m_numPerturbationIterations(1), m_minimumPointsPerturbationThreshold(0) {}

		/// A new algorithm sharing ci.m_manifold.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btConvexPlaneCollisionAlgorithm));
			return new (mem)
			    btConvexPlaneCollisionAlgorithm(ci.m_manifold, ci, body0Wrap, body1Wrap, m_swapped,
			                                    m_numPerturbationIterations, m_minimumPointsPerturbationThreshold);
		}
	};
};

#endif  // BT_CONVEX_PLANE_COLLISION_ALGORITHM_H
