// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The per-body stages that run on the task scheduler's threads (sleeping bookkeeping, the finiteness
// check of the quarantine, the motion states' poses) give the same bits as without a scheduler, at
// any thread count, in worlds with enough bodies that each loop is cut into several tasks.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "DynamicsWorldTestUtil.h"
#include "TestThreadsUtil.h"
#include "LinearMath/btThreads.h"

using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
// What one body ends a run with: its pose and velocities, its sleeping state and timer, and the pose its
// motion state was told (bit for bit).
struct BodyRecord
{
	btScalar values[12 + 6 + 1 + 12];
	int activationState;
};

bool operator==(const BodyRecord& a, const BodyRecord& b)
{
	return std::memcmp(a.values, b.values, sizeof(a.values)) == 0 && a.activationState == b.activationState;
}

void copyTransform(const btTransform& t, btScalar* out)
{
	for (int r = 0; r < 3; ++r)
		for (int c = 0; c < 3; ++c) out[r * 3 + c] = t.getBasis()[r][c];
	for (int k = 0; k < 3; ++k) out[9 + k] = t.getOrigin()[k];
}

std::vector<BodyRecord> record(const TestWorld& w)
{
	std::vector<BodyRecord> records;
	for (const btRigidBody* body : w.bodies())
	{
		BodyRecord r;
		std::memset(&r, 0, sizeof(r));
		copyTransform(body->getWorldTransform(), r.values);
		for (int k = 0; k < 3; ++k)
		{
			r.values[12 + k] = body->getLinearVelocity()[k];
			r.values[15 + k] = body->getAngularVelocity()[k];
		}
		r.values[18] = body->getDeactivationTime();
		btTransform shown;
		shown.setIdentity();
		if (body->getMotionState()) body->getMotionState()->getWorldTransform(shown);
		copyTransform(shown, r.values + 19);
		r.activationState = body->getActivationState();
		records.push_back(r);
	}
	return records;
}

// Rows of boxes and spheres resting apart on the ground (one island each), every fifth without a motion
// state, and every seventh thrown sideways so that it keeps moving for a while.
void buildRestingRows(TestWorld& w)
{
	w.addGround();
	btCollisionShape* box = w.shape<btBoxShape>(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
	btCollisionShape* sphere = w.shape<btSphereShape>(btScalar(0.4));
	for (int i = 0; i < 300; ++i)
	{
		const btVector3 at(btScalar(i % 20) * 2 - 20, btScalar(0.45), btScalar(i / 20) * 2 - 15);
		btRigidBody* body = w.addBody(i % 3 ? box : sphere, 1, at, i % 5 != 0);
		if (i % 7 == 0) body->setLinearVelocity(btVector3(btScalar(3), 0, btScalar(1)));
	}
}

std::vector<BodyRecord> runRestingRows(btITaskScheduler* scheduler, int threads, int steps)
{
	btSetTaskScheduler(scheduler);
	if (scheduler) scheduler->setNumThreads(threads);
	TestWorld w;
	buildRestingRows(w);
	w.run(steps);
	std::vector<BodyRecord> result = record(w);
	btSetTaskScheduler(0);
	return result;
}
}  // namespace

TEST(PerBodyStagesThreads, SleepingAndMotionStatesAreTheSameAtAnyThreadCount)
{
	// 150 steps of 1/60 s: more than the 2 s a resting body waits before it may sleep (gDeactivationTime),
	// not enough for the thrown bodies to stop, so some islands sleep and some are awake.
	const int steps = 150;
	const std::vector<BodyRecord> reference = runRestingRows(0, 1, steps);
	int sleeping = 0, awake = 0;
	for (const BodyRecord& r : reference)
	{
		if (r.activationState == ISLAND_SLEEPING) ++sleeping;
		if (r.activationState == ACTIVE_TAG) ++awake;
	}
	ASSERT_GT(sleeping, 100) << "the scene must put islands to sleep for the test to check sleeping";
	ASSERT_GT(awake, 0) << "and keep some awake";
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	if (!pool) GTEST_SKIP() << "a library without threads";
	for (int threads : {1, 2, 3})
	{
		const std::vector<BodyRecord> run = runRestingRows(pool.get(), threads, steps);
		ASSERT_EQ(run.size(), reference.size());
		for (size_t i = 0; i < run.size(); ++i)
			EXPECT_TRUE(run[i] == reference[i]) << "body " << i << " at " << threads << " threads";
	}
}

