// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Hierarchical convex decomposition by plane splits (docs/extras.md, "Convex decomposition"):
//   1. check and weld the mesh; it must be closed; turn it outwards if it is wound inwards;
//   2. start with one piece, the whole solid; its concavity is hull volume minus solid volume;
//   3. while the pieces' total concavity exceeds the tolerance and there are fewer than maxHulls pieces,
//      split the most concave piece by the axis-aligned plane (among evenly spaced ones and the piece's
//      vertex coordinates) that leaves the least concavity in its two halves;
//   4. each piece's hull is the hull of its points that belong to the solid.
// Volumes are exact (closed triangle soups, TriangleSoup.h); hull points are the surface's points in the
// piece plus the cap points a generalized winding number places inside the solid.
#include "ConvexDecomposition/ConvexDecomposition.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "HullShapes/MarginHullShape.h"
#include "LinearMath/btConvexHullComputer.h"
#include "TriangleSoup.h"

namespace caliber
{
using decomposition::cross;
using decomposition::dot;
using decomposition::SoupTriangle;
using decomposition::TriangleSoup;
using decomposition::Vec3;

namespace
{
const double kMaxCoordinate = 1e15;
const double kPi = 3.14159265358979323846;

// Hull volume and centroid of points (double), 0 for a flat or tiny set.
double hullVolumeOf(const std::vector<Vec3>& points, Vec3* centroid, btConvexHullComputer& hull)
{
	if (points.size() < 4) return 0;
	hull.compute(&points[0].x, int(sizeof(Vec3)), int(points.size()), 0, 0);
	if (hull.faces.size() < 4) return 0;
	const btVector3 origin = hull.vertices[0];
	double sixVolume = 0;
	Vec3 weighted = {0, 0, 0};
	for (int f = 0; f < hull.faces.size(); ++f)
	{
		const btConvexHullComputer::Edge* first = &hull.edges[hull.faces[f]];
		const btVector3 a = hull.vertices[first->getSourceVertex()] - origin;
		for (const btConvexHullComputer::Edge* e = first->getNextEdgeOfFace();
		     e->getTargetVertex() != first->getSourceVertex(); e = e->getNextEdgeOfFace())
		{
			const btVector3 b = hull.vertices[e->getSourceVertex()] - origin;
			const btVector3 c = hull.vertices[e->getTargetVertex()] - origin;
			const double six = double(a.dot(b.cross(c)));
			sixVolume += six;
			const btVector3 sum = a + b + c;  // tetrahedron (0, a, b, c): centroid (a + b + c) / 4
			weighted = weighted + Vec3{double(sum.x()), double(sum.y()), double(sum.z())} * (six / 4);
		}
	}
	if (!(sixVolume > 0)) return 0;
	if (centroid)
		*centroid = Vec3{double(origin.x()), double(origin.y()), double(origin.z())} + weighted * (1.0 / sixVolume);
	return sixVolume / 6;
}

// The checked, welded, outward mesh, centred on its bounding box for accurate volume sums.
struct SolidMesh
{
	std::vector<Vec3> vertices;
	std::vector<int> triangles;  // three per triangle
	Vec3 centre;
	double volume = 0;
	double size = 0;  // bounding-box diagonal

