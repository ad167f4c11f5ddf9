// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// serialize() of every collision shape that Bullet's .bullet format describes: each writes its data
// struct (declared next to the class) and its sub-objects (children, points, mesh parts) as chunks of
// their own, referenced by unique ids. Field meanings follow Bullet's (docs/serialization.md).
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"

#include <string.h>

// ---- base -------------------------------------------------------------------------------------

int btCollisionShape::calculateSerializeBufferSize() const { return int(sizeof(btCollisionShapeData)); }

const char* btCollisionShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btCollisionShapeData* shapeData = static_cast<btCollisionShapeData*>(dataBuffer);
	const char* name = serializer->findNameForPointer(this);
	shapeData->m_name = static_cast<char*>(serializer->getUniquePointer(const_cast<char*>(name)));
	if (shapeData->m_name) serializer->serializeName(name);
	shapeData->m_shapeType = m_shapeType;
	memset(shapeData->m_padding, 0, sizeof(shapeData->m_padding));
	return "btCollisionShapeData";
}

void btCollisionShape::serializeSingleShape(btSerializer* serializer) const
{
	// Shared shapes are written once; later references use the same unique id.
	if (serializer->findPointer(const_cast<btCollisionShape*>(this))) return;
	btChunk* chunk = serializer->allocate(size_t(calculateSerializeBufferSize()), 1);
	if (!chunk) return;
	const char* structType = serialize(chunk->m_oldPtr, serializer);
	serializer->finalizeChunk(chunk, structType, BT_SHAPE_CODE, const_cast<btCollisionShape*>(this));
}

// ---- convex primitives ------------------------------------------------------------------------

int btConvexInternalShape::calculateSerializeBufferSize() const { return int(sizeof(btConvexInternalShapeData)); }

const char* btConvexInternalShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btConvexInternalShapeData* shapeData = static_cast<btConvexInternalShapeData*>(dataBuffer);
	btCollisionShape::serialize(&shapeData->m_collisionShapeData, serializer);
	m_implicitShapeDimensions.serializeFloat(shapeData->m_implicitShapeDimensions);
	m_localScaling.serializeFloat(shapeData->m_localScaling);
	shapeData->m_collisionMargin = float(m_collisionMargin);
	shapeData->m_padding = 0;
	return "btConvexInternalShapeData";
}

int btCapsuleShape::calculateSerializeBufferSize() const { return int(sizeof(btCapsuleShapeData)); }

const char* btCapsuleShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btCapsuleShapeData* shapeData = static_cast<btCapsuleShapeData*>(dataBuffer);
	btConvexInternalShape::serialize(&shapeData->m_convexInternalShapeData, serializer);
	shapeData->m_upAxis = m_upAxis;
	memset(shapeData->m_padding, 0, sizeof(shapeData->m_padding));
	return "btCapsuleShapeData";
}

int btCylinderShape::calculateSerializeBufferSize() const { return int(sizeof(btCylinderShapeData)); }

const char* btCylinderShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btCylinderShapeData* shapeData = static_cast<btCylinderShapeData*>(dataBuffer);
	btConvexInternalShape::serialize(&shapeData->m_convexInternalShapeData, serializer);
	shapeData->m_upAxis = m_upAxis;
	memset(shapeData->m_padding, 0, sizeof(shapeData->m_padding));
	return "btCylinderShapeData";
}

int btConeShape::calculateSerializeBufferSize() const { return int(sizeof(btConeShapeData)); }

const char* btConeShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btConeShapeData* shapeData = static_cast<btConeShapeData*>(dataBuffer);
	btConvexInternalShape::serialize(&shapeData->m_convexInternalShapeData, serializer);
	// The file's cone dimensions are unscaled: the radius on the two other axes, the full height on
	// the up axis (local scaling is stored beside them).
	const int up = getConeUpIndex();
	float dims[3];
	for (int i = 0; i < 3; ++i) dims[i] = float(m_implicitShapeDimensions[i]);
	for (int i = 0; i < 3; ++i) shapeData->m_convexInternalShapeData.m_implicitShapeDimensions.m_floats[i] = dims[i];
	shapeData->m_convexInternalShapeData.m_implicitShapeDimensions.m_floats[3] = 0.f;
	shapeData->m_upIndex = up;
	memset(shapeData->m_padding, 0, sizeof(shapeData->m_padding));
	return "btConeShapeData";
}

