// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCollisionWorld::rayTest is const, and Bullet programs call it from their own worker threads (AI line of
// sight, vehicles, audio occlusion) while no step runs. Several std::threads casting rays at once against one
// world must each get, bit for bit, what the same rays give one at a time: the broadphases' ray walks keep
// their stacks on the caller's stack, the shapes' ray tests keep no scratch in the shapes, and nothing is
// cached on the way. This file is also built into ThreadingTests, which runs under ThreadSanitizer.

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btAxisSweep3.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"

namespace
{
// One ray's answer: the closest hit (object, fraction, normal, part, triangle) and the number and sum of
// the fractions of all hits (an all-hits query).
struct RayAnswer
{
	const btCollisionObject* object = nullptr;
	btScalar fraction = btScalar(2);
	btVector3 normal = btVector3(0, 0, 0);
	int part = -3;
	int index = -3;
	int allHits = 0;
	btScalar allHitsFractionSum = 0;

	bool operator==(const RayAnswer& o) const
	{
		return object == o.object && fraction == o.fraction && normal == o.normal && part == o.part &&
		       index == o.index && allHits == o.allHits && allHitsFractionSum == o.allHitsFractionSum;
	}
};

// The closest hit with the shape info the world's callbacks pass (no test macros here: it runs on threads).
struct ClosestWithShapeInfo : btCollisionWorld::ClosestRayResultCallback
{
	ClosestWithShapeInfo(const btVector3& from, const btVector3& to) : ClosestRayResultCallback(from, to) {}
	btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool normalInWorldSpace) override
	{
		m_part = r.m_localShapeInfo ? r.m_localShapeInfo->m_shapePart : -2;
		m_index = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -2;
		return ClosestRayResultCallback::addSingleResult(r, normalInWorldSpace);
	}
	int m_part = -3;
	int m_index = -3;
};

// A world over one of three broadphases with every kind of shape the world's ray test treats on its own path:
// a quantized BVH mesh terrain, a heightfield, a plane, hulls with and without polyhedral features, boxes,
// spheres, capsules, cylinders and a compound, scattered over [-20, 20]^2 above the terrain.
class RayWorld
{
public:
	explicit RayWorld(int broadphaseKind)
	{
		if (broadphaseKind == 0)
			m_broadphase.reset(new btDbvtBroadphase());
		else if (broadphaseKind == 1)
			m_broadphase.reset(new btAxisSweep3(btVector3(-100, -100, -100), btVector3(100, 100, 100)));
		else
			m_broadphase.reset(new btSimpleBroadphase());
		m_dispatcher.reset(new btCollisionDispatcher(&m_config));
		m_world.reset(new btCollisionWorld(m_dispatcher.get(), m_broadphase.get(), &m_config));

		// Terrain: a bumpy 16 x 16 grid of quads at y around 0.
		m_mesh.reset(new btTriangleMesh());
		auto height = [](int i, int j) { return btScalar(0.4) * btSin(btScalar(i) * btScalar(0.9)) * btCos(btScalar(j)); };
		for (int i = 0; i < 16; ++i)
			for (int j = 0; j < 16; ++j)
			{
				auto v = [&](int a, int b) { return btVector3(btScalar(a * 3 - 24), height(a, b), btScalar(b * 3 - 24)); };
				m_mesh->addTriangle(v(i, j), v(i, j + 1), v(i + 1, j));
				m_mesh->addTriangle(v(i + 1, j), v(i, j + 1), v(i + 1, j + 1));
			}
		add(own(new btBvhTriangleMeshShape(m_mesh.get(), true)), btTransform::getIdentity());
		// A heightfield beside it, and a plane below everything.
		m_heights.resize(9 * 9);
		for (int k = 0; k < 81; ++k) m_heights[k] = btScalar(k % 5) * btScalar(0.3);
		add(own(new btHeightfieldTerrainShape(9, 9, &m_heights[0], 1, 0, 2, 1, PHY_FLOAT, false)),
		    btTransform(btQuaternion::getIdentity(), btVector3(35, 1, 0)));
		add(own(new btStaticPlaneShape(btVector3(0, 1, 0), -5)), btTransform::getIdentity());

		btConvexHullShape* hull = own(new btConvexHullShape());
		btConvexHullShape* featuredHull = own(new btConvexHullShape());
		for (int ring = 0; ring < 3; ++ring)
			for (int k = 0; k < 8; ++k)
			{
				const btScalar angle = btScalar(k) * SIMD_PI / 4;
				const btScalar radius = ring == 1 ? btScalar(1.6) : btScalar(1);
				const btVector3 p(radius * btCos(angle), btScalar(ring - 1) * btScalar(1.5), radius * btSin(angle));
				hull->addPoint(p);
				featuredHull->addPoint(p);
			}
		featuredHull->initializePolyhedralFeatures();
		btCompoundShape* compound = own(new btCompoundShape());
		compound->addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(1, 0, 0)), own(new btSphereShape(0.7)));
		compound->addChildShape(btTransform(btQuaternion(btVector3(0, 0, 1), 0.5), btVector3(-1, 0, 0)),
		                        own(new btBoxShape(btVector3(0.5, 1, 0.3))));
		btCollisionShape* shapes[8] = {hull,
		                               featuredHull,
		                               own(new btBoxShape(btVector3(1, 0.5, 0.8))),
		                               own(new btSphereShape(0.9)),
		                               own(new btCapsuleShape(0.5, 1.5)),
		                               own(new btCylinderShape(btVector3(0.8, 1, 0.8))),
		                               compound,
		                               hull};
		for (int i = 0; i < 48; ++i)
		{
			const btVector3 origin(btScalar((i * 7) % 13) * 3 - 18, btScalar(2 + (i % 4) * 2), btScalar((i * 5) % 11) * 3 - 15);
			const btQuaternion turn(btVector3(btScalar(1 + i % 3), btScalar(2), btScalar(i % 5)).normalized(),
			                        btScalar(i) * btScalar(0.37));
			add(shapes[i % 8], btTransform(turn, origin));
		}
	}
	~RayWorld()
	{
		for (int i = m_world->getNumCollisionObjects() - 1; i >= 0; --i)
			m_world->removeCollisionObject(m_world->getCollisionObjectArray()[i]);
	}

	// The answer of ray k of the fixed set: rays from above and from the sides, a fan from inside the
	// cluster (some start inside shapes), vertical rays and short rays.
	static void ray(int k, btVector3& from, btVector3& to)
	{
		const btScalar a = btScalar(k) * btScalar(0.61803);
		switch (k % 4)
		{
			case 0:
				from = btVector3(btScalar(k % 17) * 2 - 16, 20, btScalar(k % 13) * 2 - 12);
				to = from + btVector3(btCos(a) * 10, -30, btSin(a) * 10);
				break;
			case 1:
				from = btVector3(-30, btScalar(1 + k % 7), btScalar(k % 23) - 11);
				to = btVector3(30, btScalar(k % 5) - 2, btScalar(k % 19) - 9);
				break;
			case 2:
				from = btVector3(btScalar((k * 7) % 13) * 3 - 18, btScalar(2 + (k % 4) * 2), btScalar((k * 5) % 11) * 3 - 15);
				to = from + btVector3(btCos(a) * 40, btScalar(k % 9) - 6, btSin(a) * 40);
				break;
			default:
				from = btVector3(btScalar(k % 29) - 14, 9, btScalar(k % 31) - 15);
				to = from - btVector3(0, btScalar(k % 3 == 0 ? 3 : 20), 0);
				break;
		}
	}

	RayAnswer answer(int k) const
	{
		btVector3 from, to;
		ray(k, from, to);
		ClosestWithShapeInfo closest(from, to);
		m_world->rayTest(from, to, closest);
		btCollisionWorld::AllHitsRayResultCallback all(from, to);
		m_world->rayTest(from, to, all);
		RayAnswer r;
		if (closest.hasHit())
		{
			r.object = closest.m_collisionObject;
			r.fraction = closest.m_closestHitFraction;
			r.normal = closest.m_hitNormalWorld;
			r.part = closest.m_part;
			r.index = closest.m_index;
		}
		r.allHits = all.m_hitFractions.size();
		// The all-hits order is the broadphase's, which is fixed for a given world: summed in that order.
		for (int i = 0; i < all.m_hitFractions.size(); ++i) r.allHitsFractionSum += all.m_hitFractions[i];
		return r;
	}

	const btCollisionWorld& world() const { return *m_world; }