	// Generalized winding number: 1 inside, 1/2 on the surface, 0 outside (van Oosterom and Strackee's
	// solid angle of each triangle, summed, over 4 pi).
	double windingNumber(const Vec3& point) const
	{
		double total = 0;
		for (std::size_t t = 0; t < triangles.size(); t += 3)
		{
			const Vec3 a = vertices[triangles[t]] - point, b = vertices[triangles[t + 1]] - point,
			           c = vertices[triangles[t + 2]] - point;
			const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
			const double numerator = dot(a, cross(b, c));
			const double denominator = la * lb * lc + dot(a, b) * lc + dot(b, c) * la + dot(c, a) * lb;
			total += 2 * std::atan2(numerator, denominator);
		}
		return total / (4 * kPi);
	}
};

std::uint64_t edgeKey(int from, int to) { return (std::uint64_t(std::uint32_t(from)) << 32) | std::uint32_t(to); }

bool prepareMesh(const btVector3* vertices, int numVertices, const int* indices, int numIndices, SolidMesh& mesh,
                 ConvexDecompositionResult& result)
{
	if (numIndices % 3 != 0 || numIndices < 12)
	{
		result.error =
		    "the mesh needs at least 4 triangles (3 indices each); got " + std::to_string(numIndices) + " indices";
		return false;
	}
	Vec3 lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
	for (int i = 0; i < numVertices; ++i)
	{
		const btVector3& v = vertices[i];
		for (int axis = 0; axis < 3; ++axis)
		{
			if (!std::isfinite(double(v[axis])) || std::fabs(double(v[axis])) > kMaxCoordinate)
			{
				result.error = "vertex " + std::to_string(i) + " has a non-finite or huge (beyond 1e15) coordinate";
				return false;
			}
		}
		lo = {std::min(lo.x, double(v.x())), std::min(lo.y, double(v.y())), std::min(lo.z, double(v.z()))};
		hi = {std::max(hi.x, double(v.x())), std::max(hi.y, double(v.y())), std::max(hi.z, double(v.z()))};
	}
	for (int i = 0; i < numIndices; ++i)
	{
		if (indices[i] < 0 || indices[i] >= numVertices)
		{
			result.error = "index " + std::to_string(i) + " (" + std::to_string(indices[i]) + ") is out of range (" +
			               std::to_string(numVertices) + " vertices)";
			return false;
		}
	}
	mesh.centre = (lo + hi) * 0.5;
	mesh.size = std::sqrt(dot(hi - lo, hi - lo));
	// Weld vertices at the same position: meshes often repeat a corner for each face (normals, uvs).
	struct PositionHash
	{
		std::size_t operator()(const btVector3& v) const
		{
			std::hash<double> h;
			return h(double(v.x())) ^ (h(double(v.y())) * 31) ^ (h(double(v.z())) * 1009);
		}
	};
	struct PositionEqual
	{
		bool operator()(const btVector3& a, const btVector3& b) const
		{
			return a.x() == b.x() && a.y() == b.y() && a.z() == b.z();
		}
	};
	std::unordered_map<btVector3, int, PositionHash, PositionEqual> weld;
	std::vector<int> welded(numVertices);
	for (int i = 0; i < numVertices; ++i)
	{
		auto inserted = weld.emplace(vertices[i], int(mesh.vertices.size()));
		if (inserted.second)
			mesh.vertices.push_back(Vec3{double(vertices[i].x()), double(vertices[i].y()), double(vertices[i].z())} -
			                        mesh.centre);
		welded[i] = inserted.first->second;
	}
	if (int(mesh.vertices.size()) < numVertices)
		result.warnings.push_back(std::to_string(numVertices - int(mesh.vertices.size())) +
		                          " duplicate vertices welded");
	int degenerate = 0;
	for (int t = 0; t < numIndices; t += 3)
	{
		const int a = welded[indices[t]], b = welded[indices[t + 1]], c = welded[indices[t + 2]];
		if (a == b || b == c || c == a)
		{
			++degenerate;  // no area; its edges are not counted either
			continue;
		}
		mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
	}
	if (degenerate) result.warnings.push_back(std::to_string(degenerate) + " degenerate triangles dropped");
	// Closed and manifold: every directed edge once, with its reverse once.
	std::unordered_map<std::uint64_t, int> edges;
	for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
		for (int i = 0; i < 3; ++i) ++edges[edgeKey(mesh.triangles[t + i], mesh.triangles[t + (i + 1) % 3])];
	int open = 0;
	for (const auto& edge : edges)
	{
		const int from = int(edge.first >> 32), to = int(edge.first & 0xffffffffu);
		const auto reverse = edges.find(edgeKey(to, from));
		if (edge.second != 1 || reverse == edges.end() || reverse->second != 1) ++open;
	}
	if (open)
	{
		result.error = "the mesh is not closed: " + std::to_string(open) +
		               " edges are not shared by exactly two triangles in opposite directions";
		return false;
	}
	double sixVolume = 0;
	for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
		sixVolume += dot(mesh.vertices[mesh.triangles[t]],
		                 cross(mesh.vertices[mesh.triangles[t + 1]], mesh.vertices[mesh.triangles[t + 2]]));
	mesh.volume = sixVolume / 6;
	if (!(std::fabs(mesh.volume) > 1e-9 * mesh.size * mesh.size * mesh.size))
	{
		result.error = "the mesh encloses no volume";
		return false;
	}
	if (mesh.volume < 0)
	{
		for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
			std::swap(mesh.triangles[t + 1], mesh.triangles[t + 2]);
		mesh.volume = -mesh.volume;
		result.warnings.push_back("the mesh was wound inwards; its triangles were turned");
	}
	return true;
}

struct Piece
{
	TriangleSoup soup;
	double volume = 0;
	double hullVolume = 0;
	Vec3 hullCentroid = {0, 0, 0};
	std::vector<Vec3> hullVertices;
	bool splittable = true;

