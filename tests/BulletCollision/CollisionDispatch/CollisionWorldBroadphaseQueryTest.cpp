// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The world's queries through the library's broadphases give the same answers as through the brute-force
// test broadphase (which visits every object): the ray and swept-box conventions of btBroadphaseRayCallback
// (direction inverse of to - from, m_lambda_max as a fraction, proxy boxes grown by the swept box) hold.

#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "CollisionWorldTestUtil.h"

using namespace caliber_world_test;

namespace
{
struct Scene
{
	btSphereShape sphere{btScalar(0.7)};
	btBoxShape box{btVector3(0.5, 0.9, 0.6)};
	btTriangleMesh mesh;
	std::unique_ptr<btBvhTriangleMeshShape> meshShape;
	std::vector<btTransform> poses;

	Scene()
	{
		mesh.addTriangle(btVector3(-20, -6, -20), btVector3(-20, -6, 20), btVector3(20, -6, -20));
		mesh.addTriangle(btVector3(20, -6, -20), btVector3(-20, -6, 20), btVector3(20, -6, 20));
		meshShape.reset(new btBvhTriangleMeshShape(&mesh, true));
		Random rng(77);
		for (int i = 0; i < 60; i++) poses.push_back(placed(rng.rotation(), rng.vector(5)));
	}

	std::vector<btCollisionObject*> populate(btCollisionWorld& world,
	                                         std::vector<std::unique_ptr<btCollisionObject>>& owned)
	{
		std::vector<btCollisionObject*> objects;
		for (size_t i = 0; i <= poses.size(); i++)
		{
			owned.emplace_back(new btCollisionObject());
			btCollisionObject* o = owned.back().get();
			if (i == poses.size())
				o->setCollisionShape(meshShape.get());
			else
			{
				o->setCollisionShape(i % 2 ? static_cast<btCollisionShape*>(&sphere) : &box);
				o->setWorldTransform(poses[i]);
			}
			world.addCollisionObject(o);
			objects.push_back(o);
		}
		return objects;
	}
};

// Index of the object in its world's list, so results of two worlds can be compared.
int indexOf(const std::vector<btCollisionObject*>& objects, const btCollisionObject* o)
{
	for (size_t i = 0; i < objects.size(); i++)
		if (objects[i] == o) return int(i);
	return -1;
}
}  // namespace

static void expectBruteForceAnswers(btBroadphaseInterface& broadphase)
{
	Scene scene;
	std::vector<std::unique_ptr<btCollisionObject>> ownedA, ownedB;  // outlive both worlds
	WorldFixture reference;
	const std::vector<btCollisionObject*> refObjects = scene.populate(reference.m_world, ownedA);

	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btCollisionWorld world(&dispatcher, &broadphase, &config);
	const std::vector<btCollisionObject*> objects = scene.populate(world, ownedB);

	Random rng(88);
	int rayHits = 0, sweepHits = 0;
	btSphereShape castSphere(btScalar(0.4));
	btBoxShape castBox(btVector3(0.3, 0.6, 0.2));
	for (int k = 0; k < 80; k++)
	{
		const btVector3 from = rng.unitVector() * btScalar(12);
		const btVector3 to = (k % 4 == 0) ? from : rng.vector(7);  // some zero-length queries too

		btCollisionWorld::ClosestRayResultCallback a(from, to), b(from, to);
		reference.m_world.rayTest(from, to, a);
		world.rayTest(from, to, b);
		EXPECT_EQ(a.hasHit(), b.hasHit()) << "ray " << k;
		if (a.hasHit() != b.hasHit()) continue;
		if (a.hasHit())
		{
			rayHits++;
			EXPECT_EQ(indexOf(refObjects, a.m_collisionObject), indexOf(objects, b.m_collisionObject)) << "ray " << k;
			EXPECT_EQ(a.m_closestHitFraction, b.m_closestHitFraction) << "ray " << k;
		}

		const btConvexShape* cast = (k % 2) ? static_cast<const btConvexShape*>(&castSphere) : &castBox;
		const btTransform start(rng.rotation(), from), end(rng.rotation(), to);
		btCollisionWorld::ClosestConvexResultCallback sa(from, to), sb(from, to);
		reference.m_world.convexSweepTest(cast, start, end, sa);
		world.convexSweepTest(cast, start, end, sb);
		EXPECT_EQ(sa.hasHit(), sb.hasHit()) << "sweep " << k;
		if (sa.hasHit() != sb.hasHit()) continue;
		if (sa.hasHit())
		{
			sweepHits++;
			EXPECT_EQ(indexOf(refObjects, sa.m_hitCollisionObject), indexOf(objects, sb.m_hitCollisionObject))
			    << "sweep " << k;
			EXPECT_EQ(sa.m_closestHitFraction, sb.m_closestHitFraction) << "sweep " << k;
		}
	}
	EXPECT_GT(rayHits, 25);
	EXPECT_GT(sweepHits, 25);
	for (btCollisionObject* o : objects) world.removeCollisionObject(o);
}

TEST(CollisionWorldBroadphaseQuery, SimpleBroadphaseGivesTheBruteForceAnswers)
{
	btSimpleBroadphase broadphase;
	expectBruteForceAnswers(broadphase);
}

TEST(CollisionWorldBroadphaseQuery, DbvtBroadphaseGivesTheBruteForceAnswers)
{
	btDbvtBroadphase broadphase;
	expectBruteForceAnswers(broadphase);
}
