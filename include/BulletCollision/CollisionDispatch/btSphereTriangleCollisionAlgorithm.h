// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SPHERE_TRIANGLE_COLLISION_ALGORITHM_H
#define BT_SPHERE_TRIANGLE_COLLISION_ALGORITHM_H

/// btSphereTriangleCollisionAlgorithm: the exact contact of a sphere and a triangle (via
/// SphereTriangleDetector).

#include <new>

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"

class btPersistentManifold;

/// One point between a sphere and a two-sided triangle; swapped means body 0 is the triangle. Used for
/// meshes through the convex-concave algorithm, which shares its manifold.
class btSphereTriangleCollisionAlgorithm : public btActivatingCollisionAlgorithm
{
	bool m_ownManifold;
	btPersistentManifold* m_manifoldPtr;
	bool m_swapped;

public:
	/// An algorithm filling mf, or its own manifold (made now) when mf is null.
	btSphereTriangleCollisionAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                                   const btCollisionObjectWrapper* body0Wrap,
	                                   const btCollisionObjectWrapper* body1Wrap, bool swapped);
	/// An algorithm with no manifold (reports nothing).
	btSphereTriangleCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci)
	    : btActivatingCollisionAlgorithm(ci), m_ownManifold(false), m_manifoldPtr(0), m_swapped(false)
	{
	}
	/// Releases an owned manifold through the dispatcher.
	~btSphereTriangleCollisionAlgorithm() override;

	/// Writes the contact.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the owned manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// Factory of btSphereTriangleCollisionAlgorithm (m_swapped for the triangle-sphere order).
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm sharing ci.m_manifold.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btSphereTriangleCollisionAlgorithm));
			return new (mem) btSphereTriangleCollisionAlgorithm(ci.m_manifold, ci, body0Wrap, body1Wrap, m_swapped);
		}
	};
};

#endif  // BT_SPHERE_TRIANGLE_COLLISION_ALGORITHM_H
