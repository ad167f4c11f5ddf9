// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_HULL_COMPUTER_H
#define BT_CONVEX_HULL_COMPUTER_H

/// btConvexHullComputer: the convex hull of a point cloud as vertices, half-edges and polygon faces.
///
/// Decisions (which points are corners, which are coplanar) are exact: coordinates are snapped to an
/// integer grid of 2^30 steps across the cloud's largest bounding-box side and every orientation test
/// is done in 64/128-bit integers. So duplicate, collinear and coplanar points never break the
/// topology, and a cloud scaled or offset by any amount gives the same hull. Points closer together
/// than one grid step (about 1e-9 of the cloud's size) count as the same point.
///
/// Result conventions:
/// - Hull vertices are input points, copied unchanged (converted to btScalar); a point that lies on
///   an edge or inside a face of the hull is not a vertex. Vertices are in ascending input order,
///   and the whole result is deterministic.
/// - Faces are maximal planar convex polygons, counter-clockwise seen from outside.
/// - Every edge is stored together with its reverse, in adjacent slots (2k and 2k + 1).
///
/// Degenerate input (every case leaves the arrays consistent; nothing asserts or crashes):
/// - coords null, count <= 0, or stride smaller than three coordinates: empty result, returns 0.
/// - points with a NaN or infinite coordinate are ignored (treated as absent, not as an error);
///   if no finite point remains the result is empty.
/// - one point, or only duplicates of one point: 1 vertex, no edges, no faces.
/// - collinear points: the 2 extreme points, one edge pair between them (each edge is its own
///   next-edge-of-vertex), no faces.
/// - coplanar points: the flat convex polygon; its edges in both directions and 2 faces: faces[0]
///   walks the polygon one way, faces[1] the other way, so each face is counter-clockwise seen from
///   its own side. Euler's V - E/2 + F = 2 holds for it as for a solid.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

/// Computes the convex hull of a point cloud, optionally shrunk inwards by a margin.
class btConvexHullComputer
{
private:
	// Shared body of the two public overloads: coords holds doubles if doubleCoords, else floats.
	btScalar compute(const void* coords, bool doubleCoords, int stride, int count, btScalar shrink,
	                 btScalar shrinkClamp);

public:
	/// A directed hull edge. Edges live in btConvexHullComputer::edges and refer to one another by
	/// relative offsets, so an Edge is only meaningful inside that array.
	class Edge
	{
	private:
		int next;          // offset to the next edge around the source vertex
		int reverse;       // offset to the reverse edge
		int targetVertex;  // index into btConvexHullComputer::vertices

		friend class btConvexHullComputer;

	public:
		/// Index of the vertex this edge starts from.
		int getSourceVertex() const { return (this + reverse)->targetVertex; }

		/// Index of the vertex this edge points to.
		int getTargetVertex() const { return targetVertex; }

		/// Next edge with the same source vertex. Following it visits all edges of the vertex, in
		/// clockwise order seen from outside the hull (counter-clockwise seen from inside); that is the
		/// order which makes getNextEdgeOfFace() walk faces counter-clockwise seen from outside.
		const Edge* getNextEdgeOfVertex() const { return this + next; }

		/// Next edge of the face on this edge's left (seen from outside): the faces are walked
		/// counter-clockwise seen from outside.
		const Edge* getNextEdgeOfFace() const { return (this + reverse)->getNextEdgeOfVertex(); }

		/// The same edge in the opposite direction.
		const Edge* getReverseEdge() const { return this + reverse; }
	};

	/// Hull vertices (input points; computed points after a shrink).
	btAlignedObjectArray<btVector3> vertices;

	/// For each hull vertex, the index of the input point it is; -1 for the computed vertices of a
	/// shrunk hull.
	btAlignedObjectArray<int> original_vertex_index;

	/// All hull edges, each with its reverse in the adjacent slot.
	btAlignedObjectArray<Edge> edges;

	/// One edge index per face; the face is that edge and the edges that follow it by
	/// getNextEdgeOfFace().
	btAlignedObjectArray<int> faces;

	/// Computes the hull of count points read from coords, stride bytes apart (at least
	/// 3 * sizeof(float)). Replaces any previous result.
	///
	/// If shrink > 0 and the hull is a solid, every face plane is moved inwards by shrink and the
	/// result is the hull of the moved planes (its vertices are then computed points, with
	/// original_vertex_index -1). The inner radius is the smallest distance from the hull's centroid
	/// (centre of volume) to a face plane; if shrinkClamp > 0 the shrink is limited to
	/// shrinkClamp * innerRadius. If the (clamped) shrink is not smaller than the inner radius, or the
	/// hull is flat, a segment or a point, nothing is shrunk and the plain hull is returned.
	///
	/// Returns the shrink actually applied: 0 when shrink <= 0 or nothing could be shrunk.
	btScalar compute(const float* coords, int stride, int count, btScalar shrink, btScalar shrinkClamp)
	{
		return compute(static_cast<const void*>(coords), false, stride, count, shrink, shrinkClamp);
	}

	/// Same as the float overload for double coordinates; stride is at least 3 * sizeof(double).
	btScalar compute(const double* coords, int stride, int count, btScalar shrink, btScalar shrinkClamp)
	{
		return compute(static_cast<const void*>(coords), true, stride, count, shrink, shrinkClamp);
	}
};

#endif  // BT_CONVEX_HULL_COMPUTER_H
