// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONE_MINKOWSKI_H
#define BT_CONE_MINKOWSKI_H

#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"

/// A circular cone along its up axis (Y here, X and Z in the variants). As in Bullet the local origin is
/// at HALF HEIGHT: the apex is at +height/2 and the base disc at -height/2 on the up axis (so the centre
/// of mass is height/4 below the origin). The margin lies outside the given dimensions (default
/// CONVEX_DISTANCE_MARGIN). Local scaling scales the height by the up axis component and the radius by
/// the mean of the other two. Negative sizes assert and are made positive; non-finite ones become 0.
ATTRIBUTE_ALIGNED16(class)
btConeShape : public btConvexInternalShape
{
	btScalar m_sinAngle;
	btScalar m_radius;
	btScalar m_height;
	int m_coneIndices[3];

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A Y-axis cone of base radius radius and height height (apex to base).
	btConeShape(btScalar radius, btScalar height);

	/// The apex or the point of the base rim farthest along vec.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each direction.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// The base radius (scaled).
	btScalar getRadius() const { return m_radius; }
	/// The height, apex to base (scaled).
	btScalar getHeight() const { return m_height; }
	/// Sets the (scaled) base radius.
	void setRadius(btScalar radius);
	/// Sets the (scaled) height.
	void setHeight(btScalar height);

	/// Principal inertia of the solid cone about its CENTRE OF MASS (height/4 above the base, i.e. height/4
	/// below the shape origin), axes parallel to the local axes: 3/10 m r^2 about the up axis, 3/20 m r^2 +
	/// 3/80 m h^2 across it. Bullet approximates it by a box. A negative or non-finite mass asserts and
	/// gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// "Cone".
	const char* getName() const override { return "Cone"; }

	/// Makes axis upIndex (0, 1 or 2) the cone's axis; other values assert and are ignored.
	void setConeUpIndex(int upIndex);
	/// The cone's axis (0 = X, 1 = Y, 2 = Z).
	int getConeUpIndex() const { return m_coneIndices[1]; }

	/// Rolling friction acts about the up axis only.
	btVector3 getAnisotropicRollingFrictionDirection() const override
	{
		btVector3 direction(0, 0, 0);
		direction[getConeUpIndex()] = btScalar(1);
		return direction;
	}

	/// Sets the scaling and rescales the radius and the height.
	void setLocalScaling(const btVector3& scaling) override;

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

/// A cone along the X axis.
class btConeShapeX : public btConeShape
{
public:
	/// An X-axis cone.
	btConeShapeX(btScalar radius, btScalar height);
	/// "ConeX".
	const char* getName() const override { return "ConeX"; }
	/// Rolling friction about X.
	btVector3 getAnisotropicRollingFrictionDirection() const override { return btVector3(1, 0, 0); }
};

/// A cone along the Z axis.
class btConeShapeZ : public btConeShape
{
public:
	/// A Z-axis cone.
	btConeShapeZ(btScalar radius, btScalar height);
	/// "ConeZ".
	const char* getName() const override { return "ConeZ"; }
	/// Rolling friction about Z.
	btVector3 getAnisotropicRollingFrictionDirection() const override { return btVector3(0, 0, 1); }
};

// clang-format off
/// File layout of btConeShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btConeShapeData
{
	btConvexInternalShapeData m_convexInternalShapeData;
	int m_upIndex;
	char m_padding[4];
};

// clang-format on

#endif  // BT_CONE_MINKOWSKI_H
