// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DEFAULT_COLLISION_CONFIGURATION
#define BT_DEFAULT_COLLISION_CONFIGURATION

/// btDefaultCollisionConfiguration: Caliber's standard algorithm table and memory pools.

#include "BulletCollision/CollisionDispatch/btCollisionConfiguration.h"

class btConvexPenetrationDepthSolver;

/// How btDefaultCollisionConfiguration sizes (or borrows) its pools and picks its depth solver.
struct btDefaultCollisionConstructionInfo
{
	/// A manifold pool to use instead of making one (not owned; null: make one).
	btPoolAllocator* m_persistentManifoldPool;
	/// An algorithm pool to use instead of making one (not owned; null: make one).
	btPoolAllocator* m_collisionAlgorithmPool;
	/// Manifolds in the pool made by the configuration.
	int m_defaultMaxPersistentManifoldPoolSize;
	/// Algorithms in the pool made by the configuration.
	int m_defaultMaxCollisionAlgorithmPoolSize;
	/// Size in bytes of the largest user algorithm, so that it fits the pool's elements.
	int m_customCollisionAlgorithmMaxElementSize;
	/// Non-zero: EPA (btGjkEpaPenetrationDepthSolver); zero: btMinkowskiPenetrationDepthSolver.
	int m_useEpaPenetrationAlgorithm;

	/// 4096 manifolds, 4096 algorithms, EPA.
	btDefaultCollisionConstructionInfo()
	    : m_persistentManifoldPool(0),
	      m_collisionAlgorithmPool(0),
	      m_defaultMaxPersistentManifoldPoolSize(4096),
	      m_defaultMaxCollisionAlgorithmPoolSize(4096),
	      m_customCollisionAlgorithmMaxElementSize(0),
	      m_useEpaPenetrationAlgorithm(true)
	{
	}
};

/// Owns the algorithm factories, the penetration depth solver and (unless borrowed) the pools. Pairs:
/// sphere-sphere, sphere-box, sphere-triangle, box-box, convex-plane, convex-convex, convex-concave and
/// compound algorithms when available, the empty algorithm otherwise (see docs).
class btDefaultCollisionConfiguration : public btCollisionConfiguration
{
protected:
	/// Elements in the manifold pool.
	int m_persistentManifoldPoolSize;
	/// Manifold pool.
	btPoolAllocator* m_persistentManifoldPool;
	/// True when the manifold pool was made here.
	bool m_ownsPersistentManifoldPool;
	/// Algorithm pool.
	btPoolAllocator* m_collisionAlgorithmPool;
	/// True when the algorithm pool was made here.
	bool m_ownsCollisionAlgorithmPool;
	/// Penetration depth solver of convex-convex.
	btConvexPenetrationDepthSolver* m_pdSolver;

	/// Convex-convex (GJK/EPA, polyhedral clipping).
	btCollisionAlgorithmCreateFunc* m_convexConvexCreateFunc;
	/// Convex-concave (null until available).
	btCollisionAlgorithmCreateFunc* m_convexConcaveCreateFunc;
	/// Concave-convex (null until available).
	btCollisionAlgorithmCreateFunc* m_swappedConvexConcaveCreateFunc;
	/// Compound-any (null until available).
	btCollisionAlgorithmCreateFunc* m_compoundCreateFunc;
	/// Compound-compound (null until available).
	btCollisionAlgorithmCreateFunc* m_compoundCompoundCreateFunc;
	/// Any-compound (null until available).
	btCollisionAlgorithmCreateFunc* m_swappedCompoundCreateFunc;
	/// No contacts.
	btCollisionAlgorithmCreateFunc* m_emptyCreateFunc;
	/// Sphere-sphere.
	btCollisionAlgorithmCreateFunc* m_sphereSphereCF;
	/// Sphere-box.
	btCollisionAlgorithmCreateFunc* m_sphereBoxCF;
	/// Box-sphere.
	btCollisionAlgorithmCreateFunc* m_boxSphereCF;
	/// Box-box.
	btCollisionAlgorithmCreateFunc* m_boxBoxCF;
	/// Sphere-triangle.
	btCollisionAlgorithmCreateFunc* m_sphereTriangleCF;
	/// Triangle-sphere.
	btCollisionAlgorithmCreateFunc* m_triangleSphereCF;
	/// Plane-convex.
	btCollisionAlgorithmCreateFunc* m_planeConvexCF;
	/// Convex-plane.
	btCollisionAlgorithmCreateFunc* m_convexPlaneCF;

public:
	/// Makes the factories, the depth solver and the pools not given in constructionInfo. A pool size
	/// below 1 asserts and is raised to 1 in release.
	btDefaultCollisionConfiguration(
	    const btDefaultCollisionConstructionInfo& constructionInfo = btDefaultCollisionConstructionInfo());
	/// Frees the factories, the depth solver and the owned pools.
	~btDefaultCollisionConfiguration() override;

	/// Manifold pool.
	btPoolAllocator* getPersistentManifoldPool() override { return m_persistentManifoldPool; }
	/// Algorithm pool.
	btPoolAllocator* getCollisionAlgorithmPool() override { return m_collisionAlgorithmPool; }

	/// Factory for the contact algorithm of the pair of shape types (never null).
	btCollisionAlgorithmCreateFunc* getCollisionAlgorithmCreateFunc(int proxyType0, int proxyType1) override;
	/// Factory for closest-point queries: like getCollisionAlgorithmCreateFunc but box-box goes through
	/// convex-convex (never null).
	btCollisionAlgorithmCreateFunc* getClosestPointsAlgorithmCreateFunc(int proxyType0, int proxyType1) override;

	/// Perturbed GJK runs of convex-convex per frame, while the manifold has fewer points than
	/// minimumPointsPerturbationThreshold (Bullet's default is off: 0 iterations).
	void setConvexConvexMultipointIterations(int numPerturbationIterations = 3,
	                                         int minimumPointsPerturbationThreshold = 3);
	/// Tilted support queries of convex-plane for non-polyhedral shapes (default: 1 iteration, threshold 0,
	/// i.e. off; polyhedral shapes always get all their touching vertices).
	void setPlaneConvexMultipointIterations(int numPerturbationIterations = 3,
	                                        int minimumPointsPerturbationThreshold = 3);
};

#endif  // BT_DEFAULT_COLLISION_CONFIGURATION