// As the mesh scenes of the benchmark: bodies falling apart from each other, so that most leave their fat
// boxes every other step and their leaves are re-inserted (the tree moves run on one task while the other
// threads compute the boxes after them, btCollisionWorld::updateAabbs); three layers, so that the lower
// ones land and the upper ones land on them. Plain and Mt world, no scheduler, the pool at 1, 2 and 3
// threads and a scheduler that cuts the loops unevenly: the same bits.
TEST(PerBodyStagesThreads, FallingBodiesLeavingTheirFatBoxesEndTheSameAtAnyThreadCount)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	caliber_test::UnevenSplitScheduler uneven;
	for (bool multithreaded : {false, true})
	{
		std::vector<std::vector<BodyRecord>> runs;
		for (int threads : {0, 1, 2, 3, -1})  // 0: no scheduler; -1: the uneven scheduler
		{
			if (threads > 0 && !pool) continue;
			btITaskScheduler* scheduler = threads > 0 ? pool.get() : (threads < 0 ? &uneven : 0);
			btSetTaskScheduler(scheduler);
			if (threads > 0) pool->setNumThreads(threads);
			std::unique_ptr<TestWorld> w(multithreaded ? new TestWorld(TestWorld::Multithreaded(), BT_MAX_THREAD_COUNT)
			                                           : new TestWorld());
			w->addGround();
			btCollisionShape* shapes[3] = {
			    w->shape<btBoxShape>(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4))),
			    w->shape<btSphereShape>(btScalar(0.4)), w->shape<btCapsuleShape>(btScalar(0.3), btScalar(0.5))};
			for (int i = 0; i < 300; ++i)
			{
				const int layer = i / 100, k = i % 100;
				const btVector3 at(btScalar(k % 10) * 3 - 15 + btScalar(0.1) * layer, btScalar(2 + 2 * layer),
				                   btScalar(k / 10) * 3 - 15);
				w->addBody(shapes[(i * 7) % 3], 1, at, i % 4 != 0);
			}
			unsigned moved = 0;
			for (int step = 0; step < 90; ++step)
			{
				w->run(1);
				moved += static_cast<btDbvtBroadphase*>(w->world()->getBroadphase())->m_updates_ratio > btScalar(0.3);
			}
			EXPECT_GT(moved, 20u) << "the bodies must leave their fat boxes in many steps for the test to check them";
			runs.push_back(record(*w));
			w.reset();
			btSetTaskScheduler(0);
		}
		for (size_t r = 1; r < runs.size(); ++r)
		{
			ASSERT_EQ(runs[r].size(), runs[0].size());
			for (size_t i = 0; i < runs[0].size(); ++i)
				EXPECT_TRUE(runs[r][i] == runs[0][i]) << "body " << i << ", run " << r << ", Mt world " << multithreaded;
		}
	}
}

TEST(PerBodyStagesThreads, NonFiniteBodyIsQuarantinedTheSameAtAnyThreadCount)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	std::vector<std::vector<BodyRecord>> runs;
	for (int threads : {0, 1, 2, 3})  // 0: no scheduler
	{
		if (threads > 0 && !pool) break;
		WarningCounter warnings;
		btSetTaskScheduler(threads > 0 ? pool.get() : 0);
		if (threads > 0) pool->setNumThreads(threads);
		TestWorld w;
		buildRestingRows(w);
		w.run(5);
		// One body's state goes bad behind the API's back, in a late task of the per-body loops.
		btRigidBody* bad = w.bodies()[250];
		bad->getWorldTransform().getOrigin().setY(std::numeric_limits<btScalar>::quiet_NaN());
		w.run(20);
		btSetTaskScheduler(0);
		EXPECT_EQ(bad->getActivationState(), DISABLE_SIMULATION) << threads << " threads";
		EXPECT_EQ(bad->getBroadphaseHandle(), nullptr) << "it left the broadphase";
		EXPECT_EQ(warnings.count(), 1) << "one warning per world";
		runs.push_back(record(w));
	}
	for (size_t run = 1; run < runs.size(); ++run)
	{
		ASSERT_EQ(runs[run].size(), runs[0].size());
		for (size_t i = 0; i < runs[0].size(); ++i)
			EXPECT_TRUE(runs[run][i] == runs[0][i]) << "body " << i << ", run " << run;
	}
}

