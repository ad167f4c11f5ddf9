// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_COLLISION_WORLD_TEST_UTIL_H
#define CALIBER_TESTS_COLLISION_WORLD_TEST_UTIL_H

// Helpers for the btCollisionWorld tests: a brute-force broadphase and pair cache (independent of the
// library's broadphases, so the world is tested against the interface contract alone), a fixture that
// owns a world with its shapes and objects, and analytic ray intersections used as references.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btBroadphaseInterface.h"
#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "LinearMath/btAabbUtil2.h"
#include "LinearMath/btQuaternion.h"

namespace caliber_world_test
{
class Random
{
public:
	explicit Random(unsigned seed) : m_engine(seed) {}
	btScalar uniform(double lo, double hi)
	{
		return btScalar(std::uniform_real_distribution<double>(lo, hi)(m_engine));
	}
	int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(m_engine); }
	btVector3 vector(double range)
	{
		return btVector3(uniform(-range, range), uniform(-range, range), uniform(-range, range));
	}
	btVector3 unitVector()
	{
		for (;;)
		{
			const btVector3 v = vector(1);
			const btScalar l2 = v.length2();
			if (l2 > btScalar(0.01) && l2 <= 1) return v / btSqrt(l2);
		}
	}
	btQuaternion rotation() { return btQuaternion(unitVector(), uniform(-SIMD_PI, SIMD_PI)); }

private:
	std::mt19937 m_engine;
};

// Stores pairs in one array with linear search: slow and obviously right.
class SimplePairCache : public btOverlappingPairCache
{
public:
	btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override
	{
		if (!needsBroadphaseCollision(proxy0, proxy1)) return 0;
		if (btBroadphasePair* existing = findPair(proxy0, proxy1)) return existing;
		m_pairs.push_back(btBroadphasePair(*proxy0, *proxy1));
		return &m_pairs[m_pairs.size() - 1];
	}
	void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1, btDispatcher* dispatcher) override
	{
		for (int i = 0; i < m_pairs.size(); i++)
			if (joins(m_pairs[i], proxy0, proxy1)) removeAt(i, dispatcher);
		return 0;
	}
	void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override
	{
		for (int i = m_pairs.size() - 1; i >= 0; i--)
			if (m_pairs[i].m_pProxy0 == proxy || m_pairs[i].m_pProxy1 == proxy) removeAt(i, dispatcher);
	}
	btBroadphasePair* getOverlappingPairArrayPtr() override { return m_pairs.size() ? &m_pairs[0] : 0; }
	const btBroadphasePair* getOverlappingPairArrayPtr() const override { return m_pairs.size() ? &m_pairs[0] : 0; }
	btBroadphasePairArray& getOverlappingPairArray() override { return m_pairs; }
	void cleanOverlappingPair(btBroadphasePair& pair, btDispatcher* dispatcher) override
	{
		if (!pair.m_algorithm) return;
		pair.m_algorithm->~btCollisionAlgorithm();
		dispatcher->freeCollisionAlgorithm(pair.m_algorithm);
		pair.m_algorithm = 0;
	}
	int getNumOverlappingPairs() const override { return m_pairs.size(); }
	bool needsBroadphaseCollision(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) const override
	{
		if (m_filter) return m_filter->needBroadphaseCollision(proxy0, proxy1);
		return (proxy0->m_collisionFilterGroup & proxy1->m_collisionFilterMask) != 0 &&
		       (proxy1->m_collisionFilterGroup & proxy0->m_collisionFilterMask) != 0;
	}
	btOverlapFilterCallback* getOverlapFilterCallback() override { return m_filter; }
	void cleanProxyFromPairs(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override
	{
		for (int i = 0; i < m_pairs.size(); i++)
			if (m_pairs[i].m_pProxy0 == proxy || m_pairs[i].m_pProxy1 == proxy)
				cleanOverlappingPair(m_pairs[i], dispatcher);
	}
	void setOverlapFilterCallback(btOverlapFilterCallback* callback) override { m_filter = callback; }
	void processAllOverlappingPairs(btOverlapCallback* callback, btDispatcher* dispatcher) override
	{
		for (int i = 0; i < m_pairs.size();)
		{
			if (callback->processOverlap(m_pairs[i]))
				removeAt(i, dispatcher);
			else
				i++;
		}
	}
	btBroadphasePair* findPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) override
	{
		for (int i = 0; i < m_pairs.size(); i++)
			if (joins(m_pairs[i], proxy0, proxy1)) return &m_pairs[i];
		return 0;
	}
	bool hasDeferredRemoval() override { return false; }
	void setInternalGhostPairCallback(btOverlappingPairCallback*) override {}
	void sortOverlappingPairs(btDispatcher*) override {}

private:
	static bool joins(const btBroadphasePair& pair, const btBroadphaseProxy* a, const btBroadphaseProxy* b)
	{
		return (pair.m_pProxy0 == a && pair.m_pProxy1 == b) || (pair.m_pProxy0 == b && pair.m_pProxy1 == a);
	}
	void removeAt(int i, btDispatcher* dispatcher)
	{
		cleanOverlappingPair(m_pairs[i], dispatcher);
		m_pairs.swap(i, m_pairs.size() - 1);
		m_pairs.pop_back();
	}

	btBroadphasePairArray m_pairs;
	btOverlapFilterCallback* m_filter = 0;
};