	double concavity() const { return std::max(0.0, hullVolume - volume); }
};

// Points of the soup known to be in the solid; with exact, also the others the winding number puts in it.
// Each point once: a corner is shared by about six triangles, and the hull's cost grows with its input.
void solidPoints(const TriangleSoup& soup, const SolidMesh* exact, std::vector<Vec3>& points, std::vector<Vec3>& maybe)
{
	points.clear();
	maybe.clear();
	for (const SoupTriangle& t : soup)
		for (const auto& corner : t.corner) (corner.onSolid ? points : maybe).push_back(corner.position);
	const auto less = [](const Vec3& a, const Vec3& b)
	{ return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z); };
	const auto same = [](const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
	std::sort(points.begin(), points.end(), less);
	points.erase(std::unique(points.begin(), points.end(), same), points.end());
	if (!exact) return;
	std::sort(maybe.begin(), maybe.end(), less);
	maybe.erase(std::unique(maybe.begin(), maybe.end(), same), maybe.end());
	for (const Vec3& p : maybe)
		if (exact->windingNumber(p) > 0.25) points.push_back(p);
}

class Decomposer
{
public:
	Decomposer(const SolidMesh& mesh, const ConvexDecompositionParameters& parameters)
	    : m_mesh(mesh), m_parameters(parameters)
	{
	}

	std::vector<Piece> run()
	{
		std::vector<Piece> pieces(1);
		for (std::size_t t = 0; t < m_mesh.triangles.size(); t += 3)
		{
			SoupTriangle triangle;
			triangle.cap = false;
			for (int i = 0; i < 3; ++i) triangle.corner[i] = {m_mesh.vertices[m_mesh.triangles[t + i]], true};
			pieces[0].soup.push_back(triangle);
		}
		finishPiece(pieces[0]);
		const double allowed = m_parameters.concavityTolerance * m_mesh.volume;
		while (int(pieces.size()) < m_parameters.maxHulls)
		{
			double total = 0;
			int worst = -1;
			for (std::size_t i = 0; i < pieces.size(); ++i)
			{
				total += pieces[i].concavity();
				if (pieces[i].splittable && (worst < 0 || pieces[i].concavity() > pieces[worst].concavity()))
					worst = int(i);
			}
			if (total <= allowed || worst < 0) break;
			Piece below, above;
			if (!bestSplit(pieces[worst], below, above))
			{
				pieces[worst].splittable = false;
				continue;
			}
			pieces[worst] = std::move(below);
			pieces.push_back(std::move(above));
		}
		return pieces;
	}

private:
	// Exact volume, hull and centroid of a piece.
	void finishPiece(Piece& piece)
	{
		piece.volume = decomposition::soupVolume(piece.soup);
		solidPoints(piece.soup, &m_mesh, m_points, m_maybe);
		piece.hullVolume = hullVolumeOf(m_points, &piece.hullCentroid, m_hull);
		piece.hullVertices.clear();
		if (piece.hullVolume > 0)
			for (int i = 0; i < m_hull.vertices.size(); ++i)
				piece.hullVertices.push_back(Vec3{double(m_hull.vertices[i].x()), double(m_hull.vertices[i].y()),
				                                  double(m_hull.vertices[i].z())});
	}

