// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btConvexHullComputer.h"

#include <gtest/gtest.h>

#include <float.h>
#include <math.h>
#include <string.h>

#include <algorithm>
#include <random>
#include <set>
#include <sstream>
#include <vector>

namespace
{
typedef std::vector<double> Points;  // x, y, z per point

struct V3
{
	double x, y, z;
};
V3 operator-(const V3& a, const V3& b) { return V3{a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(const V3& a, const V3& b) { return V3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(const V3& a) { return sqrt(dot(a, a)); }
V3 pointOf(const Points& xyz, int i) { return V3{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }
int pointCount(const Points& xyz) { return int(xyz.size() / 3); }

// The values compute() sees when the points are passed as Real.
template <typename Real>
Points roundedTo(const Points& xyz)
{
	Points out(xyz.size());
	for (size_t i = 0; i < xyz.size(); ++i) out[i] = double(Real(xyz[i]));
	return out;
}

// Passes the points as Real, strideBytes apart (any stride >= 3 * sizeof(Real), aligned or not).
template <typename Real>
btScalar computeHull(btConvexHullComputer& hull, const Points& xyz, int strideBytes, btScalar shrink = 0,
                     btScalar shrinkClamp = 0)
{
	const int count = pointCount(xyz);
	std::vector<double> storage((size_t(strideBytes) * count + 64) / sizeof(double) + 1);  // 8-byte aligned start
	unsigned char* bytes = reinterpret_cast<unsigned char*>(storage.data());
	for (int i = 0; i < count; ++i)
	{
		const Real c[3] = {Real(xyz[3 * i]), Real(xyz[3 * i + 1]), Real(xyz[3 * i + 2])};
		memcpy(bytes + size_t(i) * strideBytes, c, sizeof(c));
	}
	return hull.compute(reinterpret_cast<const Real*>(bytes), strideBytes, count, shrink, shrinkClamp);
}

int edgeIndex(const btConvexHullComputer& hull, const btConvexHullComputer::Edge* e) { return int(e - &hull.edges[0]); }

// Indices of the edges of face f, in getNextEdgeOfFace order (empty if the walk does not close).
std::vector<int> faceEdges(const btConvexHullComputer& hull, int f)
{
	std::vector<int> out;
	const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
	const btConvexHullComputer::Edge* e = first;
	do
	{
		out.push_back(edgeIndex(hull, e));
		e = e->getNextEdgeOfFace();
	} while (e != first && int(out.size()) <= hull.edges.size());
	if (e != first) out.clear();
	return out;
}

// Checks the half-edge structure alone: pairing, vertex and face cycles, Euler's formula.
::testing::AssertionResult checkTopology(const btConvexHullComputer& hull)
{
	const int V = hull.vertices.size(), E = hull.edges.size(), F = hull.faces.size();
	if (hull.original_vertex_index.size() != V)
		return ::testing::AssertionFailure() << "original_vertex_index has " << hull.original_vertex_index.size()
		                                     << " entries for " << V << " vertices";
	for (int e = 0; e < E; ++e)
	{
		const btConvexHullComputer::Edge& edge = hull.edges[e];
		const int r = edgeIndex(hull, edge.getReverseEdge());
		if (r != (e ^ 1)) return ::testing::AssertionFailure() << "edge " << e << " has reverse " << r;
		if (edgeIndex(hull, hull.edges[r].getReverseEdge()) != e)
			return ::testing::AssertionFailure() << "reverse of reverse of edge " << e << " is not itself";
		const int s = edge.getSourceVertex(), t = edge.getTargetVertex();
		if (s < 0 || s >= V || t < 0 || t >= V || s == t)
			return ::testing::AssertionFailure()
			       << "edge " << e << " runs " << s << " -> " << t << " with " << V << " vertices";
		const int n = edgeIndex(hull, edge.getNextEdgeOfVertex());
		if (n < 0 || n >= E || hull.edges[n].getSourceVertex() != s)
			return ::testing::AssertionFailure() << "next edge of vertex of edge " << e << " is " << n;
	}
	// Every vertex with edges has exactly one cycle around it, holding all its edges.
	std::vector<int> degree(V, 0), cycles(V, 0);
	std::vector<char> seen(E, 0);
	for (int e = 0; e < E; ++e) ++degree[hull.edges[e].getSourceVertex()];
	for (int e = 0; e < E; ++e)
	{
		if (seen[e]) continue;
		const int s = hull.edges[e].getSourceVertex();
		int length = 0, k = e;
		do
		{
			if (seen[k]) return ::testing::AssertionFailure() << "vertex cycles of edge " << e << " overlap";
			seen[k] = 1;
			++length;
			k = edgeIndex(hull, hull.edges[k].getNextEdgeOfVertex());
		} while (k != e && length <= E);
		if (k != e) return ::testing::AssertionFailure() << "vertex cycle from edge " << e << " does not close";
		if (length != degree[s])
			return ::testing::AssertionFailure()
			       << "vertex " << s << " cycle has " << length << " of " << degree[s] << " edges";
		++cycles[s];
	}
	// Every edge is on exactly one face when there are faces; consecutive edges join up.
	std::vector<int> faceOfEdge(E, -1);
	for (int f = 0; f < F; ++f)
	{
		if (hull.faces[f] < 0 || hull.faces[f] >= E)
			return ::testing::AssertionFailure() << "face " << f << " starts at edge " << hull.faces[f];
		const std::vector<int> ring = faceEdges(hull, f);
		if (ring.size() < 3) return ::testing::AssertionFailure() << "face " << f << " has " << ring.size() << " edges";
		for (size_t k = 0; k < ring.size(); ++k)
		{
			if (faceOfEdge[ring[k]] >= 0)
				return ::testing::AssertionFailure()
				       << "edge " << ring[k] << " is on faces " << faceOfEdge[ring[k]] << " and " << f;
			faceOfEdge[ring[k]] = f;
			if (hull.edges[ring[k]].getTargetVertex() != hull.edges[ring[(k + 1) % ring.size()]].getSourceVertex())
				return ::testing::AssertionFailure() << "face " << f << " breaks after edge " << ring[k];
		}
	}
	if (F > 0)
	{
		for (int e = 0; e < E; ++e)
			if (faceOfEdge[e] < 0) return ::testing::AssertionFailure() << "edge " << e << " is on no face";
		if (V - E / 2 + F != 2)
			return ::testing::AssertionFailure() << "Euler: V - E/2 + F = " << V << " - " << E / 2 << " + " << F;
	}
	return ::testing::AssertionSuccess();
}

struct FacePlane
{
	V3 normal;  // unit, from the counter-clockwise order
	double offset;
	std::vector<int> corners;
};

FacePlane facePlane(const btConvexHullComputer& hull, const std::vector<V3>& position, int f)
{
	FacePlane plane;
	V3 n{0, 0, 0}, sum{0, 0, 0};
	for (int e : faceEdges(hull, f)) plane.corners.push_back(hull.edges[e].getSourceVertex());
	for (size_t k = 0; k < plane.corners.size(); ++k)
	{
		const V3 a = position[plane.corners[k]], b = position[plane.corners[(k + 1) % plane.corners.size()]];
		const V3 c = cross(a, b);
		n = V3{n.x + c.x, n.y + c.y, n.z + c.z};
		sum = V3{sum.x + a.x, sum.y + a.y, sum.z + a.z};
	}
	const double len = length(n);
	plane.normal = V3{n.x / len, n.y / len, n.z / len};
	const double count = double(plane.corners.size());
	plane.offset = dot(plane.normal, V3{sum.x / count, sum.y / count, sum.z / count});
	return plane;
}

// Checks a solid hull of the points `input` (as compute() saw them): vertices are input points,
// faces are planar, convex and face outwards, and no input point is outside any face.
::testing::AssertionResult checkSolidGeometry(const btConvexHullComputer& hull, const Points& input, double tolerance,
                                              bool requireMaximalFaces = false)
{
	const int V = hull.vertices.size();
	std::vector<V3> position(V);
	V3 mean{0, 0, 0};
	for (int v = 0; v < V; ++v)
	{
		const int i = hull.original_vertex_index[v];
		if (i < 0 || i >= pointCount(input))
			return ::testing::AssertionFailure() << "vertex " << v << " has input index " << i;
		position[v] = pointOf(input, i);
		const btVector3& p = hull.vertices[v];
		if (p.x() != btScalar(input[3 * i]) || p.y() != btScalar(input[3 * i + 1]) ||
		    p.z() != btScalar(input[3 * i + 2]))
			return ::testing::AssertionFailure() << "vertex " << v << " differs from input point " << i;
		mean = V3{mean.x + position[v].x / V, mean.y + position[v].y / V, mean.z + position[v].z / V};
	}
	std::vector<FacePlane> planes;
	for (int f = 0; f < hull.faces.size(); ++f)
	{
		const FacePlane plane = facePlane(hull, position, f);
		const size_t n = plane.corners.size();
		for (size_t k = 0; k < n; ++k)
		{
			const V3 p = position[plane.corners[k]];
			const double off = dot(plane.normal, p) - plane.offset;
			if (fabs(off) > tolerance)
				return ::testing::AssertionFailure() << "face " << f << " corner " << k << " is " << off
				                                     << " off its plane (tolerance " << tolerance << ")";
			const V3 a = p - position[plane.corners[(k + n - 1) % n]], b = position[plane.corners[(k + 1) % n]] - p;
			const double turn = dot(cross(a, b), plane.normal);
			if (turn < -tolerance * std::max(length(a), length(b)))
				return ::testing::AssertionFailure() << "face " << f << " turns " << turn << " at corner " << k;
		}
		const double centreHeight = dot(plane.normal, mean) - plane.offset;
		if (!(centreHeight < 0))
			return ::testing::AssertionFailure()
			       << "face " << f << " faces inwards (centre height " << centreHeight << ")";
		planes.push_back(plane);
	}
	double worst = -DBL_MAX;
	int worstPoint = -1, worstFace = -1;
	for (size_t f = 0; f < planes.size(); ++f)
	{
		for (int i = 0; i < pointCount(input); ++i)
		{
			const double h = dot(planes[f].normal, pointOf(input, i)) - planes[f].offset;
			if (h > worst)
			{
				worst = h;
				worstPoint = i;
				worstFace = int(f);
			}
		}
	}
	if (worst > tolerance)
		return ::testing::AssertionFailure() << "input point " << worstPoint << " is " << worst << " outside face "
		                                     << worstFace << " (tolerance " << tolerance << ")";
	if (requireMaximalFaces)
	{
		// Across every edge the neighbouring face must bend away: no two faces share a plane.
		std::vector<int> faceOfEdge(hull.edges.size(), -1);
		for (int f = 0; f < hull.faces.size(); ++f)
			for (int e : faceEdges(hull, f)) faceOfEdge[e] = f;
		for (int e = 0; e < hull.edges.size(); ++e)
		{
			const FacePlane& mine = planes[faceOfEdge[e]];
			const FacePlane& other = planes[faceOfEdge[e ^ 1]];
			double lowest = 0;
			for (int c : other.corners) lowest = std::min(lowest, dot(mine.normal, position[c]) - mine.offset);
			if (!(lowest < -tolerance))
				return ::testing::AssertionFailure()
				       << "faces " << faceOfEdge[e] << " and " << faceOfEdge[e ^ 1] << " are coplanar";
		}
	}
	return ::testing::AssertionSuccess();
}

double extentOf(const Points& xyz)
{
	double extent = 0;
	for (double c : xyz) extent = std::max(extent, fabs(c));
	return extent;
}

// Tolerance for "on the hull": the input carries float precision, so a point within a few float
// ulps of the coordinates' magnitude is on the hull. (Hull decisions are exact on a grid 2^-30 of the
// cloud's size, some 100 times finer, so measured errors stay far below this.)
double floatTolerance(const Points& xyz) { return 8 * FLT_EPSILON * extentOf(xyz); }

enum class Cloud
{
	SphereSurface,
	CubeVolume,
	Gaussian,
	Lattice,  // small integer lattice: lots of exactly coplanar and collinear points
};

const char* cloudName(Cloud c)
{
	switch (c)
	{
		case Cloud::SphereSurface:
			return "sphere surface";
		case Cloud::CubeVolume:
			return "cube volume";
		case Cloud::Gaussian:
			return "gaussian";
		case Cloud::Lattice:
			return "lattice";
	}
	return "?";
}

Points makeCloud(Cloud kind, int count, unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> uniform(-1.0, 1.0);
	std::normal_distribution<double> normal(0.0, 1.0);
	std::uniform_int_distribution<int> lattice(-3, 3);
	Points xyz;
	for (int i = 0; i < count; ++i)
	{
		double p[3];
		switch (kind)
		{
			case Cloud::SphereSurface:
			{
				double len = 0;
				do
				{
					for (double& c : p) c = normal(rng);
					len = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
				} while (len < 1e-3);
				for (double& c : p) c /= len;
				break;
			}
			case Cloud::CubeVolume:
				for (double& c : p) c = uniform(rng);
				break;
			case Cloud::Gaussian:
				for (double& c : p) c = normal(rng);
				break;
			case Cloud::Lattice:
				for (double& c : p) c = lattice(rng);
				break;
		}
		xyz.insert(xyz.end(), p, p + 3);
	}
	return xyz;
}

// A cube [-h, h]^3 + offset sampled on a 5 x 5 x 5 grid: corners, points along its edges, on its
// faces and inside.
Points latticeCube(double halfExtent, double offset)
{
	Points xyz;
	for (int i = 0; i <= 4; ++i)
		for (int j = 0; j <= 4; ++j)
			for (int k = 0; k <= 4; ++k)
			{
				xyz.push_back(offset + halfExtent * (i - 2) / 2.0);
				xyz.push_back(offset + halfExtent * (j - 2) / 2.0);
				xyz.push_back(offset + halfExtent * (k - 2) / 2.0);
			}
	return xyz;
}

std::vector<int> faceSizes(const btConvexHullComputer& hull)
{
	std::vector<int> sizes;
	for (int f = 0; f < hull.faces.size(); ++f) sizes.push_back(int(faceEdges(hull, f).size()));
	std::sort(sizes.begin(), sizes.end());
	return sizes;
}

std::string describe(const btConvexHullComputer& hull)
{
	std::ostringstream s;
	s << hull.vertices.size() << " vertices, " << hull.edges.size() << " edges, " << hull.faces.size() << " faces";
	return s.str();
}

void expectCubeTopology(const btConvexHullComputer& hull)
{
	EXPECT_TRUE(checkTopology(hull));
	EXPECT_EQ(hull.vertices.size(), 8) << describe(hull);
	EXPECT_EQ(hull.edges.size(), 24) << describe(hull);
	EXPECT_EQ(faceSizes(hull), std::vector<int>(6, 4)) << describe(hull);
}

}  // namespace

// ---- degenerate input ---------------------------------------------------------------------------

TEST(ConvexHullComputer, BadArgumentsGiveEmptyResult)
{
	btConvexHullComputer hull;
	const float tetra[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
	ASSERT_EQ(hull.compute(tetra, 12, 4, 0, 0), btScalar(0));
	ASSERT_EQ(hull.vertices.size(), 4);  // a previous result must be cleared by each failure below

	EXPECT_EQ(hull.compute(static_cast<const float*>(nullptr), 12, 4, 0, 0), btScalar(0));
	EXPECT_EQ(hull.vertices.size() + hull.edges.size() + hull.faces.size() + hull.original_vertex_index.size(), 0);
	hull.compute(tetra, 12, 4, 0, 0);
	EXPECT_EQ(hull.compute(tetra, 12, 0, 0, 0), btScalar(0));
	EXPECT_EQ(hull.vertices.size() + hull.edges.size() + hull.faces.size(), 0);
	hull.compute(tetra, 12, 4, 0, 0);
	EXPECT_EQ(hull.compute(tetra, 12, -3, btScalar(0.1), 0), btScalar(0));
	EXPECT_EQ(hull.vertices.size() + hull.edges.size() + hull.faces.size(), 0);
	hull.compute(tetra, 12, 4, 0, 0);
	EXPECT_EQ(hull.compute(tetra, 8, 4, 0, 0), btScalar(0)) << "stride shorter than a point";
	EXPECT_EQ(hull.vertices.size() + hull.edges.size() + hull.faces.size(), 0);
	const double tetraD[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
	EXPECT_EQ(hull.compute(tetraD, 12, 4, 0, 0), btScalar(0)) << "double stride shorter than a point";
	EXPECT_EQ(hull.vertices.size(), 0);
}

TEST(ConvexHullComputer, NonFinitePointsAreIgnored)
{
	const float inf = INFINITY, nan = NAN;
	const float points[] = {nan, 0, 0, 0, 0, 0, 1, 0, 0, 0, inf, 0, 0, 1, 0, -inf, 5, 5, 0, 0, 1, 0.2f, 0.2f, nan};
	btConvexHullComputer hull;
	EXPECT_EQ(hull.compute(points, 12, 8, 0, 0), btScalar(0));
	EXPECT_TRUE(checkTopology(hull));
	std::vector<int> used(hull.original_vertex_index.size());
	for (int v = 0; v < hull.original_vertex_index.size(); ++v) used[v] = hull.original_vertex_index[v];
	EXPECT_EQ(used, (std::vector<int>{1, 2, 4, 6})) << describe(hull);
	EXPECT_EQ(hull.faces.size(), 4);

	const double allBad[] = {NAN, 0, 0, INFINITY, 1, 1, 0, -INFINITY, 0};
	EXPECT_EQ(hull.compute(allBad, 24, 3, 0, 0), btScalar(0));
	EXPECT_EQ(hull.vertices.size() + hull.edges.size() + hull.faces.size(), 0);
}

TEST(ConvexHullComputer, SinglePointAndDuplicatesGiveOneVertex)
{
	btConvexHullComputer hull;
	const double one[3] = {1.5, -2, 3};
	hull.compute(one, 24, 1, 0, 0);
	ASSERT_EQ(hull.vertices.size(), 1);
	EXPECT_EQ(hull.vertices[0], btVector3(btScalar(1.5), -2, 3));
	EXPECT_EQ(hull.original_vertex_index[0], 0);
	EXPECT_EQ(hull.edges.size() + hull.faces.size(), 0);

	Points same;
	for (int i = 0; i < 50; ++i) same.insert(same.end(), {1e6, -1e6, 7});
	same[0] = NAN;  // the first point is dropped, so the survivor is input point 1
	EXPECT_EQ(computeHull<float>(hull, same, 12, btScalar(0.5), 0), btScalar(0)) << "nothing to shrink";
	ASSERT_EQ(hull.vertices.size(), 1);
	EXPECT_EQ(hull.original_vertex_index[0], 1);
	EXPECT_EQ(hull.edges.size() + hull.faces.size(), 0);
}

TEST(ConvexHullComputer, CollinearPointsGiveOneEdgePairBetweenTheEnds)
{
	Points line;
	std::mt19937 rng(7);
	std::uniform_int_distribution<int> step(-40, 40);
	for (int i = 0; i < 200; ++i)
	{
		const double t = step(rng) / 8.0;  // exact in float: the points are exactly collinear
		line.insert(line.end(), {1 + 2 * t, -3 + 0.5 * t, 4 - t});
	}
	line.insert(line.end(), {1 + 2 * 6.0, -3 + 0.5 * 6.0, 4 - 6.0});     // point 200: one end
	line.insert(line.end(), {1 + 2 * -6.0, -3 + 0.5 * -6.0, 4 - -6.0});  // point 201: the other end
	btConvexHullComputer hull;
	EXPECT_EQ(computeHull<float>(hull, line, 16, btScalar(0.1), 0), btScalar(0));
	ASSERT_EQ(hull.vertices.size(), 2) << describe(hull);
	EXPECT_EQ(std::set<int>({hull.original_vertex_index[0], hull.original_vertex_index[1]}), std::set<int>({200, 201}));
	ASSERT_EQ(hull.edges.size(), 2);
	EXPECT_EQ(hull.faces.size(), 0);
	EXPECT_TRUE(checkTopology(hull));
	for (int e = 0; e < 2; ++e)
	{
		EXPECT_EQ(hull.edges[e].getNextEdgeOfVertex(), &hull.edges[e]) << "each end has one edge";
		EXPECT_EQ(hull.edges[e].getReverseEdge(), &hull.edges[1 - e]);
	}
	EXPECT_EQ(hull.edges[0].getSourceVertex(), hull.edges[1].getTargetVertex());
}

TEST(ConvexHullComputer, CoplanarPointsGiveTwoSidedPolygon)
{
	// Points of the plane x + y + z = 1 on a 1/16 grid (exact in float) inside the triangle
	// (0,0,1) (2,0,-1) (0,2,-1), plus those three corners as the last inputs.
	Points flat;
	std::mt19937 rng(11);
	std::uniform_int_distribution<int> coord(0, 32);
	for (int i = 0; i < 300; ++i)
	{
		const int a = coord(rng), b = coord(rng);
		if (a + b > 32 || (a + b) % 32 == 0) continue;  // inside or on the edges, never a corner
		flat.insert(flat.end(), {a / 16.0, b / 16.0, 1 - a / 16.0 - b / 16.0});
	}
	const int firstCorner = pointCount(flat);
	flat.insert(flat.end(), {0, 0, 1, 2, 0, -1, 0, 2, -1});
	for (int useDouble = 0; useDouble < 2; ++useDouble)
	{
		btConvexHullComputer hull;
		const btScalar applied = useDouble ? computeHull<double>(hull, flat, 32, btScalar(0.1), 0)
		                                   : computeHull<float>(hull, flat, 12, btScalar(0.1), 0);
		EXPECT_EQ(applied, btScalar(0)) << "a flat hull is not shrunk";
		EXPECT_TRUE(checkTopology(hull));
		ASSERT_EQ(hull.vertices.size(), 3) << describe(hull);
		std::set<int> corners;
		for (int v = 0; v < 3; ++v) corners.insert(hull.original_vertex_index[v]);
		EXPECT_EQ(corners, std::set<int>({firstCorner, firstCorner + 1, firstCorner + 2}));
		EXPECT_EQ(hull.edges.size(), 6);
		ASSERT_EQ(hull.faces.size(), 2);
		EXPECT_EQ(faceSizes(hull), std::vector<int>({3, 3}));
		// The two faces are the two sides: each edge of one is reversed in the other.
		const std::vector<int> front = faceEdges(hull, 0), back = faceEdges(hull, 1);
		for (int e : front) EXPECT_NE(std::find(back.begin(), back.end(), e ^ 1), back.end());
	}
}

TEST(ConvexHullComputer, FlatSquareWithInnerPointsGivesQuadrilateralFaces)
{
	Points flat = {0, 0, 5, 4, 0, 5, 4, 4, 5, 0, 4, 5};
	for (int i = 0; i <= 4; ++i)
		for (int j = 0; j <= 4; ++j) flat.insert(flat.end(), {double(i), double(j), 5});
	btConvexHullComputer hull;
	computeHull<double>(hull, flat, 24);
	EXPECT_TRUE(checkTopology(hull));
	EXPECT_EQ(hull.vertices.size(), 4) << describe(hull);
	EXPECT_EQ(faceSizes(hull), std::vector<int>({4, 4}));
	for (int v = 0; v < hull.vertices.size(); ++v) EXPECT_LT(hull.original_vertex_index[v], 4) << "earliest duplicate";
}

// ---- exact shapes -------------------------------------------------------------------------------

TEST(ConvexHullComputer, CubeWithPointsOnFacesAndEdgesGivesEightCornersAndSixQuads)
{
	const Points cube = latticeCube(1, 0);
	btConvexHullComputer hull;
	computeHull<float>(hull, cube, 12);
	expectCubeTopology(hull);
	for (int v = 0; v < hull.vertices.size(); ++v)
	{
		const btVector3& p = hull.vertices[v];
		EXPECT_EQ(fabs(p.x()) + fabs(p.y()) + fabs(p.z()), btScalar(3)) << "vertex " << v << " is not a corner";
	}
	EXPECT_TRUE(checkSolidGeometry(hull, cube, 0, true));
}

TEST(ConvexHullComputer, FacesRunCounterClockwiseAndVertexEdgesClockwiseSeenFromOutside)
{
	btConvexHullComputer hull;
	computeHull<float>(hull, latticeCube(1, 0), 12);
	ASSERT_EQ(hull.edges.size(), 24);
	for (int e = 0; e < hull.edges.size(); ++e)
	{
		const btConvexHullComputer::Edge& edge = hull.edges[e];
		const btVector3 source = hull.vertices[edge.getSourceVertex()];  // the outward direction at a cube corner
		const btVector3 along = hull.vertices[edge.getTargetVertex()] - source;
		const btConvexHullComputer::Edge* faceNext = edge.getNextEdgeOfFace();
		const btVector3 faceTurn =
		    along.cross(hull.vertices[faceNext->getTargetVertex()] - hull.vertices[faceNext->getSourceVertex()]);
		const btVector3 target = hull.vertices[edge.getTargetVertex()];
		EXPECT_GT(faceTurn.dot(target), 0) << "face of edge " << e << " turns clockwise seen from outside";
		const btConvexHullComputer::Edge* vertexNext = edge.getNextEdgeOfVertex();
		const btVector3 sweep = along.cross(hull.vertices[vertexNext->getTargetVertex()] - source);
		EXPECT_LT(sweep.dot(source), 0) << "edges around vertex of edge " << e << " turn counter-clockwise";
	}
}

TEST(ConvexHullComputer, RegularTetrahedronWithInnerPointsGivesFourTriangles)
{
	// Corners (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1), listed after points inside and on the edges.
	const double corner[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
	Points tetra;
	for (int a = 0; a < 4; ++a)
		for (int b = a + 1; b < 4; ++b)
			for (int axis = 0; axis < 3; ++axis) tetra.push_back(0.5 * (corner[a][axis] + corner[b][axis]));
	tetra.insert(tetra.end(), {0, 0, 0, 0.25, 0.25, 0.25, -0.1, 0.2, 0});
	const int firstCorner = pointCount(tetra);
	for (int a = 0; a < 4; ++a) tetra.insert(tetra.end(), corner[a], corner[a] + 3);
	btConvexHullComputer hull;
	computeHull<double>(hull, tetra, 24);
	EXPECT_TRUE(checkTopology(hull));
	ASSERT_EQ(hull.vertices.size(), 4) << describe(hull);
	for (int v = 0; v < 4; ++v) EXPECT_EQ(hull.original_vertex_index[v], firstCorner + v);
	EXPECT_EQ(hull.edges.size(), 12);
	EXPECT_EQ(faceSizes(hull), std::vector<int>(4, 3));
	EXPECT_TRUE(checkSolidGeometry(hull, tetra, 1e-12, true)) << "tolerance: double rounding of the plane fit";
}

TEST(ConvexHullComputer, LargeOffsetCubeHasTheSameTopologyAsUnitCube)
{
	// Side 1e6, offset 1e6: every coordinate is a multiple of 2.5e5 and exact in float.
	const Points cube = latticeCube(5e5, 1.5e6);
	for (int useDouble = 0; useDouble < 2; ++useDouble)
	{
		btConvexHullComputer hull;
		if (useDouble)
			computeHull<double>(hull, cube, 24);
		else
			computeHull<float>(hull, cube, 12);
		expectCubeTopology(hull);
		EXPECT_TRUE(checkSolidGeometry(hull, cube, 0, true));
	}
}

TEST(ConvexHullComputer, ScaledAndOffsetCloudGivesIdenticalHull)
{
	// Lattice coordinates times 2^20 plus 2^20 stay exact in double, so the hull must not change.
	for (Cloud kind : {Cloud::Lattice, Cloud::CubeVolume})
	{
		Points unit = makeCloud(kind, 400, 5);
		for (double& c : unit) c = floor(c * 1024) / 1024;
		Points big = unit;
		for (double& c : big) c = c * 1048576.0 + 1048576.0;
		btConvexHullComputer a, b;
		computeHull<double>(a, unit, 24);
		computeHull<double>(b, big, 24);
		EXPECT_TRUE(checkTopology(b));
		ASSERT_EQ(a.vertices.size(), b.vertices.size()) << cloudName(kind);
		ASSERT_EQ(a.edges.size(), b.edges.size()) << cloudName(kind);
		ASSERT_EQ(a.faces.size(), b.faces.size()) << cloudName(kind);
		for (int v = 0; v < a.vertices.size(); ++v)
			EXPECT_EQ(a.original_vertex_index[v], b.original_vertex_index[v]) << cloudName(kind);
		for (int e = 0; e < a.edges.size(); ++e)
		{
			EXPECT_EQ(a.edges[e].getTargetVertex(), b.edges[e].getTargetVertex());
			EXPECT_EQ(edgeIndex(a, a.edges[e].getNextEdgeOfVertex()), edgeIndex(b, b.edges[e].getNextEdgeOfVertex()));
		}
	}
}

// ---- random clouds ------------------------------------------------------------------------------

TEST(ConvexHullComputer, RandomCloudsGiveValidConvexHullsContainingEveryPoint)
{
	const int sizes[] = {4, 5, 9, 30, 150, 600, 2000};
	unsigned seed = 100;
	for (Cloud kind : {Cloud::SphereSurface, Cloud::CubeVolume, Cloud::Gaussian, Cloud::Lattice})
	{
		for (int size : sizes)
		{
			for (int variant = 0; variant < 3; ++variant)
			{
				const Points cloud = makeCloud(kind, size, ++seed);
				btConvexHullComputer hull;
				Points seen;
				// Float packed, float with odd (unaligned) stride, double with padding.
				if (variant == 0)
				{
					seen = roundedTo<float>(cloud);
					computeHull<float>(hull, cloud, 12);
				}
				else if (variant == 1)
				{
					seen = roundedTo<float>(cloud);
					computeHull<float>(hull, cloud, 13);
				}
				else
				{
					seen = cloud;
					computeHull<double>(hull, cloud, 40);
				}
				SCOPED_TRACE(::testing::Message() << cloudName(kind) << ", " << size << " points, variant " << variant
				                                  << ", seed " << seed << ": " << describe(hull));
				ASSERT_TRUE(checkTopology(hull));
				ASSERT_GE(hull.faces.size(), 4);
				ASSERT_TRUE(checkSolidGeometry(hull, seen, floatTolerance(seen), kind == Cloud::Lattice));
			}
		}
	}
}

TEST(ConvexHullComputer, PointsOnSphereAreAllVertices)
{
	// Distinct points on a sphere are all extreme: none may be lost or merged.
	const Points cloud = makeCloud(Cloud::SphereSurface, 3000, 42);
	btConvexHullComputer hull;
	computeHull<double>(hull, cloud, 24);
	EXPECT_TRUE(checkTopology(hull));
	EXPECT_EQ(hull.vertices.size(), 3000) << describe(hull);
	EXPECT_EQ(hull.faces.size(), 2 * 3000 - 4) << "a triangulated sphere: F = 2V - 4";
}

TEST(ConvexHullComputer, ResultDoesNotDependOnInputOrder)
{
	const Points cloud = makeCloud(Cloud::Lattice, 500, 77);
	std::vector<int> order(pointCount(cloud));
	for (size_t i = 0; i < order.size(); ++i) order[i] = int(i);
	std::shuffle(order.begin(), order.end(), std::mt19937(3));
	Points shuffled;
	for (int i : order) shuffled.insert(shuffled.end(), cloud.begin() + 3 * i, cloud.begin() + 3 * i + 3);
	btConvexHullComputer a, b;
	computeHull<float>(a, cloud, 12);
	computeHull<float>(b, shuffled, 12);
	std::multiset<std::vector<double>> cornersA, cornersB;
	for (int v = 0; v < a.vertices.size(); ++v)
		cornersA.insert({a.vertices[v].x(), a.vertices[v].y(), a.vertices[v].z()});
	for (int v = 0; v < b.vertices.size(); ++v)
		cornersB.insert({b.vertices[v].x(), b.vertices[v].y(), b.vertices[v].z()});
	EXPECT_EQ(cornersA, cornersB);
	EXPECT_EQ(faceSizes(a), faceSizes(b));
}

TEST(ConvexHullComputer, RepeatedComputeIsDeterministic)
{
	const Points cloud = makeCloud(Cloud::Gaussian, 700, 9);
	btConvexHullComputer a;
	computeHull<float>(a, cloud, 16);
	btConvexHullComputer b;
	computeHull<float>(b, makeCloud(Cloud::SphereSurface, 50, 1), 12);  // reused object
	computeHull<float>(b, cloud, 16);
	ASSERT_EQ(a.edges.size(), b.edges.size());
	ASSERT_EQ(a.vertices.size(), b.vertices.size());
	ASSERT_EQ(a.faces.size(), b.faces.size());
	EXPECT_EQ(memcmp(&a.edges[0], &b.edges[0], sizeof(btConvexHullComputer::Edge) * a.edges.size()), 0);
	for (int f = 0; f < a.faces.size(); ++f) EXPECT_EQ(a.faces[f], b.faces[f]);
}

// ---- shrink -------------------------------------------------------------------------------------

TEST(ConvexHullComputer, ShrinkMovesCubeFacesInwards)
{
	const Points cube = latticeCube(1, 0);
	for (int useDouble = 0; useDouble < 2; ++useDouble)
	{
		btConvexHullComputer hull;
		const btScalar applied = useDouble ? computeHull<double>(hull, cube, 24, btScalar(0.1), 0)
		                                   : computeHull<float>(hull, cube, 12, btScalar(0.1), 0);
		EXPECT_NEAR(applied, 0.1, 1e-6);
		expectCubeTopology(hull);
		// Rounding of the computed corners: a few ulps of btScalar at magnitude 1.
		for (int v = 0; v < hull.vertices.size(); ++v)
		{
			EXPECT_EQ(hull.original_vertex_index[v], -1);
			for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(fabs(hull.vertices[v][axis]), 0.9, 1e-6) << "vertex " << v;
		}
	}
}

TEST(ConvexHullComputer, ShrinkClampLimitsShrinkToFractionOfInnerRadius)
{
	// Inner radius of the cube of half extent 1 about its centroid is 1: a clamp of 0.05 allows 0.05.
	const Points cube = latticeCube(1, 0);
	btConvexHullComputer hull;
	const btScalar applied = computeHull<float>(hull, cube, 12, btScalar(0.3), btScalar(0.05));
	EXPECT_NEAR(applied, 0.05, 1e-6);
	expectCubeTopology(hull);
	for (int v = 0; v < hull.vertices.size(); ++v)
		for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(fabs(hull.vertices[v][axis]), 0.95, 1e-6);

	// A clamp above the request changes nothing; shrink <= 0 shrinks nothing.
	EXPECT_NEAR(computeHull<float>(hull, cube, 12, btScalar(0.2), btScalar(0.5)), 0.2, 1e-6);
	EXPECT_EQ(computeHull<float>(hull, cube, 12, btScalar(0), btScalar(0.5)), btScalar(0));
	EXPECT_EQ(computeHull<float>(hull, cube, 12, btScalar(-1), 0), btScalar(0));
	EXPECT_EQ(hull.original_vertex_index[0], 0) << "plain hull keeps input vertices";
}

TEST(ConvexHullComputer, ShrinkReachingInnerRadiusKeepsPlainHull)
{
	const Points cube = latticeCube(1, 0);
	btConvexHullComputer hull;
	EXPECT_EQ(computeHull<float>(hull, cube, 12, btScalar(1.0), 0), btScalar(0));
	expectCubeTopology(hull);
	for (int v = 0; v < hull.vertices.size(); ++v) EXPECT_GE(hull.original_vertex_index[v], 0);
	EXPECT_EQ(computeHull<float>(hull, cube, 12, btScalar(2.0), btScalar(3.0)), btScalar(0));
	EXPECT_EQ(hull.vertices.size(), 8);
}

TEST(ConvexHullComputer, ShrunkRandomHullIsInsideByShrinkDistance)
{
	for (Cloud kind : {Cloud::SphereSurface, Cloud::CubeVolume, Cloud::Gaussian})
	{
		const Points cloud = roundedTo<float>(makeCloud(kind, 300, 21));
		btConvexHullComputer plain, shrunk;
		computeHull<float>(plain, cloud, 12);
		const btScalar applied = computeHull<float>(shrunk, cloud, 12, btScalar(0.05), 0);
		SCOPED_TRACE(::testing::Message() << cloudName(kind) << ": " << describe(shrunk));
		EXPECT_NEAR(applied, 0.05, 1e-6);
		EXPECT_TRUE(checkTopology(shrunk));
		ASSERT_GE(shrunk.faces.size(), 4);
		// Every shrunk corner is at least `applied` inside every face of the plain hull, and is exactly
		// `applied` inside some face; tolerance: float rounding of the corners (magnitude <= 4).
		std::vector<V3> plainPosition;
		for (int v = 0; v < plain.vertices.size(); ++v)
			plainPosition.push_back(pointOf(cloud, plain.original_vertex_index[v]));
		std::vector<FacePlane> planes;
		for (int f = 0; f < plain.faces.size(); ++f) planes.push_back(facePlane(plain, plainPosition, f));
		const double tolerance = 1e-5;
		for (int v = 0; v < shrunk.vertices.size(); ++v)
		{
			const btVector3& p = shrunk.vertices[v];
			const V3 q{p.x(), p.y(), p.z()};
			double deepest = -DBL_MAX;
			for (const FacePlane& plane : planes) deepest = std::max(deepest, dot(plane.normal, q) - plane.offset);
			EXPECT_NEAR(deepest, -applied, tolerance) << "vertex " << v;
		}
	}
}

TEST(ConvexHullComputer, ExtremeAndNearlyDegenerateCloudsKeepValidTopology)
{
	// Magnitudes near the double limits, mixed scales per axis and slabs thinner than the grid step:
	// the topology must stay a valid closed surface (or a valid lower-dimensional result).
	struct Case
	{
		const char* name;
		double scale[3];
		double offset;
	};
	const Case cases[] = {
	    {"huge", {1e300, 1e300, 1e300}, 0},    {"near max", {8e307, 8e307, 8e307}, 8e307},
	    {"tiny", {1e-300, 1e-300, 1e-300}, 0}, {"subnormal", {1e-310, 1e-310, 1e-310}, 0},
	    {"needle", {1, 1e-12, 1e-12}, 0},      {"slab", {1, 1, 1e-7}, 0},
	    {"thin slab", {1, 1, 1e-11}, 0},       {"offset slab", {1, 1, 1e-6}, 1e3},
	    {"mixed", {1e200, 1, 1e-200}, 0},
	};
	for (const Case& c : cases)
	{
		Points cloud = makeCloud(Cloud::Gaussian, 400, 31);
		for (size_t i = 0; i < cloud.size(); ++i) cloud[i] = cloud[i] * c.scale[i % 3] + c.offset;
		btConvexHullComputer hull;
		computeHull<double>(hull, cloud, 24);
		SCOPED_TRACE(::testing::Message() << c.name << ": " << describe(hull));
		EXPECT_TRUE(checkTopology(hull));
		EXPECT_GE(hull.vertices.size(), 1);
		for (int v = 0; v < hull.vertices.size(); ++v)
		{
			const int i = hull.original_vertex_index[v];
			ASSERT_TRUE(i >= 0 && i < pointCount(cloud));
			EXPECT_EQ(hull.vertices[v],
			          btVector3(btScalar(cloud[3 * i]), btScalar(cloud[3 * i + 1]), btScalar(cloud[3 * i + 2])));
		}
		computeHull<double>(hull, cloud, 24, btScalar(0.01), btScalar(0.5));  // shrink must not break either
		EXPECT_TRUE(checkTopology(hull));
	}
}
