// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRIANGLE_BUFFER_H
#define BT_TRIANGLE_BUFFER_H

#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "LinearMath/btAlignedObjectArray.h"

/// One triangle as a btTriangleBuffer stores it: its vertices and where it came from.
struct btTriangle
{
	btVector3 m_vertex0;
	btVector3 m_vertex1;
	btVector3 m_vertex2;
	int m_partId;
	int m_triangleIndex;
};

/// A triangle callback that keeps a copy of every triangle it is given, for example to collect the
/// triangles a mesh query (processAllTriangles over an AABB) returns and use them afterwards.
class btTriangleBuffer : public btTriangleCallback
{
	btAlignedObjectArray<btTriangle> m_triangleBuffer;

public:
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		if (!triangle) return;
		btTriangle& stored = m_triangleBuffer.expand();
		stored.m_vertex0 = triangle[0];
		stored.m_vertex1 = triangle[1];
		stored.m_vertex2 = triangle[2];
		stored.m_partId = partId;
		stored.m_triangleIndex = triangleIndex;
	}

	int getNumTriangles() const { return m_triangleBuffer.size(); }

	/// Triangle index (0 <= index < getNumTriangles(); out-of-range indices assert).
	const btTriangle& getTriangle(int index) const { return m_triangleBuffer[index]; }

	void clearBuffer() { m_triangleBuffer.clear(); }
};

#endif  // BT_TRIANGLE_BUFFER_H
