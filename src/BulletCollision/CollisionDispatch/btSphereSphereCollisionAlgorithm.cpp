// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btSphereSphereCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"

btSphereSphereCollisionAlgorithm::btSphereSphereCollisionAlgorithm(btPersistentManifold* mf,
                                                                   const btCollisionAlgorithmConstructionInfo& ci,
                                                                   const btCollisionObjectWrapper* body0Wrap,
                                                                   const btCollisionObjectWrapper* body1Wrap)
    : btActivatingCollisionAlgorithm(ci, body0Wrap, body1Wrap), m_ownManifold(false), m_manifoldPtr(mf)
{
	if (!m_manifoldPtr && m_dispatcher &&
	    m_dispatcher->needsCollision(body0Wrap->getCollisionObject(), body1Wrap->getCollisionObject()))
	{
		m_manifoldPtr = m_dispatcher->getNewManifold(body0Wrap->getCollisionObject(), body1Wrap->getCollisionObject());
		m_ownManifold = true;
	}
}

btSphereSphereCollisionAlgorithm::~btSphereSphereCollisionAlgorithm()
{
	if (m_ownManifold && m_manifoldPtr) m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btSphereSphereCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                        const btCollisionObjectWrapper* body1Wrap,
                                                        const btDispatcherInfo&, btManifoldResult* resultOut)
{
	if (!m_manifoldPtr || !resultOut) return;
	resultOut->setPersistentManifold(m_manifoldPtr);
	if (!caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}

	const btSphereShape* sphere0 = static_cast<const btSphereShape*>(body0Wrap->getCollisionShape());
	const btSphereShape* sphere1 = static_cast<const btSphereShape*>(body1Wrap->getCollisionShape());
	const btVector3 diff = body0Wrap->getWorldTransform().getOrigin() - body1Wrap->getWorldTransform().getOrigin();
	const btScalar radius0 = sphere0->getRadius();
	const btScalar radius1 = sphere1->getRadius();
	const btScalar centreDistance = diff.length();

	const btScalar reach =
	    radius0 + radius1 + m_manifoldPtr->getContactBreakingThreshold() + resultOut->m_closestPointDistanceThreshold;
	if (centreDistance > reach)
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}

	// Concentric spheres have no preferred direction; any unit normal gives the right depth.
	const btVector3 normalOnB =
	    centreDistance > SIMD_EPSILON ? diff / centreDistance : btVector3(btScalar(1), btScalar(0), btScalar(0));
	const btVector3 pointOnB = body1Wrap->getWorldTransform().getOrigin() + normalOnB * radius1;
	const int countBefore = m_manifoldPtr->getNumContacts();
	resultOut->addContactPoint(normalOnB, pointOnB, centreDistance - radius0 - radius1);
	if (m_ownManifold)
	{
		caliber::keepOnlyNewestPoint(m_manifoldPtr, countBefore);
		// Ages the point (lifetime) and reports it to gContactProcessedCallback, as for every other shape.
		resultOut->refreshContactPoints();
	}
}

btScalar btSphereSphereCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                                 const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}

void btSphereSphereCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifoldArray)
{
	if (m_manifoldPtr && m_ownManifold) manifoldArray.push_back(m_manifoldPtr);
}
