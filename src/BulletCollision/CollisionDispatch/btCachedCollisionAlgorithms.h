// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CACHED_COLLISION_ALGORITHMS_H
#define CALIBER_CACHED_COLLISION_ALGORITHMS_H

// The algorithms the default factories make: Bullet's algorithms with a contact cache
// (btPairPoseCache.h). Subclasses, so that Bullet's classes keep Bullet's members; a program that
// makes btBoxBoxCollisionAlgorithm itself gets the algorithm without the cache.

#include "BulletCollision/CollisionDispatch/btBoxBoxCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btPairPoseCache.h"

namespace caliber
{
class CachedBoxBoxAlgorithm : public btBoxBoxCollisionAlgorithm
{
public:
	using btBoxBoxCollisionAlgorithm::btBoxBoxCollisionAlgorithm;

	/// Refreshes the manifold when the cache covers the pair's motion; otherwise detects and remembers
	/// the pose.
	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;

	PairPoseCache& poseCache() { return m_poseCache; }

private:
	PairPoseCache m_poseCache;
};

/// The cache is used for pairs of polyhedra (shapes with initializePolyhedralFeatures), whose manifold
/// the clipping fills in one detection; pairs that build their manifold over several steps (one GJK point
/// per step) are detected every step.
class CachedConvexConvexAlgorithm : public btConvexConvexAlgorithm
{
public:
	using btConvexConvexAlgorithm::btConvexConvexAlgorithm;

	void processCollision(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap,
	                      const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut) override;

	PairPoseCache& poseCache() { return m_poseCache; }

private:
	PairPoseCache m_poseCache;
};
}  // namespace caliber

#endif  // CALIBER_CACHED_COLLISION_ALGORITHMS_H
