// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletSoftBody/btSoftBodyConcaveCollisionAlgorithm.h"

#include "btSoftBodyInternal.h"

btSoftBodyConcaveCollisionAlgorithm::btSoftBodyConcaveCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                                                         const btCollisionObjectWrapper* body0Wrap,
                                                                         const btCollisionObjectWrapper* body1Wrap,
                                                                         bool isSwapped)
    : btCollisionAlgorithm(ci), m_isSwapped(isSwapped)
{
	(void)body0Wrap;
	(void)body1Wrap;
}

btSoftBodyConcaveCollisionAlgorithm::~btSoftBodyConcaveCollisionAlgorithm() {}

void btSoftBodyConcaveCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                           const btCollisionObjectWrapper* body1Wrap,
                                                           const btDispatcherInfo& dispatchInfo,
                                                           btManifoldResult* resultOut)
{
	(void)dispatchInfo;
	(void)resultOut;
	// The soft-rigid path measures concave shapes triangle by triangle (nearest triangle within reach).
	caliber::collideSoftRigidPair(body0Wrap, body1Wrap);
}

btScalar btSoftBodyConcaveCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
                                                                    const btDispatcherInfo& dispatchInfo,
                                                                    btManifoldResult* resultOut)
{
	(void)body0;
	(void)body1;
	(void)dispatchInfo;
	(void)resultOut;
	return 1;
}
