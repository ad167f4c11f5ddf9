// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Continuous collision: a 200 m/s sphere against a 1 cm wall. Swept CCD stops it, and so do the
// speculative contacts (on by default); with neither (discrete collision detection only) it tunnels,
// which shows that they are what stops it.

#include <gtest/gtest.h>

#include <memory>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
// The wall is the slab 0 <= x <= 0.01; the sphere (radius 0.1) starts at x = -2 moving at +200 m/s, which
// is 3.3 m per step: it would cross the wall between two steps. Returns its final x.
enum Mode
{
	kDiscreteOnly,
	kSpeculative,
	kSweptCcd
};

btScalar shootAtThinWall(Mode mode)
{
	TestWorld w(btVector3(0, 0, 0));
	// m_useContinuous off: no swept AABBs, no speculative distance, no swept CCD.
	w.world()->getDispatchInfo().m_useContinuous = mode != kDiscreteOnly;
	w.addBody(w.shape<btBoxShape>(btVector3(0.005, 2, 2)), 0, btVector3(0.005, 0, 0));
	const btScalar radius = btScalar(0.1);
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(radius), 1, btVector3(-2, 0, 0));
	ball->setLinearVelocity(btVector3(200, 0, 0));
	if (mode == kSweptCcd)
	{
		ball->setCcdMotionThreshold(radius);
		ball->setCcdSweptSphereRadius(radius);
	}
	w.run(30);
	return ball->getCenterOfMassPosition().x();
}
}  // namespace

TEST(ContinuousCollision, FastSphereIsStoppedByAThinWallWithCcd)
{
	const btScalar x = shootAtThinWall(kSweptCcd);
	// On the near side, touching the wall at most (centre no further than one radius short of x = 0, plus
	// the allowed CCD penetration of 0.04).
	EXPECT_LT(x, btScalar(-0.1) + btScalar(0.04) + btScalar(1e-3));
}

TEST(ContinuousCollision, FastSphereIsStoppedByAThinWallWithSpeculativeContacts)
{
	// The contact is kept from as far as the sphere can travel in a step, and the solver lets it close
	// the gap and no more: it ends touching the wall (centre one radius short of x = 0).
	const btScalar x = shootAtThinWall(kSpeculative);
	EXPECT_LT(x, btScalar(-0.1) + btScalar(1e-3));
	EXPECT_GT(x, btScalar(-0.1) - btScalar(0.05));
}

TEST(ContinuousCollision, FastSphereTunnelsThroughAThinWallWithDiscreteDetectionOnly)
{
	const btScalar x = shootAtThinWall(kDiscreteOnly);
	EXPECT_GT(x, btScalar(1));
}

TEST(ContinuousCollision, FastSphereIsStoppedByATurnedTriangleMeshWithSpeculativeContacts)
{
	// A floor of two triangles, its body turned 90 degrees about x so that the mesh's local z is the
	// world's y (the speculative query box is grown along the motion in the mesh's own frame). A sphere
	// falls onto it at 120 m/s, 2 m per step, from 3 m above.
	TestWorld w(btVector3(0, 0, 0));
	btTriangleMesh* triangles = new btTriangleMesh();
	triangles->addTriangle(btVector3(-5, -5, 0), btVector3(5, -5, 0), btVector3(5, 5, 0));
	triangles->addTriangle(btVector3(-5, -5, 0), btVector3(5, 5, 0), btVector3(-5, 5, 0));
	std::unique_ptr<btTriangleMesh> meshData(triangles);
	btBvhTriangleMeshShape* mesh = w.shape<btBvhTriangleMeshShape>(triangles, true);
	w.addBody(mesh, 0, btTransform(btQuaternion(btVector3(1, 0, 0), -SIMD_HALF_PI), btVector3(0, 0, 0)));
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(0, 3, 0));
	ball->setLinearVelocity(btVector3(0, -120, 0));
	w.run(30);
	// The contact is kept from as far as the sphere travels in a step and the solver lets it close the gap
	// and no more: it ends on the mesh, centre one radius above y = 0 (within the triangle margin, 0.04).
	EXPECT_GT(ball->getCenterOfMassPosition().y(), btScalar(0.5) - btScalar(0.05));
	EXPECT_LT(ball->getCenterOfMassPosition().y(), btScalar(0.5) + btScalar(0.05));
}
