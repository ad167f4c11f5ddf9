// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"

#include <cmath>

#include "LinearMath/btSideTable.h"
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

// A mesh's welding lookup: a hash grid over its vertices (cell size cellSize), built on the first
// welding addTriangle so that meshes that never weld pay nothing. Buckets hold chains through next.
// It lives in a side table keyed by the mesh (Bullet's class has no place for it), looked up once
// per welded vertex; the mesh's destructor drops it.
struct WeldGrid
{
	btAlignedObjectArray<int> bucketHeads;
	btAlignedObjectArray<int> next;
	btScalar cellSize = 0;
	int hashedCount = 0;

	unsigned bucket(long long cx, long long cy, long long cz) const
	{
		unsigned long long h = (unsigned long long)cx * 0x9E3779B97F4A7C15ull;
		h ^= (unsigned long long)cy * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
		h ^= (unsigned long long)cz * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
		h ^= h >> 29;
		return unsigned(h) & unsigned(bucketHeads.size() - 1);
	}
};

void forgetWeldGrid(const btTriangleMesh* mesh) { caliber::sideTable<WeldGrid>().release(mesh); }

// Vertex i of the mesh's only subpart, whichever layout it is stored in.
btVector3 subpartVertex(const btIndexedMesh& mesh, int i)
{
	const btScalar* v = reinterpret_cast<const btScalar*>(mesh.m_vertexBase + size_t(i) * size_t(mesh.m_vertexStride));
	return btVector3(v[0], v[1], v[2]);
}

void insertIntoWeldGrid(WeldGrid& grid, const btIndexedMesh& mesh, int vertexIndex)
{
	const btVector3 v = subpartVertex(mesh, vertexIndex);
	if (grid.next.size() <= vertexIndex) grid.next.resize(vertexIndex + 1, -1);
	if (!caliber::isFinite(v))
	{
		grid.next[vertexIndex] = -1;
		return;
	}
	const unsigned b =
	    grid.bucket(weldCell(v.x(), grid.cellSize), weldCell(v.y(), grid.cellSize), weldCell(v.z(), grid.cellSize));
	grid.next[vertexIndex] = grid.bucketHeads[b];
	grid.bucketHeads[b] = vertexIndex;
}

// Brings the grid up to date with the mesh's vertices, rebuilt when the cell size changes or the
// buckets run short.
void updateWeldGrid(WeldGrid& grid, const btIndexedMesh& mesh, btScalar cellSize)
{
	const int numVertices = mesh.m_numVertices;
	int buckets = grid.bucketHeads.size();
	const bool rebuild = cellSize != grid.cellSize || buckets < 2 * (numVertices + 1);
	if (rebuild)
	{
		buckets = 64;
		while (buckets < 4 * (numVertices + 1)) buckets *= 2;
		grid.bucketHeads.resize(0);
		grid.bucketHeads.resize(buckets, -1);
		grid.next.resize(0);
		grid.cellSize = cellSize;
		grid.hashedCount = 0;
	}
	// Doubling capacity keeps one-vertex-at-a-time growth linear overall.
	if (grid.next.capacity() < numVertices) grid.next.reserve(2 * numVertices);
	if (grid.next.size() < numVertices) grid.next.resize(numVertices, -1);
	for (; grid.hashedCount < numVertices; ++grid.hashedCount) insertIntoWeldGrid(grid, mesh, grid.hashedCount);
}

// Points the subpart at the arrays, which may have moved on any append.
void pointSubpartAtArrays(btIndexedMesh& mesh, bool use4componentVertices, bool use32bitIndices,
                          const btAlignedObjectArray<btVector3>& vertices4,
                          const btAlignedObjectArray<btScalar>& vertices3,
                          const btAlignedObjectArray<unsigned int>& indices32,
                          const btAlignedObjectArray<unsigned short int>& indices16)
{
	if (use4componentVertices)
	{
		mesh.m_numVertices = vertices4.size();
		mesh.m_vertexBase = vertices4.size() ? reinterpret_cast<const unsigned char*>(&vertices4[0]) : 0;
	}
	else
	{
		mesh.m_numVertices = vertices3.size() / 3;
		mesh.m_vertexBase = vertices3.size() ? reinterpret_cast<const unsigned char*>(&vertices3[0]) : 0;
	}
	if (use32bitIndices)
		mesh.m_triangleIndexBase = indices32.size() ? reinterpret_cast<const unsigned char*>(&indices32[0]) : 0;
	else
		mesh.m_triangleIndexBase = indices16.size() ? reinterpret_cast<const unsigned char*>(&indices16[0]) : 0;
}
}  // namespace

#define CALIBER_SYNC_SUBPART()                                                                                 \
	pointSubpartAtArrays(m_indexedMeshes[0], m_use4componentVertices, m_use32bitIndices, m_4componentVertices, \
	                     m_3componentVertices, m_32bitIndices, m_16bitIndices)

btTriangleMesh::btTriangleMesh(bool use32bitIndices, bool use4componentVertices)
    : m_use32bitIndices(use32bitIndices), m_use4componentVertices(use4componentVertices), m_weldingThreshold(0)
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
      m_weldingThreshold(other.m_weldingThreshold)
{
	CALIBER_SYNC_SUBPART();
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
	// The welding grid is rebuilt on the next welding lookup.
	forgetWeldGrid(this);
	CALIBER_SYNC_SUBPART();
	return *this;
}

btTriangleMesh::~btTriangleMesh() { forgetWeldGrid(this); }

int btTriangleMesh::findOrAddVertex(const btVector3& vertex, bool removeDuplicateVertices)
{
	if (removeDuplicateVertices && caliber::isFinite(vertex))
	{
		const btScalar threshold =
		    (m_weldingThreshold > btScalar(0) && btIsFinite(m_weldingThreshold)) ? m_weldingThreshold : btScalar(0);
		const btIndexedMesh& mesh = m_indexedMeshes[0];
		WeldGrid& grid = caliber::sideTable<WeldGrid>().acquire(this);
		// With threshold 0 only exact copies match, and they share a cell of any size.
		updateWeldGrid(grid, mesh, threshold > btScalar(0) ? threshold : btScalar(1));
		const long long cx = weldCell(vertex.x(), grid.cellSize);
		const long long cy = weldCell(vertex.y(), grid.cellSize);
		const long long cz = weldCell(vertex.z(), grid.cellSize);
		const int reach = threshold > btScalar(0) ? 1 : 0;
		const btScalar threshold2 = threshold * threshold;
		int best = -1;
		for (int dx = -reach; dx <= reach; ++dx)
			for (int dy = -reach; dy <= reach; ++dy)
				for (int dz = -reach; dz <= reach; ++dz)
				{
					for (int i = grid.bucketHeads[grid.bucket(cx + dx, cy + dy, cz + dz)]; i >= 0; i = grid.next[i])
					{
						if ((best < 0 || i < best) && (subpartVertex(mesh, i) - vertex).length2() <= threshold2)
							best = i;
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
	CALIBER_SYNC_SUBPART();
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
	CALIBER_SYNC_SUBPART();
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

#undef CALIBER_SYNC_SUBPART
