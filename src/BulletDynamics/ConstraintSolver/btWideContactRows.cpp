// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The wide sweep of coloured contact batches (see btWideContactRows.h for the layout and why the bits
// are those of the row-by-row sweep).
#include "BulletDynamics/ConstraintSolver/btWideContactRows.h"

#include <string.h>

#include <atomic>

#include "BulletDynamics/ConstraintSolver/btSolverRowKernels.h"

namespace
{
std::atomic<bool> g_wideEnabled{true};

using caliber::kWideLanes;
using caliber::WideGroup;
using caliber::WideRowBlock;

// ---- Lanes: kWideLanes scalars and the operations the kernel needs, each the same IEEE operation per
// lane as the scalar kernel's. SSE2 registers in single precision, plain arrays otherwise.
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
	btScalar lanes[kWideLanes];
	_mm_storeu_ps(lanes, a.v);
	return (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]);
}
#else
struct Lanes
{
	btScalar v[kWideLanes];
};
struct Mask
{
	bool v[kWideLanes];
};
SIMD_FORCE_INLINE Lanes load(const btScalar* p)
{
	Lanes r;
	for (int k = 0; k < kWideLanes; ++k) r.v[k] = p[k];
	return r;
}
SIMD_FORCE_INLINE void store(btScalar* p, const Lanes& a)
{
	for (int k = 0; k < kWideLanes; ++k) p[k] = a.v[k];
}
SIMD_FORCE_INLINE Lanes zero()
{
	Lanes r;
	for (int k = 0; k < kWideLanes; ++k) r.v[k] = btScalar(0);
	return r;
}
#define CALIBER_LANEWISE(name, expression)                            \
	SIMD_FORCE_INLINE Lanes name(const Lanes& a, const Lanes& b)      \
	{                                                                 \
		Lanes r;                                                      \
		for (int k = 0; k < kWideLanes; ++k) r.v[k] = (expression);   \
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
	for (int k = 0; k < kWideLanes; ++k) r.v[k] = -a.v[k];
	return r;
}
SIMD_FORCE_INLINE Mask frictionSkipped(const Lanes& normal, const Lanes& applied)
{
	Mask m;
	for (int k = 0; k < kWideLanes; ++k) m.v[k] = !(normal.v[k] > btScalar(0)) && applied.v[k] == btScalar(0);
	return m;
}
SIMD_FORCE_INLINE bool allSet(const Mask& m)
{
	for (int k = 0; k < kWideLanes; ++k)
		if (!m.v[k]) return false;
	return true;
}
SIMD_FORCE_INLINE Lanes select(const Mask& m, const Lanes& ifSet, const Lanes& ifClear)
{
	Lanes r;
	for (int k = 0; k < kWideLanes; ++k) r.v[k] = m.v[k] ? ifSet.v[k] : ifClear.v[k];
	return r;
}
SIMD_FORCE_INLINE btScalar horizontalSum(const Lanes& a) { return (a.v[0] + a.v[1]) + (a.v[2] + a.v[3]); }
#endif

// The velocity changes of a group's bodies, one lane per manifold. The fourth scalar of each btVector3
// waits in memory (kept in registers, it would push the row data out of them) and is stored back as it was.
struct BodyLanes
{
	Lanes linear[3];
	Lanes angular[3];
};
struct BodyFourths
{
	btScalar linear[kWideLanes];
	btScalar angular[kWideLanes];
};

#if defined(BT_USE_SSE)
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
SIMD_FORCE_INLINE void gatherVectors(const btSolverBody* bodies, const int* index, size_t offset, Lanes* xyz, btScalar* w)
{
	for (int k = 0; k < kWideLanes; ++k)
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
	for (int k = 0; k < kWideLanes; ++k)
	{
		btScalar* v = reinterpret_cast<btScalar*>(reinterpret_cast<char*>(&bodies[index[k]]) + offset);
		for (int c = 0; c < 3; ++c) v[c] = xyz[c].v[k];
		v[3] = w[k];
	}
}
#endif

