// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_MANIFOLD_ALLOCATION_H
#define CALIBER_MANIFOLD_ALLOCATION_H

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btPoolAllocator.h"

namespace caliber
{
/// The breaking and processing thresholds a new manifold of two objects gets (the serial and the
/// multithreaded dispatcher make manifolds alike).
struct ManifoldThresholds
{
	btScalar breaking;
	btScalar processing;
};

inline ManifoldThresholds manifoldThresholds(const btCollisionObject* b0, const btCollisionObject* b1,
                                             bool relativeBreakingThreshold)
{
	ManifoldThresholds thresholds = {gContactBreakingThreshold, BT_LARGE_FLOAT};
	if (!b0 || !b1) return thresholds;
	// A pair keeps points as long as the smaller object tolerates: a large shape's relative threshold
	// would let a small one's points drift too far.
	const btCollisionShape* shape0 = b0->getCollisionShape();
	const btCollisionShape* shape1 = b1->getCollisionShape();
	if (relativeBreakingThreshold && shape0 && shape1)
	{
		thresholds.breaking = btMin(shape0->getContactBreakingThreshold(gContactBreakingThreshold),
		                            shape1->getContactBreakingThreshold(gContactBreakingThreshold));
	}
	thresholds.processing = btMin(b0->getContactProcessingThreshold(), b1->getContactProcessingThreshold());
	return thresholds;
}

/// Memory for one manifold: from the pool while it has room (the pool locks itself, so threads may
/// share it), else from the heap unless heapAllowed is false (then 0).
inline void* allocateManifoldMemory(btPoolAllocator* pool, bool heapAllowed)
{
	void* memory = pool ? pool->allocate(int(sizeof(btPersistentManifold))) : 0;
	if (memory) return memory;
	btAssert(heapAllowed && "manifold pool exhausted: raise m_defaultMaxPersistentManifoldPoolSize");
	return heapAllowed ? btAlignedAlloc(sizeof(btPersistentManifold), 16) : 0;
}
}  // namespace caliber

#endif  // CALIBER_MANIFOLD_ALLOCATION_H