// Keeps proxies in an array; rays visit every proxy (allowed by the contract: "may hit"), so the world's
// own tests decide every hit; AABB queries and pairs use exact box overlap.
class BruteForceBroadphase : public btBroadphaseInterface
{
public:
	~BruteForceBroadphase() override
	{
		for (int i = 0; i < m_proxies.size(); i++) delete m_proxies[i];
	}
	btBroadphaseProxy* createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int, void* userPtr, int group,
	                               int mask, btDispatcher*) override
	{
		btBroadphaseProxy* proxy = new btBroadphaseProxy(aabbMin, aabbMax, userPtr, group, mask);
		proxy->m_uniqueId = ++m_nextId;
		m_proxies.push_back(proxy);
		return proxy;
	}
	void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override
	{
		m_cache.removeOverlappingPairsContainingProxy(proxy, dispatcher);
		m_proxies.remove(proxy);
		delete proxy;
	}
	void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax, btDispatcher*) override
	{
		proxy->m_aabbMin = aabbMin;
		proxy->m_aabbMax = aabbMax;
	}
	void getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const override
	{
		aabbMin = proxy->m_aabbMin;
		aabbMax = proxy->m_aabbMax;
	}
	void rayTest(const btVector3&, const btVector3&, btBroadphaseRayCallback& rayCallback, const btVector3&,
	             const btVector3&) override
	{
		m_raysTested++;
		for (int i = 0; i < m_proxies.size(); i++)
			if (!rayCallback.process(m_proxies[i])) return;
	}
	void aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback) override
	{
		for (int i = 0; i < m_proxies.size(); i++)
			if (TestAabbAgainstAabb2(aabbMin, aabbMax, m_proxies[i]->m_aabbMin, m_proxies[i]->m_aabbMax))
				callback.process(m_proxies[i]);
	}
	void calculateOverlappingPairs(btDispatcher* dispatcher) override
	{
		for (int i = 0; i < m_proxies.size(); i++)
			for (int j = i + 1; j < m_proxies.size(); j++)
			{
				btBroadphaseProxy* a = m_proxies[i];
				btBroadphaseProxy* b = m_proxies[j];
				if (TestAabbAgainstAabb2(a->m_aabbMin, a->m_aabbMax, b->m_aabbMin, b->m_aabbMax))
					m_cache.addOverlappingPair(a, b);
				else if (m_cache.findPair(a, b))
					m_cache.removeOverlappingPair(a, b, dispatcher);
			}
	}
	btOverlappingPairCache* getOverlappingPairCache() override { return &m_cache; }
	const btOverlappingPairCache* getOverlappingPairCache() const override { return &m_cache; }
	void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const override
	{
		aabbMin.setValue(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
		aabbMax.setValue(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
	}
	void printStats() override {}

	int numProxies() const { return m_proxies.size(); }
	int m_raysTested = 0;

private:
	btAlignedObjectArray<btBroadphaseProxy*> m_proxies;
	SimplePairCache m_cache;
	int m_nextId = 0;
};

// A world over the default configuration, the real dispatcher and the brute-force broadphase; owns the
// shapes and objects it is given.
class WorldFixture
{
public:
	WorldFixture() : m_dispatcher(&m_config), m_world(&m_dispatcher, &m_broadphase, &m_config) {}
	~WorldFixture()
	{
		for (int i = m_world.getNumCollisionObjects() - 1; i >= 0; i--)
			m_world.removeCollisionObject(m_world.getCollisionObjectArray()[i]);
	}

	template <class Shape>
	Shape* own(Shape* shape)
	{
		m_shapes.emplace_back(shape);
		return shape;
	}

	btCollisionObject* add(btCollisionShape* shape, const btTransform& transform,
	                       int group = btBroadphaseProxy::DefaultFilter, int mask = btBroadphaseProxy::AllFilter)
	{
		m_objects.emplace_back(new btCollisionObject());
		btCollisionObject* object = m_objects.back().get();
		object->setCollisionShape(shape);
		object->setWorldTransform(transform);
		m_world.addCollisionObject(object, group, mask);
		return object;
	}

	btDefaultCollisionConfiguration m_config;
	btCollisionDispatcher m_dispatcher;
	BruteForceBroadphase m_broadphase;
	btCollisionWorld m_world;
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btCollisionObject>> m_objects;
};

inline btTransform placed(const btQuaternion& rotation, const btVector3& origin)
{
	return btTransform(rotation, origin);
}
inline btTransform at(const btVector3& origin) { return btTransform(btQuaternion::getIdentity(), origin); }

// ---- Analytic references, in double precision ----
struct Hit
{
	bool hit = false;
	double fraction = 2;
	btVector3 normal = btVector3(0, 0, 0);
};

struct D3
{
	double x, y, z;
	D3(double a = 0, double b = 0, double c = 0) : x(a), y(b), z(c) {}
	explicit D3(const btVector3& v) : x(v.x()), y(v.y()), z(v.z()) {}
	D3 operator+(const D3& o) const { return D3(x + o.x, y + o.y, z + o.z); }
	D3 operator-(const D3& o) const { return D3(x - o.x, y - o.y, z - o.z); }
	D3 operator*(double s) const { return D3(x * s, y * s, z * s); }
	double dot(const D3& o) const { return x * o.x + y * o.y + z * o.z; }
	D3 cross(const D3& o) const { return D3(y * o.z - z * o.y, z * o.x - x * o.z, x * o.y - y * o.x); }
	double length() const { return std::sqrt(dot(*this)); }
	btVector3 bt() const { return btVector3(btScalar(x), btScalar(y), btScalar(z)); }
};

// First entry of the segment from -> to into the sphere (from outside; a start inside is not a hit here).
inline Hit raySphere(const btVector3& from, const btVector3& to, const btVector3& center, double radius)
{
	Hit h;
	const D3 f(from), d = D3(to) - D3(from), m = f - D3(center);
	const double a = d.dot(d), b = m.dot(d), c = m.dot(m) - radius * radius;
	if (c <= 0 || a == 0) return h;
	const double disc = b * b - a * c;
	if (disc < 0) return h;
	const double t = (-b - std::sqrt(disc)) / a;
	if (t < 0 || t > 1) return h;
	h.hit = true;
	h.fraction = t;
	const D3 p = f + d * t - D3(center);
	h.normal = (p * (1.0 / p.length())).bt();
	return h;
}

// First entry of the segment into the box of half extents he placed by t (slabs in the box frame).
inline Hit rayBox(const btVector3& from, const btVector3& to, const btTransform& t, const btVector3& he)
{
	Hit h;
	const D3 f(t.invXform(from)), e(t.invXform(to)), d = e - f;
	double tEnter = 0, tExit = 1;
	int enterAxis = -1;
	double enterSign = 0;
	const double fa[3] = {f.x, f.y, f.z}, da[3] = {d.x, d.y, d.z};
	for (int axis = 0; axis < 3; axis++)
	{
		const double half = he[axis];
		if (da[axis] == 0)
		{
			if (fa[axis] < -half || fa[axis] > half) return h;
			continue;
		}
		double t0 = (-half - fa[axis]) / da[axis], t1 = (half - fa[axis]) / da[axis];
		double sign = -1;
		if (t0 > t1)
		{
			std::swap(t0, t1);
			sign = 1;
		}
		if (t0 > tEnter)
		{
			tEnter = t0;
			enterAxis = axis;
			enterSign = sign;
		}
		if (t1 < tExit) tExit = t1;
		if (tEnter > tExit) return h;
	}
	if (enterAxis < 0) return h;  // starts inside
	h.hit = true;
	h.fraction = tEnter;
	btVector3 n(0, 0, 0);
	n[enterAxis] = btScalar(enterSign);
	h.normal = t.getBasis() * n;
	return h;
}

// Moller-Trumbore on the segment; the normal faces the segment's start.
inline Hit rayTriangle(const btVector3& from, const btVector3& to, const btVector3& a, const btVector3& b,
                       const btVector3& c)
{
	Hit h;
	const D3 o(from), d = D3(to) - D3(from), A(a), e1 = D3(b) - A, e2 = D3(c) - A;
	const D3 p = d.cross(e2);
	const double det = e1.dot(p);
	if (std::fabs(det) < 1e-14) return h;
	const D3 s = o - A;
	const double u = s.dot(p) / det;
	if (u < 0 || u > 1) return h;
	const D3 q = s.cross(e1);
	const double v = d.dot(q) / det;
	if (v < 0 || u + v > 1) return h;
	const double t = e2.dot(q) / det;
	if (t < 0 || t > 1) return h;
	h.hit = true;
	h.fraction = t;
	D3 n = e1.cross(e2);
	n = n * (1.0 / n.length());
	if (n.dot(d) > 0) n = n * -1.0;
	h.normal = n.bt();
	return h;
}

// Collects every ray hit with its shape info.
struct RecordingRayCallback : public btCollisionWorld::RayResultCallback
{
	struct Entry
	{
		const btCollisionObject* object;
		btScalar fraction;
		btVector3 normal;
		int part;
		int index;
	};
	btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool normalInWorldSpace) override
	{
		EXPECT_TRUE(normalInWorldSpace);
		Entry e = {r.m_collisionObject, r.m_hitFraction, r.m_hitNormalLocal,
		           r.m_localShapeInfo ? r.m_localShapeInfo->m_shapePart : -2,
		           r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -2};
		m_entries.push_back(e);
		m_collisionObject = r.m_collisionObject;
		if (m_closest) m_closestHitFraction = r.m_hitFraction;
		return m_closestHitFraction;
	}
	bool m_closest = true;
	std::vector<Entry> m_entries;
};
}  // namespace caliber_world_test

#endif  // CALIBER_TESTS_COLLISION_WORLD_TEST_UTIL_H
