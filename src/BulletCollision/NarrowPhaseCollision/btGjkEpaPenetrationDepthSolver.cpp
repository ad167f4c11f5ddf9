// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"

#include "BulletCollision/NarrowPhaseCollision/btGjkEpa2.h"

bool btGjkEpaPenetrationDepthSolver::calcPenDepth(btSimplexSolverInterface& simplexSolver, const btConvexShape* convexA,
                                                  const btConvexShape* convexB, const btTransform& transA,
                                                  const btTransform& transB, btVector3& v, btVector3& pa, btVector3& pb,
                                                  btIDebugDraw* debugDraw)
{
	(void)simplexSolver;
	(void)debugDraw;
	// The centre offset is a good first direction: it is the separating axis of round shapes.
	const btVector3 guess = transB.getOrigin() - transA.getOrigin();
	btGjkEpaSolver2::sResults results;
	const bool penetrating = btGjkEpaSolver2::Penetration(convexA, transA, convexB, transB, guess, results);
	pa = results.witnesses[0];
	pb = results.witnesses[1];
	v = results.normal;
	return penetrating;
}
