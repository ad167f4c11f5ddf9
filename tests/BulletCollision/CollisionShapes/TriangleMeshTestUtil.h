// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_TRIANGLE_MESH_TEST_UTIL_H
#define CALIBER_TESTS_TRIANGLE_MESH_TEST_UTIL_H

// Helpers for the triangle mesh and BVH tests (TriangleMesh*Test.cpp, Bvh*Test.cpp): a mesh whose
// arrays the test owns (so brute-force references read the data without the code under test), a
// triangle collector, and independent reference geometry (triangle boxes, slab test, Moller-Trumbore).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"

namespace mesh_test
{
using shapes_core_test::Random;

typedef std::pair<int, int> TriangleKey;  // (partId, triangleIndex)
typedef std::set<TriangleKey> TriangleSet;

/// One subpart stored in the requested formats; vertex(i) reads back what the mesh interface sees.
struct TestPart
{
	PHY_ScalarType vertexType = PHY_FLOAT;
	PHY_ScalarType indexType = PHY_INTEGER;
	int components = 3;
	int numVertices = 0;
	int numTriangles = 0;
	std::vector<float> floats;
	std::vector<double> doubles;
	std::vector<unsigned int> indices32;
	std::vector<unsigned short> indices16;
	std::vector<unsigned char> indices8;

	btVector3 vertex(int i) const
	{
		const size_t at = size_t(i) * size_t(components);
		if (vertexType == PHY_FLOAT)
			return btVector3(btScalar(floats[at]), btScalar(floats[at + 1]), btScalar(floats[at + 2]));
		return btVector3(btScalar(doubles[at]), btScalar(doubles[at + 1]), btScalar(doubles[at + 2]));
	}
	void setVertex(int i, const btVector3& v)
	{
		const size_t at = size_t(i) * size_t(components);
		for (int k = 0; k < 3; ++k)
		{
			if (vertexType == PHY_FLOAT)
				floats[at + k] = float(v[k]);
			else
				doubles[at + k] = double(v[k]);
		}
	}
	unsigned index(int triangle, int k) const
	{
		const size_t at = size_t(triangle) * 3 + size_t(k);
		if (indexType == PHY_INTEGER) return indices32[at];
		if (indexType == PHY_SHORT) return indices16[at];
		return indices8[at];
	}
};

/// A btTriangleIndexVertexArray over parts the test owns.
class TestMesh
{
public:
	/// Appends a part with the given formats (vertices and 3 indices per triangle).
	int addPart(const std::vector<btVector3>& vertices, const std::vector<int>& indices,
	            PHY_ScalarType vertexType = PHY_FLOAT, int components = 3, PHY_ScalarType indexType = PHY_INTEGER)
	{
		m_parts.emplace_back(new TestPart());
		TestPart& p = *m_parts.back();
		p.vertexType = vertexType;
		p.indexType = indexType;
		p.components = components;
		p.numVertices = int(vertices.size());
		p.numTriangles = int(indices.size() / 3);
		for (const btVector3& v : vertices)
			for (int k = 0; k < components; ++k)
			{
				const double value = k < 3 ? double(v[k]) : 0.0;
				if (vertexType == PHY_FLOAT)
					p.floats.push_back(float(value));
				else
					p.doubles.push_back(value);
			}
		for (int i : indices)
		{
			p.indices32.push_back(unsigned(i));
			p.indices16.push_back((unsigned short)i);
			p.indices8.push_back((unsigned char)i);
		}
		btIndexedMesh mesh;
		mesh.m_numTriangles = p.numTriangles;
		mesh.m_numVertices = p.numVertices;
		mesh.m_vertexType = vertexType;
		const int scalarSize = vertexType == PHY_FLOAT ? int(sizeof(float)) : int(sizeof(double));
		mesh.m_vertexStride = components * scalarSize;
		mesh.m_vertexBase = vertexType == PHY_FLOAT ? reinterpret_cast<const unsigned char*>(p.floats.data())
		                                            : reinterpret_cast<const unsigned char*>(p.doubles.data());
		if (indexType == PHY_INTEGER)
		{
			mesh.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(p.indices32.data());
			mesh.m_triangleIndexStride = 3 * int(sizeof(unsigned int));
		}
		else if (indexType == PHY_SHORT)
		{
			mesh.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(p.indices16.data());
			mesh.m_triangleIndexStride = 3 * int(sizeof(unsigned short));
		}
		else
		{
			mesh.m_triangleIndexBase = p.indices8.data();
			mesh.m_triangleIndexStride = 3;
		}
		m_array.addIndexedMesh(mesh, indexType);
		return int(m_parts.size()) - 1;
	}

