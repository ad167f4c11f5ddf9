// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The callbacks Bullet programs use to change contacts: gContactAddedCallback with
// CF_CUSTOM_MATERIAL_CALLBACK (per-contact friction), gContactProcessedCallback and
// gContactDestroyedCallback through the whole world.

#include <gtest/gtest.h>

#include "../Dynamics/DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kStep = btScalar(1. / 60.);
int gAddedCalls = 0;

bool makeFrictionless(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*,
                      int, int)
{
	++gAddedCalls;
	cp.m_combinedFriction = 0;
	return true;
}

// A box on a 20-degree slope (gravity tilted) with friction 1: it sticks unless the callback removes
// the friction, in which case it slides with a = g sin(20 deg) = 3.42 m/s^2.
btScalar slideSpeedAfterOneSecond(bool customMaterial)
{
	const btScalar angle = btScalar(20) * SIMD_RADS_PER_DEG;
	TestWorld w(btVector3(10 * btSin(angle), -10 * btCos(angle), 0));
	w.addGround(btScalar(1), btScalar(0));
	btRigidBody* box = w.addBody(w.shape<btBoxShape>(btVector3(0.5, 0.25, 0.5)), 1, btVector3(0, btScalar(0.25), 0));
	box->setFriction(1);
	box->setActivationState(DISABLE_DEACTIVATION);
	if (customMaterial)
		box->setCollisionFlags(box->getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
	w.run(60);
	return box->getLinearVelocity().x();
}
}  // namespace

TEST(ContactCallbackScenario, ContactAddedCallbackChangesFrictionPerContact)
{
	ContactAddedCallback saved = gContactAddedCallback;
	gContactAddedCallback = makeFrictionless;
	gAddedCalls = 0;
	const btScalar withoutFlag = slideSpeedAfterOneSecond(false);
	EXPECT_EQ(gAddedCalls, 0) << "the callback runs only for objects with CF_CUSTOM_MATERIAL_CALLBACK";
	const btScalar withFlag = slideSpeedAfterOneSecond(true);
	gContactAddedCallback = saved;
	EXPECT_GT(gAddedCalls, 0);
	// Friction 1 holds the box on a 20-degree slope (tan 20 = 0.36 < 1).
	EXPECT_NEAR(withoutFlag, 0, btScalar(0.02));
	// Frictionless, it slides with g sin(20 deg) t; the solver reproduces that to 2 %.
	const btScalar expected = 10 * btSin(btScalar(20) * SIMD_RADS_PER_DEG);
	EXPECT_NEAR(withFlag, expected, btScalar(0.02) * expected);
}

namespace
{
int gProcessed = 0;
int gDestroyed = 0;
bool countProcessed(btManifoldPoint& cp, void*, void*)
{
	++gProcessed;
	// Hand the point some user data, which the manifold gives back through the destroyed callback.
	if (!cp.m_userPersistentData) cp.m_userPersistentData = &gDestroyed;
	return true;
}
bool countDestroyed(void* userPersistentData)
{
	if (userPersistentData == &gDestroyed) ++gDestroyed;
	return true;
}
}  // namespace

TEST(ContactCallbackScenario, ProcessedAndDestroyedCallbacksFollowAContactsLife)
{
	ContactProcessedCallback savedProcessed = gContactProcessedCallback;
	ContactDestroyedCallback savedDestroyed = gContactDestroyedCallback;
	gContactProcessedCallback = countProcessed;
	gContactDestroyedCallback = countDestroyed;
	gProcessed = gDestroyed = 0;
	{
		TestWorld w;
		w.addGround();
		btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(0, btScalar(0.5), 0));
		w.run(10);
		EXPECT_GT(gProcessed, 0) << "a resting contact is processed every step";
		EXPECT_EQ(gDestroyed, 0);
		// Throw the ball up: the contact breaks and its user data is released.
		ball->setLinearVelocity(btVector3(0, 10, 0));
		w.run(10);
		EXPECT_GE(gDestroyed, 1);
	}
	gContactProcessedCallback = savedProcessed;
	gContactDestroyedCallback = savedDestroyed;
}
