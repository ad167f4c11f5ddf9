// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GEOMETRY_UTIL_H
#define BT_GEOMETRY_UTIL_H

/// Conversions between a convex polytope's vertices and its face planes, and point/plane tests.
///
/// A plane is a btVector3 whose x, y, z hold the normal n and whose 4th component ([3], getW/setW)
/// holds the offset d: points p on the plane satisfy n.p + d = 0, and n points out of the solid, so
/// "inside" means n.p + d <= 0. Normals are expected to be unit length; margins are then distances.
/// The two conversions treat distances below 1e-5 of the shape's size as zero (points that close to
/// a plane lie on it), and cost O(n^4) in the number of vertices or planes: they are meant for shapes
/// of tens of points, built once.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

/// Static helpers for convex polytopes given by vertices or by outward face planes.
class btGeometryUtil
{
public:
	/// Appends to planeEquationsOut the unit-normal face planes of the convex hull of vertices, one
	/// per face, each touching its outermost vertex. Fewer than 3 non-collinear vertices, or any
	/// non-finite coordinate, give no plane; a flat set gives its two sides.
	static void getPlaneEquationsFromVertices(btAlignedObjectArray<btVector3>& vertices,
	                                          btAlignedObjectArray<btVector3>& planeEquationsOut);

	/// Appends to verticesOut the corners of the polytope bounded by planeEquations (each corner once).
	/// An unbounded set of planes gives only the corners it has, possibly none.
	static void getVerticesFromPlaneEquations(const btAlignedObjectArray<btVector3>& planeEquations,
	                                          btAlignedObjectArray<btVector3>& verticesOut);

	/// True when every vertex lies inside the plane planeNormal, allowing margin beyond it (the same
	/// test as areVerticesBehindPlane).
	static bool isInside(const btAlignedObjectArray<btVector3>& vertices, const btVector3& planeNormal,
	                     btScalar margin);

	/// True when point lies inside every plane, allowing margin beyond each (n.p + d <= margin).
	static bool isPointInsidePlanes(const btAlignedObjectArray<btVector3>& planeEquations, const btVector3& point,
	                                btScalar margin);

	/// True when every vertex lies inside planeNormal, allowing margin beyond it (n.v + d <= margin).
	static bool areVerticesBehindPlane(const btVector3& planeNormal, const btAlignedObjectArray<btVector3>& vertices,
	                                   btScalar margin);
};

#endif  // BT_GEOMETRY_UTIL_H