	btTriangleIndexVertexArray& array() { return m_array; }
	int numParts() const { return int(m_parts.size()); }
	TestPart& part(int i) { return *m_parts[size_t(i)]; }
	const TestPart& part(int i) const { return *m_parts[size_t(i)]; }

	/// Triangle t of part p as the mesh stores it, times scaling (the reference for every query).
	void triangle(int p, int t, const btVector3& scaling, btVector3* out) const
	{
		for (int k = 0; k < 3; ++k) out[k] = part(p).vertex(int(part(p).index(t, k))) * scaling;
	}

	std::vector<TriangleKey> allTriangles() const
	{
		std::vector<TriangleKey> keys;
		for (int p = 0; p < numParts(); ++p)
			for (int t = 0; t < part(p).numTriangles; ++t) keys.push_back(TriangleKey(p, t));
		return keys;
	}

private:
	std::vector<std::unique_ptr<TestPart>> m_parts;
	btTriangleIndexVertexArray m_array;
};

/// Random triangles: centres in [-extent, extent]^3, vertices within size of the centre; every 10th is
/// degenerate (a point or a segment) so that zero-area triangles are always part of the data.
inline void randomSoup(Random& rng, int numTriangles, btScalar extent, btScalar size, std::vector<btVector3>& vertices,
                       std::vector<int>& indices)
{
	for (int t = 0; t < numTriangles; ++t)
	{
		const btVector3 centre = rng.vector(extent);
		const int base = int(vertices.size());
		btVector3 a = centre + rng.vector(size), b = centre + rng.vector(size), c = centre + rng.vector(size);
		if (t % 10 == 3) b = c = a;                        // a point
		if (t % 10 == 7) c = a + btScalar(0.5) * (b - a);  // a segment
		vertices.push_back(a);
		vertices.push_back(b);
		vertices.push_back(c);
		indices.push_back(base);
		indices.push_back(base + 1);
		indices.push_back(base + 2);
	}
}

/// An nx by ny grid of quads (two triangles each) over [0, nx] x [0, ny], height z = f(x, y).
template <class Height>
void heightGrid(int nx, int ny, Height height, std::vector<btVector3>& vertices, std::vector<int>& indices)
{
	const int base = int(vertices.size());
	for (int j = 0; j <= ny; ++j)
		for (int i = 0; i <= nx; ++i)
			vertices.push_back(btVector3(btScalar(i), btScalar(j), height(btScalar(i), btScalar(j))));
	for (int j = 0; j < ny; ++j)
		for (int i = 0; i < nx; ++i)
		{
			const int v00 = base + j * (nx + 1) + i, v10 = v00 + 1, v01 = v00 + nx + 1, v11 = v01 + 1;
			const int quad[6] = {v00, v10, v11, v00, v11, v01};
			indices.insert(indices.end(), quad, quad + 6);
		}
}

/// Collects the triangles a query reports and checks that none is reported twice.
class Collector : public btTriangleCallback
{
public:
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		const TriangleKey key(partId, triangleIndex);
		if (!keys.insert(key).second) ++duplicates;
		for (int k = 0; k < 3; ++k)
		{
			vertices.push_back(triangle[k]);
			if (!(std::isfinite(double(triangle[k].x())) && std::isfinite(double(triangle[k].y())) &&
			      std::isfinite(double(triangle[k].z()))))
				++nonFinite;
		}
		order.push_back(key);
	}
	TriangleSet keys;
	std::vector<TriangleKey> order;
	std::vector<btVector3> vertices;
	int duplicates = 0;
	int nonFinite = 0;
};