namespace
{
// A user's motion state that is not thread-safe: every call appends its body's number to one shared log
// and counts the calls made on a thread other than the one that steps the world.
class LoggingMotionState : public btMotionState
{
public:
	LoggingMotionState(const btTransform& pose, int body, std::vector<int>* log, int* foreignCalls)
	    : m_pose(pose), m_body(body), m_log(log), m_foreignCalls(foreignCalls), m_stepper(std::this_thread::get_id())
	{
	}
	void getWorldTransform(btTransform& pose) const override { pose = m_pose; }
	void setWorldTransform(const btTransform& pose) override
	{
		m_pose = pose;
		m_log->push_back(m_body);
		if (std::this_thread::get_id() != m_stepper) ++*m_foreignCalls;
	}

private:
	btTransform m_pose;
	int m_body;
	std::vector<int>* m_log;
	int* m_foreignCalls;
	std::thread::id m_stepper;
};

// A subclass of btDefaultMotionState with a setWorldTransform of its own, which may not be thread-safe
// either: it logs as LoggingMotionState does.
class LoggingDefaultMotionState : public btDefaultMotionState
{
public:
	LoggingDefaultMotionState(const btTransform& pose, int body, std::vector<int>* log, int* foreignCalls)
	    : btDefaultMotionState(pose), m_body(body), m_log(log), m_foreignCalls(foreignCalls),
	      m_stepper(std::this_thread::get_id())
	{
	}
	void setWorldTransform(const btTransform& pose) override
	{
		btDefaultMotionState::setWorldTransform(pose);
		m_log->push_back(m_body);
		if (std::this_thread::get_id() != m_stepper) ++*m_foreignCalls;
	}

private:
	int m_body;
	std::vector<int>* m_log;
	int* m_foreignCalls;
	std::thread::id m_stepper;
};

struct MotionStateRun
{
	std::vector<BodyRecord> bodies;
	std::vector<int> log;  // the logging motion states' calls, in call order
	int foreignCalls = 0;
	btScalar sharedPose[12];  // the pose last told to the motion state two bodies share for a while
};

// 300 boxes falling apart from each other (all awake, so that every body's motion state is told each
// step): most with their own btDefaultMotionState, every ninth with a LoggingMotionState, every eleventh
// with a LoggingDefaultMotionState, every thirteenth with none. From step 10 to 25 bodies 20 and 250 share
// one btDefaultMotionState (the serial loop leaves it with body 250's pose, the later one in body order).
MotionStateRun runMotionStates(btITaskScheduler* scheduler, int threads, bool multithreaded)
{
	btSetTaskScheduler(scheduler);
	if (scheduler && threads > 0) scheduler->setNumThreads(threads);
	MotionStateRun run;
	std::unique_ptr<TestWorld> w(multithreaded ? new TestWorld(TestWorld::Multithreaded(), BT_MAX_THREAD_COUNT)
	                                           : new TestWorld());
	w->addGround();
	btCollisionShape* box = w->shape<btBoxShape>(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
	std::vector<std::unique_ptr<btMotionState>> own;
	for (int i = 0; i < 300; ++i)
	{
		const btVector3 at(btScalar(i % 20) * 2 - 20, btScalar(5 + (i % 3)), btScalar(i / 20) * 2 - 15);
		btRigidBody* body = w->addBody(box, 1, at, i % 13 != 0);
		const btTransform pose(btQuaternion::getIdentity(), at);
		btMotionState* state = 0;
		if (i % 9 == 0)
			state = new LoggingMotionState(pose, i, &run.log, &run.foreignCalls);
		else if (i % 11 == 0)
			state = new LoggingDefaultMotionState(pose, i, &run.log, &run.foreignCalls);
		if (state)
		{
			own.emplace_back(state);
			body->setMotionState(state);
		}
	}
	btRigidBody* first = w->bodies()[1 + 20];  // w->bodies()[0] is the ground
	btRigidBody* second = w->bodies()[1 + 250];
	btMotionState* firstOwn = first->getMotionState();
	btMotionState* secondOwn = second->getMotionState();
	btDefaultMotionState shared(first->getWorldTransform());
	// setMotionState reads the body's pose from the motion state: put each body back where it was.
	const auto give = [](btRigidBody* body, btMotionState* state) {
		const btTransform pose = body->getWorldTransform();
		body->setMotionState(state);
		body->setWorldTransform(pose);
	};
	for (int step = 0; step < 40; ++step)
	{
		if (step == 10)
		{
			give(first, &shared);
			give(second, &shared);
		}
		if (step == 25)
		{
			copyTransform(shared.m_graphicsWorldTrans, run.sharedPose);
			give(first, firstOwn);
			give(second, secondOwn);
		}
		w->run(1);
	}
	run.bodies = record(*w);
	w.reset();
	btSetTaskScheduler(0);
	return run;
}
}  // namespace

// The motion states' calls: btDefaultMotionStates may be told on the threads, every other motion state
// (a user's, or a subclass with its own setWorldTransform) is told on the calling thread in body order,
// and a motion state two bodies share ends with the later body's pose, as in the serial loop. Checked
// against no scheduler with the pool at 1, 2 and 3 threads, the sequential scheduler, and schedulers that
// cut the loops unevenly or run their chunks last first (which would tell the shared motion state body
// 250's pose first and body 20's last, were the shared state told on the threads).
TEST(PerBodyStagesThreads, MotionStatesAreToldAsWithoutASchedulerAndUsersOnTheCallingThread)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	caliber_test::UnevenSplitScheduler uneven;
	caliber_test::LastFirstScheduler lastFirst;
	for (bool multithreaded : {false, true})
	{
		const MotionStateRun reference = runMotionStates(0, 0, multithreaded);
		ASSERT_GT(reference.log.size(), 40u * 50u) << "the logging motion states must be told every step";
		EXPECT_EQ(reference.foreignCalls, 0);
		// Within a step the log goes up in body order: count the steps (each starts below the last entry).
		int steps = 1;
		for (size_t i = 1; i < reference.log.size(); ++i) steps += reference.log[i] <= reference.log[i - 1];
		EXPECT_EQ(steps, 40);
		for (int variant = 0; variant < 6; ++variant)
		{
			btITaskScheduler* scheduler = variant < 3 ? pool.get()
			                                          : (variant == 3 ? btGetSequentialTaskScheduler()
			                                                          : (variant == 4 ? static_cast<btITaskScheduler*>(&uneven)
			                                                                          : &lastFirst));
			if (!scheduler) continue;
			const MotionStateRun run = runMotionStates(scheduler, variant < 3 ? variant + 1 : 0, multithreaded);
			EXPECT_EQ(run.foreignCalls, 0) << "variant " << variant;
			EXPECT_TRUE(run.log == reference.log) << "variant " << variant << ", Mt world " << multithreaded;
			EXPECT_EQ(std::memcmp(run.sharedPose, reference.sharedPose, sizeof(run.sharedPose)), 0)
			    << "variant " << variant << ", Mt world " << multithreaded;
			ASSERT_EQ(run.bodies.size(), reference.bodies.size());
			for (size_t i = 0; i < run.bodies.size(); ++i)
				EXPECT_TRUE(run.bodies[i] == reference.bodies[i])
				    << "body " << i << ", variant " << variant << ", Mt world " << multithreaded;
		}
	}
}

