// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The wide sweep of coloured contact batches (see btWideContactRows.h for the layout and why the bits
// are those of the row-by-row sweep). The sweeps themselves are in btWideContactSweep.h, compiled once
// for four lanes (SSE2, or plain arrays in double precision and without SIMD) and once for eight (AVX2,
// in functions compiled for it and called only when the processor has it).
#include "BulletDynamics/ConstraintSolver/btWideContactRows.h"

#include <string.h>

#include <atomic>

#include "BulletDynamics/ConstraintSolver/btSolverRowKernels.h"
#include "LinearMath/btScratchArray.h"
#include "LinearMath/btThreads.h"

#if defined(BT_USE_SSE) && (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
#define CALIBER_WIDE_EIGHT_LANES 1
#include <immintrin.h>
#else
#define CALIBER_WIDE_EIGHT_LANES 0
#endif

namespace
{
std::atomic<bool> g_wideEnabled{true};
std::atomic<int> g_wideLanes{0};  // 0: automatic

// The source of a padding lane: a row of zeros, whose second linear direction is its first one negated
// (-0) so that the negation test needs no exception for padding (the blocks do not keep that direction).
const btSolverConstraint& zeroRow()
{
	static const btSolverConstraint row = [] {
		btSolverConstraint r;
		memset(static_cast<void*>(&r), 0, sizeof(r));
		r.m_contactNormal2.setValue(-btScalar(0), -btScalar(0), -btScalar(0));
		return r;
	}();
	return row;
}

// One vector field of four rows into lanes [base, base + 4) of its structure-of-arrays place.
SIMD_FORCE_INLINE void copyField4(const btSolverConstraint* const* rows, size_t offset, btScalar* x, btScalar* y,
                                  btScalar* z)
{
#if defined(BT_USE_SSE)
	__m128 r0 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[0]) + offset));
	__m128 r1 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[1]) + offset));
	__m128 r2 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[2]) + offset));
	__m128 r3 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[3]) + offset));
	_MM_TRANSPOSE4_PS(r0, r1, r2, r3);
	_mm_store_ps(x, r0);
	_mm_store_ps(y, r1);
	_mm_store_ps(z, r2);
#else
	for (int k = 0; k < 4; ++k)
	{
		const btScalar* v = reinterpret_cast<const btScalar*>(reinterpret_cast<const char*>(rows[k]) + offset);
		x[k] = v[0];
		y[k] = v[1];
		z[k] = v[2];
	}
#endif
}

template <int W>
SIMD_FORCE_INLINE void copyField(const btSolverConstraint* const* rows, size_t offset, btScalar (&to)[3][W])
{
	for (int base = 0; base < W; base += 4) copyField4(rows + base, offset, &to[0][base], &to[1][base], &to[2][base]);
}

// Whether the second linear direction of each of n rows is its first one negated, bit for bit (as every
// contact and friction row Caliber makes has it, and zeroRow): the blocks keep only the first.
SIMD_FORCE_INLINE bool secondNormalsAreNegated(const btSolverConstraint* const* rows, int n)
{
#if defined(BT_USE_SSE)
	const __m128 sign = _mm_set1_ps(-0.0f);
	__m128i same = _mm_set1_epi32(-1);
	for (int k = 0; k < n; ++k)
	{
		const __m128 negated = _mm_xor_ps(_mm_load_ps(rows[k]->m_contactNormal1.m_floats), sign);
		same = _mm_and_si128(same, _mm_cmpeq_epi32(_mm_castps_si128(negated),
		                                           _mm_castps_si128(_mm_load_ps(rows[k]->m_contactNormal2.m_floats))));
	}
	return (_mm_movemask_ps(_mm_castsi128_ps(same)) & 7) == 7;  // x, y and z; w is not a direction
#else
	for (int k = 0; k < n; ++k)
		for (int c = 0; c < 3; ++c)
		{
			const btScalar negated = -rows[k]->m_contactNormal1[c];
			if (memcmp(&negated, &rows[k]->m_contactNormal2[c], sizeof(btScalar)) != 0) return false;
		}
	return true;
#endif
}

#if defined(BT_USE_SSE)
// The row's scalars lie in two aligned 16-byte lines, (push impulse, impulse, friction, 1 / diagonal) and
// (rhs, cfm, lower, upper): rows' lines transposed give lanes of each at once.
#define CALIBER_ROW_SCALAR_AT(field, bytes) \
	(offsetof(btSolverConstraint, field) == offsetof(btSolverConstraint, m_appliedPushImpulse) + (bytes))
static_assert(sizeof(btSolverConstraint) % 16 == 0 && offsetof(btSolverConstraint, m_appliedPushImpulse) % 16 == 0 &&
                  CALIBER_ROW_SCALAR_AT(m_appliedImpulse, 4) && CALIBER_ROW_SCALAR_AT(m_friction, 8) &&
                  CALIBER_ROW_SCALAR_AT(m_jacDiagABInv, 12) && CALIBER_ROW_SCALAR_AT(m_rhs, 16) &&
                  CALIBER_ROW_SCALAR_AT(m_cfm, 20) && CALIBER_ROW_SCALAR_AT(m_lowerLimit, 24) &&
                  CALIBER_ROW_SCALAR_AT(m_upperLimit, 28),
              "btSolverConstraint's scalars moved: copyRows reads them as two 16-byte lines");
