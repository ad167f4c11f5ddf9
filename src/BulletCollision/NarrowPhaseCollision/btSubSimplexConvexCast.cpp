// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "btConvexCastHelpers.h"

// GJK ray cast (van den Bergen, "Ray casting against general convex objects with application to
// continuous collision detection"). With C = A - B at the start transforms (margins included) and r
// the motion of A relative to B, the shapes touch at fraction t when the point x(t) = -t r lies on C.
// The loop keeps x outside C: whenever the support plane of C along v (the vector from the simplex's
// closest point to x) separates x from C, x jumps forward onto that plane, which cannot pass C.
// The simplex holds points p_i of C; its vertices x - p_i move with x, so it is rebuilt on each jump.

btSubsimplexConvexCast::btSubsimplexConvexCast(const btConvexShape* shapeA, const btConvexShape* shapeB,
                                               btSimplexSolverInterface* simplexSolver)
    : m_simplexSolver(simplexSolver), m_convexA(shapeA), m_convexB(shapeB)
{
}

namespace
{
struct SupportPair
{
	btVector3 onA;
	btVector3 onB;
};

// Support point of C = A - B along dir: A's farthest point along dir minus B's farthest against it. The
// surfaces are the cores grown by the margins (the rounded shapes GJK and EPA see; a box's
// localGetSupportingVertex would give its sharp corner instead).
SupportPair supportC(const btConvexShape* a, const btTransform& ta, btScalar marginA, const btConvexShape* b,
                     const btTransform& tb, btScalar marginB, const btVector3& dir)
{
	btVector3 unit = dir;
	const btScalar length2 = unit.length2();
	if (length2 > btScalar(0)) unit /= btSqrt(length2);
	SupportPair s;
	s.onA = ta(a->localGetSupportingVertexWithoutMargin(dir * ta.getBasis())) + unit * marginA;
	s.onB = tb(b->localGetSupportingVertexWithoutMargin(-dir * tb.getBasis())) - unit * marginB;
	return s;
}
}  // namespace

bool btSubsimplexConvexCast::calcTimeOfImpact(const btTransform& fromA, const btTransform& toA,
                                              const btTransform& fromB, const btTransform& toB, CastResult& result)
{
	return caliber::subsimplexCast(m_convexA, m_convexB, m_simplexSolver, fromA, toA, fromB, toB, result,
	                               caliber::StartInContact::kReportAtZero);
}

