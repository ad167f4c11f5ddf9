// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Joint warm starting lives in the solver (src/BulletDynamics/ConstraintSolver/btJointWarmStart.h), not in
// btTypedConstraint: a joint starts from its own last impulses and never from another joint's, whatever
// happens to it between solves (dies, changes its row count, sleeps, meets another solver).

#include <gtest/gtest.h>

#include <memory>
#include <new>

#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// A user joint written as for Bullet: `rows` soft rows that brake body A along three coupled axes, x,
// (x+y)/sqrt2 and (x+y+z)/sqrt3. Coupled soft rows make one Gauss-Seidel sweep inexact, so its result
// depends on the impulses the sweep starts from: that is what lets these tests see warm starting.
class CoupledBrake : public btTypedConstraint
{
public:
	CoupledBrake(btRigidBody& body, int rows) : btTypedConstraint(D6_CONSTRAINT_TYPE, body), m_rows(rows) {}
	void getInfo1(btConstraintInfo1* info) override
	{
		info->m_numConstraintRows = m_rows;
		info->nub = 0;
	}
	void getInfo2(btConstraintInfo2* info) override
	{
		for (int row = 0; row < m_rows; ++row)
		{
			btVector3 axis(1, row >= 1 ? 1 : 0, row >= 2 ? 1 : 0);
			axis.normalize();
			for (int k = 0; k < 3; ++k) info->m_J1linearAxis[row * info->rowskip + k] = axis[k];
			info->cfm[row * info->rowskip] = btScalar(0.5);
		}
	}
	void setParam(int, btScalar, int) override {}
	btScalar getParam(int, int) const override { return 0; }
	void setRows(int rows) { m_rows = rows; }

private:
	int m_rows;
};

// One body outside any world, and a solver driven directly.
struct DirectSolve
{
	btSphereShape shape{btScalar(0.5)};
	std::unique_ptr<btRigidBody> body;
	btContactSolverInfo info;

	DirectSolve()
	{
		btVector3 inertia;
		shape.calculateLocalInertia(2, inertia);
		body.reset(new btRigidBody(2, nullptr, &shape, inertia));
		info.m_numIterations = 1;
		info.m_timeStep = btScalar(1. / 60.);
		info.m_solverMode |= SOLVER_USE_WARMSTARTING;
	}

	// The body's velocity after one solve of joint from the same starting velocity.
	btVector3 solve(btSequentialImpulseConstraintSolver& solver, btTypedConstraint* joint, bool warmStart = true)
	{
		body->setLinearVelocity(btVector3(3, 2, 1));
		body->setAngularVelocity(btVector3(0, 0, 0));
		btContactSolverInfo solveInfo = info;
		if (!warmStart) solveInfo.m_solverMode &= ~SOLVER_USE_WARMSTARTING;
		btCollisionObject* bodies[1] = {body.get()};
		solver.solveGroup(bodies, 1, nullptr, 0, &joint, 1, solveInfo, nullptr, nullptr);
		return body->getLinearVelocity();
	}
};

int entriesOf(btSequentialImpulseConstraintSolver& solver)
{
	return caliber::solverScratchOf(solver).warmStarts.size();
}

bool hasEntry(btSequentialImpulseConstraintSolver& solver, const btTypedConstraint* joint)
{
	caliber::JointWarmStartStore& store = caliber::solverScratchOf(solver).warmStarts;
	std::lock_guard<std::mutex> lock(store.mutex());
	return store.find(joint) != nullptr;
}

void expectSameVelocity(const btVector3& a, const btVector3& b)
{
	EXPECT_EQ(a.x(), b.x());
	EXPECT_EQ(a.y(), b.y());
	EXPECT_EQ(a.z(), b.z());
}
}  // namespace

TEST(JointWarmStart, WarmStartChangesAOneSweepSolve)
{
	// The other tests compare a solve with a cold one; this one shows that the comparison can fail:
	// a joint that has impulses of its own starts from them and ends elsewhere after one sweep.
	DirectSolve rig;
	btSequentialImpulseConstraintSolver solver;
	CoupledBrake joint(*rig.body, 3);
	for (int i = 0; i < 3; ++i) rig.solve(solver, &joint);
	const btVector3 warm = rig.solve(solver, &joint);
	const btVector3 cold = rig.solve(solver, &joint, false);
	EXPECT_GT((warm - cold).length(), btScalar(1e-4)) << "warm " << warm.x() << " cold " << cold.x();
}

