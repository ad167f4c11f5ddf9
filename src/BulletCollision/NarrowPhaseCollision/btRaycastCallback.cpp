// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "TriangleRayTest.h"

namespace
{
bool trianglesFinite(const btVector3* triangle)
{
	return caliber::isFinite(triangle[0]) && caliber::isFinite(triangle[1]) && caliber::isFinite(triangle[2]);
}
}  // namespace

btTriangleRaycastCallback::btTriangleRaycastCallback(const btVector3& from, const btVector3& to, unsigned int flags)
    : m_from(from), m_to(to), m_flags(flags), m_hitFraction(btScalar(1))
{
}

void btTriangleRaycastCallback::processTriangle(btVector3* triangle, int partId, int triangleIndex)
{
	btAssert(triangle && trianglesFinite(triangle) && "ray test: non-finite triangle");
	btAssert(caliber::isFinite(m_from) && caliber::isFinite(m_to) && "ray test: non-finite ray");
	if (!triangle || !trianglesFinite(triangle) || !caliber::isFinite(m_from) || !caliber::isFinite(m_to)) return;

	caliber::testRayAgainstFiniteTriangle(*this, triangle, partId, triangleIndex);
}

btTriangleConvexcastCallback::btTriangleConvexcastCallback(const btConvexShape* convexShape,
                                                           const btTransform& convexShapeFrom,
                                                           const btTransform& convexShapeTo,
                                                           const btTransform& triangleToWorld,
                                                           const btScalar triangleCollisionMargin)
    : m_convexShape(convexShape),
      m_convexShapeFrom(convexShapeFrom),
      m_convexShapeTo(convexShapeTo),
      m_triangleToWorld(triangleToWorld),
      m_hitFraction(btScalar(1)),
      m_triangleCollisionMargin(triangleCollisionMargin),
      m_allowedPenetration(btScalar(0))
{
}

void btTriangleConvexcastCallback::processTriangle(btVector3* triangle, int partId, int triangleIndex)
{
	btAssert(m_convexShape && "convex sweep: null shape");
	btAssert(triangle && trianglesFinite(triangle) && "convex sweep: non-finite triangle");
	if (!m_convexShape || !triangle || !trianglesFinite(triangle)) return;

	btTriangleShape triangleShape(triangle[0], triangle[1], triangle[2]);
	triangleShape.setMargin(m_triangleCollisionMargin);
	btVoronoiSimplexSolver simplexSolver;
	btGjkEpaPenetrationDepthSolver depthSolver;
	btContinuousConvexCollision cast(m_convexShape, &triangleShape, &simplexSolver, &depthSolver);

	btConvexCast::CastResult result;
	result.m_fraction = m_hitFraction;
	result.m_allowedPenetration = m_allowedPenetration;
	if (!cast.calcTimeOfImpact(m_convexShapeFrom, m_convexShapeTo, m_triangleToWorld, m_triangleToWorld, result))
		return;
	// A zero normal (no direction could be found for an overlapping start) is not a usable hit.
	if (!(result.m_normal.length2() > btScalar(1e-4)) || !(result.m_fraction < m_hitFraction)) return;
	m_hitFraction =
	    reportHit(result.m_normal.normalized(), result.m_hitPoint, result.m_fraction, partId, triangleIndex);
}
