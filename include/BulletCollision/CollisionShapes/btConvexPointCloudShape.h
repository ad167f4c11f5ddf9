// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_POINT_CLOUD_SHAPE_H
#define BT_CONVEX_POINT_CLOUD_SHAPE_H

#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"

/// The convex hull of a point array the shape does NOT own: the array must outlive the shape, and
/// after changing it call recalcLocalAabb(). Points with a NaN or infinite coordinate are never used
/// as support points (setPoints asserts on them); with no usable point the shape is a point at the origin.
ATTRIBUTE_ALIGNED16(class)
btConvexPointCloudShape : public btPolyhedralConvexAabbCachingShape
{
	btVector3* m_unscaledPoints;
	int m_numPoints;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// No points.
	btConvexPointCloudShape();
	/// Uses numPoints points at points (not copied) with the given scaling; see setPoints.
	btConvexPointCloudShape(btVector3 * points, int numPoints, const btVector3& localScaling, bool computeAabb = true);

	/// Uses numPoints points at points (not copied). A null array with numPoints > 0, or a negative
	/// count, asserts and gives no points; non-finite points assert (and are skipped by every query).
	void setPoints(btVector3 * points, int numPoints, bool computeAabb = true,
	               const btVector3& localScaling = btVector3(1.f, 1.f, 1.f));

	/// The points, unscaled.
	btVector3* getUnscaledPoints() { return m_unscaledPoints; }
	/// The points, unscaled.
	const btVector3* getUnscaledPoints() const { return m_unscaledPoints; }
	/// Number of points.
	int getNumPoints() const { return m_numPoints; }
	/// Point index with local scaling applied; out of range asserts and gives the origin.
	btVector3 getScaledPoint(int index) const;

	/// The scaled finite point farthest along vec; the origin when there is none.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each of numVectors directions.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// "ConvexPointCloud".
	const char* getName() const override { return "ConvexPointCloud"; }

	/// Number of points.
	int getNumVertices() const override;
	/// Number of points (edge i joins points i and i + 1, wrapping), as in Bullet.
	int getNumEdges() const override;
	/// Edge i; out of range asserts and gives the origin twice.
	void getEdge(int i, btVector3& pa, btVector3& pb) const override;
	/// Scaled point i; out of range asserts and gives the origin.
	void getVertex(int i, btVector3& vtx) const override;
	/// 0: no planes are stored.
	int getNumPlanes() const override;
	/// There are no planes: asserts, and gives zero vectors in release builds.
	void getPlane(btVector3 & planeNormal, btVector3 & planeSupport, int i) const override;
	/// Not supported: asserts, and returns false in release builds.
	bool isInside(const btVector3& pt, btScalar tolerance) const override;
};

#endif  // BT_CONVEX_POINT_CLOUD_SHAPE_H
