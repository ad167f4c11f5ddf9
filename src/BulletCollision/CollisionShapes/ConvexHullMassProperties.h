// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CONVEX_HULL_MASS_PROPERTIES_H
#define CALIBER_CONVEX_HULL_MASS_PROPERTIES_H

// Internal helpers of the polyhedral shapes: a btConvexPolyhedron from a point cloud, and the exact
// inertia of a solid convex polyhedron. Not installed; users reach them through the shapes.

#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"

class btConvexShape;

namespace caliber
{
/// Builds poly (vertices, faces with planes, unique edges, bounds) from the convex hull of count
/// points; non-finite points are ignored. Returns true when the hull has at least one face (solid,
/// or flat with its two sides); otherwise poly is left empty (no vertices, no faces).
bool buildConvexPolyhedron(const btVector3* points, int count, btConvexPolyhedron& poly);

/// Diagonal of the inertia tensor of the solid polyhedron of uniform density and total mass,
/// about its centre of volume, in the polyhedron's axes. Returns false (inertia untouched) when the
/// polyhedron has no positive volume.
bool solidPolyhedronInertia(const btConvexPolyhedron& poly, btScalar mass, btVector3& inertia);

/// Solid inertia (as above) of the convex hull of count points; false when the hull has no volume.
bool solidHullInertia(const btVector3* points, int count, btScalar mass, btVector3& inertia);

/// Number of directions sampledSupportInertia uses (a Fibonacci sphere).
const int kInertiaSampleDirections = 400;

/// Approximate solid inertia of a convex shape with margin: the exact inertia (as above) of the hull of
/// its support points (localGetSupportingVertex) along kInertiaSampleDirections directions spread
/// evenly over the sphere. That polytope is inscribed in the shape; for a sphere its faces lie about
/// 0.5% of the radius inside. Returns false when the hull has no volume.
bool sampledSupportInertia(const btConvexShape& shape, btScalar mass, btVector3& inertia);

/// Bullet's fallback: the solid box of the shape's local AABB (margin included), I = m (b^2 + c^2) / 12.
void aabbBoxInertia(const btConvexShape& shape, btScalar mass, btVector3& inertia);
}  // namespace caliber

#endif  // CALIBER_CONVEX_HULL_MASS_PROPERTIES_H