	// Quick estimate of a half's concavity from the points known to be in the solid.
	double estimateConcavity(const TriangleSoup& soup, double volume)
	{
		solidPoints(soup, nullptr, m_points, m_maybe);
		return std::max(0.0, hullVolumeOf(m_points, nullptr, m_hull) - volume);
	}

	void candidatePlanes(const Piece& piece, int axis, std::vector<double>& offsets) const
	{
		offsets.clear();
		double lo = HUGE_VAL, hi = -HUGE_VAL;
		std::vector<double> coordinates;
		for (const SoupTriangle& t : piece.soup)
			for (const auto& corner : t.corner)
			{
				const double c = decomposition::component(corner.position, axis);
				lo = std::min(lo, c);
				hi = std::max(hi, c);
				if (!t.cap) coordinates.push_back(c);
			}
		const double extent = hi - lo;
		if (!(extent > 1e-9 * m_mesh.size)) return;
		// Planes never pass exactly through vertices: a face lying in the plane would go to one half
		// whole, and its corners would count as points of a half it only touches. Cutting just beside a
		// coordinate instead costs a sliver of 1e-5 of the piece's extent.
		const double nudge = 1e-5 * extent;
		const int count = m_parameters.planesPerAxis;
		for (int k = 0; k < count; ++k) offsets.push_back(lo + extent * (k + 0.5) / count + 0.618 * nudge);
		// The surface's own coordinates (the inner corner of an L, the floor of a cup), thinned to count,
		// each tried on both sides.
		std::sort(coordinates.begin(), coordinates.end());
		coordinates.erase(std::unique(coordinates.begin(), coordinates.end()), coordinates.end());
		const std::size_t step = std::max<std::size_t>(1, coordinates.size() / std::size_t(count));
		for (std::size_t i = 0; i < coordinates.size(); i += step)
		{
			if (!(coordinates[i] > lo + 1e-3 * extent && coordinates[i] < hi - 1e-3 * extent)) continue;
			offsets.push_back(coordinates[i] - nudge);
			offsets.push_back(coordinates[i] + nudge);
		}
	}

