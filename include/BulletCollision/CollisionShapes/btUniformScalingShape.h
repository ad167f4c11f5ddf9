// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_UNIFORM_SCALING_SHAPE_H
#define BT_UNIFORM_SCALING_SHAPE_H

#include "BulletCollision/CollisionShapes/btConvexShape.h"

/// A convex shape scaled uniformly about its origin (margin included), sharing the child (not owned).
/// A null child asserts and the shape is then a point at the origin in release builds; a negative or
/// non-finite factor asserts and becomes |factor| (0 if not finite).
ATTRIBUTE_ALIGNED16(class)
btUniformScalingShape : public btConvexShape
{
	btConvexShape* m_childConvexShape;
	btScalar m_uniformScalingFactor;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// convexChildShape scaled by uniformScalingFactor.
	btUniformScalingShape(btConvexShape * convexChildShape, btScalar uniformScalingFactor);
	/// Does not delete the child.
	virtual ~btUniformScalingShape();

	/// The child's margin-free support times the factor.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// The child's support (margin included) times the factor.
	btVector3 localGetSupportingVertex(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each of numVectors directions.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// The child's inertia times factor^2 (mass fixed, every length scaled by the factor).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// The scaling factor.
	btScalar getUniformScalingFactor() const { return m_uniformScalingFactor; }
	/// The child shape.
	btConvexShape* getChildShape() { return m_childConvexShape; }
	/// The child shape.
	const btConvexShape* getChildShape() const { return m_childConvexShape; }

	/// "UniformScalingShape".
	const char* getName() const override { return "UniformScalingShape"; }

	/// The child's AABB under the rotation of t, scaled by the factor, then moved to t's origin.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
	/// Same as getAabb, from the child's getAabbSlow.
	void getAabbSlow(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Forwards to the child.
	void setLocalScaling(const btVector3& scaling) override;
	/// The child's local scaling ((1, 1, 1) without a child).
	const btVector3& getLocalScaling() const override;
	/// Forwards to the child (the effective margin is the child's times the factor).
	void setMargin(btScalar margin) override;
	/// The child's margin times the factor.
	btScalar getMargin() const override;

	/// The child's preferred penetration directions.
	int getNumPreferredPenetrationDirections() const override;
	/// The child's preferred penetration direction index ((0, 0, 0) without a child).
	void getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const override;
};

#endif  // BT_UNIFORM_SCALING_SHAPE_H
