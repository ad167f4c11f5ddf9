// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONCAVE_SHAPE_H
#define BT_CONCAVE_SHAPE_H

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"

/// The scalar types mesh and height field data may be stored in.
typedef enum PHY_ScalarType
{
	PHY_FLOAT,
	PHY_DOUBLE,
	PHY_INTEGER,
	PHY_SHORT,
	PHY_FIXEDPOINT88,
	PHY_UCHAR
} PHY_ScalarType;

/// The base of concave shapes (meshes, height fields, the static plane): shapes queried triangle by
/// triangle through processAllTriangles. Their margin defaults to 0.
ATTRIBUTE_ALIGNED16(class)
btConcaveShape : public btCollisionShape
{
protected:
	/// The collision margin (0 by default).
	btScalar m_collisionMargin;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A concave shape with margin 0 (type set by the derived class).
	btConcaveShape();
	/// Shapes are deleted through base pointers.
	virtual ~btConcaveShape();

	/// Calls callback->processTriangle for every triangle that may overlap the local box [aabbMin, aabbMax].
	virtual void processAllTriangles(btTriangleCallback * callback, const btVector3& aabbMin, const btVector3& aabbMax)
	    const = 0;

	/// The margin.
	btScalar getMargin() const override { return m_collisionMargin; }
	/// Sets the margin; a negative or non-finite margin asserts and becomes 0.
	void setMargin(btScalar collisionMargin) override;
};

#endif  // BT_CONCAVE_SHAPE_H
