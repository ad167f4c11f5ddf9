// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_POLYHEDRAL_CONVEX_SHAPE_H
#define BT_POLYHEDRAL_CONVEX_SHAPE_H

#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"
#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"
#include "LinearMath/btMatrix3x3.h"

/// A convex shape given by a finite set of vertices (box, triangle, tetrahedron, hulls). Optionally
/// carries a btConvexPolyhedron (faces, planes, edges) for polyhedral contact clipping.
ATTRIBUTE_ALIGNED16(class)
btPolyhedralConvexShape : public btConvexInternalShape
{
protected:
	/// Face/edge description built by initializePolyhedralFeatures (owned; 0 until then).
	btConvexPolyhedron* m_polyhedron;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A shape with no polyhedral features yet.
	btPolyhedralConvexShape();
	/// Copies the shape, including a deep copy of its polyhedron.
	btPolyhedralConvexShape(const btPolyhedralConvexShape& other);
	/// Assigns the shape, including a deep copy of its polyhedron.
	btPolyhedralConvexShape& operator=(const btPolyhedralConvexShape& other);
	/// Frees the polyhedron.
	virtual ~btPolyhedralConvexShape();

	/// Builds the polyhedron from the convex hull of the (scaled) vertices: merged polygon faces with
	/// outward planes, unique edge directions and bounds. With shiftVerticesByMargin != 0 every face
	/// plane is first pushed outwards by the margin. Returns true when the hull has a face (a flat
	/// vertex set gives its polygon seen from both sides). With fewer than 3 non-collinear finite
	/// vertices it asserts; in release builds it returns false and getConvexPolyhedron() is 0.
	virtual bool initializePolyhedralFeatures(int shiftVerticesByMargin = 0);

	/// Replaces the polyhedron by a copy of polyhedron.
	virtual void setPolyhedralFeatures(btConvexPolyhedron & polyhedron);

	/// The polyhedron, or 0 before initializePolyhedralFeatures / setPolyhedralFeatures.
	const btConvexPolyhedron* getConvexPolyhedron() const { return m_polyhedron; }

	/// The vertex (getVertex) farthest along vec; the first one on ties. A zero or non-finite vec is
	/// replaced by (-1, -1, -1); with no finite vertex the result is the origin.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each of numVectors directions.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// The diagonal of the inertia tensor of the SOLID convex hull of the vertices (exact, by tetrahedra;
	/// Bullet uses the box of the AABB), about its centre of volume, margin not counted. When the hull
	/// has no volume (fewer than 4 vertices, or flat) it falls back to the solid box of the vertices'
	/// AABB grown by the margin. A negative or non-finite mass asserts and gives (0, 0, 0).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// Number of vertices.
	virtual int getNumVertices() const = 0;
	/// Number of edges.
	virtual int getNumEdges() const = 0;
	/// The two end points of edge i.
	virtual void getEdge(int i, btVector3& pa, btVector3& pb) const = 0;
	/// Vertex i (local scaling applied).
	virtual void getVertex(int i, btVector3& vtx) const = 0;
	/// Number of face planes.
	virtual int getNumPlanes() const = 0;
	/// Face plane i as an outward normal and a point on it.
	virtual void getPlane(btVector3 & planeNormal, btVector3 & planeSupport, int i) const = 0;
	/// True when pt is inside the shape, allowing tolerance beyond its faces.
	virtual bool isInside(const btVector3& pt, btScalar tolerance) const = 0;
};

/// A btPolyhedralConvexShape that caches its local AABB, for shapes with many vertices.
ATTRIBUTE_ALIGNED16(class)
btPolyhedralConvexAabbCachingShape : public btPolyhedralConvexShape
{
	btVector3 m_localAabbMin;
	btVector3 m_localAabbMax;
	bool m_isLocalAabbValid;

protected:
	/// Stores the local AABB (margin excluded).
	void setCachedLocalAabb(const btVector3& aabbMin, const btVector3& aabbMax)
	{
		m_isLocalAabbValid = true;
		m_localAabbMin = aabbMin;
		m_localAabbMax = aabbMax;
	}
	/// The stored local AABB (margin excluded; asserts when not computed yet).
	void getCachedLocalAabb(btVector3 & aabbMin, btVector3 & aabbMax) const
	{
		btAssert(m_isLocalAabbValid);
		aabbMin = m_localAabbMin;
		aabbMax = m_localAabbMax;
	}

	/// A shape with no cached AABB yet.
	btPolyhedralConvexAabbCachingShape();

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// The world AABB of the cached local box grown by margin under trans. Without a cached box (asserts)
	/// it falls back to getAabbSlow; a non-finite trans asserts and gives [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3.
	void getNonvirtualAabb(const btTransform& trans, btVector3& aabbMin, btVector3& aabbMax, btScalar margin) const;

	/// Sets the scaling and recomputes the cached AABB.
	void setLocalScaling(const btVector3& scaling) override;

	/// getNonvirtualAabb with getMargin(): exact for a pure translation, conservative under rotation.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Recomputes the cached local AABB (margin excluded) from the support along the six local axes.
	void recalcLocalAabb();
};

#endif  // BT_POLYHEDRAL_CONVEX_SHAPE_H
