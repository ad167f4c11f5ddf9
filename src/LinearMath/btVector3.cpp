// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btVector3.h"

btVector3& btVector3::normalizeSlowPath(bool assertOnDegenerate)
{
	const btScalar largest = btMax(btMax(btFabs(m_floats[0]), btFabs(m_floats[1])), btFabs(m_floats[2]));
	const bool finiteAndNonZero = largest > btScalar(0) && largest <= SIMD_INFINITY;
	if (finiteAndNonZero)
	{
		// Rescaling by the largest component puts length2 in [1, 3]: no overflow, no underflow.
		if (!assertOnDegenerate && largest * largest * btScalar(3) < SIMD_EPSILON * SIMD_EPSILON)
		{
			// safeNormalize keeps Bullet's contract: lengths below SIMD_EPSILON give (1, 0, 0).
			setValue(btScalar(1), btScalar(0), btScalar(0));
			return *this;
		}
		btVector3 scaled(m_floats[0] / largest, m_floats[1] / largest, m_floats[2] / largest);
		const btScalar l2 = scaled.length2();
		if (l2 >= SIMD_EPSILON * SIMD_EPSILON)
		{
			*this = scaled / btSqrt(l2);
			return *this;
		}
	}
	if (assertOnDegenerate) btAssert(!"btVector3::normalize of a zero, NaN or infinite vector");
	setValue(btScalar(1), btScalar(0), btScalar(0));
	return *this;
}

namespace
{
// Scans for the extreme dot product. Ties keep the first index on both paths; NaN products are
// skipped, so any array with one non-NaN product gives a valid index.
template <bool FindMax>
long extremeDot(const btVector3& direction, const btVector3* array, long count, btScalar& dotOut)
{
	long bestIndex = -1;
	btScalar best = FindMax ? -SIMD_INFINITY : SIMD_INFINITY;
	long i = 0;
#ifdef BT_USE_SSE
	if (count >= 8)
	{
		// Four vectors per iteration, transposed to x, y and z lanes; each lane keeps its own best
		// value (NaN while it has none) and index, merged at the end with "lowest index wins ties".
		const __m128 dx = _mm_set1_ps(direction.x());
		const __m128 dy = _mm_set1_ps(direction.y());
		const __m128 dz = _mm_set1_ps(direction.z());
		__m128 laneBest = _mm_set1_ps(BT_NAN);
		__m128i laneIndex = _mm_set1_epi32(-1);
		__m128i currentIndex = _mm_setr_epi32(0, 1, 2, 3);
		const __m128i four = _mm_set1_epi32(4);
		const long vectorizedEnd = count & ~3L;
		for (; i < vectorizedEnd; i += 4)
		{
			__m128 v0 = array[i + 0].get128();
			__m128 v1 = array[i + 1].get128();
			__m128 v2 = array[i + 2].get128();
			__m128 v3 = array[i + 3].get128();
			_MM_TRANSPOSE4_PS(v0, v1, v2, v3);  // v0 = x lanes, v1 = y lanes, v2 = z lanes
			// (x*dx + y*dy) + z*dz, the order btVector3::dot uses.
			const __m128 dots = _mm_add_ps(_mm_add_ps(_mm_mul_ps(v0, dx), _mm_mul_ps(v1, dy)), _mm_mul_ps(v2, dz));
			const __m128 strictlyBetter = FindMax ? _mm_cmpgt_ps(dots, laneBest) : _mm_cmplt_ps(dots, laneBest);
			const __m128 laneEmpty = _mm_cmpunord_ps(laneBest, laneBest);
			const __m128 better = _mm_and_ps(_mm_or_ps(strictlyBetter, laneEmpty), _mm_cmpord_ps(dots, dots));
			laneBest = _mm_or_ps(_mm_and_ps(better, dots), _mm_andnot_ps(better, laneBest));
			const __m128i betterMask = _mm_castps_si128(better);
			laneIndex = _mm_or_si128(_mm_and_si128(betterMask, currentIndex), _mm_andnot_si128(betterMask, laneIndex));
			currentIndex = _mm_add_epi32(currentIndex, four);
		}
		alignas(16) float values[4];
		alignas(16) int indices[4];
		_mm_store_ps(values, laneBest);
		_mm_store_si128(reinterpret_cast<__m128i*>(indices), laneIndex);
		for (int lane = 0; lane < 4; ++lane)
		{
			if (indices[lane] < 0) continue;
			const bool wins = FindMax ? values[lane] > best : values[lane] < best;
			const bool tiesEarlier = values[lane] == best && indices[lane] < bestIndex;
			if (bestIndex < 0 || wins || tiesEarlier)
			{
				best = values[lane];
				bestIndex = indices[lane];
			}
		}
	}
#endif
	for (; i < count; ++i)
	{
		const btScalar d = direction.dot(array[i]);
		if (d != d) continue;
		if (bestIndex < 0 || (FindMax ? d > best : d < best))
		{
			best = d;
			bestIndex = i;
		}
	}
	dotOut = best;
	return bestIndex;
}
}  // namespace

long btVector3::maxDot(const btVector3* array, long arrayCount, btScalar& dotOut) const
{
	return extremeDot<true>(*this, array, arrayCount, dotOut);
}

long btVector3::minDot(const btVector3* array, long arrayCount, btScalar& dotOut) const
{
	return extremeDot<false>(*this, array, arrayCount, dotOut);
}