TEST(JointWarmStart, JointBuiltAtADeadJointsAddressStartsCold)
{
	// A joint destroyed and another built in its storage: the solver must not hand the new joint the dead
	// one's impulses. Its first solve is bit for bit a cold solve.
	DirectSolve rig;
	btSequentialImpulseConstraintSolver solver;
	alignas(CoupledBrake) unsigned char storage[sizeof(CoupledBrake)];
	CoupledBrake* first = new (storage) CoupledBrake(*rig.body, 3);
	for (int i = 0; i < 3; ++i) rig.solve(solver, first);
	const btVector3 cold = rig.solve(solver, first, false);
	EXPECT_TRUE(hasEntry(solver, first));
	first->~CoupledBrake();
	EXPECT_EQ(entriesOf(solver), 0) << "a dead joint's impulses are dropped";

	CoupledBrake* second = new (storage) CoupledBrake(*rig.body, 3);
	ASSERT_EQ(static_cast<void*>(second), static_cast<void*>(first));
	expectSameVelocity(rig.solve(solver, second), cold);
	second->~CoupledBrake();
}

TEST(JointWarmStart, ChangedRowCountStartsCold)
{
	// A joint whose row count changes (a limit switching on or off) cannot reuse impulses that belong to
	// other rows: the first solve with the new count is a cold one; the next is warm again. A step without
	// rows drops the impulses.
	DirectSolve rig;
	btSequentialImpulseConstraintSolver solver;
	CoupledBrake joint(*rig.body, 2);
	for (int i = 0; i < 3; ++i) rig.solve(solver, &joint);
	joint.setRows(3);
	const btVector3 firstWithThreeRows = rig.solve(solver, &joint);
	const btVector3 cold = rig.solve(solver, &joint, false);
	expectSameVelocity(firstWithThreeRows, cold);
	const btVector3 warm = rig.solve(solver, &joint);
	EXPECT_GT((warm - cold).length(), btScalar(1e-4));

	joint.setRows(0);
	rig.solve(solver, &joint);
	EXPECT_FALSE(hasEntry(solver, &joint)) << "a joint without rows keeps no impulses";
	joint.setRows(3);
	expectSameVelocity(rig.solve(solver, &joint), cold);
}

TEST(JointWarmStart, EachSolverKeepsItsOwnImpulses)
{
	// Two solvers (two worlds) may solve the same joint: each starts from what it computed itself, and
	// the joint's death clears both.
	DirectSolve rig;
	btSequentialImpulseConstraintSolver first, second;
	std::unique_ptr<CoupledBrake> joint(new CoupledBrake(*rig.body, 3));
	for (int i = 0; i < 3; ++i) rig.solve(first, joint.get());
	const btVector3 cold = rig.solve(first, joint.get(), false);
	expectSameVelocity(rig.solve(second, joint.get()), cold);
	EXPECT_EQ(entriesOf(first), 1);
	EXPECT_EQ(entriesOf(second), 1);
	joint.reset();
	EXPECT_EQ(entriesOf(first), 0);
	EXPECT_EQ(entriesOf(second), 0);
}

TEST(JointWarmStart, DeadJointsLeaveNothingBehind)
{
	// Many short-lived joints (built, solved, destroyed): the store holds only the living ones.
	DirectSolve rig;
	btSequentialImpulseConstraintSolver solver;
	CoupledBrake keeper(*rig.body, 1);
	for (int i = 0; i < 1000; ++i)
	{
		std::unique_ptr<CoupledBrake> joint(new CoupledBrake(*rig.body, 1 + i % 3));
		btTypedConstraint* joints[2] = {&keeper, joint.get()};
		btCollisionObject* bodies[1] = {rig.body.get()};
		solver.solveGroup(bodies, 1, nullptr, 0, joints, 2, rig.info, nullptr, nullptr);
	}
	EXPECT_EQ(entriesOf(solver), 1);
	EXPECT_TRUE(hasEntry(solver, &keeper));
}

