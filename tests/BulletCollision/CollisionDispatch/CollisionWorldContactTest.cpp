// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCollisionWorld::contactTest and contactPairTest: the same contacts as the simulation step, analytic
// sphere contacts, the distance threshold, filtering and bad input.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btManifoldPoint.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "CollisionWorldTestUtil.h"

using namespace caliber_world_test;

namespace
{
typedef std::pair<const btCollisionObject*, const btCollisionObject*> ObjectPair;

ObjectPair ordered(const btCollisionObject* a, const btCollisionObject* b)
{
	return a < b ? ObjectPair(a, b) : ObjectPair(b, a);
}

// Keeps the deepest (smallest) distance reported per pair, and every point.
struct RecordingContactCallback : public btCollisionWorld::ContactResultCallback
{
	btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int,
	                         const btCollisionObjectWrapper* w1, int, int) override
	{
		const ObjectPair key = ordered(w0->getCollisionObject(), w1->getCollisionObject());
		auto it = m_deepest.find(key);
		if (it == m_deepest.end() || cp.getDistance() < it->second) m_deepest[key] = cp.getDistance();
		m_points.push_back(cp);
		m_first.push_back(w0->getCollisionObject());
		return 0;
	}
	std::map<ObjectPair, btScalar> m_deepest;
	std::vector<btManifoldPoint> m_points;
	std::vector<const btCollisionObject*> m_first;
};
}  // namespace

TEST(CollisionWorldContactTest, ContactTestFindsTheSameContactsAsTheSimulationStep)
{
	WorldFixture f;
	Random rng(303);
	std::vector<btCollisionObject*> objects;
	for (int i = 0; i < 30; i++)
	{
		btCollisionShape* shape;
		if (i % 2)
			shape = f.own(new btSphereShape(rng.uniform(0.4, 1)));
		else
			shape =
			    f.own(new btBoxShape(btVector3(rng.uniform(0.3, 0.8), rng.uniform(0.3, 0.8), rng.uniform(0.3, 0.8))));
		objects.push_back(f.add(shape, placed(rng.rotation(), rng.vector(3.5))));
		objects.back()->setCollisionFlags(0);
	}
	f.m_world.performDiscreteCollisionDetection();
	// Clearly penetrating pairs (deeper than 2 mm: below that, float rounding decides) and their depth.
	const btScalar clear = btScalar(-2e-3);
	std::map<ObjectPair, btScalar> simulated;
	for (int m = 0; m < f.m_dispatcher.getNumManifolds(); m++)
	{
		const btPersistentManifold* manifold = f.m_dispatcher.getManifoldByIndexInternal(m);
		for (int p = 0; p < manifold->getNumContacts(); p++)
		{
			const ObjectPair key = ordered(manifold->getBody0(), manifold->getBody1());
			const btScalar d = manifold->getContactPoint(p).getDistance();
			auto it = simulated.find(key);
			if (it == simulated.end() || d < it->second) simulated[key] = d;
		}
	}
	RecordingContactCallback queried;
	for (btCollisionObject* object : objects) f.m_world.contactTest(object, queried);

	int compared = 0;
	for (const auto& entry : simulated)
	{
		if (entry.second > clear) continue;
		auto it = queried.m_deepest.find(entry.first);
		ASSERT_TRUE(it != queried.m_deepest.end()) << "simulated depth " << entry.second;
		// Sphere pairs: both paths are exact up to rounding. Pairs with a box: the contact algorithms see the
		// sharp box, the closest-point algorithms (GJK/EPA) its core rounded by the margin, which differ near
		// edges and corners by up to margin * (sqrt(3) - 1).
		const bool spheres = entry.first.first->getCollisionShape()->getShapeType() == SPHERE_SHAPE_PROXYTYPE &&
		                     entry.first.second->getCollisionShape()->getShapeType() == SPHERE_SHAPE_PROXYTYPE;
		const double rounding = sizeof(btScalar) == 4 ? 2e-3 : 1e-5;
		const double tol = spheres ? rounding : 0.04 * (std::sqrt(3.0) - 1) + rounding;
		EXPECT_NEAR(it->second, entry.second, tol) << entry.first.first->getCollisionShape()->getName() << " "
		                                           << entry.first.second->getCollisionShape()->getName();
		compared++;
	}
	for (const auto& entry : queried.m_deepest)
	{
		if (entry.second > clear) continue;
		EXPECT_TRUE(simulated.count(entry.first)) << "queried depth " << entry.second;
	}
	EXPECT_GT(compared, 10);
}

