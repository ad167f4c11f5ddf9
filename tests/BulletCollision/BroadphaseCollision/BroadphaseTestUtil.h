// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Shared by the broadphase and pair cache tests (owned by the "pairs" area; the btAxisSweep3 tests may
// include it read-only): a moving random scene, an independent brute-force reference for pairs, AABB
// queries and rays, a recording ghost pair callback, and a dispatcher that counts freed algorithms.

#ifndef CALIBER_BROADPHASE_TEST_UTIL_H
#define CALIBER_BROADPHASE_TEST_UTIL_H

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btBroadphaseInterface.h"
#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"

namespace broadphase_test
{
using shapes_core_test::Random;

// Sanitizer builds run the same scenes with fewer objects and frames so that each file stays fast.
#if defined(__SANITIZE_ADDRESS__)
const int kScale = 4;
#else
const int kScale = 1;
#endif

/// An object id (0, 1, ...) as a proxy's client pointer, and back. Ids start at 1 in the pointer so that
/// no client pointer is null.
inline void* idToClient(int id) { return reinterpret_cast<void*>(static_cast<size_t>(id + 1)); }
inline int clientToId(const btBroadphaseProxy* proxy)
{
	return static_cast<int>(reinterpret_cast<size_t>(proxy->m_clientObject)) - 1;
}

/// An unordered pair of object ids, smaller first.
typedef std::pair<int, int> IdPair;
typedef std::set<IdPair> IdPairSet;

inline IdPair makeIdPair(int a, int b) { return a < b ? IdPair(a, b) : IdPair(b, a); }

/// Independent overlap test: closed boxes (touching counts, as in Bullet).
inline bool boxesOverlap(const btVector3& minA, const btVector3& maxA, const btVector3& minB, const btVector3& maxB)
{
	for (int axis = 0; axis < 3; ++axis)
	{
		if (minA[axis] > maxB[axis] || minB[axis] > maxA[axis]) return false;
	}
	return true;
}

/// Bullet's default filter, written independently of the caches.
inline bool groupMaskAccepts(int groupA, int maskA, int groupB, int maskB)
{
	return (groupA & maskB) != 0 && (groupB & maskA) != 0;
}

/// The pairs of a cache as id pairs; fails the test on a duplicate or a pair of a proxy with itself.
inline IdPairSet cachePairs(btOverlappingPairCache* cache)
{
	IdPairSet result;
	btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
	EXPECT_EQ(pairs.size(), cache->getNumOverlappingPairs());
	for (int i = 0; i < pairs.size(); ++i)
	{
		const int a = clientToId(pairs[i].m_pProxy0);
		const int b = clientToId(pairs[i].m_pProxy1);
		EXPECT_NE(a, b);
		EXPECT_LT(pairs[i].m_pProxy0->m_uniqueId, pairs[i].m_pProxy1->m_uniqueId) << "pair not stored in id order";
		EXPECT_TRUE(result.insert(makeIdPair(a, b)).second) << "duplicate pair " << a << "," << b;
	}
	return result;
}

/// A short description of the difference of two pair sets, for failure messages.
inline std::string describeDifference(const IdPairSet& expected, const IdPairSet& actual)
{
	std::ostringstream out;
	int missing = 0, extra = 0;
	for (const IdPair& p : expected)
	{
		if (actual.count(p)) continue;
		if (missing++ < 5) out << " missing(" << p.first << "," << p.second << ")";
	}
	for (const IdPair& p : actual)
	{
		if (expected.count(p)) continue;
		if (extra++ < 5) out << " extra(" << p.first << "," << p.second << ")";
	}
	out << " [" << missing << " missing, " << extra << " extra of " << expected.size() << " expected]";
	return out.str();
}

/// One object of the random scene.
struct SceneObject
{
	btVector3 center;
	btVector3 half;
	btVector3 velocity;
	int group;
	int mask;
	bool alive;
	btBroadphaseProxy* proxy;

	btVector3 aabbMin() const { return center - half; }
	btVector3 aabbMax() const { return center + half; }
};

/// Random boxes in a cube of side 2 * range that move with constant velocities and bounce off its walls.
class MovingScene
{
public:
	MovingScene(unsigned seed, int count, btScalar range, btScalar maxHalf, btScalar maxSpeed)
	    : m_rng(seed), m_range(range), m_maxHalf(maxHalf), m_maxSpeed(maxSpeed)
	{
		for (int i = 0; i < count; ++i) m_objects.push_back(makeObject());
	}

