// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/SphereTriangleDetector.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"

namespace
{
// Closest point of segment [a, b] to p.
btVector3 closestOnSegment(const btVector3& p, const btVector3& a, const btVector3& b)
{
	const btVector3 ab = b - a;
	const btScalar length2 = ab.length2();
	if (length2 <= SIMD_EPSILON * SIMD_EPSILON) return a;
	const btScalar t = btClamped((p - a).dot(ab) / length2, btScalar(0), btScalar(1));
	return a + ab * t;
}

// Closest point of triangle (a, b, c) to p, by the Voronoi regions of its vertices, edges and face.
// A triangle whose area is too small for a stable face test falls back to its three edges.
btVector3 closestOnTriangle(const btVector3& p, const btVector3& a, const btVector3& b, const btVector3& c)
{
	const btVector3 ab = b - a, ac = c - a, ap = p - a;
	const btVector3 faceNormal = ab.cross(ac);
	const btScalar scale2 = btMax(ab.length2(), ac.length2());
	if (faceNormal.length2() <= SIMD_EPSILON * scale2 * scale2 || scale2 <= SIMD_EPSILON * SIMD_EPSILON)
	{
		btVector3 best = closestOnSegment(p, a, b);
		const btVector3 onBc = closestOnSegment(p, b, c);
		const btVector3 onCa = closestOnSegment(p, c, a);
		if ((onBc - p).length2() < (best - p).length2()) best = onBc;
		if ((onCa - p).length2() < (best - p).length2()) best = onCa;
		return best;
	}
	const btScalar d1 = ab.dot(ap), d2 = ac.dot(ap);
	if (d1 <= 0 && d2 <= 0) return a;
	const btVector3 bp = p - b;
	const btScalar d3 = ab.dot(bp), d4 = ac.dot(bp);
	if (d3 >= 0 && d4 <= d3) return b;
	const btScalar vc = d1 * d4 - d3 * d2;
	if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
	const btVector3 cp = p - c;
	const btScalar d5 = ab.dot(cp), d6 = ac.dot(cp);
	if (d6 >= 0 && d5 <= d6) return c;
	const btScalar vb = d5 * d2 - d1 * d6;
	if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
	const btScalar va = d3 * d6 - d5 * d4;
	if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
	const btScalar denom = btScalar(1) / (va + vb + vc);
	return a + ab * (vb * denom) + ac * (vc * denom);
}
}  // namespace

SphereTriangleDetector::SphereTriangleDetector(btSphereShape* sphere, btTriangleShape* triangle,
                                               btScalar contactBreakingThreshold)
    : m_sphere(sphere), m_triangle(triangle), m_contactBreakingThreshold(contactBreakingThreshold)
{
}

bool SphereTriangleDetector::collide(const btVector3& sphereCenter, btVector3& point, btVector3& resultNormal,
                                     btScalar& depth, btScalar& timeOfImpact, btScalar contactBreakingThreshold)
{
	timeOfImpact = btScalar(1);
	const btVector3& a = m_triangle->getVertexPtr(0);
	const btVector3& b = m_triangle->getVertexPtr(1);
	const btVector3& c = m_triangle->getVertexPtr(2);
	const btScalar radius = m_sphere->getRadius();

	point = closestOnTriangle(sphereCenter, a, b, c);
	const btVector3 offset = sphereCenter - point;
	const btScalar distance = offset.length();
	if (distance - radius > contactBreakingThreshold) return false;

	const btScalar scale = btMax(btMax((b - a).length(), (c - a).length()), btScalar(1));
	if (distance > SIMD_EPSILON * scale)
	{
		resultNormal = offset / distance;
	}
	else
	{
		// The centre lies on the triangle: push out along the face normal (any unit vector for a
		// degenerate triangle, which has no face to push through).
		btVector3 faceNormal = (b - a).cross(c - a);
		const btScalar normalLength = faceNormal.length();
		resultNormal = normalLength > SIMD_EPSILON ? faceNormal / normalLength : btVector3(0, 1, 0);
	}
	depth = distance - radius;
	return true;
}

void SphereTriangleDetector::getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw*,
                                              bool swapResults)
{
	const bool usable =
	    m_sphere && m_triangle && caliber::isFinite(input.m_transformA) && caliber::isFinite(input.m_transformB);
	btAssert(usable && "SphereTriangleDetector: null shape or non-finite transform");
	if (!usable) return;

	const btTransform& triangleTransform = input.m_transformB;
	const btVector3 centreInTriangle = triangleTransform.invXform(input.m_transformA.getOrigin());
	btVector3 point, normal;
	btScalar depth, timeOfImpact;
	if (!collide(centreInTriangle, point, normal, depth, timeOfImpact, m_contactBreakingThreshold)) return;

	const btVector3 normalWorld = triangleTransform.getBasis() * normal;
	const btVector3 pointWorld = triangleTransform(point);
	if (swapResults)
	{
		// Reported as (triangle, sphere): the normal points at the triangle, the point lies on the sphere.
		output.addContactPoint(-normalWorld, pointWorld + normalWorld * depth, depth);
	}
	else
	{
		output.addContactPoint(normalWorld, pointWorld, depth);
	}
}
