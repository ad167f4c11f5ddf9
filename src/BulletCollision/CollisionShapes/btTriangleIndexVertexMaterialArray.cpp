// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexMaterialArray.h"

btTriangleIndexVertexMaterialArray::btTriangleIndexVertexMaterialArray(int numTriangles, int* triangleIndexBase,
                                                                       int triangleIndexStride, int numVertices,
                                                                       btScalar* vertexBase, int vertexStride,
                                                                       int numMaterials, unsigned char* materialBase,
                                                                       int materialStride, int* triangleMaterialsBase,
                                                                       int materialIndexStride)
    : btTriangleIndexVertexArray(numTriangles, triangleIndexBase, triangleIndexStride, numVertices, vertexBase,
                                 vertexStride)
{
	btMaterialProperties mat;
	mat.m_numMaterials = numMaterials;
	mat.m_materialBase = materialBase;
	mat.m_materialStride = materialStride;
#ifdef BT_USE_DOUBLE_PRECISION
	mat.m_materialType = PHY_DOUBLE;
#else
	mat.m_materialType = PHY_FLOAT;
#endif
	mat.m_numTriangles = numTriangles;
	mat.m_triangleMaterialsBase = reinterpret_cast<const unsigned char*>(triangleMaterialsBase);
	mat.m_triangleMaterialStride = materialIndexStride;
	mat.m_triangleType = PHY_INTEGER;
	addMaterialProperties(mat, PHY_INTEGER);
}

btTriangleIndexVertexMaterialArray::~btTriangleIndexVertexMaterialArray() {}

void btTriangleIndexVertexMaterialArray::addMaterialProperties(const btMaterialProperties& mat,
                                                               PHY_ScalarType triangleType)
{
	m_materials.push_back(mat);
	m_materials[m_materials.size() - 1].m_triangleType = triangleType;
}

void btTriangleIndexVertexMaterialArray::getLockedMaterialBase(unsigned char** materialBase, int& numMaterials,
                                                               PHY_ScalarType& materialType, int& materialStride,
                                                               unsigned char** triangleMaterialBase, int& numTriangles,
                                                               int& triangleMaterialStride,
                                                               PHY_ScalarType& triangleType, int subpart)
{
	const unsigned char* materials = 0;
	const unsigned char* triangleMaterials = 0;
	getLockedReadOnlyMaterialBase(&materials, numMaterials, materialType, materialStride, &triangleMaterials,
	                              numTriangles, triangleMaterialStride, triangleType, subpart);
	// The arrays belong to the user, who handed them over as writable data.
	*materialBase = const_cast<unsigned char*>(materials);
	*triangleMaterialBase = const_cast<unsigned char*>(triangleMaterials);
}

void btTriangleIndexVertexMaterialArray::getLockedReadOnlyMaterialBase(const unsigned char** materialBase,
                                                                       int& numMaterials, PHY_ScalarType& materialType,
                                                                       int& materialStride,
                                                                       const unsigned char** triangleMaterialBase,
                                                                       int& numTriangles, int& triangleMaterialStride,
                                                                       PHY_ScalarType& triangleType, int subpart)
{
	btAssert(subpart >= 0 && subpart < m_materials.size());
	const btMaterialProperties empty;
	const btMaterialProperties& mat = (subpart >= 0 && subpart < m_materials.size()) ? m_materials[subpart] : empty;
	*materialBase = mat.m_materialBase;
	numMaterials = mat.m_numMaterials;
	materialType = mat.m_materialType;
	materialStride = mat.m_materialStride;
	*triangleMaterialBase = mat.m_triangleMaterialsBase;
	numTriangles = mat.m_numTriangles;
	triangleMaterialStride = mat.m_triangleMaterialStride;
	triangleType = mat.m_triangleType;
}
