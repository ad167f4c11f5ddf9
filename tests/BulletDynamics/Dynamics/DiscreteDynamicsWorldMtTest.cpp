// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet 2.89's multithreaded world, set up as Bullet's multithreaded examples do, and the plain world
// with a scheduler set: both must give the single-threaded world's state bits at 1, 2, 3, 4 and 8
// threads, with every scheduler of the build, also when the scheduler changes between steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <thread>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btBatchedConstraints.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "BulletDynamics/Dynamics/btSimulationIslandManagerMt.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btWarningHook.h"
#include "btBulletDynamicsCommon.h"
#include "../ConstraintSolver/MtSolverTestUtil.h"

namespace
{
// Saves btSequentialImpulseConstraintSolverMt's static knobs (shared by every test in the process) and
// puts them back at the end of the scope, also when an ASSERT leaves early.
class ScopedMtSolverKnobs
{
public:
	ScopedMtSolverKnobs() = default;
	~ScopedMtSolverKnobs()
	{
		btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = m_threshold;
		btSequentialImpulseConstraintSolverMt::s_minBatchSize = m_minBatch;
		btSequentialImpulseConstraintSolverMt::s_maxBatchSize = m_maxBatch;
		btSequentialImpulseConstraintSolverMt::s_allowNestedParallelForLoops = m_nested;
		btSequentialImpulseConstraintSolverMt::s_contactBatchingMethod = m_contactMethod;
		btSequentialImpulseConstraintSolverMt::s_jointBatchingMethod = m_jointMethod;
	}
	ScopedMtSolverKnobs(const ScopedMtSolverKnobs&) = delete;
	ScopedMtSolverKnobs& operator=(const ScopedMtSolverKnobs&) = delete;

private:
	int m_threshold = btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching;
	int m_minBatch = btSequentialImpulseConstraintSolverMt::s_minBatchSize;
	int m_maxBatch = btSequentialImpulseConstraintSolverMt::s_maxBatchSize;
	bool m_nested = btSequentialImpulseConstraintSolverMt::s_allowNestedParallelForLoops;
	btBatchedConstraints::BatchingMethod m_contactMethod = btSequentialImpulseConstraintSolverMt::s_contactBatchingMethod;
	btBatchedConstraints::BatchingMethod m_jointMethod = btSequentialImpulseConstraintSolverMt::s_jointBatchingMethod;
};

enum class WorldSetup
{
	Plain,  // btDiscreteDynamicsWorld with btCollisionDispatcher and btSequentialImpulseConstraintSolver
	Mt      // the Mt classes, as Bullet 2.89's multithreaded examples make them
};

// A pile of boxes and spheres on the ground, a few chains of hinged boxes, and some free-flying bodies
// (enough bodies that the per-body stages are cut into several tasks).
class Scene
{
public:
	explicit Scene(WorldSetup setup)
	{
		if (setup == WorldSetup::Mt)
		{
			btDefaultCollisionConstructionInfo info;
			info.m_defaultMaxPersistentManifoldPoolSize = 8000;
			info.m_defaultMaxCollisionAlgorithmPoolSize = 8000;
			m_config.reset(new btDefaultCollisionConfiguration(info));
			m_dispatcher.reset(new btCollisionDispatcherMt(m_config.get(), 40));
			m_broadphase.reset(new btDbvtBroadphase());
			m_pool.reset(new btConstraintSolverPoolMt(BT_MAX_THREAD_COUNT));
			m_solver.reset(new btSequentialImpulseConstraintSolverMt());
			m_world.reset(new btDiscreteDynamicsWorldMt(m_dispatcher.get(), m_broadphase.get(), m_pool.get(),
			                                            m_solver.get(), m_config.get()));
		}
		else
		{
			m_config.reset(new btDefaultCollisionConfiguration());
			m_dispatcher.reset(new btCollisionDispatcher(m_config.get()));
			m_broadphase.reset(new btDbvtBroadphase());
			m_solver.reset(new btSequentialImpulseConstraintSolver());
			m_world.reset(
			    new btDiscreteDynamicsWorld(m_dispatcher.get(), m_broadphase.get(), m_solver.get(), m_config.get()));
		}
		m_world->setGravity(btVector3(0, -10, 0));
		m_world->getSolverInfo().m_numIterations = 10;

		m_shapes.emplace_back(new btBoxShape(btVector3(50, 1, 50)));
		addBody(0, btVector3(0, -1, 0), m_shapes.back().get());
		m_shapes.emplace_back(new btBoxShape(btVector3(0.5f, 0.5f, 0.5f)));
		btCollisionShape* box = m_shapes.back().get();
		m_shapes.emplace_back(new btSphereShape(0.4f));
		btCollisionShape* sphere = m_shapes.back().get();
		for (int layer = 0; layer < 5; ++layer)
			for (int x = 0; x < 8; ++x)
				for (int z = 0; z < 8; ++z)
					addBody(1, btVector3(x * 1.1f - 4 + 0.05f * layer, 0.5f + layer * 1.05f, z * 1.1f - 4),
					        (x + z + layer) % 3 ? box : sphere);
		for (int chain = 0; chain < 4; ++chain)
		{
			btRigidBody* previous = addBody(0, btVector3(-20.0f + chain * 3, 12, 10), box);
			for (int link = 1; link < 6; ++link)
			{
				btRigidBody* next = addBody(1, btVector3(-20.0f + chain * 3 + link * 1.2f, 12, 10), box);
				m_joints.emplace_back(new btHingeConstraint(*previous, *next, btVector3(0.6f, 0, 0),
				                                            btVector3(-0.6f, 0, 0), btVector3(0, 0, 1),
				                                            btVector3(0, 0, 1)));
				m_world->addConstraint(m_joints.back().get(), true);
				previous = next;
			}
		}
		// A small triangle mesh with boxes, capsules and compounds dropped on it: mesh and compound pairs
		// make and drop manifolds of their child pairs while the narrowphase runs.
		m_meshVertices.clear();
		m_meshIndices.clear();
		for (int z = 0; z <= 6; ++z)
			for (int x = 0; x <= 6; ++x)
			{
				m_meshVertices.push_back(btScalar(x * 2 - 6));
				m_meshVertices.push_back(btScalar(0.3f * ((x * 7 + z * 3) % 4)));
				m_meshVertices.push_back(btScalar(z * 2 - 6));
			}
		for (int z = 0; z < 6; ++z)
			for (int x = 0; x < 6; ++x)
			{
				const int v = z * 7 + x;
				const int quad[6] = {v, v + 7, v + 1, v + 1, v + 7, v + 8};
				m_meshIndices.insert(m_meshIndices.end(), quad, quad + 6);
			}
		m_meshArray.reset(new btTriangleIndexVertexArray(int(m_meshIndices.size() / 3), &m_meshIndices[0],
		                                                 3 * sizeof(int), int(m_meshVertices.size() / 3),
		                                                 &m_meshVertices[0], 3 * sizeof(btScalar)));
		m_shapes.emplace_back(new btBvhTriangleMeshShape(m_meshArray.get(), true));
		addBody(0, btVector3(0, 0, 30), m_shapes.back().get());
		m_shapes.emplace_back(new btCapsuleShape(0.3f, 0.8f));
		btCollisionShape* capsule = m_shapes.back().get();
		btCompoundShape* compound = new btCompoundShape();
		m_shapes.emplace_back(compound);
		compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(-0.6f, 0, 0)), box);
		compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(0.6f, 0, 0)), sphere);
		for (int i = 0; i < 30; ++i)
		{
			btCollisionShape* shape = i % 3 == 0 ? compound : (i % 3 == 1 ? capsule : box);
			btRigidBody* body = addBody(1, btVector3(-4.5f + (i % 6) * 1.8f, 2 + (i / 6) * 1.5f, 30 - 4 + (i % 4) * 2.0f), shape);
			body->setAngularVelocity(btVector3(0.3f * (i % 5), 0.2f, -0.1f * (i % 3)));
		}
		for (int i = 0; i < 40; ++i)
		{
			btRigidBody* body = addBody(1, btVector3(20 + (i % 5) * 2.0f, 3 + i * 0.5f, -20 + (i / 5) * 2.0f), sphere);
			body->setLinearVelocity(btVector3(btScalar(i % 7) - 3, 0, btScalar(i % 3) - 1));
			body->setAngularVelocity(btVector3(0.1f * i, 1, -0.05f * i));
		}
	}

	~Scene()
	{
		for (auto& joint : m_joints) m_world->removeConstraint(joint.get());
		for (auto& body : m_bodies) m_world->removeRigidBody(body.get());
	}

	btDiscreteDynamicsWorld& world() { return *m_world; }

	void step(int steps)
	{
		for (int i = 0; i < steps; ++i) m_world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	}

	// FNV-1a over the bits of every body's transform and velocities and of its motion state's pose, and of
	// every manifold in the dispatcher's order: its two bodies (by index in the world) and its points.
	std::uint64_t hash() const
	{
		std::uint64_t h = 1469598103934665603ull;
		auto mix = [&h](const void* data, size_t size) {
			const unsigned char* bytes = static_cast<const unsigned char*>(data);
			for (size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
		};
		for (const auto& body : m_bodies)
		{
			const btTransform& t = body->getWorldTransform();
			for (int r = 0; r < 3; ++r) mix(&t.getBasis()[r][0], 3 * sizeof(btScalar));
			mix(&t.getOrigin()[0], 3 * sizeof(btScalar));
			mix(&body->getLinearVelocity()[0], 3 * sizeof(btScalar));
			mix(&body->getAngularVelocity()[0], 3 * sizeof(btScalar));
			btTransform shown;  // what the motion state was told
			body->getMotionState()->getWorldTransform(shown);
			for (int r = 0; r < 3; ++r) mix(&shown.getBasis()[r][0], 3 * sizeof(btScalar));
			mix(&shown.getOrigin()[0], 3 * sizeof(btScalar));
		}
		btDispatcher* dispatcher = m_world->getDispatcher();
		for (int i = 0; i < dispatcher->getNumManifolds(); ++i)
		{
			const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(i);
			const int ids[2] = {manifold->getBody0()->getWorldArrayIndex(), manifold->getBody1()->getWorldArrayIndex()};
			mix(ids, sizeof(ids));
			for (int p = 0; p < manifold->getNumContacts(); ++p)
			{
				const btManifoldPoint& point = manifold->getContactPoint(p);
				mix(&point.m_positionWorldOnB[0], 3 * sizeof(btScalar));
				mix(&point.m_normalWorldOnB[0], 3 * sizeof(btScalar));
				mix(&point.m_distance1, sizeof(btScalar));
				mix(&point.m_appliedImpulse, sizeof(btScalar));
				mix(&point.m_lifeTime, sizeof(int));
			}
		}
		return h;
	}

private:
	btRigidBody* addBody(btScalar mass, const btVector3& position, btCollisionShape* shape)
	{
		btVector3 inertia(0, 0, 0);
		if (mass != 0) shape->calculateLocalInertia(mass, inertia);
		m_motionStates.emplace_back(new btDefaultMotionState(btTransform(btQuaternion::getIdentity(), position)));
		btRigidBody::btRigidBodyConstructionInfo info(mass, m_motionStates.back().get(), shape, inertia);
		m_bodies.emplace_back(new btRigidBody(info));
		m_world->addRigidBody(m_bodies.back().get());
		return m_bodies.back().get();
	}

	std::unique_ptr<btDefaultCollisionConfiguration> m_config;
	std::unique_ptr<btCollisionDispatcher> m_dispatcher;
	std::unique_ptr<btBroadphaseInterface> m_broadphase;
	std::unique_ptr<btConstraintSolverPoolMt> m_pool;
	std::unique_ptr<btSequentialImpulseConstraintSolver> m_solver;
	std::unique_ptr<btDiscreteDynamicsWorld> m_world;
	std::vector<btScalar> m_meshVertices;
	std::vector<int> m_meshIndices;
	std::unique_ptr<btTriangleIndexVertexArray> m_meshArray;  // outlives the mesh shape
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btDefaultMotionState>> m_motionStates;
	std::vector<std::unique_ptr<btRigidBody>> m_bodies;
	std::vector<std::unique_ptr<btTypedConstraint>> m_joints;
};