#undef CALIBER_ROW_SCALAR_AT
#endif

// W rows (padding lanes point at zeroRow) into a block, all but its row indices; false when a row's second
// linear direction is not its first one negated (the block cannot hold it).
template <int W>
bool copyRows(caliber::WideRowBlockT<W>& block, const btSolverConstraint* const* rows)
{
	const bool negated = secondNormalsAreNegated(rows, W);
	copyField<W>(rows, offsetof(btSolverConstraint, m_contactNormal1), block.normal1);
	copyField<W>(rows, offsetof(btSolverConstraint, m_relpos1CrossNormal), block.relpos1CrossNormal);
	copyField<W>(rows, offsetof(btSolverConstraint, m_relpos2CrossNormal), block.relpos2CrossNormal);
	copyField<W>(rows, offsetof(btSolverConstraint, m_angularComponentA), block.angularA);
	copyField<W>(rows, offsetof(btSolverConstraint, m_angularComponentB), block.angularB);
#if defined(BT_USE_SSE)
	for (int base = 0; base < W; base += 4)
	{
		__m128 l0[4], l1[4];
		for (int k = 0; k < 4; ++k)
		{
			const float* line = &rows[base + k]->m_appliedPushImpulse;
			l0[k] = _mm_load_ps(line);
			l1[k] = _mm_load_ps(line + 4);
		}
		_MM_TRANSPOSE4_PS(l0[0], l0[1], l0[2], l0[3]);
		_MM_TRANSPOSE4_PS(l1[0], l1[1], l1[2], l1[3]);
		_mm_store_ps(block.applied + base, l0[1]);
		_mm_store_ps(block.friction + base, l0[2]);
		_mm_store_ps(block.jacDiagABInv + base, l0[3]);
		_mm_store_ps(block.rhs + base, l1[0]);
		_mm_store_ps(block.cfm + base, l1[1]);
		_mm_store_ps(block.lower + base, l1[2]);
		_mm_store_ps(block.upper + base, l1[3]);
	}
#else
	for (int k = 0; k < W; ++k)
	{
		const btSolverConstraint& row = *rows[k];
		block.rhs[k] = row.m_rhs;
		block.cfm[k] = row.m_cfm;
		block.jacDiagABInv[k] = row.m_jacDiagABInv;
		block.lower[k] = row.m_lowerLimit;
		block.upper[k] = row.m_upperLimit;
		block.friction[k] = row.m_friction;
		block.applied[k] = row.m_appliedImpulse;
	}
#endif
	return negated;
}
}  // namespace

