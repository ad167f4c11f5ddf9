// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GJK_PAIR_DETECTOR_H
#define BT_GJK_PAIR_DETECTOR_H

/// btGjkPairDetector: closest points of two convex shapes by GJK, with a penetration depth solver for
/// overlaps.

#include "BulletCollision/NarrowPhaseCollision/btDiscreteCollisionDetectorInterface.h"
#include "BulletCollision/NarrowPhaseCollision/btSimplexSolverInterface.h"

class btConvexShape;
class btConvexPenetrationDepthSolver;

/// Runs GJK on the margin-free cores of two convex shapes and subtracts the margins; when the cores
/// overlap (or GJK degenerates) asks the penetration depth solver. Reports one point: the normal from
/// B towards A, the point on B and the signed distance (negative when penetrating).
/// Bad input (null shapes, a null simplex solver, non-finite transforms) asserts and reports nothing in
/// release builds; a failed depth solver also reports nothing.
ATTRIBUTE_ALIGNED16(class)
btGjkPairDetector : public btDiscreteCollisionDetectorInterface
{
	btVector3 m_cachedSeparatingAxis;
	btConvexPenetrationDepthSolver* m_penetrationDepthSolver;
	btSimplexSolverInterface* m_simplexSolver;
	const btConvexShape* m_minkowskiA;
	const btConvexShape* m_minkowskiB;
	int m_shapeTypeA;
	int m_shapeTypeB;
	btScalar m_marginA;
	btScalar m_marginB;
	bool m_ignoreMargin;
	btScalar m_cachedSeparatingDistance;
	bool m_useShapeMargins;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// How the last query got its result: -1 none, 1 GJK, 3 depth solver, 4 GJK kept over the depth
	/// solver, 5 and 6 the depth solver failed (6: fallback result kept).
	int m_lastUsedMethod;
	/// GJK iterations of the last query.
	int m_curIter;
	/// Why GJK stopped early in the last query (0: normal convergence).
	int m_degenerateSimplex;
	/// When non-zero, a degenerate GJK ending near contact is double-checked by the depth solver.
	int m_catchDegeneracies;
	/// When non-zero, a penetration normal pointing the wrong way (from A towards B) is flipped.
	int m_fixContactNormalDirection;

	/// Pair of shapes whose margins are read from the shapes at each query.
	btGjkPairDetector(const btConvexShape* objectA, const btConvexShape* objectB,
	                  btSimplexSolverInterface* simplexSolver, btConvexPenetrationDepthSolver* penetrationDepthSolver);
	/// Pair of shapes with given types and margins, used by GJK instead of the shapes' own margins (the
	/// penetration depth solver still sees the shapes themselves, with their own margins).
	btGjkPairDetector(const btConvexShape* objectA, const btConvexShape* objectB, int shapeTypeA, int shapeTypeB,
	                  btScalar marginA, btScalar marginB, btSimplexSolverInterface* simplexSolver,
	                  btConvexPenetrationDepthSolver* penetrationDepthSolver);
	/// Nothing is owned.
	~btGjkPairDetector() override {}

	/// Computes the closest points and reports at most one to output (swapResults is not needed).
	void getClosestPoints(const ClosestPointInput& input, Result& output, btIDebugDraw* debugDraw,
	                      bool swapResults = false) override;
	/// getClosestPoints without the virtual call.
	void getClosestPointsNonVirtual(const ClosestPointInput& input, Result& output, btIDebugDraw* debugDraw);

	/// Replaces shape A.
	void setMinkowskiA(const btConvexShape* minkA) { m_minkowskiA = minkA; }
	/// Replaces shape B.
	void setMinkowskiB(const btConvexShape* minkB) { m_minkowskiB = minkB; }
	/// Sets the axis GJK starts from (from B towards A; the last result's normal is a good choice).
	void setCachedSeperatingAxis(const btVector3& seperatingAxis) { m_cachedSeparatingAxis = seperatingAxis; }
	/// The separating axis of the last query: the reported normal when a point was reported, the axis
	/// that proved the pair farther apart than the maximum distance when that ended the query.
	const btVector3& getCachedSeparatingAxis() const { return m_cachedSeparatingAxis; }
	/// The signed distance of the last reported point.
	btScalar getCachedSeparatingDistance() const { return m_cachedSeparatingDistance; }
	/// Replaces the penetration depth solver (may be null: overlapping cores then report nothing).
	void setPenetrationDepthSolver(btConvexPenetrationDepthSolver * penetrationDepthSolver)
	{
		m_penetrationDepthSolver = penetrationDepthSolver;
	}
	/// When true the margins are ignored (distances between the cores are reported).
	void setIgnoreMargin(bool ignoreMargin) { m_ignoreMargin = ignoreMargin; }
};

#endif  // BT_GJK_PAIR_DETECTOR_H