int btMultiSphereShape::calculateSerializeBufferSize() const { return int(sizeof(btMultiSphereShapeData)); }

const char* btMultiSphereShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btMultiSphereShapeData* shapeData = static_cast<btMultiSphereShapeData*>(dataBuffer);
	btConvexInternalShape::serialize(&shapeData->m_convexInternalShapeData, serializer);
	const int count = m_localPositionArray.size();
	shapeData->m_localPositionArraySize = count;
	memset(shapeData->m_padding, 0, sizeof(shapeData->m_padding));
	void* arrayId = count ? const_cast<btVector3*>(&m_localPositionArray[0]) : 0;
	shapeData->m_localPositionArrayPtr = static_cast<btPositionAndRadius*>(serializer->getUniquePointer(arrayId));
	if (count)
	{
		btChunk* chunk = serializer->allocate(sizeof(btPositionAndRadius), count);
		if (chunk)
		{
			btPositionAndRadius* spheres = static_cast<btPositionAndRadius*>(chunk->m_oldPtr);
			for (int i = 0; i < count; ++i)
			{
				m_localPositionArray[i].serializeFloat(spheres[i].m_pos);
				spheres[i].m_radius = float(m_radiArray[i]);
			}
			serializer->finalizeChunk(chunk, "btPositionAndRadius", BT_ARRAY_CODE, arrayId);
		}
	}
	return "btMultiSphereShapeData";
}

int btConvexHullShape::calculateSerializeBufferSize() const { return int(sizeof(btConvexHullShapeData)); }

const char* btConvexHullShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btConvexHullShapeData* shapeData = static_cast<btConvexHullShapeData*>(dataBuffer);
	btConvexInternalShape::serialize(&shapeData->m_convexInternalShapeData, serializer);
	const int count = m_unscaledPoints.size();
	shapeData->m_numUnscaledPoints = count;
	memset(shapeData->m_padding3, 0, sizeof(shapeData->m_padding3));
	void* arrayId = count ? const_cast<btVector3*>(&m_unscaledPoints[0]) : 0;
	// The points keep the build's precision: float builds fill the float array, double builds the other.
#ifdef BT_USE_DOUBLE_PRECISION
	shapeData->m_unscaledPointsFloatPtr = 0;
	shapeData->m_unscaledPointsDoublePtr = static_cast<btVector3DoubleData*>(serializer->getUniquePointer(arrayId));
#else
	shapeData->m_unscaledPointsFloatPtr = static_cast<btVector3FloatData*>(serializer->getUniquePointer(arrayId));
	shapeData->m_unscaledPointsDoublePtr = 0;
#endif
	if (count)
	{
		btChunk* chunk = serializer->allocate(sizeof(btVector3Data), count);
		if (chunk)
		{
			btVector3Data* points = static_cast<btVector3Data*>(chunk->m_oldPtr);
			for (int i = 0; i < count; ++i) m_unscaledPoints[i].serialize(points[i]);
			serializer->finalizeChunk(chunk, btVector3DataName, BT_ARRAY_CODE, arrayId);
		}
	}
	return "btConvexHullShapeData";
}

// ---- compound and plane -----------------------------------------------------------------------

int btCompoundShape::calculateSerializeBufferSize() const { return int(sizeof(btCompoundShapeData)); }

const char* btCompoundShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btCompoundShapeData* shapeData = static_cast<btCompoundShapeData*>(dataBuffer);
	btCollisionShape::serialize(&shapeData->m_collisionShapeData, serializer);
	const int count = m_children.size();
	shapeData->m_collisionMargin = float(m_collisionMargin);
	shapeData->m_numChildShapes = count;
	void* arrayId = count ? const_cast<btCompoundShapeChild*>(&m_children[0]) : 0;
	shapeData->m_childShapePtr = static_cast<btCompoundShapeChildData*>(serializer->getUniquePointer(arrayId));
	if (count)
	{
		btChunk* chunk = serializer->allocate(sizeof(btCompoundShapeChildData), count);
		if (chunk)
		{
			btCompoundShapeChildData* children = static_cast<btCompoundShapeChildData*>(chunk->m_oldPtr);
			for (int i = 0; i < count; ++i)
			{
				const btCompoundShapeChild& child = m_children[i];
				children[i].m_childMargin = float(child.m_childShape->getMargin());
				children[i].m_childShape =
				    static_cast<btCollisionShapeData*>(serializer->getUniquePointer(child.m_childShape));
				child.m_childShape->serializeSingleShape(serializer);
				children[i].m_childShapeType = child.m_childShapeType;
				child.m_transform.serializeFloat(children[i].m_transform);
			}
			serializer->finalizeChunk(chunk, "btCompoundShapeChildData", BT_ARRAY_CODE, arrayId);
		}
	}
	return "btCompoundShapeData";
}

