// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The kinematic character against geometry and first principles: step height, slope limit, jump apex
// v^2 / (2 g), walls at speed, ground state in the air, riding a moving platform.

#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "../Dynamics/DynamicsWorldTestUtil.h"
#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletDynamics/Character/btKinematicCharacterController.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kStep = btScalar(1. / 60.);
const btScalar kRadius = btScalar(0.3), kCylinder = btScalar(1.0);
const btScalar kHalfHeight = kRadius + kCylinder / 2;

class Character
{
public:
	Character(TestWorld& w, const btVector3& feet, btScalar stepHeight = btScalar(0.35))
	    : m_world(w.world()), m_shape(kRadius, kCylinder)
	{
		m_world->getPairCache()->setInternalGhostPairCallback(&m_callback);
		m_ghost.setWorldTransform(btTransform(btQuaternion::getIdentity(), feet + btVector3(0, kHalfHeight + btScalar(0.001), 0)));
		m_ghost.setCollisionShape(&m_shape);
		m_ghost.setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
		m_world->addCollisionObject(&m_ghost, btBroadphaseProxy::CharacterFilter,
		                            btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter |
		                                btBroadphaseProxy::KinematicFilter);
		m_controller.reset(new btKinematicCharacterController(&m_ghost, &m_shape, stepHeight, btVector3(0, 1, 0)));
		m_world->addAction(m_controller.get());
	}
	~Character()
	{
		m_world->removeAction(m_controller.get());
		if (m_ghost.getBroadphaseHandle()) m_world->removeCollisionObject(&m_ghost);
		m_world->getPairCache()->setInternalGhostPairCallback(0);
	}
	btKinematicCharacterController* operator->() { return m_controller.get(); }
	btPairCachingGhostObject* ghost() { return &m_ghost; }
	btVector3 feet() const { return m_ghost.getWorldTransform().getOrigin() - btVector3(0, kHalfHeight, 0); }

private:
	btDiscreteDynamicsWorld* m_world;
	btCapsuleShape m_shape;
	btPairCachingGhostObject m_ghost;
	btGhostPairCallback m_callback;
	std::unique_ptr<btKinematicCharacterController> m_controller;
};

void addBox(TestWorld& w, const btVector3& halfExtents, const btTransform& pose)
{
	w.addBody(w.shape<btBoxShape>(halfExtents), 0, pose);
}
btTransform at(const btVector3& origin) { return btTransform(btQuaternion::getIdentity(), origin); }
}  // namespace

TEST(KinematicCharacterController, HasBulletsDefaults)
{
	TestWorld w;
	w.addGround();
	Character c(w, btVector3(0, 0, 0));
	EXPECT_NEAR(c->getGravity().y(), btScalar(-9.8 * 3), btScalar(1e-4));
	EXPECT_EQ(c->getFallSpeed(), btScalar(55));
	EXPECT_EQ(c->getJumpSpeed(), btScalar(10));
	EXPECT_NEAR(c->getMaxSlope(), btRadians(btScalar(45)), btScalar(1e-6));
	EXPECT_EQ(c->getMaxPenetrationDepth(), btScalar(0.2));
}

TEST(KinematicCharacterController, StepHeightIsHonouredToTheMillimetre)
{
	for (const btScalar delta : {btScalar(-0.001), btScalar(0.001)})
	{
		TestWorld w;
		w.addGround();
		const btScalar stepHeight = btScalar(0.35), height = stepHeight + delta;
		addBox(w, btVector3(5, height / 2, 2), at(btVector3(0, height / 2, 4)));
		Character c(w, btVector3(0, 0, 0), stepHeight);
		w.run(30, kStep);
		c->setWalkDirection(btVector3(0, 0, btScalar(0.05)));
		w.run(120, kStep);
		if (delta < 0)
			EXPECT_NEAR(c.feet().y(), height, btScalar(0.005)) << "a step 1 mm below the step height is climbed";
		else
			EXPECT_LT(c.feet().y(), btScalar(0.01)) << "a step 1 mm above the step height is a wall";
	}
}

TEST(KinematicCharacterController, SlopesJustBelowTheLimitAreClimbedJustAboveAreNot)
{
	for (const btScalar degrees : {btScalar(43), btScalar(47)})
	{
		TestWorld w;
		w.addGround();
		const btScalar angle = btRadians(degrees);
		// A ramp rising towards +z, its foot at z = 2.
		addBox(w, btVector3(5, btScalar(0.5), 10),
		       btTransform(btQuaternion(btVector3(1, 0, 0), -angle),
		                   btVector3(0, -btScalar(0.5) / btCos(angle) + 10 * btSin(angle), 2 + 10 * btCos(angle))));
		Character c(w, btVector3(0, 0, 0), btScalar(0.2));
		w.run(30, kStep);
		c->setWalkDirection(btVector3(0, 0, btScalar(0.05)));
		w.run(240, kStep);
		if (degrees < 45)
			EXPECT_GT(c.feet().y(), btScalar(3)) << degrees << " degrees: walked up";
		else
			EXPECT_LT(c.feet().y(), btScalar(0.5)) << degrees << " degrees: held back (step height 0.2)";
	}
}