	SceneObject makeObject()
	{
		SceneObject object;
		object.center = m_rng.vector(m_range);
		object.half = btVector3(m_rng.uniform(btScalar(0.1), m_maxHalf), m_rng.uniform(btScalar(0.1), m_maxHalf),
		                        m_rng.uniform(btScalar(0.1), m_maxHalf));
		object.velocity = m_rng.vector(m_maxSpeed);
		object.group = btBroadphaseProxy::DefaultFilter;
		object.mask = btBroadphaseProxy::AllFilter;
		object.alive = false;
		object.proxy = 0;
		return object;
	}

	/// Moves every object one frame; objects with zero velocity stay put.
	void step()
	{
		for (SceneObject& object : m_objects)
		{
			object.center += object.velocity;
			for (int axis = 0; axis < 3; ++axis)
			{
				if (btFabs(object.center[axis]) > m_range) object.velocity[axis] = -object.velocity[axis];
			}
		}
	}

	/// Every filtered pair of live objects whose boxes overlap, by brute force. extraFilter, when given,
	/// must also accept the pair (mirrors a user btOverlapFilterCallback).
	IdPairSet referencePairs(bool (*extraFilter)(int, int) = 0) const
	{
		IdPairSet result;
		const int n = int(m_objects.size());
		std::vector<btVector3> mins(static_cast<size_t>(n)), maxs(static_cast<size_t>(n));
		for (int i = 0; i < n; ++i)
		{
			mins[size_t(i)] = m_objects[size_t(i)].aabbMin();
			maxs[size_t(i)] = m_objects[size_t(i)].aabbMax();
		}
		for (int i = 0; i < n; ++i)
		{
			const SceneObject& a = m_objects[size_t(i)];
			if (!a.alive) continue;
			for (int j = i + 1; j < n; ++j)
			{
				const SceneObject& b = m_objects[size_t(j)];
				if (!b.alive || !boxesOverlap(mins[size_t(i)], maxs[size_t(i)], mins[size_t(j)], maxs[size_t(j)]))
					continue;
				if (extraFilter ? !extraFilter(i, j) : !groupMaskAccepts(a.group, a.mask, b.group, b.mask)) continue;
				result.insert(IdPair(i, j));
			}
		}
		return result;
	}

	/// Gives about one object in `staticEvery` the static filter (group StaticFilter, mask all but static,
	/// zero velocity) and one in `debrisEvery` a debris group that ignores other debris.
	void assignFilters(int staticEvery, int debrisEvery)
	{
		for (size_t i = 0; i < m_objects.size(); ++i)
		{
			SceneObject& object = m_objects[i];
			if (staticEvery > 0 && i % size_t(staticEvery) == 0)
			{
				object.group = btBroadphaseProxy::StaticFilter;
				object.mask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter;
				object.velocity.setValue(0, 0, 0);
			}
			else if (debrisEvery > 0 && i % size_t(debrisEvery) == 1)
			{
				object.group = btBroadphaseProxy::DebrisFilter;
				object.mask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::DebrisFilter;
			}
		}
	}

	/// Creates the proxy of object i in the broadphase.
	void create(btBroadphaseInterface& broadphase, int i, btDispatcher* dispatcher)
	{
		SceneObject& object = m_objects[size_t(i)];
		object.proxy = broadphase.createProxy(object.aabbMin(), object.aabbMax(), BOX_SHAPE_PROXYTYPE, idToClient(i),
		                                      object.group, object.mask, dispatcher);
		object.alive = object.proxy != 0;
	}

	/// Destroys the proxy of object i.
	void destroy(btBroadphaseInterface& broadphase, int i, btDispatcher* dispatcher)
	{
		SceneObject& object = m_objects[size_t(i)];
		broadphase.destroyProxy(object.proxy, dispatcher);
		object.proxy = 0;
		object.alive = false;
	}

	/// One frame: move, push the AABBs of moving live objects, destroy about `churn` live objects and
	/// re-create about `churn` dead ones (new random place), then calculateOverlappingPairs.
	void frame(btBroadphaseInterface& broadphase, btDispatcher* dispatcher, int churn)
	{
		step();
		for (size_t i = 0; i < m_objects.size(); ++i)
		{
			SceneObject& object = m_objects[i];
			if (object.alive && !object.velocity.isZero())
				broadphase.setAabb(object.proxy, object.aabbMin(), object.aabbMax(), dispatcher);
		}
		const int n = int(m_objects.size());
		for (int k = 0; k < churn; ++k)
		{
			const int i = int(m_rng.uniform(0, btScalar(n) - btScalar(0.001)));
			if (m_objects[size_t(i)].alive)
			{
				destroy(broadphase, i, dispatcher);
			}
			else
			{
				m_objects[size_t(i)].center = m_rng.vector(m_range);
				create(broadphase, i, dispatcher);
			}
		}
		broadphase.calculateOverlappingPairs(dispatcher);
	}