// applyGravity and clearForces on the threads: every awake body gets exactly its gravity force, a sleeping
// one none, and clearForces leaves every body without force, whatever the scheduler.
TEST(PerBodyStagesThreads, GravityAndClearedForcesAreTheSameAtAnyThreadCount)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	caliber_test::LastFirstScheduler lastFirst;
	for (int variant = 0; variant < 4; ++variant)
	{
		btITaskScheduler* scheduler = variant == 0 ? 0 : (variant == 1 ? &lastFirst : pool.get());
		if (variant >= 2 && !pool) continue;
		btSetTaskScheduler(scheduler);
		if (variant >= 2) pool->setNumThreads(variant);
		{
			TestWorld w;
			btCollisionShape* box = w.shape<btBoxShape>(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
			for (int i = 0; i < 300; ++i)
			{
				btRigidBody* body = w.addBody(box, btScalar(1 + i % 4), btVector3(btScalar(i) * 2, 10, 0));
				if (i % 5 == 0) body->setActivationState(ISLAND_SLEEPING);
			}
			w.world()->setGravity(btVector3(btScalar(0.5), btScalar(-9.75), btScalar(0.25)));
			w.world()->applyGravity();
			for (int i = 0; i < 300; ++i)
			{
				const btRigidBody* body = w.bodies()[i];
				// Mass (1 to 4) times the world's gravity: exact in binary, as is adding it to no force.
				const btScalar mass = btScalar(1 + i % 4);
				const btVector3 expected = i % 5 == 0 ? btVector3(0, 0, 0)
				                                      : btVector3(btScalar(0.5) * mass, btScalar(-9.75) * mass,
				                                                  btScalar(0.25) * mass);
				EXPECT_TRUE(body->getTotalForce() == expected) << "body " << i << ", variant " << variant;
			}
			w.world()->clearForces();
			for (int i = 0; i < 300; ++i)
				EXPECT_TRUE(w.bodies()[i]->getTotalForce() == btVector3(0, 0, 0)) << "body " << i << ", variant " << variant;
		}
		btSetTaskScheduler(0);
	}
}

