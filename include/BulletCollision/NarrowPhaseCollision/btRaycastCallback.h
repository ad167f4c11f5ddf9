// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_RAYCAST_TRI_CALLBACK_H
#define BT_RAYCAST_TRI_CALLBACK_H

/// btTriangleRaycastCallback and btTriangleConvexcastCallback: ray and convex-sweep tests against the
/// triangles a concave shape reports. Both classes live in this header, at Bullet's path.

#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "LinearMath/btTransform.h"

class btConvexShape;

/// Intersects the segment m_from -> m_to with each triangle it is given (all in the triangles' frame)
/// and reports hits closer than m_hitFraction; the value reportHit returns becomes the new
/// m_hitFraction, so returning the hit fraction keeps only closer hits. Degenerate (zero-area)
/// triangles, rays parallel to a triangle's plane and non-finite input never hit.
class btTriangleRaycastCallback : public btTriangleCallback
{
public:
	/// Start of the ray (triangle frame).
	btVector3 m_from;
	/// End of the ray (triangle frame).
	btVector3 m_to;

	/// Options of the ray test (bits of m_flags).
	enum EFlags
	{
		/// Defaults: both faces hit, normal faces the ray origin.
		kF_None = 0,
		/// Triangles whose front (counter-clockwise) face points away from m_from are not hit.
		kF_FilterBackfaces = 1 << 0,
		/// Report the triangle's own normal even when the ray hits its back face.
		kF_KeepUnflippedNormal = 1 << 1,
		/// For convex shapes in the world's ray test: use btSubsimplexConvexCast (the default).
		kF_UseSubSimplexConvexCastRaytest = 1 << 2,
		/// For convex shapes in the world's ray test: use btGjkConvexCast.
		kF_UseGjkConvexCastRaytest = 1 << 3,
		/// For height fields: test every triangle instead of walking the grid.
		kF_DisableHeightfieldAccelerator = 1 << 4,
		/// Keeps the enum 32 bits wide.
		kF_Terminator = 0xFFFFFFFF
	};
	/// Bits of EFlags.
	unsigned int m_flags;

	/// Hits at or beyond this fraction are ignored; starts at 1 and follows reportHit's return value.
	btScalar m_hitFraction;

	/// A ray from from to to (triangle frame) with EFlags bits.
	btTriangleRaycastCallback(const btVector3& from, const btVector3& to, unsigned int flags = 0);

	/// Intersects the ray with one triangle and calls reportHit on a hit closer than m_hitFraction.
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override;

	/// One hit: unit normal (triangle frame; faces m_from unless kF_KeepUnflippedNormal), fraction along
	/// the ray, and the triangle's ids. Returns the new m_hitFraction.
	virtual btScalar reportHit(const btVector3& hitNormalLocal, btScalar hitFraction, int partId,
	                           int triangleIndex) = 0;
};

/// Sweeps a convex shape from m_convexShapeFrom to m_convexShapeTo against each triangle it is given
/// (the triangles placed by m_triangleToWorld, with margin m_triangleCollisionMargin) using
/// btContinuousConvexCollision, and reports hits closer than m_hitFraction; the value reportHit
/// returns becomes the new m_hitFraction.
class btTriangleConvexcastCallback : public btTriangleCallback
{
public:
	/// The swept shape (not owned).
	const btConvexShape* m_convexShape;
	/// Start transform of the swept shape (world).
	btTransform m_convexShapeFrom;
	/// End transform of the swept shape (world).
	btTransform m_convexShapeTo;
	/// Places the triangles in the world.
	btTransform m_triangleToWorld;
	/// Hits at or beyond this fraction are ignored; starts at 1 and follows reportHit's return value.
	btScalar m_hitFraction;
	/// Margin given to each triangle.
	btScalar m_triangleCollisionMargin;
	/// Passed to the cast as CastResult::m_allowedPenetration (0 by default).
	btScalar m_allowedPenetration;

	/// A sweep of convexShape from convexShapeFrom to convexShapeTo against triangles placed by triangleToWorld.
	btTriangleConvexcastCallback(const btConvexShape* convexShape, const btTransform& convexShapeFrom,
	                             const btTransform& convexShapeTo, const btTransform& triangleToWorld,
	                             const btScalar triangleCollisionMargin);

	/// Sweeps against one triangle and calls reportHit on a hit closer than m_hitFraction.
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override;

	/// One hit: unit normal (from the triangle towards the shape) and contact point on the triangle, both
	/// in world space despite their names (as in Bullet), the fraction and the triangle's ids. Returns
	/// the new m_hitFraction.
	virtual btScalar reportHit(const btVector3& hitNormalLocal, const btVector3& hitPointLocal, btScalar hitFraction,
	                           int partId, int triangleIndex) = 0;
};

#endif  // BT_RAYCAST_TRI_CALLBACK_H
