// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MULTI_SPHERE_SHAPE_H
#define BT_MULTI_SPHERE_SHAPE_H

#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"
#include "LinearMath/btAlignedObjectArray.h"

/// The convex hull of a set of spheres. The margin is part of the spheres (the surface with margin is
/// exactly the hull of the spheres). Under local scaling S each sphere becomes the ellipsoid S * ball.
ATTRIBUTE_ALIGNED16(class)
btMultiSphereShape : public btConvexInternalAabbCachingShape
{
	btAlignedObjectArray<btVector3> m_localPositionArray;
	btAlignedObjectArray<btScalar> m_radiArray;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Copies numSpheres centres and radii. Null arrays with numSpheres > 0 assert and give no sphere;
	/// a negative or non-finite radius asserts and becomes |radius| (0 if not finite); a sphere with a
	/// non-finite centre asserts and is dropped. With no sphere the core is the origin (the margin ball).
	btMultiSphereShape(const btVector3* positions, const btScalar* radi, int numSpheres);

	/// Approximate solid inertia: the exact inertia of the polytope spanned by the shape's support points
	/// along 400 evenly spread directions (within about 1% of the true hull of spheres; Bullet uses the
	/// box of the AABB instead). Falls back to that box when the shape has no volume. A negative or
	/// non-finite mass asserts and gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// The surface point farthest along vec minus the margin along the unit vec.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each of numVectors directions.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// Number of spheres.
	int getSphereCount() const { return m_localPositionArray.size(); }
	/// Centre of sphere index (unscaled); out of range asserts and gives the origin.
	const btVector3& getSpherePosition(int index) const;
	/// Radius of sphere index (unscaled); out of range asserts and gives 0.
	btScalar getSphereRadius(int index) const;

	/// "MultiSphere".
	const char* getName() const override { return "MultiSphere"; }

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btPositionAndRadius in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btPositionAndRadius
{
	btVector3FloatData m_pos;
	float m_radius;
};

/// File layout of btMultiSphereShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btMultiSphereShapeData
{
	btConvexInternalShapeData m_convexInternalShapeData;
	btPositionAndRadius* m_localPositionArrayPtr;
	int m_localPositionArraySize;
	char m_padding[4];
};

// clang-format on

#endif  // BT_MULTI_SPHERE_SHAPE_H
