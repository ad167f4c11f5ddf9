// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

namespace
{
// A hit point may lie this far outside an edge, in barycentric units, and still count: rays through a
// shared edge of a mesh then hit at least one of its two triangles despite rounding.
const btScalar kEdgeTolerance = btScalar(64) * SIMD_EPSILON;
// Triangles whose doubled area is below this fraction of the product of two edge lengths (the sine of
// their angle) are degenerate: their normal has no reliable direction.
const btScalar kDegenerateSine = btScalar(16) * SIMD_EPSILON;

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

	const btVector3& v0 = triangle[0];
	const btVector3 edge1 = triangle[1] - v0;
	const btVector3 edge2 = triangle[2] - v0;
	const btVector3 normal = edge1.cross(edge2);
	const btScalar normalLength2 = normal.length2();
	if (!(normalLength2 > kDegenerateSine * kDegenerateSine * edge1.length2() * edge2.length2())) return;

	// Signed distances of the ray's ends to the plane (times |normal|); a hit needs a strict sign change.
	const btScalar distFrom = normal.dot(m_from - v0);
	const btScalar distTo = normal.dot(m_to - v0);
	const bool crosses =
	    (distFrom > btScalar(0) && distTo < btScalar(0)) || (distFrom < btScalar(0) && distTo > btScalar(0));
	if (!crosses) return;
	const bool backFace = distFrom < btScalar(0);
	if (backFace && (m_flags & kF_FilterBackfaces)) return;

	const btScalar fraction = distFrom / (distFrom - distTo);
	if (!(fraction < m_hitFraction)) return;

	// Barycentric weights of the hit point (relative to v0 for precision): each is the signed area of
	// the sub-triangle opposite its corner over the whole area.
	const btVector3 hitRelative = (m_from - v0) + (m_to - m_from) * fraction;
	const btScalar invArea = btScalar(1) / normalLength2;
	// hit = weight1 * edge1 + weight2 * edge2 in the triangle's plane.
	const btScalar weight1 = hitRelative.cross(edge2).dot(normal) * invArea;
	const btScalar weight2 = edge1.cross(hitRelative).dot(normal) * invArea;
	const btScalar weight0 = btScalar(1) - weight1 - weight2;
	if (weight0 < -kEdgeTolerance || weight1 < -kEdgeTolerance || weight2 < -kEdgeTolerance) return;

	btVector3 hitNormal = normal / btSqrt(normalLength2);
	if (backFace && !(m_flags & kF_KeepUnflippedNormal)) hitNormal = -hitNormal;
	m_hitFraction = reportHit(hitNormal, fraction, partId, triangleIndex);
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
