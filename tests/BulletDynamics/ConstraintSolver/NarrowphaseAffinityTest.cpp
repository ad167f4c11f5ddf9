// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The narrowphase's thread affinity (btManifoldOwners.h, docs/threading.md "The narrowphase"): the Mt
// solver notes which thread wrote each manifold back, the owners follow the manifolds through the
// dispatcher's swaps when pairs go and come, the next narrowphase lays its chunks out by owner, and none
// of it changes a manifold, a point or a body's state at any thread count or scheduler.
#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletCollision/CollisionDispatch/btManifoldOwners.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "LinearMath/btThreads.h"
#include "MtSolverTestUtil.h"
#include "TestThreadsUtil.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// A user's scheduler that reports two threads and runs each loop whole, in order, on the calling thread:
// the near callbacks then come in the chunks' layout order.
class InOrderTwoThreads : public btITaskScheduler
{
public:
	InOrderTwoThreads() : btITaskScheduler("InOrderTwoThreads") {}
	int getMaxNumThreads() const override { return 2; }
	int getNumThreads() const override { return 2; }
	void setNumThreads(int) override {}
	void parallelFor(int iBegin, int iEnd, int, const btIParallelForBody& body) override
	{
		if (iBegin < iEnd) body.forLoop(iBegin, iEnd);
	}
	btScalar parallelSum(int iBegin, int iEnd, int, const btIParallelSumBody& body) override
	{
		return body.sumLoop(iBegin, iEnd);
	}
};

// The affinity on (or off) for a scope; off after, as by default.
class ScopedAffinity
{
public:
	explicit ScopedAffinity(bool on) { caliber::setNarrowphaseAffinity(on); }
	~ScopedAffinity() { caliber::setNarrowphaseAffinity(false); }
	ScopedAffinity(const ScopedAffinity&) = delete;
	ScopedAffinity& operator=(const ScopedAffinity&) = delete;
};

typedef std::pair<int, int> PairKey;  // the two objects' user indices, lower first

PairKey keyOf(const btCollisionObject* a, const btCollisionObject* b)
{
	return PairKey(btMin(a->getUserIndex(), b->getUserIndex()), btMax(a->getUserIndex(), b->getUserIndex()));
}

std::mutex g_sequenceLock;
std::vector<PairKey>* g_sequence = 0;
std::vector<const btBroadphasePair*>* g_addresses = 0;  // the pairs' places in the pair array, in call order

void recordingNearCallback(btBroadphasePair& pair, btCollisionDispatcher& dispatcher, const btDispatcherInfo& info)
{
	if (g_sequence)
	{
		std::lock_guard<std::mutex> lock(g_sequenceLock);
		g_sequence->push_back(keyOf(static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject),
		                            static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject)));
		g_addresses->push_back(&pair);
	}
	btCollisionDispatcher::defaultNearCallback(pair, dispatcher, info);
}

// The owner a test gives a manifold: unknown, the calling thread (0) or the second thread (1), by turns
// along the array, so neighbours in the array (which the swap-remove moves into each other's place)
// differ.
const unsigned int kTurns[3] = {caliber::kNoManifoldOwner, 0, 1};

struct CollisionOutcome
{
	std::vector<btScalar> bits;  // per manifold: the two user indices, then each point's numbers
	bool ownersFollowed = true;  // every surviving manifold kept its owner through the removals
	int ownedPairs = 0;          // (in-order scheduler) pairs with owner 0 or 1 noted,
	int misplacedPairs = 0;      // and of those, owner-0 pairs in the second half of the calls
	                             // or owner-1 pairs in the first
	bool layoutMoved = false;    // (in-order scheduler) some dispatch ran pairs out of pair order
	int ownersChecked = 0;
};

