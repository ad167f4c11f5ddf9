// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btConvexHullComputer.h"

#include "ConvexHullInternal.h"

#include <math.h>
#include <string.h>

#include <algorithm>

static_assert(sizeof(btConvexHullComputer::Edge) == 3 * sizeof(int), "Edge must stay three ints, as in Bullet");

namespace caliber
{
namespace hull
{
namespace
{
struct Vec
{
	double x, y, z;
};

inline Vec operator+(const Vec& a, const Vec& b) { return Vec{a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec operator-(const Vec& a, const Vec& b) { return Vec{a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec operator*(const Vec& a, double s) { return Vec{a.x * s, a.y * s, a.z * s}; }
inline double dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec cross(const Vec& a, const Vec& b)
{
	return Vec{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Vec pointAt(const btAlignedObjectArray<double>& xyz, int i)
{
	return Vec{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
}

/// Bullet's half-edge arrays, built from a topology's faces; the Edge fields are set from these.
struct HalfEdges
{
	btAlignedObjectArray<int> target;         // output vertex index
	btAlignedObjectArray<int> nextOffset;     // to the next edge around the source vertex
	btAlignedObjectArray<int> reverseOffset;  // +1 or -1: reverse edges sit in adjacent slots
	btAlignedObjectArray<int> faceEdge;       // one edge per face
};

// Newell's normal (twice the vector area) of face f: well defined for any planar polygon, even one
// with nearly collinear corners.
Vec faceAreaNormal(const btAlignedObjectArray<double>& xyz, const HullTopology& hull, int f, Vec* centroid)
{
	const int first = hull.faceStart[f], count = hull.faceStart[f + 1] - first;
	Vec normal{0, 0, 0}, sum{0, 0, 0};
	for (int k = 0; k < count; ++k)
	{
		const Vec a = pointAt(xyz, hull.faceVertices[first + k]);
		const Vec b = pointAt(xyz, hull.faceVertices[first + (k + 1) % count]);
		normal = normal + cross(a, b);
		sum = sum + a;
	}
	if (centroid) *centroid = sum * (1.0 / count);
	return normal;
}

// Builds the half-edges of a segment (dimension 1) or of a polygon-faced surface (dimensions 2, 3).
// vertexOfPoint maps point indices to output vertex indices. False if the faces do not pair up into
// a closed surface (impossible for a topology from computeHullTopology).
bool buildHalfEdges(const HullTopology& hull, const btAlignedObjectArray<int>& vertexOfPoint, HalfEdges& out)
{
	if (hull.dimension == 1)
	{
		// One edge each way; each is the only edge of its source vertex, so its own next.
		out.target.push_back(vertexOfPoint[hull.vertices[1]]);
		out.target.push_back(vertexOfPoint[hull.vertices[0]]);
		out.reverseOffset.push_back(1);
		out.reverseOffset.push_back(-1);
		out.nextOffset.push_back(0);
		out.nextOffset.push_back(0);
		return true;
	}
	if (hull.dimension < 2) return true;

	// Half-edge h runs from faceVertices[h] to the next corner of its face. Sorting by the unordered
	// pair puts each edge next to its reverse; the sorted position becomes its output slot.
	const int count = hull.faceVertices.size();
	btAlignedObjectArray<int> successor;  // half-edge index of the next edge in the same face
	successor.resize(count);
	for (int f = 0; f < hull.faceCount(); ++f)
	{
		const int first = hull.faceStart[f], last = hull.faceStart[f + 1];
		for (int h = first; h < last; ++h) successor[h] = h + 1 < last ? h + 1 : first;
	}
	struct Key
	{
		int low, high, source, halfEdge;
	};
	if (count % 2 != 0) return false;
	// Bucket by the lower vertex (counting sort), then sort each small bucket.
	const int vertexCount = hull.vertices.size();
	btAlignedObjectArray<int> bucketStart;
	bucketStart.resize(vertexCount + 1, 0);
	for (int h = 0; h < count; ++h)
	{
		const int s = vertexOfPoint[hull.faceVertices[h]], t = vertexOfPoint[hull.faceVertices[successor[h]]];
		if (s < 0 || t < 0) return false;
		++bucketStart[std::min(s, t) + 1];
	}
	for (int v = 0; v < vertexCount; ++v) bucketStart[v + 1] += bucketStart[v];
	btAlignedObjectArray<int> fill;
	fill = bucketStart;
	btAlignedObjectArray<Key> keys;
	keys.resize(count);
	for (int h = 0; h < count; ++h)
	{
		const int s = vertexOfPoint[hull.faceVertices[h]], t = vertexOfPoint[hull.faceVertices[successor[h]]];
		keys[fill[std::min(s, t)]++] = Key{std::min(s, t), std::max(s, t), s, h};
	}
	for (int v = 0; v < vertexCount; ++v)
	{
		std::sort(&keys[0] + bucketStart[v], &keys[0] + bucketStart[v + 1],
		          [](const Key& a, const Key& b) { return a.high != b.high ? a.high < b.high : a.source < b.source; });
	}
	btAlignedObjectArray<int> slot;
	slot.resize(count);
	out.target.resize(count);
	out.reverseOffset.resize(count);
	out.nextOffset.resize(count, 0);
	for (int k = 0; k < count; k += 2)
	{
		const Key& a = keys[k];
		const Key& b = keys[k + 1];
		if (a.low != b.low || a.high != b.high || a.source == b.source || a.low == a.high) return false;
		if (k + 2 < count && keys[k + 2].low == a.low && keys[k + 2].high == a.high) return false;
		slot[a.halfEdge] = k;
		slot[b.halfEdge] = k + 1;
		out.target[k] = a.source == a.low ? a.high : a.low;
		out.target[k + 1] = b.source == b.low ? b.high : b.low;
		out.reverseOffset[k] = 1;
		out.reverseOffset[k + 1] = -1;
	}
	// In a face, edge e = (s -> t) is followed by n = (t -> u). Around t, n comes right after the
	// reverse of e, so that getNextEdgeOfFace(e) = getNextEdgeOfVertex(reverse(e)) = n.
	for (int h = 0; h < count; ++h)
	{
		const int reverse = slot[h] ^ 1;
		out.nextOffset[reverse] = slot[successor[h]] - reverse;
	}
	for (int f = 0; f < hull.faceCount(); ++f) out.faceEdge.push_back(slot[hull.faceStart[f]]);
	return true;
}

// Shrinks a solid hull: every face plane moves inwards by the shrink, and the hull of the moved
// planes is found as the polar dual of the hull of the planes' dual points, taken about a centre
// strictly inside. Returns the shrink applied, 0 if none (the outputs are then untouched).
double shrinkHull(const btAlignedObjectArray<double>& xyz, const HullTopology& hull, double shrink, double shrinkClamp,
                  btAlignedObjectArray<double>& shrunkXyz, HullTopology& shrunkHull)
{
	const int faceCount = hull.faceCount();
	if (hull.dimension != 3 || faceCount < 4) return 0;
	btAlignedObjectArray<Vec> normals;  // unit, outwards
	btAlignedObjectArray<double> offsets;
	normals.resize(faceCount);
	offsets.resize(faceCount);
	for (int f = 0; f < faceCount; ++f)
	{
		Vec centroid;
		const Vec n = faceAreaNormal(xyz, hull, f, &centroid);
		const double length = sqrt(dot(n, n));
		if (!(length > 0)) return 0;
		normals[f] = n * (1.0 / length);
		offsets[f] = dot(normals[f], centroid);
	}

	// Centre of volume: tetrahedra from a point inside (the corners' mean) to fan triangles of each face.
	Vec mean{0, 0, 0};
	for (int k = 0; k < hull.vertices.size(); ++k) mean = mean + pointAt(xyz, hull.vertices[k]);
	mean = mean * (1.0 / hull.vertices.size());
	Vec weighted{0, 0, 0};
	double volume = 0;
	for (int f = 0; f < faceCount; ++f)
	{
		const int first = hull.faceStart[f], count = hull.faceStart[f + 1] - first;
		const Vec a = pointAt(xyz, hull.faceVertices[first]) - mean;
		for (int k = 1; k + 1 < count; ++k)
		{
			const Vec b = pointAt(xyz, hull.faceVertices[first + k]) - mean;
			const Vec c = pointAt(xyz, hull.faceVertices[first + k + 1]) - mean;
			const double v = dot(a, cross(b, c));
			volume += v;
			weighted = weighted + (a + b + c) * (v * 0.25);
		}
	}
	const Vec centre = volume > 0 ? mean + weighted * (1.0 / volume) : mean;

	double innerRadius = offsets[0] - dot(normals[0], centre);
	for (int f = 1; f < faceCount; ++f) innerRadius = std::min(innerRadius, offsets[f] - dot(normals[f], centre));
	if (!(innerRadius > 0)) return 0;
	if (shrinkClamp > 0 && shrink > shrinkClamp * innerRadius) shrink = shrinkClamp * innerRadius;
	if (!(shrink < innerRadius)) return 0;

	// Plane n . (x - centre) <= d has the dual point n / d; the moved planes are all still at d > 0.
	btAlignedObjectArray<double> dual;
	dual.resize(3 * faceCount);
	for (int f = 0; f < faceCount; ++f)
	{
		const double distance = offsets[f] - dot(normals[f], centre) - shrink;
		const Vec u = normals[f] * (1.0 / distance);
		dual[3 * f] = u.x;
		dual[3 * f + 1] = u.y;
		dual[3 * f + 2] = u.z;
	}
	HullTopology dualHull;
	if (!computeHullTopology(&dual[0], faceCount, dualHull) || dualHull.dimension != 3) return 0;

	// Each dual face, plane m . y = k, is a corner of the shrunk hull at centre + m / k.
	btAlignedObjectArray<double> corners;
	for (int g = 0; g < dualHull.faceCount(); ++g)
	{
		Vec centroid;
		const Vec m = faceAreaNormal(dual, dualHull, g, &centroid);
		const double k = dot(m, centroid);
		if (!(k > 0)) continue;
		const Vec x = centre + m * (1.0 / k);
		corners.push_back(x.x);
		corners.push_back(x.y);
		corners.push_back(x.z);
	}
	// The corners are already in convex position; one more exact hull merges any that rounding split
	// and yields the faces and edges in the usual form.
	HullTopology result;
	if (corners.size() == 0 || !computeHullTopology(&corners[0], corners.size() / 3, result)) return 0;
	shrunkXyz = corners;
	shrunkHull.dimension = result.dimension;
	shrunkHull.vertices = result.vertices;
	shrunkHull.faceStart = result.faceStart;
	shrunkHull.faceVertices = result.faceVertices;
	return shrink;
}

template <typename Real>
void readFinitePoints(const void* coords, int stride, int count, btAlignedObjectArray<double>& xyz,
                      btAlignedObjectArray<int>& inputIndex)
{
	const unsigned char* base = static_cast<const unsigned char*>(coords);
	for (int i = 0; i < count; ++i)
	{
		// memcpy: a stride in bytes need not keep the coordinates aligned.
		Real c[3];
		memcpy(c, base + size_t(i) * size_t(stride), sizeof(c));
		if (!isfinite(double(c[0])) || !isfinite(double(c[1])) || !isfinite(double(c[2]))) continue;
		xyz.push_back(double(c[0]));
		xyz.push_back(double(c[1]));
		xyz.push_back(double(c[2]));
		inputIndex.push_back(i);
	}
}

}  // namespace
}  // namespace hull
}  // namespace caliber

btScalar btConvexHullComputer::compute(const void* coords, bool doubleCoords, int stride, int count, btScalar shrink,
                                       btScalar shrinkClamp)
{
	using namespace caliber::hull;
	vertices.clear();
	original_vertex_index.clear();
	edges.clear();
	faces.clear();
	const int pointSize = 3 * int(doubleCoords ? sizeof(double) : sizeof(float));
	if (coords == nullptr || count <= 0 || stride < pointSize) return btScalar(0);

	btAlignedObjectArray<double> xyz;
	btAlignedObjectArray<int> inputIndex;
	if (doubleCoords)
		readFinitePoints<double>(coords, stride, count, xyz, inputIndex);
	else
		readFinitePoints<float>(coords, stride, count, xyz, inputIndex);
	const int pointCount = inputIndex.size();
	if (pointCount == 0) return btScalar(0);

	HullTopology hull;
	if (!computeHullTopology(&xyz[0], pointCount, hull)) return btScalar(0);

	double applied = 0;
	btAlignedObjectArray<double> shrunkXyz;
	HullTopology shrunkHull;
	if (shrink > 0) applied = shrinkHull(xyz, hull, double(shrink), double(shrinkClamp), shrunkXyz, shrunkHull);
	const bool shrunk = applied > 0;
	const HullTopology& result = shrunk ? shrunkHull : hull;
	const btAlignedObjectArray<double>& positions = shrunk ? shrunkXyz : xyz;

	btAlignedObjectArray<int> vertexOfPoint;
	vertexOfPoint.resize(positions.size() / 3, -1);
	for (int k = 0; k < result.vertices.size(); ++k)
	{
		const int p = result.vertices[k];
		vertexOfPoint[p] = k;
		vertices.push_back(
		    btVector3(btScalar(positions[3 * p]), btScalar(positions[3 * p + 1]), btScalar(positions[3 * p + 2])));
		original_vertex_index.push_back(shrunk ? -1 : inputIndex[p]);
	}
	HalfEdges halfEdges;
	if (!buildHalfEdges(result, vertexOfPoint, halfEdges))
	{
		btAssert(!"btConvexHullComputer: faces do not form a closed surface");
		vertices.clear();
		original_vertex_index.clear();
		return btScalar(0);
	}
	edges.resize(halfEdges.target.size());
	for (int e = 0; e < edges.size(); ++e)
	{
		edges[e].next = halfEdges.nextOffset[e];
		edges[e].reverse = halfEdges.reverseOffset[e];
		edges[e].targetVertex = halfEdges.target[e];
	}
	for (int f = 0; f < halfEdges.faceEdge.size(); ++f) faces.push_back(halfEdges.faceEdge[f]);
	return btScalar(applied);
}