// ---- Four lanes ---------------------------------------------------------------------------------
namespace
{
namespace lanes4
{
const int kLanes = 4;

// kLanes scalars and the operations the kernel needs, each the same IEEE operation per lane as the
// scalar kernel's. SSE2 registers in single precision, plain arrays otherwise.
#if defined(BT_USE_SSE)
struct Lanes
{
	__m128 v;
};
struct Mask
{
	__m128 v;
};
SIMD_FORCE_INLINE Lanes load(const btScalar* p) { return Lanes{_mm_load_ps(p)}; }
SIMD_FORCE_INLINE void store(btScalar* p, Lanes a) { _mm_store_ps(p, a.v); }
SIMD_FORCE_INLINE Lanes zero() { return Lanes{_mm_setzero_ps()}; }
SIMD_FORCE_INLINE Lanes operator+(Lanes a, Lanes b) { return Lanes{_mm_add_ps(a.v, b.v)}; }
SIMD_FORCE_INLINE Lanes operator-(Lanes a, Lanes b) { return Lanes{_mm_sub_ps(a.v, b.v)}; }
SIMD_FORCE_INLINE Lanes operator*(Lanes a, Lanes b) { return Lanes{_mm_mul_ps(a.v, b.v)}; }
SIMD_FORCE_INLINE Lanes negate(Lanes a) { return Lanes{_mm_xor_ps(a.v, _mm_set1_ps(-0.0f))}; }
// b < a ? b : a and a < b ? b : a, as btMinBranchless and btMaxBranchless (minps and maxps return their
// second operand unless the first wins the comparison).
SIMD_FORCE_INLINE Lanes minBranchless(Lanes a, Lanes b) { return Lanes{_mm_min_ps(b.v, a.v)}; }
SIMD_FORCE_INLINE Lanes maxBranchless(Lanes a, Lanes b) { return Lanes{_mm_max_ps(b.v, a.v)}; }
// Lanes where a friction row is skipped: no normal impulse and no impulse of its own.
SIMD_FORCE_INLINE Mask frictionSkipped(Lanes normal, Lanes applied)
{
	const __m128 noNormal = _mm_cmpnlt_ps(_mm_setzero_ps(), normal.v);  // !(normal > 0), NaN included
	return Mask{_mm_and_ps(noNormal, _mm_cmpeq_ps(applied.v, _mm_setzero_ps()))};
}
SIMD_FORCE_INLINE bool allSet(Mask m) { return _mm_movemask_ps(m.v) == 0xf; }
SIMD_FORCE_INLINE Lanes select(Mask m, Lanes ifSet, Lanes ifClear)
{
	return Lanes{_mm_or_ps(_mm_and_ps(m.v, ifSet.v), _mm_andnot_ps(m.v, ifClear.v))};
}
SIMD_FORCE_INLINE btScalar horizontalSum(Lanes a)
{
	btScalar lanes[kLanes];
	_mm_storeu_ps(lanes, a.v);
	return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
}
SIMD_FORCE_INLINE void gatherVectors(const btSolverBody* bodies, const int* index, size_t offset, Lanes* xyz, btScalar* w)
{
	const char* base = reinterpret_cast<const char*>(bodies);
	__m128 r0 = _mm_load_ps(reinterpret_cast<const float*>(base + size_t(index[0]) * sizeof(btSolverBody) + offset));
	__m128 r1 = _mm_load_ps(reinterpret_cast<const float*>(base + size_t(index[1]) * sizeof(btSolverBody) + offset));
	__m128 r2 = _mm_load_ps(reinterpret_cast<const float*>(base + size_t(index[2]) * sizeof(btSolverBody) + offset));
	__m128 r3 = _mm_load_ps(reinterpret_cast<const float*>(base + size_t(index[3]) * sizeof(btSolverBody) + offset));
	_MM_TRANSPOSE4_PS(r0, r1, r2, r3);
	xyz[0].v = r0;
	xyz[1].v = r1;
	xyz[2].v = r2;
	_mm_store_ps(w, r3);
}
SIMD_FORCE_INLINE void scatterVectors(btSolverBody* bodies, const int* index, size_t offset, const Lanes* xyz,
                                      const btScalar* w)
{
	__m128 r0 = xyz[0].v, r1 = xyz[1].v, r2 = xyz[2].v, r3 = _mm_load_ps(w);
	_MM_TRANSPOSE4_PS(r0, r1, r2, r3);
	char* base = reinterpret_cast<char*>(bodies);
	_mm_store_ps(reinterpret_cast<float*>(base + size_t(index[0]) * sizeof(btSolverBody) + offset), r0);
	_mm_store_ps(reinterpret_cast<float*>(base + size_t(index[1]) * sizeof(btSolverBody) + offset), r1);
	_mm_store_ps(reinterpret_cast<float*>(base + size_t(index[2]) * sizeof(btSolverBody) + offset), r2);
	_mm_store_ps(reinterpret_cast<float*>(base + size_t(index[3]) * sizeof(btSolverBody) + offset), r3);
}
#else
struct Lanes
{
	btScalar v[kLanes];
};
struct Mask
{
	bool v[kLanes];
};
SIMD_FORCE_INLINE Lanes load(const btScalar* p)
{
	Lanes r;
	for (int k = 0; k < kLanes; ++k) r.v[k] = p[k];
	return r;
}
SIMD_FORCE_INLINE void store(btScalar* p, const Lanes& a)
{
	for (int k = 0; k < kLanes; ++k) p[k] = a.v[k];
}
SIMD_FORCE_INLINE Lanes zero()
{
	Lanes r;
	for (int k = 0; k < kLanes; ++k) r.v[k] = btScalar(0);
	return r;
}
#define CALIBER_LANEWISE(name, expression)                            \
	SIMD_FORCE_INLINE Lanes name(const Lanes& a, const Lanes& b)      \
	{                                                                 \
		Lanes r;                                                      \
		for (int k = 0; k < kLanes; ++k) r.v[k] = (expression);   \
		return r;                                                     \
	}
CALIBER_LANEWISE(operator+, a.v[k] + b.v[k])
CALIBER_LANEWISE(operator-, a.v[k] - b.v[k])
CALIBER_LANEWISE(operator*, a.v[k] * b.v[k])
CALIBER_LANEWISE(minBranchless, caliber::btMinBranchless(a.v[k], b.v[k]))
CALIBER_LANEWISE(maxBranchless, caliber::btMaxBranchless(a.v[k], b.v[k]))
#undef CALIBER_LANEWISE
SIMD_FORCE_INLINE Lanes negate(const Lanes& a)
{
	Lanes r;
	for (int k = 0; k < kLanes; ++k) r.v[k] = -a.v[k];
	return r;
}
SIMD_FORCE_INLINE Mask frictionSkipped(const Lanes& normal, const Lanes& applied)
{
	Mask m;
	for (int k = 0; k < kLanes; ++k) m.v[k] = !(normal.v[k] > btScalar(0)) && applied.v[k] == btScalar(0);
	return m;
}
SIMD_FORCE_INLINE bool allSet(const Mask& m)
{
	for (int k = 0; k < kLanes; ++k)
		if (!m.v[k]) return false;
	return true;
}
SIMD_FORCE_INLINE Lanes select(const Mask& m, const Lanes& ifSet, const Lanes& ifClear)
{
	Lanes r;
	for (int k = 0; k < kLanes; ++k) r.v[k] = m.v[k] ? ifSet.v[k] : ifClear.v[k];
	return r;
}
SIMD_FORCE_INLINE btScalar horizontalSum(const Lanes& a) { return (a.v[0] + a.v[1]) + (a.v[2] + a.v[3]); }
SIMD_FORCE_INLINE void gatherVectors(const btSolverBody* bodies, const int* index, size_t offset, Lanes* xyz, btScalar* w)
{
	for (int k = 0; k < kLanes; ++k)
	{
		const btScalar* v =
		    reinterpret_cast<const btScalar*>(reinterpret_cast<const char*>(&bodies[index[k]]) + offset);
		for (int c = 0; c < 3; ++c) xyz[c].v[k] = v[c];
		w[k] = v[3];
	}
}
SIMD_FORCE_INLINE void scatterVectors(btSolverBody* bodies, const int* index, size_t offset, const Lanes* xyz,
                                      const btScalar* w)
{
	for (int k = 0; k < kLanes; ++k)
	{
		btScalar* v = reinterpret_cast<btScalar*>(reinterpret_cast<char*>(&bodies[index[k]]) + offset);
		for (int c = 0; c < 3; ++c) v[c] = xyz[c].v[k];
		v[3] = w[k];
	}
}
#endif

#include "BulletDynamics/ConstraintSolver/btWideContactSweep.h"
}  // namespace lanes4
}  // namespace

