// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btBoxBoxCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/NarrowPhaseCollision/ManifoldPrefetch.h"
#include "BulletCollision/CollisionDispatch/btBoxBoxDetector.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionDispatch/btCachedCollisionAlgorithms.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"

#include "LinearMath/btMemberAccess.h"

#include <new>

CALIBER_MEMBER_ACCESS(BoxBoxManifold, btBoxBoxCollisionAlgorithm, btPersistentManifold*, m_manifoldPtr)
CALIBER_MEMBER_ACCESS(BoxBoxOwnsManifold, btBoxBoxCollisionAlgorithm, bool, m_ownManifold)

namespace caliber
{
void CachedBoxBoxAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                             const btCollisionObjectWrapper* body1Wrap,
                                             const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut)
{
	btPersistentManifold* manifold = this->*memberOf(BoxBoxManifold{});
	const btScalar cacheDistance = contactCacheDistance();
	if (manifold && resultOut && body0Wrap && body1Wrap &&
	    pairMayUseContactCache(this->*memberOf(BoxBoxOwnsManifold{}), body0Wrap, body1Wrap, cacheDistance) &&
	    slowEnoughForContactCache(resultOut->m_closestPointDistanceThreshold, cacheDistance))
	{
		const btVector3 half0 =
		    static_cast<const btBoxShape*>(body0Wrap->getCollisionShape())->getHalfExtentsWithMargin();
		const btVector3 half1 =
		    static_cast<const btBoxShape*>(body1Wrap->getCollisionShape())->getHalfExtentsWithMargin();
		const PairShapes shapes = {-half0, half0, -half1, half1};
		if (keepCachedContacts(m_poseCache, manifold, shapes, body0Wrap, body1Wrap, resultOut, cacheDistance)) return;
		const btTransform& t0 = body0Wrap->getWorldTransform();
		const btTransform& t1 = body1Wrap->getWorldTransform();
		const btScalar reach = resultOut->m_closestPointDistanceThreshold;
		btBoxBoxCollisionAlgorithm::processCollision(body0Wrap, body1Wrap, dispatchInfo, resultOut);
		m_poseCache.store(t0, t1, reach, shapes, manifold->getNumContacts());
		return;
	}
	m_poseCache.valid = false;
	btBoxBoxCollisionAlgorithm::processCollision(body0Wrap, body1Wrap, dispatchInfo, resultOut);
}

int cachedBoxBoxAlgorithmSize() { return int(sizeof(CachedBoxBoxAlgorithm)); }
}  // namespace caliber

btCollisionAlgorithm* btBoxBoxCollisionAlgorithm::CreateFunc::CreateCollisionAlgorithm(
    btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0Wrap,
    const btCollisionObjectWrapper* body1Wrap)
{
	void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(caliber::CachedBoxBoxAlgorithm));
	return new (mem) caliber::CachedBoxBoxAlgorithm(ci.m_manifold, ci, body0Wrap, body1Wrap);
}

btBoxBoxCollisionAlgorithm::btBoxBoxCollisionAlgorithm(btPersistentManifold* mf,
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

btBoxBoxCollisionAlgorithm::~btBoxBoxCollisionAlgorithm()
{
	if (m_ownManifold && m_manifoldPtr) m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btBoxBoxCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                  const btCollisionObjectWrapper* body1Wrap,
                                                  const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut)
{
	if (!m_manifoldPtr || !resultOut) return;
	caliber::prefetchWholeManifold(m_manifoldPtr);
	resultOut->setPersistentManifold(m_manifoldPtr);
	if (!caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}
	const btBoxShape* box0 = static_cast<const btBoxShape*>(body0Wrap->getCollisionShape());
	const btBoxShape* box1 = static_cast<const btBoxShape*>(body1Wrap->getCollisionShape());

	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = body0Wrap->getWorldTransform();
	input.m_transformB = body1Wrap->getWorldTransform();
	const btScalar reach = m_manifoldPtr->getContactBreakingThreshold() + resultOut->m_closestPointDistanceThreshold;
	input.m_maximumDistanceSquared = reach * reach;

	if (m_ownManifold) caliber::dropStalePoints(m_manifoldPtr, body0Wrap, body1Wrap);
	btBoxBoxDetector detector(box0, box1);
	detector.getClosestPoints(input, *resultOut, dispatchInfo.m_debugDraw);

	if (m_ownManifold) resultOut->refreshContactPoints();
}

btScalar btBoxBoxCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                           const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}

void btBoxBoxCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifoldArray)
{
	if (m_manifoldPtr && m_ownManifold) manifoldArray.push_back(m_manifoldPtr);
}