TEST(KinematicCharacterController, StandsOnASlopeBelowTheLimitWithoutSliding)
{
	TestWorld w;
	const btScalar angle = btRadians(btScalar(40));
	addBox(w, btVector3(20, btScalar(0.5), 20),
	       btTransform(btQuaternion(btVector3(1, 0, 0), -angle), btVector3(0, -btScalar(0.5) / btCos(angle), 0)));
	Character c(w, btVector3(0, btScalar(0.3), 0));
	w.run(60, kStep);
	const btVector3 start = c.feet();
	w.run(600, kStep);
	EXPECT_LT((c.feet() - start).length(), btScalar(1e-3)) << "drift over 10 s";
	EXPECT_TRUE(c->onGround());
}

TEST(KinematicCharacterController, JumpApexIsVSquaredOverTwoGAndItIsAirborneUntilLanding)
{
	TestWorld w;
	w.addGround();
	Character c(w, btVector3(0, 0, 0));
	w.run(30, kStep);
	ASSERT_TRUE(c->onGround());
	ASSERT_TRUE(c->canJump());
	const btScalar y0 = c.feet().y();
	c->jump();
	EXPECT_FALSE(c->onGround()) << "airborne from take-off";
	btScalar apex = y0;
	int airborneSteps = 0;
	while (!c->onGround() && airborneSteps < 600)
	{
		w.run(1, kStep);
		apex = btMax(apex, c.feet().y());
		if (!c->onGround()) ++airborneSteps;
	}
	const btScalar g = btScalar(9.8 * 3), v = 10;
	// Gravity is integrated exactly per substep, so the sampled apex is within g h^2 / 8 of v^2 / (2 g).
	EXPECT_NEAR(apex - y0, v * v / (2 * g), btScalar(0.005));
	// Time of flight 2 v / g (40.8 substeps): onGround stayed false through the apex until landing.
	EXPECT_NEAR(airborneSteps, 2 * v / g / kStep, 2);
}

TEST(KinematicCharacterController, DoesNotPassAWallAt20MetresPerSecond)
{
	TestWorld w;
	w.addGround();
	addBox(w, btVector3(5, 2, btScalar(0.05)), at(btVector3(0, 2, 3)));  // 10 cm thick
	Character c(w, btVector3(0, 0, 0));
	w.run(10, kStep);
	c->setVelocityForTimeInterval(btVector3(0, 0, 20), 2);
	w.run(120, kStep);
	EXPECT_LT(c.feet().z(), btScalar(3 - 0.05 - kRadius + 0.01));
	EXPECT_GT(c.feet().z(), btScalar(3 - 0.05 - kRadius - 0.02)) << "it reached the wall";
}

TEST(KinematicCharacterController, DoesNotSlipThroughACornerAt20MetresPerSecond)
{
	// Two 10 cm walls meeting at a right angle; the character runs diagonally into the corner, where the
	// two surfaces' pushes meet, at 20 m/s (a third of a metre per step, more than the walls' thickness).
	TestWorld w;
	w.addGround();
	const btScalar half = btScalar(0.05);
	addBox(w, btVector3(5, 2, half), at(btVector3(0, 2, 3)));
	addBox(w, btVector3(half, 2, 5), at(btVector3(3, 2, 0)));
	Character c(w, btVector3(0, 0, 0));
	w.run(10, kStep);
	const btScalar diagonal = btScalar(20) / btSqrt(btScalar(2));
	c->setVelocityForTimeInterval(btVector3(diagonal, 0, diagonal), 2);
	btScalar farthestX = -BT_LARGE_FLOAT, farthestZ = -BT_LARGE_FLOAT;
	for (int i = 0; i < 120; ++i)
	{
		w.run(1, kStep);
		farthestX = btMax(farthestX, c.feet().x());
		farthestZ = btMax(farthestZ, c.feet().z());
	}
	// The capsule's surface stops at each wall's inner face (within the 1 cm the sweeps keep as skin).
	const btScalar limit = 3 - half - kRadius;
	EXPECT_LT(farthestX, limit + btScalar(0.01)) << "never through the wall at x = 3";
	EXPECT_LT(farthestZ, limit + btScalar(0.01)) << "never through the wall at z = 3";
	EXPECT_GT(c.feet().x(), limit - btScalar(0.02)) << "it reached the corner";
	EXPECT_GT(c.feet().z(), limit - btScalar(0.02));
}

