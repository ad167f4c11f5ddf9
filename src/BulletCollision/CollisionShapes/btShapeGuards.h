// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SHAPE_GUARDS_H
#define CALIBER_SHAPE_GUARDS_H

// Internal helpers the shapes share to turn bad input into documented, finite results.

#include "LinearMath/btScalar.h"
#include "LinearMath/btVector3.h"
#include "LinearMath/btTransform.h"

namespace caliber
{

/// The documented AABB of a shape under a non-finite transform: [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3.
SIMD_FORCE_INLINE void setOverflowAabb(btVector3& aabbMin, btVector3& aabbMax)
{
	aabbMin.setValue(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
	aabbMax.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
}

/// Checks t for getAabb: true when it is usable; otherwise asserts, writes the overflow AABB and
/// returns false (release builds).
SIMD_FORCE_INLINE bool checkAabbTransform(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax)
{
	if (btLikely(caliber::isFinite(t))) return true;
	btAssert(caliber::isFinite(t) && "getAabb: non-finite transform");
	setOverflowAabb(aabbMin, aabbMax);
	return false;
}

/// A shape dimension made valid: |value| for finite values, 0 for NaN or infinite ones.
SIMD_FORCE_INLINE btScalar sanitizeDimension(btScalar value) { return btIsFinite(value) ? btFabs(value) : btScalar(0); }

/// The direction support functions use: dir itself, or (-1, -1, -1) when dir is zero, tiny or not finite
/// (every point of a shape is a support point for the zero direction; this picks one on the surface).
SIMD_FORCE_INLINE btVector3 supportDirection(const btVector3& dir)
{
	if (btLikely(caliber::isFinite(dir) && !(dir.length2() < SIMD_EPSILON * SIMD_EPSILON))) return dir;
	return btVector3(btScalar(-1), btScalar(-1), btScalar(-1));
}

/// Checks a mass for calculateLocalInertia: true when it is finite and >= 0; otherwise asserts, sets
/// inertia to (0, 0, 0) and returns false (release builds).
SIMD_FORCE_INLINE bool checkMass(btScalar mass, btVector3& inertia)
{
	if (btLikely(mass >= btScalar(0) && btIsFinite(mass))) return true;
	btAssert(mass >= btScalar(0) && btIsFinite(mass) && "calculateLocalInertia: bad mass");
	inertia.setValue(btScalar(0), btScalar(0), btScalar(0));
	return false;
}

/// A size given to a shape constructor or setter: asserts it is finite and >= 0, returns |size| (0 when
/// not finite).
SIMD_FORCE_INLINE btScalar checkSize(btScalar size)
{
	btAssert(size >= btScalar(0) && btIsFinite(size) && "shape size must be finite and >= 0");
	return sanitizeDimension(size);
}

/// checkSize per component.
SIMD_FORCE_INLINE btVector3 checkSize(const btVector3& size)
{
	return btVector3(checkSize(size.x()), checkSize(size.y()), checkSize(size.z()));
}

/// The margin-free local AABB of a convex shape from its supports along the six axis directions
/// (exact for a convex shape); both AABB-caching shape bases use it.
template <class ConvexShape>
inline void localAabbFromSupports(const ConvexShape& shape, btVector3& aabbMin, btVector3& aabbMax)
{
	static const btVector3 directions[6] = {btVector3(1, 0, 0),  btVector3(0, 1, 0),  btVector3(0, 0, 1),
	                                        btVector3(-1, 0, 0), btVector3(0, -1, 0), btVector3(0, 0, -1)};
	btVector3 supports[6];
	shape.batchedUnitVectorGetSupportingVertexWithoutMargin(directions, supports, 6);
	for (int axis = 0; axis < 3; ++axis)
	{
		aabbMax[axis] = supports[axis][axis];
		aabbMin[axis] = supports[axis + 3][axis];
	}
	aabbMin[3] = aabbMax[3] = 0;
}

}  // namespace caliber

#endif  // CALIBER_SHAPE_GUARDS_H
