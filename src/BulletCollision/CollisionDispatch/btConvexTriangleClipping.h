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
/// deeper than those. Writes their indices to chosen in order around the patch (first, left, farthest,
/// right: the solver's order, see the .cpp) and returns how many.
int chooseManifoldPoints(const btVector3* points, const btScalar* distances, int count, const btVector3& normal,
                         int chosen[4]);

/// How the mesh algorithms find a convex's face over a triangle (see triangleFaceContact).
enum TriangleClipping
{
	kNoClipping,     // GJK's point per triangle (spheres, cones, ...; capsules have their own closed form)
	kClipBeforeGjk,  // boxes: the lowest point and the face in closed form, before GJK, which most triangles skip
	kClipAfterGjk    // hulls and polyhedra: settled before GJK only when the face search along the triangle's
	                 // normal needs no GJK (hullTriangleFaceContactBeforeGjk), else by GJK's normal
};

/// The clipping the mesh algorithms give a convex shape: boxes before GJK; btConvexHullShape (its face from
/// its points) and every other polyhedral shape with a btConvexPolyhedron (initializePolyhedralFeatures;
/// its face from the polyhedron's faces) after GJK.
TriangleClipping triangleClippingOf(const btCollisionShape& convex);

/// True when the mesh algorithms clip the convex's face against triangles (its points then wait in the
/// mesh collector, which keeps the best 4).
inline bool clipsAgainstMeshTriangles(const btCollisionShape& convex)
{
	return triangleClippingOf(convex) != kNoClipping;
}

/// A mesh triangle in world space: its corners and the unnormalised normal of their winding.
struct WorldTriangle
{
	btVector3 corners[3];
	btVector3 windingNormal;  // (c1 - c0) x (c2 - c0), twice the area long
	btScalar normalLength2;
};

/// Fills `world` from the triangle and its transform; false for a sliver (its cross product is mostly
/// rounding: GJK's point is better there) or non-finite corners.
bool worldTriangleOf(const btTriangleShape& triangle, const btTransform& transform, WorldTriangle& world);

enum TriangleFaceOutcome
{
	kTriangleOutOfReach,        // the face normal separates them by more than reach: nothing to report
	kTriangleFaceContact,       // the face's points are reported and are the whole contact
	kTriangleFacePointsAndGjk,  // face points reported, but the convex's lowest point is beyond an edge
	kTriangleNeedsGjk           // nothing reported: the contact is at an edge or a vertex, or deep
};

/// The contact of a box or convex hull with a triangle, found along the triangle's normal (turned towards
/// the convex's centre) without GJK: the convex's face most opposed to the normal (a box's face; a
/// polyhedron's face, also tilted; a hull's vertices near its supporting plane, two of them for an edge;
/// the last two moved out by the margin) is clipped against the triangle's prism,
/// and its points within reach of the plane are reported to out with the triangle's normal (at most 4,
/// spanning the largest area). The outcome says whether GJK must still look at the pair.
TriangleFaceOutcome triangleFaceContact(const btConvexShape& convex, const btTransform& convexTransform,
                                        const btTriangleShape& triangle, const btTransform& triangleTransform,
                                        btScalar reach, btDiscreteCollisionDetectorInterface::Result& out);

/// The face search along a triangle's normal (triangleFaceContact's), done once before GJK and kept for
/// the search along GJK's normal, which asks the same one when GJK's normal is not the face's.
struct TriangleFaceSearch : public btDiscreteCollisionDetectorInterface::Result
{
	bool done = false;  // world, outcome and points hold the search
	WorldTriangle world;  // the triangle in world space (found once for both searches)
	TriangleFaceOutcome outcome = kTriangleNeedsGjk;
	int count = 0;  // at most 4 points a triangle
	btVector3 normals[4], points[4];
	btScalar distances[4];

	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3& normal, const btVector3& point, btScalar distance) override
	{
		if (count == 4) return;
		normals[count] = normal;
		points[count] = point;
		distances[count] = distance;
		++count;
	}
	/// Reports the kept points to out.
	void replay(btDiscreteCollisionDetectorInterface::Result& out) const
	{
		for (int i = 0; i < count; ++i) out.addContactPoint(normals[i], points[i], distances[i]);
	}
};

/// triangleFaceContact for a hull (kClipAfterGjk) before GJK, deciding only what needs no GJK: the hull's
/// lowest point along the triangle's normal is out of reach (kTriangleOutOfReach, a separating axis), or it
/// lies over the triangle's face, where the face normal is the closest direction and the clipped face the
/// whole contact (its points reported, kTriangleFaceContact). Otherwise kTriangleNeedsGjk, reporting nothing
/// (the search is kept in `search` for triangleFaceContactAlongGjkNormal): GJK and that decide as before.
TriangleFaceOutcome hullTriangleFaceContactBeforeGjk(const btConvexShape& convex, const btTransform& convexTransform,
                                                     const btTriangleShape& triangle,
                                                     const btTransform& triangleTransform, btScalar reach,
                                                     btDiscreteCollisionDetectorInterface::Result& out,
                                                     TriangleFaceSearch& search);

/// triangleFaceContact for a hull after GJK, by gjkNormal (GJK's, from the triangle towards the convex, any
/// length). When it is the triangle's face normal on either side to within about 2.5 degrees (GJK's
/// tolerance for a convex resting on a face): triangleFaceContact. When it is instead the normal of one
/// of the convex's faces (the face lies on the triangle's edge or vertex): the triangle clipped against
/// that face, its points within `touching` (the breaking threshold: resting contacts, not speculative
/// ones; asked only when gjkDistance is within it) reported with the face's normal, kTriangleFaceContact
/// (GJK's point is one of them). Otherwise, when the pair closes in (reach beyond twice `touching`): the
/// convex's face points over the triangle along its face normal (a face overhanging the triangle it landed
/// on) and kTriangleFacePointsAndGjk, or kTriangleNeedsGjk when there are none; at rest kTriangleNeedsGjk.
/// A zero or non-finite normal: kTriangleNeedsGjk, reporting nothing. `before`, when not null and done,
/// is the search along the triangle's normal made before GJK with the same reach: it is used, not redone.
TriangleFaceOutcome triangleFaceContactAlongGjkNormal(const btConvexShape& convex, const btTransform& convexTransform,
                                                      const btTriangleShape& triangle,
                                                      const btTransform& triangleTransform, btScalar reach,
                                                      const btVector3& gjkNormal, btScalar gjkDistance,
                                                      btScalar touching,
                                                      btDiscreteCollisionDetectorInterface::Result& out,
                                                      const TriangleFaceSearch* before = 0);
}  // namespace caliber

#endif  // CALIBER_CONVEX_TRIANGLE_CLIPPING_H
