// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_ALGORITHM_UTIL_H
#define CALIBER_ALGORITHM_UTIL_H

// Internal helpers shared by the collision algorithms: input checks and manifold upkeep.

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"

// True when both wrappers place their shapes with finite transforms. A non-finite transform asserts; in
// release the algorithm then reports nothing (and empties a manifold it owns) so that no NaN reaches
// the manifold or the solver.
inline bool caliberPairIsUsable(const btCollisionObjectWrapper* body0Wrap, const btCollisionObjectWrapper* body1Wrap)
{
	const bool usable = body0Wrap && body1Wrap && body0Wrap->getCollisionShape() && body1Wrap->getCollisionShape() &&
	                    caliberIsFinite(body0Wrap->getWorldTransform()) &&
	                    caliberIsFinite(body1Wrap->getWorldTransform());
	btAssert(usable && "collision algorithm: null shape or non-finite transform");
	return usable;
}

// Single-point algorithms (sphere-sphere, sphere-box, sphere-triangle) know the whole contact each frame.
// After adding the new point, any older point that the new one did not replace is stale: remove it so
// the manifold holds exactly the current contact (a replaced point keeps its warm-start impulses).
inline void caliberKeepOnlyNewestPoint(btPersistentManifold* manifold, int countBeforeAdd)
{
	if (manifold->getNumContacts() <= countBeforeAdd) return;  // the new point replaced an old one (or none)
	// The new point is last; removing from the highest old index down moves it forwards each time.
	for (int i = countBeforeAdd - 1; i >= 0; --i) manifold->removeContactPoint(i);
}

#endif  // CALIBER_ALGORITHM_UTIL_H