TEST(JointWarmStart, JointMayOutliveItsSolverAndTheOtherWayRound)
{
	// Misuse-proof lifetimes: a solver destroyed before the joints it solved, and joints destroyed before
	// their solver (the sanitizer build checks that neither touches freed memory).
	DirectSolve rig;
	CoupledBrake survivor(*rig.body, 3);
	{
		btSequentialImpulseConstraintSolver solver;
		rig.solve(solver, &survivor);
		{
			CoupledBrake shortLived(*rig.body, 2);
			rig.solve(solver, &shortLived);
		}
		EXPECT_EQ(entriesOf(solver), 1);
	}
	// A solver built later (perhaps at the dead one's address) starts the survivor cold.
	btSequentialImpulseConstraintSolver later;
	const btVector3 cold = rig.solve(later, &survivor, false);
	btSequentialImpulseConstraintSolver another;
	expectSameVelocity(rig.solve(another, &survivor), cold);
}

namespace
{
// A ball hung from the world on a point-to-point joint, in a world that lets it sleep.
struct HangingBall
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher{&configuration};
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
	btSphereShape shape{btScalar(0.1)};
	std::unique_ptr<btRigidBody> ball;

	HangingBall()
	{
		world.setGravity(btVector3(0, -10, 0));
		btVector3 inertia;
		shape.calculateLocalInertia(1, inertia);
		btRigidBody::btRigidBodyConstructionInfo info(1, nullptr, &shape, inertia);
		info.m_startWorldTransform.setOrigin(btVector3(0, 4, 0));
		ball.reset(new btRigidBody(info));
		world.addRigidBody(ball.get());
	}
	~HangingBall() { world.removeRigidBody(ball.get()); }
	void step(int steps)
	{
		for (int i = 0; i < steps; ++i) world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
	}
};

btAlignedObjectArray<btScalar> impulsesOf(btSequentialImpulseConstraintSolver& solver, const btTypedConstraint* joint)
{
	caliber::JointWarmStartStore& store = caliber::solverScratchOf(solver).warmStarts;
	std::lock_guard<std::mutex> lock(store.mutex());
	const caliber::JointImpulses* found = store.find(joint);
	return found ? *found : btAlignedObjectArray<btScalar>();
}
}  // namespace

TEST(JointWarmStart, SleepingJointKeepsItsImpulses)
{
	// An island that falls asleep is not solved; when it wakes its joints start from the impulses they had
	// when it fell asleep (the ball's weight, 10 N over 1/60 s, on the vertical row).
	HangingBall rig;
	btPoint2PointConstraint joint(*rig.ball, btVector3(0, 1, 0));
	rig.world.addConstraint(&joint);
	rig.step(240);
	ASSERT_FALSE(rig.ball->isActive()) << "the hanging ball should be asleep after 4 s at rest";
	const btAlignedObjectArray<btScalar> asleep = impulsesOf(rig.solver, &joint);
	ASSERT_EQ(asleep.size(), 3);
	btScalar vertical = 0;
	for (int i = 0; i < 3; ++i) vertical = btMax(vertical, btFabs(asleep[i]));
	EXPECT_NEAR(vertical, btScalar(10. / 60.), btScalar(1e-3));
	rig.step(120);
	const btAlignedObjectArray<btScalar> later = impulsesOf(rig.solver, &joint);
	ASSERT_EQ(later.size(), 3);
	for (int i = 0; i < 3; ++i) EXPECT_EQ(later[i], asleep[i]) << "row " << i;
	rig.world.removeConstraint(&joint);
}

TEST(JointWarmStart, JointRemovedDeletedAndReplacedAtTheSameAddressStartsCold)
{
	// In a world: a joint removed and deleted, and a new one built in its storage and added. The solver
	// forgets the dead joint's impulses at once, and the new joint gets its own.
	HangingBall rig;
	alignas(btPoint2PointConstraint) unsigned char storage[sizeof(btPoint2PointConstraint)];
	btPoint2PointConstraint* first = new (storage) btPoint2PointConstraint(*rig.ball, btVector3(0, 1, 0));
	rig.world.addConstraint(first);
	rig.step(10);
	EXPECT_TRUE(hasEntry(rig.solver, first));
	rig.world.removeConstraint(first);
	first->~btPoint2PointConstraint();
	EXPECT_FALSE(hasEntry(rig.solver, first));
	btPoint2PointConstraint* second = new (storage) btPoint2PointConstraint(*rig.ball, btVector3(0, 1, 0));
	rig.world.addConstraint(second);
	rig.step(1);
	EXPECT_EQ(impulsesOf(rig.solver, second).size(), 3);
	rig.world.removeConstraint(second);
	second->~btPoint2PointConstraint();
}
