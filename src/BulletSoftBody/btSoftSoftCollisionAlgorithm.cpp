// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletSoftBody/btSoftSoftCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletSoftBody/btSoftBody.h"
#include "BulletSoftBody/btSoftBodySolvers.h"

btSoftSoftCollisionAlgorithm::btSoftSoftCollisionAlgorithm(btPersistentManifold* mf,
                                                           const btCollisionAlgorithmConstructionInfo& ci,
                                                           const btCollisionObjectWrapper* body0Wrap,
                                                           const btCollisionObjectWrapper* body1Wrap)
    : btCollisionAlgorithm(ci), m_softBody0(0), m_softBody1(0)
{
	(void)mf;
	(void)body0Wrap;
	(void)body1Wrap;
}

btSoftSoftCollisionAlgorithm::~btSoftSoftCollisionAlgorithm() {}

void btSoftSoftCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                    const btCollisionObjectWrapper* body1Wrap,
                                                    const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut)
{
	(void)dispatchInfo;
	(void)resultOut;
	m_softBody0 = const_cast<btSoftBody*>(btSoftBody::upcast(body0Wrap->getCollisionObject()));
	m_softBody1 = const_cast<btSoftBody*>(btSoftBody::upcast(body1Wrap->getCollisionObject()));
	if (!m_softBody0 || !m_softBody1) return;
	if (m_softBody0->getSoftBodySolver())
		m_softBody0->getSoftBodySolver()->processCollision(m_softBody0, m_softBody1);
	else
		m_softBody0->defaultCollisionHandler(m_softBody1);
}

btScalar btSoftSoftCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
                                                             const btDispatcherInfo& dispatchInfo,
                                                             btManifoldResult* resultOut)
{
	(void)body0;
	(void)body1;
	(void)dispatchInfo;
	(void)resultOut;
	return 1;
}
