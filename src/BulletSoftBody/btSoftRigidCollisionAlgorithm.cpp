// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletSoftBody/btSoftRigidCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletSoftBody/btSoftBody.h"
#include "BulletSoftBody/btSoftBodySolvers.h"
#include "btSoftBodyInternal.h"

btSoftRigidCollisionAlgorithm::btSoftRigidCollisionAlgorithm(btPersistentManifold* mf,
                                                             const btCollisionAlgorithmConstructionInfo& ci,
                                                             const btCollisionObjectWrapper* col0,
                                                             const btCollisionObjectWrapper* col1Wrap, bool isSwapped)
    : btCollisionAlgorithm(ci), m_softBody(0), m_rigidCollisionObject(0), m_isSwapped(isSwapped)
{
	(void)mf;
	(void)col0;
	(void)col1Wrap;
}

btSoftRigidCollisionAlgorithm::~btSoftRigidCollisionAlgorithm() {}

void btSoftRigidCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                     const btCollisionObjectWrapper* body1Wrap,
                                                     const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut)
{
	(void)dispatchInfo;
	(void)resultOut;
	btCollisionObject* rigid = 0;
	m_softBody = caliber::collideSoftRigidPair(body0Wrap, body1Wrap, &rigid);
	m_rigidCollisionObject = rigid;
}

btSoftBody* caliber::collideSoftRigidPair(const btCollisionObjectWrapper* body0Wrap,
                                          const btCollisionObjectWrapper* body1Wrap, btCollisionObject** rigidOut)
{
	// Which side is soft is read from the objects, whatever order the dispatcher passes them in.
	const btCollisionObjectWrapper* softWrap = body0Wrap;
	const btCollisionObjectWrapper* rigidWrap = body1Wrap;
	if (!btSoftBody::upcast(body0Wrap->getCollisionObject()))
	{
		softWrap = body1Wrap;
		rigidWrap = body0Wrap;
	}
	btSoftBody* soft = const_cast<btSoftBody*>(btSoftBody::upcast(softWrap->getCollisionObject()));
	if (!soft || btSoftBody::upcast(rigidWrap->getCollisionObject())) return 0;
	btCollisionObject* rigid = const_cast<btCollisionObject*>(rigidWrap->getCollisionObject());
	if (rigidOut) *rigidOut = rigid;
	if (soft->m_collisionDisabledObjects.findLinearSearch(rigid) != soft->m_collisionDisabledObjects.size())
		return soft;
	if (soft->getSoftBodySolver())
		soft->getSoftBodySolver()->processCollision(soft, rigidWrap);
	else
		soft->defaultCollisionHandler(rigidWrap);
	return soft;
}

btScalar btSoftRigidCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
                                                              const btDispatcherInfo& dispatchInfo,
                                                              btManifoldResult* resultOut)
{
	(void)body0;
	(void)body1;
	(void)dispatchInfo;
	(void)resultOut;
	return 1;
}
