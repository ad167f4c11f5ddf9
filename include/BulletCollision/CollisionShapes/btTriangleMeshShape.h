// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRIANGLE_MESH_SHAPE_H
#define BT_TRIANGLE_MESH_SHAPE_H

#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"

/// The base of static triangle mesh shapes over a btStridingMeshInterface (not owned). Without an
/// acceleration structure every query scans all triangles; use btBvhTriangleMeshShape. The local
/// scaling lives in the mesh interface. A null mesh interface asserts and gives an empty shape.
ATTRIBUTE_ALIGNED16(class)
btTriangleMeshShape : public btConcaveShape
{
protected:
	/// The local AABB of the (scaled) triangles; (0, 0, 0) twice for an empty mesh.
	btVector3 m_localAabbMin;
	/// The local AABB of the (scaled) triangles.
	btVector3 m_localAabbMax;
	/// The mesh (not owned).
	btStridingMeshInterface* m_meshInterface;
	/// Scaling reported when there is no mesh interface.
	btVector3 m_fallbackScaling;

	/// A shape over meshInterface; its AABB is the mesh's premade one or is computed from the triangles.
	btTriangleMeshShape(btStridingMeshInterface * meshInterface);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Shapes are deleted through base pointers (the mesh interface is not deleted).
	virtual ~btTriangleMeshShape();

	/// The vertex farthest along vec (brute force over all triangles); the origin for an empty mesh.
	virtual btVector3 localGetSupportingVertex(const btVector3& vec) const;
	/// Same as localGetSupportingVertex (the mesh has no margin in its vertices).
	virtual btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const
	{
		return localGetSupportingVertex(vec);
	}

	/// Recomputes the local AABB from the triangles (one pass over the mesh).
	void recalcLocalAabb();

	/// The world AABB of the local box grown by the margin under t; a non-finite t asserts and gives
	/// [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Reports every triangle whose AABB overlaps [aabbMin, aabbMax] (brute force over all triangles).
	void processAllTriangles(btTriangleCallback * callback, const btVector3& aabbMin, const btVector3& aabbMax)
	    const override;

	/// Mesh shapes are static: the inertia is (0, 0, 0); a non-zero mass asserts.
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// Sets the scaling of the mesh interface and recomputes the AABB.
	void setLocalScaling(const btVector3& scaling) override;
	/// The scaling of the mesh interface.
	const btVector3& getLocalScaling() const override;

	/// The mesh.
	btStridingMeshInterface* getMeshInterface() { return m_meshInterface; }
	/// The mesh.
	const btStridingMeshInterface* getMeshInterface() const { return m_meshInterface; }

	/// Minimum corner of the local AABB.
	const btVector3& getLocalAabbMin() const { return m_localAabbMin; }
	/// Maximum corner of the local AABB.
	const btVector3& getLocalAabbMax() const { return m_localAabbMax; }

	/// "TRIANGLEMESH", as in Bullet.
	const char* getName() const override { return "TRIANGLEMESH"; }
};

#endif  // BT_TRIANGLE_MESH_SHAPE_H
