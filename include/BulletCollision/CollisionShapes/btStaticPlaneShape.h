// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_STATIC_PLANE_SHAPE_H
#define BT_STATIC_PLANE_SHAPE_H

#include "BulletCollision/CollisionShapes/btConcaveShape.h"

/// An infinite plane {x : planeNormal . x = planeConstant}; the solid side is below it (against the normal).
/// For static bodies only: its AABB is [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3 and its inertia zero. The normal
/// is normalised; a zero or non-finite normal asserts and becomes (1, 0, 0), a non-finite constant
/// asserts and becomes 0. Local scaling is stored but does not change the plane.
ATTRIBUTE_ALIGNED16(class)
btStaticPlaneShape : public btConcaveShape
{
protected:
	/// Lower corner of the local AABB (-BT_LARGE_FLOAT on every axis).
	btVector3 m_localAabbMin;
	/// Upper corner of the local AABB.
	btVector3 m_localAabbMax;
	/// The unit normal.
	btVector3 m_planeNormal;
	/// The plane's offset along the normal.
	btScalar m_planeConstant;
	/// The stored local scaling.
	btVector3 m_localScaling;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// The plane planeNormal . x = planeConstant.
	btStaticPlaneShape(const btVector3& planeNormal, btScalar planeConstant);
	/// Shapes are deleted through base pointers.
	virtual ~btStaticPlaneShape();

	/// [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3 whatever t is.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Two triangles forming a square in the plane that covers the part of the plane inside [aabbMin,
	/// aabbMax] (the square is centred on the box centre projected onto the plane, with half side the
	/// box's half diagonal), wound counter-clockwise seen from the normal side. A box with a non-finite
	/// corner asserts and gives no triangles.
	void processAllTriangles(btTriangleCallback * callback, const btVector3& aabbMin, const btVector3& aabbMax)
	    const override;

	/// Zero: the plane is for static bodies.
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// Stores the scaling (a non-finite one asserts and is ignored).
	void setLocalScaling(const btVector3& scaling) override;
	/// The stored scaling.
	const btVector3& getLocalScaling() const override { return m_localScaling; }

	/// The unit normal.
	const btVector3& getPlaneNormal() const { return m_planeNormal; }
	/// The plane constant.
	const btScalar& getPlaneConstant() const { return m_planeConstant; }

	/// "STATICPLANE".
	const char* getName() const override { return "STATICPLANE"; }

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btStaticPlaneShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btStaticPlaneShapeData
{
	btCollisionShapeData m_collisionShapeData;
	btVector3FloatData m_localScaling;
	btVector3FloatData m_planeNormal;
	float m_planeConstant;
	char m_pad[4];
};

// clang-format on

#endif  // BT_STATIC_PLANE_SHAPE_H
