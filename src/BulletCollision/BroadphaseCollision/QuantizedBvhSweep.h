// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_QUANTIZED_BVH_SWEEP_H
#define CALIBER_QUANTIZED_BVH_SWEEP_H

// Internal: the moving box of btQuantizedBvh's ray and box-cast walks (btQuantizedBvh.cpp walks the tree in
// Bullet's order, btQuantizedBvhRayWalk.cpp nearer child first), and the tolerance both grow the tree's
// boxes by.

#include "BulletCollision/BroadphaseCollision/btQuantizedBvh.h"

namespace caliber
{
/// A moving box (or a point when boxMin == boxMax == 0): the segment source + t * dir, t in [0, 1],
/// against node boxes grown by the moving box and by a tolerance.
struct BvhSweep
{
	/// The segment's start.
	btVector3 source;
	/// target - source.
	btVector3 dir;
	/// 1 / dir per axis, 0 where dir is 0.
	btVector3 inv;
	/// Subtracted from node minima: boxMax + tolerance.
	btVector3 growMin;
	/// Added to node maxima: -boxMin + tolerance.
	btVector3 growMax;
	/// The box the whole sweep covers, grown by the tolerance.
	btVector3 sweepMin;
	/// See sweepMin.
	btVector3 sweepMax;
	/// The bound on t, read at every box (null: 1).
	const btScalar* maxFraction;

	/// The largest t a box may be entered at and still count: *maxFraction (plus the rounding of the
	/// fraction itself, which the boxes' tolerance does not cover) when it is below 1, else 1.
	btScalar exitBound() const
	{
		if (maxFraction && *maxFraction < btScalar(1)) return *maxFraction + btScalar(1e-5);
		return btScalar(1);
	}

	/// True when the sweep reaches [nodeMin, nodeMax] (grown) for some t in [0, exitBound()].
	bool hits(const btVector3& nodeMin, const btVector3& nodeMax) const
	{
		btScalar tEnter = 0, tExit = exitBound();
		for (int a = 0; a < 3; ++a)
		{
			const btScalar lo = nodeMin[a] - growMin[a];
			const btScalar hi = nodeMax[a] + growMax[a];
			if (dir[a] == btScalar(0))
			{
				if (source[a] < lo || source[a] > hi) return false;
				continue;
			}
			btScalar t0 = (lo - source[a]) * inv[a];
			btScalar t1 = (hi - source[a]) * inv[a];
			if (inv[a] < 0) btSwap(t0, t1);
			// Written so that a NaN (0 * inf for a denormal direction on a box face) is ignored.
			if (t0 > tEnter) tEnter = t0;
			if (t1 < tExit) tExit = t1;
			if (tEnter > tExit) return false;
		}
		return true;
	}
};

/// Sets up the sweep of the box [aabbMin, aabbMax] from raySource to rayTarget against bvh (quantized or
/// not). The tolerance (64 ulps of the largest coordinate involved: the ray, the box and the tree's root
/// box) covers the rounding of t and of the node bounds, so a segment exactly on a box face (a flat
/// triangle's box) is not missed.
void setUpBvhSweep(const btQuantizedBvh& bvh, const btVector3& raySource, const btVector3& rayTarget,
                   const btVector3& aabbMin, const btVector3& aabbMax, const btScalar* maxFraction, BvhSweep& sweep);
}  // namespace caliber

#endif  // CALIBER_QUANTIZED_BVH_SWEEP_H
