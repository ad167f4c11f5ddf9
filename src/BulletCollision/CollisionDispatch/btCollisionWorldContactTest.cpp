// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/NarrowPhaseCollision/btManifoldPoint.h"
#include "LinearMath/btQuickprof.h"

// btCollisionWorld::contactTest and contactPairTest: the closest-point algorithms of the dispatcher run on
// the pair, and their points go straight to the user's callback instead of into a manifold.

namespace
{
typedef btCollisionWorld::ContactResultCallback ContactResultCallback;

// A manifold result that reports each point to a ContactResultCallback (in the order of the manifold the
// algorithm uses, as btManifoldResult stores them) and stores nothing.
class ContactCallbackResult : public btManifoldResult
{
public:
	ContactCallbackResult(const btCollisionObjectWrapper* obj0Wrap, const btCollisionObjectWrapper* obj1Wrap,
	                      ContactResultCallback& resultCallback)
	    : btManifoldResult(obj0Wrap, obj1Wrap), m_resultCallback(resultCallback)
	{
	}

	void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override
	{
		const bool finiteInput =
		    caliber::isFinite(normalOnBInWorld) && caliber::isFinite(pointInWorld) && btIsFinite(depth);
		btAssert(finiteInput && "contactTest: non-finite contact");
		if (!finiteInput || !m_body0Wrap || !m_body1Wrap) return;
		// The same distance filter as a manifold applies, so that queries and the simulation agree.
		if (m_manifoldPtr && depth > m_manifoldPtr->getContactBreakingThreshold() + m_closestPointDistanceThreshold)
			return;

		// The algorithm reports in its own order (body 0 first); its manifold may have the pair swapped.
		const bool isSwapped = m_manifoldPtr && m_manifoldPtr->getBody0() != m_body0Wrap->getCollisionObject();
		const btCollisionObjectWrapper* wrapA = isSwapped ? m_body1Wrap : m_body0Wrap;
		const btCollisionObjectWrapper* wrapB = isSwapped ? m_body0Wrap : m_body1Wrap;
		const btVector3 pointA = pointInWorld + normalOnBInWorld * depth;
		const btVector3 localA = wrapA->getCollisionObject()->getWorldTransform().invXform(pointA);
		const btVector3 localB = wrapB->getCollisionObject()->getWorldTransform().invXform(pointInWorld);

		btManifoldPoint point(localA, localB, normalOnBInWorld, depth);
		point.m_positionWorldOnA = pointA;
		point.m_positionWorldOnB = pointInWorld;
		point.m_partId0 = isSwapped ? m_partId1 : m_partId0;
		point.m_partId1 = isSwapped ? m_partId0 : m_partId1;
		point.m_index0 = isSwapped ? m_index1 : m_index0;
		point.m_index1 = isSwapped ? m_index0 : m_index1;
		const btCollisionObject* body0 = m_body0Wrap->getCollisionObject();
		const btCollisionObject* body1 = m_body1Wrap->getCollisionObject();
		point.m_combinedFriction = gCalculateCombinedFrictionCallback(body0, body1);
		point.m_combinedRestitution = gCalculateCombinedRestitutionCallback(body0, body1);
		point.m_combinedRollingFriction = gCalculateCombinedRollingFrictionCallback(body0, body1);
		point.m_combinedSpinningFriction = gCalculateCombinedSpinningFrictionCallback(body0, body1);
		m_resultCallback.addSingleResult(point, wrapA, point.m_partId0, point.m_index0, wrapB, point.m_partId1,
		                                 point.m_index1);
	}

private:
	ContactResultCallback& m_resultCallback;
};

// Runs the closest-point algorithm of the pair once and reports its points.
void runPairQuery(btDispatcher* dispatcher, const btDispatcherInfo& dispatchInfo, btCollisionObject* colObjA,
                  btCollisionObject* colObjB, ContactResultCallback& resultCallback)
{
	btCollisionObjectWrapper wrapA(0, colObjA->getCollisionShape(), colObjA, colObjA->getWorldTransform(), -1, -1);
	btCollisionObjectWrapper wrapB(0, colObjB->getCollisionShape(), colObjB, colObjB->getWorldTransform(), -1, -1);
	btCollisionAlgorithm* algorithm = dispatcher->findAlgorithm(&wrapA, &wrapB, 0, BT_CLOSEST_POINT_ALGORITHMS);
	if (!algorithm) return;
	ContactCallbackResult result(&wrapA, &wrapB, resultCallback);
	result.m_closestPointDistanceThreshold = resultCallback.m_closestDistanceThreshold;
	algorithm->processCollision(&wrapA, &wrapB, dispatchInfo, &result);
	algorithm->~btCollisionAlgorithm();
	dispatcher->freeCollisionAlgorithm(algorithm);
}

bool isQueryable(const btCollisionObject* colObj)
{
	return colObj && colObj->getCollisionShape() && caliber::isFinite(colObj->getWorldTransform());
}

// Visited by the broadphase for each object whose box overlaps the query object's box.
struct ContactTestCallback : public btBroadphaseAabbCallback
{
	ContactTestCallback(btCollisionObject* queryObject, btDispatcher* dispatcher, const btDispatcherInfo& dispatchInfo,
	                    ContactResultCallback& resultCallback)
	    : m_queryObject(queryObject),
	      m_dispatcher(dispatcher),
	      m_dispatchInfo(dispatchInfo),
	      m_resultCallback(resultCallback)
	{
	}

