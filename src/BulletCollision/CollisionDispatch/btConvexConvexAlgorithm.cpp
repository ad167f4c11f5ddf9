// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h"

#include "BulletCollision/CollisionDispatch/btAlgorithmUtil.h"
#include "BulletCollision/NarrowPhaseCollision/ManifoldPrefetch.h"
#include "BulletCollision/CollisionDispatch/btCachedCollisionAlgorithms.h"
#include "BulletCollision/CollisionDispatch/btCapsuleCapsuleContact.h"
#include "BulletCollision/CollisionDispatch/btCapsuleTriangleContact.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btConvexTriangleClipping.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/ClosestPointOnTriangle.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "LinearMath/btMemberAccess.h"
#include "LinearMath/btQuaternion.h"

#include <new>

CALIBER_MEMBER_ACCESS(ConvexPairManifold, btConvexConvexAlgorithm, btPersistentManifold*, m_manifoldPtr)
CALIBER_MEMBER_ACCESS(ConvexPairOwnsManifold, btConvexConvexAlgorithm, bool, m_ownManifold)

namespace
{
// Keeps GJK's single point so that the algorithm can decide how to use it.
struct GjkPointResult : public btStorageResult
{
	bool found() const { return m_distance < btScalar(BT_LARGE_FLOAT); }
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
};

// Discards everything (findSeparatingAxis may report an edge point we do not use).
struct DiscardResult : public btDiscreteCollisionDetectorInterface::Result
{
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3&, const btVector3&, btScalar) override {}
};

// Clipping works on the polyhedra, which for hulls are the margin-free cores (boxes list their full
// corners). This adapter puts the margins back so that clipped points agree with GJK's distances, and
// counts the points so that the algorithm can fall back to GJK's point when clipping finds none.
struct MarginRestoringResult : public btDiscreteCollisionDetectorInterface::Result
{
	btDiscreteCollisionDetectorInterface::Result& m_output;
	btScalar m_marginA;
	btScalar m_marginB;
	int m_count;

	MarginRestoringResult(btDiscreteCollisionDetectorInterface::Result& output, btScalar marginA, btScalar marginB)
	    : m_output(output), m_marginA(marginA), m_marginB(marginB), m_count(0)
	{
	}
	void setShapeIdentifiersA(int partId, int index) override { m_output.setShapeIdentifiersA(partId, index); }
	void setShapeIdentifiersB(int partId, int index) override { m_output.setShapeIdentifiersB(partId, index); }
	void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override
	{
		++m_count;
		m_output.addContactPoint(normalOnBInWorld, pointInWorld + normalOnBInWorld * m_marginB,
		                         depth - m_marginA - m_marginB);
	}
};

// GJK ran on a copy of one shape rotated slightly; this maps the point found on the rotated copy back
// onto the real shape (same local point, real transform) and recomputes the depth along the normal.
struct UnperturbingResult : public btDiscreteCollisionDetectorInterface::Result
{
	btDiscreteCollisionDetectorInterface::Result& m_output;
	btTransform m_rotatedToReal;
	bool m_perturbedA;

	UnperturbingResult(btDiscreteCollisionDetectorInterface::Result& output, const btTransform& rotatedToReal,
	                   bool perturbedA)
	    : m_output(output), m_rotatedToReal(rotatedToReal), m_perturbedA(perturbedA)
	{
	}
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3& normalOnBInWorld, const btVector3& pointInWorld, btScalar depth) override
	{
		btVector3 pointOnA = pointInWorld + normalOnBInWorld * depth;
		btVector3 pointOnB = pointInWorld;
		if (m_perturbedA)
			pointOnA = m_rotatedToReal(pointOnA);
		else
			pointOnB = m_rotatedToReal(pointOnB);
		const btScalar realDepth = (pointOnA - pointOnB).dot(normalOnBInWorld);
		m_output.addContactPoint(normalOnBInWorld, pointOnA - normalOnBInWorld * realDepth, realDepth);
	}
};

