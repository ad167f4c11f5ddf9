// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONVEX_PENETRATION_DEPTH_H
#define BT_CONVEX_PENETRATION_DEPTH_H

/// btConvexPenetrationDepthSolver: the interface of penetration depth solvers used by btGjkPairDetector.

#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

class btConvexShape;
class btIDebugDraw;

/// Computes how deep two overlapping convex shapes penetrate.
class btConvexPenetrationDepthSolver
{
public:
	/// Solvers are deleted through base pointers.
	virtual ~btConvexPenetrationDepthSolver() {}
	/// For overlapping shapes (margins included) writes the deepest point of A (pa), the matching point
	/// on B's surface (pb) and a direction v; returns true on success. pb - pa points from B towards A.
	virtual bool calcPenDepth(btSimplexSolverInterface& simplexSolver, const btConvexShape* convexA,
	                          const btConvexShape* convexB, const btTransform& transA, const btTransform& transB,
	                          btVector3& v, btVector3& pa, btVector3& pb, btIDebugDraw* debugDraw) = 0;
};

#endif  // BT_CONVEX_PENETRATION_DEPTH_H
