// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_BOX_BOX_DETECTOR_BUILDS_H
#define CALIBER_BOX_BOX_DETECTOR_BUILDS_H

// btBoxBoxDetector::getClosestPoints runs an AVX2 build on processors that have it (btCpuFeatures.h,
// btBoxBoxDetectorBody.h). For tests, both builds by name.

#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"

class btBoxShape;

namespace caliber
{
/// Whether getClosestPoints runs the AVX2 build on this processor.
bool boxBoxUsesAvx2();
/// getClosestPoints in the AVX2 build when avx2 and the processor has it, otherwise in the baseline build.
void boxBoxClosestPointsIn(const btBoxShape* box1, const btBoxShape* box2,
                           const btDiscreteCollisionDetectorInterface::ClosestPointInput& input,
                           btDiscreteCollisionDetectorInterface::Result& output, bool swapResults, bool avx2);
}  // namespace caliber

#endif  // CALIBER_BOX_BOX_DETECTOR_BUILDS_H
