// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_RAY_WALK_H
#define CALIBER_DBVT_RAY_WALK_H

// Internal: the ray walk of btDbvtBroadphase::rayTest. Unlike btDbvt::rayTestInternal (Bullet's API, which
// takes the ray's length by value) it reads the length bound again at every box, so a closest-hit query
// that shortens the ray prunes the subtrees beyond its closest hit so far, and it opens the nearer child
// first, so that the closest hit tends to be found first and to prune the most.

#include "BulletCollision/BroadphaseCollision/RaySlabTest.h"
#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "LinearMath/btAabbUtil2.h"

namespace caliber
{
/// A ray rayFrom + t (rayTo - rayFrom) against tree boxes grown by a swept box [sweptMin, sweptMax].
struct DbvtRay
{
	/// The ray's start.
	btVector3 from;
	/// 1 / (rayTo - rayFrom) per axis (BT_LARGE_FLOAT or infinite where the direction is 0).
	btVector3 directionInverse;
	/// signs[axis] = directionInverse[axis] < 0.
	unsigned int signs[3];
	/// The swept box's corners (0 for a ray).
	btVector3 sweptMin;
	/// See sweptMin.
	btVector3 sweptMax;

#ifdef BT_USE_SSE
	/// All ones in the lanes of the axes with signs[axis] set (filled by prepare()).
	__m128 negativeMask;
#endif
	/// False when the swept box is a point (every coordinate 0, of either sign; filled by prepare()).
	bool swept;

	/// Call once the fields are set, before hits().
	void prepare()
	{
#ifdef BT_USE_SSE
		negativeMask = raySlabNegativeMask(signs[0] != 0, signs[1] != 0, signs[2] != 0);
#endif
		swept = false;
		for (int a = 0; a < 3; ++a)
			if (sweptMin[a] != btScalar(0) || sweptMax[a] != btScalar(0)) swept = true;
	}

	/// btRayAabb2 against [boxMin - sweptMax, boxMax - sweptMin] with t in [0, lambdaMax]; enter is the
	/// entry parameter on a hit. The SSE path performs btRayAabb2's operations lane by lane (the same t for
	/// every plane, a NaN plane ignored as btRayAabb2 ignores it), so both give the same answer.
	SIMD_FORCE_INLINE bool hits(const btVector3& boxMin, const btVector3& boxMax, btScalar lambdaMax,
	                            btScalar& enter) const
	{
#ifdef BT_USE_SSE
		const __m128 start = from.get128();
		const __m128 inverse = directionInverse.get128();
		const __m128 tLow = _mm_mul_ps(_mm_sub_ps(_mm_sub_ps(boxMin.get128(), sweptMax.get128()), start), inverse);
		const __m128 tHigh = _mm_mul_ps(_mm_sub_ps(_mm_sub_ps(boxMax.get128(), sweptMin.get128()), start), inverse);
		return raySlabHits(tLow, tHigh, negativeMask, lambdaMax, enter);
#else
		const btVector3 bounds[2] = {boxMin - sweptMax, boxMax - sweptMin};
		return btRayAabb2(from, directionInverse, signs, bounds, enter, btScalar(0), lambdaMax);
#endif
	}

