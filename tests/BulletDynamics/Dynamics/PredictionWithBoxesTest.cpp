// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// With threads, btDiscreteDynamicsWorld and btDiscreteDynamicsWorldMt predict their bodies chunk by chunk
// inside the box loop (caliber::PredictionPrologue, handed to updateAabbs) instead of in a loop of their
// own before it. Bodies falling onto a triangle mesh, with the mesh after, before and between the bodies in
// the object array, end with the bits, the manifolds and the contact points of the world without a
// scheduler, at 1, 2 and 3 threads and with users' schedulers that split or order loops their own way.

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletDynamics/Dynamics/btPredictionPrologue.h"
#include "DynamicsWorldTestUtil.h"
#include "TestThreadsUtil.h"

using caliber_test::TestWorld;

namespace
{
enum class TerrainAt
{
	Last,    // bodies at objects 0..n-1: the prediction goes with the boxes
	First,   // bodies at objects 1..n: still one run
	Between  // half the bodies, the terrain, the other half: not one run, the world predicts first
};

const int kBodies = 300;

struct Result
{
	std::vector<btScalar> bodyBits;
	std::vector<btScalar> manifoldBits;  // per manifold: its two bodies' indices, then each point's numbers
	int manifolds = 0;
	int terrainPoints = 0;
};

void addTerrain(TestWorld& w)
{
	// A 16 x 16 grid of quads over 48 m x 48 m, gently wavy, as two triangles each.
	btTriangleMesh* mesh = w.keep(new btTriangleMesh);
	const int n = 16;
	const btScalar pitch = 3;
	auto height = [](int i, int j) { return btScalar(0.4) * btScalar((i * 7 + j * 3) % 5) - btScalar(0.8); };
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
		{
			const btVector3 a((i - n / 2) * pitch, height(i, j), (j - n / 2) * pitch);
			const btVector3 b((i + 1 - n / 2) * pitch, height(i + 1, j), (j - n / 2) * pitch);
			const btVector3 c((i + 1 - n / 2) * pitch, height(i + 1, j + 1), (j + 1 - n / 2) * pitch);
			const btVector3 d((i - n / 2) * pitch, height(i, j + 1), (j + 1 - n / 2) * pitch);
			mesh->addTriangle(a, b, c);
			mesh->addTriangle(a, c, d);
		}
	btBvhTriangleMeshShape* shape = w.shape<btBvhTriangleMeshShape>(mesh, true);
	w.addBody(shape, 0, btVector3(0, 0, 0));
}

void addBodies(TestWorld& w, int begin, int end)
{
	btCollisionShape* shapes[4] = {w.shape<btBoxShape>(btVector3(btScalar(0.5), btScalar(0.4), btScalar(0.6))),
	                               w.shape<btSphereShape>(btScalar(0.5)),
	                               w.shape<btCapsuleShape>(btScalar(0.3), btScalar(0.8)), 0};
	btConvexHullShape* hull = w.shape<btConvexHullShape>();
	for (int k = 0; k < 12; ++k)
	{
		const btScalar angle = btScalar(k) * SIMD_2_PI / 12;
		hull->addPoint(btVector3(btCos(angle) * btScalar(0.5), k % 2 ? btScalar(0.4) : btScalar(-0.4),
		                         btSin(angle) * btScalar(0.5)));
	}
	shapes[3] = hull;
	for (int i = begin; i < end; ++i)
	{
		// 15 x 20 columns 2.5 m apart, the lowest 1 m above the terrain, so that most land within the run.
		const btVector3 origin(btScalar(i % 15) * btScalar(2.5) - 18, btScalar(1.5) + btScalar(i % 7) * btScalar(0.7),
		                       btScalar(i / 15) * btScalar(2.2) - 21);
		btRigidBody* body = w.addBody(
		    shapes[i % 4], 1, btTransform(btQuaternion(btScalar(0.1) * btScalar(i % 5), btScalar(0.2), 0), origin));
		body->setUserIndex(i);
	}
}

Result run(int threads, btITaskScheduler* userScheduler, bool multithreaded, TerrainAt terrainAt, int steps = 50)
{
	caliber_test::ScopedTaskScheduler scheduler(userScheduler ? 0 : threads);
	if (userScheduler) btSetTaskScheduler(userScheduler);
	Result result;
	{
		std::unique_ptr<TestWorld> world(multithreaded ? new TestWorld(TestWorld::Multithreaded(), BT_MAX_THREAD_COUNT)
		                                               : new TestWorld());
		TestWorld& w = *world;
		if (terrainAt == TerrainAt::First) addTerrain(w);
		addBodies(w, 0, kBodies / 2);
		if (terrainAt == TerrainAt::Between) addTerrain(w);
		addBodies(w, kBodies / 2, kBodies);
		if (terrainAt == TerrainAt::Last) addTerrain(w);
		w.run(steps);
		result.bodyBits = caliber_test::bodyStateBits(w.bodies());
		btDispatcher* dispatcher = w.world()->getDispatcher();
		result.manifolds = dispatcher->getNumManifolds();
		for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
		{
			const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
			result.manifoldBits.push_back(btScalar(manifold->getBody0()->getUserIndex()));
			result.manifoldBits.push_back(btScalar(manifold->getBody1()->getUserIndex()));
			const bool terrain = manifold->getBody0()->isStaticObject() || manifold->getBody1()->isStaticObject();
			for (int p = 0; p < manifold->getNumContacts(); ++p)
			{
				const btManifoldPoint& point = manifold->getContactPoint(p);
				for (int k = 0; k < 3; ++k)
				{
					result.manifoldBits.push_back(point.m_positionWorldOnA[k]);
					result.manifoldBits.push_back(point.m_normalWorldOnB[k]);
				}
				result.manifoldBits.push_back(point.m_distance1);
				result.manifoldBits.push_back(point.m_appliedImpulse);
				if (terrain) ++result.terrainPoints;
			}
		}
	}
	btSetTaskScheduler(0);
	return result;
}

bool sameBits(const std::vector<btScalar>& a, const std::vector<btScalar>& b)
{
	return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)) == 0);
}

