// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btMultimaterialTriangleMeshShape.h"

#include <cstring>

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexMaterialArray.h"

btMultimaterialTriangleMeshShape::btMultimaterialTriangleMeshShape(btStridingMeshInterface* meshInterface,
                                                                   bool useQuantizedAabbCompression, bool buildBvh)
    : btBvhTriangleMeshShape(meshInterface, useQuantizedAabbCompression, buildBvh),
      // The tables live only in the material array; any other interface has none to look up.
      m_materialMesh(dynamic_cast<btTriangleIndexVertexMaterialArray*>(meshInterface))
{
	m_shapeType = MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE;
}

btMultimaterialTriangleMeshShape::btMultimaterialTriangleMeshShape(btStridingMeshInterface* meshInterface,
                                                                   bool useQuantizedAabbCompression,
                                                                   const btVector3& bvhAabbMin,
                                                                   const btVector3& bvhAabbMax, bool buildBvh)
    : btBvhTriangleMeshShape(meshInterface, useQuantizedAabbCompression, bvhAabbMin, bvhAabbMax, buildBvh),
      m_materialMesh(dynamic_cast<btTriangleIndexVertexMaterialArray*>(meshInterface))
{
	m_shapeType = MULTIMATERIAL_TRIANGLE_MESH_PROXYTYPE;
}

btMultimaterialTriangleMeshShape::~btMultimaterialTriangleMeshShape() {}

const btMaterial* btMultimaterialTriangleMeshShape::getMaterialProperties(int partID, int triIndex)
{
	btAssert(m_materialMesh && "btMultimaterialTriangleMeshShape: the mesh has no material tables");
	if (!m_materialMesh) return 0;
	btAssert(partID >= 0 && partID < m_materialMesh->getNumMaterialSubParts() &&
	         "btMultimaterialTriangleMeshShape::getMaterialProperties: part id out of range");
	if (partID < 0 || partID >= m_materialMesh->getNumMaterialSubParts()) return 0;

	const unsigned char* materialBase = 0;
	const unsigned char* triangleMaterialBase = 0;
	int numMaterials = 0, materialStride = 0, numTriangles = 0, triangleMaterialStride = 0;
	PHY_ScalarType materialType = PHY_FLOAT, triangleType = PHY_INTEGER;
	m_materialMesh->getLockedReadOnlyMaterialBase(&materialBase, numMaterials, materialType, materialStride,
	                                              &triangleMaterialBase, numTriangles, triangleMaterialStride,
	                                              triangleType, partID);
	btAssert(triIndex >= 0 && triIndex < numTriangles &&
	         "btMultimaterialTriangleMeshShape::getMaterialProperties: triangle index out of range");
	if (triIndex < 0 || triIndex >= numTriangles || !materialBase || !triangleMaterialBase) return 0;

	// memcpy: the user's stride need not keep the index aligned.
	const unsigned char* entry = triangleMaterialBase + size_t(triIndex) * size_t(triangleMaterialStride);
	int materialIndex = -1;
	if (triangleType == PHY_INTEGER)
	{
		std::memcpy(&materialIndex, entry, sizeof(int));
	}
	else if (triangleType == PHY_SHORT)
	{
		short index16 = 0;
		std::memcpy(&index16, entry, sizeof(short));
		materialIndex = index16;
	}
	else
	{
		btAssert(!"btMultimaterialTriangleMeshShape: material indices must be PHY_INTEGER or PHY_SHORT");
		return 0;
	}
	btAssert(materialIndex >= 0 && materialIndex < numMaterials &&
	         "btMultimaterialTriangleMeshShape: a triangle's material index is out of range");
	if (materialIndex < 0 || materialIndex >= numMaterials) return 0;
	return reinterpret_cast<const btMaterial*>(materialBase + size_t(materialIndex) * size_t(materialStride));
}