// Lanes that share a body (the fixed entry, or padding on it) store the same values, so the order of
// the stores does not matter.
SIMD_FORCE_INLINE void gatherBodies(const btSolverBody* bodies, const int* index, BodyLanes& lanes, BodyFourths& w)
{
	gatherVectors(bodies, index, offsetof(btSolverBody, m_deltaLinearVelocity), lanes.linear, w.linear);
	gatherVectors(bodies, index, offsetof(btSolverBody, m_deltaAngularVelocity), lanes.angular, w.angular);
}
SIMD_FORCE_INLINE void scatterBodies(btSolverBody* bodies, const int* index, const BodyLanes& lanes,
                                     const BodyFourths& w)
{
	scatterVectors(bodies, index, offsetof(btSolverBody, m_deltaLinearVelocity), lanes.linear, w.linear);
	scatterVectors(bodies, index, offsetof(btSolverBody, m_deltaAngularVelocity), lanes.angular, w.angular);
}

// rowDeltaVelocity of btSolverRowKernels.h, lane by lane, with its association.
SIMD_FORCE_INLINE Lanes deltaVelocity(const WideRowBlock& block, const BodyLanes& a, const BodyLanes& b)
{
	Lanes sum[3];
	for (int c = 0; c < 3; ++c)
		sum[c] = ((load(block.normal1[c]) * a.linear[c] + load(block.relpos1CrossNormal[c]) * a.angular[c]) +
		          load(block.normal2[c]) * b.linear[c]) +
		         load(block.relpos2CrossNormal[c]) * b.angular[c];
	return (sum[0] + sum[1]) + sum[2];
}

// btSolverBody::applyImpulse on both bodies of every lane.
SIMD_FORCE_INLINE void applyImpulses(const WideRowBlock& block, const WideGroup& group, Lanes deltaImpulse,
                                     BodyLanes& a, BodyLanes& b)
{
	for (int c = 0; c < 3; ++c)
	{
		a.linear[c] = a.linear[c] + (load(block.normal1[c]) * load(group.invMassA[c])) * deltaImpulse;
		a.angular[c] = a.angular[c] + load(block.angularA[c]) * (deltaImpulse * load(group.angularFactorA[c]));
		b.linear[c] = b.linear[c] + (load(block.normal2[c]) * load(group.invMassB[c])) * deltaImpulse;
		b.angular[c] = b.angular[c] + load(block.angularB[c]) * (deltaImpulse * load(group.angularFactorB[c]));
	}
}

// resolveRow of btSolverRowKernels.h, lane by lane; returns the squared impulse changes.
SIMD_FORCE_INLINE Lanes resolveBlock(WideRowBlock& block, const WideGroup& group, Lanes lower, Lanes upper,
                                     BodyLanes& a, BodyLanes& b)
{
	const Lanes applied = load(block.applied);
	Lanes deltaImpulse =
	    (load(block.rhs) - applied * load(block.cfm)) - deltaVelocity(block, a, b) * load(block.jacDiagABInv);
	const Lanes clamped = maxBranchless(lower, minBranchless(upper, applied + deltaImpulse));
	deltaImpulse = clamped - applied;
	store(block.applied, clamped);
	applyImpulses(block, group, deltaImpulse, a, b);
	return deltaImpulse * deltaImpulse;
}

SIMD_FORCE_INLINE void storeImpulses(const WideRowBlock& block, btConstraintArray& rows)
{
	for (int k = 0; k < kWideLanes; ++k)
		if (block.row[k] >= 0) rows[block.row[k]].m_appliedImpulse = block.applied[k];
}

// The source of a padding lane: a row of zeros.
const btSolverConstraint& zeroRow()
{
	static const btSolverConstraint row = [] {
		btSolverConstraint r;
		memset(static_cast<void*>(&r), 0, sizeof(r));
		return r;
	}();
	return row;
}

