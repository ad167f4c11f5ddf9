// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDiscreteDynamicsWorld as a facade: a subclass written for Bullet, reaching Bullet's protected stages
// and members, compiles and runs Bullet's pipeline (docs/architecture.md, "Bullet's classes are a facade").

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "Caliber/JointPositionCorrection.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// Bullet's internalSingleStepSimulation, written as a Bullet user would, from Bullet's protected stages.
class BulletStyleWorld : public btDiscreteDynamicsWorld
{
public:
	using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
	int sortedConstraintsSeen = 0;

protected:
	void internalSingleStepSimulation(btScalar timeStep) override
	{
		if (m_internalPreTickCallback) (*m_internalPreTickCallback)(this, timeStep);
		predictUnconstraintMotion(timeStep);
		btDispatcherInfo& dispatchInfo = getDispatchInfo();
		dispatchInfo.m_timeStep = timeStep;
		dispatchInfo.m_stepCount = 0;
		dispatchInfo.m_debugDraw = getDebugDrawer();
		performDiscreteCollisionDetection();
		calculateSimulationIslands();
		getSolverInfo().m_timeStep = timeStep;
		solveConstraints(getSolverInfo());
		sortedConstraintsSeen = m_sortedConstraints.size();
		integrateTransforms(timeStep);
		updateActions(timeStep);
		updateActivationState(timeStep);
		if (m_internalTickCallback) (*m_internalTickCallback)(this, timeStep);
	}
};

// A 14-link chain of balls hung from the world (long enough for the exact tree correction), swinging
// under gravity; returns every link's final position.
template <class World>
std::vector<btVector3> swingChain(int jointPositionIterations, int* sortedConstraintsSeen = nullptr)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	World world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, -10, 0));
	if (jointPositionIterations >= 0) caliber::setJointPositionIterations(world, jointPositionIterations);
	btSphereShape ball(btScalar(0.05));
	std::vector<std::unique_ptr<btRigidBody>> links;
	std::vector<std::unique_ptr<btPoint2PointConstraint>> joints;
	for (int i = 0; i < 14; ++i)
	{
		btVector3 inertia;
		ball.calculateLocalInertia(1, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, &ball, inertia);
		info.m_startWorldTransform.setOrigin(btVector3(btScalar(0.2) * (i + 1), 10, 0));
		links.emplace_back(new btRigidBody(info));
		links.back()->setSleepingThresholds(0, 0);
		world.addRigidBody(links.back().get());
		if (i == 0)
			joints.emplace_back(new btPoint2PointConstraint(*links[0], btVector3(-0.1, 0, 0)));
		else
			joints.emplace_back(
			    new btPoint2PointConstraint(*links[i - 1], *links[i], btVector3(0.1, 0, 0), btVector3(-0.1, 0, 0)));
		world.addConstraint(joints.back().get(), true);
	}
	for (int step = 0; step < 90; ++step) world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
	std::vector<btVector3> positions;
	for (auto& link : links) positions.push_back(link->getCenterOfMassPosition());
	for (auto& joint : joints) world.removeConstraint(joint.get());
	for (auto& link : links) world.removeRigidBody(link.get());
	if (sortedConstraintsSeen) *sortedConstraintsSeen = static_cast<BulletStyleWorld&>(world).sortedConstraintsSeen;
	return positions;
}
}  // namespace

TEST(DiscreteDynamicsWorldFacade, BulletStyleSubclassRunsTheWorldWithoutCaliberOnlyStages)
{
	int sortedConstraintsSeen = 0;
	const std::vector<btVector3> subclass = swingChain<BulletStyleWorld>(-1, &sortedConstraintsSeen);
	const std::vector<btVector3> withoutCorrection = swingChain<btDiscreteDynamicsWorld>(0);
	const std::vector<btVector3> withCorrection = swingChain<btDiscreteDynamicsWorld>(-1);
	EXPECT_EQ(sortedConstraintsSeen, 14) << "m_sortedConstraints keeps Bullet's meaning";
	bool correctionMovedSomething = false;
	for (size_t i = 0; i < subclass.size(); ++i)
	{
		for (int k = 0; k < 3; ++k)
			EXPECT_EQ(subclass[i][k], withoutCorrection[i][k])
			    << "link " << i << " axis " << k << ": the subclass should step exactly as the world without "
			    << "the joint position correction";
		correctionMovedSomething = correctionMovedSomething || !(withCorrection[i] == withoutCorrection[i]);
	}
	EXPECT_TRUE(correctionMovedSomething) << "the default world corrects joint positions";
}
