// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"

#include <cmath>

#include "btShapeGuards.h"

namespace
{
// Cell coordinates are clamped so that huge (finite) coordinates stay representable.
long long weldCell(btScalar value, btScalar cellSize)
{
	double c = std::floor(double(value) / double(cellSize));
	const double limit = 1099511627776.0;  // 2^40
	if (c > limit) c = limit;
	if (c < -limit) c = -limit;
	return (long long)c;
}
}  // namespace

btTriangleMesh::btTriangleMesh(bool use32bitIndices, bool use4componentVertices)
    : m_use32bitIndices(use32bitIndices),
      m_use4componentVertices(use4componentVertices),
      m_weldCellSize(0),
      m_weldHashedCount(0),
      m_weldingThreshold(0)
{
	btIndexedMesh mesh;
	mesh.m_indexType = use32bitIndices ? PHY_INTEGER : PHY_SHORT;
	mesh.m_triangleIndexStride = use32bitIndices ? int(3 * sizeof(unsigned int)) : int(3 * sizeof(unsigned short));
	mesh.m_vertexStride = use4componentVertices ? int(sizeof(btVector3)) : int(3 * sizeof(btScalar));
	m_indexedMeshes.push_back(mesh);
}

btTriangleMesh::btTriangleMesh(const btTriangleMesh& other)
    : btTriangleIndexVertexArray(other),
      m_4componentVertices(other.m_4componentVertices),
      m_3componentVertices(other.m_3componentVertices),
      m_32bitIndices(other.m_32bitIndices),
      m_16bitIndices(other.m_16bitIndices),
      m_use32bitIndices(other.m_use32bitIndices),
      m_use4componentVertices(other.m_use4componentVertices),
      m_weldCellSize(0),
      m_weldHashedCount(0),
      m_weldingThreshold(other.m_weldingThreshold)
{
	syncIndexedMesh();
}

btTriangleMesh& btTriangleMesh::operator=(const btTriangleMesh& other)
{
	if (this == &other) return *this;
	btTriangleIndexVertexArray::operator=(other);
	m_4componentVertices = other.m_4componentVertices;
	m_3componentVertices = other.m_3componentVertices;
	m_32bitIndices = other.m_32bitIndices;
	m_16bitIndices = other.m_16bitIndices;
	m_use32bitIndices = other.m_use32bitIndices;
	m_use4componentVertices = other.m_use4componentVertices;
	m_weldingThreshold = other.m_weldingThreshold;
	// The welding hash is rebuilt on the next welding lookup.
	m_weldBucketHeads.resize(0);
	m_weldNext.resize(0);
	m_weldCellSize = 0;
	m_weldHashedCount = 0;
	syncIndexedMesh();
	return *this;
}

void btTriangleMesh::syncIndexedMesh()
{
	// Arrays may reallocate on every append, so the subpart's pointers are refreshed each time.
	btIndexedMesh& mesh = m_indexedMeshes[0];
	if (m_use4componentVertices)
	{
		mesh.m_numVertices = m_4componentVertices.size();
		mesh.m_vertexBase =
		    m_4componentVertices.size() ? reinterpret_cast<const unsigned char*>(&m_4componentVertices[0]) : 0;
	}
	else
	{
		mesh.m_numVertices = m_3componentVertices.size() / 3;
		mesh.m_vertexBase =
		    m_3componentVertices.size() ? reinterpret_cast<const unsigned char*>(&m_3componentVertices[0]) : 0;
	}
	if (m_use32bitIndices)
		mesh.m_triangleIndexBase =
		    m_32bitIndices.size() ? reinterpret_cast<const unsigned char*>(&m_32bitIndices[0]) : 0;
	else
		mesh.m_triangleIndexBase =
		    m_16bitIndices.size() ? reinterpret_cast<const unsigned char*>(&m_16bitIndices[0]) : 0;
}

btVector3 btTriangleMesh::storedVertex(int i) const
{
	if (m_use4componentVertices) return m_4componentVertices[i];
	return btVector3(m_3componentVertices[3 * i], m_3componentVertices[3 * i + 1], m_3componentVertices[3 * i + 2]);
}

unsigned btTriangleMesh::weldBucket(long long cx, long long cy, long long cz) const
{
	unsigned long long h = (unsigned long long)cx * 0x9E3779B97F4A7C15ull;
	h ^= (unsigned long long)cy * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
	h ^= (unsigned long long)cz * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
	h ^= h >> 29;
	return unsigned(h) & unsigned(m_weldBucketHeads.size() - 1);
}

void btTriangleMesh::insertIntoWeldHash(int vertexIndex)
{
	const btVector3 v = storedVertex(vertexIndex);
	if (m_weldNext.size() <= vertexIndex) m_weldNext.resize(vertexIndex + 1, -1);
	if (!caliber::isFinite(v))
	{
		m_weldNext[vertexIndex] = -1;
		return;
	}
	const unsigned b =
	    weldBucket(weldCell(v.x(), m_weldCellSize), weldCell(v.y(), m_weldCellSize), weldCell(v.z(), m_weldCellSize));
	m_weldNext[vertexIndex] = m_weldBucketHeads[b];
	m_weldBucketHeads[b] = vertexIndex;
}