// Shape types known to derive from btPolyhedralConvexShape (and so to possibly carry a polyhedron).
bool isPolyhedralShapeClass(int shapeType)
{
	switch (shapeType)
	{
		case BOX_SHAPE_PROXYTYPE:
		case TRIANGLE_SHAPE_PROXYTYPE:
		case TETRAHEDRAL_SHAPE_PROXYTYPE:
		case CONVEX_TRIANGLEMESH_SHAPE_PROXYTYPE:
		case CONVEX_HULL_SHAPE_PROXYTYPE:
		case CONVEX_POINT_CLOUD_SHAPE_PROXYTYPE:
			return true;
		default:
			return false;
	}
}

const btConvexPolyhedron* polyhedronOf(const btConvexShape* shape)
{
	if (!isPolyhedralShapeClass(shape->getShapeType())) return 0;
	return static_cast<const btPolyhedralConvexShape*>(shape)->getConvexPolyhedron();
}

// GJK's starting axis (from B towards A) when one shape is a triangle: its normal, turned towards the
// other shape's origin. The first GJK step is then the face test, which rejects a shape beyond reach
// on either side of the plane at once (most triangles a mesh query returns), and a shape resting on
// the face starts from its contact normal. False for other pairs and for degenerate triangles.
bool triangleStartAxis(const btConvexShape* shapeA, const btTransform& transformA, const btConvexShape* shapeB,
                       const btTransform& transformB, btVector3& axis)
{
	const bool triangleIsB = shapeB->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE;
	if (!triangleIsB && shapeA->getShapeType() != TRIANGLE_SHAPE_PROXYTYPE) return false;
	const btTriangleShape* triangle = static_cast<const btTriangleShape*>(triangleIsB ? shapeB : shapeA);
	const btTransform& triangleTransform = triangleIsB ? transformB : transformA;
	const btVector3* corners = triangle->m_vertices1;
	const btVector3 edge1 = corners[1] - corners[0];
	const btVector3 edge2 = corners[2] - corners[0];
	const btVector3 normal = triangleTransform.getBasis() * edge1.cross(edge2);
	const btScalar normalLengthSquared = normal.length2();
	// A sliver's cross product is mostly rounding: its direction would be no better than the default.
	if (!(normalLengthSquared > SIMD_EPSILON * edge1.length2() * edge2.length2()) || !btIsFinite(normalLengthSquared))
		return false;
	const btVector3 corner = triangleTransform(corners[0]);
	const btVector3 towardsA = triangleIsB ? transformA.getOrigin() - corner : corner - transformB.getOrigin();
	axis = normal / btSqrt(normalLengthSquared);
	if (axis.dot(towardsA) < btScalar(0)) axis = -axis;
	return true;
}

