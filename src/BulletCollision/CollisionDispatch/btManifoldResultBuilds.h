// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_MANIFOLD_RESULT_BUILDS_H
#define CALIBER_MANIFOLD_RESULT_BUILDS_H

// btManifoldResult::addContactPoint runs an AVX2 build on processors that have it (btCpuFeatures.h). For
// tests, both builds by name.

#include "LinearMath/btVector3.h"

class btManifoldResult;

namespace caliber
{
/// Whether addContactPoint runs the AVX2 build on this processor.
bool addContactPointUsesAvx2();
/// addContactPoint in the AVX2 build when avx2 and the processor has it, otherwise in the baseline build.
void addContactPointIn(btManifoldResult& result, const btVector3& normalOnBInWorld, const btVector3& pointInWorld,
                       btScalar depth, bool avx2);
}  // namespace caliber

#endif  // CALIBER_MANIFOLD_RESULT_BUILDS_H
