// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CONVEX_CAST_HELPERS_H
#define CALIBER_CONVEX_CAST_HELPERS_H

// Internal helpers shared by the three convex casts: input checks, the tolerance of the conservative
// advancement casts, and the contact query used when shapes already touch at the start of a cast.

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/NarrowPhaseCollision/btConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"

class btConvexShape;
class btConvexPenetrationDepthSolver;

namespace caliber
{

// The conservative advancement casts (btGjkConvexCast, btContinuousConvexCollision) stop once the
// distance plus the allowed penetration is below this. Absolute, like Bullet's: a millimetre at metre
// scale in float, where GJK distances carry about 1e-5 of rounding at the scale of a few metres (a
// tighter stop could be unreachable); double rounds far less, so it stops much closer.
#ifdef BT_USE_DOUBLE_PRECISION
const btScalar kCastDistanceTolerance = btScalar(1e-6);
#else
const btScalar kCastDistanceTolerance = btScalar(1e-3);
#endif
// Conservative advancement steps before a cast gives up (reportFailure(-2, n), no hit). Face-on and
// centre-line approaches converge in 1-3 steps; grazing curved contacts take the most.
const int kCastMaxIterations = 64;

// A cast that runs out of iterations still reports its (conservative) fraction when the shapes are this
// close there: tight double-precision tolerances can take more steps than the limit on curved contacts,
// and a miss would let the shapes pass through each other. Farther away it reports a failure and no hit.
const btScalar kCastExhaustedAcceptDistance = btScalar(1e-3);

// Checks the inputs every cast shares. Asserts and returns false on null shapes or solver (when
// required) and on non-finite transforms; the cast then returns false and leaves its result alone.
inline bool castInputsValid(const void* shapeA, const void* shapeB, const void* simplexSolver, const btTransform& fromA,
                            const btTransform& toA, const btTransform& fromB, const btTransform& toB)
{
	const bool shapesOk = shapeA != nullptr && shapeB != nullptr && simplexSolver != nullptr;
	btAssert(shapesOk && "convex cast: null shape or simplex solver");
	const bool finite =
	    caliber::isFinite(fromA) && caliber::isFinite(toA) && caliber::isFinite(fromB) && caliber::isFinite(toB);
	btAssert(finite && "convex cast: non-finite transform");
	return shapesOk && finite;
}

// Closest points of two convex shapes (margins included) by btGjkPairDetector with depthSolver (may be
// null). Returns false when nothing was reported (overlapping cores without a depth solver, or a
// failed depth solver). normal is unit, from B towards A; pointOnB on B; distance < 0 when overlapping.
// axisHint (from B towards A; zero for none) starts GJK: the previous step's normal saves iterations.
bool castClosestPoints(const btConvexShape* shapeA, const btConvexShape* shapeB, const btTransform& transA,
                       const btTransform& transB, btSimplexSolverInterface* simplexSolver,
                       btConvexPenetrationDepthSolver* depthSolver, const btVector3& axisHint, btVector3& normal,
                       btVector3& pointOnB, btScalar& distance);

// Writes a hit into result.
inline void writeCastHit(btConvexCast::CastResult& result, btScalar fraction, const btVector3& normal,
                         const btVector3& pointOnB, const btTransform& transA, const btTransform& transB)
{
	result.m_fraction = fraction;
	result.m_normal = normal;
	result.m_hitPoint = pointOnB;
	result.m_hitTransformA = transA;
	result.m_hitTransformB = transB;
}

// The normal reported when the shapes overlap at the start and no depth is available: against the
// relative motion r of A (A came from there), or (0, 0, 0) when there is no motion.
inline btVector3 fallbackNormal(const btVector3& relativeMotionA)
{
	if (relativeMotionA.length2() > SIMD_EPSILON * SIMD_EPSILON) return -relativeMotionA.normalized();
	return btVector3(btScalar(0), btScalar(0), btScalar(0));
}

// What a cast does when the shapes already touch or overlap at its start. The casts' calcTimeOfImpact
// report a hit at fraction 0 with the contact of the start pose (EPA's normal when they overlap). The
// world's ray test against convex shapes uses kMiss, Bullet's answer: a ray does not hit a shape it starts
// inside (or within the cast's tolerance of), and costs no depth query.
enum class StartInContact
{
	kReportAtZero,
	kMiss
};

// btSubsimplexConvexCast::calcTimeOfImpact and btGjkConvexCast::calcTimeOfImpact with the start-contact
// rule as a parameter (the classes pass kReportAtZero).
bool subsimplexCast(const btConvexShape* shapeA, const btConvexShape* shapeB, btSimplexSolverInterface* simplexSolver,
                    const btTransform& fromA, const btTransform& toA, const btTransform& fromB, const btTransform& toB,
                    btConvexCast::CastResult& result, StartInContact startInContact);
bool gjkCast(const btConvexShape* shapeA, const btConvexShape* shapeB, btSimplexSolverInterface* simplexSolver,
             const btTransform& fromA, const btTransform& toA, const btTransform& fromB, const btTransform& toB,
             btConvexCast::CastResult& result, StartInContact startInContact);

}  // namespace caliber

#endif  // CALIBER_CONVEX_CAST_HELPERS_H
