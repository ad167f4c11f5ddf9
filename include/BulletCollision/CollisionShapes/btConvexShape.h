// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_SHAPE_H
#define BT_CONVEX_SHAPE_H

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "LinearMath/btVector3.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btMatrix3x3.h"

/// The most preferred penetration directions a convex shape may report.
#define MAX_PREFERRED_PENETRATION_DIRECTIONS 10

/// The base of convex shapes: a shape described by its support function, which GJK, EPA and the convex
/// casts query. The shape with margin is the margin-free core grown by a sphere of radius getMargin().
ATTRIBUTE_ALIGNED16(class)
btConvexShape : public btCollisionShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A convex shape (type set by the derived class).
	btConvexShape();
	/// Shapes are deleted through base pointers.
	virtual ~btConvexShape();

	/// The point of the shape, margin included, farthest along vec (local coordinates).
	virtual btVector3 localGetSupportingVertex(const btVector3& vec) const = 0;
	/// The point of the margin-free core farthest along vec (local coordinates).
	virtual btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const = 0;

	/// localGetSupportingVertexWithoutMargin without a virtual call for the common primitives.
	btVector3 localGetSupportVertexWithoutMarginNonVirtual(const btVector3& vec) const;
	/// localGetSupportingVertex without a virtual call for the common primitives: the margin-free
	/// support plus getMarginNonVirtual() along the normalised vec ((-1, -1, -1) for a zero vec).
	btVector3 localGetSupportVertexNonVirtual(const btVector3& vec) const;
	/// getMargin without a virtual call for the common primitives.
	btScalar getMarginNonVirtual() const;
	/// getAabb without a virtual call for the common primitives.
	void getAabbNonVirtual(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const;

	/// The interval [minProj, maxProj] of the shape (margin included) projected on the world direction dir
	/// under trans, with the world points where the extremes are reached.
	virtual void project(const btTransform& trans, const btVector3& dir, btScalar& minProj, btScalar& maxProj,
	                     btVector3& witnesPtMin, btVector3& witnesPtMax) const;

	/// Margin-free support points for numVectors unit directions at once.
	virtual void batchedUnitVectorGetSupportingVertexWithoutMargin(
	    const btVector3* vectors, btVector3* supportVerticesOut, int numVectors) const = 0;

	/// The world AABB (margin included) under t.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override = 0;
	/// The world AABB computed from support points along the six world axis directions.
	virtual void getAabbSlow(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const = 0;

	void setLocalScaling(const btVector3& scaling) override = 0;
	const btVector3& getLocalScaling() const override = 0;
	void setMargin(btScalar margin) override = 0;
	btScalar getMargin() const override = 0;

	/// How many directions the shape suggests trying first when resolving penetration.
	virtual int getNumPreferredPenetrationDirections() const = 0;
	/// The index-th preferred penetration direction (index < getNumPreferredPenetrationDirections()).
	virtual void getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const = 0;
};

#endif  // BT_CONVEX_SHAPE_H
