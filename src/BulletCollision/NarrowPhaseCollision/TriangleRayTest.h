// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TRIANGLE_RAY_TEST_H
#define CALIBER_TRIANGLE_RAY_TEST_H

// Internal: the triangle ray test of btTriangleRaycastCallback::processTriangle without its input checks, for
// callers that already know the triangle and the ray to be finite (the world's ray test reads mesh triangles
// through checks of its own). processTriangle checks and then runs this, so both give the same answers, bit
// for bit.

#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"

namespace caliber
{
// A hit point may lie this far outside an edge, in barycentric units, and still count: rays through a
// shared edge of a mesh then hit at least one of its two triangles despite rounding.
const btScalar kTriangleRayEdgeTolerance = btScalar(64) * SIMD_EPSILON;
// Triangles whose doubled area is below this fraction of the product of two edge lengths (the sine of
// their angle) are degenerate: their normal has no reliable direction.
const btScalar kTriangleRayDegenerateSine = btScalar(16) * SIMD_EPSILON;

/// The ray callback.m_from -> callback.m_to against triangle[0..2] (all finite): on a hit below
/// callback.m_hitFraction, reports it through callback.reportHit and stores the bound it returns.
SIMD_FORCE_INLINE void testRayAgainstFiniteTriangle(btTriangleRaycastCallback& callback, const btVector3* triangle,
                                                    int partId, int triangleIndex)
{
	const btVector3& from = callback.m_from;
	const btVector3& to = callback.m_to;
	const btVector3& v0 = triangle[0];
	const btVector3 edge1 = triangle[1] - v0;
	const btVector3 edge2 = triangle[2] - v0;
	const btVector3 normal = edge1.cross(edge2);
	const btScalar normalLength2 = normal.length2();
	if (!(normalLength2 > kTriangleRayDegenerateSine * kTriangleRayDegenerateSine * edge1.length2() * edge2.length2()))
		return;

	// Signed distances of the ray's ends to the plane (times |normal|); a hit needs a strict sign change.
	const btScalar distFrom = normal.dot(from - v0);
	const btScalar distTo = normal.dot(to - v0);
	const bool crosses =
	    (distFrom > btScalar(0) && distTo < btScalar(0)) || (distFrom < btScalar(0) && distTo > btScalar(0));
	if (!crosses) return;
	const bool backFace = distFrom < btScalar(0);
	if (backFace && (callback.m_flags & btTriangleRaycastCallback::kF_FilterBackfaces)) return;

	const btScalar fraction = distFrom / (distFrom - distTo);
	if (!(fraction < callback.m_hitFraction)) return;

	// Barycentric weights of the hit point (relative to v0 for precision): each is the signed area of
	// the sub-triangle opposite its corner over the whole area.
	const btVector3 hitRelative = (from - v0) + (to - from) * fraction;
	const btScalar invArea = btScalar(1) / normalLength2;
	// hit = weight1 * edge1 + weight2 * edge2 in the triangle's plane.
	const btScalar weight1 = hitRelative.cross(edge2).dot(normal) * invArea;
	const btScalar weight2 = edge1.cross(hitRelative).dot(normal) * invArea;
	const btScalar weight0 = btScalar(1) - weight1 - weight2;
	if (weight0 < -kTriangleRayEdgeTolerance || weight1 < -kTriangleRayEdgeTolerance ||
	    weight2 < -kTriangleRayEdgeTolerance)
		return;

	btVector3 hitNormal = normal / btSqrt(normalLength2);
	if (backFace && !(callback.m_flags & btTriangleRaycastCallback::kF_KeepUnflippedNormal)) hitNormal = -hitNormal;
	callback.m_hitFraction = callback.reportHit(hitNormal, fraction, partId, triangleIndex);
}
}  // namespace caliber

#endif  // CALIBER_TRIANGLE_RAY_TEST_H