const int kSteps = 60;
const int kThreadCounts[] = {1, 2, 3, 4, 8};

std::uint64_t singleThreadedHash(WorldSetup setup = WorldSetup::Plain)
{
	btSetTaskScheduler(0);
	Scene scene(setup);
	scene.step(kSteps);
	return scene.hash();
}

std::vector<btITaskScheduler*> schedulersOfThisBuild(btITaskScheduler* pool)
{
	std::vector<btITaskScheduler*> all;
	if (pool) all.push_back(pool);
	if (btGetOpenMPTaskScheduler()) all.push_back(btGetOpenMPTaskScheduler());
	if (btGetTBBTaskScheduler()) all.push_back(btGetTBBTaskScheduler());
	return all;
}
}  // namespace

TEST(DiscreteDynamicsWorldMt, SameStateBitsAsWithoutASchedulerAtAnyThreadCount)
{
	const std::uint64_t reference = singleThreadedHash();
	const std::uint64_t referenceMt = singleThreadedHash(WorldSetup::Mt);
	{
		// The same world stepped twice gives the same bits (the test could not tell otherwise).
		Scene again(WorldSetup::Plain);
		const std::uint64_t before = again.hash();
		again.step(kSteps);
		ASSERT_NE(again.hash(), before);  // the scene moves
		ASSERT_EQ(again.hash(), reference);
	}
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	for (btITaskScheduler* scheduler : schedulersOfThisBuild(pool.get()))
	{
		btSetTaskScheduler(scheduler);
		for (int threads : kThreadCounts)
		{
			scheduler->setNumThreads(threads);
			for (WorldSetup setup : {WorldSetup::Plain, WorldSetup::Mt})
			{
				Scene scene(setup);
				scene.step(kSteps);
				EXPECT_EQ(scene.hash(), setup == WorldSetup::Mt ? referenceMt : reference)
				    << scheduler->getName() << " threads " << threads
				    << (setup == WorldSetup::Mt ? " Mt world" : " plain world");
			}
		}
	}
	btSetTaskScheduler(0);
}

