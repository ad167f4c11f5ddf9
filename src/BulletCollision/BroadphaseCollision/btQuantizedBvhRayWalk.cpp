// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The closest-hit walk of a btQuantizedBvh (caliber::reportBoxCastOverlappingNodes with a fraction bound):
// the nearer child first, each box tested against the bound as it stands when the box is opened, so that the
// closest hit tends to be found early and prunes the rest of the tree. A quantized tree is tested in its
// own integer frame, where the node bounds need no conversion back to the mesh's frame.

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhCast.h"
#include "BulletCollision/BroadphaseCollision/QuantizedBvhSweep.h"
#include "BulletCollision/BroadphaseCollision/RaySlabTest.h"
#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "LinearMath/btAabbUtil2.h"

namespace
{
// The sweep in a quantized tree's frame, q(p) = (p - bvhMin) * quantization (per axis, so t is unchanged).
// A node's integer bounds lo, hi are grown to lo - growMin and hi + growMax; the tests below use
// nearStart = source + growMin and farStart = source - growMax, so that t = (lo - nearStart) * inverse.
// The rounding of this frame change is a fraction of an ulp of the coordinates, far inside the sweep's
// tolerance (64 ulps of the largest coordinate, see setUpBvhSweep).
struct QuantizedSweep
{
	btVector3 nearStart;
	btVector3 farStart;
	// 1 / (dir * quantization). On an axis the segment does not move along (a direction of 0, or so small that
	// its inverse is not finite) it is BT_LARGE_FLOAT and that axis's slab is grown by one more unit: a start
	// inside the slab then gives t below -BT_LARGE_FLOAT on the low plane and above BT_LARGE_FLOAT on the
	// high one (no constraint), a start outside gives two hugely negative or two hugely positive t (a miss),
	// and never 0 * inf = NaN.
	btVector3 inverse;
	bool negative[3];
	// nearStart >= farStart on every axis (a ray, or a cast box with min <= max): hitsQuantizedNode applies.
	bool ordered;
#ifdef BT_USE_SSE
	__m128 negativeMask;
#endif
};

QuantizedSweep quantizeSweep(const btQuantizedBvh& bvh, const caliber::BvhSweep& sweep)
{
	const btVector3& quantization = caliber::bvhQuantization(bvh);
	const btVector3 source = (sweep.source - caliber::bvhAabbMin(bvh)) * quantization;
	QuantizedSweep q;
	q.nearStart = source + sweep.growMin * quantization;
	q.farStart = source - sweep.growMax * quantization;
	const btVector3 dir = sweep.dir * quantization;
	for (int a = 0; a < 3; ++a)
	{
		const btScalar inverse = dir[a] != btScalar(0) ? btScalar(1) / dir[a] : btScalar(0);
		if (dir[a] != btScalar(0) && btFabs(inverse) < btScalar(BT_LARGE_FLOAT))
		{
			q.inverse[a] = inverse;
		}
		else
		{
			q.inverse[a] = btScalar(BT_LARGE_FLOAT);
			q.nearStart[a] += btScalar(1);
			q.farStart[a] -= btScalar(1);
		}
		q.negative[a] = q.inverse[a] < btScalar(0);
	}
	q.ordered = q.nearStart.x() >= q.farStart.x() && q.nearStart.y() >= q.farStart.y() &&
	            q.nearStart.z() >= q.farStart.z();
#ifdef BT_USE_SSE
	q.negativeMask = caliber::raySlabNegativeMask(q.negative[0], q.negative[1], q.negative[2]);
#endif
	return q;
}

// The slab test of one quantized node against the sweep with t in [0, exitBound]; enter is the entry t.
#ifdef BT_USE_SSE
// Lanes x, y, z (lane w is not used): entries, the entry t of each axis's slab, at least 0, and exits, the exit
// t, at most bound (exitBound in every lane).
SIMD_FORCE_INLINE void quantizedNodeSlabs(const QuantizedSweep& q, const btQuantizedBvhNode& node, __m128 bound,
                                          __m128& entries, __m128& exits)
{
	// The node's 16 bytes: min x, y, z, max x, y, z (unsigned 16-bit) and the escape or triangle index. The
	// maxima are read from the bytes shifted down by three 16-bit lanes, so each lands in its axis's lane.
	const __m128i raw = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&node));
	const __m128i zero = _mm_setzero_si128();
	const __m128 minima = _mm_cvtepi32_ps(_mm_unpacklo_epi16(raw, zero));                      // x, y, z, max x
	const __m128 maxima = _mm_cvtepi32_ps(_mm_unpacklo_epi16(_mm_srli_si128(raw, 6), zero));  // x, y, z, index
	const __m128 inverse = q.inverse.get128();
	const __m128 tLow = _mm_mul_ps(_mm_sub_ps(minima, q.nearStart.get128()), inverse);
	const __m128 tHigh = _mm_mul_ps(_mm_sub_ps(maxima, q.farStart.get128()), inverse);
	// Neither is NaN (the inverse is finite and not 0, the differences are finite), and with nearStart >=
	// farStart (quantizeSweep checks it, else the general test is used) and min <= max the exact difference
	// on the low plane is at most that on the high plane; rounding and then multiplying keep that order
	// (reversed for a negative inverse), so the smaller is the near plane's t and the larger the far plane's:
	// the values the direction's sign would pick (two equal values are the same bits: a difference of 0 is
	// +0 in both).
	entries = _mm_max_ps(_mm_min_ps(tLow, tHigh), _mm_setzero_ps());
	exits = _mm_min_ps(_mm_max_ps(tLow, tHigh), bound);
}

