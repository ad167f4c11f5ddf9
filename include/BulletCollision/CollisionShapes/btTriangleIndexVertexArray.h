// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRIANGLE_INDEX_VERTEX_ARRAY_H
#define BT_TRIANGLE_INDEX_VERTEX_ARRAY_H

#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

/// One subpart of a btTriangleIndexVertexArray: pointers into arrays the user keeps alive.
ATTRIBUTE_ALIGNED16(struct)
btIndexedMesh
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Number of triangles (three indices each).
	int m_numTriangles;
	/// First byte of the index array.
	const unsigned char* m_triangleIndexBase;
	/// Bytes from one triangle's indices to the next one's.
	int m_triangleIndexStride;
	/// Number of vertices (indices must be below it).
	int m_numVertices;
	/// First byte of the vertex array.
	const unsigned char* m_vertexBase;
	/// Bytes from one vertex to the next.
	int m_vertexStride;
	/// PHY_INTEGER, PHY_SHORT or PHY_UCHAR.
	PHY_ScalarType m_indexType;
	/// PHY_FLOAT or PHY_DOUBLE.
	PHY_ScalarType m_vertexType;

	/// An empty mesh with 32-bit indices and btScalar vertices.
	btIndexedMesh()
	    : m_numTriangles(0),
	      m_triangleIndexBase(0),
	      m_triangleIndexStride(0),
	      m_numVertices(0),
	      m_vertexBase(0),
	      m_vertexStride(0),
	      m_indexType(PHY_INTEGER),
#ifdef BT_USE_DOUBLE_PRECISION
	      m_vertexType(PHY_DOUBLE)
#else
	      m_vertexType(PHY_FLOAT)
#endif
	{
	}
};

/// The subparts of a btTriangleIndexVertexArray.
typedef btAlignedObjectArray<btIndexedMesh> IndexedMeshArray;

/// A btStridingMeshInterface over user-owned arrays, one btIndexedMesh per subpart. The arrays are not
/// copied: they must outlive the interface and every shape using it.
ATTRIBUTE_ALIGNED16(class)
btTriangleIndexVertexArray : public btStridingMeshInterface
{
protected:
	/// The subparts.
	IndexedMeshArray m_indexedMeshes;
	/// 1 once setPremadeAabb was called.
	mutable int m_hasAabb;
	/// The premade AABB.
	mutable btVector3 m_aabbMin;
	/// The premade AABB.
	mutable btVector3 m_aabbMax;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An interface with no subparts.
	btTriangleIndexVertexArray() : m_hasAabb(0), m_aabbMin(0, 0, 0), m_aabbMax(0, 0, 0) {}
	/// Interfaces are deleted through base pointers.
	virtual ~btTriangleIndexVertexArray();

	/// One subpart of 32-bit indices (3 per triangle, triangleIndexStride bytes apart) and btScalar
	/// vertices (vertexStride bytes apart).
	btTriangleIndexVertexArray(int numTriangles, int* triangleIndexBase, int triangleIndexStride, int numVertices,
	                           btScalar* vertexBase, int vertexStride);

	/// Appends a subpart, overriding its index type with indexType.
	void addIndexedMesh(const btIndexedMesh& mesh, PHY_ScalarType indexType = PHY_INTEGER)
	{
		m_indexedMeshes.push_back(mesh);
		m_indexedMeshes[m_indexedMeshes.size() - 1].m_indexType = indexType;
	}

	/// The arrays of subpart (writable); an out-of-range subpart asserts and gives an empty part.
	void getLockedVertexIndexBase(unsigned char** vertexbase, int& numverts, PHY_ScalarType& type, int& vertexStride,
	                              unsigned char** indexbase, int& indexstride, int& numfaces,
	                              PHY_ScalarType& indicestype, int subpart = 0) override;
	/// The arrays of subpart; an out-of-range subpart asserts and gives an empty part.
	void getLockedReadOnlyVertexIndexBase(const unsigned char** vertexbase, int& numverts, PHY_ScalarType& type,
	                                      int& vertexStride, const unsigned char** indexbase, int& indexstride,
	                                      int& numfaces, PHY_ScalarType& indicestype, int subpart = 0) const override;
	/// Nothing to do: the data is always accessible.
	void unLockVertexBase(int subpart) override { (void)subpart; }
	/// Nothing to do: the data is always accessible.
	void unLockReadOnlyVertexBase(int subpart) const override { (void)subpart; }

	/// Number of subparts.
	int getNumSubParts() const override { return m_indexedMeshes.size(); }

	/// The subparts.
	IndexedMeshArray& getIndexedMeshArray() { return m_indexedMeshes; }
	/// The subparts.
	const IndexedMeshArray& getIndexedMeshArray() const { return m_indexedMeshes; }

	/// Nothing to preallocate (the user owns the arrays).
	void preallocateVertices(int numverts) override { (void)numverts; }
	/// Nothing to preallocate (the user owns the arrays).
	void preallocateIndices(int numindices) override { (void)numindices; }

	/// True after setPremadeAabb.
	bool hasPremadeAabb() const override;
	/// Stores the AABB that shapes then use instead of scanning the vertices.
	void setPremadeAabb(const btVector3& aabbMin, const btVector3& aabbMax) const override;
	/// The stored AABB.
	void getPremadeAabb(btVector3 * aabbMin, btVector3 * aabbMax) const override;
};

#endif  // BT_TRIANGLE_INDEX_VERTEX_ARRAY_H