// The margin clipping must add back: boxes' polyhedra already have their full size.
btScalar clippingMargin(const btConvexShape* shape)
{
	return shape->getShapeType() == BOX_SHAPE_PROXYTYPE ? btScalar(0) : shape->getMargin();
}
// The closed-form contacts tried before GJK; true when they settle the pair (GJK is not run).
// facePointsReported: the triangle's face points were reported and GJK still runs for its edges.
bool contactWithoutGjk(const btConvexShape* shapeA, const btTransform& transformA, const btConvexShape* shapeB,
                       const btTransform& transformB, caliber::TriangleClipping clipping, btScalar reach,
                       btManifoldResult& resultOut, bool& facePointsReported, caliber::TriangleFaceSearch& faceSearch)
{
	if (shapeA->getShapeType() == CAPSULE_SHAPE_PROXYTYPE && shapeB->getShapeType() == CAPSULE_SHAPE_PROXYTYPE)
	{
		// Two capsules in closed form (as Bullet does); crossing core segments go on to GJK/EPA.
		btVector3 normalOnB, pointOnB;
		btScalar distance;
		if (caliber::capsuleCapsuleContact(*static_cast<const btCapsuleShape*>(shapeA), transformA,
		                                   *static_cast<const btCapsuleShape*>(shapeB), transformB, normalOnB, pointOnB,
		                                   distance))
		{
			if (distance <= reach) resultOut.addContactPoint(normalOnB, pointOnB, distance);
			return true;
		}
	}
	// A box against a mesh triangle: the contact along the triangle's normal, in closed form before GJK,
	// with the whole clipped face when the box is over the face (a box landing flat, or fast on
	// speculative points, is held at its corners at once). GJK is spared for most triangles (beyond reach,
	// or under the box) and left the edges and vertices. The mesh collector chooses among all triangles'
	// points.
	if (clipping == caliber::kClipBeforeGjk)
	{
		const caliber::TriangleFaceOutcome outcome = caliber::triangleFaceContact(
		    *shapeA, transformA, *static_cast<const btTriangleShape*>(shapeB), transformB, reach, resultOut);
		if (outcome == caliber::kTriangleOutOfReach || outcome == caliber::kTriangleFaceContact) return true;
		facePointsReported = outcome == caliber::kTriangleFacePointsAndGjk;
	}
	// A hull against a mesh triangle: the cases GJK is not needed for, decided along the triangle's normal
	// (beyond reach, or the hull's lowest point over the face: its clipped face is the contact). GJK and the
	// search along its normal take the rest (the search made here is kept for it).
	if (clipping == caliber::kClipAfterGjk)
	{
		const caliber::TriangleFaceOutcome outcome = caliber::hullTriangleFaceContactBeforeGjk(
		    *shapeA, transformA, *static_cast<const btTriangleShape*>(shapeB), transformB, reach, resultOut,
		    faceSearch);
		if (outcome == caliber::kTriangleOutOfReach || outcome == caliber::kTriangleFaceContact) return true;
	}
	// A capsule against a mesh triangle in closed form: both ends of a capsule lying on the face, and the
	// edge's point when an edge is nearer (GJK gave one point per triangle, on which a capsule rolls).
	if (shapeB->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE && shapeA->getShapeType() == CAPSULE_SHAPE_PROXYTYPE)
	{
		const caliber::TriangleFaceOutcome outcome =
		    caliber::capsuleTriangleContact(*static_cast<const btCapsuleShape*>(shapeA), transformA,
		                                    *static_cast<const btTriangleShape*>(shapeB), transformB, reach, resultOut);
		if (outcome != caliber::kTriangleNeedsGjk) return true;
	}
	return false;
}

// The two polyhedral shapes of a pair, their polyhedra, the pair's transforms and its objects.
struct PolyhedralPair
{
	const btConvexShape* shapeA;
	const btConvexShape* shapeB;
	const btConvexPolyhedron* polyA;
	const btConvexPolyhedron* polyB;
	const btDiscreteCollisionDetectorInterface::ClosestPointInput* input;
	const btCollisionObjectWrapper* body0Wrap;
	const btCollisionObjectWrapper* body1Wrap;
};

// Two polyhedra: the face of one clipped against the other along a separating axis (SAT's when enabled,
// else GJK's normal), the margins added back; GJK's point when clipping keeps none. ownManifold is the
// manifold to drop stale points from before clipping, or null when the algorithm does not own it.
void clipPolyhedra(const PolyhedralPair& pair, const GjkPointResult& gjkPoint, const btDispatcherInfo& dispatchInfo,
                   btScalar reach, btPersistentManifold* ownManifold, btVertexArray& worldVertsB1,
                   btVertexArray& worldVertsB2, btManifoldResult& resultOut)
{
	const btTransform& transformA = pair.input->m_transformA;
	const btTransform& transformB = pair.input->m_transformB;
	bool haveAxis = false;
	btVector3 separatingAxis(0, 0, 0);
	if (dispatchInfo.m_enableSatConvex)
	{
		// SAT sees the margin-free polyhedra: cores that are apart while the margins touch fall
		// through to GJK's axis below.
		DiscardResult discard;
		haveAxis = btPolyhedralContactClipping::findSeparatingAxis(*pair.polyA, *pair.polyB, transformA, transformB,
		                                                           separatingAxis, discard);
	}
	if (!haveAxis && gjkPoint.found() && gjkPoint.m_distance <= reach)
	{
		const btScalar axisLength = gjkPoint.m_normalOnSurfaceB.length();
		haveAxis = axisLength > SIMD_EPSILON;
		if (haveAxis) separatingAxis = gjkPoint.m_normalOnSurfaceB / axisLength;
	}
	if (!haveAxis) return;
	if (ownManifold) caliber::dropStalePoints(ownManifold, pair.body0Wrap, pair.body1Wrap);
	MarginRestoringResult clipped(resultOut, clippingMargin(pair.shapeA), clippingMargin(pair.shapeB));
	// The margins are added back after clipping, so clipping may keep points up to reach + margins.
	btPolyhedralContactClipping::clipHullAgainstHull(
	    separatingAxis, *pair.polyA, *pair.polyB, transformA, transformB, btScalar(-BT_LARGE_FLOAT),
	    reach + clipped.m_marginA + clipped.m_marginB, worldVertsB1, worldVertsB2, clipped);
	if (clipped.m_count == 0 && gjkPoint.found())
		resultOut.addContactPoint(gjkPoint.m_normalOnSurfaceB, gjkPoint.m_closestPointInB, gjkPoint.m_distance);
}

