// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CAPSULE_SHAPE_H
#define BT_CAPSULE_SHAPE_H

#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"

/// A capsule: a segment of length 2 * halfHeight along the up axis (Y here, X and Z in the variants),
/// centred on the origin, grown by a sphere of the radius. The core is the segment and the margin is
/// the radius (setMargin is ignored). Local scaling scales the segment by the up axis component and the
/// radius by the component of the axis after it ((upAxis + 2) % 3). Negative sizes assert and are made
/// positive; non-finite sizes assert and become 0.
ATTRIBUTE_ALIGNED16(class)
btCapsuleShape : public btConvexInternalShape
{
protected:
	/// 0, 1 or 2: the axis of the segment.
	int m_upAxis;
	/// (radius, halfHeight, radius) before scaling, permuted by the up axis.
	btVector3 m_unscaledDimensions;

	/// For the X and Z variants, which set their dimensions themselves.
	btCapsuleShape();
	/// Sets radius and half height along upAxis, before scaling.
	void setDimensions(int upAxis, btScalar radius, btScalar height);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A Y-axis capsule: height is the distance between the centres of the two hemispheres.
	btCapsuleShape(btScalar radius, btScalar height);

	/// Analytic inertia of the solid capsule (a cylinder and two hemispheres of one density) about its
	/// centre. Bullet approximates it by a box. A negative or non-finite mass asserts and gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// The end of the segment farthest along vec (the upper end for a vec perpendicular to it).
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each direction.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// Ignored: the margin of a capsule is its radius.
	void setMargin(btScalar collisionMargin) override { (void)collisionMargin; }

	/// The exact world AABB: the segment's end points' box grown by the radius.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// "CapsuleShape".
	const char* getName() const override { return "CapsuleShape"; }

	/// The axis of the segment (0 = X, 1 = Y, 2 = Z).
	int getUpAxis() const { return m_upAxis; }
	/// The radius (scaled).
	btScalar getRadius() const { return m_implicitShapeDimensions[(m_upAxis + 2) % 3]; }
	/// Half the distance between the hemisphere centres (scaled).
	btScalar getHalfHeight() const { return m_implicitShapeDimensions[m_upAxis]; }

	/// Sets the scaling and rescales the radius and the half height.
	void setLocalScaling(const btVector3& scaling) override;

	/// Rolling friction acts about the up axis only.
	btVector3 getAnisotropicRollingFrictionDirection() const override
	{
		btVector3 direction(0, 0, 0);
		direction[m_upAxis] = btScalar(1);
		return direction;
	}

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

/// A capsule along the X axis.
class btCapsuleShapeX : public btCapsuleShape
{
public:
	/// An X-axis capsule.
	btCapsuleShapeX(btScalar radius, btScalar height);
	/// "CapsuleX".
	const char* getName() const override { return "CapsuleX"; }
};

/// A capsule along the Z axis.
class btCapsuleShapeZ : public btCapsuleShape
{
public:
	/// A Z-axis capsule.
	btCapsuleShapeZ(btScalar radius, btScalar height);
	/// "CapsuleZ".
	const char* getName() const override { return "CapsuleZ"; }
};

// clang-format off
/// File layout of btCapsuleShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCapsuleShapeData
{
	btConvexInternalShapeData m_convexInternalShapeData;
	int m_upAxis;
	char m_padding[4];
};

// clang-format on

#endif  // BT_CAPSULE_SHAPE_H