TEST(DiscreteDynamicsWorldMt, TheMtSolverColoursOnlyLargeSolvesAndIsThePlainSolverBelow)
{
	// The scene's pile is one island of more than 250 manifolds: the Mt world's solver colours it (another
	// Gauss-Seidel order, so other bits than the plain world's), and below the threshold the Mt world is
	// the plain world, bit for bit.
	EXPECT_NE(singleThreadedHash(WorldSetup::Mt), singleThreadedHash());
	caliber_test::ScopedManifoldBatchingThreshold neverColour(1 << 30);
	EXPECT_EQ(singleThreadedHash(WorldSetup::Mt), singleThreadedHash());
}

TEST(DiscreteDynamicsWorldMt, TwoWorldsSteppedAtOnceFromTwoThreadsKeepTheirBits)
{
	// Two programs' worlds (or two worlds of one program) may be stepped at the same time on different
	// threads, sharing the one scheduler: one of them gets the scheduler's threads for each loop, the
	// other runs that loop on its own thread. Neither may see the other's chunk logs, batches or scratch.
	const std::uint64_t referenceMt = singleThreadedHash(WorldSetup::Mt);
	const std::uint64_t reference = singleThreadedHash();
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	btITaskScheduler* scheduler = pool ? pool.get() : btGetSequentialTaskScheduler();
	btSetTaskScheduler(scheduler);
	scheduler->setNumThreads(2);
	std::uint64_t hashes[2] = {0, 0};
	{
		Scene mt(WorldSetup::Mt), plain(WorldSetup::Plain);
		std::thread other([&] {
			plain.step(kSteps);
			hashes[1] = plain.hash();
		});
		mt.step(kSteps);
		hashes[0] = mt.hash();
		other.join();
	}
	btSetTaskScheduler(0);
	EXPECT_EQ(hashes[0], referenceMt);
	EXPECT_EQ(hashes[1], reference);
}