int btStaticPlaneShape::calculateSerializeBufferSize() const { return int(sizeof(btStaticPlaneShapeData)); }

const char* btStaticPlaneShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btStaticPlaneShapeData* shapeData = static_cast<btStaticPlaneShapeData*>(dataBuffer);
	btCollisionShape::serialize(&shapeData->m_collisionShapeData, serializer);
	m_localScaling.serializeFloat(shapeData->m_localScaling);
	m_planeNormal.serializeFloat(shapeData->m_planeNormal);
	shapeData->m_planeConstant = float(m_planeConstant);
	memset(shapeData->m_pad, 0, sizeof(shapeData->m_pad));
	return "btStaticPlaneShapeData";
}

// ---- triangle meshes --------------------------------------------------------------------------

int btStridingMeshInterface::calculateSerializeBufferSize() const { return int(sizeof(btStridingMeshInterfaceData)); }

namespace
{
// Writes the index list of one mesh part in the narrowest of Bullet's index structs that matches it.
void writePartIndices(btMeshPartData& part, const unsigned char* indexBase, int indexStride, int numTriangles,
                      PHY_ScalarType indexType, btSerializer* serializer)
{
	if (numTriangles <= 0 || !indexBase) return;
	void* id = const_cast<unsigned char*>(indexBase);
	switch (indexType)
	{
		case PHY_INTEGER:
		{
			btChunk* chunk = serializer->allocate(sizeof(btIntIndexData), numTriangles * 3);
			if (!chunk) return;
			part.m_indices32 = static_cast<btIntIndexData*>(serializer->getUniquePointer(id));
			btIntIndexData* out = static_cast<btIntIndexData*>(chunk->m_oldPtr);
			for (int t = 0; t < numTriangles; ++t)
			{
				const unsigned char* tri = indexBase + size_t(t) * size_t(indexStride);
				for (int k = 0; k < 3; ++k) memcpy(&out[t * 3 + k].m_value, tri + 4 * k, 4);
			}
			serializer->finalizeChunk(chunk, "btIntIndexData", BT_ARRAY_CODE, id);
			break;
		}
		case PHY_SHORT:
		{
			btChunk* chunk = serializer->allocate(sizeof(btShortIntIndexTripletData), numTriangles);
			if (!chunk) return;
			part.m_3indices16 = static_cast<btShortIntIndexTripletData*>(serializer->getUniquePointer(id));
			btShortIntIndexTripletData* out = static_cast<btShortIntIndexTripletData*>(chunk->m_oldPtr);
			for (int t = 0; t < numTriangles; ++t)
			{
				const unsigned char* tri = indexBase + size_t(t) * size_t(indexStride);
				for (int k = 0; k < 3; ++k) memcpy(&out[t].m_values[k], tri + 2 * k, 2);
			}
			serializer->finalizeChunk(chunk, "btShortIntIndexTripletData", BT_ARRAY_CODE, id);
			break;
		}
		case PHY_UCHAR:
		{
			btChunk* chunk = serializer->allocate(sizeof(btCharIndexTripletData), numTriangles);
			if (!chunk) return;
			part.m_3indices8 = static_cast<btCharIndexTripletData*>(serializer->getUniquePointer(id));
			btCharIndexTripletData* out = static_cast<btCharIndexTripletData*>(chunk->m_oldPtr);
			for (int t = 0; t < numTriangles; ++t)
			{
				const unsigned char* tri = indexBase + size_t(t) * size_t(indexStride);
				for (int k = 0; k < 3; ++k) out[t].m_values[k] = char(tri[k]);
			}
			serializer->finalizeChunk(chunk, "btCharIndexTripletData", BT_ARRAY_CODE, id);
			break;
		}
		default:
			btReportWarning(
			    "Caliber: btStridingMeshInterface::serialize: a mesh part has an index type the "
			    ".bullet format cannot hold; its triangles are not written\n");
			part.m_numTriangles = 0;
			break;
	}
}

void writePartVertices(btMeshPartData& part, const unsigned char* vertexBase, int vertexStride, int numVertices,
                       PHY_ScalarType vertexType, btSerializer* serializer)
{
	if (numVertices <= 0 || !vertexBase) return;
	void* id = const_cast<unsigned char*>(vertexBase);
	if (vertexType == PHY_FLOAT)
	{
		btChunk* chunk = serializer->allocate(sizeof(btVector3FloatData), numVertices);
		if (!chunk) return;
		part.m_vertices3f = static_cast<btVector3FloatData*>(serializer->getUniquePointer(id));
		btVector3FloatData* out = static_cast<btVector3FloatData*>(chunk->m_oldPtr);
		for (int v = 0; v < numVertices; ++v)
			memcpy(out[v].m_floats, vertexBase + size_t(v) * size_t(vertexStride), 3 * sizeof(float));
		serializer->finalizeChunk(chunk, "btVector3FloatData", BT_ARRAY_CODE, id);
	}
	else if (vertexType == PHY_DOUBLE)
	{
		btChunk* chunk = serializer->allocate(sizeof(btVector3DoubleData), numVertices);
		if (!chunk) return;
		part.m_vertices3d = static_cast<btVector3DoubleData*>(serializer->getUniquePointer(id));
		btVector3DoubleData* out = static_cast<btVector3DoubleData*>(chunk->m_oldPtr);
		for (int v = 0; v < numVertices; ++v)
			memcpy(out[v].m_floats, vertexBase + size_t(v) * size_t(vertexStride), 3 * sizeof(double));
		serializer->finalizeChunk(chunk, "btVector3DoubleData", BT_ARRAY_CODE, id);
	}
	else
	{
		btReportWarning(
		    "Caliber: btStridingMeshInterface::serialize: a mesh part has a vertex type the "
		    ".bullet format cannot hold; its vertices are not written\n");
		part.m_numVertices = 0;
	}
}
}  // namespace

