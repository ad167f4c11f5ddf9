// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "ObjLoader/PolygonTriangulation.h"

#include <cmath>
#include <vector>

namespace caliber
{
namespace
{
struct Point2
{
	double x, y;
};

double cross2(const Point2& a, const Point2& b, const Point2& c)
{
	return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Inside or on the boundary of the counter-clockwise triangle abc.
bool insideTriangle(const Point2& p, const Point2& a, const Point2& b, const Point2& c)
{
	return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}
}  // namespace

void triangulatePolygon(const btVector3* points, int count, btAlignedObjectArray<int>& trianglesOut)
{
	if (!points || count < 3) return;
	if (count == 3)
	{
		trianglesOut.push_back(0);
		trianglesOut.push_back(1);
		trianglesOut.push_back(2);
		return;
	}
	// Newell's normal: robust for non-planar and concave polygons; its sign gives the winding.
	double normal[3] = {0, 0, 0};
	for (int i = 0; i < count; ++i)
	{
		const btVector3& a = points[i];
		const btVector3& b = points[(i + 1) % count];
		normal[0] += (double(a.y()) - b.y()) * (double(a.z()) + b.z());
		normal[1] += (double(a.z()) - b.z()) * (double(a.x()) + b.x());
		normal[2] += (double(a.x()) - b.x()) * (double(a.y()) + b.y());
	}
	// Project onto the plane of the two axes the normal is least aligned with; flip one axis so that
	// the projected polygon is counter-clockwise.
	int drop = 0;
	if (std::fabs(normal[1]) > std::fabs(normal[drop])) drop = 1;
	if (std::fabs(normal[2]) > std::fabs(normal[drop])) drop = 2;
	const int u = (drop + 1) % 3, v = (drop + 2) % 3;
	const double flip = normal[drop] < 0 ? -1.0 : 1.0;
	btAlignedObjectArray<Point2> flat;
	flat.resize(count);
	std::vector<int> remaining(count);  // polygon order matters, so an ordered erase
	for (int i = 0; i < count; ++i)
	{
		flat[i].x = points[i][u];
		flat[i].y = flip * points[i][v];
		remaining[i] = i;
	}
	while (remaining.size() > 3u)
	{
		const int n = int(remaining.size());
		int bestEar = -1;
		int leastBadCorner = 0;
		double leastBadArea = -HUGE_VAL;
		for (int k = 0; k < n && bestEar < 0; ++k)
		{
			const int ip = remaining[(k + n - 1) % n], ic = remaining[k], in = remaining[(k + 1) % n];
			const double area = cross2(flat[ip], flat[ic], flat[in]);
			if (area > leastBadArea)
			{
				leastBadArea = area;
				leastBadCorner = k;
			}
			if (area <= 0) continue;  // reflex or flat corner: not an ear
			bool empty = true;
			for (int j = 0; j < n && empty; ++j)
			{
				const int other = remaining[j];
				if (other == ip || other == ic || other == in) continue;
				const Point2& p = flat[other];
				const bool isCorner = (p.x == flat[ip].x && p.y == flat[ip].y) ||
				                      (p.x == flat[ic].x && p.y == flat[ic].y) ||
				                      (p.x == flat[in].x && p.y == flat[in].y);
				if (!isCorner && insideTriangle(p, flat[ip], flat[ic], flat[in])) empty = false;
			}
			if (empty) bestEar = k;
		}
		// No proper ear (self-intersecting, degenerate or numerically flat polygon): cut the most convex
		// corner anyway, so the result always has count - 2 triangles.
		const int k = bestEar >= 0 ? bestEar : leastBadCorner;
		trianglesOut.push_back(remaining[(k + n - 1) % n]);
		trianglesOut.push_back(remaining[k]);
		trianglesOut.push_back(remaining[(k + 1) % n]);
		remaining.erase(remaining.begin() + k);
	}
	trianglesOut.push_back(remaining[0]);
	trianglesOut.push_back(remaining[1]);
	trianglesOut.push_back(remaining[2]);
}
}  // namespace caliber