private:
	template <class Shape>
	Shape* own(Shape* shape)
	{
		m_shapes.emplace_back(shape);
		return shape;
	}
	void add(btCollisionShape* shape, const btTransform& transform)
	{
		m_objects.emplace_back(new btCollisionObject());
		m_objects.back()->setCollisionShape(shape);
		m_objects.back()->setWorldTransform(transform);
		m_world->addCollisionObject(m_objects.back().get());
	}

	btDefaultCollisionConfiguration m_config;
	std::unique_ptr<btCollisionDispatcher> m_dispatcher;
	std::unique_ptr<btBroadphaseInterface> m_broadphase;
	std::unique_ptr<btCollisionWorld> m_world;
	std::unique_ptr<btTriangleMesh> m_mesh;
	std::vector<btScalar> m_heights;
	std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
	std::vector<std::unique_ptr<btCollisionObject>> m_objects;
};
}  // namespace

TEST(CollisionWorldConcurrentRays, RaysFromSeveralThreadsAtOnceAnswerAsSerialRays)
{
	const int kRays = 240;
	const int kThreads = 4;
	for (int broadphaseKind = 0; broadphaseKind < 3; ++broadphaseKind)
	{
		const RayWorld world(broadphaseKind);
		std::vector<RayAnswer> serial(kRays);
		int hits = 0;
		for (int k = 0; k < kRays; ++k)
		{
			serial[k] = world.answer(k);
			if (serial[k].object) ++hits;
		}
		// The rays must reach the shapes, or the comparison below proves little.
		EXPECT_GT(hits, kRays / 2) << "broadphase " << broadphaseKind;

		// Every thread casts every ray, each starting at its own place in the set, all released at once so
		// that their queries overlap.
		std::vector<std::vector<RayAnswer>> answers(kThreads, std::vector<RayAnswer>(kRays));
		std::atomic<int> ready(0);
		std::vector<std::thread> threads;
		for (int t = 0; t < kThreads; ++t)
			threads.emplace_back([&, t]() {
				ready.fetch_add(1);
				while (ready.load() < kThreads) std::this_thread::yield();
				for (int i = 0; i < kRays; ++i)
				{
					const int k = (i + t * kRays / kThreads) % kRays;
					answers[t][k] = world.answer(k);
				}
			});
		for (std::thread& thread : threads) thread.join();
		for (int t = 0; t < kThreads; ++t)
			for (int k = 0; k < kRays; ++k)
				EXPECT_TRUE(answers[t][k] == serial[k]) << "broadphase " << broadphaseKind << " thread " << t << " ray " << k;
	}
}