namespace
{
// A kinematic body's motion state that moves it along x by a fixed distance each step.
class SlidingMotionState : public btMotionState
{
public:
	explicit SlidingMotionState(const btTransform& pose) : m_pose(pose) {}
	void getWorldTransform(btTransform& pose) const override { pose = m_pose; }
	void setWorldTransform(const btTransform&) override {}
	void slide(btScalar dx) { m_pose.getOrigin().setX(m_pose.getOrigin().x() + dx); }

private:
	btTransform m_pose;
};
}  // namespace

// saveKinematicState looks for awake kinematic bodies on the threads when the world has at least 512
// objects, and saves them (reading their motion states, user code) on the calling thread: a kinematic
// paddle among 600 boxes gets the velocity of its move and pushes the same boxes, with the same bits,
// with no scheduler, the pool at 1, 2 and 3 threads and a last-first user scheduler.
TEST(PerBodyStagesThreads, KinematicBodiesAreSavedTheSameAmongManyObjectsAtAnyThreadCount)
{
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	caliber_test::LastFirstScheduler lastFirst;
	std::vector<std::vector<BodyRecord>> runs;
	const btScalar h = btScalar(1. / 60.);
	const btScalar dx = btScalar(0.05);  // 3 m/s
	for (int variant = 0; variant < 5; ++variant)
	{
		if (variant >= 1 && variant <= 3 && !pool) continue;
		btITaskScheduler* scheduler = variant == 0 ? 0 : (variant == 4 ? static_cast<btITaskScheduler*>(&lastFirst) : pool.get());
		btSetTaskScheduler(scheduler);
		if (variant >= 1 && variant <= 3) pool->setNumThreads(variant);
		{
			TestWorld w;
			w.addGround();
			btCollisionShape* box = w.shape<btBoxShape>(btVector3(btScalar(0.4), btScalar(0.4), btScalar(0.4)));
			for (int i = 0; i < 600; ++i)
				w.addBody(box, 1, btVector3(btScalar(i % 30) - 15, btScalar(0.4), btScalar(i / 30) * 2 - 20));
			const btTransform start(btQuaternion::getIdentity(), btVector3(-17, btScalar(0.5), 0));
			SlidingMotionState paddleState(start);
			btRigidBody* paddle = w.addBody(w.shape<btBoxShape>(btVector3(btScalar(0.5), btScalar(0.5), btScalar(3))), 0,
			                                start, false);
			paddle->setCollisionFlags(paddle->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
			paddle->setActivationState(DISABLE_DEACTIVATION);
			paddle->setMotionState(&paddleState);
			for (int step = 0; step < 60; ++step)
			{
				paddleState.slide(dx);
				w.run(1, h);
			}
			// The velocity saveKinematicState derived from the last move, dx per step along x: the difference
			// of two float positions near 15 m (a few 1e-6 m off) over 1/60 s, so within 1e-3 m/s. The
			// position: 60 float additions of dx, each off by at most half an ulp near 17 m (1e-6 m).
			EXPECT_NEAR(paddle->getLinearVelocity().x(), dx / h, btScalar(1e-3)) << "variant " << variant;
			EXPECT_NEAR(paddle->getWorldTransform().getOrigin().x(), btScalar(-17) + 60 * dx, btScalar(1e-3));
			// It pushed the first boxes in its path (centres at x = -15, z = -2, 0, 2; w.bodies()[0] is the
			// ground) ahead of its front face, now at x = -13.5.
			for (int i : {270, 300, 330})
				EXPECT_GT(w.bodies()[size_t(1 + i)]->getWorldTransform().getOrigin().x(), btScalar(-13.5)) << "box " << i;
			runs.push_back(record(w));
			paddle->setMotionState(0);
		}
		btSetTaskScheduler(0);
	}
	ASSERT_GT(runs.size(), 1u);
	for (size_t r = 1; r < runs.size(); ++r)
	{
		ASSERT_EQ(runs[r].size(), runs[0].size());
		for (size_t i = 0; i < runs[0].size(); ++i) EXPECT_TRUE(runs[r][i] == runs[0][i]) << "body " << i << ", run " << r;
	}
}
