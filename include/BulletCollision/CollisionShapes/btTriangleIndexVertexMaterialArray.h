// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MULTIMATERIAL_TRIANGLE_INDEX_VERTEX_ARRAY_H
#define BT_MULTIMATERIAL_TRIANGLE_INDEX_VERTEX_ARRAY_H

#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"

/// The materials of one subpart: a table of user material records and one material index per triangle
/// (pointers into arrays the user keeps alive).
ATTRIBUTE_ALIGNED16(struct)
btMaterialProperties
{
	/// Number of material records.
	int m_numMaterials;
	/// First byte of the material records.
	const unsigned char* m_materialBase;
	/// Bytes from one material record to the next.
	int m_materialStride;
	/// Scalar type of the records (informational; the records are the user's).
	PHY_ScalarType m_materialType;
	/// Number of per-triangle material indices.
	int m_numTriangles;
	/// First byte of the per-triangle material indices.
	const unsigned char* m_triangleMaterialsBase;
	/// Bytes from one triangle's material index to the next.
	int m_triangleMaterialStride;
	/// Type of the per-triangle material indices (PHY_INTEGER).
	PHY_ScalarType m_triangleType;

	/// No materials.
	btMaterialProperties()
	    : m_numMaterials(0),
	      m_materialBase(0),
	      m_materialStride(0),
	      m_materialType(PHY_FLOAT),
	      m_numTriangles(0),
	      m_triangleMaterialsBase(0),
	      m_triangleMaterialStride(0),
	      m_triangleType(PHY_INTEGER)
	{
	}
};

/// The material tables of all subparts.
typedef btAlignedObjectArray<btMaterialProperties> MaterialArray;

/// A btTriangleIndexVertexArray that also carries, per subpart, a material table and a material index
/// per triangle (for btMultimaterialTriangleMeshShape-style lookups).
ATTRIBUTE_ALIGNED16(class)
btTriangleIndexVertexMaterialArray : public btTriangleIndexVertexArray
{
protected:
	/// One entry per subpart that has materials.
	MaterialArray m_materials;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// No subparts, no materials.
	btTriangleIndexVertexMaterialArray() {}

	/// One subpart (as btTriangleIndexVertexArray's constructor) with numMaterials records of
	/// materialStride bytes and one int material index per triangle, materialIndexStride bytes apart.
	btTriangleIndexVertexMaterialArray(int numTriangles, int* triangleIndexBase, int triangleIndexStride,
	                                   int numVertices, btScalar* vertexBase, int vertexStride, int numMaterials,
	                                   unsigned char* materialBase, int materialStride, int* triangleMaterialsBase,
	                                   int materialIndexStride);

	/// Interfaces are deleted through base pointers.
	virtual ~btTriangleIndexVertexMaterialArray();

	/// Appends the material table of the next subpart, overriding its index type with triangleType.
	void addMaterialProperties(const btMaterialProperties& mat, PHY_ScalarType triangleType = PHY_INTEGER);

	/// The material arrays of subpart (writable); an out-of-range subpart asserts and gives empty arrays.
	virtual void getLockedMaterialBase(unsigned char** materialBase, int& numMaterials, PHY_ScalarType& materialType,
	                                   int& materialStride, unsigned char** triangleMaterialBase, int& numTriangles,
	                                   int& triangleMaterialStride, PHY_ScalarType& triangleType, int subpart = 0);

	/// The material arrays of subpart; an out-of-range subpart asserts and gives empty arrays.
	virtual void getLockedReadOnlyMaterialBase(
	    const unsigned char** materialBase, int& numMaterials, PHY_ScalarType& materialType, int& materialStride,
	    const unsigned char** triangleMaterialBase, int& numTriangles, int& triangleMaterialStride,
	    PHY_ScalarType& triangleType, int subpart = 0);

	/// Number of material tables.
	int getNumMaterialSubParts() const { return m_materials.size(); }
};

#endif  // BT_MULTIMATERIAL_TRIANGLE_INDEX_VERTEX_ARRAY_H
