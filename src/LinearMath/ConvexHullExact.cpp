// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Exact convex hull of a point cloud: snap to an integer grid, then an incremental (quickhull-like)
// construction whose every orientation test is an exact integer determinant, then coplanar triangles
// merged into polygon faces and points lying along polygon edges dropped.

#include "ConvexHullInternal.h"

#include <math.h>

#include <algorithm>

#if !defined(__SIZEOF_INT128__)
#error "btConvexHullComputer needs a compiler with 128-bit integers (__int128)"
#endif

namespace caliber
{
namespace hull
{
namespace
{
typedef long long Int64;
typedef __int128 Int128;

// Grid coordinates lie in [-2^29, 2^29]. Differences then fit in 31 bits, cross products of
// differences in 62 bits (Int64) and a plane test (normal . point) in about 93 bits (Int128): every
// predicate below is exact.
const int kGridBits = 29;

struct GridPoint
{
	Int64 x, y, z;
	int source;  // index of the point in the caller's list
};

struct IntVec
{
	Int64 x, y, z;
};

inline IntVec operator-(const GridPoint& a, const GridPoint& b) { return IntVec{a.x - b.x, a.y - b.y, a.z - b.z}; }

inline IntVec cross(const IntVec& a, const IntVec& b)
{
	return IntVec{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

inline Int128 dot(const IntVec& a, const IntVec& b)
{
	return Int128(a.x) * b.x + Int128(a.y) * b.y + Int128(a.z) * b.z;
}

inline Int128 dot(const IntVec& a, const GridPoint& p)
{
	return Int128(a.x) * p.x + Int128(a.y) * p.y + Int128(a.z) * p.z;
}

inline bool isZero(const IntVec& v) { return v.x == 0 && v.y == 0 && v.z == 0; }

inline bool lexicographicLess(const GridPoint& a, const GridPoint& b)
{
	if (a.x != b.x) return a.x < b.x;
	if (a.y != b.y) return a.y < b.y;
	if (a.z != b.z) return a.z < b.z;
	return a.source < b.source;  // among duplicates the earliest input point comes first
}

inline bool samePosition(const GridPoint& a, const GridPoint& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// Snaps the points to the grid with one uniform scale (so that coplanarity and convexity carry over)
// chosen from the largest bounding-box side, then removes duplicates, keeping the earliest point.
void snapToGrid(const double* xyz, int count, btAlignedObjectArray<GridPoint>& grid)
{
	double lo[3] = {xyz[0], xyz[1], xyz[2]};
	double hi[3] = {xyz[0], xyz[1], xyz[2]};
	for (int i = 1; i < count; ++i)
	{
		for (int axis = 0; axis < 3; ++axis)
		{
			const double v = xyz[3 * i + axis];
			if (v < lo[axis]) lo[axis] = v;
			if (v > hi[axis]) hi[axis] = v;
		}
	}
	double centre[3];
	double largestSpan = 0;
	for (int axis = 0; axis < 3; ++axis)
	{
		largestSpan = std::max(largestSpan, hi[axis] - lo[axis]);
		centre[axis] = lo[axis] * 0.5 + hi[axis] * 0.5;
	}
	// ldexp by (shift) maps offsets from the centre, at most half the span, into [-2^29, 2^29].
	int shift = 0;
	if (largestSpan > 0)
	{
		int exponent = 0;
		if (isfinite(largestSpan))
		{
			frexp(largestSpan, &exponent);  // largestSpan < 2^exponent
			shift = kGridBits + 1 - exponent;
		}
		else
		{
			// The span overflows a double; the half span cannot.
			double halfSpan = 0;
			for (int axis = 0; axis < 3; ++axis) halfSpan = std::max(halfSpan, hi[axis] * 0.5 - lo[axis] * 0.5);
			frexp(halfSpan, &exponent);
			shift = kGridBits - exponent;
		}
	}
	const double limit = double(Int64(1) << kGridBits);
	grid.resize(count);
	for (int i = 0; i < count; ++i)
	{
		Int64 q[3] = {0, 0, 0};
		if (largestSpan > 0)
		{
			for (int axis = 0; axis < 3; ++axis)
			{
				double v = ldexp(xyz[3 * i + axis] - centre[axis], shift);
				// Rounding of the centre can put an extreme point a hair past the limit.
				v = std::min(limit, std::max(-limit, v));
				q[axis] = Int64(floor(v + 0.5));
			}
		}
		grid[i] = GridPoint{q[0], q[1], q[2], i};
	}
	if (count > 1)
	{
		std::sort(&grid[0], &grid[0] + count, lexicographicLess);
		int unique = 1;
		for (int i = 1; i < count; ++i)
		{
			if (!samePosition(grid[i], grid[unique - 1])) grid[unique++] = grid[i];
		}
		grid.resize(unique);
	}
}

// Flat hull: Andrew's monotone chain in the coordinate plane most nearly parallel to the points'
// plane (the projection is one-to-one on that plane, so the 2D hull is the projected 3D hull).
void planarHull(const btAlignedObjectArray<GridPoint>& points, const IntVec& normal, HullTopology& topology)
{
	const Int64 n[3] = {normal.x, normal.y, normal.z};
	int dropAxis = 0;
	for (int axis = 1; axis < 3; ++axis)
	{
		if ((n[axis] < 0 ? -n[axis] : n[axis]) > (n[dropAxis] < 0 ? -n[dropAxis] : n[dropAxis])) dropAxis = axis;
	}
	// With (u, v) = axes (k + 1, k + 2), the 2D cross product equals component k of the 3D one.
	struct Point2
	{
		Int64 u, v;
		int id;
	};
	const int count = points.size();
	btAlignedObjectArray<Point2> flat;
	flat.resize(count);
	for (int i = 0; i < count; ++i)
	{
		const Int64 c[3] = {points[i].x, points[i].y, points[i].z};
		flat[i] = Point2{c[(dropAxis + 1) % 3], c[(dropAxis + 2) % 3], i};
	}
	std::sort(&flat[0], &flat[0] + count,
	          [](const Point2& a, const Point2& b) { return a.u != b.u ? a.u < b.u : a.v < b.v; });
	auto turn = [](const Point2& o, const Point2& a, const Point2& b)
	{ return (a.u - o.u) * (b.v - o.v) - (a.v - o.v) * (b.u - o.u); };

	// Lower chain left to right, then upper chain right to left: counter-clockwise, strict turns only.
	btAlignedObjectArray<int> chain;
	chain.resize(2 * count);
	int size = 0;
	for (int i = 0; i < count; ++i)
	{
		while (size >= 2 && turn(flat[chain[size - 2]], flat[chain[size - 1]], flat[i]) <= 0) --size;
		chain[size++] = i;
	}
	const int lowerSize = size;
	for (int i = count - 2; i >= 0; --i)
	{
		while (size > lowerSize && turn(flat[chain[size - 2]], flat[chain[size - 1]], flat[i]) <= 0) --size;
		chain[size++] = i;
	}
	--size;  // the last point repeats the first

	btAlignedObjectArray<int> polygon;  // counter-clockwise about the normal
	polygon.resize(size);
	for (int i = 0; i < size; ++i)
	{
		const int id = points[flat[chain[i]].id].source;
		polygon[n[dropAxis] > 0 ? i : size - 1 - i] = id;
	}
	topology.dimension = 2;
	for (int i = 0; i < size; ++i) topology.vertices.push_back(polygon[i]);
	std::sort(&topology.vertices[0], &topology.vertices[0] + size);
	topology.faceStart.push_back(0);
	for (int i = 0; i < size; ++i) topology.faceVertices.push_back(polygon[i]);
	topology.faceStart.push_back(size);
	topology.faceVertices.push_back(polygon[0]);
	for (int i = size - 1; i > 0; --i) topology.faceVertices.push_back(polygon[i]);
	topology.faceStart.push_back(2 * size);
}

// Solid hull by incremental insertion: every outside point is assigned to one triangle it sees; the
// farthest point of a triangle is added next, replacing the triangles it sees by a fan from it to
// their horizon. A point that sees none of the new fan triangles is inside the new hull for good.
class SolidHull
{
public:
	explicit SolidHull(const btAlignedObjectArray<GridPoint>& points) : m_points(points) {}

	// Builds the triangulated hull from a non-degenerate tetrahedron. False if a check failed.
	bool build(int a, int b, int c, int d);

	// Merges coplanar triangles into faces and fills the topology. False if a check failed.
	bool extractFaces(HullTopology& topology);

private:
	struct Triangle
	{
		int vertex[3];     // counter-clockwise seen from outside
		int neighbour[3];  // triangle across edge vertex[i] -> vertex[(i + 1) % 3]
		IntVec normal;     // (v1 - v0) x (v2 - v0), pointing outwards
		Int128 offset;     // normal . v0
		double inverseNormalLength;
		int firstConflict;  // first outside point assigned here, -1 if none
		int farthestConflict;
		double farthestDistance;
		int visitStamp;
		bool visible;
		bool alive;
	};

	struct HorizonEdge
	{
		int from, to;  // counter-clockwise on the hidden triangle's visible neighbour
		int hidden;    // the triangle that stays
	};

	const btAlignedObjectArray<GridPoint>& m_points;
	btAlignedObjectArray<Triangle> m_triangles;
	btAlignedObjectArray<int> m_freeTriangles;
	btAlignedObjectArray<int> m_nextConflict;        // per point: next point in the same conflict list
	btAlignedObjectArray<int> m_triangleFromVertex;  // per point: new fan triangle starting there, else -1
	btAlignedObjectArray<int> m_pending;             // triangles that may hold conflicts
	btAlignedObjectArray<int> m_stack;
	btAlignedObjectArray<int> m_visible;
	btAlignedObjectArray<HorizonEdge> m_horizon;
	btAlignedObjectArray<int> m_orphans;
	btAlignedObjectArray<int> m_fan;
	int m_stamp = 0;

	Int128 height(const Triangle& t, int point) const { return dot(t.normal, m_points[point]) - t.offset; }
	int newTriangle(int a, int b, int c);
	void addConflict(int triangle, int point, Int128 heightAbove);
	bool addPoint(int seedTriangle, int apex);
};

int SolidHull::newTriangle(int a, int b, int c)
{
	int index;
	if (m_freeTriangles.size() > 0)
	{
		index = m_freeTriangles[m_freeTriangles.size() - 1];
		m_freeTriangles.pop_back();
	}
	else
	{
		index = m_triangles.size();
		m_triangles.expandNonInitializing();
	}
	Triangle& t = m_triangles[index];
	t.vertex[0] = a;
	t.vertex[1] = b;
	t.vertex[2] = c;
	t.neighbour[0] = t.neighbour[1] = t.neighbour[2] = -1;
	const GridPoint& p = m_points[a];
	t.normal = cross(m_points[b] - p, m_points[c] - p);
	t.offset = dot(t.normal, p);
	const double nx = double(t.normal.x), ny = double(t.normal.y), nz = double(t.normal.z);
	t.inverseNormalLength = 1.0 / sqrt(nx * nx + ny * ny + nz * nz);
	t.firstConflict = -1;
	t.farthestConflict = -1;
	t.farthestDistance = 0;
	t.visitStamp = 0;
	t.visible = false;
	t.alive = true;
	btAssert(!isZero(t.normal));
	return index;
}

void SolidHull::addConflict(int triangle, int point, Int128 heightAbove)
{
	Triangle& t = m_triangles[triangle];
	m_nextConflict[point] = t.firstConflict;
	t.firstConflict = point;
	// Only the choice of the next point uses this rounded distance, never a topological decision.
	const double distance = double(heightAbove) * t.inverseNormalLength;
	if (t.farthestConflict < 0 || distance > t.farthestDistance)
	{
		t.farthestConflict = point;
		t.farthestDistance = distance;
	}
}

bool SolidHull::build(int a, int b, int c, int d)
{
	const int pointCount = m_points.size();
	m_nextConflict.resize(pointCount, -1);
	m_triangleFromVertex.resize(pointCount, -1);

	// Four faces, each wound so that the corner it leaves out is behind it.
	const int corner[4] = {a, b, c, d};
	for (int omit = 0; omit < 4; ++omit)
	{
		int v[3];
		int n = 0;
		for (int k = 0; k < 4; ++k)
			if (k != omit) v[n++] = corner[k];
		const GridPoint& p = m_points[v[0]];
		const IntVec normal = cross(m_points[v[1]] - p, m_points[v[2]] - p);
		if (dot(normal, m_points[corner[omit]] - p) > 0) std::swap(v[1], v[2]);
		newTriangle(v[0], v[1], v[2]);
	}
	for (int t = 0; t < 4; ++t)
	{
		for (int i = 0; i < 3; ++i)
		{
			const int from = m_triangles[t].vertex[i], to = m_triangles[t].vertex[(i + 1) % 3];
			for (int u = 0; u < 4; ++u)
			{
				for (int j = 0; j < 3; ++j)
				{
					if (m_triangles[u].vertex[j] == to && m_triangles[u].vertex[(j + 1) % 3] == from)
						m_triangles[t].neighbour[i] = u;
				}
			}
			if (m_triangles[t].neighbour[i] < 0) return false;
		}
	}

	for (int p = 0; p < pointCount; ++p)
	{
		if (p == a || p == b || p == c || p == d) continue;
		int best = -1;
		double bestDistance = 0;
		Int128 bestHeight = 0;
		for (int t = 0; t < 4; ++t)
		{
			const Int128 h = height(m_triangles[t], p);
			if (h <= 0) continue;
			const double distance = double(h) * m_triangles[t].inverseNormalLength;
			if (best < 0 || distance > bestDistance)
			{
				best = t;
				bestDistance = distance;
				bestHeight = h;
			}
		}
		if (best >= 0) addConflict(best, p, bestHeight);
	}
	for (int t = 0; t < 4; ++t) m_pending.push_back(t);

	// Each step makes one more point a hull vertex and removes it from the conflicts, so there are
	// at most pointCount steps; the counter only guards against a broken invariant.
	int steps = 0;
	while (m_pending.size() > 0)
	{
		const int t = m_pending[m_pending.size() - 1];
		m_pending.pop_back();
		if (!m_triangles[t].alive || m_triangles[t].firstConflict < 0) continue;
		if (++steps > pointCount) return false;
		if (!addPoint(t, m_triangles[t].farthestConflict)) return false;
	}
	return true;
}

bool SolidHull::addPoint(int seedTriangle, int apex)
{
	// The triangles the apex sees (strictly) form a disc: flood it from the seed.
	++m_stamp;
	m_visible.resize(0);
	m_stack.resize(0);
	m_triangles[seedTriangle].visitStamp = m_stamp;
	m_triangles[seedTriangle].visible = true;
	m_stack.push_back(seedTriangle);
	while (m_stack.size() > 0)
	{
		const int t = m_stack[m_stack.size() - 1];
		m_stack.pop_back();
		m_visible.push_back(t);
		for (int i = 0; i < 3; ++i)
		{
			Triangle& n = m_triangles[m_triangles[t].neighbour[i]];
			if (n.visitStamp == m_stamp) continue;
			n.visitStamp = m_stamp;
			n.visible = height(n, apex) > 0;
			if (n.visible) m_stack.push_back(m_triangles[t].neighbour[i]);
		}
	}

	// Its boundary is a simple cycle: each horizon vertex starts exactly one horizon edge.
	m_horizon.resize(0);
	for (int k = 0; k < m_visible.size(); ++k)
	{
		const Triangle& t = m_triangles[m_visible[k]];
		for (int i = 0; i < 3; ++i)
		{
			if (m_triangles[t.neighbour[i]].visible) continue;
			const int from = t.vertex[i];
			if (m_triangleFromVertex[from] != -1) return false;
			m_triangleFromVertex[from] = -2;  // claimed; the fan triangle is stored below
			m_horizon.push_back(HorizonEdge{from, t.vertex[(i + 1) % 3], t.neighbour[i]});
		}
	}
	if (m_horizon.size() < 3) return false;

	m_orphans.resize(0);
	for (int k = 0; k < m_visible.size(); ++k)
	{
		Triangle& t = m_triangles[m_visible[k]];
		for (int p = t.firstConflict; p >= 0; p = m_nextConflict[p])
			if (p != apex) m_orphans.push_back(p);
		t.alive = false;
		t.visible = false;
		t.firstConflict = -1;
		m_freeTriangles.push_back(m_visible[k]);
	}

	// Fan from the apex to every horizon edge, stitched to the hidden side and to each other.
	m_fan.resize(0);
	for (int k = 0; k < m_horizon.size(); ++k)
	{
		const HorizonEdge edge = m_horizon[k];
		const int t = newTriangle(edge.from, edge.to, apex);
		m_triangles[t].neighbour[0] = edge.hidden;
		Triangle& hidden = m_triangles[edge.hidden];
		bool linked = false;
		for (int j = 0; j < 3; ++j)
		{
			if (hidden.vertex[j] == edge.to && hidden.vertex[(j + 1) % 3] == edge.from)
			{
				hidden.neighbour[j] = t;
				linked = true;
			}
		}
		if (!linked) return false;
		m_triangleFromVertex[edge.from] = t;
		m_fan.push_back(t);
	}
	for (int k = 0; k < m_fan.size(); ++k)
	{
		const int t = m_fan[k];
		const int next = m_triangleFromVertex[m_triangles[t].vertex[1]];
		if (next < 0) return false;
		m_triangles[t].neighbour[1] = next;
		m_triangles[next].neighbour[2] = t;
	}
	for (int k = 0; k < m_horizon.size(); ++k) m_triangleFromVertex[m_horizon[k].from] = -1;

	// An orphan outside the new hull sees one of the fan triangles: it was above a removed triangle,
	// and everything above that triangle's plane that the old hull does not cover belongs to the fan.
	for (int k = 0; k < m_orphans.size(); ++k)
	{
		const int p = m_orphans[k];
		for (int f = 0; f < m_fan.size(); ++f)
		{
			const Int128 h = height(m_triangles[m_fan[f]], p);
			if (h > 0)
			{
				addConflict(m_fan[f], p, h);
				break;
			}
		}
	}
	for (int f = 0; f < m_fan.size(); ++f)
		if (m_triangles[m_fan[f]].firstConflict >= 0) m_pending.push_back(m_fan[f]);
	return true;
}

bool SolidHull::extractFaces(HullTopology& topology)
{
	const int triangleCount = m_triangles.size();
	const int pointCount = m_points.size();

	// Faces: flood fill across edges whose two triangles lie in one plane (exactly).
	btAlignedObjectArray<int> faceOf;
	faceOf.resize(triangleCount, -1);
	btAlignedObjectArray<int> members;  // triangles grouped by face
	btAlignedObjectArray<int> memberStart;
	for (int seed = 0; seed < triangleCount; ++seed)
	{
		if (!m_triangles[seed].alive || faceOf[seed] >= 0) continue;
		const int face = memberStart.size();
		memberStart.push_back(members.size());
		faceOf[seed] = face;
		members.push_back(seed);
		for (int k = memberStart[face]; k < members.size(); ++k)
		{
			const Triangle& t = m_triangles[members[k]];
			for (int i = 0; i < 3; ++i)
			{
				const int n = t.neighbour[i];
				if (faceOf[n] >= 0) continue;
				const Triangle& other = m_triangles[n];
				if (height(t, other.vertex[0]) == 0 && height(t, other.vertex[1]) == 0 &&
				    height(t, other.vertex[2]) == 0)
				{
					faceOf[n] = face;
					members.push_back(n);
				}
			}
		}
	}
	const int faceCount = memberStart.size();
	memberStart.push_back(members.size());

	// Each face is a convex polygon: its boundary edges form one cycle. Keep the strict corners; a
	// point where the boundary runs straight on lies inside a hull edge and is no vertex.
	btAlignedObjectArray<int> boundaryNext;
	boundaryNext.resize(pointCount, -1);
	btAlignedObjectArray<char> isCorner;
	isCorner.resize(pointCount, 0);
	btAlignedObjectArray<int> starts;
	btAlignedObjectArray<int> cycle;
	topology.faceStart.push_back(0);
	for (int face = 0; face < faceCount; ++face)
	{
		starts.resize(0);
		for (int k = memberStart[face]; k < memberStart[face + 1]; ++k)
		{
			const Triangle& t = m_triangles[members[k]];
			for (int i = 0; i < 3; ++i)
			{
				if (faceOf[t.neighbour[i]] == face) continue;
				const int from = t.vertex[i];
				if (boundaryNext[from] >= 0) return false;
				boundaryNext[from] = t.vertex[(i + 1) % 3];
				starts.push_back(from);
			}
		}
		cycle.resize(0);
		int v = starts[0];
		do
		{
			cycle.push_back(v);
			v = boundaryNext[v];
		} while (v >= 0 && v != starts[0] && cycle.size() <= starts.size());
		for (int k = 0; k < starts.size(); ++k) boundaryNext[starts[k]] = -1;
		if (v != starts[0] || cycle.size() != starts.size()) return false;

		const int length = cycle.size();
		const int first = topology.faceVertices.size();
		for (int k = 0; k < length; ++k)
		{
			const GridPoint& prev = m_points[cycle[(k + length - 1) % length]];
			const GridPoint& here = m_points[cycle[k]];
			const GridPoint& next = m_points[cycle[(k + 1) % length]];
			if (isZero(cross(here - prev, next - here))) continue;
			isCorner[cycle[k]] = 1;
			topology.faceVertices.push_back(m_points[cycle[k]].source);
		}
		const int corners = topology.faceVertices.size() - first;
		if (corners < 3) return false;
		// Start every face at its lowest input index: the output does not depend on insertion order.
		int lowest = first;
		for (int k = first + 1; k < first + corners; ++k)
			if (topology.faceVertices[k] < topology.faceVertices[lowest]) lowest = k;
		std::rotate(&topology.faceVertices[first], &topology.faceVertices[lowest],
		            &topology.faceVertices[first] + corners);
		topology.faceStart.push_back(topology.faceVertices.size());
	}
	for (int p = 0; p < pointCount; ++p)
		if (isCorner[p]) topology.vertices.push_back(m_points[p].source);
	if (topology.vertices.size() > 1)
		std::sort(&topology.vertices[0], &topology.vertices[0] + topology.vertices.size());
	topology.dimension = 3;
	return true;
}

bool hullOfGrid(const btAlignedObjectArray<GridPoint>& points, HullTopology& topology)
{
	const int count = points.size();
	// An extreme first point (lexicographically smallest), then points that span as much as possible:
	// the initial simplex only needs to be non-degenerate, a large one just saves work.
	const int a = 0;
	int b = 0;
	Int64 bestLength = 0;
	for (int i = 1; i < count; ++i)
	{
		const IntVec d = points[i] - points[a];
		const Int64 length = d.x * d.x + d.y * d.y + d.z * d.z;
		if (length > bestLength)
		{
			bestLength = length;
			b = i;
		}
	}
	if (b == a)
	{
		topology.dimension = 0;
		topology.vertices.push_back(points[a].source);
		return true;
	}
	const IntVec ab = points[b] - points[a];
	int c = -1;
	Int128 bestArea = 0;
	for (int i = 0; i < count; ++i)
	{
		const IntVec n = cross(ab, points[i] - points[a]);
		const Int128 area = dot(n, n);
		if (area > bestArea)
		{
			bestArea = area;
			c = i;
		}
	}
	if (c < 0)
	{
		// Collinear: the lexicographically smallest point and the one farthest from it are the ends.
		topology.dimension = 1;
		topology.vertices.push_back(std::min(points[a].source, points[b].source));
		topology.vertices.push_back(std::max(points[a].source, points[b].source));
		return true;
	}
	const IntVec normal = cross(ab, points[c] - points[a]);
	int d = -1;
	Int128 bestVolume = 0;
	for (int i = 0; i < count; ++i)
	{
		Int128 volume = dot(normal, points[i] - points[a]);
		if (volume < 0) volume = -volume;
		if (volume > bestVolume)
		{
			bestVolume = volume;
			d = i;
		}
	}
	if (d < 0)
	{
		planarHull(points, normal, topology);
		return true;
	}
	SolidHull solid(points);
	return solid.build(a, b, c, d) && solid.extractFaces(topology);
}

}  // namespace

bool computeHullTopology(const double* xyz, int count, HullTopology& topology)
{
	topology.clear();
	if (xyz == nullptr || count <= 0) return true;
	btAlignedObjectArray<GridPoint> grid;
	snapToGrid(xyz, count, grid);
	if (hullOfGrid(grid, topology)) return true;
	btAssert(!"exact convex hull: inconsistent topology");
	topology.clear();
	return false;
}

}  // namespace hull
}  // namespace caliber
