// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"

#include "btShapeGuards.h"

btTriangleIndexVertexArray::~btTriangleIndexVertexArray() {}

btTriangleIndexVertexArray::btTriangleIndexVertexArray(int numTriangles, int* triangleIndexBase,
                                                       int triangleIndexStride, int numVertices, btScalar* vertexBase,
                                                       int vertexStride)
    : m_hasAabb(0), m_aabbMin(0, 0, 0), m_aabbMax(0, 0, 0)
{
	btIndexedMesh mesh;
	mesh.m_numTriangles = numTriangles;
	mesh.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(triangleIndexBase);
	mesh.m_triangleIndexStride = triangleIndexStride;
	mesh.m_numVertices = numVertices;
	mesh.m_vertexBase = reinterpret_cast<const unsigned char*>(vertexBase);
	mesh.m_vertexStride = vertexStride;
	addIndexedMesh(mesh, PHY_INTEGER);
}

void btTriangleIndexVertexArray::getLockedVertexIndexBase(unsigned char** vertexbase, int& numverts,
                                                          PHY_ScalarType& type, int& vertexStride,
                                                          unsigned char** indexbase, int& indexstride, int& numfaces,
                                                          PHY_ScalarType& indicestype, int subpart)
{
	const unsigned char* vertices = 0;
	const unsigned char* indices = 0;
	getLockedReadOnlyVertexIndexBase(&vertices, numverts, type, vertexStride, &indices, indexstride, numfaces,
	                                 indicestype, subpart);
	// The arrays belong to the user, who handed them over as writable data.
	*vertexbase = const_cast<unsigned char*>(vertices);
	*indexbase = const_cast<unsigned char*>(indices);
}

void btTriangleIndexVertexArray::getLockedReadOnlyVertexIndexBase(const unsigned char** vertexbase, int& numverts,
                                                                  PHY_ScalarType& type, int& vertexStride,
                                                                  const unsigned char** indexbase, int& indexstride,
                                                                  int& numfaces, PHY_ScalarType& indicestype,
                                                                  int subpart) const
{
	btAssert(subpart >= 0 && subpart < getNumSubParts());
	if (subpart < 0 || subpart >= getNumSubParts())
	{
		const btIndexedMesh empty;
		*vertexbase = 0;
		numverts = 0;
		type = empty.m_vertexType;
		vertexStride = 0;
		*indexbase = 0;
		indexstride = 0;
		numfaces = 0;
		indicestype = empty.m_indexType;
		return;
	}
	const btIndexedMesh& mesh = m_indexedMeshes[subpart];
	*vertexbase = mesh.m_vertexBase;
	numverts = mesh.m_numVertices;
	type = mesh.m_vertexType;
	vertexStride = mesh.m_vertexStride;
	*indexbase = mesh.m_triangleIndexBase;
	indexstride = mesh.m_triangleIndexStride;
	numfaces = mesh.m_numTriangles;
	indicestype = mesh.m_indexType;
}

bool btTriangleIndexVertexArray::hasPremadeAabb() const { return m_hasAabb == 1; }

void btTriangleIndexVertexArray::setPremadeAabb(const btVector3& aabbMin, const btVector3& aabbMax) const
{
	const bool valid = caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax) && aabbMin.x() <= aabbMax.x() &&
	                   aabbMin.y() <= aabbMax.y() && aabbMin.z() <= aabbMax.z();
	btAssert(valid && "setPremadeAabb: non-finite or inverted box");
	if (!valid) return;
	m_aabbMin = aabbMin;
	m_aabbMax = aabbMax;
	m_hasAabb = 1;
}

void btTriangleIndexVertexArray::getPremadeAabb(btVector3* aabbMin, btVector3* aabbMax) const
{
	if (aabbMin) *aabbMin = m_aabbMin;
	if (aabbMax) *aabbMax = m_aabbMax;
}