// ---- Eight lanes --------------------------------------------------------------------------------
#if CALIBER_WIDE_EIGHT_LANES
#pragma GCC push_options
#pragma GCC target("avx2")
namespace
{
namespace lanes8
{
const int kLanes = 8;

// As lanes4 with AVX registers. Only AVX2 is enabled, not FMA: a fused multiply-add would round once
// where the scalar kernel rounds twice, and the bits would differ.
struct Lanes
{
	__m256 v;
};
struct Mask
{
	__m256 v;
};
// The blocks are 16-byte aligned: unaligned loads.
SIMD_FORCE_INLINE Lanes load(const btScalar* p) { return Lanes{_mm256_loadu_ps(p)}; }
SIMD_FORCE_INLINE void store(btScalar* p, Lanes a) { _mm256_storeu_ps(p, a.v); }
SIMD_FORCE_INLINE Lanes zero() { return Lanes{_mm256_setzero_ps()}; }
SIMD_FORCE_INLINE Lanes operator+(Lanes a, Lanes b) { return Lanes{_mm256_add_ps(a.v, b.v)}; }
SIMD_FORCE_INLINE Lanes operator-(Lanes a, Lanes b) { return Lanes{_mm256_sub_ps(a.v, b.v)}; }
SIMD_FORCE_INLINE Lanes operator*(Lanes a, Lanes b) { return Lanes{_mm256_mul_ps(a.v, b.v)}; }
SIMD_FORCE_INLINE Lanes negate(Lanes a) { return Lanes{_mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f))}; }
SIMD_FORCE_INLINE Lanes minBranchless(Lanes a, Lanes b) { return Lanes{_mm256_min_ps(b.v, a.v)}; }
SIMD_FORCE_INLINE Lanes maxBranchless(Lanes a, Lanes b) { return Lanes{_mm256_max_ps(b.v, a.v)}; }
SIMD_FORCE_INLINE Mask frictionSkipped(Lanes normal, Lanes applied)
{
	const __m256 noNormal = _mm256_cmp_ps(_mm256_setzero_ps(), normal.v, _CMP_NLT_UQ);  // !(0 < normal)
	return Mask{_mm256_and_ps(noNormal, _mm256_cmp_ps(applied.v, _mm256_setzero_ps(), _CMP_EQ_OQ))};
}
SIMD_FORCE_INLINE bool allSet(Mask m) { return _mm256_movemask_ps(m.v) == 0xff; }
SIMD_FORCE_INLINE Lanes select(Mask m, Lanes ifSet, Lanes ifClear)
{
	return Lanes{_mm256_or_ps(_mm256_and_ps(m.v, ifSet.v), _mm256_andnot_ps(m.v, ifClear.v))};
}
SIMD_FORCE_INLINE btScalar horizontalSum(Lanes a)
{
	btScalar lanes[kLanes];
	_mm256_storeu_ps(lanes, a.v);
	return ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) + ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
}

