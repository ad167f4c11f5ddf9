// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "btConvexCastHelpers.h"

// Conservative advancement for translations: with n the unit normal (B towards A) and d the signed
// distance at fraction t, every pair of points keeps n.(a - b) >= d + s n.r for the further fraction s
// of the relative motion r of A, so the distance cannot vanish before s = d / (-n.r). Stepping by
// that amount never passes the first contact and lands on it exactly for face-on approaches.

btGjkConvexCast::btGjkConvexCast(const btConvexShape* convexA, const btConvexShape* convexB,
                                 btSimplexSolverInterface* simplexSolver)
    : m_simplexSolver(simplexSolver), m_convexA(convexA), m_convexB(convexB)
{
}

bool btGjkConvexCast::calcTimeOfImpact(const btTransform& fromA, const btTransform& toA, const btTransform& fromB,
                                       const btTransform& toB, CastResult& result)
{
	return caliber::gjkCast(m_convexA, m_convexB, m_simplexSolver, fromA, toA, fromB, toB, result,
	                        caliber::StartInContact::kReportAtZero);
}

bool caliber::gjkCast(const btConvexShape* convexA, const btConvexShape* convexB, btSimplexSolverInterface* simplexSolver,
                      const btTransform& fromA, const btTransform& toA, const btTransform& fromB, const btTransform& toB,
                      btConvexCast::CastResult& result, StartInContact startInContact)
{
	if (!caliber::castInputsValid(convexA, convexB, simplexSolver, fromA, toA, fromB, toB)) return false;

	const btVector3 motionA = toA.getOrigin() - fromA.getOrigin();
	const btVector3 motionB = toB.getOrigin() - fromB.getOrigin();
	const btVector3 relativeMotion = motionA - motionB;
	const btScalar allowedPenetration = btIsFinite(result.m_allowedPenetration) ? result.m_allowedPenetration : 0;

	// Bullet's btGjkConvexCast has no depth solver; EPA here lets overlapping starts report a normal. With
	// kMiss an overlap at the start is a miss, so no depth is needed (GJK alone reports no overlap).
	btGjkEpaPenetrationDepthSolver epa;
	btConvexPenetrationDepthSolver* depthSolver = startInContact == StartInContact::kMiss ? nullptr : &epa;
	btTransform transA = fromA, transB = fromB;
	btScalar lambda = btScalar(0);
	btVector3 lastNormal = caliber::fallbackNormal(relativeMotion);
	for (int iteration = 0;; ++iteration)
	{
		btVector3 normal, pointOnB;
		btScalar distance;
		if (!caliber::castClosestPoints(convexA, convexB, transA, transB, simplexSolver, depthSolver, lastNormal, normal,
		                                pointOnB, distance))
		{
			// kMiss: cores that overlap at the start are no hit. Otherwise only a failed depth solver, or cores
			// reached through rounding after an advance, get here: the shapes overlap, so this is the contact.
			if (!depthSolver && iteration == 0) return false;
			caliber::writeCastHit(result, lambda, lastNormal, transB.getOrigin(), transA, transB);
			return true;
		}
		lastNormal = normal;
		const btScalar gap = distance + allowedPenetration;
		// kMiss: a start inside the shapes (margins included) or one that does not approach is no hit.
		if (iteration == 0 && startInContact == StartInContact::kMiss && gap <= caliber::kCastDistanceTolerance &&
		    (distance < btScalar(0) || !(normal.dot(relativeMotion) < btScalar(0))))
			return false;
		if (gap <= caliber::kCastDistanceTolerance)
		{
			caliber::writeCastHit(result, lambda, normal, pointOnB, transA, transB);
			return true;
		}
		if (iteration + 1 >= caliber::kCastMaxIterations)
		{
			result.reportFailure(-2, iteration + 1);
			if (gap > caliber::kCastExhaustedAcceptDistance) return false;
			caliber::writeCastHit(result, lambda, normal, pointOnB, transA, transB);
			return true;
		}
		const btScalar approachSpeed = -normal.dot(relativeMotion);
		if (!(approachSpeed > SIMD_EPSILON)) return false;
		btScalar next = lambda + gap / approachSpeed;
		if (next > btScalar(1))
		{
			// The end of the motion may still come within the tolerance: look there once.
			if (lambda < btScalar(1) && lambda + (gap - caliber::kCastDistanceTolerance) / approachSpeed <= btScalar(1))
				next = btScalar(1);
			else
				return false;
		}
		lambda = next;
		transA.setOrigin(fromA.getOrigin() + motionA * lambda);
		transB.setOrigin(fromB.getOrigin() + motionB * lambda);
		if (result.m_debugDrawer)
		{
			result.DebugDraw(lambda);
			result.drawCoordSystem(transA);
		}
	}
}
