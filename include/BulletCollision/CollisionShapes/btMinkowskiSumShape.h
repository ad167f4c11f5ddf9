// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MINKOWSKI_SUM_SHAPE_H
#define BT_MINKOWSKI_SUM_SHAPE_H

#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"

/// Bullet's "Minkowski sum" of two convex shapes, each placed by its own transform in this shape's
/// frame. As in Bullet it is A + (-B), i.e. support(d) = transA(supportA(d)) - transB(supportB(-d))
/// (the same as a true sum when B is symmetric about its origin). The children are not owned. A null child
/// asserts and counts as a point at the origin with no margin in release builds.
ATTRIBUTE_ALIGNED16(class)
btMinkowskiSumShape : public btConvexInternalShape
{
	btTransform m_transA;
	btTransform m_transB;
	const btConvexShape* m_shapeA;
	const btConvexShape* m_shapeB;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// The sum of shapeA and shapeB, both with identity transforms.
	btMinkowskiSumShape(const btConvexShape* shapeA, const btConvexShape* shapeB);

	/// The sum of the margin-free supports of the two placed children along vec.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each of numVectors directions.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// Approximate solid inertia from the support points along 400 directions (see btMultiSphereShape;
	/// Bullet asserts here). Falls back to the box of the AABB without volume; a bad mass asserts and
	/// gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// Places shape A.
	void setTransformA(const btTransform& transA) { m_transA = transA; }
	/// Places shape B.
	void setTransformB(const btTransform& transB) { m_transB = transB; }
	/// The placement of shape A.
	const btTransform& getTransformA() const { return m_transA; }
	/// The placement of shape B.
	const btTransform& getTransformB() const { return m_transB; }
	/// The placement of shape B (Bullet's spelling).
	const btTransform& GetTransformB() const { return m_transB; }

	/// The sum of the children's margins.
	btScalar getMargin() const override;

	/// Shape A.
	const btConvexShape* getShapeA() const { return m_shapeA; }
	/// Shape B.
	const btConvexShape* getShapeB() const { return m_shapeB; }

	/// "MinkowskiSum".
	const char* getName() const override { return "MinkowskiSum"; }
};

#endif  // BT_MINKOWSKI_SUM_SHAPE_H