// Bullet's optional multipoint: the shape with the smaller angular disc rotated slightly about axes
// across the normal, iterations times around it; each rotated copy touches at another point of a flat
// contact, reported back in the unrotated frame.
void addPerturbedPoints(btGjkPairDetector& gjk, btVoronoiSimplexSolver& simplexSolver,
                        const btDiscreteCollisionDetectorInterface::ClosestPointInput& input,
                        const btConvexShape* shapeA, const btConvexShape* shapeB, btVector3 normal, int iterations,
                        btIDebugDraw* debugDraw, btManifoldResult& resultOut)
{
	normal.safeNormalize();
	btVector3 tangent0, tangent1;
	btPlaneSpace1(normal, tangent0, tangent1);
	const btScalar discA = shapeA->getAngularMotionDisc();
	const btScalar discB = shapeB->getAngularMotionDisc();
	const bool perturbA = discA < discB;
	const btScalar disc = perturbA ? discA : discB;
	const btScalar angleLimit = btScalar(0.125) * SIMD_PI;
	btScalar tiltAngle = disc > SIMD_EPSILON ? gContactBreakingThreshold / disc : angleLimit;
	if (tiltAngle > angleLimit) tiltAngle = angleLimit;
	const btQuaternion tilt(tangent0, tiltAngle);
	for (int i = 0; i < iterations; ++i)
	{
		const btQuaternion aroundNormal(normal, SIMD_2_PI * btScalar(i) / btScalar(iterations));
		const btMatrix3x3 rotation(aroundNormal.inverse() * tilt * aroundNormal);
		btDiscreteCollisionDetectorInterface::ClosestPointInput perturbed = input;
		const btTransform& real = perturbA ? input.m_transformA : input.m_transformB;
		btTransform& rotated = perturbA ? perturbed.m_transformA : perturbed.m_transformB;
		rotated.setBasis(rotation * real.getBasis());
		UnperturbingResult unperturbing(resultOut, real * rotated.inverse(), perturbA);
		simplexSolver.reset();
		gjk.getClosestPoints(perturbed, unperturbing, debugDraw);
	}
}
}  // namespace

btConvexConvexAlgorithm::CreateFunc::CreateFunc(btConvexPenetrationDepthSolver* pdSolver)
    : m_pdSolver(pdSolver), m_numPerturbationIterations(0), m_minimumPointsPerturbationThreshold(3)
{
}

btConvexConvexAlgorithm::CreateFunc::~CreateFunc() {}

btCollisionAlgorithm* btConvexConvexAlgorithm::CreateFunc::CreateCollisionAlgorithm(
    btCollisionAlgorithmConstructionInfo& ci, const btCollisionObjectWrapper* body0Wrap,
    const btCollisionObjectWrapper* body1Wrap)
{
	void* mem = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(caliber::CachedConvexConvexAlgorithm));
	return new (mem) caliber::CachedConvexConvexAlgorithm(ci.m_manifold, ci, body0Wrap, body1Wrap, m_pdSolver,
	                                                      m_numPerturbationIterations,
	                                                      m_minimumPointsPerturbationThreshold);
}