	Random& rng() { return m_rng; }
	std::vector<SceneObject>& objects() { return m_objects; }

private:
	Random m_rng;
	btScalar m_range;
	btScalar m_maxHalf;
	btScalar m_maxSpeed;
	std::vector<SceneObject> m_objects;
};

/// Mirrors the pairs a cache reports through its ghost pair callback; flags inconsistent calls.
class RecordingPairCallback : public btOverlappingPairCallback
{
public:
	btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override
	{
		if (!m_pairs.insert(makeIdPair(clientToId(proxy0), clientToId(proxy1))).second) ++m_errors;
		++m_adds;
		return 0;
	}
	void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1, btDispatcher*) override
	{
		if (m_pairs.erase(makeIdPair(clientToId(proxy0), clientToId(proxy1))) != 1) ++m_errors;
		++m_removes;
		return 0;
	}
	void removeOverlappingPairsContainingProxy(btBroadphaseProxy*, btDispatcher*) override { ++m_errors; }

	IdPairSet m_pairs;
	int m_adds = 0;
	int m_removes = 0;
	int m_errors = 0;  // an add of a known pair, a remove of an unknown one, or a bulk call
};

/// Collects the proxies a query reports.
struct CollectingAabbCallback : public btBroadphaseAabbCallback
{
	bool process(const btBroadphaseProxy* proxy) override
	{
		ids.push_back(clientToId(proxy));
		return true;
	}
	std::vector<int> ids;
};

/// A ray callback with the inverse direction and signs filled in, collecting the proxies it is given.
struct CollectingRayCallback : public btBroadphaseRayCallback
{
	CollectingRayCallback(const btVector3& from, const btVector3& to)
	{
		const btVector3 direction = to - from;
		for (int axis = 0; axis < 3; ++axis)
		{
			m_rayDirectionInverse[axis] =
			    direction[axis] == btScalar(0) ? btScalar(BT_LARGE_FLOAT) : btScalar(1) / direction[axis];
			m_signs[axis] = m_rayDirectionInverse[axis] < btScalar(0) ? 1u : 0u;
		}
		m_lambda_max = btScalar(1);
	}
	bool process(const btBroadphaseProxy* proxy) override
	{
		ids.push_back(clientToId(proxy));
		return true;
	}
	std::vector<int> ids;
};

/// Reference segment-box test with a safety band: 1 = surely hit, 0 = surely missed, -1 = too close to
/// call (a grazing ray, where float rounding may go either way in the code under test).
inline int segmentHitsBox(const btVector3& from, const btVector3& to, const btVector3& boxMin, const btVector3& boxMax)
{
	// A band of 1e-4 of the box size covers float rounding of the slab parameters for boxes of size ~1-10.
	const double band = 1e-4;
	double enterSure = 0, exitSure = 1, enterLoose = 0, exitLoose = 1;
	for (int axis = 0; axis < 3; ++axis)
	{
		const double o = double(from[axis]);
		const double d = double(to[axis]) - o;
		const double lo = double(boxMin[axis]);
		const double hi = double(boxMax[axis]);
		const double pad = band * (1 + (hi - lo));
		if (d == 0)
		{
			if (o < lo - pad || o > hi + pad) return 0;
			if (o < lo + pad || o > hi - pad) enterSure = 2;  // on the slab's edge: not sure
			continue;
		}
		double t0 = (lo - o) / d, t1 = (hi - o) / d;
		if (t0 > t1) std::swap(t0, t1);
		const double padT = pad / std::fabs(d);
		enterSure = std::max(enterSure, t0 + padT);
		exitSure = std::min(exitSure, t1 - padT);
		enterLoose = std::max(enterLoose, t0 - padT);
		exitLoose = std::min(exitLoose, t1 + padT);
	}
	if (enterLoose > exitLoose) return 0;
	if (enterSure <= exitSure) return 1;
	return -1;
}

/// aabbTest with random boxes: the reported proxies must be exactly the live objects whose AABBs overlap
/// the query (each once).
inline void checkAabbQueries(btBroadphaseInterface& broadphase, MovingScene& scene, int queries, btScalar range)
{
	std::vector<SceneObject>& objects = scene.objects();
	for (int q = 0; q < queries; ++q)
	{
		const btVector3 center = scene.rng().vector(range);
		const btVector3 half(scene.rng().uniform(0, 6), scene.rng().uniform(0, 6), scene.rng().uniform(0, 6));
		CollectingAabbCallback callback;
		broadphase.aabbTest(center - half, center + half, callback);
		std::set<int> reported(callback.ids.begin(), callback.ids.end());
		EXPECT_EQ(reported.size(), callback.ids.size()) << "a proxy was reported twice, query " << q;
		std::set<int> expected;
		for (size_t i = 0; i < objects.size(); ++i)
		{
			if (objects[i].alive &&
			    boxesOverlap(center - half, center + half, objects[i].aabbMin(), objects[i].aabbMax()))
				expected.insert(int(i));
		}
		EXPECT_EQ(reported, expected) << "query " << q;
	}
}

