// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_POLYHEDRON_H
#define BT_CONVEX_POLYHEDRON_H

/// btFace and btConvexPolyhedron: the vertex/face/edge description of a convex polytope that the
/// polyhedral contact clipping works on (built by btPolyhedralConvexShape::initializePolyhedralFeatures).

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btTransform.h"

/// One polygon face: vertex indices counter-clockwise seen from outside, and its plane.
struct btFace
{
	/// Indices into btConvexPolyhedron::m_vertices, counter-clockwise seen from outside.
	btAlignedObjectArray<int> m_indices;
	/// Plane (nx, ny, nz, d): unit outward normal n, points p on the face satisfy n.p + d = 0.
	btScalar m_plane[4];
};

/// A convex polytope: vertices, polygon faces with planes, unique edge directions and a few bounds.
ATTRIBUTE_ALIGNED16(class)
btConvexPolyhedron
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An empty polyhedron (no vertices, no faces, zero bounds).
	btConvexPolyhedron();
	/// Virtual so that users may derive, as in Bullet.
	virtual ~btConvexPolyhedron();

	/// Vertices, in the shape's local frame.
	btAlignedObjectArray<btVector3> m_vertices;
	/// Faces with their planes.
	btAlignedObjectArray<btFace> m_faces;
	/// Edge directions, unit length, one per direction up to sign (for SAT edge-edge axes).
	btAlignedObjectArray<btVector3> m_uniqueEdges;

	/// Centre of volume (of area for a flat polyhedron, of the vertices for fewer than one face).
	btVector3 m_localCenter;
	/// Half extents of a box centred at m_localCenter that lies inside the polyhedron.
	btVector3 m_extents;
	/// Radius of a sphere centred at m_localCenter that lies inside (distance to the closest face plane).
	btScalar m_radius;
	/// Centre of the vertices' bounding box.
	btVector3 mC;
	/// Half extents of the vertices' bounding box.
	btVector3 mE;

	/// Fills m_uniqueEdges from the faces, then calls initialize2().
	void initialize();
	/// Computes m_localCenter, m_radius, mC, mE and m_extents from m_vertices and m_faces. Faces with
	/// fewer than 3 indices or with an index out of range are skipped (btAssert in assert builds).
	void initialize2();
	/// True when the 8 corners of the box m_localCenter +- m_extents are behind or on every face plane.
	bool testContainment() const;
	/// Projects the polyhedron, placed by trans, on dir: minProj/maxProj are the extreme values of
	/// dir.(trans * v) over the vertices and the witnesses the world vertices that reach them. With no
	/// vertices (btAssert in assert builds) both projections are dir.origin and both witnesses the origin.
	void project(const btTransform& trans, const btVector3& dir, btScalar& minProj, btScalar& maxProj,
	             btVector3& witnesPtMin, btVector3& witnesPtMax) const;
};

#endif  // BT_CONVEX_POLYHEDRON_H
