// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CYLINDER_MINKOWSKI_H
#define BT_CYLINDER_MINKOWSKI_H

#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"

/// A circular cylinder centred on the origin along its up axis (Y here, X and Z in the variants). It is
/// given by half extents: the up axis component is the half height and the radius is the component of
/// getRadius() (x for Y and Z cylinders, y for X cylinders); the third one is stored but unused. As in
/// Bullet the margin lies inside these dimensions: the core is the cylinder shrunk by the margin, and the
/// shape is that core grown by a sphere of the margin (its rims are rounded by the margin). The default
/// margin is min(CONVEX_DISTANCE_MARGIN, 0.1 * min(radius, half height)), and setMargin clamps the margin to the
/// smallest of the radius and half height so that the core never turns inside out. Negative half extents
/// assert and are made positive; non-finite ones assert and become 0.
ATTRIBUTE_ALIGNED16(class)
btCylinderShape : public btConvexInternalShape
{
protected:
	/// 0, 1 or 2: the axis of the cylinder.
	int m_upAxis;

	/// The axis whose half extent is the radius.
	int radiusAxis() const { return m_upAxis == 0 ? 1 : 0; }
	/// Sets the half extents (margin included, before scaling) for the given up axis.
	void setDimensions(int upAxis, const btVector3& halfExtents);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A Y-axis cylinder of the given half extents (margin included).
	btCylinderShape(const btVector3& halfExtents);

	/// The scaled half extents, margin included.
	btVector3 getHalfExtentsWithMargin() const
	{
		const btScalar m = getMargin();
		return getHalfExtentsWithoutMargin() + btVector3(m, m, m);
	}
	/// The scaled half extents of the core (margin excluded).
	const btVector3& getHalfExtentsWithoutMargin() const { return m_implicitShapeDimensions; }

	/// The exact world AABB of the shape with its rounded rims.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Solid cylinder of the outer dimensions: m r^2 / 2 about the axis, m (3 r^2 + H^2) / 12 across it
	/// (H the full height). A negative or non-finite mass asserts and gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// The point of the core farthest along vec.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each direction.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// Sets the margin and keeps the outer dimensions (clamped as described above).
	void setMargin(btScalar collisionMargin) override;
	/// Sets the scaling and rescales the outer dimensions.
	void setLocalScaling(const btVector3& scaling) override;

	/// Rolling friction acts about the up axis only.
	btVector3 getAnisotropicRollingFrictionDirection() const override
	{
		btVector3 direction(0, 0, 0);
		direction[m_upAxis] = btScalar(1);
		return direction;
	}

	/// The axis of the cylinder (0 = X, 1 = Y, 2 = Z).
	int getUpAxis() const { return m_upAxis; }
	/// The radius (scaled, margin included).
	virtual btScalar getRadius() const { return getHalfExtentsWithMargin()[radiusAxis()]; }

	/// "CylinderY".
	const char* getName() const override { return "CylinderY"; }

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

/// A cylinder along the X axis (radius from the y half extent).
class btCylinderShapeX : public btCylinderShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();
	/// An X-axis cylinder.
	btCylinderShapeX(const btVector3& halfExtents);
	/// "CylinderX".
	const char* getName() const override { return "CylinderX"; }
};

/// A cylinder along the Z axis (radius from the x half extent).
class btCylinderShapeZ : public btCylinderShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();
	/// A Z-axis cylinder.
	btCylinderShapeZ(const btVector3& halfExtents);
	/// "CylinderZ".
	const char* getName() const override { return "CylinderZ"; }
};

// clang-format off
/// File layout of btCylinderShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCylinderShapeData
{
	btConvexInternalShapeData m_convexInternalShapeData;
	int m_upAxis;
	char m_padding[4];
};

// clang-format on

#endif  // BT_CYLINDER_MINKOWSKI_H
