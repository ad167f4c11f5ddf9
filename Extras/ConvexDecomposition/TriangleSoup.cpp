// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "TriangleSoup.h"

namespace caliber
{
namespace decomposition
{
namespace
{
bool lexicographicallyLess(const Vec3& a, const Vec3& b)
{
	if (a.x != b.x) return a.x < b.x;
	if (a.y != b.y) return a.y < b.y;
	return a.z < b.z;
}

// Where the edge (a, b) crosses the plane. Computed from the lexicographically smaller end, so the two
// triangles sharing an edge get bit-identical points and the caps close exactly.
SoupVertex crossing(const SoupVertex& a, double da, const SoupVertex& b, double db, bool onSolid)
{
	const bool swap = lexicographicallyLess(b.position, a.position);
	const Vec3& p = swap ? b.position : a.position;
	const Vec3& q = swap ? a.position : b.position;
	const double dp = swap ? db : da, dq = swap ? da : db;
	const double t = dp / (dp - dq);
	return {p + (q - p) * t, onSolid};
}

void appendFan(const std::vector<SoupVertex>& polygon, bool cap, TriangleSoup& out)
{
	for (std::size_t i = 1; i + 1 < polygon.size(); ++i) out.push_back({{polygon[0], polygon[i], polygon[i + 1]}, cap});
}

// A cut segment, wound as the cap below the plane needs it.
struct Segment
{
	SoupVertex from, to;
};

void appendCap(const std::vector<Segment>& segments, bool forBelow, TriangleSoup& out)
{
	if (segments.empty()) return;
	const SoupVertex& apex = segments[0].from;
	for (const Segment& s : segments)
	{
		if (forBelow)
			out.push_back({{apex, s.from, s.to}, true});
		else
			out.push_back({{apex, s.to, s.from}, true});
	}
}
}  // namespace

double soupVolume(const TriangleSoup& soup)
{
	double sixTimes = 0;
	for (const SoupTriangle& t : soup)
		sixTimes += dot(t.corner[0].position, cross(t.corner[1].position, t.corner[2].position));
	return sixTimes / 6;
}

void splitSoup(const TriangleSoup& soup, const Vec3& normal, double offset, TriangleSoup& below, TriangleSoup& above)
{
	below.clear();
	above.clear();
	std::vector<Segment> segments;
	std::vector<SoupVertex> belowPolygon, abovePolygon;
	for (const SoupTriangle& triangle : soup)
	{
		double distance[3];
		bool isBelow[3];
		int belowCount = 0;
		for (int i = 0; i < 3; ++i)
		{
			distance[i] = dot(normal, triangle.corner[i].position) - offset;
			isBelow[i] = distance[i] < 0;
			belowCount += isBelow[i];
		}
		if (belowCount == 3)
		{
			below.push_back(triangle);
			continue;
		}
		if (belowCount == 0)
		{
			above.push_back(triangle);
			continue;
		}
		belowPolygon.clear();
		abovePolygon.clear();
		SoupVertex exitPoint = {}, enterPoint = {};  // leaving and re-entering the part below
		for (int i = 0; i < 3; ++i)
		{
			const int j = (i + 1) % 3;
			const SoupVertex& a = triangle.corner[i];
			(isBelow[i] ? belowPolygon : abovePolygon).push_back(a);
			if (isBelow[i] == isBelow[j]) continue;
			// A surface triangle's cut point is on the surface; a cap triangle's may be off the solid.
			const SoupVertex x = crossing(a, distance[i], triangle.corner[j], distance[j], !triangle.cap);
			belowPolygon.push_back(x);
			abovePolygon.push_back(x);
			if (isBelow[i])
				exitPoint = x;
			else
				enterPoint = x;
		}
		appendFan(belowPolygon, triangle.cap, below);
		appendFan(abovePolygon, triangle.cap, above);
		// The part below has the edge exit -> enter on the plane; its cap needs enter -> exit.
		segments.push_back({enterPoint, exitPoint});
	}
	appendCap(segments, true, below);
	appendCap(segments, false, above);
}
}  // namespace decomposition
}  // namespace caliber