TEST(CollisionWorldContactTest, ContactPairTestGivesTheAnalyticSphereContact)
{
	WorldFixture f;
	btSphereShape* a = f.own(new btSphereShape(1));
	btSphereShape* b = f.own(new btSphereShape(btScalar(0.5)));
	const btVector3 ca(0, 0, 0), cb(1.2, 0.4, 0);
	btCollisionObject* objA = f.add(a, at(ca));
	btCollisionObject* objB = f.add(b, at(cb));
	RecordingContactCallback cb0;
	f.m_world.contactPairTest(objA, objB, cb0);
	ASSERT_EQ(cb0.m_points.size(), 1u);
	const btManifoldPoint& p = cb0.m_points[0];
	const btScalar centreDistance = (cb - ca).length();
	const btVector3 nOnB = (ca - cb) / centreDistance;  // from B towards A
	const btScalar tol = btScalar(1e-5);
	EXPECT_EQ(cb0.m_first[0], objA);
	EXPECT_NEAR(p.getDistance(), centreDistance - 1.5, tol);
	EXPECT_GT(p.m_normalWorldOnB.dot(nOnB), btScalar(0.99999));
	EXPECT_LE((p.m_positionWorldOnB - (cb + nOnB * btScalar(0.5))).length(), tol);
	EXPECT_LE((p.m_positionWorldOnA - (ca - nOnB * btScalar(1))).length(), tol);
	EXPECT_LE((p.m_localPointA - (ca - nOnB)).length(), tol);
}

TEST(CollisionWorldContactTest, DistanceThresholdReportsSeparatedPairs)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* a = f.add(sphere, at(btVector3(0, 0, 0)));
	f.add(sphere, at(btVector3(2.5, 0, 0)));
	RecordingContactCallback strict;
	f.m_world.contactTest(a, strict);
	EXPECT_TRUE(strict.m_points.empty());
	RecordingContactCallback loose;
	loose.m_closestDistanceThreshold = 1;
	f.m_world.contactTest(a, loose);
	ASSERT_EQ(loose.m_points.size(), 1u);
	EXPECT_NEAR(loose.m_points[0].getDistance(), 0.5, 1e-4);
}

TEST(CollisionWorldContactTest, ContactTestHonoursGroupMaskAndIgnoreLists)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* query = f.add(sphere, at(btVector3(0, 0, 0)));
	btCollisionObject* group2 = f.add(sphere, at(btVector3(1, 0, 0)), 2, btBroadphaseProxy::AllFilter);
	btCollisionObject* group4 = f.add(sphere, at(btVector3(-1, 0, 0)), 4, btBroadphaseProxy::AllFilter);
	btCollisionObject* ignored = f.add(sphere, at(btVector3(0, 1, 0)));
	query->setIgnoreCollisionCheck(ignored, true);

	RecordingContactCallback all;
	f.m_world.contactTest(query, all);
	EXPECT_EQ(all.m_deepest.size(), 2u);  // group2 and group4; never itself, never the ignored one
	EXPECT_TRUE(all.m_deepest.count(ordered(query, group2)));
	EXPECT_TRUE(all.m_deepest.count(ordered(query, group4)));

	RecordingContactCallback only4;
	only4.m_collisionFilterMask = 4;
	f.m_world.contactTest(query, only4);
	ASSERT_EQ(only4.m_deepest.size(), 1u);
	EXPECT_TRUE(only4.m_deepest.count(ordered(query, group4)));
}

TEST(CollisionWorldContactTest, ContactPairTestWorksOnObjectsOutsideTheWorld)
{
	WorldFixture f;
	btBoxShape box(btVector3(1, 1, 1));
	btCollisionObject a, b;
	a.setCollisionShape(&box);
	b.setCollisionShape(&box);
	b.setWorldTransform(at(btVector3(0, 1.5, 0)));
	RecordingContactCallback cb;
	f.m_world.contactPairTest(&a, &b, cb);
	ASSERT_FALSE(cb.m_points.empty());
	// Boxes stacked with 0.5 of overlap along y.
	EXPECT_NEAR(cb.m_deepest.begin()->second, -0.5, sizeof(btScalar) == 4 ? 2e-3 : 1e-5);
}

TEST(CollisionWorldContactTest, NullObjectAssertsOrReportsNothing)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* a = f.add(sphere, at(btVector3(0, 0, 0)));
	RecordingContactCallback cb;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.contactTest(0, cb), "assertion failed");
	EXPECT_DEATH(f.m_world.contactPairTest(a, 0, cb), "assertion failed");
#else
	f.m_world.contactTest(0, cb);
	f.m_world.contactPairTest(a, 0, cb);
	EXPECT_TRUE(cb.m_points.empty());
#endif
}
