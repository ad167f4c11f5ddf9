// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h"

btActivatingCollisionAlgorithm::btActivatingCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci)
    : btCollisionAlgorithm(ci)
{
}

btActivatingCollisionAlgorithm::btActivatingCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                                               const btCollisionObjectWrapper*,
                                                               const btCollisionObjectWrapper*)
    : btCollisionAlgorithm(ci)
{
}

btActivatingCollisionAlgorithm::~btActivatingCollisionAlgorithm() {}
