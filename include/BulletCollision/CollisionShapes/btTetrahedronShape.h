// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMPLEX_1TO4_SHAPE_H
#define BT_SIMPLEX_1TO4_SHAPE_H

#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"

/// A simplex of 0 to 4 vertices: a point, a segment, a triangle or a tetrahedron. Local scaling applies
/// to the vertices. With no vertex it behaves as a point at the origin.
ATTRIBUTE_ALIGNED16(class)
btBU_Simplex1to4 : public btPolyhedralConvexAabbCachingShape
{
protected:
	/// Number of vertices in use (0..4).
	int m_numVertices;
	/// The vertices, unscaled.
	btVector3 m_vertices[4];

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// No vertices.
	btBU_Simplex1to4();
	/// A point.
	btBU_Simplex1to4(const btVector3& pt0);
	/// A segment.
	btBU_Simplex1to4(const btVector3& pt0, const btVector3& pt1);
	/// A triangle.
	btBU_Simplex1to4(const btVector3& pt0, const btVector3& pt1, const btVector3& pt2);
	/// A tetrahedron.
	btBU_Simplex1to4(const btVector3& pt0, const btVector3& pt1, const btVector3& pt2, const btVector3& pt3);

	/// Removes all vertices.
	void reset() { m_numVertices = 0; }

	/// The world AABB (margin included) from the cached local box.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// Appends a vertex and refreshes the cached AABB. A fifth vertex or a non-finite one asserts and
	/// is ignored in release builds.
	void addVertex(const btVector3& pt);

	/// Number of vertices (0..4).
	int getNumVertices() const override { return m_numVertices; }
	/// 0, 1, 3 or 6 edges for 0-1, 2, 3 and 4 vertices.
	int getNumEdges() const override;
	/// Edge i (pairs (0,1), (1,2), (2,0), (0,3), (1,3), (2,3)); out of range asserts and gives the origin twice.
	void getEdge(int i, btVector3& pa, btVector3& pb) const override;
	/// Scaled vertex i; out of range asserts and gives the origin.
	void getVertex(int i, btVector3& vtx) const override;
	/// 2 for a triangle (its two sides), 4 for a tetrahedron, else 0.
	int getNumPlanes() const override;
	/// Plane i: outward unit normal and a point on it (tetrahedron face i is the one opposite vertex i).
	/// A degenerate face or an index out of range gives a zero normal (out of range asserts).
	void getPlane(btVector3 & planeNormal, btVector3 & planeSupport, int i) const override;
	/// Always 0, as in Bullet.
	virtual int getIndex(int i) const;
	/// For a tetrahedron: pt is behind every face plane grown by tolerance; false for fewer vertices.
	bool isInside(const btVector3& pt, btScalar tolerance) const override;

	/// "btBU_Simplex1to4".
	const char* getName() const override { return "btBU_Simplex1to4"; }
};

#endif  // BT_SIMPLEX_1TO4_SHAPE_H