namespace caliber
{
int cachedConvexConvexAlgorithmSize() { return int(sizeof(CachedConvexConvexAlgorithm)); }

void CachedConvexConvexAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                                   const btCollisionObjectWrapper* body1Wrap,
                                                   const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut)
{
	const btScalar cacheDistance = contactCacheDistance();
	if (resultOut && body0Wrap && body1Wrap && body0Wrap->getCollisionShape() && body1Wrap->getCollisionShape() &&
	    pairMayUseContactCache(this->*memberOf(ConvexPairOwnsManifold{}), body0Wrap, body1Wrap, cacheDistance) &&
	    slowEnoughForContactCache(resultOut->m_closestPointDistanceThreshold, cacheDistance))
	{
		const btConvexShape* shape0 = static_cast<const btConvexShape*>(body0Wrap->getCollisionShape());
		const btConvexShape* shape1 = static_cast<const btConvexShape*>(body1Wrap->getCollisionShape());
		// Triangles (a mesh's, or a lone btTriangleShape) take the face paths, which are not cached.
		if (polyhedronOf(shape0) && polyhedronOf(shape1) && shape0->getShapeType() != TRIANGLE_SHAPE_PROXYTYPE &&
		    shape1->getShapeType() != TRIANGLE_SHAPE_PROXYTYPE)
		{
			PairShapes shapes;
			shape0->getAabb(btTransform::getIdentity(), shapes.min0, shapes.max0);
			shape1->getAabb(btTransform::getIdentity(), shapes.min1, shapes.max1);
			if (keepCachedContacts(m_poseCache, this->*memberOf(ConvexPairManifold{}), shapes, body0Wrap, body1Wrap,
			                       resultOut, cacheDistance))
				return;
			const btTransform& t0 = body0Wrap->getWorldTransform();
			const btTransform& t1 = body1Wrap->getWorldTransform();
			const btScalar reach = resultOut->m_closestPointDistanceThreshold;
			btConvexConvexAlgorithm::processCollision(body0Wrap, body1Wrap, dispatchInfo, resultOut);
			btPersistentManifold* made = this->*memberOf(ConvexPairManifold{});
			m_poseCache.store(t0, t1, reach, shapes, made ? made->getNumContacts() : -1);
			return;
		}
	}
	m_poseCache.valid = false;
	btConvexConvexAlgorithm::processCollision(body0Wrap, body1Wrap, dispatchInfo, resultOut);
}
}  // namespace caliber

btConvexConvexAlgorithm::btConvexConvexAlgorithm(btPersistentManifold* mf,
                                                 const btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0Wrap,
                                                 const btCollisionObjectWrapper* body1Wrap,
                                                 btConvexPenetrationDepthSolver* pdSolver,
                                                 int numPerturbationIterations, int minimumPointsPerturbationThreshold)
    : btActivatingCollisionAlgorithm(ci, body0Wrap, body1Wrap),
      m_pdSolver(pdSolver),
      m_ownManifold(false),
      m_manifoldPtr(mf),
      m_lowLevelOfDetail(false),
      m_numPerturbationIterations(numPerturbationIterations),
      m_minimumPointsPerturbationThreshold(minimumPointsPerturbationThreshold),
      m_lastSeparatingAxis(btScalar(0), btScalar(1), btScalar(0)),
      m_haveLastSeparatingAxis(false)
{
}

btConvexConvexAlgorithm::~btConvexConvexAlgorithm()
{
	if (m_ownManifold && m_manifoldPtr) m_dispatcher->releaseManifold(m_manifoldPtr);
}

