// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SPHERE_MINKOWSKI_H
#define BT_SPHERE_MINKOWSKI_H

#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"

/// A sphere centred on the local origin. Its core is the origin point and its margin is the radius, so the
/// margin always equals getRadius() and setMargin has no visible effect. Local scaling uses only x.
/// A negative radius asserts and is made positive; a non-finite radius asserts and becomes 0.
ATTRIBUTE_ALIGNED16(class)
btSphereShape : public btConvexInternalShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A sphere of the given radius.
	btSphereShape(btScalar radius);

	/// The point of the sphere surface farthest along vec ((-1, -1, -1) is used for a zero vec).
	btVector3 localGetSupportingVertex(const btVector3& vec) const override;
	/// The centre (the core of a sphere is a point).
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// The centre for every direction.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// Solid sphere: 2/5 m r^2 on every axis. A negative or non-finite mass asserts and gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// The exact world AABB: origin +- radius.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// The radius with local scaling (x) applied.
	btScalar getRadius() const { return m_implicitShapeDimensions.getX() * m_localScaling.getX(); }
	/// Sets the radius before scaling (same rules as the constructor).
	void setUnscaledRadius(btScalar radius);

	/// "SPHERE".
	const char* getName() const override { return "SPHERE"; }

	/// Stored for Bullet compatibility; the margin of a sphere is always its radius.
	void setMargin(btScalar margin) override { btConvexInternalShape::setMargin(margin); }
	/// The radius.
	btScalar getMargin() const override { return getRadius(); }
};

#endif  // BT_SPHERE_MINKOWSKI_H
