// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_POLYHEDRAL_CONTACT_CLIPPING_H
#define BT_POLYHEDRAL_CONTACT_CLIPPING_H

/// btPolyhedralContactClipping: separating-axis test and face clipping between two btConvexPolyhedron,
/// giving a contact manifold (several points) instead of GJK's single point.
///
/// Convention: the separating normal points from hull B towards hull A (it is the "normal on B" of
/// btDiscreteCollisionDetectorInterface::Result). Moving A by depth * normal separates the hulls.
/// Reported points lie on B; the depth is their signed distance to A's reference face plane (negative
/// when penetrating).

#include "BulletCollision/CollisionShapes/btConvexPolyhedron.h"
#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"
#include "LinearMath/btAlignedObjectArray.h"

/// A polygon (or a point list) in world space; callers pass two to reuse their storage between queries.
typedef btAlignedObjectArray<btVector3> btVertexArray;

/// Candidate separating axes offered to findSeparatingAxis since start-up (diagnostic counter).
extern int gExpectedNbTests;
/// Candidate axes findSeparatingAxis actually projected: parallel edge pairs and axes on which the hulls'
/// inner sphere or box already overlap more than the best axis so far are skipped (diagnostic counter).
extern int gActualNbTests;

/// Static functions of the polyhedral contact generation (SAT + Sutherland-Hodgman clipping).
struct btPolyhedralContactClipping
{
	/// Picks the face of B most aligned with separatingNormal1 (B towards A) and clips it against A with
	/// clipFaceAgainstHull. A zero or non-finite normal or transform asserts and reports nothing.
	static void clipHullAgainstHull(const btVector3& separatingNormal1, const btConvexPolyhedron& hullA,
	                                const btConvexPolyhedron& hullB, const btTransform& transA,
	                                const btTransform& transB, const btScalar minDist, btScalar maxDist,
	                                btVertexArray& worldVertsB1, btVertexArray& worldVertsB2,
	                                btDiscreteCollisionDetectorInterface::Result& resultOut);

	/// Clips the world polygon worldVertsB1 (a face of B) against the side planes of A's face most
	/// opposed to separatingNormal, then reports each remaining vertex whose distance to that face plane
	/// is at most maxDist. Distances below minDist (a lower bound on the penetration, such as the SAT
	/// depth) are reported as minDist. worldVertsB2 is scratch; worldVertsB1 is overwritten.
	static void clipFaceAgainstHull(const btVector3& separatingNormal, const btConvexPolyhedron& hullA,
	                                const btTransform& transA, btVertexArray& worldVertsB1, btVertexArray& worldVertsB2,
	                                const btScalar minDist, btScalar maxDist,
	                                btDiscreteCollisionDetectorInterface::Result& resultOut);

	/// Separating-axis test over the face normals of A, then of B, then the cross products of their
	/// unique edges (for larger hulls: of the edge pairs whose Gauss-map arcs cross). Returns false when some axis
	/// separates the hulls; otherwise true with sep the unit axis of least overlap, pointing from B towards A. Face
	/// axes win ties (an edge axis must be smaller by a small tolerance). When an edge pair wins, its closest point on
	/// B is reported to resultOut with the negative overlap as depth. Hulls without faces or vertices, or non-finite
	/// transforms, assert and return false.
	static bool findSeparatingAxis(const btConvexPolyhedron& hullA, const btConvexPolyhedron& hullB,
	                               const btTransform& transA, const btTransform& transB, btVector3& sep,
	                               btDiscreteCollisionDetectorInterface::Result& resultOut);

	/// Sutherland-Hodgman step: appends to ppVtxOut the part of the closed polygon pVtxIn that lies
	/// behind the plane (planeNormalWS . x + planeEqWS <= 0). The arrays must differ.
	static void clipFace(const btVertexArray& pVtxIn, btVertexArray& ppVtxOut, const btVector3& planeNormalWS,
	                     btScalar planeEqWS);
};

#endif  // BT_POLYHEDRAL_CONTACT_CLIPPING_H
