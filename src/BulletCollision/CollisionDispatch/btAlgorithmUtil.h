// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ALGORITHM_UTIL_H
#define CALIBER_ALGORITHM_UTIL_H

// Internal helpers shared by the collision algorithms: input checks and manifold upkeep.

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"

namespace caliber
{

// True when both wrappers place their shapes with finite transforms. A non-finite transform asserts; in
// release the algorithm then reports nothing (and empties a manifold it owns) so that no NaN reaches
// the manifold or the solver.
inline bool pairIsUsable(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap)
{
	const bool usable = body0Wrap && body1Wrap && body0Wrap->getCollisionShape() && body1Wrap->getCollisionShape() &&
	                    caliber::isFinite(body0Wrap->getWorldTransform()) &&
	                    caliber::isFinite(body1Wrap->getWorldTransform());
	btAssert(usable && "collision algorithm: null shape or non-finite transform");
	return usable;
}

// Single-point algorithms (sphere-sphere, sphere-box, sphere-triangle) know the whole contact each frame.
// After adding the new point, any older point that the new one did not replace is stale: remove it so
// the manifold holds exactly the current contact (a replaced point keeps its warm-start impulses).
inline void keepOnlyNewestPoint(btPersistentManifold* manifold, int countBeforeAdd)
{
	if (manifold->getNumContacts() <= countBeforeAdd) return;  // the new point replaced an old one (or none)
	// The new point is last; removing from the highest old index down moves it forwards each time.
	for (int i = countBeforeAdd - 1; i >= 0; --i) manifold->removeContactPoint(i);
}

// Algorithms that find the whole contact patch each frame (box-box, polyhedral clipping) call this before
// adding the new points: points whose two halves have moved apart by more than the breaking threshold
// (along the normal or across it) since last frame are dropped first. Otherwise a body that slides
// further than the threshold per step finds its manifold full of last frame's points, and the area rule
// would keep a lopsided mix of old and new ones. Lifetimes and callbacks are left to the
// refreshContactPoints that follows the detection.
inline void dropStalePoints(btPersistentManifold* manifold, const btCollisionObjectWrapper* body0Wrap,
                            const btCollisionObjectWrapper* body1Wrap)
{
	const bool inOrder = manifold->getBody0() == body0Wrap->getCollisionObject();
	const btTransform& trA = inOrder ? body0Wrap->getWorldTransform() : body1Wrap->getWorldTransform();
	const btTransform& trB = inOrder ? body1Wrap->getWorldTransform() : body0Wrap->getWorldTransform();
	const btScalar threshold = manifold->getContactBreakingThreshold();
	for (int i = manifold->getNumContacts() - 1; i >= 0; --i)
	{
		const btManifoldPoint& point = manifold->getContactPoint(i);
		const btVector3 onA = trA(point.m_localPointA);
		const btVector3 onB = trB(point.m_localPointB);
		const btScalar distance = (onA - onB).dot(point.m_normalWorldOnB);
		const btVector3 drift = (onA - point.m_normalWorldOnB * distance) - onB;
		if (distance > threshold || drift.length2() > threshold * threshold) manifold->removeContactPoint(i);
	}
}

}  // namespace caliber

#endif  // CALIBER_ALGORITHM_UTIL_H
