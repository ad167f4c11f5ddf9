// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The contact cache (include/Caliber/ContactCache.h): a collision world of 256 boxes resting on a slab,
// each nudged by up to 0.1 mm per step (a settled pile's jitter), detected with the cache off (distance 0,
// Bullet's behaviour) and on (1 mm). "points_per_box" is the sanity figure: the cache must not lose
// contacts (4 per box either way).
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "Caliber/ContactCache.h"

namespace
{
const int kBoxes = 256;

void BM_RestingBoxesDetection(benchmark::State& state)
{
	const btScalar previousDistance = caliber::getContactCacheDistance();
	caliber::setContactCacheDistance(btScalar(state.range(0)) * btScalar(0.001));
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btDbvtBroadphase broadphase;
	btCollisionWorld world(&dispatcher, &broadphase, &config);
	btBoxShape slabShape(btVector3(40, 1, 40));
	btBoxShape boxShape(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	btCollisionObject slab;
	slab.setCollisionShape(&slabShape);
	world.addCollisionObject(&slab);
	std::vector<std::unique_ptr<btCollisionObject>> boxes;
	std::vector<btVector3> rest;
	for (int i = 0; i < kBoxes; ++i)
	{
		boxes.emplace_back(new btCollisionObject());
		boxes.back()->setCollisionShape(&boxShape);
		// 1.5 m apart: each box touches only the slab.
		rest.push_back(
		    btVector3(btScalar(i % 16) * btScalar(1.5) - 12, btScalar(1.49), btScalar(i / 16) * btScalar(1.5) - 12));
		boxes.back()->setWorldTransform(btTransform(btQuaternion::getIdentity(), rest.back()));
		world.addCollisionObject(boxes.back().get());
	}
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> jitter(-0.00005, 0.00005);  // up to 0.1 mm from rest
	long long points = 0, steps = 0;
	for (auto _ : state)
	{
		for (int i = 0; i < kBoxes; ++i)
		{
			const btVector3 offset(btScalar(jitter(rng)), btScalar(jitter(rng)), btScalar(jitter(rng)));
			boxes[i]->setWorldTransform(btTransform(btQuaternion::getIdentity(), rest[i] + offset));
		}
		world.performDiscreteCollisionDetection();
		for (int m = 0; m < dispatcher.getNumManifolds(); ++m)
			points += dispatcher.getManifoldByIndexInternal(m)->getNumContacts();
		++steps;
	}
	state.counters["points_per_box"] = double(points) / double(steps * kBoxes);
	state.SetItemsProcessed(steps * kBoxes);
	for (auto& box : boxes) world.removeCollisionObject(box.get());
	world.removeCollisionObject(&slab);
	caliber::setContactCacheDistance(previousDistance);
}
BENCHMARK(BM_RestingBoxesDetection)->Arg(0)->Arg(1)->ArgName("cache_mm");
}  // namespace
