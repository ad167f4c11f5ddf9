// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btConvexConcaveCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"

btConvexTriangleCallback::btConvexTriangleCallback(btDispatcher* dispatcher, const btCollisionObjectWrapper* body0Wrap,
                                                   const btCollisionObjectWrapper* body1Wrap, bool isSwapped)
    : m_aabbMin(0, 0, 0),
      m_aabbMax(0, 0, 0),
      m_convexBodyWrap(isSwapped ? body1Wrap : body0Wrap),
      m_triBodyWrap(isSwapped ? body0Wrap : body1Wrap),
      m_resultOut(0),
      m_dispatcher(dispatcher),
      m_dispatchInfoPtr(0),
      m_collisionMarginTriangle(0),
      m_triangleAlgorithm(0),
      m_isSwapped(isSwapped),
      m_triangleCount(0),
      m_manifoldPtr(0)
{
	// The manifold is always (convex, concave): every triangle algorithm reports in that order.
	m_manifoldPtr =
	    m_dispatcher->getNewManifold(m_convexBodyWrap->getCollisionObject(), m_triBodyWrap->getCollisionObject());
	clearCache();
}

btConvexTriangleCallback::~btConvexTriangleCallback()
{
	if (m_triangleAlgorithm)
	{
		m_triangleAlgorithm->~btCollisionAlgorithm();
		m_dispatcher->freeCollisionAlgorithm(m_triangleAlgorithm);
	}
	clearCache();
	m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btConvexTriangleCallback::clearCache() { m_dispatcher->clearManifold(m_manifoldPtr); }

void btConvexTriangleCallback::setTimeStepAndCounters(btScalar collisionMarginTriangle,
                                                      const btDispatcherInfo& dispatchInfo,
                                                      const btCollisionObjectWrapper* convexBodyWrap,
                                                      const btCollisionObjectWrapper* triBodyWrap,
                                                      btManifoldResult* resultOut)
{
	m_convexBodyWrap = convexBodyWrap;
	m_triBodyWrap = triBodyWrap;
	m_dispatchInfoPtr = &dispatchInfo;
	m_collisionMarginTriangle = collisionMarginTriangle;
	m_resultOut = resultOut;

	const btTransform convexInTriangleSpace =
	    triBodyWrap->getWorldTransform().inverse() * convexBodyWrap->getWorldTransform();
	convexBodyWrap->getCollisionShape()->getAabb(convexInTriangleSpace, m_aabbMin, m_aabbMax);
	// Triangles within the breaking threshold must be seen too, or contacts would flicker at rest.
	const btScalar extra = collisionMarginTriangle + m_manifoldPtr->getContactBreakingThreshold() +
	                       resultOut->m_closestPointDistanceThreshold;
	const btVector3 grow(extra, extra, extra);
	m_aabbMin -= grow;
	m_aabbMax += grow;
}

void btConvexTriangleCallback::processTriangle(btVector3* triangle, int partId, int triangleIndex)
{
	if (!m_convexBodyWrap || !m_triBodyWrap || !m_resultOut) return;
	++m_triangleCount;

	btTriangleShape triangleShape(triangle[0], triangle[1], triangle[2]);
	triangleShape.setMargin(m_collisionMarginTriangle);
	btCollisionObjectWrapper triangleWrap(m_triBodyWrap, &triangleShape, m_triBodyWrap->getCollisionObject(),
	                                      m_triBodyWrap->getWorldTransform(), partId, triangleIndex);

	if (!m_triangleAlgorithm)
	{
		// Every triangle gives the same pair of shape types, so one algorithm serves them all.
		const ebtDispatcherQueryType queryType = m_resultOut->m_closestPointDistanceThreshold > 0
		                                             ? BT_CLOSEST_POINT_ALGORITHMS
		                                             : BT_CONTACT_POINT_ALGORITHMS;
		m_triangleAlgorithm = m_dispatcher->findAlgorithm(m_convexBodyWrap, &triangleWrap, m_manifoldPtr, queryType);
		if (!m_triangleAlgorithm) return;
	}

	// The result sees the triangle as the concave side of the pair for this call.
	const btCollisionObjectWrapper* savedWrap;
	if (m_isSwapped)
	{
		savedWrap = m_resultOut->getBody0Wrap();
		m_resultOut->setBody0Wrap(&triangleWrap);
		m_resultOut->setShapeIdentifiersA(partId, triangleIndex);
	}
	else
	{
		savedWrap = m_resultOut->getBody1Wrap();
		m_resultOut->setBody1Wrap(&triangleWrap);
		m_resultOut->setShapeIdentifiersB(partId, triangleIndex);
	}
	m_triangleAlgorithm->processCollision(m_convexBodyWrap, &triangleWrap, *m_dispatchInfoPtr, m_resultOut);
	if (m_isSwapped)
		m_resultOut->setBody0Wrap(savedWrap);
	else
		m_resultOut->setBody1Wrap(savedWrap);
}

btConvexConcaveCollisionAlgorithm::btConvexConcaveCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                                                     const btCollisionObjectWrapper* body0Wrap,
                                                                     const btCollisionObjectWrapper* body1Wrap,
                                                                     bool isSwapped)
    : btActivatingCollisionAlgorithm(ci, body0Wrap, body1Wrap),
      m_btConvexTriangleCallback(ci.m_dispatcher1, body0Wrap, body1Wrap, isSwapped),
      m_isSwapped(isSwapped)
{
}

btConvexConcaveCollisionAlgorithm::~btConvexConcaveCollisionAlgorithm() {}

void btConvexConcaveCollisionAlgorithm::clearCache() { m_btConvexTriangleCallback.clearCache(); }

void btConvexConcaveCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifoldArray)
{
	if (m_btConvexTriangleCallback.m_manifoldPtr) manifoldArray.push_back(m_btConvexTriangleCallback.m_manifoldPtr);
}

void btConvexConcaveCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                         const btCollisionObjectWrapper* body1Wrap,
                                                         const btDispatcherInfo& dispatchInfo,
                                                         btManifoldResult* resultOut)
{
	if (!resultOut) return;
	btPersistentManifold* manifold = m_btConvexTriangleCallback.m_manifoldPtr;
	resultOut->setPersistentManifold(manifold);
	if (!caliberPairIsUsable(body0Wrap, body1Wrap))
	{
		manifold->clearManifold();
		return;
	}
	const btCollisionObjectWrapper* convexBodyWrap = m_isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* triBodyWrap = m_isSwapped ? body0Wrap : body1Wrap;
	if (!triBodyWrap->getCollisionShape()->isConcave() || !convexBodyWrap->getCollisionShape()->isConvex()) return;

	const btConcaveShape* concave = static_cast<const btConcaveShape*>(triBodyWrap->getCollisionShape());
	m_btConvexTriangleCallback.m_triangleCount = 0;
	m_btConvexTriangleCallback.setTimeStepAndCounters(concave->getMargin(), dispatchInfo, convexBodyWrap, triBodyWrap,
	                                                  resultOut);
	manifold->setBodies(convexBodyWrap->getCollisionObject(), triBodyWrap->getCollisionObject());
	concave->processAllTriangles(&m_btConvexTriangleCallback, m_btConvexTriangleCallback.getAabbMin(),
	                             m_btConvexTriangleCallback.getAabbMax());
	resultOut->refreshContactPoints();
	m_btConvexTriangleCallback.clearWrapperData();
}

btScalar btConvexConcaveCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                                  const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}
