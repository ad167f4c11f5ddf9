// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_AABB_UTIL2
#define BT_AABB_UTIL2

/// Axis-aligned bounding box helpers: overlap tests, ray and segment tests, transformed boxes.
/// Boxes are closed: touching boxes overlap.

#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"
#include "LinearMath/btMinMax.h"

/// Grows a box: aabbMin += expansionMin, aabbMax += expansionMax.
SIMD_FORCE_INLINE void AabbExpand(btVector3& aabbMin, btVector3& aabbMax, const btVector3& expansionMin,
                                  const btVector3& expansionMax)
{
	aabbMin = aabbMin + expansionMin;
	aabbMax = aabbMax + expansionMax;
}

/// True when point lies in the box [aabbMin1, aabbMax1] (boundary included).
SIMD_FORCE_INLINE bool TestPointAgainstAabb2(const btVector3& aabbMin1, const btVector3& aabbMax1,
                                             const btVector3& point)
{
	return !(aabbMin1.x() > point.x() || aabbMax1.x() < point.x() || aabbMin1.y() > point.y() ||
	         aabbMax1.y() < point.y() || aabbMin1.z() > point.z() || aabbMax1.z() < point.z());
}

/// True when the two boxes overlap or touch.
SIMD_FORCE_INLINE bool TestAabbAgainstAabb2(const btVector3& aabbMin1, const btVector3& aabbMax1,
                                            const btVector3& aabbMin2, const btVector3& aabbMax2)
{
	return !(aabbMin1.x() > aabbMax2.x() || aabbMax1.x() < aabbMin2.x() || aabbMin1.y() > aabbMax2.y() ||
	         aabbMax1.y() < aabbMin2.y() || aabbMin1.z() > aabbMax2.z() || aabbMax1.z() < aabbMin2.z());
}

/// Conservative triangle/box test: true when the triangle's own bounding box overlaps the box.
SIMD_FORCE_INLINE bool TestTriangleAgainstAabb2(const btVector3* vertices, const btVector3& aabbMin,
                                                const btVector3& aabbMax)
{
	// setMin/setMax take the same component as btMin/btMax would, NaN included.
	btVector3 triangleMin = vertices[0];
	btVector3 triangleMax = vertices[0];
	for (int corner = 1; corner < 3; ++corner)
	{
		triangleMin.setMin(vertices[corner]);
		triangleMax.setMax(vertices[corner]);
	}
	return TestAabbAgainstAabb2(triangleMin, triangleMax, aabbMin, aabbMax);
}

/// Which sides of the centred box [-halfExtent, halfExtent] point p lies outside of: bits 0, 1, 2
/// for below -x, -y, -z and bits 3, 4, 5 for above +x, +y, +z. 0 means inside.
SIMD_FORCE_INLINE int btOutcode(const btVector3& p, const btVector3& halfExtent)
{
	return (p.getX() < -halfExtent.getX() ? 0x01 : 0x0) | (p.getX() > halfExtent.getX() ? 0x08 : 0x0) |
	       (p.getY() < -halfExtent.getY() ? 0x02 : 0x0) | (p.getY() > halfExtent.getY() ? 0x10 : 0x0) |
	       (p.getZ() < -halfExtent.getZ() ? 0x04 : 0x0) | (p.getZ() > halfExtent.getZ() ? 0x20 : 0x0);
}

/// Slab test of the ray rayFrom + t * direction, t in [lambda_min, lambda_max], against the box
/// bounds[0] (min) .. bounds[1] (max). rayInvDirection holds 1 / direction (infinite for zero
/// components) and raySign[i] = (rayInvDirection[i] < 0). On a hit returns true and tmin is the entry
/// parameter (clamped to lambda_min when the ray starts inside).
SIMD_FORCE_INLINE bool btRayAabb2(const btVector3& rayFrom, const btVector3& rayInvDirection,
                                  const unsigned int raySign[3], const btVector3 bounds[2], btScalar& tmin,
                                  btScalar lambda_min, btScalar lambda_max)
{
	btScalar enter = lambda_min;
	btScalar exit = lambda_max;
	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar nearPlane = bounds[raySign[axis]][axis];
		const btScalar farPlane = bounds[1 - raySign[axis]][axis];
		btScalar tNear = (nearPlane - rayFrom[axis]) * rayInvDirection[axis];
		btScalar tFar = (farPlane - rayFrom[axis]) * rayInvDirection[axis];
		// A ray parallel to a slab gives 0 * inf = NaN when it starts on the slab's plane: treat that
		// as inside the slab on that axis.
		if (tNear != tNear) tNear = -SIMD_INFINITY;
		if (tFar != tFar) tFar = SIMD_INFINITY;
		if (tNear > enter) enter = tNear;
		if (tFar < exit) exit = tFar;
		if (enter > exit) return false;
	}
	tmin = enter;
	return true;
}