SIMD_FORCE_INLINE bool hitsQuantizedNode(const QuantizedSweep& q, const btQuantizedBvhNode& node, btScalar exitBound,
                                         btScalar& enter)
{
	__m128 entries, exits;
	quantizedNodeSlabs(q, node, _mm_set1_ps(exitBound), entries, exits);
	const __m128 enterXYZ = _mm_max_ss(_mm_max_ss(entries, CALIBER_SPLAT(entries, 1)), CALIBER_SPLAT(entries, 2));
	const __m128 exitXYZ = _mm_min_ss(_mm_min_ss(exits, CALIBER_SPLAT(exits, 1)), CALIBER_SPLAT(exits, 2));
	enter = _mm_cvtss_f32(enterXYZ);
	return _mm_comile_ss(enterXYZ, exitXYZ) != 0;
}

// hitsQuantizedNode of two nodes at once, the three-axis reductions of both done side by side. The entries
// are never NaN nor -0 (max with +0 returns +0 for -0), so their maximum does not depend on the order the axes
// are taken in; the exits are never NaN, and their minimum may differ only in the sign of a zero, which the
// comparison does not see.
SIMD_FORCE_INLINE void hitsQuantizedNodes(const QuantizedSweep& q, const btQuantizedBvhNode& a,
                                          const btQuantizedBvhNode& b, btScalar exitBound, btScalar& enterA,
                                          btScalar& enterB, bool& hitA, bool& hitB)
{
	const __m128 bound = _mm_set1_ps(exitBound);
	__m128 entriesA, exitsA, entriesB, exitsB;
	quantizedNodeSlabs(q, a, bound, entriesA, exitsA);
	quantizedNodeSlabs(q, b, bound, entriesB, exitsB);
	caliber::reduceSlabsOfTwoBoxes(entriesA, exitsA, entriesB, exitsB, enterA, enterB, hitA, hitB);
}

// The general test (the near and far planes picked by the direction's signs), for a sweep whose grown box
// is inverted (nearStart below farStart on some axis: a cast box with a minimum above its maximum).
SIMD_FORCE_INLINE bool hitsQuantizedNodeBySign(const QuantizedSweep& q, const btQuantizedBvhNode& node,
                                               btScalar exitBound, btScalar& enter)
{
	const __m128i raw = _mm_loadu_si128(reinterpret_cast<const __m128i*>(&node));
	const __m128i zero = _mm_setzero_si128();
	const __m128 minima = _mm_cvtepi32_ps(_mm_unpacklo_epi16(raw, zero));
	const __m128 maxima = _mm_cvtepi32_ps(_mm_unpacklo_epi16(_mm_srli_si128(raw, 6), zero));
	const __m128 inverse = q.inverse.get128();
	const __m128 tLow = _mm_mul_ps(_mm_sub_ps(minima, q.nearStart.get128()), inverse);
	const __m128 tHigh = _mm_mul_ps(_mm_sub_ps(maxima, q.farStart.get128()), inverse);
	return caliber::raySlabHits(tLow, tHigh, q.negativeMask, exitBound, enter);
}
#else
SIMD_FORCE_INLINE bool hitsQuantizedNode(const QuantizedSweep& q, const btQuantizedBvhNode& node, btScalar exitBound,
                                         btScalar& enter)
{
	btScalar tEnter = btScalar(0), tExit = exitBound;
	for (int a = 0; a < 3; ++a)
	{
		const btScalar tLow = (btScalar(node.m_quantizedAabbMin[a]) - q.nearStart[a]) * q.inverse[a];
		const btScalar tHigh = (btScalar(node.m_quantizedAabbMax[a]) - q.farStart[a]) * q.inverse[a];
		const btScalar tNear = q.negative[a] ? tHigh : tLow;
		const btScalar tFar = q.negative[a] ? tLow : tHigh;
		tEnter = btMax(tEnter, tNear);
		tExit = btMin(tExit, tFar);
	}
	enter = tEnter;
	return tEnter <= tExit;
}

