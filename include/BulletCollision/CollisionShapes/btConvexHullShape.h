// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_HULL_SHAPE_H
#define BT_CONVEX_HULL_SHAPE_H

#include "BulletCollision/CollisionShapes/btPolyhedralConvexShape.h"
#include "LinearMath/btAlignedObjectArray.h"

/// The convex hull of a point cloud the shape owns a copy of. The points need not be hull vertices
/// (optimizeConvexHull drops the others); support queries scan them all. Points with a NaN or infinite
/// coordinate are bad input: they assert and, in release builds, are not stored.
ATTRIBUTE_ALIGNED16(class)
btConvexHullShape : public btPolyhedralConvexAabbCachingShape
{
	btAlignedObjectArray<btVector3> m_unscaledPoints;
	// The support scan's copy of the points: the distinct ones (bitwise, first occurrences in order) in
	// blocks of four, stored as 4 x, 4 y and 4 z; a partial last block repeats the first point. Kept in
	// step by the methods that change the points; handing out the writable points makes it stale, and
	// support queries then scan m_unscaledPoints until the next addPoint or optimizeConvexHull.
	btAlignedObjectArray<btScalar> m_supportLanes;
	int m_supportCount;
	bool m_supportLanesValid;

	void rebuildSupportLanes();
	void appendSupportLane(const btVector3& point);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Copies numPoints points, stride bytes apart, each three btScalars (x, y, z). Null points or
	/// numPoints <= 0 give an empty hull (its core is the origin: the margin ball); null points with
	/// numPoints > 0, or a stride below 3 btScalars, assert and give an empty hull in release builds.
	btConvexHullShape(const btScalar* points = 0, int numPoints = 0, int stride = sizeof(btVector3));

	/// Appends a point and, if recalculateLocalAabb, refreshes the cached AABB.
	void addPoint(const btVector3& point, bool recalculateLocalAabb = true);

	/// The stored points, local scaling not applied. Points edited through this pointer are seen by the
	/// support queries (which then scan all the points) until the next addPoint or optimizeConvexHull;
	/// call recalcLocalAabb after editing, as the cached AABB needs it.
	btVector3* getUnscaledPoints()
	{
		m_supportLanesValid = false;
		return m_unscaledPoints.size() ? &m_unscaledPoints[0] : 0;
	}
	/// The stored points, local scaling not applied.
	const btVector3* getUnscaledPoints() const { return m_unscaledPoints.size() ? &m_unscaledPoints[0] : 0; }
	/// Same as getUnscaledPoints (Bullet's older name).
	const btVector3* getPoints() const { return getUnscaledPoints(); }

	/// Keeps only the points that are vertices of the hull (in their original order).
	void optimizeConvexHull();

	/// Point i with local scaling applied; an index out of range asserts and gives the origin.
	btVector3 getScaledPoint(int i) const
	{
		btAssert(i >= 0 && i < m_unscaledPoints.size());
		if (i < 0 || i >= m_unscaledPoints.size()) return btVector3(0, 0, 0);
		return m_unscaledPoints[i] * m_localScaling;
	}
	/// Number of stored points.
	int getNumPoints() const { return m_unscaledPoints.size(); }

	/// The scaled point farthest along vec; the origin for an empty hull.
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override;
	/// localGetSupportingVertexWithoutMargin for each of numVectors directions.
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* supportVerticesOut,
	                                                       int numVectors) const override;

	/// "Convex", as in Bullet.
	const char* getName() const override { return "Convex"; }

	/// Number of points.
	int getNumVertices() const override;
	/// Number of points: edge i joins point i to point i + 1 (wrapping), as in Bullet.
	int getNumEdges() const override;
	/// Edge i: scaled points i and (i + 1) mod n; out of range asserts and gives the origin twice.
	void getEdge(int i, btVector3& pa, btVector3& pb) const override;
	/// Scaled point i; out of range asserts and gives the origin.
	void getVertex(int i, btVector3& vtx) const override;
	/// 0: the hull's planes are not stored (use initializePolyhedralFeatures).
	int getNumPlanes() const override;
	/// There are no planes: asserts, and gives a zero normal and support in release builds.
	void getPlane(btVector3 & planeNormal, btVector3 & planeSupport, int i) const override;
	/// Not supported (no planes): asserts, and returns false in release builds.
	bool isInside(const btVector3& pt, btScalar tolerance) const override;

public:
	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btConvexHullShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btConvexHullShapeData
{
	btConvexInternalShapeData m_convexInternalShapeData;
	btVector3FloatData* m_unscaledPointsFloatPtr;
	btVector3DoubleData* m_unscaledPointsDoublePtr;
	int m_numUnscaledPoints;
	char m_padding3[4];
};

// clang-format on

#endif  // BT_CONVEX_HULL_SHAPE_H