TEST(DiscreteDynamicsWorldMt, SwitchingSchedulersBetweenStepsKeepsTheBits)
{
	const std::uint64_t reference = singleThreadedHash(WorldSetup::Mt);
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	std::vector<btITaskScheduler*> schedulers = schedulersOfThisBuild(pool.get());
	schedulers.push_back(btGetSequentialTaskScheduler());
	Scene scene(WorldSetup::Mt);
	for (int step = 0; step < kSteps; ++step)
	{
		btITaskScheduler* scheduler = schedulers[step % schedulers.size()];
		btSetTaskScheduler(scheduler);
		scheduler->setNumThreads(1 + step % 4);
		scene.step(1);
	}
	btSetTaskScheduler(0);
	EXPECT_EQ(scene.hash(), reference);
}

TEST(DiscreteDynamicsWorldMt, TheMtWorldHasBulletsMtIslandManagerAndSolverPool)
{
	Scene scene(WorldSetup::Mt);
	btSimulationIslandManagerMt* islands =
	    dynamic_cast<btSimulationIslandManagerMt*>(scene.world().getSimulationIslandManager());
	ASSERT_NE(islands, nullptr);
	EXPECT_NE(dynamic_cast<btConstraintSolverPoolMt*>(scene.world().getConstraintSolver()), nullptr);
	EXPECT_EQ(islands->getIslandDispatchFunction(), &btSimulationIslandManagerMt::serialIslandDispatch);
	islands->setIslandDispatchFunction(btSimulationIslandManagerMt::parallelIslandDispatch);
	EXPECT_EQ(islands->getIslandDispatchFunction(), &btSimulationIslandManagerMt::parallelIslandDispatch);
	islands->setIslandDispatchFunction(0);
	EXPECT_EQ(islands->getIslandDispatchFunction(), &btSimulationIslandManagerMt::serialIslandDispatch);
	islands->setMinimumSolverBatchSize(-4);
	EXPECT_EQ(islands->getMinimumSolverBatchSize(), 1);
	// The solver's knobs are accepted (they change how a large island is cut into batches, so the state
	// may differ from the default knobs' but stays finite); they are put back for the other tests.
	ScopedMtSolverKnobs knobs;
	btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = 100;
	btSequentialImpulseConstraintSolverMt::s_minBatchSize = 30;
	btSequentialImpulseConstraintSolverMt::s_maxBatchSize = 60;
	btSequentialImpulseConstraintSolverMt::s_allowNestedParallelForLoops = true;
	btSequentialImpulseConstraintSolverMt::s_contactBatchingMethod = btBatchedConstraints::BATCHING_METHOD_SPATIAL_GRID_3D;
	scene.step(5);
	const btCollisionObjectArray& objects = scene.world().getCollisionObjectArray();
	for (int i = 0; i < objects.size(); ++i)
	{
		const btVector3& origin = objects[i]->getWorldTransform().getOrigin();
		EXPECT_TRUE(std::isfinite(origin.x()) && std::isfinite(origin.y()) && std::isfinite(origin.z())) << i;
	}
}

