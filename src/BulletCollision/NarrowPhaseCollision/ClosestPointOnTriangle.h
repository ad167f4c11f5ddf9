// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CLOSEST_POINT_ON_TRIANGLE_H
#define CALIBER_CLOSEST_POINT_ON_TRIANGLE_H

// Closest points on segments and triangles (internal; the sphere-triangle detector and the soft
// bodies' mesh contacts share them).

#include "LinearMath/btVector3.h"

namespace caliber
{
// Closest point of segment [a, b] to p.
inline btVector3 closestPointOnSegment(const btVector3& p, const btVector3& a, const btVector3& b)
{
	const btVector3 ab = b - a;
	const btScalar length2 = ab.length2();
	if (length2 <= SIMD_EPSILON * SIMD_EPSILON) return a;
	const btScalar t = btClamped((p - a).dot(ab) / length2, btScalar(0), btScalar(1));
	return a + ab * t;
}

// Closest point of triangle (a, b, c) to p, by the Voronoi regions of its vertices, edges and face.
// A triangle whose area is too small for a stable face test falls back to its three edges.
inline btVector3 closestPointOnTriangle(const btVector3& p, const btVector3& a, const btVector3& b, const btVector3& c)
{
	const btVector3 ab = b - a, ac = c - a, ap = p - a;
	const btVector3 faceNormal = ab.cross(ac);
	const btScalar scale2 = btMax(ab.length2(), ac.length2());
	if (faceNormal.length2() <= SIMD_EPSILON * scale2 * scale2 || scale2 <= SIMD_EPSILON * SIMD_EPSILON)
	{
		btVector3 best = closestPointOnSegment(p, a, b);
		const btVector3 onBc = closestPointOnSegment(p, b, c);
		const btVector3 onCa = closestPointOnSegment(p, c, a);
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
}  // namespace caliber

#endif  // CALIBER_CLOSEST_POINT_ON_TRIANGLE_H
