// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef GRAHAM_SCAN_2D_CONVEX_HULL_H
#define GRAHAM_SCAN_2D_CONVEX_HULL_H

/// GrahamScanConvexHull2D: the convex polygon around 3D points projected onto a plane (Graham's scan).
///
/// The plane is the one perpendicular to normalAxis; its in-plane axes come from btPlaneSpace1, so the
/// output polygon is counter-clockwise about normalAxis, starting near the point with the smallest first
/// plane coordinate. Despite the name (kept from Bullet's API) the hull is found by 2D quickhull: the
/// farthest point outside an edge is always a vertex, so no rounded sort order (angles or coordinates
/// of nearly collinear points) can misplace a vertex. Expected O(n log n).
/// btAngleCompareFunc is kept for code that sorts GrahamVector3s by angle itself.
///
/// Conventions:
/// - The hull holds copies of input points (with their m_orgIndex), never computed points.
/// - Points on a hull edge (collinear within rounding) are dropped; collinear input gives its two end
///   points, and input whose points all project to one point gives that one point.
/// - Points that project to the same plane point count as one.
/// - Fewer than 3 input points are copied to the hull unchanged.
/// - Points with a non-finite projection are ignored. A zero or non-finite normalAxis is taken as z.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

/// A point for GrahamScanConvexHull2D: the point, an index the caller chooses and a sort angle.
struct GrahamVector3 : public btVector3
{
	/// The point org, tagged with orgIndex (returned unchanged with the hull).
	GrahamVector3(const btVector3& org, int orgIndex) : btVector3(org), m_angle(0), m_orgIndex(orgIndex) {}

	/// An angle in radians, the sort key of btAngleCompareFunc (the scan neither reads nor sets it).
	btScalar m_angle;
	/// The caller's index for this point.
	int m_orgIndex;
};

/// Orders GrahamVector3s by m_angle, then by distance from the anchor (nearer first), then by m_orgIndex.
struct btAngleCompareFunc
{
	/// The point the angles are measured about.
	btVector3 m_anchor;

	/// A comparator for angles measured about anchor.
	btAngleCompareFunc(const btVector3& anchor) : m_anchor(anchor) {}

	/// True when a comes before b.
	bool operator()(const GrahamVector3& a, const GrahamVector3& b) const
	{
		if (a.m_angle != b.m_angle) return a.m_angle < b.m_angle;
		const btScalar distanceA = a.distance2(m_anchor);
		const btScalar distanceB = b.distance2(m_anchor);
		if (distanceA != distanceB) return distanceA < distanceB;
		return a.m_orgIndex < b.m_orgIndex;
	}
};