void expectSame(const Result& reference, const Result& other, const char* what)
{
	EXPECT_TRUE(sameBits(reference.bodyBits, other.bodyBits)) << what;
	EXPECT_EQ(reference.manifolds, other.manifolds) << what;
	EXPECT_TRUE(sameBits(reference.manifoldBits, other.manifoldBits)) << what;
}

// A user's world: it keeps Bullet's pipeline of virtual stages (no prediction in the box loop).
class UsersWorld : public btDiscreteDynamicsWorld
{
public:
	using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
};
}  // namespace

TEST(PredictionWithBoxes, BodiesOnAMeshEndWithTheBitsOfNoSchedulerAtAnyThreadCountAndLayout)
{
	caliber_test::UnevenSplitScheduler uneven;
	caliber_test::LastFirstScheduler lastFirst;
	const TerrainAt layouts[] = {TerrainAt::Last, TerrainAt::First, TerrainAt::Between};
	for (const bool multithreaded : {false, true})
		for (const TerrainAt layout : layouts)
		{
			const Result reference = run(0, 0, multithreaded, layout);
			// The run means something: bodies rest on the terrain and touch each other.
			ASSERT_GT(reference.terrainPoints, 100);
			ASSERT_GT(reference.manifolds, 150);
			expectSame(reference, run(1, 0, multithreaded, layout), "1 thread");
			expectSame(reference, run(2, 0, multithreaded, layout), "2 threads");
			expectSame(reference, run(3, 0, multithreaded, layout), "3 threads");
			expectSame(reference, run(0, &uneven, multithreaded, layout), "uneven splits");
			expectSame(reference, run(0, &lastFirst, multithreaded, layout), "last chunk first");
		}
}

TEST(PredictionWithBoxes, OnlyTheWorldClassesThemselvesWithThreadsAndOneRunOfBodiesHandThePredictionOver)
{
	caliber_test::ScopedTaskScheduler scheduler(2);
	if (btGetTaskScheduler()->getNumThreads() < 2) GTEST_SKIP() << "a library without threads";
	{
		TestWorld w;
		addBodies(w, 0, 40);
		addTerrain(w);
		btAlignedObjectArray<btRigidBody*> bodies;
		for (btRigidBody* body : w.bodies())
			if (!body->isStaticObject()) bodies.push_back(body);
		caliber::PredictionPrologue prologue;
		EXPECT_TRUE(prologue.begin(*w.world(), bodies, btScalar(1. / 60.)));
		// Not one run of the object array (a body missing from the middle), or no body.
		btAlignedObjectArray<btRigidBody*> gap = bodies;
		gap.remove(gap[10]);
		EXPECT_FALSE(prologue.begin(*w.world(), gap, btScalar(1. / 60.)));
		EXPECT_FALSE(prologue.begin(*w.world(), btAlignedObjectArray<btRigidBody*>(), btScalar(1. / 60.)));
		// One thread.
		btGetTaskScheduler()->setNumThreads(1);
		EXPECT_FALSE(prologue.begin(*w.world(), bodies, btScalar(1. / 60.)));
		btGetTaskScheduler()->setNumThreads(2);
	}
	{
		btDefaultCollisionConfiguration configuration;
		btCollisionDispatcher dispatcher(&configuration);
		btDbvtBroadphase broadphase;
		btSequentialImpulseConstraintSolver solver;
		UsersWorld world(&dispatcher, &broadphase, &solver, &configuration);
		btSphereShape sphere(1);
		btRigidBody body(1, 0, &sphere);
		world.addRigidBody(&body);
		btAlignedObjectArray<btRigidBody*> bodies;
		bodies.push_back(&body);
		caliber::PredictionPrologue prologue;
		EXPECT_FALSE(prologue.begin(world, bodies, btScalar(1. / 60.)));
		world.removeRigidBody(&body);
	}
}
