// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/NarrowPhaseCollision/btConvexPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "LinearMath/btTransformUtil.h"
#include "btConvexCastHelpers.h"

// Conservative advancement with rotation (Mirtich's bound, as in Coumans' continuous collision
// detection): a point of A at distance at most rA from A's origin moves along the unit normal n at most
// |v_A . n| + |w_A| rA per unit fraction, and likewise for B, so the signed distance d cannot vanish
// before the further fraction d / (-(v_A - v_B) . n + |w_A| rA + |w_B| rB). rA and rB are the shapes'
// getAngularMotionDisc(). Stepping by that bound never passes the first contact.

btContinuousConvexCollision::btContinuousConvexCollision(const btConvexShape* shapeA, const btConvexShape* shapeB,
                                                         btSimplexSolverInterface* simplexSolver,
                                                         btConvexPenetrationDepthSolver* penetrationDepthSolver)
    : m_simplexSolver(simplexSolver),
      m_penetrationDepthSolver(penetrationDepthSolver),
      m_convexA(shapeA),
      m_convexB1(shapeB),
      m_planeShape(nullptr)
{
}

btContinuousConvexCollision::btContinuousConvexCollision(const btConvexShape* shapeA, const btStaticPlaneShape* plane)
    : m_simplexSolver(nullptr),
      m_penetrationDepthSolver(nullptr),
      m_convexA(shapeA),
      m_convexB1(nullptr),
      m_planeShape(plane)
{
}

namespace
{
// The signed distance (margins included) of convexA placed by transA and B (convexB, or else plane)
// placed by transB, into pointCollector. GJK starts from separatingAxisHint unless it is zero.
void closestPoints(const btConvexShape* convexA, const btConvexShape* convexB, const btStaticPlaneShape* plane,
                   btSimplexSolverInterface* simplexSolver, btConvexPenetrationDepthSolver* penetrationDepthSolver,
                   const btTransform& transA, const btTransform& transB, const btVector3& separatingAxisHint,
                   btPointCollector& pointCollector)
{
	if (convexB)
	{
		btGjkPairDetector detector(convexA, convexB, simplexSolver, penetrationDepthSolver);
		if (!separatingAxisHint.fuzzyZero()) detector.setCachedSeperatingAxis(separatingAxisHint);
		btDiscreteCollisionDetectorInterface::ClosestPointInput input;
		input.m_transformA = transA;
		input.m_transformB = transB;
		detector.getClosestPointsNonVirtual(input, pointCollector, nullptr);
		return;
	}
	// Convex against plane: A's deepest point against the world normal gives the signed distance. The
	// core's support plus the margin is the rounded surface GJK sees, so both paths agree (a box's
	// localGetSupportingVertex would give its sharp corner instead).
	const btVector3 normal = transB.getBasis() * plane->getPlaneNormal();
	const btVector3 planePoint = transB(plane->getPlaneNormal() * plane->getPlaneConstant());
	const btVector3 deepestOnA = transA(convexA->localGetSupportingVertexWithoutMargin(-normal * transA.getBasis())) -
	                             normal * convexA->getMargin();
	const btScalar distance = normal.dot(deepestOnA - planePoint);
	pointCollector.addContactPoint(normal, deepestOnA - normal * distance, distance);
}
}  // namespace

void btContinuousConvexCollision::computeClosestPoints(const btTransform& transA, const btTransform& transB,
                                                       btPointCollector& pointCollector)
{
	closestPoints(m_convexA, m_convexB1, m_planeShape, m_simplexSolver, m_penetrationDepthSolver, transA, transB,
	              btVector3(0, 0, 0), pointCollector);
}

namespace
{
// The pose at fraction t of the screw motion (from, linear velocity, angular velocity) over [0, 1].
// btTransformUtil::integrateTransform caps the angle of one step at a quarter of pi, which suits time
// steps but would bend the path between two given poses, so the rotation is applied here in full.
void poseAt(const btTransform& from, const btVector3& linVel, const btVector3& angVel, btScalar angle, btScalar t,
            btTransform& pose)
{
	pose.setOrigin(from.getOrigin() + linVel * t);
	if (angle > btScalar(0))
		pose.setBasis(btMatrix3x3(btQuaternion(angVel / angle, angle * t)) * from.getBasis());
	else
		pose.setBasis(from.getBasis());
}
}  // namespace