bool caliber::subsimplexCast(const btConvexShape* convexA, const btConvexShape* convexB,
                             btSimplexSolverInterface* simplexSolver, const btTransform& fromA, const btTransform& toA,
                             const btTransform& fromB, const btTransform& toB, btConvexCast::CastResult& result,
                             StartInContact startInContact)
{
	if (!caliber::castInputsValid(convexA, convexB, simplexSolver, fromA, toA, fromB, toB)) return false;

	// Work relative to the midpoint of the start origins so that far-away pairs keep their precision.
	const btVector3 offset = (fromA.getOrigin() + fromB.getOrigin()) * btScalar(0.5);
	btTransform transA = fromA, transB = fromB;
	transA.getOrigin() -= offset;
	transB.getOrigin() -= offset;
	const btVector3 motionA = toA.getOrigin() - fromA.getOrigin();
	const btVector3 motionB = toB.getOrigin() - fromB.getOrigin();
	const btVector3 relativeMotion = motionA - motionB;
	const btVector3 rayDir = -relativeMotion;

	const btScalar marginA = convexA->getMargin();
	const btScalar marginB = convexB->getMargin();
	const btScalar epsilonSquared = btMax(result.m_subSimplexCastEpsilon, btScalar(0));
	const int maxIterations = result.m_subSimplexCastMaxIterations;

	btSimplexSolverInterface& simplex = *simplexSolver;
	simplex.reset();

	btScalar lambda = btScalar(0);
	btVector3 x(btScalar(0), btScalar(0), btScalar(0));
	btVector3 lastPlaneNormal(btScalar(0), btScalar(0), btScalar(0));
	bool advanced = false;

	// Any point of C starts v.
	const SupportPair start = supportC(convexA, transA, marginA, convexB, transB, marginB, relativeMotion);
	btVector3 v = x - (start.onA - start.onB);
	btScalar distanceSquared = v.length2();

	int iteration = 0;
	while (distanceSquared > epsilonSquared)
	{
		if (iteration++ >= maxIterations)
		{
			result.reportFailure(-1, iteration - 1);
			if (advanced &&
			    distanceSquared <= caliber::kCastExhaustedAcceptDistance * caliber::kCastExhaustedAcceptDistance)
				break;
			return false;
		}
		const SupportPair s = supportC(convexA, transA, marginA, convexB, transB, marginB, v);
		const btVector3 p = s.onA - s.onB;
		const btVector3 w = x - p;
		if (!caliber::isFinite(w)) return false;
		const btScalar vDotW = v.dot(w);
		if (vDotW > btScalar(0))
		{
			// x is separated from C by the support plane; move x onto it, or miss when the ray does not
			// approach the plane.
			const btScalar vDotR = v.dot(rayDir);
			if (!(vDotR < btScalar(0))) return false;
			lambda -= vDotW / vDotR;
			if (lambda > btScalar(1)) return false;
			x = rayDir * lambda;
			lastPlaneNormal = v;
			advanced = true;
			if (result.m_debugDrawer) result.DebugDraw(lambda);

			// The kept vertices are x - p_i for the new x.
			btVector3 keptA[VORONOI_SIMPLEX_MAX_VERTS], keptB[VORONOI_SIMPLEX_MAX_VERTS],
			    keptW[VORONOI_SIMPLEX_MAX_VERTS];
			const int kept = simplex.getSimplex(keptA, keptB, keptW);
			simplex.reset();
			for (int i = 0; i < kept && i < 3; ++i) simplex.addVertex(x - (keptA[i] - keptB[i]), keptA[i], keptB[i]);
		}
		simplex.addVertex(x - p, s.onA, s.onB);
		if (!simplex.closest(v)) return false;
		distanceSquared = v.length2();
		// The closest point of a full tetrahedron is x itself: x is in C.
		if (simplex.fullSimplex()) distanceSquared = btScalar(0);
	}

	btVector3 normal;
	btVector3 pointOnB;
	if (!advanced)
	{
		if (startInContact == StartInContact::kMiss) return false;
		// The shapes touch or overlap at the start: report fraction 0 with the contact of the start pose.
		btVector3 onA, fallbackPoint = start.onB;
		if (!simplex.emptySimplex()) simplex.compute_points(onA, fallbackPoint);
		btGjkEpaPenetrationDepthSolver epa;
		btScalar distance;
		if (!caliber::castClosestPoints(convexA, convexB, transA, transB, simplexSolver, &epa,
		                                caliber::fallbackNormal(relativeMotion), normal, pointOnB, distance))
		{
			normal = caliber::fallbackNormal(relativeMotion);
			pointOnB = fallbackPoint;
		}
		pointOnB += offset;
		caliber::writeCastHit(result, btScalar(0), normal, pointOnB, fromA, fromB);
		return true;
	}

	// The simplex's face near x only approximates C's surface, so its direction can be off by the face's
	// size over the curvature radius. One distance query at the hit pose, where the shapes are within
	// sqrt(m_subSimplexCastEpsilon), gives the exact normal and point; the simplex's point and the
	// support plane of the last advance are the fallback.
	btVector3 onA, fallbackPoint;
	simplex.compute_points(onA, fallbackPoint);
	btTransform queryA = transA, queryB = transB;
	queryA.getOrigin() += motionA * lambda;
	queryB.getOrigin() += motionB * lambda;
	btGjkEpaPenetrationDepthSolver epa;
	btScalar distance;
	if (caliber::castClosestPoints(convexA, convexB, queryA, queryB, simplexSolver, &epa, -lastPlaneNormal,
	                               normal, pointOnB, distance))
	{
		pointOnB += offset;
	}
	else
	{
		normal = -lastPlaneNormal.normalized();
		pointOnB = fallbackPoint + motionB * lambda + offset;
	}
	btTransform hitA = fromA, hitB = fromB;
	hitA.getOrigin() += motionA * lambda;
	hitB.getOrigin() += motionB * lambda;
	if (result.m_debugDrawer) result.drawCoordSystem(hitA);
	caliber::writeCastHit(result, lambda, normal, pointOnB, hitA, hitB);
	return true;
}
