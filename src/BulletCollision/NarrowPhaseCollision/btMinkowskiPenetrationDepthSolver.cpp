// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btMinkowskiPenetrationDepthSolver.h"

#include "BulletCollision/CollisionShapes/btConvexShape.h"

namespace
{
const int kNumSphereDirections = 42;

btVector3 worldSupport(const btConvexShape* shape, const btTransform& t, const btVector3& unitDir)
{
	return t(shape->localGetSupportingVertexWithoutMargin(unitDir * t.getBasis())) + unitDir * shape->getMargin();
}

// Tracks the direction of least overlap.
struct BestDirection
{
	const btConvexShape* a;
	const btConvexShape* b;
	const btTransform* transA;
	const btTransform* transB;
	btScalar overlap;
	btVector3 normal;
	btVector3 deepestA;

	// Overlap when A lies on the +n side of B: how far B reaches along n past A's lowest point.
	void consider(const btVector3& direction)
	{
		if (!(direction.length2() > SIMD_EPSILON)) return;
		const btVector3 n = direction.normalized();
		const btVector3 lowA = worldSupport(a, *transA, -n);
		const btScalar candidate = worldSupport(b, *transB, n).dot(n) - lowA.dot(n);
		if (candidate < overlap)
		{
			overlap = candidate;
			normal = n;
			deepestA = lowA;
		}
	}
};
}  // namespace

btVector3* btMinkowskiPenetrationDepthSolver::getPenetrationDirections()
{
	// Fibonacci lattice: equal-area bands in z, golden-angle steps in longitude.
	static btVector3 directions[kNumSphereDirections];
	static const bool initialised = []
	{
		const btScalar goldenAngle = SIMD_PI * (btScalar(3) - btSqrt(btScalar(5)));
		for (int i = 0; i < kNumSphereDirections; ++i)
		{
			const btScalar z = btScalar(1) - (btScalar(2) * btScalar(i) + btScalar(1)) / btScalar(kNumSphereDirections);
			const btScalar r = btSqrt(btMax(btScalar(0), btScalar(1) - z * z));
			const btScalar angle = goldenAngle * btScalar(i);
			directions[i].setValue(r * btCos(angle), r * btSin(angle), z);
		}
		return true;
	}();
	(void)initialised;
	return directions;
}

bool btMinkowskiPenetrationDepthSolver::calcPenDepth(btSimplexSolverInterface& simplexSolver,
                                                     const btConvexShape* convexA, const btConvexShape* convexB,
                                                     const btTransform& transA, const btTransform& transB, btVector3& v,
                                                     btVector3& pa, btVector3& pb, btIDebugDraw* debugDraw)
{
	(void)simplexSolver;
	(void)debugDraw;
	const btVector3 zero(btScalar(0), btScalar(0), btScalar(0));
	v = zero;
	pa = zero;
	pb = zero;
	btAssert(convexA && convexB && caliber::isFinite(transA) && caliber::isFinite(transB));
	if (!convexA || !convexB || !caliber::isFinite(transA) || !caliber::isFinite(transB)) return false;

	BestDirection best = {convexA, convexB, &transA, &transB, BT_LARGE_FLOAT, zero, zero};
	const btVector3* sphere = getPenetrationDirections();
	for (int i = 0; i < kNumSphereDirections; ++i) best.consider(sphere[i]);
	for (int axis = 0; axis < 3; ++axis)
	{
		const btVector3 axisA = transA.getBasis().getColumn(axis);
		const btVector3 axisB = transB.getBasis().getColumn(axis);
		best.consider(axisA);
		best.consider(-axisA);
		best.consider(axisB);
		best.consider(-axisB);
	}
	const btVector3 centres = transA.getOrigin() - transB.getOrigin();
	best.consider(centres);
	best.consider(-centres);
	for (int i = 0; i < convexA->getNumPreferredPenetrationDirections(); ++i)
	{
		btVector3 local;
		convexA->getPreferredPenetrationDirection(i, local);
		const btVector3 world = transA.getBasis() * local;
		best.consider(world);
		best.consider(-world);
	}
	for (int i = 0; i < convexB->getNumPreferredPenetrationDirections(); ++i)
	{
		btVector3 local;
		convexB->getPreferredPenetrationDirection(i, local);
		const btVector3 world = transB.getBasis() * local;
		best.consider(world);
		best.consider(-world);
	}
	if (!(best.overlap > btScalar(0)) || !(best.overlap < BT_LARGE_FLOAT) || !caliber::isFinite(best.deepestA))
		return false;
	v = best.normal;
	pa = best.deepestA;
	pb = best.deepestA + best.normal * best.overlap;
	return true;
}