// Four 4x4 transposes at once: body k in the low half of row k, body k + 4 in its high half.
SIMD_FORCE_INLINE void transposeHalves(__m256& r0, __m256& r1, __m256& r2, __m256& r3)
{
	const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1);
	const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3);
	r0 = _mm256_shuffle_ps(t0, t2, 0x44);
	r1 = _mm256_shuffle_ps(t0, t2, 0xee);
	r2 = _mm256_shuffle_ps(t1, t3, 0x44);
	r3 = _mm256_shuffle_ps(t1, t3, 0xee);
}
SIMD_FORCE_INLINE const float* vectorAt(const btSolverBody* bodies, int index, size_t offset)
{
	return reinterpret_cast<const float*>(reinterpret_cast<const char*>(bodies) + size_t(index) * sizeof(btSolverBody) +
	                                      offset);
}
SIMD_FORCE_INLINE float* vectorAt(btSolverBody* bodies, int index, size_t offset)
{
	return reinterpret_cast<float*>(reinterpret_cast<char*>(bodies) + size_t(index) * sizeof(btSolverBody) + offset);
}
SIMD_FORCE_INLINE void gatherVectors(const btSolverBody* bodies, const int* index, size_t offset, Lanes* xyz, btScalar* w)
{
	__m256 r[4];
	for (int k = 0; k < 4; ++k)
		r[k] = _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(vectorAt(bodies, index[k], offset))),
		                            _mm_load_ps(vectorAt(bodies, index[k + 4], offset)), 1);
	transposeHalves(r[0], r[1], r[2], r[3]);
	xyz[0].v = r[0];
	xyz[1].v = r[1];
	xyz[2].v = r[2];
	_mm256_storeu_ps(w, r[3]);
}
SIMD_FORCE_INLINE void scatterVectors(btSolverBody* bodies, const int* index, size_t offset, const Lanes* xyz,
                                      const btScalar* w)
{
	__m256 r0 = xyz[0].v, r1 = xyz[1].v, r2 = xyz[2].v, r3 = _mm256_loadu_ps(w);
	transposeHalves(r0, r1, r2, r3);
	const __m256 r[4] = {r0, r1, r2, r3};
	for (int k = 0; k < 4; ++k)
	{
		_mm_store_ps(vectorAt(bodies, index[k], offset), _mm256_castps256_ps128(r[k]));
		_mm_store_ps(vectorAt(bodies, index[k + 4], offset), _mm256_extractf128_ps(r[k], 1));
	}
}

// The 16-byte line at offset of eight rows, transposed: lane k of r[c] is component c of row k's line.
SIMD_FORCE_INLINE void loadRowLines(const btSolverConstraint* const* rows, size_t offset, __m256 (&r)[4])
{
	const auto line = [offset](const btSolverConstraint* row)
	{ return _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(row) + offset)); };
	for (int k = 0; k < 4; ++k)
		r[k] = _mm256_insertf128_ps(_mm256_castps128_ps256(line(rows[k])), line(rows[k + 4]), 1);
	transposeHalves(r[0], r[1], r[2], r[3]);
}
SIMD_FORCE_INLINE void copyRowField(const btSolverConstraint* const* rows, size_t offset, btScalar (&to)[3][kLanes])
{
	__m256 r[4];
	loadRowLines(rows, offset, r);
	for (int c = 0; c < 3; ++c) _mm256_storeu_ps(to[c], r[c]);
}
// copyGroupBodies for eight lanes, by the sweep's gathers.
void copyGroupBodies(caliber::WideGroupT<kLanes>& group, const btSolverBody* bodies)
{
	Lanes xyz[3];
	btScalar w[kLanes];
	gatherVectors(bodies, group.bodyA, offsetof(btSolverBody, m_invMass), xyz, w);
	for (int c = 0; c < 3; ++c) store(group.invMassA[c], xyz[c]);
	gatherVectors(bodies, group.bodyA, offsetof(btSolverBody, m_angularFactor), xyz, w);
	for (int c = 0; c < 3; ++c) store(group.angularFactorA[c], xyz[c]);
	gatherVectors(bodies, group.bodyB, offsetof(btSolverBody, m_invMass), xyz, w);
	for (int c = 0; c < 3; ++c) store(group.invMassB[c], xyz[c]);
	gatherVectors(bodies, group.bodyB, offsetof(btSolverBody, m_angularFactor), xyz, w);
	for (int c = 0; c < 3; ++c) store(group.angularFactorB[c], xyz[c]);
}

// copyRows<8> with 8-lane transposes (a copy: the same bits).
bool copyRows(caliber::WideRowBlockT<kLanes>& block, const btSolverConstraint* const* rows)
{
	const bool negated = secondNormalsAreNegated(rows, kLanes);
	copyRowField(rows, offsetof(btSolverConstraint, m_contactNormal1), block.normal1);
	copyRowField(rows, offsetof(btSolverConstraint, m_relpos1CrossNormal), block.relpos1CrossNormal);
	copyRowField(rows, offsetof(btSolverConstraint, m_relpos2CrossNormal), block.relpos2CrossNormal);
	copyRowField(rows, offsetof(btSolverConstraint, m_angularComponentA), block.angularA);
	copyRowField(rows, offsetof(btSolverConstraint, m_angularComponentB), block.angularB);
	__m256 l[4];
	loadRowLines(rows, offsetof(btSolverConstraint, m_appliedPushImpulse), l);
	_mm256_storeu_ps(block.applied, l[1]);
	_mm256_storeu_ps(block.friction, l[2]);
	_mm256_storeu_ps(block.jacDiagABInv, l[3]);
	loadRowLines(rows, offsetof(btSolverConstraint, m_rhs), l);
	_mm256_storeu_ps(block.rhs, l[0]);
	_mm256_storeu_ps(block.cfm, l[1]);
	_mm256_storeu_ps(block.lower, l[2]);
	_mm256_storeu_ps(block.upper, l[3]);
	return negated;
}

