// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDiscreteDynamicsWorld::stepSimulation: the integrator against its exact discrete answer, fixed
// substeps, the accumulated remainder, clamping, the variable step, interpolated motion states and the
// tick callbacks.

#include <gtest/gtest.h>

#include <vector>

#include "DynamicsWorldTestUtil.h"

using caliber_test::TestWorld;

namespace
{
const btScalar kStep = btScalar(1. / 60.);

struct TickLog
{
	std::vector<btScalar> pre;
	std::vector<btScalar> post;
};

void preTick(btDynamicsWorld* world, btScalar timeStep)
{
	static_cast<TickLog*>(world->getWorldUserInfo())->pre.push_back(timeStep);
}

void postTick(btDynamicsWorld* world, btScalar timeStep)
{
	static_cast<TickLog*>(world->getWorldUserInfo())->post.push_back(timeStep);
}
}  // namespace

TEST(DiscreteDynamicsWorldStep, FreeFallMatchesSemiImplicitEulerExactly)
{
	// Semi-implicit Euler: v_k = v0 + k g h, x_n = x0 + h sum_{k=1..n} v_k = x0 + n h v0 + g h^2 n (n+1) / 2.
	// That is the integrator's exact discrete answer; the tolerance is float rounding over 120 steps.
	TestWorld w;
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(0, 100, 0));
	const btVector3 v0(3, 4, -2);
	ball->setLinearVelocity(v0);
	const btScalar g = -10;
	const int n = 120;
	w.run(n);
	const btScalar t = n * kStep;
	const btVector3 expected(v0.x() * t, 100 + v0.y() * t + g * kStep * kStep * n * (n + 1) / 2, v0.z() * t);
	const btVector3 actual = ball->getCenterOfMassPosition();
	for (int axis = 0; axis < 3; ++axis) EXPECT_NEAR(actual[axis], expected[axis], 2e-3) << "axis " << axis;
	EXPECT_NEAR(ball->getLinearVelocity().y(), v0.y() + g * t, 1e-3);
	// And it is not the continuous answer x0 + v0 t + g t^2 / 2, which differs by g h t / 2 = 0.167.
	EXPECT_GT(btFabs(actual.y() - (100 + v0.y() * t + g * t * t / 2)), btScalar(0.1));
}

TEST(DiscreteDynamicsWorldStep, ProjectileRangeMatchesTheDiscreteTrajectory)
{
	// Launched at 45 degrees from the ground plane y = 0 with speed 10 in g = 10: the continuous range is
	// v^2/g = 10 m. Discretely the body lands where its discrete height first drops below 0; we check the
	// range against the continuous value within one step of travel (v_x h = 0.118 m).
	TestWorld w;
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.05)), 1, btVector3(0, 0, 0));
	const btScalar speed = 10;
	const btScalar vx = speed * btSqrt(btScalar(0.5));
	ball->setLinearVelocity(btVector3(vx, vx, 0));
	btScalar landingX = 0;
	for (int i = 0; i < 300; ++i)
	{
		w.run(1);
		if (ball->getCenterOfMassPosition().y() < 0)
		{
			landingX = ball->getCenterOfMassPosition().x();
			break;
		}
	}
	EXPECT_NEAR(landingX, speed * speed / 10, vx * kStep + 1e-3);
}

TEST(DiscreteDynamicsWorldStep, SubstepsAccumulateTheRemainderAndClampToMaxSubSteps)
{
	TestWorld w;
	TickLog log;
	w.world()->setInternalTickCallback(postTick, &log);
	// Half a substep: nothing happens yet, the time waits.
	EXPECT_EQ(w.world()->stepSimulation(kStep / 2, 10, kStep), 0);
	EXPECT_EQ(log.post.size(), 0u);
	// The other half plus one full substep: two substeps.
	EXPECT_EQ(w.world()->stepSimulation(kStep * btScalar(1.5), 10, kStep), 2);
	EXPECT_EQ(log.post.size(), 2u);
	// A long frame: 60 substeps are due, only maxSubSteps = 3 run, the rest is dropped. (60.5 substeps of
	// time, because 1 / (1/60) rounds to 59.99... in float, and Bullet's semantics round down.)
	log.post.clear();
	EXPECT_EQ(w.world()->stepSimulation(btScalar(60.5) * kStep, 3, kStep), 60);
	EXPECT_EQ(log.post.size(), 3u);
	for (btScalar h : log.post) EXPECT_FLOAT_EQ(h, kStep);
	// Dropped time is not carried over: the next frame of one substep runs one substep.
	log.post.clear();
	EXPECT_EQ(w.world()->stepSimulation(kStep, 3, kStep), 1);
	EXPECT_EQ(log.post.size(), 1u);
}

TEST(DiscreteDynamicsWorldStep, MaxSubStepsZeroTakesOneVariableStep)
{
	TestWorld w;
	TickLog log;
	w.world()->setInternalTickCallback(postTick, &log);
	btRigidBody* ball = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(0, 10, 0));
	EXPECT_EQ(w.world()->stepSimulation(btScalar(0.013), 0), 1);
	ASSERT_EQ(log.post.size(), 1u);
	EXPECT_FLOAT_EQ(log.post[0], btScalar(0.013));
	// One semi-implicit Euler step of h: y = 10 + g h^2.
	EXPECT_NEAR(ball->getCenterOfMassPosition().y(), 10 - 10 * 0.013 * 0.013, 1e-5);
	// A zero step does nothing.
	EXPECT_EQ(w.world()->stepSimulation(btScalar(0), 0), 0);
	EXPECT_EQ(log.post.size(), 1u);
}

