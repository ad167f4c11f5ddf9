// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionShapes/btShapeHull.h"

#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btConvexHull.h"

namespace
{
// Unit directions of a geodesic sphere: the icosahedron's faces split into frequency^2 triangles each, the
// points pushed out onto the sphere (10 * frequency^2 + 2 directions, evenly spread, symmetric under x -> -x).
void buildGeodesicDirections(int frequency, btAlignedObjectArray<btVector3>& directions)
{
	const btScalar phi = (btScalar(1) + btSqrt(btScalar(5))) * btScalar(0.5);
	btVector3 corners[12];
	int count = 0;
	for (int a = -1; a <= 1; a += 2)
		for (int b = -1; b <= 1; b += 2)
		{
			corners[count++] = btVector3(0, btScalar(a), btScalar(b) * phi);
			corners[count++] = btVector3(btScalar(a), btScalar(b) * phi, 0);
			corners[count++] = btVector3(btScalar(b) * phi, 0, btScalar(a));
		}

	// Icosahedron edges have length 2 for this corner set; faces are the triples of mutually adjacent corners.
	const btScalar edge2 = btScalar(4), tolerance = btScalar(0.01);
	const auto adjacent = [&](int i, int j) { return btFabs(corners[i].distance2(corners[j]) - edge2) < tolerance; };
	directions.resize(0);
	for (int i = 0; i < 12; ++i)
		for (int j = i + 1; j < 12; ++j)
			for (int k = j + 1; k < 12; ++k)
			{
				if (!adjacent(i, j) || !adjacent(j, k) || !adjacent(i, k)) continue;
				for (int u = 0; u <= frequency; ++u)
					for (int v = 0; u + v <= frequency; ++v)
					{
						const int w = frequency - u - v;
						btVector3 p = (corners[i] * btScalar(u) + corners[j] * btScalar(v) + corners[k] * btScalar(w)) /
						              btScalar(frequency);
						p.normalize();
						bool duplicate = false;
						for (int d = 0; d < directions.size() && !duplicate; ++d)
							duplicate = directions[d].distance2(p) < btScalar(1e-6);
						if (!duplicate) directions.push_back(p);
					}
			}
}

struct SampleDirections
{
	btAlignedObjectArray<btVector3> low;   // 42 directions
	btAlignedObjectArray<btVector3> high;  // 162 directions
	SampleDirections()
	{
		buildGeodesicDirections(2, low);
		buildGeodesicDirections(4, high);
	}
};

const btAlignedObjectArray<btVector3>& sampleDirections(bool highres)
{
	// Built once, on first use (thread-safe function-local static).
	static const SampleDirections directions;
	return highres ? directions.high : directions.low;
}
}  // namespace

btShapeHull::btShapeHull(const btConvexShape* shape) : m_numIndices(0), m_shape(shape)
{
	btAssert(shape && "btShapeHull: null shape");
}

btShapeHull::~btShapeHull() {}

bool btShapeHull::buildHull(btScalar margin, int highres)
{
	(void)margin;
	m_vertices.resize(0);
	m_indices.resize(0);
	m_numIndices = 0;
	btAssert(m_shape && "btShapeHull::buildHull: null shape");
	if (!m_shape) return false;

	const btAlignedObjectArray<btVector3>& directions = sampleDirections(highres != 0);
	const int preferred = btMax(m_shape->getNumPreferredPenetrationDirections(), 0);
	btAlignedObjectArray<btVector3> points;
	points.reserve(directions.size() + preferred);
	for (int i = 0; i < directions.size(); ++i)
	{
		const btVector3 support = m_shape->localGetSupportingVertex(directions[i]);
		if (caliber::isFinite(support)) points.push_back(support);
	}
	for (int i = 0; i < preferred; ++i)
	{
		btVector3 direction(0, 0, 0);
		m_shape->getPreferredPenetrationDirection(i, direction);
		if (!caliber::isFinite(direction) || direction.length2() < SIMD_EPSILON) continue;
		const btVector3 support = m_shape->localGetSupportingVertex(direction.normalized());
		if (caliber::isFinite(support)) points.push_back(support);
	}
	if (points.size() < 4) return false;

	// No vertex limit: every sampled corner stays, so the hull is exactly the hull of the samples. A point,
	// segment or flat sample set has no hull (QE_FAIL) and leaves the mesh empty.
	HullDesc desc(QF_TRIANGLES, static_cast<unsigned int>(points.size()), &points[0]);
	desc.mMaxVertices = static_cast<unsigned int>(points.size());
	desc.mMaxFaces = 2 * desc.mMaxVertices;
	HullLibrary library;
	HullResult result;
	if (library.CreateConvexHull(desc, result) != QE_OK) return false;

	m_vertices.resize(result.m_OutputVertices.size());
	for (int i = 0; i < m_vertices.size(); ++i) m_vertices[i] = result.m_OutputVertices[i];
	m_indices.resize(result.m_Indices.size());
	for (int i = 0; i < m_indices.size(); ++i) m_indices[i] = result.m_Indices[i];
	m_numIndices = static_cast<unsigned int>(m_indices.size());
	library.ReleaseResult(result);
	return m_numIndices > 0;
}

int btShapeHull::numTriangles() const { return static_cast<int>(m_numIndices / 3); }

int btShapeHull::numVertices() const { return m_vertices.size(); }

int btShapeHull::numIndices() const { return static_cast<int>(m_numIndices); }