#include "BulletDynamics/ConstraintSolver/btWideContactSweep.h"
}  // namespace lanes8
}  // namespace
#pragma GCC pop_options
#endif

// ---- The layout ---------------------------------------------------------------------------------
namespace
{
bool eightLanesAvailable()
{
#if CALIBER_WIDE_EIGHT_LANES
	static const bool available = __builtin_cpu_supports("avx2") != 0;
	return available;
#else
	return false;
#endif
}


// Batches per task of the plan's count of blocks.
const int kBatchesPerPlanTask = 8;

// The blocks of each group of batches [iBegin, iEnd) (its manifolds' most points), and each batch's total
// in batchFirstBlock[b + 1] (made a running sum afterwards): a batch reads and writes only its own.
template <int W>
struct CountGroupBlocks : public btIParallelForBody
{
	caliber::WideLayout<W>* layout;
	const btAlignedObjectArray<int>* batchFirstGroup;
	const btAlignedObjectArray<int>* orderedManifolds;
	const btAlignedObjectArray<int>* batchManifoldBegin;
	const btAlignedObjectArray<int>* manifoldFirstRow;
	int* batchBlocks;

	void forLoop(int iBegin, int iEnd) const override
	{
		const btAlignedObjectArray<int>& firstRow = *manifoldFirstRow;
		for (int b = iBegin; b < iEnd; ++b)
		{
			int g = (*batchFirstGroup)[b], total = 0;
			const int batchEnd = (*batchManifoldBegin)[b + 1];
			for (int first = (*batchManifoldBegin)[b]; first < batchEnd; first += W, ++g)
			{
				const int last = btMin(first + W, batchEnd);
				int most = 0;
				for (int i = first; i < last; ++i)
				{
					const int m = (*orderedManifolds)[i];
					most = btMax(most, firstRow[m + 1] - firstRow[m]);
				}
				layout->groups[g].numBlocks = most;
				total += most;
			}
			batchBlocks[b + 1] = total;
		}
	}
};

// A batch's groups follow from its manifold count; their blocks (the most points of their manifolds) are
// counted batch by batch on the threads, and each batch's first block is their running sum (fill then
// gives the groups their first blocks, batch by batch on any thread).
template <int W>
void planLayout(caliber::WideLayout<W>& layout, btAlignedObjectArray<int>& batchFirstGroup,
                btAlignedObjectArray<int>& batchFirstBlock, const btAlignedObjectArray<int>& orderedManifolds,
                const btAlignedObjectArray<int>& batchManifoldBegin, const btAlignedObjectArray<int>& manifoldFirstRow,
                int frictionRows)
{
	const int numBatches = batchManifoldBegin.size() - 1;
	caliber::resizeScratch(batchFirstGroup, numBatches + 1);
	caliber::resizeScratch(batchFirstBlock, numBatches + 1);
	int numGroups = 0;
	for (int b = 0; b < numBatches; ++b)
	{
		batchFirstGroup[b] = numGroups;
		numGroups += (batchManifoldBegin[b + 1] - batchManifoldBegin[b] + W - 1) / W;
	}
	batchFirstGroup[numBatches] = numGroups;
	caliber::resizeScratch(layout.groups, numGroups);
	batchFirstBlock[0] = 0;
	CountGroupBlocks<W> count;
	count.layout = &layout;
	count.batchFirstGroup = &batchFirstGroup;
	count.orderedManifolds = &orderedManifolds;
	count.batchManifoldBegin = &batchManifoldBegin;
	count.manifoldFirstRow = &manifoldFirstRow;
	count.batchBlocks = &batchFirstBlock[0];
	btParallelFor(0, numBatches, kBatchesPerPlanTask, count);
	for (int b = 0; b < numBatches; ++b) batchFirstBlock[b + 1] += batchFirstBlock[b];
	const int numBlocks = batchFirstBlock[numBatches];
	caliber::resizeScratch(layout.normalBlocks, numBlocks);
	caliber::resizeScratch(layout.frictionBlocks, numBlocks * frictionRows);
}

// A block's rows copied by the widest transposes this build has.
SIMD_FORCE_INLINE bool copyBlockRows(caliber::WideRowBlockT<4>& block, const btSolverConstraint* const* rows)
{
	return copyRows<4>(block, rows);
}
SIMD_FORCE_INLINE bool copyBlockRows(caliber::WideRowBlockT<8>& block, const btSolverConstraint* const* rows)
{
#if CALIBER_WIDE_EIGHT_LANES
	if (eightLanesAvailable()) return lanes8::copyRows(block, rows);
#endif
	return copyRows<8>(block, rows);
}

// The constants of a group's bodies (their indices set) into its lanes.
template <int W>
SIMD_FORCE_INLINE void copyGroupBodiesScalar(caliber::WideGroupT<W>& group, const btSolverBody* bodies)
{
	for (int k = 0; k < W; ++k)
		for (int c = 0; c < 3; ++c)
		{
			group.invMassA[c][k] = bodies[group.bodyA[k]].m_invMass[c];
			group.angularFactorA[c][k] = bodies[group.bodyA[k]].m_angularFactor[c];
			group.invMassB[c][k] = bodies[group.bodyB[k]].m_invMass[c];
			group.angularFactorB[c][k] = bodies[group.bodyB[k]].m_angularFactor[c];
		}
}
SIMD_FORCE_INLINE void copyGroupBodies(caliber::WideGroupT<4>& group, const btSolverBody* bodies)
{
	copyGroupBodiesScalar(group, bodies);
}
SIMD_FORCE_INLINE void copyGroupBodies(caliber::WideGroupT<8>& group, const btSolverBody* bodies)
{
#if CALIBER_WIDE_EIGHT_LANES
	if (eightLanesAvailable())
	{
		lanes8::copyGroupBodies(group, bodies);
		return;
	}
#endif
	copyGroupBodiesScalar(group, bodies);
}

template <int W>
bool fillLayout(caliber::WideLayout<W>& layout, const btAlignedObjectArray<int>& batchFirstGroup,
                const btAlignedObjectArray<int>& batchFirstBlock, int frictionRowsPerContact, int batchBegin,
                int batchEnd,
                const btAlignedObjectArray<int>& orderedManifolds, const btAlignedObjectArray<int>& batchManifoldBegin,
                const btAlignedObjectArray<int>& manifoldFirstRow, const btAlignedObjectArray<int>& batchPaddingBody,
                unsigned int solveCount, const btSolverBody* bodies, const btConstraintArray& contacts,
                const btConstraintArray& friction)
{
	bool fits = true;
	// Plain pointers: the loops below store through others, which the arrays' accessors would make the
	// compiler read again at every lane.
	const btSolverConstraint* const contactRows = contacts.size() ? &contacts[0] : nullptr;
	const btSolverConstraint* const frictionRows = friction.size() ? &friction[0] : nullptr;
	const btSolverConstraint* const padding = &zeroRow();
	for (int b = batchBegin; b < batchEnd; ++b)
	{
		int first = batchManifoldBegin[b];
		int nextBlock = batchFirstBlock[b];
		for (int g = batchFirstGroup[b]; g < batchFirstGroup[b + 1]; ++g, first += W)
		{
			caliber::WideGroupT<W>& group = layout.groups[g];
			group.firstBlock = nextBlock;
			nextBlock += group.numBlocks;
			const int lanes = btMin(W, batchManifoldBegin[b + 1] - first);
			for (int k = 0; k < W; ++k)
			{
				int bodyA = batchPaddingBody[b], bodyB = batchPaddingBody[b];
				if (k < lanes)
				{
					const btSolverConstraint& row = contacts[manifoldFirstRow[orderedManifolds[first + k]]];
					bodyA = row.m_solverBodyIdA;
					bodyB = row.m_solverBodyIdB;
				}
				group.bodyA[k] = bodyA;
				group.bodyB[k] = bodyB;
			}
			copyGroupBodies(group, bodies);
			// Each lane's manifold: its first row, its point count and the rotation of the row-by-row sweep
			// (appendBatchRows); lanes past the batch's manifolds have no points.
			int laneFirstRow[W], laneCount[W], laneRotation[W];
			for (int k = 0; k < W; ++k)
			{
				laneFirstRow[k] = 0;
				laneCount[k] = 0;
				laneRotation[k] = 0;
				if (k < lanes)
				{
					const int m = orderedManifolds[first + k];
					laneFirstRow[k] = manifoldFirstRow[m];
					laneCount[k] = manifoldFirstRow[m + 1] - laneFirstRow[k];
					if (laneCount[k] > 0) laneRotation[k] = int(solveCount % unsigned(laneCount[k]));
				}
			}
			for (int s = 0; s < group.numBlocks; ++s)
			{
				caliber::WideRowBlockT<W>& normalBlock = layout.normalBlocks[group.firstBlock + s];
				const btSolverConstraint* normalSource[W];
				for (int k = 0; k < W; ++k)
				{
					int row = -1;
					if (s < laneCount[k])
					{
						const int rotated = s + laneRotation[k];
						row = laneFirstRow[k] + (rotated < laneCount[k] ? rotated : rotated - laneCount[k]);
					}
					normalBlock.row[k] = row;
					normalSource[k] = row >= 0 ? contactRows + row : padding;
				}
				if (!copyBlockRows(normalBlock, normalSource)) fits = false;
				for (int f = 0; f < frictionRowsPerContact; ++f)
				{
					caliber::WideRowBlockT<W>& frictionBlock =
					    layout.frictionBlocks[(group.firstBlock + s) * frictionRowsPerContact + f];
					const btSolverConstraint* frictionSource[W];
					for (int k = 0; k < W; ++k)
					{
						const int normalRow = normalBlock.row[k];
						const int row = normalRow >= 0 ? normalRow * frictionRowsPerContact + f : -1;
						frictionBlock.row[k] = row;
						frictionSource[k] = row >= 0 ? frictionRows + row : padding;
					}
					if (!copyBlockRows(frictionBlock, frictionSource)) fits = false;
				}
			}
		}
	}
	return fits;
}

}  // namespace

