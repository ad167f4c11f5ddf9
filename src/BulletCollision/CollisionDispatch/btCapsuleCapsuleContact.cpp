// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCapsuleCapsuleContact.h"

namespace caliber
{
namespace
{
btScalar clamp01(btScalar x) { return x < 0 ? btScalar(0) : (x > 1 ? btScalar(1) : x); }
}  // namespace

void closestPointsOfSegments(const btVector3& p0, const btVector3& p1, const btVector3& q0, const btVector3& q1,
                             btScalar& s, btScalar& t)
{
	// Minimise |p0 + s u - q0 - t v|^2 over the unit square: the unconstrained minimum along s for the
	// best t, clamped, then t for that s, clamped, then s again for the clamped t.
	const btVector3 u = p1 - p0, v = q1 - q0, w = p0 - q0;
	const btScalar uu = u.dot(u), vv = v.dot(v), uv = u.dot(v), uw = u.dot(w), vw = v.dot(w);
	const btScalar tiny = SIMD_EPSILON * SIMD_EPSILON;
	if (uu <= tiny && vv <= tiny)
	{
		s = t = 0;  // two points
		return;
	}
	if (uu <= tiny)
	{
		s = 0;
		t = clamp01(vw / vv);
		return;
	}
	if (vv <= tiny)
	{
		t = 0;
		s = clamp01(-uw / uu);
		return;
	}
	// Parallel segments (denominator 0) have a line of closest pairs: start from s = 0.
	const btScalar denominator = uu * vv - uv * uv;
	s = denominator > tiny * uu * vv ? clamp01((uv * vw - vv * uw) / denominator) : btScalar(0);
	t = (uv * s + vw) / vv;
	if (t < 0)
	{
		t = 0;
		s = clamp01(-uw / uu);
	}
	else if (t > 1)
	{
		t = 1;
		s = clamp01((uv - uw) / uu);
	}
}

bool capsuleCapsuleContact(const btCapsuleShape& a, const btTransform& ta, const btCapsuleShape& b,
                           const btTransform& tb, btVector3& normalOnB, btVector3& pointOnB, btScalar& distance)
{
	const btVector3 axisA = ta.getBasis().getColumn(a.getUpAxis()) * a.getHalfHeight();
	const btVector3 axisB = tb.getBasis().getColumn(b.getUpAxis()) * b.getHalfHeight();
	const btVector3 a0 = ta.getOrigin() - axisA, a1 = ta.getOrigin() + axisA;
	const btVector3 b0 = tb.getOrigin() - axisB, b1 = tb.getOrigin() + axisB;
	btScalar s, t;
	closestPointsOfSegments(a0, a1, b0, b1, s, t);
	const btVector3 onA = a0 + (a1 - a0) * s;
	const btVector3 onB = b0 + (b1 - b0) * t;
	const btVector3 between = onA - onB;
	const btScalar length2 = between.length2();
	const btScalar scale = btMax(a.getRadius() + b.getRadius(), btScalar(1e-3));
	if (!(length2 > scale * scale * btScalar(1e-10))) return false;
	const btScalar length = btSqrt(length2);
	normalOnB = between / length;
	pointOnB = onB + normalOnB * b.getRadius();
	distance = length - a.getRadius() - b.getRadius();
	return true;
}
}  // namespace caliber
