// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btBoxBoxDetector.h"

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionDispatch/btBoxBoxDetectorBuilds.h"
#include "LinearMath/btCpuFeatures.h"

namespace
{
namespace baseline
{
#include "BulletCollision/CollisionDispatch/btBoxBoxDetectorBody.h"
}  // namespace baseline
}  // namespace

#if CALIBER_AVX2_BUILDS
#pragma GCC push_options
#pragma GCC target("avx2")
namespace
{
namespace avx2
{
#include "BulletCollision/CollisionDispatch/btBoxBoxDetectorBody.h"
}  // namespace avx2
}  // namespace
#pragma GCC pop_options

namespace
{
// Whether this processor runs the AVX2 build (decided at load; false, so the baseline, before that).
const bool g_avx2BoxBox = caliber::detectAvx2();
}  // namespace
#endif

btBoxBoxDetector::btBoxBoxDetector(const btBoxShape* box1, const btBoxShape* box2) : m_box1(box1), m_box2(box2) {}

void btBoxBoxDetector::getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw* /*debugDraw*/,
                                        bool swapResults)
{
#if CALIBER_AVX2_BUILDS
	if (g_avx2BoxBox)
	{
		avx2::closestPoints(m_box1, m_box2, input, output, swapResults);
		return;
	}
#endif
	baseline::closestPoints(m_box1, m_box2, input, output, swapResults);
}

void caliber::boxBoxClosestPointsIn(const btBoxShape* box1, const btBoxShape* box2,
                                    const btDiscreteCollisionDetectorInterface::ClosestPointInput& input,
                                    btDiscreteCollisionDetectorInterface::Result& output, bool swapResults, bool avx2)
{
#if CALIBER_AVX2_BUILDS
	if (avx2 && g_avx2BoxBox)
	{
		avx2::closestPoints(box1, box2, input, output, swapResults);
		return;
	}
#else
	(void)avx2;
#endif
	baseline::closestPoints(box1, box2, input, output, swapResults);
}

bool caliber::boxBoxUsesAvx2()
{
#if CALIBER_AVX2_BUILDS
	return g_avx2BoxBox;
#else
	return false;
#endif
}