void caliber::setWideContactRowsEnabled(bool enabled) { g_wideEnabled.store(enabled, std::memory_order_relaxed); }
bool caliber::wideContactRowsEnabled() { return g_wideEnabled.load(std::memory_order_relaxed); }
void caliber::setWideContactLanes(int lanes) { g_wideLanes.store(lanes, std::memory_order_relaxed); }
bool caliber::wideContactEightLanesAvailable() { return eightLanesAvailable(); }
int caliber::wideContactLanes()
{
	const int asked = g_wideLanes.load(std::memory_order_relaxed);
	if (asked == 4) return 4;
	return eightLanesAvailable() ? 8 : 4;
}

void caliber::WideContactRows::plan(const btAlignedObjectArray<int>& orderedManifolds,
                                    const btAlignedObjectArray<int>& batchManifoldBegin,
                                    const btAlignedObjectArray<int>& manifoldFirstRow, int frictionRows)
{
	frictionRowsPerContact = frictionRows;
	lanes = wideContactLanes();
	if (lanes == 8)
		planLayout(eight, batchFirstGroup, batchFirstBlock, orderedManifolds, batchManifoldBegin, manifoldFirstRow,
		           frictionRows);
	else
		planLayout(four, batchFirstGroup, batchFirstBlock, orderedManifolds, batchManifoldBegin, manifoldFirstRow,
		           frictionRows);
}