// `count` overlapping objects in rows (spheres, boxes and compounds of two small spheres by turns) in a
// collision world. Before each dispatch after the first the test notes owners by turns; the objects move
// back and forth between dispatches, so points come and go and the compounds' child pairs make and release
// manifolds inside the dispatch (the replay must put those in pair order); before the last dispatch every
// seventh object is removed (its manifolds are released, the others swapped into their places) and a few
// new ones are added.
CollisionOutcome runCollision(bool multithreaded, int threads, btITaskScheduler* user, int count, bool affine = true)
{
	ScopedAffinity affinity(affine);
	caliber_test::ScopedTaskScheduler scheduler(user ? 0 : threads);
	if (user) btSetTaskScheduler(user);
	CollisionOutcome outcome;
	{
		btDefaultCollisionConfiguration configuration;
		std::unique_ptr<btCollisionDispatcher> dispatcher(multithreaded ? new btCollisionDispatcherMt(&configuration, 7)
		                                                                : new btCollisionDispatcher(&configuration));
		dispatcher->setNearCallback(recordingNearCallback);
		btDbvtBroadphase broadphase;
		btCollisionWorld world(dispatcher.get(), &broadphase, &configuration);
		btSphereShape sphere(btScalar(0.6));
		btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
		btSphereShape small(btScalar(0.3));
		btCompoundShape pair;
		pair.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(btScalar(-0.35), 0, 0)), &small);
		pair.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(btScalar(0.35), 0, 0)), &small);
		btCollisionShape* shapes[3] = {&sphere, &box, &pair};
		std::vector<std::unique_ptr<btCollisionObject>> objects;
		auto add = [&](int i)
		{
			objects.emplace_back(new btCollisionObject);
			btCollisionObject& object = *objects.back();
			object.setCollisionShape(shapes[i % 3]);
			object.setCollisionFlags(0);
			object.setUserIndex(i);
			object.setWorldTransform(
			    btTransform(btQuaternion(btScalar(0.1) * btScalar(i % 7), 0, 0),
			                btVector3(btScalar(i % 40) * btScalar(0.55), 0, btScalar(i / 40) * btScalar(0.55))));
			world.addCollisionObject(&object);
		};
		for (int i = 0; i < count; ++i) add(i);
		const int dispatches = 5;
		for (int d = 0; d < dispatches; ++d)
		{
			for (auto& object : objects)
				if (object->getBroadphaseHandle())
				{
					btTransform t = object->getWorldTransform();
					const int turn = (object->getUserIndex() + d) % 3 - 1;
					t.getOrigin() += btVector3(btScalar(0.12) * btScalar(turn), btScalar(0.01), 0);
					object->setWorldTransform(t);
				}
			// Owners by turns, as a solver would note them (the serial dispatcher keeps none: nothing noted).
			std::map<PairKey, unsigned int> pairOwner;
			if (d > 0)
			{
				const caliber::ManifoldOwnerWriter writer = caliber::manifoldOwnerWriter(dispatcher.get());
				EXPECT_EQ(bool(writer),
				          affine && multithreaded && dispatcher->getNumManifolds() > 0 && (user || threads > 1));
				for (int m = 0; writer && m < dispatcher->getNumManifolds(); ++m)
				{
					const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
					writer.note(manifold, m, kTurns[m % 3]);
					pairOwner[keyOf(manifold->getBody0(), manifold->getBody1())] = kTurns[m % 3];
				}
			}
			if (d == dispatches - 1)
			{
				// Removals and additions between dispatches: each surviving manifold keeps its owner.
				std::map<const btPersistentManifold*, int> before;
				for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
				{
					const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
					before[manifold] = caliber::manifoldOwner(dispatcher.get(), manifold);
				}
				for (size_t i = 0; i < objects.size(); i += 7) world.removeCollisionObject(objects[i].get());
				for (int i = count; i < count + 10; ++i) add(i);
				for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
				{
					const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
					auto it = before.find(manifold);
					if (it == before.end()) continue;
					++outcome.ownersChecked;
					if (caliber::manifoldOwner(dispatcher.get(), manifold) != it->second)
						outcome.ownersFollowed = false;
				}
			}
			std::vector<PairKey> sequence;
			std::vector<const btBroadphasePair*> addresses;
			g_sequence = &sequence;
			g_addresses = &addresses;
			world.performDiscreteCollisionDetection();
			g_sequence = 0;
			g_addresses = 0;
			// With the in-order scheduler the calls come in layout order: the calling thread's pairs first
			// (from the third dispatch: the first one's new manifolds had no index yet when it noted its
			// pairs' manifolds; not after the removals, whose swaps move manifold indices).
			// Counted over the pairs of single shapes (a compound's pair has a manifold per child pair, and
			// the layout follows its first); a pair whose manifold a release's swap moved since the last
			// dispatch may land on the wrong side, so a few per cent are allowed.
			for (size_t k = 0; d >= 2 && d < dispatches - 1 && k < sequence.size(); ++k)
			{
				if (k > 0 && addresses[k] < addresses[k - 1]) outcome.layoutMoved = true;
				if (sequence[k].first % 3 == 2 || sequence[k].second % 3 == 2) continue;
				auto it = pairOwner.find(sequence[k]);
				if (it == pairOwner.end() || it->second > 1) continue;
				++outcome.ownedPairs;
				const bool firstHalf = 2 * k < sequence.size();
				if (firstHalf != (it->second == 0)) ++outcome.misplacedPairs;
			}
		}
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
		for (auto& object : objects)
			if (object->getBroadphaseHandle()) world.removeCollisionObject(object.get());
	}
	btSetTaskScheduler(0);
	return outcome;
}

