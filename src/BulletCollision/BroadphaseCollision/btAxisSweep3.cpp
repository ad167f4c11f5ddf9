// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/BroadphaseCollision/btAxisSweep3.h"

// Grids: 16 bits gives 65,534 cells per axis, 32 bits about 4.3 billion; the top value is the sentinel.
btAxisSweep3::btAxisSweep3(const btVector3& worldAabbMin, const btVector3& worldAabbMax, unsigned short int maxHandles,
                           btOverlappingPairCache* pairCache, bool disableRaycastAccelerator)
    : btAxisSweep3Internal<unsigned short int>(worldAabbMin, worldAabbMax, 0xfffe, 0xffff, maxHandles, pairCache,
                                               disableRaycastAccelerator)
{
}

bt32BitAxisSweep3::bt32BitAxisSweep3(const btVector3& worldAabbMin, const btVector3& worldAabbMax,
                                     unsigned int maxHandles, btOverlappingPairCache* pairCache,
                                     bool disableRaycastAccelerator)
    : btAxisSweep3Internal<unsigned int>(worldAabbMin, worldAabbMax, 0xfffffffeu, 0xffffffffu, maxHandles, pairCache,
                                         disableRaycastAccelerator)
{
}
