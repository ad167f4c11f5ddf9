// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btJacobianEntry (Bullet 2's per-row Jacobian): an impulse lambda along a row changes the row's relative
// velocity by lambda times getDiagonal(), and another row's by lambda times getNonDiagonal(), computed here
// from Newton's laws for two rotated bodies with diagonal inertia.

#include <gtest/gtest.h>

#include "BulletDynamics/ConstraintSolver/btJacobianEntry.h"
#include "LinearMath/btQuaternion.h"

namespace
{
struct Body
{
	btMatrix3x3 basis;  // inertia frame to world
	btVector3 inertiaInv;
	btScalar massInv;
};

// The velocity changes of A and B (world frame) from an impulse lambda along axis at rA on A, and its
// opposite at rB on B.
void applyRowImpulse(const Body& a, const Body& b, const btVector3& rA, const btVector3& rB, const btVector3& axis,
                     btScalar lambda, btVector3& dvA, btVector3& dwA, btVector3& dvB, btVector3& dwB)
{
	dvA = axis * (lambda * a.massInv);
	dvB = -axis * (lambda * b.massInv);
	// I^-1 in world = R diag R^T.
	dwA = a.basis * (a.inertiaInv * (a.basis.transpose() * rA.cross(axis * lambda)));
	dwB = b.basis * (b.inertiaInv * (b.basis.transpose() * rB.cross(-axis * lambda)));
}
}  // namespace

TEST(JacobianEntry, AnImpulseChangesTheRowVelocityByItsDiagonalAndAnotherRowsByTheNonDiagonal)
{
	const Body a{btMatrix3x3(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7))), btVector3(2, 3, 5),
	             btScalar(0.5)};
	const Body b{btMatrix3x3(btQuaternion(btVector3(-2, 1, 1).normalized(), btScalar(1.9))), btVector3(1, 4, 2),
	             btScalar(0.25)};
	const btVector3 rA(btScalar(0.3), btScalar(-0.2), btScalar(0.5)), rB(btScalar(-0.4), btScalar(0.1), btScalar(0.2));
	const btVector3 axis1 = btVector3(1, 1, 0).normalized(), axis2 = btVector3(0, 1, 2).normalized();
	btJacobianEntry row1(a.basis.transpose(), b.basis.transpose(), rA, rB, axis1, a.inertiaInv, a.massInv,
	                     b.inertiaInv, b.massInv);
	btJacobianEntry row2(a.basis.transpose(), b.basis.transpose(), rA, rB, axis2, a.inertiaInv, a.massInv,
	                     b.inertiaInv, b.massInv);
	const btScalar lambda = btScalar(1.5);
	btVector3 dvA, dwA, dvB, dwB;
	applyRowImpulse(a, b, rA, rB, axis1, lambda, dvA, dwA, dvB, dwB);
	// The rows take angular velocities in the bodies' inertia frames.
	const btVector3 localA = a.basis.transpose() * dwA, localB = b.basis.transpose() * dwB;
	// Float rounding of sums of order 10.
	EXPECT_NEAR(row1.getRelativeVelocity(dvA, localA, dvB, localB), lambda * row1.getDiagonal(), 1e-5);
	EXPECT_NEAR(row2.getRelativeVelocity(dvA, localA, dvB, localB),
	            lambda * row1.getNonDiagonal(row2, a.massInv, b.massInv), 1e-5);
	// The diagonal is the effective mass's inverse: positive, and symmetric couplings.
	EXPECT_GT(row1.getDiagonal(), 0);
	EXPECT_NEAR(row1.getNonDiagonal(row2, a.massInv, b.massInv), row2.getNonDiagonal(row1, a.massInv, b.massInv),
	            1e-5);
}

TEST(JacobianEntry, AngularRowAboutAnAxisHasTheInertiaAboutItAsDiagonal)
{
	// Unrotated bodies: about the world x axis the inverse inertias are the x entries.
	const btMatrix3x3 identity = btMatrix3x3::getIdentity();
	btJacobianEntry row(btVector3(1, 0, 0), identity, identity, btVector3(2, 3, 5), btVector3(4, 1, 1));
	EXPECT_FLOAT_EQ(row.getDiagonal(), 6);
	btJacobianEntry local(btVector3(0, 1, 0), btVector3(0, 1, 0), btVector3(2, 3, 5), btVector3(4, 1, 1));
	EXPECT_FLOAT_EQ(local.getDiagonal(), 4);
	// One body at a lever arm: 1/m + |r x n|^2 / I for r across n.
	btJacobianEntry single(identity, btVector3(0, 2, 0), btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(1, 1, 1),
	                       btScalar(0.5));
	EXPECT_FLOAT_EQ(single.getDiagonal(), btScalar(0.5) + 4);
}