TEST(KinematicCharacterController, RidesAMovingPlatformWithoutSliding)
{
	TestWorld w;
	w.addGround();
	btRigidBody* platform = w.addBody(w.shape<btBoxShape>(btVector3(2, btScalar(0.1), 2)), 0, btVector3(0, 1, 0));
	platform->setCollisionFlags(platform->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
	platform->setActivationState(DISABLE_DEACTIVATION);
	Character c(w, btVector3(0, btScalar(1.1), 0));
	w.run(30, kStep);
	ASSERT_TRUE(c->onGround());
	const btVector3 offset = c.feet() - platform->getWorldTransform().getOrigin();
	// The platform moves at 1 m/s along x and 0.5 m/s up (a lift) for 3 s.
	for (int i = 0; i < 180; ++i)
	{
		btTransform pose = platform->getWorldTransform();
		pose.setOrigin(pose.getOrigin() + btVector3(1, btScalar(0.5), 0) * kStep);
		platform->getMotionState()->setWorldTransform(pose);
		w.run(1, kStep);
	}
	const btVector3 drift = c.feet() - platform->getWorldTransform().getOrigin() - offset;
	EXPECT_NEAR(platform->getWorldTransform().getOrigin().x(), 3, btScalar(0.02));
	EXPECT_LT(drift.length(), btScalar(0.01)) << "moved " << drift.x() << ", " << drift.y() << ", " << drift.z()
	                                          << " relative to the platform";
	EXPECT_TRUE(c->onGround());
}

TEST(KinematicCharacterController, WalkingIntoACornerDoesNotJitter)
{
	// Two walls meeting at a right angle; the character walks diagonally into the corner for 5 s.
	TestWorld w;
	w.addGround();
	addBox(w, btVector3(5, 2, btScalar(0.1)), at(btVector3(0, 2, 3)));
	addBox(w, btVector3(btScalar(0.1), 2, 5), at(btVector3(3, 2, 0)));
	Character c(w, btVector3(0, 0, 0));
	w.run(10, kStep);
	c->setWalkDirection(btVector3(btScalar(0.05), 0, btScalar(0.05)));
	w.run(120, kStep);
	const btVector3 settled = c.feet();
	btScalar worst = 0;
	for (int i = 0; i < 300; ++i)
	{
		w.run(1, kStep);
		worst = btMax(worst, (c.feet() - settled).length());
	}
	EXPECT_NEAR(settled.x(), 3 - btScalar(0.1) - kRadius, btScalar(0.01)) << "it reached the corner";
	EXPECT_NEAR(settled.z(), 3 - btScalar(0.1) - kRadius, btScalar(0.01));
	EXPECT_LT(worst, btScalar(1e-4)) << "largest excursion in the corner over 5 s";
}

TEST(KinematicCharacterControllerBadInput, NonFiniteWalkAndZeroUpAreRejected)
{
	caliber_test::WarningCounter warnings;
	TestWorld w;
	w.addGround();
	Character c(w, btVector3(0, 0, 0));
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(c->setWalkDirection(btVector3(nan, 0, 0)), "non-finite direction");
	EXPECT_DEATH(c->setUp(btVector3(0, 0, 0)), "zero or non-finite up");
	EXPECT_DEATH(c->setVelocityForTimeInterval(btVector3(0, 0, nan), 1), "non-finite velocity");
#else
	c->setWalkDirection(btVector3(nan, 0, 0));
	c->setUp(btVector3(0, 0, 0));
	c->setVelocityForTimeInterval(btVector3(0, 0, nan), 1);
	EXPECT_EQ(warnings.count(), 3);
#endif
	EXPECT_EQ(c->getUp(), btVector3(0, 1, 0));
	w.run(60, kStep);
	EXPECT_TRUE(btIsFinite(c.feet().x()) && btIsFinite(c.feet().y()) && btIsFinite(c.feet().z()));
	EXPECT_TRUE(c->onGround());
}

TEST(KinematicCharacterControllerBadInput, NullGhostOrShapeIsReported)
{
	caliber_test::WarningCounter warnings;
	TestWorld w;
	btCapsuleShape shape(kRadius, kCylinder);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btKinematicCharacterController(0, &shape, btScalar(0.3), btVector3(0, 1, 0)), "null ghost");
#else
	btKinematicCharacterController controller(0, &shape, btScalar(0.3), btVector3(0, 1, 0));
	w.world()->addAction(&controller);
	w.run(10, kStep);
	w.world()->removeAction(&controller);
	EXPECT_EQ(warnings.count(), 1);
#endif
}

TEST(KinematicCharacterControllerBadInput, GhostRemovedWhileTheControllerIsStillAnActionWaits)
{
	caliber_test::WarningCounter warnings;
	TestWorld w;
	w.addGround();
	Character c(w, btVector3(0, 0, 0));
	w.run(10, kStep);
	w.world()->removeCollisionObject(c.ghost());
	c->setWalkDirection(btVector3(0, 0, btScalar(0.05)));
	const btVector3 parked = c.feet();
	w.run(60, kStep);
	EXPECT_EQ(warnings.count(), 1) << "reported once, not every substep";
	EXPECT_EQ(c.feet(), parked);
	w.world()->addCollisionObject(c.ghost(), btBroadphaseProxy::CharacterFilter,
	                              btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
	w.run(60, kStep);
	EXPECT_NEAR(c.feet().z() - parked.z(), btScalar(3), btScalar(0.01)) << "added back, it walks again";
}
