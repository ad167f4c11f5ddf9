// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCollisionDispatcherMt cuts the pairs into chunks of at most grainSize pairs, smaller when that gives each
// thread several chunks: every pair still goes through the near callback exactly once per dispatch, and the
// manifolds come out in the serial dispatcher's order with its points, at any thread count and grain, and
// with users' schedulers that split or order loops their own way.

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "TestThreadsUtil.h"

namespace
{
// The near callback's calls per pair (by the two objects' user indices), from any thread.
std::mutex g_callsLock;
std::map<std::pair<int, int>, int>* g_calls = 0;

void countingNearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info)
{
	{
		std::lock_guard<std::mutex> lock(g_callsLock);
		const int a = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject)->getUserIndex();
		const int b = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject)->getUserIndex();
		++(*g_calls)[std::make_pair(btMin(a, b), btMax(a, b))];
	}
	btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

struct Outcome
{
	std::vector<btScalar> bits;  // per manifold: the two user indices, then each point's numbers
	int pairs = 0;
	bool eachPairOnce = true;
};

// `count` objects in a row, each overlapping its neighbours (spheres and boxes by turns), so the pairs
// number about twice the objects; `dispatches` dispatches, the objects nudged between them.
Outcome run(bool multithreaded, int grain, int threads, btITaskScheduler* user, int count, int dispatches = 3)
{
	caliber_test::ScopedTaskScheduler scheduler(user ? 0 : threads);
	if (user) btSetTaskScheduler(user);
	Outcome outcome;
	{
		btDefaultCollisionConfiguration configuration;
		std::unique_ptr<btCollisionDispatcher> dispatcher(multithreaded
		                                                      ? new btCollisionDispatcherMt(&configuration, grain)
		                                                      : new btCollisionDispatcher(&configuration));
		dispatcher->setNearCallback(countingNearCallback);
		btDbvtBroadphase broadphase;
		btCollisionWorld world(dispatcher.get(), &broadphase, &configuration);
		btSphereShape sphere(btScalar(0.6));
		btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
		std::vector<std::unique_ptr<btCollisionObject>> objects;
		for (int i = 0; i < count; ++i)
		{
			objects.emplace_back(new btCollisionObject);
			btCollisionObject& object = *objects.back();
			object.setCollisionShape(i % 2 ? static_cast<btCollisionShape*>(&box) : &sphere);
			object.setCollisionFlags(0);
			object.setUserIndex(i);
			object.setWorldTransform(
			    btTransform(btQuaternion(btScalar(0.1) * btScalar(i % 7), 0, 0),
			                btVector3(btScalar(i % 40) * btScalar(0.55), 0, btScalar(i / 40) * btScalar(0.55))));
			world.addCollisionObject(&object);
		}
		std::map<std::pair<int, int>, int> calls;
		g_calls = &calls;
		for (int d = 0; d < dispatches; ++d)
		{
			for (auto& object : objects)
			{
				btTransform t = object->getWorldTransform();
				t.getOrigin() += btVector3(0, btScalar(0.01), 0);
				object->setWorldTransform(t);
			}
			calls.clear();
			world.performDiscreteCollisionDetection();
			outcome.pairs = broadphase.getOverlappingPairCache()->getNumOverlappingPairs();
			if (int(calls.size()) != outcome.pairs) outcome.eachPairOnce = false;
			for (const auto& entry : calls)
				if (entry.second != 1) outcome.eachPairOnce = false;
		}
		g_calls = 0;
		for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
		{
			const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
			outcome.bits.push_back(btScalar(manifold->getBody0()->getUserIndex()));
			outcome.bits.push_back(btScalar(manifold->getBody1()->getUserIndex()));
			for (int p = 0; p < manifold->getNumContacts(); ++p)
			{
				const btManifoldPoint& point = manifold->getContactPoint(p);
				for (int k = 0; k < 3; ++k)
				{
					outcome.bits.push_back(point.m_positionWorldOnB[k]);
					outcome.bits.push_back(point.m_normalWorldOnB[k]);
				}
				outcome.bits.push_back(point.m_distance1);
			}
		}
		for (auto& object : objects) world.removeCollisionObject(object.get());
	}
	btSetTaskScheduler(0);
	return outcome;
}

bool sameBits(const std::vector<btScalar>& a, const std::vector<btScalar>& b)
{
	return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)) == 0);
}
}  // namespace

TEST(CollisionDispatcherMtChunks, EveryPairOnceAndTheSerialManifoldsAtAnyThreadCountGrainAndPairCount)
{
	caliber_test::UnevenSplitScheduler uneven;
	caliber_test::LastFirstScheduler lastFirst;
	// 30 objects: fewer pairs than chunks of the minimum size for 8 a thread; 120 and 400: cut below the grain.
	for (const int count : {30, 120, 400})
	{
		const Outcome serial = run(false, 40, 0, 0, count);
		ASSERT_TRUE(serial.eachPairOnce);
		ASSERT_GT(serial.pairs, count);  // the row overlaps: about two pairs an object
		for (const int grain : {1, 7, 40, 1000})
		{
			struct Case
			{
				int threads;
				btITaskScheduler* user;
				const char* name;
			} cases[] = {{1, 0, "1 thread"},
			             {2, 0, "2 threads"},
			             {3, 0, "3 threads"},
			             {0, &uneven, "uneven splits"},
			             {0, &lastFirst, "last chunk first"}};
			for (const Case& c : cases)
			{
				const Outcome mt = run(true, grain, c.threads, c.user, count);
				EXPECT_TRUE(mt.eachPairOnce) << c.name << ", grain " << grain << ", " << count << " objects";
				EXPECT_EQ(mt.pairs, serial.pairs) << c.name;
				EXPECT_TRUE(sameBits(mt.bits, serial.bits))
				    << c.name << ", grain " << grain << ", " << count << " objects";
			}
		}
	}
}