void btConvexConvexAlgorithm::processCollision(const btCollisionObjectWrapper* body0Wrap,
                                               const btCollisionObjectWrapper* body1Wrap,
                                               const btDispatcherInfo& dispatchInfo, btManifoldResult* resultOut)
{
	if (!resultOut || !body0Wrap || !body1Wrap) return;
	if (!m_manifoldPtr)
	{
		if (!m_dispatcher) return;
		m_manifoldPtr = m_dispatcher->getNewManifold(body0Wrap->getCollisionObject(), body1Wrap->getCollisionObject());
		// A full manifold pool without dynamic allocation gives none: the pair is skipped this step.
		if (!m_manifoldPtr) return;
		m_ownManifold = true;
	}
	caliber::prefetchWholeManifold(m_manifoldPtr);
	resultOut->setPersistentManifold(m_manifoldPtr);
	if (!caliber::pairIsUsable(body0Wrap, body1Wrap))
	{
		if (m_ownManifold) m_manifoldPtr->clearManifold();
		return;
	}

	const btConvexShape* shapeA = static_cast<const btConvexShape*>(body0Wrap->getCollisionShape());
	const btConvexShape* shapeB = static_cast<const btConvexShape*>(body1Wrap->getCollisionShape());
	const btScalar reach = m_manifoldPtr->getContactBreakingThreshold() + resultOut->m_closestPointDistanceThreshold;

	const bool againstTriangle = shapeB->getShapeType() == TRIANGLE_SHAPE_PROXYTYPE;
	const caliber::TriangleClipping clipping =
	    againstTriangle ? caliber::triangleClippingOf(*shapeA) : caliber::kNoClipping;
	bool facePointsReported = false;
	caliber::TriangleFaceSearch faceSearch;
	if (contactWithoutGjk(shapeA, body0Wrap->getWorldTransform(), shapeB, body1Wrap->getWorldTransform(), clipping,
	                      reach, *resultOut, facePointsReported, faceSearch))
	{
		if (m_ownManifold) resultOut->refreshContactPoints();
		return;
	}

	btVoronoiSimplexSolver simplexSolver;
	btGjkPairDetector gjk(shapeA, shapeB, &simplexSolver, m_pdSolver);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = body0Wrap->getWorldTransform();
	input.m_transformB = body1Wrap->getWorldTransform();
	const btScalar maxDistance = shapeA->getMargin() + shapeB->getMargin() + reach;
	input.m_maximumDistanceSquared = maxDistance * maxDistance;

	// One algorithm serves all the triangles of a convex-mesh pair: each starts from its normal. A pair
	// of its own starts from where its last step ended (bodies move little per step: a pair kept apart
	// last step is usually shown apart again by the first support step).
	btVector3 startAxis;
	const bool triangle = triangleStartAxis(shapeA, input.m_transformA, shapeB, input.m_transformB, startAxis);
	if (triangle)
	{
		// A hull the face search along the triangle's normal left to GJK lies beside the triangle or over an
		// edge: the way from the triangle's nearest point to the hull's origin separates them sooner.
		if (faceSearch.done)
		{
			const btVector3* corners = faceSearch.world.corners;
			const btVector3 away =
			    input.m_transformA.getOrigin() -
			    caliber::closestPointOnTriangle(input.m_transformA.getOrigin(), corners[0], corners[1], corners[2]);
			if (away.length2() > SIMD_EPSILON) startAxis = away;
		}
		gjk.setCachedSeperatingAxis(startAxis);
	}
	else if (m_haveLastSeparatingAxis)
		gjk.setCachedSeperatingAxis(m_lastSeparatingAxis);

	GjkPointResult gjkPoint;
	gjk.getClosestPoints(input, gjkPoint, dispatchInfo.m_debugDraw);
	if (!triangle)
	{
		m_lastSeparatingAxis = gjk.getCachedSeparatingAxis();
		m_haveLastSeparatingAxis = true;
	}

	// A hull or polyhedron against a mesh triangle: its face (or edge) clipped against the triangle once
	// GJK's normal is the triangle's face normal, i.e. the hull lies over the triangle's face (against a
	// triangle's edge or vertex GJK's point is the contact, and no face is searched). Also at rest on a
	// full manifold: GJK's single point (any point of the face) would replace one of the face's corners in
	// the manifold, and a narrow face rocks on the changing set.
	if (clipping == caliber::kClipAfterGjk && gjkPoint.found() && gjkPoint.m_distance <= reach)
	{
		const caliber::TriangleFaceOutcome outcome = caliber::triangleFaceContactAlongGjkNormal(
		    *shapeA, input.m_transformA, *static_cast<const btTriangleShape*>(shapeB), input.m_transformB, reach,
		    gjkPoint.m_normalOnSurfaceB, gjkPoint.m_distance, m_manifoldPtr->getContactBreakingThreshold(), *resultOut,
		    &faceSearch);
		if (outcome == caliber::kTriangleFaceContact || outcome == caliber::kTriangleOutOfReach)
		{
			if (m_ownManifold) resultOut->refreshContactPoints();
			return;
		}
		facePointsReported = outcome == caliber::kTriangleFacePointsAndGjk;
	}

	const btConvexPolyhedron* polyA = polyhedronOf(shapeA);
	const btConvexPolyhedron* polyB = polyhedronOf(shapeB);
	if (polyA && polyB && !facePointsReported)
	{
		const PolyhedralPair pair = {shapeA, shapeB, polyA, polyB, &input, body0Wrap, body1Wrap};
		clipPolyhedra(pair, gjkPoint, dispatchInfo, reach, m_ownManifold ? m_manifoldPtr : 0, worldVertsB1,
		              worldVertsB2, *resultOut);
		if (m_ownManifold) resultOut->refreshContactPoints();
		return;
	}

	if (gjkPoint.found())
		resultOut->addContactPoint(gjkPoint.m_normalOnSurfaceB, gjkPoint.m_closestPointInB, gjkPoint.m_distance);

	// Optional multipoint: rotate the shape with the smaller angular disc slightly about axes across the
	// normal; each rotated copy touches at another point of a flat contact.
	if (gjkPoint.found() && m_numPerturbationIterations > 0 &&
	    m_manifoldPtr->getNumContacts() < m_minimumPointsPerturbationThreshold)
		addPerturbedPoints(gjk, simplexSolver, input, shapeA, shapeB, gjkPoint.m_normalOnSurfaceB,
		                   m_numPerturbationIterations, dispatchInfo.m_debugDraw, *resultOut);

	if (m_ownManifold) resultOut->refreshContactPoints();
}