// One vector field of kWideLanes rows into its structure-of-arrays place.
SIMD_FORCE_INLINE void copyField(const btSolverConstraint* const* rows, size_t offset, btScalar (&to)[3][kWideLanes])
{
#if defined(BT_USE_SSE)
	__m128 r0 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[0]) + offset));
	__m128 r1 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[1]) + offset));
	__m128 r2 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[2]) + offset));
	__m128 r3 = _mm_load_ps(reinterpret_cast<const float*>(reinterpret_cast<const char*>(rows[3]) + offset));
	_MM_TRANSPOSE4_PS(r0, r1, r2, r3);
	_mm_store_ps(to[0], r0);
	_mm_store_ps(to[1], r1);
	_mm_store_ps(to[2], r2);
#else
	for (int k = 0; k < kWideLanes; ++k)
	{
		const btScalar* v = reinterpret_cast<const btScalar*>(reinterpret_cast<const char*>(rows[k]) + offset);
		for (int c = 0; c < 3; ++c) to[c][k] = v[c];
	}
#endif
}

// kWideLanes rows (padding lanes point at zeroRow) into a block.
void copyRows(WideRowBlock& block, const btSolverConstraint* const* rows, const int* rowIndex)
{
	copyField(rows, offsetof(btSolverConstraint, m_contactNormal1), block.normal1);
	copyField(rows, offsetof(btSolverConstraint, m_relpos1CrossNormal), block.relpos1CrossNormal);
	copyField(rows, offsetof(btSolverConstraint, m_contactNormal2), block.normal2);
	copyField(rows, offsetof(btSolverConstraint, m_relpos2CrossNormal), block.relpos2CrossNormal);
	copyField(rows, offsetof(btSolverConstraint, m_angularComponentA), block.angularA);
	copyField(rows, offsetof(btSolverConstraint, m_angularComponentB), block.angularB);
	for (int k = 0; k < kWideLanes; ++k)
	{
		const btSolverConstraint& row = *rows[k];
		block.rhs[k] = row.m_rhs;
		block.cfm[k] = row.m_cfm;
		block.jacDiagABInv[k] = row.m_jacDiagABInv;
		block.lower[k] = row.m_lowerLimit;
		block.upper[k] = row.m_upperLimit;
		block.friction[k] = row.m_friction;
		block.applied[k] = row.m_appliedImpulse;
		block.row[k] = rowIndex[k];
	}
}
}  // namespace

void caliber::setWideContactRowsEnabled(bool enabled) { g_wideEnabled.store(enabled, std::memory_order_relaxed); }
bool caliber::wideContactRowsEnabled() { return g_wideEnabled.load(std::memory_order_relaxed); }

void caliber::WideContactRows::plan(const btAlignedObjectArray<int>& orderedManifolds,
                                    const btAlignedObjectArray<int>& batchManifoldBegin,
                                    const btAlignedObjectArray<int>& manifoldFirstRow, int frictionRows)
{
	frictionRowsPerContact = frictionRows;
	const int numBatches = batchManifoldBegin.size() - 1;
	batchFirstGroup.resizeNoInitialize(numBatches + 1);
	int numGroups = 0, numBlocks = 0;
	for (int b = 0; b < numBatches; ++b)
	{
		batchFirstGroup[b] = numGroups;
		for (int first = batchManifoldBegin[b]; first < batchManifoldBegin[b + 1]; first += kWideLanes)
		{
			const int last = btMin(first + kWideLanes, batchManifoldBegin[b + 1]);
			int most = 0;
			for (int i = first; i < last; ++i)
			{
				const int m = orderedManifolds[i];
				most = btMax(most, manifoldFirstRow[m + 1] - manifoldFirstRow[m]);
			}
			++numGroups;
			numBlocks += most;
		}
	}
	batchFirstGroup[numBatches] = numGroups;
	groups.resizeNoInitialize(numGroups);
	normalBlocks.resizeNoInitialize(numBlocks);
	frictionBlocks.resizeNoInitialize(numBlocks * frictionRows);
	// The groups' first blocks, in order (fill then runs batch by batch on any thread).
	int nextBlock = 0, g = 0;
	for (int b = 0; b < numBatches; ++b)
		for (int first = batchManifoldBegin[b]; first < batchManifoldBegin[b + 1]; first += kWideLanes, ++g)
		{
			const int last = btMin(first + kWideLanes, batchManifoldBegin[b + 1]);
			int most = 0;
			for (int i = first; i < last; ++i)
			{
				const int m = orderedManifolds[i];
				most = btMax(most, manifoldFirstRow[m + 1] - manifoldFirstRow[m]);
			}
			groups[g].firstBlock = nextBlock;
			groups[g].numBlocks = most;
			nextBlock += most;
		}
}

