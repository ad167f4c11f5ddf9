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

	/// Call once the fields are set, before hits().
	void prepare()
	{
#ifdef BT_USE_SSE
		negativeMask = raySlabNegativeMask(signs[0] != 0, signs[1] != 0, signs[2] != 0);
#endif
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
};

/// Visits, nearer boxes first, the leaves of the trees rooted at roots[0 .. rootCount) whose boxes the ray
/// reaches within *lambdaMax, calling visitLeaf(leaf) for each. *lambdaMax is read again before every box
/// is opened, so visitLeaf may lower it. The set of leaves visited is that of btDbvt::rayTestInternal
/// with the bound as it stands when each leaf is reached (a leaf's box lies inside its parents' boxes, and
/// the slab test's rounding is monotone in the box, so no leaf the bound admits is pruned above it); only
/// the order differs. A stack on the C++ stack: queries may run on several threads at once.
template <class LeafVisitor>
void walkDbvtRayNearestFirst(const btDbvtNode* const* roots, int rootCount, const DbvtRay& ray,
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
		const Entry entry = stack.pop();
		if (entry.enter > *lambdaMax) continue;  // the bound shrank below this box since it was pushed
		const btDbvtNode* node = entry.node;
		if (node->isinternal())
			pushPair(node->childs[0], node->childs[1]);
		else
			visitLeaf(node);
	}
}
}  // namespace caliber

#endif  // CALIBER_DBVT_RAY_WALK_H
