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

/// The three-axis reductions of two boxes' slab entries and exits, side by side: box A's entry is the
/// maximum of entriesA's x, y and z lanes and its exit the minimum of exitsA's, likewise for B, and a box is
/// hit when its entry is at most its exit. The w lanes are not read.
SIMD_FORCE_INLINE void reduceSlabsOfTwoBoxes(__m128 entriesA, __m128 exitsA, __m128 entriesB, __m128 exitsB,
                                             btScalar& enterA, btScalar& enterB, bool& hitA, bool& hitB)
{
	// Lanes A.x, B.x, A.y, B.y and A.z, B.z, A.w, B.w: lanes 0 and 1 of the result reduce x, z, then y.
	const __m128 entriesXY = _mm_unpacklo_ps(entriesA, entriesB);
	const __m128 entriesZW = _mm_unpackhi_ps(entriesA, entriesB);
	const __m128 exitsXY = _mm_unpacklo_ps(exitsA, exitsB);
	const __m128 exitsZW = _mm_unpackhi_ps(exitsA, exitsB);
	const __m128 enter = _mm_max_ps(_mm_max_ps(entriesXY, entriesZW), _mm_movehl_ps(entriesXY, entriesXY));
	const __m128 exit = _mm_min_ps(_mm_min_ps(exitsXY, exitsZW), _mm_movehl_ps(exitsXY, exitsXY));
	const int hits = _mm_movemask_ps(_mm_cmple_ps(enter, exit));
	enterA = _mm_cvtss_f32(enter);
	enterB = _mm_cvtss_f32(CALIBER_SPLAT(enter, 1));
	hitA = (hits & 1) != 0;
	hitB = (hits & 2) != 0;
}

/// raySlabHits of two boxes A and B at once, the three-axis reductions done side by side. The entries are
/// never NaN nor -0 (maxps with +0 as its second operand returns +0 for both), so their maximum does not depend
/// on the order the axes are taken in; the exits are NaN only when exitBound is (then in every lane, and
/// both tests fail), else their minimum may differ only in the sign of a zero, which the comparison does not
/// see. So each answer and entry is raySlabHits's, bit for bit.
SIMD_FORCE_INLINE void raySlabHitsBoth(__m128 tLowA, __m128 tHighA, __m128 tLowB, __m128 tHighB, __m128 negativeMask,
                                       btScalar exitBound, btScalar& enterA, btScalar& enterB, bool& hitA, bool& hitB)
{
	const __m128 bound = _mm_set1_ps(exitBound);
	const __m128 zero = _mm_setzero_ps();
	const __m128 nearA = _mm_or_ps(_mm_and_ps(negativeMask, tHighA), _mm_andnot_ps(negativeMask, tLowA));
	const __m128 farA = _mm_or_ps(_mm_and_ps(negativeMask, tLowA), _mm_andnot_ps(negativeMask, tHighA));
	const __m128 nearB = _mm_or_ps(_mm_and_ps(negativeMask, tHighB), _mm_andnot_ps(negativeMask, tLowB));
	const __m128 farB = _mm_or_ps(_mm_and_ps(negativeMask, tLowB), _mm_andnot_ps(negativeMask, tHighB));
	reduceSlabsOfTwoBoxes(_mm_max_ps(nearA, zero), _mm_min_ps(farA, bound), _mm_max_ps(nearB, zero),
	                      _mm_min_ps(farB, bound), enterA, enterB, hitA, hitB);
}
}  // namespace caliber
#endif  // BT_USE_SSE

#endif  // CALIBER_RAY_SLAB_TEST_H
