// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GJK_EPA_PENETRATION_DEPTH_H
#define BT_GJK_EPA_PENETRATION_DEPTH_H

/// btGjkEpaPenetrationDepthSolver: penetration depth by EPA (btGjkEpaSolver2).

#include "BulletCollision/NarrowPhaseCollision/btConvexPenetrationDepthSolver.h"

/// The default penetration depth solver: exact up to EPA's tolerance, margins included.
ATTRIBUTE_ALIGNED16(class)
btGjkEpaPenetrationDepthSolver : public btConvexPenetrationDepthSolver
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A stateless solver.
	btGjkEpaPenetrationDepthSolver() {}

	/// Runs EPA on the shapes with margins. Returns true with pa (deepest point of A), pb (on B's
	/// surface) and v (unit normal from B towards A) when they overlap. When they are apart, writes the
	/// closest points and the unit normal instead and returns false; on failure returns false with
	/// zero outputs.
	bool calcPenDepth(btSimplexSolverInterface & simplexSolver, const btConvexShape* convexA,
	                  const btConvexShape* convexB, const btTransform& transA, const btTransform& transB, btVector3& v,
	                  btVector3& pa, btVector3& pb, btIDebugDraw* debugDraw) override;
};

#endif  // BT_GJK_EPA_PENETRATION_DEPTH_H
