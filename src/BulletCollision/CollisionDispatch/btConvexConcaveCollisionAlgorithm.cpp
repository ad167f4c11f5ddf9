// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btConvexConcaveCollisionAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btConvexTriangleClipping.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionDispatch/btMeshContactCollector.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

namespace
{
// Casts the convex body's CCD swept sphere along its motion against each triangle it reaches, all
// in the concave body's space; keeps the earliest fraction.
class SweptSphereTriangleCallback : public btTriangleCallback
{
public:
	SweptSphereTriangleCallback(const btTransform& from, const btTransform& to, btScalar radius, btScalar hitFraction)
	    : m_from(from), m_to(to), m_sphere(radius), m_hitFraction(hitFraction)
	{
	}
	void processTriangle(btVector3* triangle, int, int) override
	{
		btTriangleShape triangleShape(triangle[0], triangle[1], triangle[2]);
		// The swept sphere's radius is the whole allowance; a triangle margin would add to it.
		triangleShape.setMargin(btScalar(0));
		btVoronoiSimplexSolver simplexSolver;
		btGjkConvexCast cast(&m_sphere, &triangleShape, &simplexSolver);
		btConvexCast::CastResult result;
		const btTransform identity = btTransform::getIdentity();
		if (!cast.calcTimeOfImpact(m_from, m_to, identity, identity, result)) return;
		if (result.m_fraction >= btScalar(0) && result.m_fraction < m_hitFraction) m_hitFraction = result.m_fraction;
	}
	btScalar hitFraction() const { return m_hitFraction; }

private:
	btTransform m_from;
	btTransform m_to;
	btSphereShape m_sphere;
	btScalar m_hitFraction;
};

// The exact box of a hull (margin included) in the frame transform maps it into: its supports along
// the frame's axes. A turned hull's cached local box, turned in turn, can be much larger (a barrel on
// its side: 2.7 instead of 2.2 across), and every triangle it takes in costs a GJK query.
void hullAabb(const btConvexShape& hull, const btTransform& transform, btVector3& aabbMin, btVector3& aabbMax)
{
	const btMatrix3x3& basis = transform.getBasis();
	btVector3 directions[6];
	for (int axis = 0; axis < 3; ++axis)
	{
		directions[axis] = basis[axis];
		directions[axis + 3] = -basis[axis];
	}
	btVector3 supports[6];
	hull.batchedUnitVectorGetSupportingVertexWithoutMargin(directions, supports, 6);
	const btScalar margin = hull.getMargin();
	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar offset = transform.getOrigin()[axis];
		aabbMax[axis] = offset + directions[axis].dot(supports[axis]) + margin;
		aabbMin[axis] = offset + directions[axis].dot(supports[axis + 3]) - margin;
	}
}
// How far the mesh query's box reaches beyond the convex's own box (in the concave's frame): by extra all
// round, and by travel ahead of the motion.
struct QueryGrowth
{
	btScalar extra;
	btVector3 travel;

	void grow(btVector3& boxMin, btVector3& boxMax) const
	{
		for (int axis = 0; axis < 3; ++axis)
		{
			if (travel[axis] < 0)
				boxMin[axis] += travel[axis];
			else
				boxMax[axis] += travel[axis];
		}
		const btVector3 all(extra, extra, extra);
		boxMin -= all;
		boxMax += all;
	}
	/// The convex's own box back from the query's (up to rounding, which slack covers).
	void shrink(btVector3& boxMin, btVector3& boxMax, btScalar slack) const
	{
		const btVector3 all(extra - slack, extra - slack, extra - slack);
		boxMin += all;
		boxMax -= all;
		for (int axis = 0; axis < 3; ++axis)
		{
			if (travel[axis] < 0)
				boxMin[axis] -= travel[axis];
			else
				boxMax[axis] -= travel[axis];
		}
	}
};

QueryGrowth queryGrowth(btScalar collisionMarginTriangle, btScalar breakingThreshold,
                        const btDispatcherInfo& dispatchInfo, const btCollisionObjectWrapper* convexBodyWrap,
                        const btCollisionObjectWrapper* triBodyWrap, const btManifoldResult& resultOut)
{
	// Triangles within the breaking threshold must be seen too, or contacts would flicker at rest.
	QueryGrowth growth;
	growth.extra = collisionMarginTriangle + breakingThreshold;
	growth.travel.setValue(0, 0, 0);
	const btScalar speculative = resultOut.m_closestPointDistanceThreshold;
	if (speculative > btScalar(0) && dispatchInfo.m_timeStep > btScalar(0))
	{
		// The speculative reach (how far the pair can close this step) only matters ahead of the convex:
		// grow the box along its motion relative to the mesh, and by the turning part all round. Triangles
		// behind a falling body are not worth a collision query.
		const btCollisionObject* convex = convexBodyWrap->getCollisionObject();
		const btCollisionObject* mesh = triBodyWrap->getCollisionObject();
		const btVector3 relative = convex->getInterpolationLinearVelocity() - mesh->getInterpolationLinearVelocity();
		const btVector3 travel =
		    triBodyWrap->getWorldTransform().getBasis().transpose() * relative * dispatchInfo.m_timeStep;
		const btScalar turning = btMax(btScalar(0), speculative - relative.length() * dispatchInfo.m_timeStep);
		if (btIsFinite(travel.x()) && btIsFinite(travel.y()) && btIsFinite(travel.z()) && btIsFinite(turning))
		{
			growth.extra += turning;
			growth.travel = travel;
		}
		else
		{
			growth.extra += speculative;
		}
	}
	return growth;
}

