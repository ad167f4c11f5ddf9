// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_PERSISTENT_MANIFOLD_BUILDS_H
#define CALIBER_PERSISTENT_MANIFOLD_BUILDS_H

// btPersistentManifold::refreshContactPoints' first pass (world points, distance, age, which points stay)
// runs an AVX2 build on processors that have it (btCpuFeatures.h). For tests, both builds by name.

#include "LinearMath/btTransform.h"

class btManifoldPoint;

namespace caliber
{
/// Whether refreshContactPoints runs the AVX2 build of its first pass on this processor.
bool refreshContactPointsUsesAvx2();
/// The first pass over count points (at most MANIFOLD_CACHE_SIZE), in the AVX2 build when avx2 and the processor has
/// it, otherwise in the baseline build: sets each point's world points, distance and lifetime as refreshContactPoints
/// does, and returns which points stay (bit i for point i), or -1 when a transform is not finite (nothing is changed
/// then).
int refreshWorldPointsIn(btManifoldPoint* points, int count, const btTransform& trA, const btTransform& trB,
                         btScalar threshold, bool avx2);
}  // namespace caliber

#endif  // CALIBER_PERSISTENT_MANIFOLD_BUILDS_H
