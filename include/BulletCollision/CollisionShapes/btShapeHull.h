// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SHAPE_HULL_H
#define BT_SHAPE_HULL_H

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "LinearMath/btAlignedObjectArray.h"

/// A triangle mesh approximating a convex shape (for drawing, or to turn any convex shape into a
/// btConvexHullShape): the convex hull of the shape's support points (with margin) in a fixed set of
/// directions plus the shape's preferred penetration directions. See docs/collision-shapes-and-narrowphase.md
/// ("btShapeHull").
ATTRIBUTE_ALIGNED16(class)
btShapeHull
{
protected:
	/// The hull's corners.
	btAlignedObjectArray<btVector3> m_vertices;
	/// Three indices into m_vertices per triangle, counter-clockwise seen from outside.
	btAlignedObjectArray<unsigned int> m_indices;
	/// Number of entries in m_indices.
	unsigned int m_numIndices;
	/// The shape sampled by buildHull (not owned).
	const btConvexShape* m_shape;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A hull builder for shape (not owned; must outlive buildHull calls). The hull starts empty.
	btShapeHull(const btConvexShape* shape);
	/// Frees the mesh.
	~btShapeHull();

	/// Rebuilds the mesh: 42 sample directions, or 162 when highres is non-zero. margin is unused (kept for
	/// Bullet compatibility; the support points already include the shape's margin). Returns false, with an
	/// empty mesh, for a null shape or when the support points span no volume (a point, a segment, a flat
	/// shape).
	bool buildHull(btScalar margin, int highres = 0);

	/// Number of triangles (numIndices() / 3).
	int numTriangles() const;
	/// Number of hull vertices.
	int numVertices() const;
	/// Number of triangle indices.
	int numIndices() const;

	/// The hull vertices (null when the hull is empty).
	const btVector3* getVertexPointer() const { return m_vertices.size() ? &m_vertices[0] : 0; }
	/// The triangle indices (null when the hull is empty).
	const unsigned int* getIndexPointer() const { return m_indices.size() ? &m_indices[0] : 0; }
};

#endif  // BT_SHAPE_HULL_H
