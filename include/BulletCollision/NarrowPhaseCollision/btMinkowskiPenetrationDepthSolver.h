// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MINKOWSKI_PENETRATION_DEPTH_SOLVER_H
#define BT_MINKOWSKI_PENETRATION_DEPTH_SOLVER_H

/// btMinkowskiPenetrationDepthSolver: penetration depth by sampling directions (a fallback to EPA).

#include "BulletCollision/NarrowPhaseCollision/btConvexPenetrationDepthSolver.h"

/// Estimates the penetration depth as the smallest overlap of the two shapes' projections over a fixed
/// set of directions: 42 near-uniform directions on the sphere, both shapes' local axes, the centre
/// offset and the shapes' preferred penetration directions. Exact when the true normal is among them
/// (face contacts of boxes), otherwise an upper bound on the depth.
class btMinkowskiPenetrationDepthSolver : public btConvexPenetrationDepthSolver
{
protected:
	/// The 42 fixed sampling directions (unit vectors, spread near-uniformly over the sphere).
	static btVector3* getPenetrationDirections();

public:
	/// Returns true when every sampled direction shows an overlap (margins included), with v the unit
	/// normal from B towards A of the smallest overlap, pa the deepest point of A along -v and
	/// pb = pa + v * depth. Returns false (zero outputs) when some direction separates the shapes or
	/// on bad input (null shapes, non-finite transforms; asserts first).
	bool calcPenDepth(btSimplexSolverInterface& simplexSolver, const btConvexShape* convexA,
	                  const btConvexShape* convexB, const btTransform& transA, const btTransform& transB, btVector3& v,
	                  btVector3& pa, btVector3& pb, btIDebugDraw* debugDraw) override;
};

#endif  // BT_MINKOWSKI_PENETRATION_DEPTH_SOLVER_H
