// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The cluster split factors (m_cfg.kSK_SPLT_CL, kSR_SPLT_CL, kSS_SPLT_CL; docs/soft-bodies.md, "Clusters"):
// of a cluster contact's push beyond stopping the approach (the recovery of a penetration), the split
// moves positions alone and the rest becomes a separating velocity, as Bullet's split cluster impulses.

#include <gtest/gtest.h>

#include <limits>

#include "SoftBodyTestUtil.h"

using caliber_test::rigidSoftBox;
using caliber_test::SoftTestWorld;

namespace
{
const btScalar kStep = btScalar(1) / 60;

btVector3 meanVelocity(const btSoftBody& b)
{
	btVector3 v(0, 0, 0);
	for (int i = 0; i < b.m_nodes.size(); ++i) v += b.m_nodes[i].m_v;
	return v / btScalar(b.m_nodes.size());
}

struct Recovery
{
	btScalar rise;      // how far the box came out of the ground in one step (m)
	btScalar velocity;  // its upward velocity after it (m/s)
};

// A 1 kg soft box sunk 5 cm into the static ground, at rest, in zero gravity: one step.
Recovery recoverFromGround(btScalar split)
{
	SoftTestWorld w(btVector3(0, 0, 0));
	w.addGround();
	btSoftBody* box =
	    rigidSoftBox(w, btVector3(0, 0.25, 0), btVector3(0.3, 0.3, 0.3), 1, btSoftBody::fCollision::CL_RS);
	box->m_cfg.kSK_SPLT_CL = split;
	const btScalar before = box->evaluateCom().y();
	w.step(1);
	return Recovery{box->evaluateCom().y() - before, meanVelocity(*box).y()};
}
}  // namespace

TEST(SoftBodyClusterSplit, SplitFactorDecidesHowMuchOfAPenetrationsRecoveryBecomesVelocity)
{
	// Against a static object the cluster's hardness (kSKHR_CL = 1) closes the penetration whatever the split;
	// the split decides the velocity it leaves: nothing approached, so (1 - split) of the recovery over the step
	// becomes velocity, (1 - split) rise / h. A split of 1 recovers without adding any velocity.
	const Recovery whole = recoverFromGround(1), half = recoverFromGround(btScalar(0.5)), none = recoverFromGround(0);
	// Out of the ground in one step (hardness 1; the pushes at the manifold's points may overshoot a little,
	// by less than the margin within which contacts are kept).
	EXPECT_GT(whole.rise, 0.05 - 1e-4);
	EXPECT_LT(whole.rise, 0.05 + 0.25);
	EXPECT_NEAR(half.rise, whole.rise, 1e-5);
	EXPECT_NEAR(none.rise, whole.rise, 1e-5);
	EXPECT_NEAR(whole.velocity, 0, 1e-4);
	EXPECT_NEAR(half.velocity, btScalar(0.5) * whole.rise / kStep, 0.01 * whole.rise / kStep);
	EXPECT_NEAR(none.velocity, whole.rise / kStep, 0.01 * whole.rise / kStep);
}

TEST(SoftBodyClusterSplit, SoftSoftSplitSeparatesPenetratingBodiesKeepingMomentum)
{
	// Two 1 kg soft boxes overlapping (their hulls keep 0.125 m apart; they start 0.025 m apart), at rest, in
	// zero gravity, with CL_SS: with kSS_SPLT_CL = 1 they are pushed apart without velocity; with 0 the whole
	// of the separation gained in the step becomes their relative velocity. The pushes are opposite: no momentum.
	for (btScalar split : {btScalar(1), btScalar(0.25), btScalar(0)})
	{
		SoftTestWorld w(btVector3(0, 0, 0));
		btSoftBody* a = rigidSoftBox(w, btVector3(0, 5, 0), btVector3(0.3, 0.3, 0.3), 1, btSoftBody::fCollision::CL_SS);
		btSoftBody* b =
		    rigidSoftBox(w, btVector3(0.625, 5, 0), btVector3(0.3, 0.3, 0.3), 1, btSoftBody::fCollision::CL_SS);
		a->m_cfg.kSS_SPLT_CL = b->m_cfg.kSS_SPLT_CL = split;
		const btScalar before = b->evaluateCom().x() - a->evaluateCom().x();
		w.step(1);
		const btScalar gained = b->evaluateCom().x() - a->evaluateCom().x() - before;
		EXPECT_GT(gained, 0.01) << "split " << split;
		const btScalar separating = meanVelocity(*b).x() - meanVelocity(*a).x();
		EXPECT_NEAR(separating, (1 - split) * gained / kStep, 0.01 * gained / kStep + 1e-4) << "split " << split;
		EXPECT_NEAR((meanVelocity(*a) + meanVelocity(*b)).length(), 0, 1e-4) << "split " << split;
	}
}

TEST(SoftBodyClusterSplit, SplitFactorsOutOfRangeAreClampedAndNaNAddsNoVelocity)
{
	// docs/bad-input.md: a split above 1 is 1, below 0 is 0, NaN is 1; the state stays finite.
	const Recovery whole = recoverFromGround(1), none = recoverFromGround(0);
	const Recovery above = recoverFromGround(3), below = recoverFromGround(-2),
	               nan = recoverFromGround(std::numeric_limits<btScalar>::quiet_NaN());
	EXPECT_EQ(above.velocity, whole.velocity);
	EXPECT_EQ(below.velocity, none.velocity);
	EXPECT_EQ(nan.velocity, whole.velocity);
	EXPECT_EQ(nan.rise, whole.rise);
}