// Passes on the triangles a hull may reach: a triangle whose plane, or one of whose side planes (through
// an edge, along the normal), has the hull's own box (in the concave's frame, margin included) beyond it
// by more than reach is out of reach (a separating axis), and its face search and GJK are skipped. The
// box is the hull's exact extent along the concave's axes, so against the nearly level triangles of a
// terrain the plane test is about as sharp as the hull's points. Exact: the triangles skipped are those
// the face search would find out of reach (up to rounding at the limit).
class ReachableTriangles : public btTriangleCallback
{
public:
	ReachableTriangles(btConvexTriangleCallback& next, const btVector3& boxMin, const btVector3& boxMax, btScalar allowed)
	    : m_next(next), m_centre((boxMin + boxMax) * btScalar(0.5)), m_half((boxMax - boxMin) * btScalar(0.5)),
	      m_allowed2(allowed * allowed)
	{
	}
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		if (!beyondReach(triangle))
			m_next.processTriangle(triangle, partId, triangleIndex);
		else
			++m_next.m_triangleCount;  // still one the query returned
	}

private:
	// The box's clearance beyond the plane through `from` with (unnormalised) normal `axis`, compared
	// squared with the allowed distance (no square root for the many triangles out of reach).
	bool beyondPlane(const btVector3& from, const btVector3& axis, bool twoSided) const
	{
		const btScalar centre = axis.dot(m_centre - from);
		const btScalar extent = btFabs(axis.x()) * m_half.x() + btFabs(axis.y()) * m_half.y() +
		                        btFabs(axis.z()) * m_half.z();
		const btScalar clearance = (twoSided ? btFabs(centre) : centre) - extent;
		return clearance > 0 && clearance * clearance > m_allowed2 * axis.length2();
	}
	bool beyondReach(const btVector3* corners) const
	{
		const btVector3 edge1 = corners[1] - corners[0];
		const btVector3 edge2 = corners[2] - corners[0];
		const btVector3 normal = edge1.cross(edge2);
		// A sliver's normal is mostly rounding: the full search decides.
		if (!(normal.length2() > SIMD_EPSILON * edge1.length2() * edge2.length2())) return false;
		if (beyondPlane(corners[0], normal, true)) return true;
		for (int k = 0; k < 3; ++k)
		{
			const btVector3 side = (corners[k == 2 ? 0 : k + 1] - corners[k]).cross(normal);  // outwards
			if (beyondPlane(corners[k], side, false)) return true;
		}
		return false;
	}

	btConvexTriangleCallback& m_next;
	btVector3 m_centre, m_half;
	btScalar m_allowed2;
};
}  // namespace

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
	if (m_manifoldPtr) m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btConvexTriangleCallback::clearCache()
{
	if (m_manifoldPtr) m_dispatcher->clearManifold(m_manifoldPtr);
}

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
	const btCollisionShape* convexShape = convexBodyWrap->getCollisionShape();
	if (convexShape->getShapeType() == CONVEX_HULL_SHAPE_PROXYTYPE)
		hullAabb(*static_cast<const btConvexShape*>(convexShape), convexInTriangleSpace, m_aabbMin, m_aabbMax);
	else
		convexShape->getAabb(convexInTriangleSpace, m_aabbMin, m_aabbMax);
	const QueryGrowth growth = queryGrowth(collisionMarginTriangle, m_manifoldPtr->getContactBreakingThreshold(),
	                                       dispatchInfo, convexBodyWrap, triBodyWrap, *resultOut);
	growth.grow(m_aabbMin, m_aabbMax);
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
	btPersistentManifold* manifold = m_btConvexTriangleCallback.m_manifoldPtr;
	// A full manifold pool without dynamic allocation gives none: the pair is skipped.
	if (!resultOut || !manifold) return;
	resultOut->setPersistentManifold(manifold);
	if (!caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		manifold->clearManifold();
		return;
	}
	const btCollisionObjectWrapper* convexBodyWrap = m_isSwapped ? body1Wrap : body0Wrap;
	const btCollisionObjectWrapper* triBodyWrap = m_isSwapped ? body0Wrap : body1Wrap;
	if (!triBodyWrap->getCollisionShape()->isConcave() || !convexBodyWrap->getCollisionShape()->isConvex()) return;

	const btConcaveShape* concave = static_cast<const btConcaveShape*>(triBodyWrap->getCollisionShape());
	m_btConvexTriangleCallback.m_triangleCount = 0;
	// The triangles report into a collector, which drops internal-edge points and passes on the rest (for
	// face-clipped boxes and hulls, the best 4 of all the triangles' points). Objects with a custom material
	// callback see every triangle's raw points instead, as in Bullet (their owners fix internal edges
	// themselves, e.g. with btAdjustInternalEdgeContacts).
	const caliber::TriangleClipping clipping = caliber::triangleClippingOf(*convexBodyWrap->getCollisionShape());
	const bool clips = clipping != caliber::kNoClipping;
	const bool collect = !((convexBodyWrap->getCollisionObject()->getCollisionFlags() |
	                        triBodyWrap->getCollisionObject()->getCollisionFlags()) &
	                       btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
	caliber::MeshContactCollector collector(*resultOut, !m_isSwapped, concave->getMargin(), clips && collect);
	m_btConvexTriangleCallback.setTimeStepAndCounters(concave->getMargin(), dispatchInfo, convexBodyWrap, triBodyWrap,
	                                                  collect ? &collector : resultOut);
	manifold->setBodies(convexBodyWrap->getCollisionObject(), triBodyWrap->getCollisionObject());
	// Boxes and hulls get their whole contact patch each frame (face clipping): last frame's points that
	// have moved away would crowd the manifold.
	if (clips) caliber::dropStalePoints(manifold, body0Wrap, body1Wrap);
	if (clipping == caliber::kClipAfterGjk)
	{
		// Hulls: triangles beyond reach of the hull's own box are skipped before any search.
		const QueryGrowth growth =
		    queryGrowth(concave->getMargin(), manifold->getContactBreakingThreshold(), dispatchInfo, convexBodyWrap,
		                triBodyWrap, collect ? static_cast<btManifoldResult&>(collector) : *resultOut);
		btVector3 boxMin = m_btConvexTriangleCallback.getAabbMin();
		btVector3 boxMax = m_btConvexTriangleCallback.getAabbMax();
		const btScalar size = (boxMax - boxMin).length();
		growth.shrink(boxMin, boxMax, btScalar(1e-5) * (size + btScalar(1)));
		const btScalar allowed = manifold->getContactBreakingThreshold() +
		                         (collect ? collector.m_closestPointDistanceThreshold
		                                  : resultOut->m_closestPointDistanceThreshold) +
		                         concave->getMargin();
		ReachableTriangles reachable(m_btConvexTriangleCallback, boxMin, boxMax, allowed);
		concave->processAllTriangles(&reachable, m_btConvexTriangleCallback.getAabbMin(),
		                             m_btConvexTriangleCallback.getAabbMax());
	}
	else
	{
		concave->processAllTriangles(&m_btConvexTriangleCallback, m_btConvexTriangleCallback.getAabbMin(),
		                             m_btConvexTriangleCallback.getAabbMax());
	}
	if (collect) collector.flush(triBodyWrap);
	resultOut->refreshContactPoints();
	m_btConvexTriangleCallback.clearWrapperData();
}

