// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SIMD_BATCH_H
#define CALIBER_SIMD_BATCH_H

// Several vector operations at once, with the bits of doing them one by one: four dot products
// whose sums run side by side in the lanes of one register, and transforms of many points by one
// pose with its basis turned into columns once. Each lane performs the same operations in the same
// order as btVector3::dot ((x*x' + y*y') + z*z') and btMatrix3x3 * btVector3, so results are
// bit-identical to the one-at-a-time forms on both code paths.

#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
/// Four dot products a_k . b_k, each summed (x + y) + z like btVector3::dot, kept side by side.
struct Dot4
{
#ifdef BT_USE_SSE
	__m128 lanes;
#else
	btScalar d[4];
#endif
	/// (d0 + d1) + (d2 + d3).
	SIMD_FORCE_INLINE btScalar sumOfPairs() const
	{
#ifdef BT_USE_SSE
		// (d0 + d1, d1 + d0, d2 + d3, d3 + d2); d1 + d0 has the bits of d0 + d1.
		const __m128 pairs = _mm_add_ps(lanes, _mm_shuffle_ps(lanes, lanes, CALIBER_SHUFFLE(1, 0, 3, 2)));
		return _mm_cvtss_f32(_mm_add_ss(pairs, _mm_movehl_ps(pairs, pairs)));
#else
		return (d[0] + d[1]) + (d[2] + d[3]);
#endif
	}
	/// ((d0 + d1) + d2) + d3.
	SIMD_FORCE_INLINE btScalar sumInOrder() const
	{
#ifdef BT_USE_SSE
		__m128 sum = _mm_add_ss(lanes, CALIBER_SPLAT(lanes, 1));
		sum = _mm_add_ss(sum, _mm_movehl_ps(lanes, lanes));
		return _mm_cvtss_f32(_mm_add_ss(sum, CALIBER_SPLAT(lanes, 3)));
#else
		return ((d[0] + d[1]) + d[2]) + d[3];
#endif
	}
};

SIMD_FORCE_INLINE Dot4 dot4(const btVector3& a0, const btVector3& b0, const btVector3& a1, const btVector3& b1,
                            const btVector3& a2, const btVector3& b2, const btVector3& a3, const btVector3& b3)
{
	Dot4 out;
#ifdef BT_USE_SSE
	__m128 p0 = _mm_mul_ps(a0.get128(), b0.get128());
	__m128 p1 = _mm_mul_ps(a1.get128(), b1.get128());
	__m128 p2 = _mm_mul_ps(a2.get128(), b2.get128());
	__m128 p3 = _mm_mul_ps(a3.get128(), b3.get128());
	// After the transpose p0 holds the four x products, p1 the y and p2 the z products.
	_MM_TRANSPOSE4_PS(p0, p1, p2, p3);
	out.lanes = _mm_add_ps(_mm_add_ps(p0, p1), p2);
#else
	out.d[0] = a0.dot(b0);
	out.d[1] = a1.dot(b1);
	out.d[2] = a2.dot(b2);
	out.d[3] = a3.dot(b3);
#endif
	return out;
}

/// A pose ready to transform many points: basis * p + origin with btTransform's bits.
struct ColumnTransform
{
#ifdef BT_USE_SSE
	__m128 column[3];
	__m128 origin;

	explicit ColumnTransform(const btTransform& t)
	{
		const btMatrix3x3& m = t.getBasis();
		__m128 r0 = m[0].get128(), r1 = m[1].get128(), r2 = m[2].get128(), r3 = _mm_setzero_ps();
		_MM_TRANSPOSE4_PS(r0, r1, r2, r3);
		column[0] = r0;
		column[1] = r1;
		column[2] = r2;
		origin = t.getOrigin().get128();
	}
	SIMD_FORCE_INLINE btVector3 operator()(const btVector3& p) const
	{
		// Lane i: (m[i][0] x + m[i][1] y) + m[i][2] z, as btMatrix3x3 * btVector3 sums it. That product
		// leaves +0 in w, to which the origin's w is added; clearing w before the add does the same.
		const __m128 v = p.get128();
		const __m128 x = _mm_mul_ps(column[0], CALIBER_SPLAT(v, 0));
		const __m128 y = _mm_mul_ps(column[1], CALIBER_SPLAT(v, 1));
		const __m128 z = _mm_mul_ps(column[2], CALIBER_SPLAT(v, 2));
		return btVector3(_mm_add_ps(CALIBER_CLEAR_W(_mm_add_ps(_mm_add_ps(x, y), z)), origin));
	}
#else
	const btTransform& pose;

	explicit ColumnTransform(const btTransform& t) : pose(t) {}
	SIMD_FORCE_INLINE btVector3 operator()(const btVector3& p) const { return pose(p); }
#endif
};
}  // namespace caliber

#endif  // CALIBER_SIMD_BATCH_H