void caliber::WideContactRows::fill(int batchBegin, int batchEnd, const btAlignedObjectArray<int>& orderedManifolds,
                                    const btAlignedObjectArray<int>& batchManifoldBegin,
                                    const btAlignedObjectArray<int>& manifoldFirstRow,
                                    const btAlignedObjectArray<int>& batchPaddingBody, unsigned int solveCount,
                                    const btSolverBody* bodies, const btConstraintArray& contacts,
                                    const btConstraintArray& friction)
{
	for (int b = batchBegin; b < batchEnd; ++b)
	{
		int first = batchManifoldBegin[b];
		for (int g = batchFirstGroup[b]; g < batchFirstGroup[b + 1]; ++g, first += kWideLanes)
		{
			WideGroup& group = groups[g];
			const int lanes = btMin(kWideLanes, batchManifoldBegin[b + 1] - first);
			for (int k = 0; k < kWideLanes; ++k)
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
				for (int c = 0; c < 3; ++c)
				{
					group.invMassA[c][k] = bodies[bodyA].m_invMass[c];
					group.angularFactorA[c][k] = bodies[bodyA].m_angularFactor[c];
					group.invMassB[c][k] = bodies[bodyB].m_invMass[c];
					group.angularFactorB[c][k] = bodies[bodyB].m_angularFactor[c];
				}
			}
			for (int s = 0; s < group.numBlocks; ++s)
			{
				int normalRow[kWideLanes];
				const btSolverConstraint* normalSource[kWideLanes];
				for (int k = 0; k < kWideLanes; ++k)
				{
					normalRow[k] = -1;
					if (k < lanes)
					{
						const int m = orderedManifolds[first + k];
						const int count = manifoldFirstRow[m + 1] - manifoldFirstRow[m];
						if (s < count)
						{
							// The rotation of the row-by-row sweep (appendBatchRows).
							const int rotated = s + int(solveCount % unsigned(count));
							normalRow[k] = manifoldFirstRow[m] + (rotated < count ? rotated : rotated - count);
						}
					}
					normalSource[k] = normalRow[k] >= 0 ? &contacts[normalRow[k]] : &zeroRow();
				}
				copyRows(normalBlocks[group.firstBlock + s], normalSource, normalRow);
				for (int f = 0; f < frictionRowsPerContact; ++f)
				{
					int frictionRow[kWideLanes];
					const btSolverConstraint* frictionSource[kWideLanes];
					for (int k = 0; k < kWideLanes; ++k)
					{
						frictionRow[k] = normalRow[k] >= 0 ? normalRow[k] * frictionRowsPerContact + f : -1;
						frictionSource[k] = frictionRow[k] >= 0 ? &friction[frictionRow[k]] : &zeroRow();
					}
					copyRows(frictionBlocks[(group.firstBlock + s) * frictionRowsPerContact + f], frictionSource,
					         frictionRow);
				}
			}
		}
	}
}

