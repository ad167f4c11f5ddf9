// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bad input to the world: each case is reported (btReportWarning; btAssert in debug builds, so the
// release behaviour is tested only where btAssert is compiled out), rejected or quarantined, and the
// rest of the world keeps simulating with finite values.

#include <gtest/gtest.h>

#include <limits>

#include "Caliber/JointPositionCorrection.h"
#include "DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
bool finiteState(const btRigidBody* body)
{
	const btTransform& t = body->getWorldTransform();
	for (int k = 0; k < 3; ++k)
	{
		if (!btIsFinite(t.getOrigin()[k]) || !btIsFinite(body->getLinearVelocity()[k]) ||
		    !btIsFinite(body->getAngularVelocity()[k]))
			return false;
		for (int j = 0; j < 3; ++j)
			if (!btIsFinite(t.getBasis()[k][j])) return false;
	}
	return true;
}

const btScalar kNaN = std::numeric_limits<btScalar>::quiet_NaN();
const btScalar kInf = std::numeric_limits<btScalar>::infinity();
}  // namespace

TEST(DiscreteDynamicsWorldBadInput, NonFiniteBodyIsQuarantinedAndTheOthersKeepSimulating)
{
	WarningCounter warnings;
	TestWorld w;
	w.addGround();
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
	btRigidBody* bad = w.addBody(box, 1, btVector3(0, btScalar(0.5), 0));
	btRigidBody* neighbour = w.addBody(box, 1, btVector3(btScalar(0.9), btScalar(1.5), 0));
	w.run(5);
	// The state of a body goes bad behind the API's back (as a user's own integrator or a corrupted
	// transform would make it).
	bad->getWorldTransform().getOrigin().setX(kNaN);
	w.run(120);
	EXPECT_EQ(bad->getActivationState(), DISABLE_SIMULATION);
	EXPECT_TRUE(finiteState(bad)) << "the quarantined body is put back at its last finite pose";
	EXPECT_TRUE(finiteState(neighbour));
	// The neighbour, which was leaning on it, fell to the ground: the world kept simulating it.
	EXPECT_LT(neighbour->getCenterOfMassPosition().y(), btScalar(1.0));
	EXPECT_GE(warnings.count(), 1);
}

TEST(DiscreteDynamicsWorldBadInput, NonFiniteOrNegativeTimeStepIsRejected)
{
	WarningCounter warnings;
	TestWorld w;
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(0, 5, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.world()->stepSimulation(kNaN), "bad time step");
	EXPECT_DEATH(w.world()->stepSimulation(btScalar(-1)), "bad time step");
#else
	{
		EXPECT_EQ(w.world()->stepSimulation(kNaN), 0);
		EXPECT_EQ(w.world()->stepSimulation(kInf), 0);
		EXPECT_EQ(w.world()->stepSimulation(btScalar(-1)), 0);
		EXPECT_EQ(w.world()->stepSimulation(btScalar(1. / 60.), 1, btScalar(0)), 0);
		EXPECT_EQ(w.world()->stepSimulation(btScalar(1. / 60.), -1), 0);
		EXPECT_EQ(warnings.count(), 5);
		EXPECT_FLOAT_EQ(ball->getCenterOfMassPosition().y(), 5);
	}
#endif
	// The world is unharmed: a good step still works.
	EXPECT_EQ(w.world()->stepSimulation(btScalar(1. / 60.)), 1);
	EXPECT_LT(ball->getCenterOfMassPosition().y(), 5);
	EXPECT_TRUE(finiteState(ball));
}

TEST(DiscreteDynamicsWorldBadInput, BodyAddedTwiceOrRemovedWhenNeverAddedIsReportedAndIgnored)
{
	WarningCounter warnings;
	TestWorld w;
	btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.5));
	btRigidBody* body = w.addBody(ball, 1, btVector3(0, 5, 0));
	btRigidBody stranger(1, 0, ball, btVector3(1, 1, 1));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.world()->addRigidBody(body), "added twice");
	EXPECT_DEATH(w.world()->removeRigidBody(&stranger), "not in this world");
#else
	w.world()->addRigidBody(body);
	w.world()->removeRigidBody(&stranger);
	EXPECT_EQ(warnings.count(), 2);
#endif
	EXPECT_EQ(w.world()->getNumCollisionObjects(), 1);
	EXPECT_EQ(w.world()->getNonStaticRigidBodies().size(), 1);
	w.run(10);
	EXPECT_LT(body->getCenterOfMassPosition().y(), 5);
}

namespace
{
struct RemovalRequest
{
	btDiscreteDynamicsWorld* world;
	btRigidBody* victim;
	int ticks;
};

void removeOnThirdTick(btDynamicsWorld* world, btScalar)
{
	RemovalRequest* request = static_cast<RemovalRequest*>(world->getWorldUserInfo());
	if (++request->ticks == 3 && request->victim)
	{
		request->world->removeRigidBody(request->victim);
		request->victim = 0;
	}
}
}  // namespace

TEST(DiscreteDynamicsWorldBadInput, BodyRemovedFromATickCallbackLeavesTheWorldWorking)
{
	for (bool preTick : {false, true})
	{
		TestWorld w;
		w.addGround();
		btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
		btRigidBody* victim = w.addBody(box, 1, btVector3(0, btScalar(0.5), 0));
		btRigidBody* survivor = w.addBody(box, 1, btVector3(0, btScalar(1.6), 0));
		RemovalRequest request = {w.world(), victim, 0};
		w.world()->setInternalTickCallback(removeOnThirdTick, &request, preTick);
		// Several substeps in one call, so the removal happens between substeps of the same call.
		w.world()->stepSimulation(btScalar(10. / 60.), 10, btScalar(1. / 60.));
		EXPECT_EQ(request.victim, nullptr);
		EXPECT_EQ(w.world()->getNumCollisionObjects(), 2);
		w.run(120);
		// With its support gone, the survivor fell onto the ground.
		EXPECT_NEAR(survivor->getCenterOfMassPosition().y(), btScalar(0.5), btScalar(0.01));
		EXPECT_TRUE(finiteState(survivor));
	}
}

TEST(DiscreteDynamicsWorldBadInput, SetGravityRejectsNonFiniteValues)
{
	WarningCounter warnings;
	TestWorld w;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.world()->setGravity(btVector3(0, kNaN, 0)), "non-finite gravity");
#else
	w.world()->setGravity(btVector3(0, kNaN, 0));
	EXPECT_EQ(warnings.count(), 1);
#endif
	EXPECT_EQ(w.world()->getGravity(), btVector3(0, -10, 0));
}

TEST(DiscreteDynamicsWorldBadInput, JointPositionIterationsOutOfRangeAreReported)
{
	WarningCounter warnings;
	TestWorld w;
	caliber::setJointPositionIterations(*w.world(), 5);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(caliber::setJointPositionIterations(*w.world(), -1), "out of range");
	EXPECT_DEATH(caliber::setJointPositionIterations(*w.world(), 1 << 30), "out of range");
#else
	// Negative: ignored, the last good count stays. Huge: clamped, so a garbage count cannot stall the step.
	caliber::setJointPositionIterations(*w.world(), -1);
	EXPECT_EQ(caliber::getJointPositionIterations(*w.world()), 5);
	caliber::setJointPositionIterations(*w.world(), 1 << 30);
	EXPECT_EQ(caliber::getJointPositionIterations(*w.world()), 1024);
	EXPECT_EQ(warnings.count(), 2);
#endif
	// Each world has its own setting.
	TestWorld other;
	EXPECT_EQ(caliber::getJointPositionIterations(*other.world()), 3);
}
