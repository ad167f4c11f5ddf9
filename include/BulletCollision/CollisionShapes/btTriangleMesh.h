// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TRIANGLE_MESH_H
#define BT_TRIANGLE_MESH_H

#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

/// A triangle mesh that owns its data: one subpart built with addTriangle (optionally welding vertices
/// closer than m_weldingThreshold) or addIndex / addTriangleIndices. Indices are 32 or 16 bits,
/// vertices 4 btScalars (btVector3) or 3 btScalars.
ATTRIBUTE_ALIGNED16(class)
btTriangleMesh : public btTriangleIndexVertexArray
{
	btAlignedObjectArray<btVector3> m_4componentVertices;
	btAlignedObjectArray<btScalar> m_3componentVertices;
	btAlignedObjectArray<unsigned int> m_32bitIndices;
	btAlignedObjectArray<unsigned short int> m_16bitIndices;
	bool m_use32bitIndices;
	bool m_use4componentVertices;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// addTriangle with removeDuplicateVertices merges a vertex into a stored one at most this far away
	/// (a distance; 0 merges exact duplicates only). Bullet compares the squared distance with it instead.
	btScalar m_weldingThreshold;

	/// An empty mesh with 32-bit (else 16-bit) indices and 4-component (else 3-component) vertices.
	btTriangleMesh(bool use32bitIndices = true, bool use4componentVertices = true);

	/// A deep copy (the copy's subpart points at its own arrays).
	btTriangleMesh(const btTriangleMesh& other);
	/// A deep copy (the subpart points at this mesh's own arrays).
	btTriangleMesh& operator=(const btTriangleMesh& other);
	~btTriangleMesh() override;

	/// True when indices are 32 bits.
	bool getUse32bitIndices() const { return m_use32bitIndices; }
	/// True when vertices are stored as btVector3.
	bool getUse4componentVertices() const { return m_use4componentVertices; }

	/// Appends a triangle, its vertices welded to stored ones when removeDuplicateVertices. With 16-bit
	/// indices a vertex index above 65535 asserts and, in release builds, the triangle is not added.
	void addTriangle(const btVector3& vertex0, const btVector3& vertex1, const btVector3& vertex2,
	                 bool removeDuplicateVertices = false);

	/// Appends a triangle of already stored vertices (same 16-bit rule as addTriangle).
	void addTriangleIndices(int index1, int index2, int index3);

	/// Number of triangles.
	int getNumTriangles() const;

	/// Reserves room for numverts more vertices.
	void preallocateVertices(int numverts) override;
	/// Reserves room for numindices more indices.
	void preallocateIndices(int numindices) override;

	/// The index of a stored vertex within m_weldingThreshold of vertex (the lowest such index) when
	/// removeDuplicateVertices, else of a newly appended copy of vertex. Non-finite vertices are never
	/// welded.
	int findOrAddVertex(const btVector3& vertex, bool removeDuplicateVertices);
	/// Appends one index (does not count a triangle). A negative index, or one above 65535 with 16-bit
	/// indices, asserts; in release builds it is stored as an index that readers reject as out of range
	/// (0xFFFF for 16 bits, unless the mesh has more than 65535 vertices).
	void addIndex(int index);
};

#endif  // BT_TRIANGLE_MESH_H