void btTriangleMesh::updateWeldHash(btScalar cellSize)
{
	const int numVertices = m_indexedMeshes[0].m_numVertices;
	int buckets = m_weldBucketHeads.size();
	const bool rebuild = cellSize != m_weldCellSize || buckets < 2 * (numVertices + 1);
	if (rebuild)
	{
		buckets = 64;
		while (buckets < 4 * (numVertices + 1)) buckets *= 2;
		m_weldBucketHeads.resize(0);
		m_weldBucketHeads.resize(buckets, -1);
		m_weldNext.resize(0);
		m_weldCellSize = cellSize;
		m_weldHashedCount = 0;
	}
	// Doubling capacity keeps one-vertex-at-a-time growth linear overall.
	if (m_weldNext.capacity() < numVertices) m_weldNext.reserve(2 * numVertices);
	if (m_weldNext.size() < numVertices) m_weldNext.resize(numVertices, -1);
	for (; m_weldHashedCount < numVertices; ++m_weldHashedCount) insertIntoWeldHash(m_weldHashedCount);
}

int btTriangleMesh::findOrAddVertex(const btVector3& vertex, bool removeDuplicateVertices)
{
	if (removeDuplicateVertices && caliber::isFinite(vertex))
	{
		const btScalar threshold =
		    (m_weldingThreshold > btScalar(0) && btIsFinite(m_weldingThreshold)) ? m_weldingThreshold : btScalar(0);
		// With threshold 0 only exact copies match, and they share a cell of any size.
		updateWeldHash(threshold > btScalar(0) ? threshold : btScalar(1));
		const long long cx = weldCell(vertex.x(), m_weldCellSize);
		const long long cy = weldCell(vertex.y(), m_weldCellSize);
		const long long cz = weldCell(vertex.z(), m_weldCellSize);
		const int reach = threshold > btScalar(0) ? 1 : 0;
		const btScalar threshold2 = threshold * threshold;
		int best = -1;
		for (int dx = -reach; dx <= reach; ++dx)
			for (int dy = -reach; dy <= reach; ++dy)
				for (int dz = -reach; dz <= reach; ++dz)
				{
					for (int i = m_weldBucketHeads[weldBucket(cx + dx, cy + dy, cz + dz)]; i >= 0; i = m_weldNext[i])
					{
						if ((best < 0 || i < best) && (storedVertex(i) - vertex).length2() <= threshold2) best = i;
					}
				}
		if (best >= 0) return best;
	}
	if (m_use4componentVertices)
	{
		m_4componentVertices.push_back(vertex);
		m_4componentVertices[m_4componentVertices.size() - 1][3] = btScalar(0);
	}
	else
	{
		m_3componentVertices.push_back(vertex.x());
		m_3componentVertices.push_back(vertex.y());
		m_3componentVertices.push_back(vertex.z());
	}
	syncIndexedMesh();
	return m_indexedMeshes[0].m_numVertices - 1;
}

void btTriangleMesh::addIndex(int index)
{
	if (m_use32bitIndices)
	{
		btAssert(index >= 0 && "btTriangleMesh::addIndex: negative index");
		m_32bitIndices.push_back(unsigned(index));  // a negative index becomes huge: out of range
	}
	else
	{
		const bool fits = index >= 0 && index <= 0xFFFF;
		btAssert(fits && "btTriangleMesh::addIndex: index does not fit 16 bits");
		m_16bitIndices.push_back(fits ? (unsigned short)index : (unsigned short)0xFFFF);
	}
	syncIndexedMesh();
}

void btTriangleMesh::addTriangleIndices(int index1, int index2, int index3)
{
	if (!m_use32bitIndices)
	{
		const bool fits =
		    index1 >= 0 && index1 <= 0xFFFF && index2 >= 0 && index2 <= 0xFFFF && index3 >= 0 && index3 <= 0xFFFF;
		btAssert(fits && "btTriangleMesh: vertex index does not fit 16-bit indices");
		if (!fits) return;
	}
	addIndex(index1);
	addIndex(index2);
	addIndex(index3);
	m_indexedMeshes[0].m_numTriangles++;
}

void btTriangleMesh::addTriangle(const btVector3& vertex0, const btVector3& vertex1, const btVector3& vertex2,
                                 bool removeDuplicateVertices)
{
	const int i0 = findOrAddVertex(vertex0, removeDuplicateVertices);
	const int i1 = findOrAddVertex(vertex1, removeDuplicateVertices);
	const int i2 = findOrAddVertex(vertex2, removeDuplicateVertices);
	addTriangleIndices(i0, i1, i2);
}

int btTriangleMesh::getNumTriangles() const { return m_indexedMeshes[0].m_numTriangles; }

void btTriangleMesh::preallocateVertices(int numverts)
{
	if (numverts <= 0) return;
	if (m_use4componentVertices)
		m_4componentVertices.reserve(m_4componentVertices.size() + numverts);
	else
		m_3componentVertices.reserve(m_3componentVertices.size() + 3 * numverts);
}

void btTriangleMesh::preallocateIndices(int numindices)
{
	if (numindices <= 0) return;
	if (m_use32bitIndices)
		m_32bitIndices.reserve(m_32bitIndices.size() + numindices);
	else
		m_16bitIndices.reserve(m_16bitIndices.size() + numindices);
}