const char* btStridingMeshInterface::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btStridingMeshInterfaceData* meshData = static_cast<btStridingMeshInterfaceData*>(dataBuffer);
	const int partCount = getNumSubParts();
	meshData->m_numMeshParts = partCount;
	memset(meshData->m_padding, 0, sizeof(meshData->m_padding));
	m_scaling.serializeFloat(meshData->m_scaling);
	meshData->m_meshPartsPtr = 0;
	if (partCount > 0)
	{
		btChunk* chunk = serializer->allocate(sizeof(btMeshPartData), partCount);
		if (chunk)
		{
			btMeshPartData* parts = static_cast<btMeshPartData*>(chunk->m_oldPtr);
			// The parts array has no object of its own: its chunk data stands for it.
			void* partsId = chunk->m_oldPtr;
			meshData->m_meshPartsPtr = static_cast<btMeshPartData*>(serializer->getUniquePointer(partsId));
			for (int p = 0; p < partCount; ++p)
			{
				const unsigned char* vertexBase = 0;
				const unsigned char* indexBase = 0;
				int numVertices = 0, vertexStride = 0, indexStride = 0, numTriangles = 0;
				PHY_ScalarType vertexType = PHY_FLOAT, indexType = PHY_INTEGER;
				getLockedReadOnlyVertexIndexBase(&vertexBase, numVertices, vertexType, vertexStride, &indexBase,
				                                 indexStride, numTriangles, indexType, p);
				parts[p].m_numTriangles = numTriangles;
				parts[p].m_numVertices = numVertices;
				writePartIndices(parts[p], indexBase, indexStride, numTriangles, indexType, serializer);
				writePartVertices(parts[p], vertexBase, vertexStride, numVertices, vertexType, serializer);
				unLockReadOnlyVertexBase(p);
			}
			serializer->finalizeChunk(chunk, "btMeshPartData", BT_ARRAY_CODE, partsId);
		}
	}
	return "btStridingMeshInterfaceData";
}

int btBvhTriangleMeshShape::calculateSerializeBufferSize() const { return int(sizeof(btTriangleMeshShapeData)); }

const char* btBvhTriangleMeshShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btTriangleMeshShapeData* shapeData = static_cast<btTriangleMeshShapeData*>(dataBuffer);
	btCollisionShape::serialize(&shapeData->m_collisionShapeData, serializer);
	m_meshInterface->serialize(&shapeData->m_meshInterface, serializer);
	shapeData->m_collisionMargin = float(m_collisionMargin);
	memset(shapeData->m_pad3, 0, sizeof(shapeData->m_pad3));
	shapeData->m_quantizedFloatBvh = 0;
	shapeData->m_quantizedDoubleBvh = 0;
	shapeData->m_triangleInfoMap = 0;
	const int flags = serializer->getSerializationFlags();
	// A BVH or map shared by several shapes is written once; later shapes point at the same id.
	if (m_bvh && !(flags & BT_SERIALIZE_NO_BVH))
	{
		void* id = serializer->findPointer(m_bvh) ? serializer->getUniquePointer(m_bvh) : 0;
		if (!id)
		{
			btChunk* chunk = serializer->allocate(size_t(m_bvh->calculateSerializeBufferSizeNew()), 1);
			if (chunk)
			{
				const char* structType = m_bvh->serialize(chunk->m_oldPtr, serializer);
				serializer->finalizeChunk(chunk, structType, BT_QUANTIZED_BVH_CODE, m_bvh);
				id = serializer->getUniquePointer(m_bvh);
			}
		}
#ifdef BT_USE_DOUBLE_PRECISION
		shapeData->m_quantizedDoubleBvh = static_cast<btQuantizedBvhDoubleData*>(id);
#else
		shapeData->m_quantizedFloatBvh = static_cast<btQuantizedBvhFloatData*>(id);
#endif
	}
	if (m_triangleInfoMap && !(flags & BT_SERIALIZE_NO_TRIANGLEINFOMAP))
	{
		void* id = serializer->findPointer(m_triangleInfoMap) ? serializer->getUniquePointer(m_triangleInfoMap) : 0;
		if (!id)
		{
			btChunk* chunk = serializer->allocate(size_t(m_triangleInfoMap->calculateSerializeBufferSize()), 1);
			if (chunk)
			{
				const char* structType = m_triangleInfoMap->serialize(chunk->m_oldPtr, serializer);
				serializer->finalizeChunk(chunk, structType, BT_TRIANLGE_INFO_MAP, m_triangleInfoMap);
				id = serializer->getUniquePointer(m_triangleInfoMap);
			}
		}
		shapeData->m_triangleInfoMap = static_cast<btTriangleInfoMapData*>(id);
	}
	return "btTriangleMeshShapeData";
}

void btBvhTriangleMeshShape::serializeSingleBvh(btSerializer* serializer) const
{
	if (!m_bvh) return;
	btChunk* chunk = serializer->allocate(size_t(m_bvh->calculateSerializeBufferSizeNew()), 1);
	if (!chunk) return;
	const char* structType = m_bvh->serialize(chunk->m_oldPtr, serializer);
	serializer->finalizeChunk(chunk, structType, BT_QUANTIZED_BVH_CODE, m_bvh);
}

void btBvhTriangleMeshShape::serializeSingleTriangleInfoMap(btSerializer* serializer) const
{
	if (!m_triangleInfoMap) return;
	btChunk* chunk = serializer->allocate(size_t(m_triangleInfoMap->calculateSerializeBufferSize()), 1);
	if (!chunk) return;
	const char* structType = m_triangleInfoMap->serialize(chunk->m_oldPtr, serializer);
	serializer->finalizeChunk(chunk, structType, BT_TRIANLGE_INFO_MAP, m_triangleInfoMap);
}

int btScaledBvhTriangleMeshShape::calculateSerializeBufferSize() const
{
	return int(sizeof(btScaledTriangleMeshShapeData));
}

const char* btScaledBvhTriangleMeshShape::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btScaledTriangleMeshShapeData* shapeData = static_cast<btScaledTriangleMeshShapeData*>(dataBuffer);
	// The child mesh is embedded (not a chunk of its own); the outer type says it is scaled.
	m_bvhTriMeshShape->serialize(&shapeData->m_trimeshShapeData, serializer);
	shapeData->m_trimeshShapeData.m_collisionShapeData.m_shapeType = SCALED_TRIANGLE_MESH_SHAPE_PROXYTYPE;
	m_localScaling.serializeFloat(shapeData->m_localScaling);
	return "btScaledTriangleMeshShapeData";
}