/// rayTest with random segments (some along an axis): every live object the segment surely hits is
/// reported, none it surely misses is, none twice.
inline void checkRayQueries(btBroadphaseInterface& broadphase, MovingScene& scene, int rays, btScalar range)
{
	std::vector<SceneObject>& objects = scene.objects();
	for (int r = 0; r < rays; ++r)
	{
		const btVector3 from = scene.rng().vector(range * btScalar(1.2));
		btVector3 to = scene.rng().vector(range * btScalar(1.2));
		if (r % 4 == 0) to = btVector3(from.x(), from.y(), to.z());  // axis-parallel: zero direction components
		CollectingRayCallback callback(from, to);
		broadphase.rayTest(from, to, callback);
		std::set<int> reported(callback.ids.begin(), callback.ids.end());
		EXPECT_EQ(reported.size(), callback.ids.size()) << "a proxy was reported twice, ray " << r;
		for (size_t i = 0; i < objects.size(); ++i)
		{
			const int verdict =
			    objects[i].alive ? segmentHitsBox(from, to, objects[i].aabbMin(), objects[i].aabbMax()) : 0;
			if (verdict == 1)
			{
				EXPECT_EQ(reported.count(int(i)), 1u) << "missed object " << i << " ray " << r;
			}
			else if (verdict == 0)
			{
				EXPECT_EQ(reported.count(int(i)), 0u) << "false hit object " << i << " ray " << r;
			}
		}
	}
}

/// A btCollisionAlgorithm that counts its destruction.
class CountingAlgorithm : public btCollisionAlgorithm
{
public:
	explicit CountingAlgorithm(int* destroyed) : m_destroyed(destroyed) {}
	~CountingAlgorithm() override { ++*m_destroyed; }
	void processCollision(const btCollisionObjectWrapper*, const btCollisionObjectWrapper*, const btDispatcherInfo&,
	                      btManifoldResult*) override
	{
	}
	btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
	                               btManifoldResult*) override
	{
		return btScalar(1);
	}
	void getAllContactManifolds(btManifoldArray&) override {}

private:
	int* m_destroyed;
};

/// A dispatcher that only allocates and frees algorithm memory, counting both.
class CountingDispatcher : public btDispatcher
{
public:
	btCollisionAlgorithm* findAlgorithm(const btCollisionObjectWrapper*, const btCollisionObjectWrapper*,
	                                    btPersistentManifold*, ebtDispatcherQueryType) override
	{
		return 0;
	}
	btPersistentManifold* getNewManifold(const btCollisionObject*, const btCollisionObject*) override { return 0; }
	void releaseManifold(btPersistentManifold*) override {}
	void clearManifold(btPersistentManifold*) override {}
	bool needsCollision(const btCollisionObject*, const btCollisionObject*) override { return true; }
	bool needsResponse(const btCollisionObject*, const btCollisionObject*) override { return true; }
	void dispatchAllCollisionPairs(btOverlappingPairCache*, const btDispatcherInfo&, btDispatcher*) override {}
	int getNumManifolds() const override { return 0; }
	btPersistentManifold* getManifoldByIndexInternal(int) override { return 0; }
	btPersistentManifold** getInternalManifoldPointer() override { return 0; }
	btPoolAllocator* getInternalManifoldPool() override { return 0; }
	const btPoolAllocator* getInternalManifoldPool() const override { return 0; }
	void* allocateCollisionAlgorithm(int size) override
	{
		++allocated;
		return btAlignedAlloc(size_t(size), 16);
	}
	void freeCollisionAlgorithm(void* ptr) override
	{
		++freed;
		btAlignedFree(ptr);
	}

	/// Gives the pair a CountingAlgorithm allocated through this dispatcher.
	void attachAlgorithm(btBroadphasePair& pair)
	{
		pair.m_algorithm =
		    new (allocateCollisionAlgorithm(int(sizeof(CountingAlgorithm)))) CountingAlgorithm(&destroyed);
	}

	int allocated = 0;
	int freed = 0;
	int destroyed = 0;
};

}  // namespace broadphase_test

#endif  // CALIBER_BROADPHASE_TEST_UTIL_H