	/// hits() of two boxes at once. Swept false (the swept box a point): the box is not grown, which changes
	/// a plane's t at most in the sign of a zero (box - 0 is box but for a -0 coordinate, then +0), which
	/// neither the answer nor the entry (at least +0) sees.
	template <bool Swept>
	SIMD_FORCE_INLINE void hitsBoth(const btDbvtNode* a, const btDbvtNode* b, btScalar lambdaMax, btScalar& enterA,
	                                btScalar& enterB, bool& hitA, bool& hitB) const
	{
#ifdef BT_USE_SSE
		const __m128 start = from.get128();
		const __m128 inverse = directionInverse.get128();
		__m128 lowA = a->volume.Mins().get128(), highA = a->volume.Maxs().get128();
		__m128 lowB = b->volume.Mins().get128(), highB = b->volume.Maxs().get128();
		if (Swept)
		{
			lowA = _mm_sub_ps(lowA, sweptMax.get128());
			highA = _mm_sub_ps(highA, sweptMin.get128());
			lowB = _mm_sub_ps(lowB, sweptMax.get128());
			highB = _mm_sub_ps(highB, sweptMin.get128());
		}
		const __m128 tLowA = _mm_mul_ps(_mm_sub_ps(lowA, start), inverse);
		const __m128 tHighA = _mm_mul_ps(_mm_sub_ps(highA, start), inverse);
		const __m128 tLowB = _mm_mul_ps(_mm_sub_ps(lowB, start), inverse);
		const __m128 tHighB = _mm_mul_ps(_mm_sub_ps(highB, start), inverse);
		raySlabHitsBoth(tLowA, tHighA, tLowB, tHighB, negativeMask, lambdaMax, enterA, enterB, hitA, hitB);
#else
		hitA = hits(a->volume.Mins(), a->volume.Maxs(), lambdaMax, enterA);
		hitB = hits(b->volume.Mins(), b->volume.Maxs(), lambdaMax, enterB);
#endif
	}
};

/// Visits, nearer boxes first, the leaves of the trees rooted at roots[0 .. rootCount) whose boxes the ray
/// reaches within *lambdaMax, calling visitLeaf(leaf) for each. *lambdaMax is read again before every box
/// is opened, so visitLeaf may lower it. The set of leaves visited is that of btDbvt::rayTestInternal
/// with the bound as it stands when each leaf is reached (a leaf's box lies inside its parents' boxes, and
/// the slab test's rounding is monotone in the box, so no leaf the bound admits is pruned above it); only
/// the order differs. A stack on the C++ stack: queries may run on several threads at once.
template <bool Swept, class LeafVisitor>
void walkDbvtRayNearestFirstOf(const btDbvtNode* const* roots, int rootCount, const DbvtRay& ray,
                               const btScalar* lambdaMax, LeafVisitor& visitLeaf)
{
	struct Entry
	{
		const btDbvtNode* node;
		btScalar enter;
	};
	DbvtLocalStack<Entry, 64> stack;
	// Pushes the boxes that are hit, the farther first, so that the nearer is opened first; equal entries
	// keep the given order (a first, as rayTestInternal and the trees' other walks do).
	auto pushPair = [&](const btDbvtNode* a, const btDbvtNode* b) {
		Entry ea = {a, btScalar(0)}, eb = {b, btScalar(0)};
		const bool hitA = a && ray.hits(a->volume.Mins(), a->volume.Maxs(), *lambdaMax, ea.enter);
		const bool hitB = b && ray.hits(b->volume.Mins(), b->volume.Maxs(), *lambdaMax, eb.enter);
		if (hitA && hitB)
		{
			if (eb.enter < ea.enter)
			{
				stack.push(ea);
				stack.push(eb);
			}
			else
			{
				stack.push(eb);
				stack.push(ea);
			}
		}
		else if (hitA)
			stack.push(ea);
		else if (hitB)
			stack.push(eb);
	};
	for (int r = 0; r < rootCount; r += 2) pushPair(roots[r], r + 1 < rootCount ? roots[r + 1] : 0);
	while (!stack.empty())
	{
		Entry entry = stack.pop();
		// Of two children that are hit the farther is pushed and the nearer opened at once: the order of
		// pushing both and popping the nearer.
		for (;;)
		{
			if (entry.enter > *lambdaMax) break;  // the bound shrank below this box since it was pushed
			const btDbvtNode* node = entry.node;
			if (!node->isinternal())
			{
				visitLeaf(node);
				break;
			}
			const btDbvtNode* a = node->childs[0];
			const btDbvtNode* b = node->childs[1];  // an internal node has both children
			Entry ea = {a, btScalar(0)}, eb = {b, btScalar(0)};
			bool hitA, hitB;
			ray.template hitsBoth<Swept>(a, b, *lambdaMax, ea.enter, eb.enter, hitA, hitB);
			if (hitA && hitB)
			{
				if (eb.enter < ea.enter)
				{
					stack.push(ea);
					entry = eb;
				}
				else
				{
					stack.push(eb);
					entry = ea;
				}
			}
			else if (hitA)
				entry = ea;
			else if (hitB)
				entry = eb;
			else
				break;
		}
	}
}
/// Visits, nearer boxes first, the leaves of the trees rooted at roots[0 .. rootCount) whose boxes the ray
/// reaches within *lambdaMax (see walkDbvtRayNearestFirstOf).
template <class LeafVisitor>
void walkDbvtRayNearestFirst(const btDbvtNode* const* roots, int rootCount, const DbvtRay& ray,
                             const btScalar* lambdaMax, LeafVisitor& visitLeaf)
{
	if (ray.swept)
		walkDbvtRayNearestFirstOf<true>(roots, rootCount, ray, lambdaMax, visitLeaf);
	else
		walkDbvtRayNearestFirstOf<false>(roots, rootCount, ray, lambdaMax, visitLeaf);
}
}  // namespace caliber

#endif  // CALIBER_DBVT_RAY_WALK_H