	bool process(const btBroadphaseProxy* proxy) override
	{
		btCollisionObject* other = static_cast<btCollisionObject*>(proxy->m_clientObject);
		if (other == m_queryObject || !isQueryable(other)) return true;
		if (!m_resultCallback.needsCollision(other->getBroadphaseHandle())) return true;
		// The objects' own ignore lists apply as they do in the simulation.
		if (!m_queryObject->checkCollideWith(other) || !other->checkCollideWith(m_queryObject)) return true;
		runPairQuery(m_dispatcher, m_dispatchInfo, m_queryObject, other, m_resultCallback);
		return true;
	}

	btCollisionObject* m_queryObject;
	btDispatcher* m_dispatcher;
	const btDispatcherInfo& m_dispatchInfo;
	ContactResultCallback& m_resultCallback;
};
}  // namespace

void btCollisionWorld::contactTest(btCollisionObject* colObj, ContactResultCallback& resultCallback)
{
	BT_PROFILE("contactTest");
	const bool valid = isQueryable(colObj);
	btAssert(valid && "btCollisionWorld::contactTest: null object, no shape or non-finite transform");
	if (!valid || !m_broadphasePairCache || !m_dispatcher1) return;

	// The broadphase boxes are already grown by the contact breaking threshold; the query box is grown by
	// the extra distance the caller asks for.
	btVector3 aabbMin, aabbMax;
	colObj->getCollisionShape()->getAabb(colObj->getWorldTransform(), aabbMin, aabbMax);
	const btScalar extra = btMax(resultCallback.m_closestDistanceThreshold, btScalar(0));
	aabbMin -= btVector3(extra, extra, extra);
	aabbMax += btVector3(extra, extra, extra);
	if (!caliber::isFinite(aabbMin) || !caliber::isFinite(aabbMax)) return;
	ContactTestCallback callback(colObj, m_dispatcher1, m_dispatchInfo, resultCallback);
	m_broadphasePairCache->aabbTest(aabbMin, aabbMax, callback);
}

void btCollisionWorld::contactPairTest(btCollisionObject* colObjA, btCollisionObject* colObjB,
                                       ContactResultCallback& resultCallback)
{
	BT_PROFILE("contactPairTest");
	const bool valid = isQueryable(colObjA) && isQueryable(colObjB);
	btAssert(valid && "btCollisionWorld::contactPairTest: null object, no shape or non-finite transform");
	if (!valid || !m_dispatcher1) return;
	runPairQuery(m_dispatcher1, m_dispatchInfo, colObjA, colObjB, resultCallback);
}
