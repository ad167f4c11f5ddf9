// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GJK_CONVEX_CAST_H
#define BT_GJK_CONVEX_CAST_H

/// btGjkConvexCast: time of impact of two translating convex shapes by conservative advancement.

#include "BulletCollision/NarrowPhaseCollision/btConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"

class btConvexShape;

/// Conservative advancement with btGjkPairDetector distances (margins included, EPA for overlaps):
/// each step moves by distance / approach speed along the normal, which never passes the first
/// contact. Linear motion only (the bases of fromA and fromB are used). Stops when the distance plus
/// m_allowedPenetration is within the cast tolerance (see docs). Null shapes or solver and non-finite
/// transforms assert and return false.
class btGjkConvexCast : public btConvexCast
{
	btSimplexSolverInterface* m_simplexSolver;
	const btConvexShape* m_convexA;
	const btConvexShape* m_convexB;

public:
	/// Shapes and solver are not owned.
	btGjkConvexCast(const btConvexShape* convexA, const btConvexShape* convexB,
	                btSimplexSolverInterface* simplexSolver);

	/// See btConvexCast::calcTimeOfImpact.
	bool calcTimeOfImpact(const btTransform& fromA, const btTransform& toA, const btTransform& fromB,
	                      const btTransform& toB, CastResult& result) override;
};

#endif  // BT_GJK_CONVEX_CAST_H
