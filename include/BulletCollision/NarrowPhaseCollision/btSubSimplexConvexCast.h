// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SUBSIMPLEX_CONVEX_CAST_H
#define BT_SUBSIMPLEX_CONVEX_CAST_H

/// btSubsimplexConvexCast: time of impact of two translating convex shapes by a GJK ray cast.

#include "BulletCollision/NarrowPhaseCollision/btConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"

class btConvexShape;

/// Casts the ray along the relative motion against the Minkowski difference A - B (margins included),
/// advancing to GJK support planes (van den Bergen's GJK ray cast). Linear motion only: the rotations
/// of toA and toB are ignored (the bases of fromA and fromB are used). The hit fraction is a lower
/// bound on the exact one, with the shapes within sqrt(m_subSimplexCastEpsilon) of each other;
/// m_allowedPenetration is not used. Null shapes or solver and non-finite transforms assert and
/// return false.
class btSubsimplexConvexCast : public btConvexCast
{
	btSimplexSolverInterface* m_simplexSolver;
	const btConvexShape* m_convexA;
	const btConvexShape* m_convexB;

public:
	/// Shapes and solver are not owned.
	btSubsimplexConvexCast(const btConvexShape* shapeA, const btConvexShape* shapeB,
	                       btSimplexSolverInterface* simplexSolver);

	/// See btConvexCast::calcTimeOfImpact.
	bool calcTimeOfImpact(const btTransform& fromA, const btTransform& toA, const btTransform& fromB,
	                      const btTransform& toB, CastResult& result) override;
};

#endif  // BT_SUBSIMPLEX_CONVEX_CAST_H