btScalar btConvexConvexAlgorithm::calculateTimeOfImpact(btCollisionObject* body0, btCollisionObject* body1,
                                                        const btDispatcherInfo&, btManifoldResult*)
{
	btScalar fraction = btScalar(1);
	if (!body0 || !body1 || !body0->getCollisionShape() || !body1->getCollisionShape()) return fraction;
	// CCD only matters when one body moves farther than its motion threshold during the step.
	const btScalar motion0 =
	    (body0->getInterpolationWorldTransform().getOrigin() - body0->getWorldTransform().getOrigin()).length2();
	const btScalar motion1 =
	    (body1->getInterpolationWorldTransform().getOrigin() - body1->getWorldTransform().getOrigin()).length2();
	if (!(motion0 >= body0->getCcdSquareMotionThreshold()) && !(motion1 >= body1->getCcdSquareMotionThreshold()))
		return fraction;
	if (!caliber::isFinite(body0->getWorldTransform()) || !caliber::isFinite(body0->getInterpolationWorldTransform()) ||
	    !caliber::isFinite(body1->getWorldTransform()) || !caliber::isFinite(body1->getInterpolationWorldTransform()))
		return fraction;

	// Each body's shape is cast against the other body's CCD swept sphere (a conservative inner core),
	// so thin fast bodies do not tunnel; the earliest hit wins and lowers both hit fractions.
	for (int side = 0; side < 2; ++side)
	{
		btCollisionObject* shapeBody = side == 0 ? body0 : body1;
		btCollisionObject* sphereBody = side == 0 ? body1 : body0;
		const btConvexShape* convex = static_cast<const btConvexShape*>(shapeBody->getCollisionShape());
		btSphereShape sweptSphere(sphereBody->getCcdSweptSphereRadius());
		btVoronoiSimplexSolver simplexSolver;
		btGjkConvexCast cast(convex, &sweptSphere, &simplexSolver);
		btConvexCast::CastResult result;
		if (!cast.calcTimeOfImpact(shapeBody->getWorldTransform(), shapeBody->getInterpolationWorldTransform(),
		                           sphereBody->getWorldTransform(), sphereBody->getInterpolationWorldTransform(),
		                           result))
			continue;
		if (!(result.m_fraction >= btScalar(0) && result.m_fraction <= btScalar(1))) continue;
		if (body0->getHitFraction() > result.m_fraction) body0->setHitFraction(result.m_fraction);
		if (body1->getHitFraction() > result.m_fraction) body1->setHitFraction(result.m_fraction);
		if (fraction > result.m_fraction) fraction = result.m_fraction;
	}
	return fraction;
}

void btConvexConvexAlgorithm::getAllContactManifolds(btManifoldArray& manifoldArray)
{
	if (m_manifoldPtr && m_ownManifold) manifoldArray.push_back(m_manifoldPtr);
}
