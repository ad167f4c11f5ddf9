// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_RAY_SLAB_TEST_H
#define CALIBER_RAY_SLAB_TEST_H

// Internal: the last half of the SSE slab test shared by the nearest-first ray walks of btDbvtBroadphase
// (btDbvtRayWalk.h) and of a BVH mesh's tree (btQuantizedBvhRayWalk.cpp). Each walk computes, lane by lane
// (x, y, z; lane w is ignored), the ray parameters tLow and tHigh where the ray crosses a box's low and high
// planes in its own frame; this picks the near and far plane of each axis by the direction's sign, clamps
// to [0, exitBound] and reduces over the three axes, with btRayAabb2's operations and order.

#include "LinearMath/btVector3.h"

#ifdef BT_USE_SSE
namespace caliber
{
/// All ones in the lanes x, y, z whose flag is set, zero elsewhere (lane w zero).
SIMD_FORCE_INLINE __m128 raySlabNegativeMask(bool x, bool y, bool z)
{
	return _mm_castsi128_ps(_mm_setr_epi32(x ? -1 : 0, y ? -1 : 0, z ? -1 : 0, 0));
}

/// True when the largest entry over x, y, z (each the near plane's t, at least 0) is at most the smallest exit
/// (each the far plane's t, at most exitBound); enter is that entry. The near plane is the low one unless
/// negativeMask is set in the lane. maxps and minps return their second operand when either is NaN, so a NaN
/// plane (0 * inf) leaves the bound as btRayAabb2's comparisons do.
SIMD_FORCE_INLINE bool raySlabHits(__m128 tLow, __m128 tHigh, __m128 negativeMask, btScalar exitBound, btScalar& enter)
{
	const __m128 tNear = _mm_or_ps(_mm_and_ps(negativeMask, tHigh), _mm_andnot_ps(negativeMask, tLow));
	const __m128 tFar = _mm_or_ps(_mm_and_ps(negativeMask, tLow), _mm_andnot_ps(negativeMask, tHigh));
	const __m128 entries = _mm_max_ps(tNear, _mm_setzero_ps());
	const __m128 exits = _mm_min_ps(tFar, _mm_set1_ps(exitBound));
	const __m128 enterXYZ = _mm_max_ss(_mm_max_ss(entries, CALIBER_SPLAT(entries, 1)), CALIBER_SPLAT(entries, 2));
	const __m128 exitXYZ = _mm_min_ss(_mm_min_ss(exits, CALIBER_SPLAT(exits, 1)), CALIBER_SPLAT(exits, 2));
	enter = _mm_cvtss_f32(enterXYZ);
	return _mm_comile_ss(enterXYZ, exitXYZ) != 0;
}
}  // namespace caliber
#endif  // BT_USE_SSE

#endif  // CALIBER_RAY_SLAB_TEST_H
