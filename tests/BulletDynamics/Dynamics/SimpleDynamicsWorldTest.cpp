// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSimpleDynamicsWorld: one variable step per call, every body in one solver group.

#include <gtest/gtest.h>

#include "LinearMath/btWarningHook.h"
#include "btBulletDynamicsCommon.h"

TEST(SimpleDynamicsWorld, FallsWithSemiImplicitEulerAndRestsOnTheGround)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSimpleDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	EXPECT_EQ(world.getWorldType(), BT_SIMPLE_DYNAMICS_WORLD);
	EXPECT_EQ(world.getGravity(), btVector3(0, 0, -10)) << "Bullet's default for this world";
	world.setGravity(btVector3(0, -10, 0));

	btBoxShape groundShape(btVector3(50, 1, 50));
	btRigidBody::btRigidBodyConstructionInfo groundInfo(0, 0, &groundShape);
	groundInfo.m_startWorldTransform.setOrigin(btVector3(0, -1, 0));
	btRigidBody ground(groundInfo);
	world.addRigidBody(&ground);

	btSphereShape ballShape(btScalar(0.5));
	btVector3 inertia;
	ballShape.calculateLocalInertia(1, inertia);
	btRigidBody::btRigidBodyConstructionInfo ballInfo(1, 0, &ballShape, inertia);
	ballInfo.m_startWorldTransform.setOrigin(btVector3(0, 10, 0));
	btRigidBody ball(ballInfo);
	world.addRigidBody(&ball);

	// Ten free-fall steps of h: y_n = y0 - g h^2 n (n + 1) / 2 (float rounding only).
	const btScalar h = btScalar(1. / 60.);
	for (int i = 0; i < 10; ++i) EXPECT_EQ(world.stepSimulation(h), 1);
	EXPECT_NEAR(ball.getCenterOfMassPosition().y(), 10 - 10 * h * h * 55, 1e-4);
	EXPECT_EQ(world.stepSimulation(0), 0) << "a zero step does nothing";

	// Then it comes to rest at its radius, to within one step's sag g h^2.
	for (int i = 0; i < 240; ++i) world.stepSimulation(h);
	EXPECT_NEAR(ball.getCenterOfMassPosition().y(), btScalar(0.5), 10 * h * h);

	world.removeRigidBody(&ball);
	world.removeRigidBody(&ground);
	EXPECT_EQ(world.getNumCollisionObjects(), 0);
}

// btSimpleDynamicsWorld has no action stage: addAction says so (a vehicle added there would silently do
// nothing otherwise) and the action is never run.
TEST(SimpleDynamicsWorld, AddActionIsReportedAndTheActionNeverRuns)
{
	struct CountingAction : btActionInterface
	{
		int updates = 0;
		void updateAction(btCollisionWorld*, btScalar) override { ++updates; }
		void debugDraw(btIDebugDraw*) override {}
	};
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSimpleDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	int warnings = 0;
	btSetWarningHook([](const char*, void* count) { ++*static_cast<int*>(count); }, &warnings);
	CountingAction action;
	world.addAction(&action);
	EXPECT_EQ(warnings, 1);
	for (int i = 0; i < 10; ++i) world.stepSimulation(btScalar(1. / 60.));
	EXPECT_EQ(action.updates, 0);
	world.removeAction(&action);
	EXPECT_EQ(warnings, 1) << "removing it is harmless";
	btSetWarningHook(0, 0);
}