/// Replaces hull with the convex polygon of originalPoints projected onto the plane perpendicular to
/// normalAxis, counter-clockwise about normalAxis (see the conventions at the top of this header).
inline void GrahamScanConvexHull2D(btAlignedObjectArray<GrahamVector3>& originalPoints,
                                   btAlignedObjectArray<GrahamVector3>& hull, const btVector3& normalAxis)
{
	hull.clear();
	const int count = originalPoints.size();
	if (count < 3)
	{
		for (int i = 0; i < count; ++i) hull.push_back(originalPoints[i]);
		return;
	}

	btVector3 normal = normalAxis;
	const btScalar normalLength2 = normal.length2();
	if (normalLength2 > btScalar(0) && normalLength2 <= SIMD_INFINITY)
		normal /= btSqrt(normalLength2);
	else
		normal.setValue(0, 0, 1);
	btVector3 axis0, axis1;
	btPlaneSpace1(normal, axis0, axis1);

	// Origin of the plane coordinates: the first point with finite coordinates.
	int anchorIndex = -1;
	for (int i = 0; i < count && anchorIndex < 0; ++i)
	{
		const btVector3& p = originalPoints[i];
		if (btIsFinite(p.x()) && btIsFinite(p.y()) && btIsFinite(p.z())) anchorIndex = i;
	}
	if (anchorIndex < 0) return;  // no finite point

	// Plane coordinates relative to the anchor, computed from the 3D difference: the difference of two
	// nearby points is exact, so the coordinates carry rounding of the cloud's size, not of its distance
	// from the origin. Each point's btVector3 part holds (x, y, 0) and m_orgIndex its input position.
	const btVector3 anchor = originalPoints[anchorIndex];
	btAlignedObjectArray<GrahamVector3> planar;
	planar.reserve(count);
	btScalar extent = 0;
	for (int i = 0; i < count; ++i)
	{
		const btVector3 offset = originalPoints[i] - anchor;
		const btScalar x = offset.dot(axis0);
		const btScalar y = offset.dot(axis1);
		if (!btIsFinite(x) || !btIsFinite(y)) continue;
		GrahamVector3 point(btVector3(x, y, 0), i);
		planar.push_back(point);
		extent = btMax(extent, btMax(btFabs(x), btFabs(y)));
	}
	// A point s is outside the directed edge p -> q (the hull is on the left of its edges) when the
	// cross product is below minus the rounding of the coordinates (a few SIMD_EPSILON times extent
	// each) times the edge lengths; points within that band count as on the edge and are dropped.
	const btScalar turnTolerance = btScalar(8) * SIMD_EPSILON * extent;
	auto outside = [turnTolerance](const btVector3& p, const btVector3& q, const btVector3& s)
	{
		const btScalar e1x = q.x() - p.x(), e1y = q.y() - p.y();
		const btScalar e2x = s.x() - p.x(), e2y = s.y() - p.y();
		const btScalar size = btMax(btFabs(e1x), btFabs(e1y)) + btMax(btFabs(e2x), btFabs(e2y));
		return e1x * e2y - e1y * e2x < -turnTolerance * size;
	};
	auto height = [](const btVector3& p, const btVector3& q, const btVector3& s)
	{ return (q.x() - p.x()) * (p.y() - s.y()) - (q.y() - p.y()) * (p.x() - s.x()); };

	// Quickhull's divide and conquer, which never depends on a rounded sort order: the farthest
	// point outside an edge is always a hull vertex. Start from the extreme points in x.
	int left = 0, right = 0;
	for (int i = 1; i < planar.size(); ++i)
	{
		if (planar[i].x() < planar[left].x() || (planar[i].x() == planar[left].x() && planar[i].y() < planar[left].y()))
			left = i;
		if (planar[i].x() > planar[right].x() ||
		    (planar[i].x() == planar[right].x() && planar[i].y() > planar[right].y()))
			right = i;
	}
	btAlignedObjectArray<GrahamVector3> polygon;
	polygon.push_back(planar[left]);
	if (planar[right].x() != planar[left].x() || planar[right].y() != planar[left].y())
	{
		// Work items: an edge (p, q) with its outside points in candidates[begin, end), or (end < 0)
		// the vertex p to emit. Processed last in, first out, so vertices come out in order.
		struct Task
		{
			int p, q, begin, end;
		};
		btAlignedObjectArray<int> candidates;
		candidates.reserve(2 * planar.size());
		const GrahamVector3& l = planar[left];
		const GrahamVector3& r = planar[right];
		for (int i = 0; i < planar.size(); ++i)
			if (outside(l, r, planar[i])) candidates.push_back(i);
		const int lowerEnd = candidates.size();
		for (int i = 0; i < planar.size(); ++i)
			if (outside(r, l, planar[i])) candidates.push_back(i);
		btAlignedObjectArray<Task> tasks;
		tasks.push_back(Task{right, left, lowerEnd, candidates.size()});
		tasks.push_back(Task{right, -1, 0, -1});
		tasks.push_back(Task{left, right, 0, lowerEnd});
		while (tasks.size() > 0)
		{
			const Task task = tasks[tasks.size() - 1];
			tasks.pop_back();
			if (task.end < 0)
			{
				polygon.push_back(planar[task.p]);
				continue;
			}
			if (task.begin == task.end) continue;
			const GrahamVector3& p = planar[task.p];
			const GrahamVector3& q = planar[task.q];
			int farthest = candidates[task.begin];
			btScalar farthestHeight = height(p, q, planar[farthest]);
			for (int k = task.begin + 1; k < task.end; ++k)
			{
				const btScalar h = height(p, q, planar[candidates[k]]);
				if (h > farthestHeight)
				{
					farthestHeight = h;
					farthest = candidates[k];
				}
			}
			// Partition in place: outside p -> farthest first, then outside farthest -> q; the rest are
			// inside the triangle and dropped.
			const GrahamVector3& f = planar[farthest];
			int middle = task.begin;
			for (int k = task.begin; k < task.end; ++k)
				if (candidates[k] != farthest && outside(p, f, planar[candidates[k]]))
				{
					const int swapped = candidates[middle];
					candidates[middle++] = candidates[k];
					candidates[k] = swapped;
				}
			int last = middle;
			for (int k = middle; k < task.end; ++k)
				if (candidates[k] != farthest && outside(f, q, planar[candidates[k]]))
				{
					const int swapped = candidates[last];
					candidates[last++] = candidates[k];
					candidates[k] = swapped;
				}
			tasks.push_back(Task{farthest, task.q, middle, last});
			tasks.push_back(Task{farthest, -1, 0, -1});
			tasks.push_back(Task{task.p, farthest, task.begin, middle});
		}
	}

	// The extreme points in x may lie on an edge when rounding ties them with their neighbours: drop
	// every vertex that is not a strict left turn, until none is left.
	auto leftTurn = [&outside](const btVector3& a, const btVector3& b, const btVector3& c)
	{ return outside(a, c, b) && !outside(a, b, c) && !outside(b, c, a); };
	bool removed = true;
	while (removed && polygon.size() >= 3)
	{
		removed = false;
		for (int i = 0; i < polygon.size() && polygon.size() >= 3; ++i)
		{
			const int n = polygon.size();
			if (!leftTurn(polygon[(i + n - 1) % n], polygon[i], polygon[(i + 1) % n]))
			{
				for (int k = i; k + 1 < n; ++k) polygon[k] = polygon[k + 1];
				polygon.pop_back();
				removed = true;
			}
		}
	}

	hull.reserve(polygon.size());
	for (int i = 0; i < polygon.size(); ++i) hull.push_back(originalPoints[polygon[i].m_orgIndex]);
}

#endif  // GRAHAM_SCAN_2D_CONVEX_HULL_H