TEST(DiscreteDynamicsWorldStep, PreAndPostTickCallbacksBracketEverySubstep)
{
	TestWorld w;
	TickLog log;
	w.world()->setInternalTickCallback(preTick, &log, true);
	w.world()->setInternalTickCallback(postTick, &log, false);
	EXPECT_EQ(w.world()->stepSimulation(3 * kStep, 5, kStep), 3);
	EXPECT_EQ(log.pre.size(), 3u);
	EXPECT_EQ(log.post.size(), 3u);
}

TEST(DiscreteDynamicsWorldStep, MotionStateGetsThePoseInterpolatedOneSubstepBehind)
{
	// Constant velocity, no gravity. After 1.5 substeps of time one substep has run (x = v h) and half a
	// substep waits. With latency interpolation the motion state shows x = v h + v (0.5 h - h) = 0.5 v h:
	// halfway between the last two substeps, never ahead of the simulation.
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(0, 0, 0));
	const btScalar v = 6;
	body->setLinearVelocity(btVector3(v, 0, 0));
	EXPECT_EQ(w.world()->stepSimulation(kStep * btScalar(1.5), 10, kStep), 1);
	EXPECT_NEAR(body->getCenterOfMassPosition().x(), v * kStep, 1e-5);
	btTransform shown;
	body->getMotionState()->getWorldTransform(shown);
	EXPECT_NEAR(shown.getOrigin().x(), btScalar(0.5) * v * kStep, 1e-5);

	// Without latency interpolation the pose is extrapolated by the waiting time: 1.5 v h.
	w.world()->setLatencyMotionStateInterpolation(false);
	w.world()->synchronizeMotionStates();
	body->getMotionState()->getWorldTransform(shown);
	EXPECT_NEAR(shown.getOrigin().x(), btScalar(1.5) * v * kStep, 1e-5);
}

TEST(DiscreteDynamicsWorldStep, ForcesLastOneStepAndGravityFollowsTheWorld)
{
	TestWorld w(btVector3(0, 0, 0));
	btRigidBody* body = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 2, btVector3(0, 0, 0));
	// F = 4 on m = 2 for one step: v = a h = 2 h; then the force is cleared.
	body->applyCentralForce(btVector3(4, 0, 0));
	w.run(1);
	EXPECT_NEAR(body->getLinearVelocity().x(), 2 * kStep, 1e-6);
	EXPECT_TRUE(body->getTotalForce().fuzzyZero());
	w.run(1);
	EXPECT_NEAR(body->getLinearVelocity().x(), 2 * kStep, 1e-6);

	w.world()->setGravity(btVector3(0, -5, 0));
	EXPECT_FLOAT_EQ(body->getGravity().y(), -5);
	// A body that opts out keeps its own gravity.
	btRigidBody* floating = w.addBody(w.shape<btSphereShape>(btScalar(0.5)), 1, btVector3(5, 0, 0));
	floating->setFlags(floating->getFlags() | BT_DISABLE_WORLD_GRAVITY);
	floating->setGravity(btVector3(0, 0, 0));
	w.world()->setGravity(btVector3(0, -9, 0));
	EXPECT_FLOAT_EQ(floating->getGravity().y(), 0);
	w.run(10);
	EXPECT_FLOAT_EQ(floating->getLinearVelocity().y(), 0);
	EXPECT_LT(body->getLinearVelocity().y(), 0);
}

TEST(DiscreteDynamicsWorldStep, ActionsRunOncePerSubstep)
{
	struct CountingAction : public btActionInterface
	{
		int updates = 0;
		btScalar lastStep = 0;
		void updateAction(btCollisionWorld*, btScalar deltaTimeStep) override
		{
			++updates;
			lastStep = deltaTimeStep;
		}
		void debugDraw(btIDebugDraw*) override {}
	};
	TestWorld w;
	CountingAction action;
	w.world()->addAction(&action);
	w.world()->stepSimulation(4 * kStep, 10, kStep);
	EXPECT_EQ(action.updates, 4);
	EXPECT_FLOAT_EQ(action.lastStep, kStep);
	w.world()->removeAction(&action);
	w.run(2);
	EXPECT_EQ(action.updates, 4);
}

TEST(DiscreteDynamicsWorldStep, SameSceneTwiceGivesBitIdenticalStates)
{
	auto runScene = [](std::vector<btScalar>& state)
	{
		TestWorld w;
		w.addGround(btScalar(0.7), btScalar(0.2));
		btCollisionShape* box = w.shape<btBoxShape>(btVector3(0.5, 0.5, 0.5));
		btCollisionShape* ball = w.shape<btSphereShape>(btScalar(0.4));
		for (int i = 0; i < 24; ++i)
		{
			const btQuaternion tilt(btVector3(1, 0.3, 0.2).normalized(), btScalar(0.1) * i);
			w.addBody(
			    i % 3 ? box : ball, 1,
			    btTransform(tilt, btVector3(btScalar(0.3) * (i % 4), btScalar(1 + 1.1 * i), btScalar(0.2) * (i % 3))));
		}
		w.run(180);
		for (btRigidBody* body : w.bodies())
		{
			const btTransform& t = body->getWorldTransform();
			for (int k = 0; k < 3; ++k)
			{
				state.push_back(t.getOrigin()[k]);
				for (int j = 0; j < 3; ++j) state.push_back(t.getBasis()[k][j]);
				state.push_back(body->getLinearVelocity()[k]);
				state.push_back(body->getAngularVelocity()[k]);
			}
		}
	};
	std::vector<btScalar> first, second;
	runScene(first);
	runScene(second);
	ASSERT_EQ(first.size(), second.size());
	for (size_t i = 0; i < first.size(); ++i) ASSERT_EQ(first[i], second[i]) << "state value " << i;
}