SIMD_FORCE_INLINE bool hitsQuantizedNodeBySign(const QuantizedSweep& q, const btQuantizedBvhNode& node,
                                               btScalar exitBound, btScalar& enter)
{
	return hitsQuantizedNode(q, node, exitBound, enter);
}

SIMD_FORCE_INLINE void hitsQuantizedNodes(const QuantizedSweep& q, const btQuantizedBvhNode& a,
                                          const btQuantizedBvhNode& b, btScalar exitBound, btScalar& enterA,
                                          btScalar& enterB, bool& hitA, bool& hitB)
{
	hitA = hitsQuantizedNode(q, a, exitBound, enterA);
	hitB = hitsQuantizedNode(q, b, exitBound, enterB);
}
#endif

struct NodeEntry
{
	int node;
	btScalar enter;
};

// Walks the tree from its root, nearer child first. Tree: isLeaf(i), subtreeSize(i) (1 for a leaf),
// hits(i, exitBound, enter) and hitsBoth(i, j, ...) (hits of both); report(i) hands a leaf to the callback. Of
// two children that are hit the farther is pushed and the nearer opened at once (the order of a stack that
// pushed both and popped the nearer).
template <class Tree>
void walkNearestFirst(const Tree& tree, const caliber::BvhSweep& sweep)
{
	caliber::DbvtLocalStack<NodeEntry, 64> stack;
	// Only report() can lower the bound (through the callback's fraction): it is read again after each.
	btScalar exitBound = sweep.exitBound();
	NodeEntry entry = {0, btScalar(0)};
	if (!tree.hits(0, exitBound, entry.enter)) return;
	for (;;)
	{
		// Skipped when the bound shrank below this box since it was pushed.
		if (!(entry.enter > exitBound))
		{
			if (tree.isLeaf(entry.node))
			{
				tree.report(entry.node);
				exitBound = sweep.exitBound();
			}
			else
			{
				const int left = entry.node + 1;
				const int right = left + tree.subtreeSize(left);
				NodeEntry l = {left, btScalar(0)}, r = {right, btScalar(0)};
				bool hitLeft, hitRight;
				if (right < tree.count)
					tree.hitsBoth(left, right, exitBound, l.enter, r.enter, hitLeft, hitRight);
				else
				{
					hitLeft = tree.hits(left, exitBound, l.enter);
					hitRight = false;
				}
				// On a tie the left child is opened first, as in Bullet's walk.
				if (hitLeft && hitRight)
				{
					if (r.enter < l.enter)
					{
						stack.push(l);
						entry = r;
					}
					else
					{
						stack.push(r);
						entry = l;
					}
					continue;
				}
				if (hitLeft)
				{
					entry = l;
					continue;
				}
				if (hitRight)
				{
					entry = r;
					continue;
				}
			}
		}
		if (stack.empty()) return;
		entry = stack.pop();
	}
}

// BySign: the general node test (for an inverted cast box), else the one that needs nearStart >= farStart.
template <bool BySign>
struct QuantizedTree
{
	const btQuantizedBvhNode* nodes;
	int count;
	QuantizedSweep sweep;
	btNodeOverlapCallback* callback;

	bool isLeaf(int i) const { return nodes[i].isLeafNode(); }
	int subtreeSize(int i) const { return nodes[i].isLeafNode() ? 1 : nodes[i].getEscapeIndex(); }
	bool hits(int i, btScalar exitBound, btScalar& enter) const
	{
		return BySign ? hitsQuantizedNodeBySign(sweep, nodes[i], exitBound, enter)
		              : hitsQuantizedNode(sweep, nodes[i], exitBound, enter);
	}
	void hitsBoth(int i, int j, btScalar exitBound, btScalar& enterI, btScalar& enterJ, bool& hitI, bool& hitJ) const
	{
		if (BySign)
		{
			hitI = hitsQuantizedNodeBySign(sweep, nodes[i], exitBound, enterI);
			hitJ = hitsQuantizedNodeBySign(sweep, nodes[j], exitBound, enterJ);
		}
		else
			hitsQuantizedNodes(sweep, nodes[i], nodes[j], exitBound, enterI, enterJ, hitI, hitJ);
	}
	void report(int i) const { callback->processNode(nodes[i].getPartId(), nodes[i].getTriangleIndex()); }
};

