// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CONVEX_HULL_INTERNAL_H
#define CALIBER_CONVEX_HULL_INTERNAL_H

// Internal to btConvexHullComputer. The hull is found in two steps:
//   computeHullTopology (ConvexHullExact.cpp): which points are corners and which corners bound
//     which face, decided exactly on an integer grid;
//   buildHalfEdges (btConvexHullComputer.cpp): turns the faces into Bullet's half-edge arrays.

#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
namespace hull
{
/// The hull of a point set as corners and faces; every index refers to the point list it was
/// computed from.
struct HullTopology
{
	/// -1 no points, 0 a single point, 1 a segment, 2 a flat polygon, 3 a solid.
	int dimension = -1;
	/// The hull's corners, ascending.
	btAlignedObjectArray<int> vertices;
	/// Face f is faceVertices[faceStart[f]] .. faceVertices[faceStart[f + 1] - 1], counter-clockwise
	/// seen from outside. faceStart holds faceCount() + 1 entries (none when there are no faces).
	btAlignedObjectArray<int> faceStart;
	btAlignedObjectArray<int> faceVertices;

	/// Number of faces.
	int faceCount() const { return faceStart.size() > 0 ? faceStart.size() - 1 : 0; }
	/// Empties the topology (dimension -1).
	void clear()
	{
		dimension = -1;
		vertices.clear();
		faceStart.clear();
		faceVertices.clear();
	}
};

/// Exact convex hull of count points stored as x, y, z doubles, all finite. Returns false, with an
/// empty topology, only if an internal consistency check failed (exact predicates rule that out).
bool computeHullTopology(const double* xyz, int count, HullTopology& topology);

}  // namespace hull
}  // namespace caliber

#endif  // CALIBER_CONVEX_HULL_INTERNAL_H
