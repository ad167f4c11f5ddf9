// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_CONCAVE_COLLISION_ALGORITHM_H
#define BT_CONVEX_CONCAVE_COLLISION_ALGORITHM_H

/// btConvexConcaveCollisionAlgorithm: contacts of a convex shape with the triangles of a concave shape
/// (triangle meshes, height fields, ...).

#include <new>

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "LinearMath/btVector3.h"

class btManifoldResult;
class btPersistentManifold;

/// Receives the triangles of the concave shape that overlap the convex shape's AABB (in the concave's
/// frame) and runs the convex-triangle algorithm on each, all into one shared manifold. The per-triangle
/// algorithm is made once (from the dispatcher, for the (convex, triangle) pair) and reused for every
/// triangle and frame, so steady-state processing allocates nothing.
ATTRIBUTE_ALIGNED16(class)
btConvexTriangleCallback : public btTriangleCallback
{
	btVector3 m_aabbMin;
	btVector3 m_aabbMax;
	const btCollisionObjectWrapper* m_convexBodyWrap;
	const btCollisionObjectWrapper* m_triBodyWrap;
	btManifoldResult* m_resultOut;
	btDispatcher* m_dispatcher;
	const btDispatcherInfo* m_dispatchInfoPtr;
	btScalar m_collisionMarginTriangle;
	btCollisionAlgorithm* m_triangleAlgorithm;
	bool m_isSwapped;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Triangles processed in the last frame.
	int m_triangleCount;
	/// The shared manifold (convex object first), owned through the dispatcher.
	btPersistentManifold* m_manifoldPtr;

	/// A callback for the pair; isSwapped means body 0 is the concave object.
	btConvexTriangleCallback(btDispatcher * dispatcher, const btCollisionObjectWrapper* body0Wrap,
	                         const btCollisionObjectWrapper* body1Wrap, bool isSwapped);
	/// Destroys the per-triangle algorithm and releases the manifold.
	~btConvexTriangleCallback() override;

	/// Prepares one frame: the triangles' margin, the dispatch info, the pair and the result; computes the
	/// convex AABB in the concave's frame (grown by the margin and the closest-point distance).
	void setTimeStepAndCounters(btScalar collisionMarginTriangle, const btDispatcherInfo& dispatchInfo,
	                            const btCollisionObjectWrapper* convexBodyWrap,
	                            const btCollisionObjectWrapper* triBodyWrap, btManifoldResult* resultOut);
	/// Forgets the frame's wrappers (they live on the caller's stack).
	void clearWrapperData()
	{
		m_convexBodyWrap = 0;
		m_triBodyWrap = 0;
	}
	/// Collides the convex shape with one triangle (concave-local vertices).
	void processTriangle(btVector3 * triangle, int partId, int triangleIndex) override;
	/// Empties the manifold.
	void clearCache();

	/// Lower corner of the convex AABB in the concave's frame.
	SIMD_FORCE_INLINE const btVector3& getAabbMin() const { return m_aabbMin; }
	/// Upper corner of the convex AABB in the concave's frame.
	SIMD_FORCE_INLINE const btVector3& getAabbMax() const { return m_aabbMax; }
};

/// Convex against concave: the triangles overlapping the convex's AABB go through btConvexTriangleCallback.
class btConvexConcaveCollisionAlgorithm : public btActivatingCollisionAlgorithm
{
	btConvexTriangleCallback m_btConvexTriangleCallback;
	bool m_isSwapped;

public:
	/// An algorithm for the pair; isSwapped means body 0 is the concave object.
	btConvexConcaveCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
	                                  const btCollisionObjectWrapper* body0Wrap,
	                                  const btCollisionObjectWrapper* body1Wrap, bool isSwapped);
	/// Releases the manifold and the per-triangle algorithm.
	~btConvexConcaveCollisionAlgorithm() override;

	/// Collides the convex with the overlapping triangles and refreshes the manifold.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Always 1 for now: continuous collision is handled by the world's CCD.
	btScalar calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
	                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;
	/// Appends the manifold.
	void getAllContactManifolds(btManifoldArray& manifoldArray) override;
	/// Empties the manifold.
	void clearCache();

	/// Factory for the (convex, concave) order.
	struct CreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btConvexConcaveCollisionAlgorithm));
			return new (mem) btConvexConcaveCollisionAlgorithm(ci, body0Wrap, body1Wrap, false);
		}
	};

	/// Factory for the (concave, convex) order.
	struct SwappedCreateFunc : public btCollisionAlgorithmCreateFunc
	{
		/// A new algorithm.
		btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
		                                               const btCollisionObjectWrapper* body0Wrap,
		                                               const btCollisionObjectWrapper* body1Wrap) override
		{
			void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(btConvexConcaveCollisionAlgorithm));
			return new (mem) btConvexConcaveCollisionAlgorithm(ci, body0Wrap, body1Wrap, true);
		}
	};
};

#endif  // BT_CONVEX_CONCAVE_COLLISION_ALGORITHM_H