btScalar caliber::WideContactRows::sweepNormal(int batch, bool reverse, btSolverBody* bodies,
                                               btConstraintArray& contacts)
{
	Lanes residual = zero();
	const int firstGroup = batchFirstGroup[batch], endGroup = batchFirstGroup[batch + 1];
	for (int i = firstGroup; i < endGroup; ++i)
	{
		const WideGroup& group = groups[reverse ? firstGroup + endGroup - 1 - i : i];
		BodyLanes a, b;
		ATTRIBUTE_ALIGNED16(BodyFourths) fourthsA;
		ATTRIBUTE_ALIGNED16(BodyFourths) fourthsB;
		gatherBodies(bodies, group.bodyA, a, fourthsA);
		gatherBodies(bodies, group.bodyB, b, fourthsB);
		for (int s = 0; s < group.numBlocks; ++s)
		{
			WideRowBlock& block = normalBlocks[group.firstBlock + (reverse ? group.numBlocks - 1 - s : s)];
			residual = residual + resolveBlock(block, group, load(block.lower), load(block.upper), a, b);
			storeImpulses(block, contacts);
		}
		scatterBodies(bodies, group.bodyA, a, fourthsA);
		scatterBodies(bodies, group.bodyB, b, fourthsB);
	}
	return horizontalSum(residual);
}

btScalar caliber::WideContactRows::sweepFriction(int batch, bool reverse, btSolverBody* bodies,
                                                 btConstraintArray& friction)
{
	Lanes residual = zero();
	const int firstGroup = batchFirstGroup[batch], endGroup = batchFirstGroup[batch + 1];
	for (int i = firstGroup; i < endGroup; ++i)
	{
		const WideGroup& group = groups[reverse ? firstGroup + endGroup - 1 - i : i];
		BodyLanes a, b;
		ATTRIBUTE_ALIGNED16(BodyFourths) fourthsA;
		ATTRIBUTE_ALIGNED16(BodyFourths) fourthsB;
		gatherBodies(bodies, group.bodyA, a, fourthsA);
		gatherBodies(bodies, group.bodyB, b, fourthsB);
		for (int s = 0; s < group.numBlocks; ++s)
		{
			const int normalIndex = group.firstBlock + (reverse ? group.numBlocks - 1 - s : s);
			const Lanes normalImpulse = load(normalBlocks[normalIndex].applied);
			for (int f = 0; f < frictionRowsPerContact; ++f)
			{
				WideRowBlock& block = frictionBlocks[normalIndex * frictionRowsPerContact + f];
				// solveFrictionRow: a row without normal impulse and without an impulse of its own is skipped.
				const Mask skipped = frictionSkipped(normalImpulse, load(block.applied));
				if (allSet(skipped)) continue;
				const Lanes bound = load(block.friction) * maxBranchless(zero(), normalImpulse);
				// resolveBlock with the skipped lanes' impulse change forced to zero: their bodies then gain
				// products with zero, which leave a sum unchanged (a velocity change, which starts at +0 and
				// only ever has numbers added to it, is never -0), and their impulse is put back.
				const Lanes applied = load(block.applied);
				Lanes deltaImpulse =
				    (load(block.rhs) - applied * load(block.cfm)) - deltaVelocity(block, a, b) * load(block.jacDiagABInv);
				const Lanes clamped = select(
				    skipped, applied, maxBranchless(negate(bound), minBranchless(bound, applied + deltaImpulse)));
				deltaImpulse = clamped - applied;
				store(block.applied, clamped);
				applyImpulses(block, group, deltaImpulse, a, b);
				const Lanes squared = deltaImpulse * deltaImpulse;
				residual = residual + squared;
				storeImpulses(block, friction);
			}
		}
		scatterBodies(bodies, group.bodyA, a, fourthsA);
		scatterBodies(bodies, group.bodyB, b, fourthsB);
	}
	return horizontalSum(residual);
}
