// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRIANGLE_SHAPE_H
#define BT_TRIANGLE_SHAPE_H

#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"

namespace caliber
{
/// A triangle's corner index clamped into 0..2 (asserts when it was outside).
inline int triangleCornerIndex(int index)
{
	btAssert(index >= 0 && index < 3);
	return index < 0 ? 0 : (index > 2 ? 2 : index);
}
}  // namespace caliber

/// A single triangle (used by the concave mesh shapes for each triangle they report). Local scaling
/// does not apply: the vertices are used as stored. A degenerate triangle (zero area) is allowed, as
/// meshes often hold them: its normal is (0, 0, 0) and isInside is false; nothing asserts.
ATTRIBUTE_ALIGNED16(class)
btTriangleShape : public btPolyhedralConvexShape
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// The three corners, counter-clockwise seen from the side the normal points to.
	btVector3 m_vertices1[3];

	/// A triangle with all three corners at the origin.
	btTriangleShape();
	/// The triangle p0, p1, p2.
	btTriangleShape(const btVector3& p0, const btVector3& p1, const btVector3& p2);

	/// 3.
	int getNumVertices() const override { return 3; }
	/// Corner index (0..2; others assert and are clamped into range).
	btVector3& getVertexPtr(int index) { return m_vertices1[caliber::triangleCornerIndex(index)]; }
	/// Corner index (0..2; others assert and are clamped into range).
	const btVector3& getVertexPtr(int index) const { return m_vertices1[caliber::triangleCornerIndex(index)]; }
	/// Corner index (0..2; others assert and are clamped into range).
	void getVertex(int index, btVector3& vert) const override
	{
		vert = m_vertices1[caliber::triangleCornerIndex(index)];
	}
	/// 3.
	int getNumEdges() const override { return 3; }
	/// Edge i from corner i to corner (i + 1) mod 3.
	void getEdge(int i, btVector3& pa, btVector3& pb) const override;
	/// The world AABB (margin included) from support points.
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;

	/// The corner farthest along dir (the first on ties; a zero or non-finite dir uses (-1, -1, -1)).
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& dir) const override;
	/// localGetSupportingVertexWithoutMargin for each of numVectors directions.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// The triangle's plane (i is ignored): see getPlaneEquation.
	void getPlane(btVector3 & planeNormal, btVector3 & planeSupport, int i) const override;
	/// 1.
	int getNumPlanes() const override { return 1; }
	/// The unit normal (p1 - p0) x (p2 - p0), normalised; (0, 0, 0) for a degenerate triangle.
	void calcNormal(btVector3 & normal) const;
	/// The plane of the triangle: calcNormal and corner 0 (i is ignored).
	virtual void getPlaneEquation(int i, btVector3& planeNormal, btVector3& planeSupport) const;

	/// (0, 0, 0): a triangle has no volume (Bullet asserts here; Caliber does not, so that static
	/// triangles may be given a mass of 0 through generic code).
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;

	/// True when pt is within tolerance of the triangle's plane and inside its three edges grown by
	/// tolerance; false for a degenerate triangle.
	bool isInside(const btVector3& pt, btScalar tolerance) const override;

	/// "Triangle".
	const char* getName() const override { return "Triangle"; }

	/// 2: the normal and its opposite.
	int getNumPreferredPenetrationDirections() const override { return 2; }
	/// Index 0: the normal; any other index: minus the normal.
	void getPreferredPenetrationDirection(int index, btVector3& penetrationVector) const override;
};

#endif  // BT_TRIANGLE_SHAPE_H