// Whether the library has threads (without CALIBER_THREADSAFE the narrowphase never runs in chunks).
bool libraryHasThreads()
{
	caliber_test::ScopedTaskScheduler scheduler(2);
	return btGetTaskScheduler()->getNumThreads() >= 2;
}

bool sameBits(const std::vector<btScalar>& a, const std::vector<btScalar>& b)
{
	return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(btScalar)) == 0);
}

const btScalar kHalf = btScalar(0.5);

// Stacks of boxes on a ground box in the Mt world as Bullet's multithreaded examples build it, every solve
// coloured (so the Mt solver's write-back by batch notes the owners).
struct Stacks
{
	explicit Stacks(int threads) : scheduler(threads)
	{
		btDefaultCollisionConstructionInfo info;
		info.m_defaultMaxPersistentManifoldPoolSize = 4096;
		info.m_defaultMaxCollisionAlgorithmPoolSize = 4096;
		config.reset(new btDefaultCollisionConfiguration(info));
		dispatcher.reset(new btCollisionDispatcherMt(config.get(), 8));
		pool.reset(new btConstraintSolverPoolMt(BT_MAX_THREAD_COUNT));
		solverMt.reset(new btSequentialImpulseConstraintSolverMt());
		broadphase.reset(new btDbvtBroadphase());
		world.reset(new btDiscreteDynamicsWorldMt(dispatcher.get(), broadphase.get(), pool.get(), solverMt.get(),
		                                          config.get()));
		world->setGravity(btVector3(0, -10, 0));
		ground.reset(new btBoxShape(btVector3(30, 1, 30)));
		box.reset(new btBoxShape(btVector3(kHalf, kHalf, kHalf)));
		add(0, ground.get(), btVector3(0, -1, 0));
		// 6 x 6 stacks of 6 boxes, touching their neighbours' sides: one island, about 400 manifolds.
		for (int x = 0; x < 6; ++x)
			for (int z = 0; z < 6; ++z)
				for (int level = 0; level < 6; ++level)
					add(1, box.get(),
					    btVector3(btScalar(x) * btScalar(1.0), kHalf + btScalar(level) * btScalar(1.0),
					              btScalar(z) * btScalar(1.0)));
	}
	~Stacks()
	{
		for (auto& body : bodies) world->removeRigidBody(body.get());
	}
	void add(btScalar mass, btCollisionShape* shape, const btVector3& at)
	{
		btVector3 inertia(0, 0, 0);
		if (mass != 0) shape->calculateLocalInertia(mass, inertia);
		motionStates.emplace_back(new btDefaultMotionState(btTransform(btQuaternion::getIdentity(), at)));
		btRigidBody::btRigidBodyConstructionInfo info(mass, motionStates.back().get(), shape, inertia);
		bodies.emplace_back(new btRigidBody(info));
		bodies.back()->setActivationState(DISABLE_DEACTIVATION);
		world->addRigidBody(bodies.back().get());
	}
	void step(int steps)
	{
		for (int i = 0; i < steps; ++i) world->stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	}
	// How many of the dispatcher's manifolds with points have an owner noted.
	int manifoldsWithOwners(int* withPoints) const
	{
		int owned = 0;
		*withPoints = 0;
		for (int m = 0; m < dispatcher->getNumManifolds(); ++m)
		{
			const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
			if (manifold->getNumContacts() == 0) continue;
			++*withPoints;
			if (caliber::manifoldOwner(dispatcher.get(), manifold) >= 0) ++owned;
		}
		return owned;
	}

