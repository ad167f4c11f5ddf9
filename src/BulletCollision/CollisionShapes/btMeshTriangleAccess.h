// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_MESH_TRIANGLE_ACCESS_H
#define CALIBER_MESH_TRIANGLE_ACCESS_H

// Internal: reading triangles out of a btStridingMeshInterface subpart with the checks every mesh
// consumer shares. Bytes are copied with memcpy because user strides need not keep the data aligned.

#include <cstring>

#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"
#include "btShapeGuards.h"

namespace caliber
{
/// One subpart of a mesh, locked read-only while held (released by release(), the next acquire or the
/// destructor), so that a query touching many triangles of one part locks it once.
class ReadOnlyMeshPart
{
public:
	ReadOnlyMeshPart()
	    : m_mesh(0),
	      m_part(-1),
	      m_usable(false),
	      m_vertexBase(0),
	      m_numVertices(0),
	      m_vertexType(PHY_FLOAT),
	      m_vertexStride(0),
	      m_indexBase(0),
	      m_indexStride(0),
	      m_numFaces(0),
	      m_indexType(PHY_INTEGER)
	{
	}
	~ReadOnlyMeshPart() { release(); }
	ReadOnlyMeshPart(const ReadOnlyMeshPart&) = delete;
	ReadOnlyMeshPart& operator=(const ReadOnlyMeshPart&) = delete;

	/// Locks subpart part of mesh (releasing the part held before). Returns whether its data can be
	/// read; a part with an unsupported type, a null base or a short stride asserts and reads as empty.
	bool acquire(const btStridingMeshInterface* mesh, int part);
	/// Unlocks the held part, if any.
	void release()
	{
		if (m_mesh) m_mesh->unLockReadOnlyVertexBase(m_part);
		m_mesh = 0;
		m_part = -1;
		m_usable = false;
	}
	/// The held part, or -1.
	int part() const { return m_part; }
	/// Number of triangles of the held part (0 when it is not readable).
	int numTriangles() const { return m_usable ? m_numFaces : 0; }

	/// Writes triangle triangleIndex of the held part, each vertex times scaling, to out[0..2]. Returns
	/// false (after asserting) when an index is out of range or a vertex is not finite.
	bool readTriangle(int triangleIndex, const btVector3& scaling, btVector3* out) const
	{
		if (!m_usable || triangleIndex < 0 || triangleIndex >= m_numFaces)
		{
			btAssert(m_usable && triangleIndex >= 0 && triangleIndex < m_numFaces && "mesh triangle out of range");
			return false;
		}
		const unsigned char* indices = m_indexBase + size_t(triangleIndex) * size_t(m_indexStride);
		for (int k = 0; k < 3; ++k)
		{
			const unsigned index = readIndex(indices, k);
			if (index >= unsigned(m_numVertices))
			{
				btAssert(index < unsigned(m_numVertices) && "mesh index out of range");
				return false;
			}
			out[k] = readVertex(index) * scaling;
			if (!caliber::isFinite(out[k]))
			{
				btAssert(caliber::isFinite(out[k]) && "mesh vertex not finite");
				return false;
			}
		}
		return true;
	}

private:
	unsigned readIndex(const unsigned char* indices, int k) const
	{
		switch (m_indexType)
		{
			case PHY_INTEGER:
			{
				unsigned int value;
				std::memcpy(&value, indices + k * sizeof(value), sizeof(value));
				return value;
			}
			case PHY_SHORT:
			{
				unsigned short value;
				std::memcpy(&value, indices + k * sizeof(value), sizeof(value));
				return value;
			}
			default:
				return indices[k];
		}
	}
	btVector3 readVertex(unsigned index) const
	{
		const unsigned char* p = m_vertexBase + size_t(index) * size_t(m_vertexStride);
		if (m_vertexType == PHY_FLOAT)
		{
			float v[3];
			std::memcpy(v, p, sizeof(v));
			return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2]));
		}
		double v[3];
		std::memcpy(v, p, sizeof(v));
		return btVector3(btScalar(v[0]), btScalar(v[1]), btScalar(v[2]));
	}

	const btStridingMeshInterface* m_mesh;
	int m_part;
	bool m_usable;
	const unsigned char* m_vertexBase;
	int m_numVertices;
	PHY_ScalarType m_vertexType;
	int m_vertexStride;
	const unsigned char* m_indexBase;
	int m_indexStride;
	int m_numFaces;
	PHY_ScalarType m_indexType;
};

/// Calls visit(triangle, partId, triangleIndex) for every readable triangle of mesh (vertices scaled
/// by the mesh's scaling). No virtual call per triangle.
template <class Visitor>
void forEachMeshTriangle(const btStridingMeshInterface& mesh, Visitor&& visit)
{
	const btVector3 scaling = mesh.getScaling();
	ReadOnlyMeshPart part;
	btVector3 triangle[3];
	const int numParts = mesh.getNumSubParts();
	for (int p = 0; p < numParts; ++p)
	{
		if (!part.acquire(&mesh, p)) continue;
		const int n = part.numTriangles();
		for (int t = 0; t < n; ++t)
			if (part.readTriangle(t, scaling, triangle)) visit(triangle, p, t);
	}
}

/// The AABB of a triangle (min and max of its vertices).
inline void triangleAabb(const btVector3* triangle, btVector3& aabbMin, btVector3& aabbMax)
{
	aabbMin = triangle[0];
	aabbMax = triangle[0];
	aabbMin.setMin(triangle[1]);
	aabbMax.setMax(triangle[1]);
	aabbMin.setMin(triangle[2]);
	aabbMax.setMax(triangle[2]);
}

}  // namespace caliber

#endif  // CALIBER_MESH_TRIANGLE_ACCESS_H
