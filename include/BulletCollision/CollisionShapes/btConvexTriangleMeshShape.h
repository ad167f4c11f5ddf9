// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_TRIANGLEMESH_SHAPE_H
#define BT_CONVEX_TRIANGLEMESH_SHAPE_H

#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"

/// The convex hull of the vertices of the triangles of a mesh (not owned; it must outlive the shape).
/// Support queries scan every readable triangle; the local scaling lives in the mesh interface. A null
/// mesh interface asserts and gives a shape whose core is the origin.
ATTRIBUTE_ALIGNED16(class)
btConvexTriangleMeshShape : public btPolyhedralConvexAabbCachingShape
{
	btStridingMeshInterface* m_stridingMesh;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A shape over meshInterface; calcAabb computes the cached AABB now (else call recalcLocalAabb).
	btConvexTriangleMeshShape(btStridingMeshInterface * meshInterface, bool calcAabb = true);

	/// The mesh.
	btStridingMeshInterface* getMeshInterface() { return m_stridingMesh; }
	/// The mesh.
	const btStridingMeshInterface* getMeshInterface() const { return m_stridingMesh; }

	/// The (scaled) mesh vertex farthest along vec; the first on ties; the origin for an empty mesh.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// The support grown by the margin along vec.
	btVector3 localGetSupportingVertex(const btVector3& vec) const override;
	/// All numVectors supports in a single pass over the mesh.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// "ConvexTrimesh", as in Bullet.
	const char* getName() const override { return "ConvexTrimesh"; }

	/// 0: vertices are not enumerated (as in Bullet); supports scan the mesh.
	int getNumVertices() const override { return 0; }
	/// 0 (as in Bullet).
	int getNumEdges() const override { return 0; }
	/// Not supported: asserts; gives the origin twice in release builds.
	void getEdge(int i, btVector3& pa, btVector3& pb) const override;
	/// Not supported: asserts; gives the origin in release builds.
	void getVertex(int i, btVector3& vtx) const override;
	/// 0 (as in Bullet).
	int getNumPlanes() const override { return 0; }
	/// Not supported: asserts; gives zero vectors in release builds.
	void getPlane(btVector3 & planeNormal, btVector3 & planeSupport, int i) const override;
	/// Not supported: asserts; returns false in release builds.
	bool isInside(const btVector3& pt, btScalar tolerance) const override;

	/// Sets the scaling of the mesh interface and recomputes the cached AABB.
	void setLocalScaling(const btVector3& scaling) override;
	/// The scaling of the mesh interface.
	const btVector3& getLocalScaling() const override;

	/// The inertia of the solid bounded by the mesh (which should be closed and consistently wound; the
	/// sign of the winding does not matter) at unit density: principal gets the centre of mass and the
	/// principal axes, inertia the principal moments per unit mass, volume the enclosed volume. A mesh
	/// enclosing no volume gives volume 0, inertia (0, 0, 0) and principal = translation to the centre of
	/// the AABB.
	void calculatePrincipalAxisTransform(btTransform & principal, btVector3 & inertia, btScalar & volume) const;

	/// The diagonal inertia of the solid convex hull of the vertices (as btPolyhedralConvexShape does for
	/// its vertex list); hulls without volume fall back to the box of the AABB grown by the margin.
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;
};

#endif  // BT_CONVEX_TRIANGLEMESH_SHAPE_H
