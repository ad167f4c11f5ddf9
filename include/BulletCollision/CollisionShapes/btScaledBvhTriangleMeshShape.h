// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SCALED_BVH_TRIANGLE_MESH_SHAPE_H
#define BT_SCALED_BVH_TRIANGLE_MESH_SHAPE_H

#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"

/// A btBvhTriangleMeshShape (not owned) seen through an extra local scaling, so that one mesh and tree
/// serve bodies of several sizes. Queries map the box into the child's space and scale the triangles
/// back. Negative components mirror; a zero component flattens the mesh onto that plane. A null child
/// asserts and gives an empty shape.
ATTRIBUTE_ALIGNED16(class)
btScaledBvhTriangleMeshShape : public btConcaveShape
{
	btVector3 m_localScaling;
	btBvhTriangleMeshShape* m_bvhTriMeshShape;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// The child shape scaled by localScaling (a non-finite scaling asserts and becomes (1, 1, 1)).
	btScaledBvhTriangleMeshShape(btBvhTriangleMeshShape * childShape, const btVector3& localScaling);
	/// Does not delete the child.
	virtual ~btScaledBvhTriangleMeshShape();

	/// The world AABB of the child's local AABB scaled, grown by the child's margin, under t.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
	/// Sets the extra scaling; a non-finite one asserts and is ignored.
	void setLocalScaling(const btVector3& scaling) override;
	/// The extra scaling.
	const btVector3& getLocalScaling() const override { return m_localScaling; }
	/// Static only: (0, 0, 0); a non-zero mass asserts.
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// Reports the child's triangles (scaled) whose scaled tree box overlaps [aabbMin, aabbMax].
	void processAllTriangles(btTriangleCallback * callback, const btVector3& aabbMin, const btVector3& aabbMax)
	    const override;

	/// The shared child.
	btBvhTriangleMeshShape* getChildShape() { return m_bvhTriMeshShape; }
	/// The shared child.
	const btBvhTriangleMeshShape* getChildShape() const { return m_bvhTriMeshShape; }

	/// "SCALEDBVHTRIANGLEMESH", as in Bullet.
	const char* getName() const override { return "SCALEDBVHTRIANGLEMESH"; }

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btScaledTriangleMeshShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btScaledTriangleMeshShapeData
{
	btTriangleMeshShapeData m_trimeshShapeData;
	btVector3FloatData m_localScaling;
};

// clang-format on

#endif  // BT_SCALED_BVH_TRIANGLE_MESH_SHAPE_H
