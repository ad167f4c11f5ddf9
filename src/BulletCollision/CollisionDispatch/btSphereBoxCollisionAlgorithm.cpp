// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btSphereBoxCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"

btSphereBoxCollisionAlgorithm::btSphereBoxCollisionAlgorithm(btPersistentManifold* mf,
                                                             const btCollisionAlgorithmConstructionInfo& ci,
                                                             const btCollisionObjectWrapper* body0Wrap,
                                                             const btCollisionObjectWrapper* body1Wrap, bool isSwapped)
    : btActivatingCollisionAlgorithm(ci, body0Wrap, body1Wrap),
      m_ownManifold(false),
      m_manifoldPtr(mf),
      m_isSwapped(isSwapped)
{
	const btCollisionObjectWrapper* sphereWrap = isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* boxWrap = isSwapped ? body0Wrap : body1Wrap;
	if (!m_manifoldPtr && m_dispatcher &&
	    m_dispatcher->needsCollision(sphereWrap->getCollisionObject(), boxWrap->getCollisionObject()))
	{
		// The manifold is always (sphere, box) so that the algorithm reports in one order.
		m_manifoldPtr = m_dispatcher->getNewManifold(sphereWrap->getCollisionObject(), boxWrap->getCollisionObject());
		m_ownManifold = true;
	}
}

btSphereBoxCollisionAlgorithm::~btSphereBoxCollisionAlgorithm()
{
	if (m_ownManifold && m_manifoldPtr) m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btSphereBoxCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                     const btCollisionObjectWrapper* body1Wrap, const btDispatcherInfo&,
                                                     btManifoldResult* resultOut)
{
	if (!m_manifoldPtr || !resultOut) return;
	resultOut->setPersistentManifold(m_manifoldPtr);
	if (!caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}
	const btCollisionObjectWrapper* sphereWrap = m_isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* boxWrap = m_isSwapped ? body0Wrap : body1Wrap;
	const btSphereShape* sphere = static_cast<const btSphereShape*>(sphereWrap->getCollisionShape());

	btVector3 pointOnBox, normal;
	btScalar distance;
	const btScalar maxContactDistance =
	    m_manifoldPtr->getContactBreakingThreshold() + resultOut->m_closestPointDistanceThreshold;
	if (!getSphereDistance(boxWrap, pointOnBox, normal, distance, sphereWrap->getWorldTransform().getOrigin(),
	                       sphere->getRadius(), maxContactDistance))
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}
	const int countBefore = m_manifoldPtr->getNumContacts();
	resultOut->addContactPoint(normal, pointOnBox, distance);
	if (m_ownManifold)
	{
		caliber::keepOnlyNewestPoint(m_manifoldPtr, countBefore);
		// Ages the point (lifetime) and reports it to gContactProcessedCallback, as for every other shape.
		resultOut->refreshContactPoints();
	}
}

btScalar btSphereBoxCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject*, btCollisionObject*,
                                                              const btDispatcherInfo&, btManifoldResult*)
{
	return btScalar(1);
}

void btSphereBoxCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifoldArray)
{
	if (m_manifoldPtr && m_ownManifold) manifoldArray.push_back(m_manifoldPtr);
}

bool btSphereBoxCollisionAlgorithm::getSphereDistance(const btCollisionObjectWrapper* boxObjWrap,
                                                      btVector3& v3PointOnBox, btVector3& normal,
                                                      btScalar& penetrationDepth, const btVector3& v3SphereCenter,
                                                      btScalar fRadius, btScalar maxContactDistance)
{
	const btBoxShape* box = static_cast<const btBoxShape*>(boxObjWrap->getCollisionShape());
	const btVector3 halfExtents = box->getHalfExtentsWithMargin();
	const btTransform& boxTransform = boxObjWrap->getWorldTransform();
	const btVector3 centreInBox = boxTransform.invXform(v3SphereCenter);

	btVector3 closest = centreInBox;
	closest.setMax(-halfExtents);
	closest.setMin(halfExtents);
	const btVector3 outside = centreInBox - closest;
	const btScalar outsideDistance2 = outside.length2();

	if (outsideDistance2 > SIMD_EPSILON * SIMD_EPSILON)
	{
		// Centre outside the box: the clamped point is the closest point, whatever region it is in.
		const btScalar outsideDistance = btSqrt(outsideDistance2);
		penetrationDepth = outsideDistance - fRadius;
		if (penetrationDepth > maxContactDistance) return false;
		normal = boxTransform.getBasis() * (outside / outsideDistance);
		v3PointOnBox = boxTransform(closest);
		return true;
	}

	btVector3 faceNormal;
	penetrationDepth = getSpherePenetration(halfExtents, centreInBox, closest, faceNormal) - fRadius;
	normal = boxTransform.getBasis() * faceNormal;
	v3PointOnBox = boxTransform(closest);
	return true;
}

btScalar btSphereBoxCollisionAlgorithm::getSpherePenetration(btVector3 const& boxHalfExtent,
                                                             btVector3 const& sphereRelPos, btVector3& closestPoint,
                                                             btVector3& normal)
{
	// The nearest face is the one with the smallest gap between the centre and the face plane; the first
	// axis wins ties so that the result is deterministic (a centre at the box centre picks +x).
	int bestAxis = 0;
	btScalar bestGap = boxHalfExtent[0] - btFabs(sphereRelPos[0]);
	for (int axis = 1; axis < 3; ++axis)
	{
		const btScalar gap = boxHalfExtent[axis] - btFabs(sphereRelPos[axis]);
		if (gap < bestGap)
		{
			bestGap = gap;
			bestAxis = axis;
		}
	}
	const btScalar side = sphereRelPos[bestAxis] < btScalar(0) ? btScalar(-1) : btScalar(1);
	normal.setValue(0, 0, 0);
	normal[bestAxis] = side;
	closestPoint = sphereRelPos;
	closestPoint[bestAxis] = side * boxHalfExtent[bestAxis];
	return -bestGap;
}
