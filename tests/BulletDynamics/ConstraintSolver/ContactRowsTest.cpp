// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Which manifold points become solver rows: touching points always; speculative (separated) points only
// when their bodies approach fast enough to close the gap within the step.

#include <gtest/gtest.h>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
// The default solver, with the number of contact rows of its last solve made visible.
class CountingSolver : public btSequentialImpulseConstraintSolver
{
public:
	int m_rows = 0;
	btScalar solveGroup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds, int numManifolds,
	                    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& info,
	                    btIDebugDraw* drawer, btDispatcher* dispatcher) override
	{
		const btScalar residual = btSequentialImpulseConstraintSolver::solveGroup(
		    bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, drawer, dispatcher);
		m_rows += m_tmpSolverContactConstraintPool.size();
		return residual;
	}
};

// Two unit cubes side by side, 1 cm apart, without gravity; b moves towards a at the given speed.
int rowsForApproach(btScalar speed, btScalar& gapAfter)
{
	TestWorld w(btVector3(0, 0, 0));
	CountingSolver solver;
	w.world()->setConstraintSolver(&solver);
	btCollisionShape* cube = w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
	btRigidBody* a = w.addBody(cube, 1, btVector3(0, 0, 0));
	btRigidBody* b = w.addBody(cube, 1, btVector3(btScalar(1.01), 0, 0));
	b->setLinearVelocity(btVector3(-speed, 0, 0));
	w.run(1);
	solver.m_rows = 0;
	w.run(1);
	gapAfter = b->getCenterOfMassPosition().x() - a->getCenterOfMassPosition().x() - 1;
	w.world()->setConstraintSolver(w.solver());
	return solver.m_rows;
}
}  // namespace

TEST(ContactRows, SeparatedPointsGetRowsOnlyWhenTheirBodiesCanCloseTheGapThisStep)
{
	btScalar gap = 0;
	// At rest 1 cm apart: the manifold keeps the points (within the breaking threshold) but nothing can
	// close the gap, so no rows are built.
	EXPECT_EQ(rowsForApproach(0, gap), 0);
	EXPECT_NEAR(gap, 0.01, 1e-6);
	// Approaching at 1 m/s the gap would close in 0.6 of a step: the speculative rows are there, and they
	// let the cube close the gap exactly, no further.
	EXPECT_GT(rowsForApproach(1, gap), 0);
	EXPECT_GE(gap, -1e-4) << "no overlap";
}

TEST(ContactRows, ABoxFallingWithTheOneBelowItIsStillCaughtByIt)
{
	// Two unit cubes stacked on the ground with a 0.1 mm gap between them, released. Gravity gives both
	// the same velocity, so the pair does not approach at the start of the step; but the ground stops the
	// lower one during the solve. The upper one must still be held by the contact between them: without
	// it, it would sink g h^2 = 2.8 mm into the lower one in this step.
	TestWorld w(btVector3(0, -10, 0));
	w.addGround();
	btCollisionShape* cube = w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
	btRigidBody* lower = w.addBody(cube, 1, btVector3(0, btScalar(0.5), 0));
	btRigidBody* upper = w.addBody(cube, 1, btVector3(0, btScalar(1.5001), 0));
	w.run(1);
	w.run(1);
	const btScalar gap = upper->getCenterOfMassPosition().y() - lower->getCenterOfMassPosition().y() - 1;
	EXPECT_GT(gap, btScalar(-5e-4)) << "overlap after the step";
}