	// Among the planes whose halves leave nearly the least concavity (within a tenth of the piece's own, or of
	// the tolerated total if that is less),
	// the one that halves the piece's volume most evenly. Evenness matters when no single cut helps much:
	// a ring cut anywhere through its hole leaves nearly the same total hull, and shaving pieces off its
	// rim costs many hulls, while halves, then quarters, do shrink it.
	bool bestSplit(const Piece& piece, Piece& below, Piece& above)
	{
		const double minimumVolume = 1e-4 * m_mesh.volume;  // no slivers
		struct Candidate
		{
			Vec3 normal;
			double offset, concavity, imbalance;
		};
		std::vector<Candidate> candidates;
		std::vector<double> offsets;
		double leastConcavity = HUGE_VAL;
		for (int axis = 0; axis < 3; ++axis)
		{
			const Vec3 normal = {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
			candidatePlanes(piece, axis, offsets);
			for (double offset : offsets)
			{
				decomposition::splitSoup(piece.soup, normal, offset, m_below, m_above);
				const double volumeBelow = decomposition::soupVolume(m_below);
				const double volumeAbove = decomposition::soupVolume(m_above);
				if (volumeBelow < minimumVolume || volumeAbove < minimumVolume) continue;
				const double concavity =
				    estimateConcavity(m_below, volumeBelow) + estimateConcavity(m_above, volumeAbove);
				candidates.push_back({normal, offset, concavity, std::fabs(volumeBelow - volumeAbove)});
				leastConcavity = std::min(leastConcavity, concavity);
			}
		}
		const double slack =
		    0.1 * std::min(piece.concavity(), m_parameters.concavityTolerance * m_mesh.volume) + 1e-9 * m_mesh.volume;
		const Candidate* best = nullptr;
		for (const Candidate& candidate : candidates)
			if (candidate.concavity <= leastConcavity + slack && (!best || candidate.imbalance < best->imbalance))
				best = &candidate;
		const bool found = best != nullptr;
		const Vec3 bestNormal = found ? best->normal : Vec3{0, 0, 0};
		const double bestOffset = found ? best->offset : 0;
		if (!found) return false;
		decomposition::splitSoup(piece.soup, bestNormal, bestOffset, below.soup, above.soup);
		finishPiece(below);
		finishPiece(above);
		return true;
	}

	const SolidMesh& m_mesh;
	const ConvexDecompositionParameters& m_parameters;
	std::vector<Vec3> m_points, m_maybe;
	btConvexHullComputer m_hull;
	TriangleSoup m_below, m_above;
};
}  // namespace

bool decomposeConvex(const btVector3* vertices, int numVertices, const int* indices, int numIndices,
                     const ConvexDecompositionParameters& parameters, ConvexDecompositionResult& result)
{
	result = ConvexDecompositionResult();
	if (parameters.maxHulls < 1 || !(parameters.concavityTolerance >= 0) || parameters.planesPerAxis < 1 ||
	    parameters.planesPerAxis > 256)
	{
		btAssert(!"decomposeConvex: maxHulls < 1, a negative or NaN tolerance, or planesPerAxis outside 1..256");
		result.error = "bad parameters: maxHulls must be at least 1, the tolerance non-negative, planesPerAxis 1..256";
		return false;
	}
	if ((!vertices && numVertices != 0) || (!indices && numIndices != 0) || numVertices < 0 || numIndices < 0)
	{
		btAssert(!"decomposeConvex: null arrays with non-zero counts, or negative counts");
		result.error = "null arrays with non-zero counts, or negative counts";
		return false;
	}
	SolidMesh mesh;
	if (!prepareMesh(vertices, numVertices, indices, numIndices, mesh, result)) return false;

	Decomposer decomposer(mesh, parameters);
	const std::vector<Piece> pieces = decomposer.run();
	result.meshVolume = mesh.volume;
	double concavity = 0;
	for (const Piece& piece : pieces)
	{
		if (piece.hullVertices.empty()) continue;  // a piece too thin to have a hull (cannot happen for the root)
		ConvexDecompositionHull hull;
		for (const Vec3& v : piece.hullVertices)
		{
			const Vec3 p = v + mesh.centre;
			hull.vertices.push_back(btVector3(btScalar(p.x), btScalar(p.y), btScalar(p.z)));
		}
		const Vec3 c = piece.hullCentroid + mesh.centre;
		hull.centroid = btVector3(btScalar(c.x), btScalar(c.y), btScalar(c.z));
		hull.volume = piece.hullVolume;
		hull.meshVolume = piece.volume;
		result.hullVolume += piece.hullVolume;
		concavity += piece.concavity();
		result.hulls.push_back(hull);
	}
	result.withinTolerance = concavity <= parameters.concavityTolerance * mesh.volume;
	if (result.hulls.empty()) result.error = "no hull could be built";
	return result.ok();
}

double convexHullVolume(const btAlignedObjectArray<btVector3>& points, btVector3* centroid)
{
	std::vector<Vec3> copy;
	for (int i = 0; i < points.size(); ++i)
		copy.push_back(Vec3{double(points[i].x()), double(points[i].y()), double(points[i].z())});
	btConvexHullComputer hull;
	Vec3 c = {0, 0, 0};
	const double volume = hullVolumeOf(copy, &c, hull);
	if (centroid) *centroid = btVector3(btScalar(c.x), btScalar(c.y), btScalar(c.z));
	return volume;
}

DecompositionShape buildDecompositionShape(const ConvexDecompositionResult& result)
{
	DecompositionShape shape;
	if (result.hulls.empty()) return shape;
	shape.compound.reset(new btCompoundShape(true, int(result.hulls.size())));
	for (const ConvexDecompositionHull& hull : result.hulls)
	{
		btAlignedObjectArray<btVector3> local;
		for (int i = 0; i < hull.vertices.size(); ++i) local.push_back(hull.vertices[i] - hull.centroid);
		std::unique_ptr<btConvexHullShape> child = makeMarginHullShape(local);
		if (!child) continue;  // cannot happen: every hull of the result has volume
		btTransform place;
		place.setIdentity();
		place.setOrigin(hull.centroid);
		shape.compound->addChildShape(place, child.get());
		shape.hulls.push_back(std::move(child));
	}
	return shape;
}
}  // namespace caliber
