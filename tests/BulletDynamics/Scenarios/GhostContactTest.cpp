// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Speculative contacts must not stop what would not have touched: a body passing close to a static
// corner at speed keeps its velocity exactly.

#include <gtest/gtest.h>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
// A sphere of radius 0.5 flying along +x at 20 m/s in zero gravity past a static cube (half extents 1)
// turned 45 degrees about y, so that one of its vertical edges points across the path; the sphere's
// surface passes that edge at clearance. Returns the sphere's velocity once it is well past.
btVector3 flyPastTheEdge(btScalar clearance, btScalar h)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* cube = w.addBody(w.shape<btBoxShape>(btVector3(1, 1, 1)), 0,
	                              btTransform(btQuaternion(btVector3(0, 1, 0), SIMD_PI / 4), btVector3(0, 0, 0)));
	cube->setFriction(btScalar(0.5));
	const btScalar radius = btScalar(0.5);
	const btScalar edgeZ = btSqrt(btScalar(2));  // the turned cube's edge at (0, y, sqrt 2)
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(radius), 1, btVector3(-6, 0, edgeZ + radius + clearance));
	ball->setFriction(btScalar(0.5));
	ball->setDamping(0, 0);
	ball->setActivationState(DISABLE_DEACTIVATION);
	ball->setLinearVelocity(btVector3(20, 0, 0));
	w.run(int(btScalar(0.6) / h), h);
	return ball->getLinearVelocity();
}
}  // namespace

TEST(GhostContact, SpherePassingACornerOneCentimetreAwayAtTwentyMetresPerSecondKeepsItsVelocity)
{
	const btScalar steps[] = {btScalar(1. / 60.), btScalar(1. / 120.)};
	for (btScalar h : steps)
	{
		// Several clearances, so that the pass falls at different places within a step.
		for (int i = 0; i < 5; ++i)
		{
			const btScalar clearance = btScalar(0.01) + btScalar(i) * btScalar(0.0037);
			const btVector3 v = flyPastTheEdge(clearance, h);
			// Nothing touched it: no force acted, so the velocity is exactly what it was (float rounding only).
			EXPECT_NEAR(v.x(), 20, 1e-4) << "clearance " << clearance << " h " << h;
			EXPECT_NEAR(v.y(), 0, 1e-4) << "clearance " << clearance << " h " << h;
			EXPECT_NEAR(v.z(), 0, 1e-4) << "clearance " << clearance << " h " << h;
		}
	}
}

TEST(GhostContact, SphereHittingTheCornerIsStillStopped)
{
	// The other side of the same line: a path that does meet the edge (1 cm of overlap) is deflected.
	const btVector3 v = flyPastTheEdge(btScalar(-0.01), btScalar(1. / 60.));
	EXPECT_GT(btFabs(v.z()) + btFabs(v.x() - 20), btScalar(0.01));
}