namespace
{
// Counts what the island dispatch hands the solver pool.
int gIslandsDispatched = 0;
void countingDispatch(btAlignedObjectArray<btSimulationIslandManagerMt::Island*>* islands,
                      const btSimulationIslandManagerMt::SolverParams& params)
{
	gIslandsDispatched += islands->size();
	btSimulationIslandManagerMt::serialIslandDispatch(islands, params);
}
}  // namespace

TEST(DiscreteDynamicsWorldMt, IslandManagerMtGathersAwakeIslandsForItsDispatchFunction)
{
	// Two boxes resting apart on static ground are two islands; a hinge pair a third.
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	Scene scene(WorldSetup::Mt);
	scene.step(2);
	btSimulationIslandManagerMt* islands =
	    static_cast<btSimulationIslandManagerMt*>(scene.world().getSimulationIslandManager());
	islands->setIslandDispatchFunction(countingDispatch);
	btAlignedObjectArray<btTypedConstraint*> constraints;
	for (int i = 0; i < scene.world().getNumConstraints(); ++i) constraints.push_back(scene.world().getConstraint(i));
	btSimulationIslandManagerMt::SolverParams params;
	params.m_solverPool = scene.world().getConstraintSolver();
	params.m_solverMt = 0;
	params.m_solverInfo = &scene.world().getSolverInfo();
	params.m_debugDrawer = 0;
	params.m_dispatcher = scene.world().getDispatcher();
	gIslandsDispatched = 0;
	islands->buildAndProcessIslands(scene.world().getDispatcher(), &scene.world(), constraints, params);
	// The pile touches itself (one island), each chain is one island, each flying sphere its own: at
	// least the 4 chains and the pile.
	EXPECT_GE(gIslandsDispatched, 5);
	// The parallel dispatch solves the same islands with the pool's solvers on the scheduler's threads.
	if (pool)
	{
		btSetTaskScheduler(pool.get());
		pool->setNumThreads(3);
		islands->setIslandDispatchFunction(btSimulationIslandManagerMt::parallelIslandDispatch);
		islands->buildAndProcessIslands(scene.world().getDispatcher(), &scene.world(), constraints, params);
		btSetTaskScheduler(0);
	}
	// And bad arguments are refused with a warning.
	int warnings = 0;
	btSetWarningHook([](const char*, void* count) { ++*static_cast<int*>(count); }, &warnings);
	islands->buildAndProcessIslands(0, &scene.world(), constraints, params);
	btSetWarningHook(0, 0);
	EXPECT_EQ(warnings, 1);
}