bool btContinuousConvexCollision::calcTimeOfImpact(const btTransform& fromA, const btTransform& toA,
                                                   const btTransform& fromB, const btTransform& toB, CastResult& result)
{
	const void* shapeB = m_convexB1 ? static_cast<const void*>(m_convexB1) : static_cast<const void*>(m_planeShape);
	// The plane case needs no simplex solver.
	const void* solver = m_convexB1 ? static_cast<const void*>(m_simplexSolver) : shapeB;
	if (!caliber::castInputsValid(m_convexA, shapeB, solver, fromA, toA, fromB, toB)) return false;

	btVector3 linVelA, angVelA, linVelB, angVelB;
	btTransformUtil::calculateVelocity(fromA, toA, btScalar(1), linVelA, angVelA);
	btTransformUtil::calculateVelocity(fromB, toB, btScalar(1), linVelB, angVelB);
	const btScalar angleA = angVelA.length();
	const btScalar angleB = angVelB.length();
	// The radii cost an AABB each, so they are only asked for when the shape turns. A plane has no
	// bounded radius; planes are static, so its rotation is followed but not bounded.
	const btScalar radiusA = angleA > btScalar(0) ? m_convexA->getAngularMotionDisc() : btScalar(0);
	const btScalar radiusB = (m_convexB1 && angleB > btScalar(0)) ? m_convexB1->getAngularMotionDisc() : btScalar(0);
	const btScalar angularBound = angleA * radiusA + angleB * radiusB;
	const btVector3 relativeLinVel = linVelA - linVelB;
	const btScalar allowedPenetration = btIsFinite(result.m_allowedPenetration) ? result.m_allowedPenetration : 0;

	btTransform transA = fromA, transB = fromB;
	btScalar lambda = btScalar(0);
	btVector3 lastNormal = caliber::fallbackNormal(relativeLinVel);
	// Each GJK call starts from the last normal found.
	btVector3 separatingAxisHint = lastNormal;
	btVector3 lastPoint = fromB.getOrigin();
	for (int iteration = 0;; ++iteration)
	{
		btPointCollector collector;
		closestPoints(m_convexA, m_convexB1, m_planeShape, m_simplexSolver, m_penetrationDepthSolver, transA, transB,
		              separatingAxisHint, collector);
		if (!collector.m_hasResult || !btIsFinite(collector.m_distance) ||
		    !caliber::isFinite(collector.m_normalOnBInWorld))
		{
			// Overlapping cores without a (working) depth solver: advancement never gets here from a
			// separated start, so the shapes overlapped already; this is the contact.
			caliber::writeCastHit(result, lambda, lastNormal, lastPoint, transA, transB);
			return true;
		}
		const btVector3 normal = collector.m_normalOnBInWorld;
		lastNormal = normal;
		separatingAxisHint = normal;
		lastPoint = collector.m_pointInWorld;
		const btScalar gap = collector.m_distance + allowedPenetration;
		if (gap <= caliber::kCastDistanceTolerance)
		{
			caliber::writeCastHit(result, lambda, normal, collector.m_pointInWorld, transA, transB);
			return true;
		}
		if (iteration + 1 >= caliber::kCastMaxIterations)
		{
			result.reportFailure(-2, iteration + 1);
			if (gap > caliber::kCastExhaustedAcceptDistance) return false;
			caliber::writeCastHit(result, lambda, normal, collector.m_pointInWorld, transA, transB);
			return true;
		}
		const btScalar approachBound = -normal.dot(relativeLinVel) + angularBound;
		if (!(approachBound > SIMD_EPSILON)) return false;
		btScalar next = lambda + gap / approachBound;
		if (next > btScalar(1))
		{
			// The end of the motion may still come within the tolerance: look there once.
			if (lambda < btScalar(1) && lambda + (gap - caliber::kCastDistanceTolerance) / approachBound <= btScalar(1))
				next = btScalar(1);
			else
				return false;
		}
		lambda = next;
		poseAt(fromA, linVelA, angVelA, angleA, lambda, transA);
		poseAt(fromB, linVelB, angVelB, angleB, lambda, transB);
		if (result.m_debugDrawer)
		{
			result.DebugDraw(lambda);
			result.drawCoordSystem(transA);
		}
	}
}