	caliber_test::ScopedTaskScheduler scheduler;
	std::unique_ptr<btDefaultCollisionConfiguration> config;
	std::unique_ptr<btCollisionDispatcher> dispatcher;
	std::unique_ptr<btConstraintSolverPoolMt> pool;
	std::unique_ptr<btSequentialImpulseConstraintSolverMt> solverMt;
	std::unique_ptr<btBroadphaseInterface> broadphase;
	std::unique_ptr<btDiscreteDynamicsWorld> world;
	std::unique_ptr<btCollisionShape> ground, box;
	std::vector<std::unique_ptr<btDefaultMotionState>> motionStates;
	std::vector<std::unique_ptr<btRigidBody>> bodies;
};
}  // namespace

TEST(NarrowphaseAffinity, LayoutByOwnerKeepsTheSerialManifoldsAndOwnersFollowRemovals)
{
	if (!libraryHasThreads()) GTEST_SKIP() << "a library without threads";
	InOrderTwoThreads inOrder;
	caliber_test::LastFirstScheduler lastFirst;
	caliber_test::UnevenSplitScheduler uneven;
	for (const int count : {120, 400})
	{
		const CollisionOutcome serial = runCollision(false, 0, 0, count);
		ASSERT_FALSE(serial.bits.empty());
		struct Case
		{
			int threads;
			btITaskScheduler* user;
			const char* name;
		} cases[] = {{2, 0, "2 threads"},
		             {3, 0, "3 threads"},
		             {0, &inOrder, "in order"},
		             {0, &lastFirst, "last chunk first"},
		             {0, &uneven, "uneven splits"}};
		for (const Case& c : cases)
		{
			const CollisionOutcome mt = runCollision(true, c.threads, c.user, count);
			EXPECT_TRUE(sameBits(mt.bits, serial.bits)) << c.name << ", " << count << " objects";
			EXPECT_TRUE(mt.ownersFollowed) << c.name << ", " << count << " objects";
			// The removals leave most manifolds (every seventh object goes): the check is not empty.
			EXPECT_GT(mt.ownersChecked, count) << c.name;
			if (c.user == &inOrder)
			{
				// Off, the pairs go in pair order and nothing is noted; the same manifolds.
				const CollisionOutcome off = runCollision(true, 0, &inOrder, count, false);
				EXPECT_TRUE(sameBits(off.bits, serial.bits)) << count << " objects, affinity off";
				EXPECT_FALSE(off.layoutMoved) << count << " objects, affinity off";
				EXPECT_EQ(off.ownedPairs, 0) << count << " objects, affinity off";
				EXPECT_TRUE(mt.layoutMoved) << count << " objects";
				EXPECT_GT(mt.ownedPairs, count) << count << " objects";
				EXPECT_LE(mt.misplacedPairs * 20, mt.ownedPairs) << count << " objects";  // at most 5 %
			}
		}
	}
}

TEST(NarrowphaseAffinity, SolverNotesOwnersAndTheStateIsTheSameAtOneTwoAndThreeThreads)
{
	if (!libraryHasThreads()) GTEST_SKIP() << "a library without threads";
	caliber_test::ScopedManifoldBatchingThreshold colourAll;
	ScopedAffinity affinity(true);
	std::vector<btScalar> reference;
	for (const int threads : {1, 2, 3})
	{
		Stacks stacks(threads);
		stacks.step(40);
		int withPoints = 0;
		const int owned = stacks.manifoldsWithOwners(&withPoints);
		ASSERT_GT(withPoints, 200) << threads << " threads";
		if (threads == 1)
			EXPECT_EQ(owned, 0);  // one thread: a serial narrowphase, no table kept
		else
			EXPECT_GT(owned, withPoints / 2) << threads << " threads";  // the coloured write-back noted them
		const std::vector<btScalar> state = caliber_test::bodyStateBits(stacks.bodies);
		if (threads == 1)
			reference = state;
		else
			EXPECT_TRUE(sameBits(state, reference)) << threads << " threads";
	}
}