struct PlainTree
{
	const btOptimizedBvhNode* nodes;
	int count;
	const caliber::BvhSweep* sweep;
	btNodeOverlapCallback* callback;

	bool isLeaf(int i) const { return nodes[i].m_escapeIndex < 0; }
	int subtreeSize(int i) const { return nodes[i].m_escapeIndex < 0 ? 1 : nodes[i].m_escapeIndex; }
	bool hits(int i, btScalar exitBound, btScalar& enter) const
	{
		(void)exitBound;  // the sweep reads its bound itself
		enter = btScalar(0);
		const btVector3& lo = nodes[i].m_aabbMinOrg;
		const btVector3& hi = nodes[i].m_aabbMaxOrg;
		if (!TestAabbAgainstAabb2(sweep->sweepMin, sweep->sweepMax, lo, hi) || !sweep->hits(lo, hi)) return false;
		// The entry t orders the children only; the test above decides.
		for (int a = 0; a < 3; ++a)
		{
			if (sweep->dir[a] == btScalar(0)) continue;
			const btScalar t = ((sweep->inv[a] < 0 ? hi[a] + sweep->growMax[a] : lo[a] - sweep->growMin[a]) -
			                    sweep->source[a]) *
			                   sweep->inv[a];
			if (t > enter) enter = t;
		}
		return true;
	}
	void hitsBoth(int i, int j, btScalar exitBound, btScalar& enterI, btScalar& enterJ, bool& hitI, bool& hitJ) const
	{
		hitI = hits(i, exitBound, enterI);
		hitJ = hits(j, exitBound, enterJ);
	}
	void report(int i) const { callback->processNode(nodes[i].m_subPart, nodes[i].m_triangleIndex); }
};
}  // namespace

void caliber::reportBoxCastOverlappingNodesNearestFirst(const btQuantizedBvh& bvh, btNodeOverlapCallback* nodeCallback,
                                                        const btVector3& raySource, const btVector3& rayTarget,
                                                        const btVector3& aabbMin, const btVector3& aabbMax,
                                                        const btScalar* maxFraction)
{
	btAssert(nodeCallback != 0 && maxFraction != 0);
	const bool finite = caliber::isFinite(raySource) && caliber::isFinite(rayTarget) && caliber::isFinite(aabbMin) &&
	                    caliber::isFinite(aabbMax);
	btAssert(finite && "reportBoxCastOverlappingNodex: non-finite input");
	const int count = caliber::bvhNodeCount(bvh);
	if (!nodeCallback || !maxFraction || !finite || count == 0) return;
	BvhSweep sweep;
	setUpBvhSweep(bvh, raySource, rayTarget, aabbMin, aabbMax, maxFraction, sweep);
	if (bvh.isQuantized())
	{
		// The sweep's box outside the quantization box: nothing to find (and its clamped coordinates could
		// not be trusted).
		if (!TestAabbAgainstAabb2(sweep.sweepMin, sweep.sweepMax, caliber::bvhAabbMin(bvh), caliber::bvhAabbMax(bvh)))
			return;
		// Bullet declares only a non-const accessor of the quantized nodes; they are only read here.
		const btQuantizedBvhNode* nodes = &const_cast<btQuantizedBvh&>(bvh).getQuantizedNodeArray()[0];
		const QuantizedSweep quantized = quantizeSweep(bvh, sweep);
		if (quantized.ordered)
		{
			const QuantizedTree<false> tree = {nodes, count, quantized, nodeCallback};
			walkNearestFirst(tree, sweep);
		}
		else
		{
			const QuantizedTree<true> tree = {nodes, count, quantized, nodeCallback};
			walkNearestFirst(tree, sweep);
		}
		return;
	}
	PlainTree tree;
	tree.nodes = &caliber::bvhNodeArray(bvh)[0];
	tree.count = count;
	tree.sweep = &sweep;
	tree.callback = nodeCallback;
	walkNearestFirst(tree, sweep);
}
