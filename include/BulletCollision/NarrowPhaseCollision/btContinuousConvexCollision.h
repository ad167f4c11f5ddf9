// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONTINUOUS_COLLISION_CONVEX_CAST_H
#define BT_CONTINUOUS_COLLISION_CONVEX_CAST_H

/// btContinuousConvexCollision: time of impact of two moving and rotating convex shapes (or a convex
/// shape and a static plane) by conservative advancement.

#include "BulletCollision/NarrowPhaseCollision/btConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"

class btConvexShape;
class btConvexPenetrationDepthSolver;
class btStaticPlaneShape;
struct btPointCollector;

/// Each shape moves on the screw motion from its from to its to transform (constant linear velocity of
/// its origin, constant angular velocity about it, the short way round). Conservative advancement
/// bounds the approach speed by the linear speed along the normal plus |angular velocity| times
/// getAngularMotionDisc(), so it never steps past the first contact. Stops when the distance plus
/// m_allowedPenetration is within the cast tolerance (see docs). A null penetration depth solver is
/// allowed (overlapping cores then count as contact). Null shapes or solver and non-finite transforms
/// assert and return false.
class btContinuousConvexCollision : public btConvexCast
{
	btSimplexSolverInterface* m_simplexSolver;
	btConvexPenetrationDepthSolver* m_penetrationDepthSolver;
	const btConvexShape* m_convexA;
	const btConvexShape* m_convexB1;
	const btStaticPlaneShape* m_planeShape;

	/// Signed distance (margins included) of the shapes placed by transA and transB, into pointCollector.
	void computeClosestPoints(const btTransform& transA, const btTransform& transB, btPointCollector& pointCollector);

public:
	/// Two convex shapes; nothing is owned.
	btContinuousConvexCollision(const btConvexShape* shapeA, const btConvexShape* shapeB,
	                            btSimplexSolverInterface* simplexSolver,
	                            btConvexPenetrationDepthSolver* penetrationDepthSolver);
	/// A convex shape (A) against a static plane (B, its transform places the plane); nothing is owned.
	/// The plane's rotation between fromB and toB is followed but not bounded (planes are static).
	btContinuousConvexCollision(const btConvexShape* shapeA, const btStaticPlaneShape* plane);

	/// See btConvexCast::calcTimeOfImpact.
	bool calcTimeOfImpact(const btTransform& fromA, const btTransform& toA, const btTransform& fromB,
	                      const btTransform& toB, CastResult& result) override;
};

#endif  // BT_CONTINUOUS_COLLISION_CONVEX_CAST_H