/// Same for btInternalTriangleIndexCallback.
class IndexCollector : public btInternalTriangleIndexCallback
{
public:
	void internalProcessTriangleIndex(btVector3* triangle, int partId, int triangleIndex) override
	{
		order.push_back(TriangleKey(partId, triangleIndex));
		for (int k = 0; k < 3; ++k) vertices.push_back(triangle[k]);
	}
	std::vector<TriangleKey> order;
	std::vector<btVector3> vertices;
};

inline void triangleBox(const btVector3* t, btVector3& mn, btVector3& mx)
{
	mn = t[0];
	mx = t[0];
	for (int k = 1; k < 3; ++k)
		for (int a = 0; a < 3; ++a)
		{
			if (t[k][a] < mn[a]) mn[a] = t[k][a];
			if (t[k][a] > mx[a]) mx[a] = t[k][a];
		}
}

/// Boxes overlap or touch (the inclusive test the BVH uses), each grown by grow on every side.
inline bool boxesOverlap(const btVector3& aMin, const btVector3& aMax, const btVector3& bMin, const btVector3& bMax,
                         const btVector3& grow = btVector3(0, 0, 0))
{
	for (int a = 0; a < 3; ++a)
		if (aMin[a] - grow[a] > bMax[a] || aMax[a] + grow[a] < bMin[a]) return false;
	return true;
}

/// Whether the segment p0 -> p1 touches the box [mn, mx] (clipping in double precision).
inline bool segmentTouchesBox(const btVector3& p0, const btVector3& p1, const btVector3& mn, const btVector3& mx)
{
	double lo = 0, hi = 1;
	for (int a = 0; a < 3; ++a)
	{
		const double o = double(p0[a]), d = double(p1[a]) - double(p0[a]);
		const double bmin = double(mn[a]), bmax = double(mx[a]);
		if (d == 0)
		{
			if (o < bmin || o > bmax) return false;
			continue;
		}
		double t0 = (bmin - o) / d, t1 = (bmax - o) / d;
		if (t0 > t1) std::swap(t0, t1);
		lo = std::max(lo, t0);
		hi = std::min(hi, t1);
		if (lo > hi) return false;
	}
	return true;
}

/// Moller-Trumbore segment p0 -> p1 against a triangle, in double precision, no tolerance.
inline bool segmentHitsTriangle(const btVector3& p0, const btVector3& p1, const btVector3* tri)
{
	double o[3], d[3], e1[3], e2[3], s[3];
	for (int a = 0; a < 3; ++a)
	{
		o[a] = double(p0[a]);
		d[a] = double(p1[a]) - double(p0[a]);
		e1[a] = double(tri[1][a]) - double(tri[0][a]);
		e2[a] = double(tri[2][a]) - double(tri[0][a]);
		s[a] = o[a] - double(tri[0][a]);
	}
	auto cross = [](const double* x, const double* y, double* out)
	{
		out[0] = x[1] * y[2] - x[2] * y[1];
		out[1] = x[2] * y[0] - x[0] * y[2];
		out[2] = x[0] * y[1] - x[1] * y[0];
	};
	auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
	double pv[3], qv[3];
	cross(d, e2, pv);
	const double det = dot(e1, pv);
	if (std::fabs(det) < 1e-300) return false;  // parallel or degenerate triangle
	const double u = dot(s, pv) / det;
	if (u < 0 || u > 1) return false;
	cross(s, e1, qv);
	const double v = dot(d, qv) / det;
	if (v < 0 || u + v > 1) return false;
	const double t = dot(e2, qv) / det;
	return t >= 0 && t <= 1;
}

inline std::string describe(const TriangleSet& s)
{
	std::string out;
	int n = 0;
	for (const TriangleKey& k : s)
	{
		if (n++ == 8)
		{
			out += " ...";
			break;
		}
		out += " (" + std::to_string(k.first) + "," + std::to_string(k.second) + ")";
	}
	return out;
}

/// The elements of a not in b.
inline TriangleSet minus(const TriangleSet& a, const TriangleSet& b)
{
	TriangleSet out;
	for (const TriangleKey& k : a)
		if (!b.count(k)) out.insert(k);
	return out;
}

}  // namespace mesh_test

#endif  // CALIBER_TESTS_TRIANGLE_MESH_TEST_UTIL_H