namespace
{
// Boxes resting apart on one kinematic platform: one island each, all sharing the platform (enough of
// them that a parallel dispatch spreads them over the threads).
const int kPlatformBoxes = 32;
struct KinematicPlatformScene
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcherMt dispatcher{&config, 40};
	btDbvtBroadphase broadphase;
	btConstraintSolverPoolMt pool{4};
	btDiscreteDynamicsWorldMt world{&dispatcher, &broadphase, &pool, 0, &config};
	btBoxShape platformShape{btVector3(21, 0.5f, 2)};
	btBoxShape boxShape{btVector3(0.5f, 0.5f, 0.5f)};
	std::vector<std::unique_ptr<btRigidBody>> bodies;

	KinematicPlatformScene()
	{
		world.setGravity(btVector3(0, -10, 0));
		bodies.emplace_back(new btRigidBody(0, 0, &platformShape));
		btRigidBody* platform = bodies.back().get();
		platform->setCollisionFlags(platform->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
		platform->setActivationState(DISABLE_DEACTIVATION);
		world.addRigidBody(platform);
		for (int i = 0; i < kPlatformBoxes; ++i)
		{
			btVector3 inertia;
			boxShape.calculateLocalInertia(1, inertia);
			bodies.emplace_back(new btRigidBody(1, 0, &boxShape, inertia));
			bodies.back()->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(-19.f + 1.2f * i, 1, 0)));
			world.addRigidBody(bodies.back().get());
		}
		world.stepSimulation(btScalar(1. / 60.), 0);  // contacts exist from here on
	}
	~KinematicPlatformScene()
	{
		for (auto& body : bodies) world.removeRigidBody(body.get());
	}

	// One island solve of the world's current contacts by the given dispatch; the boxes' velocities after it.
	std::vector<btVector3> solveWith(btSimulationIslandManagerMt::IslandDispatchFunc dispatch)
	{
		btSimulationIslandManagerMt* islands = static_cast<btSimulationIslandManagerMt*>(world.getSimulationIslandManager());
		islands->setIslandDispatchFunction(dispatch);
		btAlignedObjectArray<btTypedConstraint*> constraints;
		btSimulationIslandManagerMt::SolverParams params;
		params.m_solverPool = world.getConstraintSolver();
		params.m_solverMt = 0;
		params.m_solverInfo = &world.getSolverInfo();
		params.m_debugDrawer = 0;
		params.m_dispatcher = world.getDispatcher();
		for (int i = 1; i <= kPlatformBoxes; ++i) bodies[size_t(i)]->setLinearVelocity(btVector3(0, -1, 0));
		islands->buildAndProcessIslands(world.getDispatcher(), &world, constraints, params);
		islands->setIslandDispatchFunction(0);
		std::vector<btVector3> velocities;
		for (int i = 1; i <= kPlatformBoxes; ++i) velocities.push_back(bodies[size_t(i)]->getLinearVelocity());
		return velocities;
	}
};
}  // namespace