bool caliber::WideContactRows::fill(int batchBegin, int batchEnd, const btAlignedObjectArray<int>& orderedManifolds,
                                    const btAlignedObjectArray<int>& batchManifoldBegin,
                                    const btAlignedObjectArray<int>& manifoldFirstRow,
                                    const btAlignedObjectArray<int>& batchPaddingBody, unsigned int solveCount,
                                    const btSolverBody* bodies, const btConstraintArray& contacts,
                                    const btConstraintArray& friction)
{
	if (lanes == 8)
		return fillLayout(eight, batchFirstGroup, batchFirstBlock, frictionRowsPerContact, batchBegin, batchEnd,
		                  orderedManifolds, batchManifoldBegin, manifoldFirstRow, batchPaddingBody, solveCount, bodies,
		                  contacts, friction);
	return fillLayout(four, batchFirstGroup, batchFirstBlock, frictionRowsPerContact, batchBegin, batchEnd,
	                  orderedManifolds, batchManifoldBegin, manifoldFirstRow, batchPaddingBody, solveCount, bodies,
	                  contacts, friction);
}

btScalar caliber::WideContactRows::sweepNormal(int batch, bool reverse, btSolverBody* bodies,
                                               btConstraintArray* contacts)
{
#if CALIBER_WIDE_EIGHT_LANES
	if (lanes == 8)
		return lanes8::sweepNormal(eight, batchFirstGroup[batch], batchFirstGroup[batch + 1], reverse, bodies, contacts);
#endif
	return lanes4::sweepNormal(four, batchFirstGroup[batch], batchFirstGroup[batch + 1], reverse, bodies, contacts);
}

btScalar caliber::WideContactRows::sweepFriction(int batch, bool reverse, btSolverBody* bodies,
                                                 btConstraintArray* friction)
{
#if CALIBER_WIDE_EIGHT_LANES
	if (lanes == 8)
		return lanes8::sweepFriction(eight, batchFirstGroup[batch], batchFirstGroup[batch + 1], reverse,
		                             frictionRowsPerContact, bodies, friction);
#endif
	return lanes4::sweepFriction(four, batchFirstGroup[batch], batchFirstGroup[batch + 1], reverse,
	                             frictionRowsPerContact, bodies, friction);
}

void caliber::WideContactRows::storeImpulses(int batchBegin, int batchEnd, btConstraintArray& contacts,
                                             btConstraintArray& friction)
{
#if CALIBER_WIDE_EIGHT_LANES
	if (lanes == 8)
	{
		lanes8::storeAllImpulses(eight, batchFirstGroup[batchBegin], batchFirstGroup[batchEnd], frictionRowsPerContact,
		                         contacts, friction);
		return;
	}
#endif
	lanes4::storeAllImpulses(four, batchFirstGroup[batchBegin], batchFirstGroup[batchEnd], frictionRowsPerContact,
	                         contacts, friction);
}
