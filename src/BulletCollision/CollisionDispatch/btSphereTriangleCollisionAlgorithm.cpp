// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btSphereTriangleCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/SphereTriangleDetector.h"
#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"

btSphereTriangleCollisionAlgorithm::btSphereTriangleCollisionAlgorithm(btPersistentManifold* mf,
                                                                       const btCollisionAlgorithmConstructionInfo& ci,
                                                                       const btCollisionObjectWrapper* body0Wrap,
                                                                       const btCollisionObjectWrapper* body1Wrap,
                                                                       bool swapped)
    : btActivatingCollisionAlgorithm(ci, body0Wrap, body1Wrap),
      m_ownManifold(false),
      m_manifoldPtr(mf),
      m_swapped(swapped)
{
	if (!m_manifoldPtr && m_dispatcher &&
	    m_dispatcher->needsCollision(body0Wrap->getCollisionObject(), body1Wrap->getCollisionObject()))
	{
		m_manifoldPtr = m_dispatcher->getNewManifold(body0Wrap->getCollisionObject(), body1Wrap->getCollisionObject());
		m_ownManifold = true;
	}
}

btSphereTriangleCollisionAlgorithm::~btSphereTriangleCollisionAlgorithm()
{
	if (m_ownManifold && m_manifoldPtr) m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btSphereTriangleCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                          const btCollisionObjectWrapper* body1Wrap,
                                                          const btDispatcherInfo& dispatchInfo,
                                                          btManifoldResult* resultOut)
{
	if (!m_manifoldPtr || !resultOut) return;
	resultOut->setPersistentManifold(m_manifoldPtr);
	if (!caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}
	const btCollisionObjectWrapper* sphereWrap = m_swapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* triangleWrap = m_swapped ? body0Wrap : body1Wrap;
	// The detector's API takes non-const shapes but only reads them.
	btSphereShape* sphere =
	    const_cast<btSphereShape*>(static_cast<const btSphereShape*>(sphereWrap->getCollisionShape()));
	btTriangleShape* triangle =
	    const_cast<btTriangleShape*>(static_cast<const btTriangleShape*>(triangleWrap->getCollisionShape()));

	SphereTriangleDetector detector(
	    sphere, triangle, m_manifoldPtr->getContactBreakingThreshold() + resultOut->m_closestPointDistanceThreshold);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_maximumDistanceSquared = btScalar(BT_LARGE_FLOAT);
	input.m_transformA = sphereWrap->getWorldTransform();
	input.m_transformB = triangleWrap->getWorldTransform();

	const int countBefore = m_manifoldPtr->getNumContacts();
	detector.getClosestPoints(input, *resultOut, dispatchInfo.m_debugDraw, m_swapped);
	if (m_ownManifold)
	{
		if (m_manifoldPtr->getNumContacts() == countBefore && countBefore > 0)
			resultOut->refreshContactPoints();  // nothing new: drop what separated
		else
			caliber::keepOnlyNewestPoint(m_manifoldPtr, countBefore);
	}
}

btScalar btSphereTriangleCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                                   const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}

void btSphereTriangleCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifoldArray)
{
	if (m_manifoldPtr && m_ownManifold) manifoldArray.push_back(m_manifoldPtr);
}
