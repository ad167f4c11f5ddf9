// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_AXIS_SWEEP_3_H
#define BT_AXIS_SWEEP_3_H

#include "BulletCollision/BroadphaseCollision/btAxisSweep3Internal.h"

/// Sweep and prune with 16-bit quantised bounds: up to 16383 boxes (default 16384 handles, one of them
/// the sentinel) in fixed world bounds; see btAxisSweep3Internal. Fast when most objects move little
/// each step; boxes outside the bounds are clamped to them (use btDbvtBroadphase for open worlds).
class btAxisSweep3 : public btAxisSweep3Internal<unsigned short int>
{
public:
	btAxisSweep3(const btVector3& worldAabbMin, const btVector3& worldAabbMax, unsigned short int maxHandles = 16384,
	             btOverlappingPairCache* pairCache = 0, bool disableRaycastAccelerator = false);
};

/// Sweep and prune with 32-bit quantised bounds: a finer grid and up to about 1.5 million boxes, at twice
/// the edge memory of btAxisSweep3.
class bt32BitAxisSweep3 : public btAxisSweep3Internal<unsigned int>
{
public:
	bt32BitAxisSweep3(const btVector3& worldAabbMin, const btVector3& worldAabbMax, unsigned int maxHandles = 1500000,
	                  btOverlappingPairCache* pairCache = 0, bool disableRaycastAccelerator = false);
};

#endif  // BT_AXIS_SWEEP_3_H