/// Segment rayFrom -> rayTo against the box. param is in/out: on entry the largest accepted fraction
/// (normally 1 or the closest hit so far); on a hit it becomes the entry fraction and normal the
/// outward normal of the face entered. A segment that starts inside the box hits at fraction 0
/// with a zero normal.
SIMD_FORCE_INLINE bool btRayAabb(const btVector3& rayFrom, const btVector3& rayTo, const btVector3& aabbMin,
                                 const btVector3& aabbMax, btScalar& param, btVector3& normal)
{
	const btVector3 direction = rayTo - rayFrom;
	btScalar enter = btScalar(0.0);
	btScalar exit = param;
	int enterAxis = -1;
	btScalar enterSign = btScalar(0.0);
	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar d = direction[axis];
		if (d == btScalar(0.0))
		{
			if (rayFrom[axis] < aabbMin[axis] || rayFrom[axis] > aabbMax[axis]) return false;
			continue;
		}
		const btScalar inv = btScalar(1.0) / d;
		btScalar t0 = (aabbMin[axis] - rayFrom[axis]) * inv;  // fraction at the min plane
		btScalar t1 = (aabbMax[axis] - rayFrom[axis]) * inv;  // fraction at the max plane
		btScalar faceSign = btScalar(-1.0);                   // entering through the min face
		if (t0 > t1)
		{
			btSwap(t0, t1);
			faceSign = btScalar(1.0);
		}
		if (t0 > enter)
		{
			enter = t0;
			enterAxis = axis;
			enterSign = faceSign;
		}
		if (t1 < exit) exit = t1;
		if (enter > exit) return false;
	}
	param = enter;
	normal.setValue(btScalar(0.0), btScalar(0.0), btScalar(0.0));
	if (enterAxis >= 0) normal[enterAxis] = enterSign;
	return true;
}

/// World box of a centred local box (halfExtents grown by margin) under transform t.
SIMD_FORCE_INLINE void btTransformAabb(const btVector3& halfExtents, btScalar margin, const btTransform& t,
                                       btVector3& aabbMinOut, btVector3& aabbMaxOut)
{
	const btVector3 halfExtentsWithMargin = halfExtents + btVector3(margin, margin, margin);
	const btMatrix3x3 absBasis = t.getBasis().absolute();
	const btVector3 extent = absBasis * halfExtentsWithMargin;
	aabbMinOut = t.getOrigin() - extent;
	aabbMaxOut = t.getOrigin() + extent;
}

/// World box of the local box [localAabbMin, localAabbMax] grown by margin under transform trans.
SIMD_FORCE_INLINE void btTransformAabb(const btVector3& localAabbMin, const btVector3& localAabbMax, btScalar margin,
                                       const btTransform& trans, btVector3& aabbMinOut, btVector3& aabbMaxOut)
{
	btAssert(localAabbMin.getX() <= localAabbMax.getX());
	btAssert(localAabbMin.getY() <= localAabbMax.getY());
	btAssert(localAabbMin.getZ() <= localAabbMax.getZ());
	const btVector3 localHalfExtents =
	    btScalar(0.5) * (localAabbMax - localAabbMin) + btVector3(margin, margin, margin);
	const btVector3 localCenter = btScalar(0.5) * (localAabbMax + localAabbMin);
	const btVector3 center = trans(localCenter);
	const btVector3 extent = trans.getBasis().absolute() * localHalfExtents;
	aabbMinOut = center - extent;
	aabbMaxOut = center + extent;
}

/// Overlap test of two boxes in quantised (16-bit per axis) coordinates; 1 when they overlap or touch.
SIMD_FORCE_INLINE unsigned testQuantizedAabbAgainstQuantizedAabb(const unsigned short int* aabbMin1,
                                                                 const unsigned short int* aabbMax1,
                                                                 const unsigned short int* aabbMin2,
                                                                 const unsigned short int* aabbMax2)
{
	const bool overlap = aabbMin1[0] <= aabbMax2[0] && aabbMax1[0] >= aabbMin2[0] && aabbMin1[2] <= aabbMax2[2] &&
	                     aabbMax1[2] >= aabbMin2[2] && aabbMin1[1] <= aabbMax2[1] && aabbMax1[1] >= aabbMin2[1];
	return overlap ? 1u : 0u;
}

#endif  // BT_AABB_UTIL2
