// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btStridingMeshInterface.h"

#include "btMeshTriangleAccess.h"

namespace caliber
{
static int scalarTypeSize(PHY_ScalarType type)
{
	switch (type)
	{
		case PHY_FLOAT:
			return int(sizeof(float));
		case PHY_DOUBLE:
			return int(sizeof(double));
		case PHY_INTEGER:
			return int(sizeof(unsigned int));
		case PHY_SHORT:
			return int(sizeof(unsigned short));
		case PHY_UCHAR:
			return 1;
		default:
			return 0;
	}
}

bool ReadOnlyMeshPart::acquire(const btStridingMeshInterface* mesh, int part)
{
	release();
	if (!mesh) return false;
	m_vertexBase = 0;
	m_indexBase = 0;
	m_numVertices = 0;
	m_numFaces = 0;
	m_vertexStride = 0;
	m_indexStride = 0;
	m_vertexType = PHY_FLOAT;
	m_indexType = PHY_INTEGER;
	mesh->getLockedReadOnlyVertexIndexBase(&m_vertexBase, m_numVertices, m_vertexType, m_vertexStride, &m_indexBase,
	                                       m_indexStride, m_numFaces, m_indexType, part);
	m_mesh = mesh;
	m_part = part;
	if (m_numFaces <= 0)
	{
		btAssert(m_numFaces >= 0 && "mesh part with a negative triangle count");
		m_usable = false;
		return false;
	}
	const bool vertexTypeOk = m_vertexType == PHY_FLOAT || m_vertexType == PHY_DOUBLE;
	const bool indexTypeOk = m_indexType == PHY_INTEGER || m_indexType == PHY_SHORT || m_indexType == PHY_UCHAR;
	m_usable = vertexTypeOk && indexTypeOk && m_vertexBase != 0 && m_indexBase != 0 && m_numVertices >= 0 &&
	           m_vertexStride >= 3 * scalarTypeSize(m_vertexType) && m_indexStride >= 3 * scalarTypeSize(m_indexType);
	btAssert(m_usable && "mesh part: unsupported type, null base or stride too small");
	return m_usable;
}
}  // namespace caliber

namespace
{
class AabbAccumulator
{
public:
	AabbAccumulator() : m_min(0, 0, 0), m_max(0, 0, 0), m_any(false) {}
	void operator()(const btVector3* triangle, int, int)
	{
		if (!m_any)
		{
			m_min = m_max = triangle[0];
			m_any = true;
		}
		for (int k = 0; k < 3; ++k)
		{
			m_min.setMin(triangle[k]);
			m_max.setMax(triangle[k]);
		}
	}
	btVector3 m_min, m_max;
	bool m_any;
};
}  // namespace

btStridingMeshInterface::~btStridingMeshInterface() {}

void btStridingMeshInterface::InternalProcessAllTriangles(btInternalTriangleIndexCallback* callback,
                                                          const btVector3& aabbMin, const btVector3& aabbMax) const
{
	(void)aabbMin;
	(void)aabbMax;
	btAssert(callback != 0);
	if (!callback) return;
	caliber::forEachMeshTriangle(*this,
	                             [callback](const btVector3* triangle, int partId, int triangleIndex)
	                             {
		                             // The callback receives a copy it may modify.
		                             btVector3 copy[3] = {triangle[0], triangle[1], triangle[2]};
		                             callback->internalProcessTriangleIndex(copy, partId, triangleIndex);
	                             });
}

void btStridingMeshInterface::calculateAabbBruteForce(btVector3& aabbMin, btVector3& aabbMax)
{
	AabbAccumulator acc;
	caliber::forEachMeshTriangle(*this, acc);
	aabbMin = acc.m_min;
	aabbMax = acc.m_max;
}

void btStridingMeshInterface::setScaling(const btVector3& scaling)
{
	btAssert(caliber::isFinite(scaling) && "btStridingMeshInterface::setScaling: non-finite scaling");
	if (caliber::isFinite(scaling)) m_scaling = scaling;
}
