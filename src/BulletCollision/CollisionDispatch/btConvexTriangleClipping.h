// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CONVEX_TRIANGLE_CLIPPING_H
#define CALIBER_CONVEX_TRIANGLE_CLIPPING_H

// A whole face manifold for a box or convex hull over a triangle's face, found without GJK: the convex's
// face most opposed to the triangle normal is clipped against the triangle's prism. Internal.

#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"
#include "LinearMath/btTransform.h"

namespace caliber
{
/// Picks at most 4 of count points for a manifold: the one farthest from their centre, the farthest from
/// it, then the farthest on either side of the line through both (seen along normal), which spans the
/// largest area the points offer; the deepest (smallest distance) replaces the last when it is clearly
/// deeper than those. Writes their indices to chosen (a fixed order) and returns how many.
int chooseManifoldPoints(const btVector3* points, const btScalar* distances, int count, const btVector3& normal,
                         int chosen[4]);

/// True for the convex shapes the mesh algorithms clip against triangles: boxes. triangleFaceContact
/// takes convex hulls too, but a hull's face costs a scan of its points per triangle, and clipping hulls
/// cost about 4 % of the barrel benchmark (convex_mesh) for barrels that mostly lie on an edge; hulls get
/// GJK's point per triangle and the collector's internal-edge filter.
inline bool clipsAgainstMeshTriangles(int shapeType) { return shapeType == BOX_SHAPE_PROXYTYPE; }

enum TriangleFaceOutcome
{
	kTriangleOutOfReach,        // the face normal separates them by more than reach: nothing to report
	kTriangleFaceContact,       // the face's points are reported and are the whole contact
	kTriangleFacePointsAndGjk,  // face points reported, but the convex's lowest point is beyond an edge
	kTriangleNeedsGjk           // nothing reported: the contact is at an edge or a vertex, or deep
};

/// The contact of a box or convex hull with a triangle, found along the triangle's normal (turned towards
/// the convex's centre) without GJK: the convex's face most opposed to the normal (a box's face; a hull's
/// vertices near its supporting plane, moved out by its margin) is clipped against the triangle's prism,
/// and its points within reach of the plane are reported to out with the triangle's normal (at most 4,
/// spanning the largest area). The outcome says whether GJK must still look at the pair.
TriangleFaceOutcome triangleFaceContact(const btConvexShape& convex, const btTransform& convexTransform,
                                        const btTriangleShape& triangle, const btTransform& triangleTransform,
                                        btScalar reach, btDiscreteCollisionDetectorInterface::Result& out);
}  // namespace caliber

#endif  // CALIBER_CONVEX_TRIANGLE_CLIPPING_H
