// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Speculative contacts must not stop what would not have touched: a body passing close to a static
// corner at speed keeps its velocity exactly.

#include <gtest/gtest.h>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
// A sphere of radius 0.5 flying along +x at 20 m/s in zero gravity past a static cube (half extents 1)
// turned by cubeTurn, whose feature nearest to the path (an edge or a vertex) is at z = featureZ, the
// cube's largest z; the path runs at z = featureZ + radius + clearance, so the sphere's surface passes
// that feature at clearance. Returns the sphere's velocity once it is well past.
btVector3 flyPast(const btQuaternion& cubeTurn, btScalar featureZ, btScalar clearance, btScalar h)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* cube =
	    w.addBody(w.shape<btBoxShape>(btVector3(1, 1, 1)), 0, btTransform(cubeTurn, btVector3(0, 0, 0)));
	cube->setFriction(btScalar(0.5));
	const btScalar radius = btScalar(0.5);
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(radius), 1, btVector3(-6, 0, featureZ + radius + clearance));
	ball->setFriction(btScalar(0.5));
	ball->setDamping(0, 0);
	ball->setActivationState(DISABLE_DEACTIVATION);
	ball->setLinearVelocity(btVector3(20, 0, 0));
	w.run(int(btScalar(0.6) / h), h);
	return ball->getLinearVelocity();
}

// Turned 45 degrees about y: one of its vertical edges, at (0, y, sqrt 2), points across the path.
btVector3 flyPastTheEdge(btScalar clearance, btScalar h)
{
	return flyPast(btQuaternion(btVector3(0, 1, 0), SIMD_PI / 4), btSqrt(btScalar(2)), clearance, h);
}

// Turned so that its corner (1, 1, 1) points along +z, to (0, 0, sqrt 3): the path above it is nearest
// to the box at that vertex.
btVector3 flyPastTheVertex(btScalar clearance, btScalar h)
{
	const btVector3 corner = btVector3(1, 1, 1).normalized();
	const btQuaternion turn(corner.cross(btVector3(0, 0, 1)).normalized(), btAcos(corner.z()));
	return flyPast(turn, btSqrt(btScalar(3)), clearance, h);
}

void expectKeepsItsVelocityPast(btVector3 (*fly)(btScalar, btScalar))
{
	const btScalar steps[] = {btScalar(1. / 60.), btScalar(1. / 120.)};
	for (btScalar h : steps)
	{
		// Several clearances, so that the pass falls at different places within a step.
		for (int i = 0; i < 5; ++i)
		{
			const btScalar clearance = btScalar(0.01) + btScalar(i) * btScalar(0.0037);
			const btVector3 v = fly(clearance, h);
			// Nothing touched it: no force acted, so the velocity is exactly what it was (float rounding only).
			EXPECT_NEAR(v.x(), 20, 1e-4) << "clearance " << clearance << " h " << h;
			EXPECT_NEAR(v.y(), 0, 1e-4) << "clearance " << clearance << " h " << h;
			EXPECT_NEAR(v.z(), 0, 1e-4) << "clearance " << clearance << " h " << h;
		}
	}
}
}  // namespace

TEST(GhostContact, SpherePassingACornerOneCentimetreAwayAtTwentyMetresPerSecondKeepsItsVelocity)
{
	expectKeepsItsVelocityPast(flyPastTheEdge);
}

TEST(GhostContact, SphereHittingTheCornerIsStillStopped)
{
	// The other side of the same line: a path that does meet the edge (1 cm of overlap) is deflected.
	const btVector3 v = flyPastTheEdge(btScalar(-0.01), btScalar(1. / 60.));
	EXPECT_GT(btFabs(v.z()) + btFabs(v.x() - 20), btScalar(0.01));
}

TEST(GhostContact, SpherePassingAVertexOneCentimetreAwayAtTwentyMetresPerSecondKeepsItsVelocity)
{
	expectKeepsItsVelocityPast(flyPastTheVertex);
}

TEST(GhostContact, SphereHittingTheVertexIsStillStopped)
{
	// A path whose sphere overlaps the vertex by 1 cm is deflected: the test above can fail.
	const btVector3 v = flyPastTheVertex(btScalar(-0.01), btScalar(1. / 60.));
	EXPECT_GT(btFabs(v.z()) + btFabs(v.x() - 20), btScalar(0.01));
}