btScalar btConvexConcaveCollisionAlgorithm::calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
                                                                  const btDispatcherInfo&, btManifoldResult*)
{
	const btScalar noHit = btScalar(1);
	btCollisionObject* convexBody = m_isSwapped ? body1 : body0;
	btCollisionObject* triBody = m_isSwapped ? body0 : body1;
	if (!convexBody || !triBody || !triBody->getCollisionShape() || !triBody->getCollisionShape()->isConcave())
		return noHit;
	// Only the convex body's motion is swept: the concave side is static or kinematic in Bullet's CCD.
	const btScalar motion =
	    (convexBody->getInterpolationWorldTransform().getOrigin() - convexBody->getWorldTransform().getOrigin())
	        .length2();
	if (!(motion >= convexBody->getCcdSquareMotionThreshold())) return noHit;
	if (!caliber::isFinite(convexBody->getWorldTransform()) ||
	    !caliber::isFinite(convexBody->getInterpolationWorldTransform()) ||
	    !caliber::isFinite(triBody->getWorldTransform()))
		return noHit;

	const btTransform worldToMesh = triBody->getWorldTransform().inverse();
	const btTransform from = worldToMesh * convexBody->getWorldTransform();
	const btTransform to = worldToMesh * convexBody->getInterpolationWorldTransform();
	// Only the triangles near the sweep matter: the box around the path grown by the sphere.
	const btScalar radius = convexBody->getCcdSweptSphereRadius();
	btVector3 sweepMin = from.getOrigin();
	btVector3 sweepMax = from.getOrigin();
	sweepMin.setMin(to.getOrigin());
	sweepMax.setMax(to.getOrigin());
	const btVector3 grow(radius, radius, radius);
	sweepMin -= grow;
	sweepMax += grow;

	SweptSphereTriangleCallback sweep(from, to, radius, convexBody->getHitFraction());
	static_cast<btConcaveShape*>(triBody->getCollisionShape())->processAllTriangles(&sweep, sweepMin, sweepMax);
	if (sweep.hitFraction() < convexBody->getHitFraction())
	{
		convexBody->setHitFraction(sweep.hitFraction());
		return sweep.hitFraction();
	}
	return noHit;
}
