// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_EMPTY_SHAPE_H
#define BT_EMPTY_SHAPE_H

#include "BulletCollision/CollisionShapes/btConcaveShape.h"

/// A shape that collides with nothing (for objects that only need a place in the world, and as a
/// placeholder). Its AABB is the point at the transform's origin grown by the margin.
ATTRIBUTE_ALIGNED16(class)
btEmptyShape : public btConcaveShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An empty shape.
	btEmptyShape();
	/// Shapes are deleted through base pointers.
	virtual ~btEmptyShape();

	/// The origin of t grown by the margin; a non-finite t asserts and gives
	/// [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3 in release builds.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Stores the scaling (a non-finite one asserts and is ignored).
	void setLocalScaling(const btVector3& scaling) override;
	/// The stored scaling.
	const btVector3& getLocalScaling() const override { return m_localScaling; }

	/// Zero (Bullet asserts here; an empty shape has no mass distribution).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// "Empty".
	const char* getName() const override { return "Empty"; }

	/// No triangles.
	void processAllTriangles(btTriangleCallback*, const btVector3&, const btVector3&) const override {}

protected:
	/// The stored scaling.
	btVector3 m_localScaling;
};

#endif  // BT_EMPTY_SHAPE_H
