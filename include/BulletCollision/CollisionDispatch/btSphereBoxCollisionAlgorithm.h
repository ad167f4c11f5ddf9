// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SPHERE_BOX_COLLISION_ALGORITHM_H
#define BT_SPHERE_BOX_COLLISION_ALGORITHM_H

/// btSphereBoxCollisionAlgorithm: the exact contact of a sphere and a box.

#include <new>

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"
#include "LinearMath/btVector3.h"

class btPersistentManifold;

/// One point between a sphere and a box (the box at its full size, getHalfExtentsWithMargin): outside,
/// the closest point of the box; inside, the nearest face. The normal points from the box towards the
/// sphere. isSwapped means body 0 is the box.
class btSphereBoxCollisionAlgorithm : public btActivatingCollisionAlgorithm
{
	bool m_ownManifold;
	btPersistentManifold* m_manifoldPtr;
	bool m_isSwapped;

public:
	/// An algorithm filling mf, or its own manifold (made now) when mf is null.
	btSphereBoxCollisionAlgorithm(btPersistentManifold* mf, const btCollisionAlgorithmConstructionInfo& ci,
	                              const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                              bool isSwapped);
	/// Releases an owned manifold through the dispatcher.
	~btSphereBoxCollisionAlgorithm() override;

	/// Writes the contact (or empties an owned manifold when apart).
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the owned manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;

	/// The contact of a sphere (centre in world space, radius) with the box of boxObjWrap: the point on the
	/// box, the normal from the box towards the sphere and the signed distance. Returns false when the
	/// distance exceeds maxContactDistance.
	bool getSphereDistance(const btCollisionObjectWrapper* boxObjWrap, btVector3& v3PointOnBox, btVector3& normal,
	                       btScalar& penetrationDepth, const btVector3& v3SphereCenter, btScalar fRadius,
	                       btScalar maxContactDistance);
	/// For a centre inside the box (box frame): the point on the nearest face, its outward normal, and the
	/// (negative) distance of the centre to that face.
	btScalar getSpherePenetration(btVector3 const& boxHalfExtent, btVector3 const& sphereRelPos,
	                              btVector3& closestPoint, btVector3& normal);

	/// Factory of btSphereBoxCollisionAlgorithm (m_swapped for the box-sphere order).
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm sharing ci.m_manifold.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btSphereBoxCollisionAlgorithm));
			return new (mem) btSphereBoxCollisionAlgorithm(ci.m_manifold, ci, body0Wrap, body1Wrap, m_swapped);
		}
	};
};

#endif  // BT_SPHERE_BOX_COLLISION_ALGORITHM_H
