// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDiscreteDynamicsWorld as a facade: a subclass written for Bullet, reaching Bullet's protected stages
// and members, compiles and runs Bullet's pipeline (docs/architecture.md, "Bullet's classes are a facade").

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "Caliber/JointPositionCorrection.h"
#include "DynamicsWorldTestUtil.h"
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

namespace
{
// Bullet's way of adding predictive contacts from a subclass: each substep the base releases last step's
// manifolds; the subclass then makes its own through the dispatcher, under m_predictiveManifoldsMutex.
class PredictiveWorld : public btDiscreteDynamicsWorld
{
public:
	using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
	btRigidBody* pairA = nullptr;
	btRigidBody* pairB = nullptr;
	int calls = 0;
	int predictiveManifolds() const { return m_predictiveManifolds.size(); }
	bool latencyInterpolation() const { return m_latencyMotionStateInterpolation; }
	void serializeParts()
	{
		serializeDynamicsWorldInfo(nullptr);
		serializeRigidBodies(nullptr);
	}

protected:
	void createPredictiveContacts(btScalar timeStep) override
	{
		btDiscreteDynamicsWorld::createPredictiveContacts(timeStep);
		++calls;
		if (m_nonStaticRigidBodies.size())
			createPredictiveContactsInternal(&m_nonStaticRigidBodies[0], m_nonStaticRigidBodies.size(), timeStep);
		btPersistentManifold* manifold = m_dispatcher1->getNewManifold(pairA, pairB);
		m_predictiveManifoldsMutex.lock();
		m_predictiveManifolds.push_back(manifold);
		m_predictiveManifoldsMutex.unlock();
	}
};
}  // namespace

TEST(DiscreteDynamicsWorldFacade, PredictiveContactsOfASubclassLiveForOneStep)
{
	// Caliber makes no predictive contacts of its own (speculative contacts cover fast bodies), but a
	// subclass that makes them as in Bullet has its override called once per substep, and each step's
	// manifolds are released at the next step and when the world goes.
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSphereShape ball(btScalar(0.5));
	btRigidBody a(1, nullptr, &ball, btVector3(1, 1, 1));
	btRigidBody b(1, nullptr, &ball, btVector3(1, 1, 1));
	btTransform far;
	far.setIdentity();
	far.setOrigin(btVector3(10, 0, 0));
	b.setWorldTransform(far);
	{
		PredictiveWorld world(&dispatcher, &broadphase, &solver, &configuration);
		world.setGravity(btVector3(0, 0, 0));
		world.addRigidBody(&a);
		world.addRigidBody(&b);
		world.pairA = &a;
		world.pairB = &b;
		EXPECT_TRUE(world.latencyInterpolation());
		for (int step = 0; step < 5; ++step) world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		EXPECT_EQ(world.calls, 5);
		EXPECT_EQ(world.predictiveManifolds(), 1) << "last step's manifolds are released before new ones";
		EXPECT_EQ(dispatcher.getNumManifolds(), 1) << "the bodies are far apart: no other manifold";
		world.removeRigidBody(&a);
		world.removeRigidBody(&b);
	}
	EXPECT_EQ(dispatcher.getNumManifolds(), 0) << "the world releases its predictive manifolds when it goes";
}

#if CALIBER_ASSERTS_ENABLED
TEST(DiscreteDynamicsWorldFacadeDeathTest, SerializationWithoutSerializerAsserts)
{
	// The protected parts and the public entry points all refuse a null serializer.
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	PredictiveWorld world(&dispatcher, &broadphase, &solver, &configuration);
	EXPECT_DEATH(world.serializeParts(), "assertion failed");
	EXPECT_DEATH(world.serialize(nullptr), "assertion failed");
	EXPECT_DEATH(world.btCollisionWorld::serialize(nullptr), "assertion failed");
}
#else
TEST(DiscreteDynamicsWorldFacade, SerializationWithoutSerializerWarnsAndWritesNothing)
{
	// Bullet would crash on a null serializer; Caliber reports it once per call and writes nothing.
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	PredictiveWorld world(&dispatcher, &broadphase, &solver, &configuration);
	caliber_test::WarningCounter warnings;
	world.serializeParts();
	EXPECT_EQ(warnings.count(), 2);
	world.serialize(nullptr);
	EXPECT_EQ(warnings.count(), 3) << "serialize reports once";
	world.btCollisionWorld::serialize(nullptr);
	EXPECT_EQ(warnings.count(), 4);
}
#endif