TEST(DiscreteDynamicsWorldMt, ParallelIslandDispatchSolvesIslandsSharingAKinematicBodySafely)
{
	// Every island's solver gives the shared platform a solver entry (and writes its companion id), so
	// those islands must not run at once; ThreadSanitizer (the tsan stage) checks that they do not.
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	KinematicPlatformScene serial, parallel;
	const std::vector<btVector3> expected = serial.solveWith(btSimulationIslandManagerMt::serialIslandDispatch);
	if (pool)
	{
		btSetTaskScheduler(pool.get());
		pool->setNumThreads(2);
	}
	const std::vector<btVector3> got = parallel.solveWith(btSimulationIslandManagerMt::parallelIslandDispatch);
	btSetTaskScheduler(0);
	for (int i = 0; i < kPlatformBoxes; ++i)
	{
		// The platform stops each box's 1 m/s fall into it: the solve is real, and the same either way.
		EXPECT_GT(expected[size_t(i)].y(), btScalar(-0.5)) << "box " << i;
		EXPECT_EQ(got[size_t(i)], expected[size_t(i)]) << "box " << i;
	}
}

TEST(DiscreteDynamicsWorldMt, SolverPoolRefusesBadSizesWithAWarning)
{
	int warnings = 0;
	btSetWarningHook([](const char*, void* count) { ++*static_cast<int*>(count); }, &warnings);
	{
		btConstraintSolverPoolMt empty(0);
		EXPECT_EQ(empty.getSolverType(), BT_SEQUENTIAL_IMPULSE_SOLVER);
		btConstraintSolver* solvers[2] = {new btSequentialImpulseConstraintSolver(), 0};
		btConstraintSolverPoolMt withNull(solvers, 2);  // takes the valid solver over and deletes it
		btConstraintSolverPoolMt none(0, 3);
		EXPECT_EQ(none.getSolverType(), BT_SEQUENTIAL_IMPULSE_SOLVER);
	}
	btSetWarningHook(0, 0);
	EXPECT_EQ(warnings, 3);
}

TEST(BatchedConstraints, OneBatchCoversEveryRowAndValidates)
{
	btConstraintArray rows;
	rows.resize(5);
	btAlignedObjectArray<btSolverBody> bodies;
	bodies.resize(3);
	for (int i = 0; i < 3; ++i) bodies[i].m_invMass = btVector3(1, 1, 1);
	bodies[2].m_invMass = btVector3(0, 0, 0);  // static
	for (int i = 0; i < 5; ++i)
	{
		rows[i].m_solverBodyIdA = i % 2;
		rows[i].m_solverBodyIdB = 2;
	}
	btBatchedConstraints batches;
	batches.setup(&rows, bodies, btBatchedConstraints::BATCHING_METHOD_SPATIAL_GRID_2D, 1, 10, 0);
	EXPECT_EQ(batches.m_constraintIndices.size(), 5);
	EXPECT_EQ(batches.m_phases.size(), 1);
	EXPECT_TRUE(batches.validate(&rows, bodies));
	// Two batches in one phase sharing dynamic body 0 are invalid; sharing only the static body is fine.
	batches.m_batches.resize(0);
	batches.m_batches.push_back(btBatchedConstraints::Range(0, 2));
	batches.m_batches.push_back(btBatchedConstraints::Range(2, 5));
	batches.m_phases[0] = btBatchedConstraints::Range(0, 2);
	EXPECT_FALSE(batches.validate(&rows, bodies));
	for (int i = 0; i < 5; ++i) rows[i].m_solverBodyIdA = i < 2 ? 0 : 1;
	EXPECT_TRUE(batches.validate(&rows, bodies));
	rows[4].m_solverBodyIdB = 7;  // no such body
	EXPECT_FALSE(batches.validate(&rows, bodies));
}
