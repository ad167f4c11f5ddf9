// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Ray tests against a 100,352-triangle btBvhTriangleMeshShape (a 224 x 224 bumpy grid): 100,000 rays per
// iteration through btCollisionWorld::rayTest (world with btDbvtBroadphase, btCollisionDispatcher), and the
// same rays straight through btBvhTriangleMeshShape::performRaycast, so the world's overhead is visible.
// Also rays against 1,000 spheres and boxes in a world (closed-form convex tests). Sanity figure: hitRate
// (fraction of rays that hit), the same for both mesh paths.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"

namespace
{
const int kGridQuads = 224;  // 2 * 224 * 224 = 100,352 triangles
const int kRays = 100000;
const btScalar kSpacing = btScalar(1);

struct MeshScene
{
	std::vector<btScalar> vertices;
	std::vector<int> indices;
	btTriangleIndexVertexArray mesh;
	btBvhTriangleMeshShape* shape;
	std::vector<btVector3> from, to;

	MeshScene()
	{
		for (int j = 0; j <= kGridQuads; ++j)
			for (int i = 0; i <= kGridQuads; ++i)
			{
				vertices.push_back(btScalar(i) * kSpacing);
				vertices.push_back(btScalar(3 * std::sin(0.07 * i) * std::cos(0.05 * j)));
				vertices.push_back(btScalar(j) * kSpacing);
			}
		for (int j = 0; j < kGridQuads; ++j)
			for (int i = 0; i < kGridQuads; ++i)
			{
				const int v00 = j * (kGridQuads + 1) + i, v10 = v00 + 1, v01 = v00 + kGridQuads + 1, v11 = v01 + 1;
				const int quad[6] = {v00, v01, v10, v10, v01, v11};
				indices.insert(indices.end(), quad, quad + 6);
			}
		btIndexedMesh part;
		part.m_numTriangles = int(indices.size() / 3);
		part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(indices.data());
		part.m_triangleIndexStride = 3 * int(sizeof(int));
		part.m_numVertices = int(vertices.size() / 3);
		part.m_vertexBase = reinterpret_cast<const unsigned char*>(vertices.data());
		part.m_vertexStride = 3 * int(sizeof(btScalar));
		mesh.addIndexedMesh(part, PHY_INTEGER);
		shape = new btBvhTriangleMeshShape(&mesh, true);

		// Rays from above at random slants, 20 units long: most hit, some pass off the edge.
		std::mt19937 rng(1234);
		std::uniform_real_distribution<double> across(-10, kGridQuads * kSpacing + 10), slant(-6, 6);
		for (int r = 0; r < kRays; ++r)
		{
			const btVector3 start(btScalar(across(rng)), btScalar(10), btScalar(across(rng)));
			from.push_back(start);
			to.push_back(start + btVector3(btScalar(slant(rng)), btScalar(-20), btScalar(slant(rng))));
		}
	}
	~MeshScene() { delete shape; }
};

MeshScene& meshScene()
{
	static MeshScene scene;
	return scene;
}

struct World
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher;
	btDbvtBroadphase broadphase;
	btCollisionWorld world;
	World() : dispatcher(&config), world(&dispatcher, &broadphase, &config) {}
};

// The world's closest-hit callback for one object: keeps the closest hit, counts nothing else.
struct ClosestTriangle : btTriangleRaycastCallback
{
	ClosestTriangle(const btVector3& from, const btVector3& to) : btTriangleRaycastCallback(from, to) {}
	btScalar reportHit(const btVector3&, btScalar hitFraction, int, int) override { return hitFraction; }
};

void BM_RayWorldBvhMesh(benchmark::State& state)
{
	MeshScene& scene = meshScene();
	World w;
	btCollisionObject ground;
	ground.setCollisionShape(scene.shape);
	w.world.addCollisionObject(&ground);
	long long hits = 0, rays = 0;
	for (auto _ : state)
	{
		for (int r = 0; r < kRays; ++r)
		{
			btCollisionWorld::ClosestRayResultCallback cb(scene.from[r], scene.to[r]);
			w.world.rayTest(scene.from[r], scene.to[r], cb);
			hits += cb.hasHit() ? 1 : 0;
		}
		rays += kRays;
	}
	w.world.removeCollisionObject(&ground);
	state.SetItemsProcessed(rays);
	state.counters["hitRate"] = rays ? double(hits) / double(rays) : 0;
	state.SetLabel("btCollisionWorld::rayTest, 100,352 triangles, rays/s");
}
BENCHMARK(BM_RayWorldBvhMesh)->Unit(benchmark::kMillisecond);

void BM_RayDirectBvhMesh(benchmark::State& state)
{
	MeshScene& scene = meshScene();
	long long hits = 0, rays = 0;
	for (auto _ : state)
	{
		for (int r = 0; r < kRays; ++r)
		{
			ClosestTriangle cb(scene.from[r], scene.to[r]);
			scene.shape->performRaycast(&cb, scene.from[r], scene.to[r]);
			hits += cb.m_hitFraction < btScalar(1) ? 1 : 0;
		}
		rays += kRays;
	}
	state.SetItemsProcessed(rays);
	state.counters["hitRate"] = rays ? double(hits) / double(rays) : 0;
	state.SetLabel("btBvhTriangleMeshShape::performRaycast, 100,352 triangles, rays/s");
}
BENCHMARK(BM_RayDirectBvhMesh)->Unit(benchmark::kMillisecond);

// 1,000 spheres and boxes scattered in a 60-unit cube; rays across it (broadphase plus closed-form tests).
void BM_RayWorldConvexObjects(benchmark::State& state)
{
	World w;
	btSphereShape sphere(btScalar(0.8));
	btBoxShape box(btVector3(0.6, 0.6, 0.6));
	std::vector<btCollisionObject> objects(1000);
	std::mt19937 rng(99);
	std::uniform_real_distribution<double> inside(-30, 30);
	for (size_t i = 0; i < objects.size(); ++i)
	{
		objects[i].setCollisionShape(i % 2 ? static_cast<btCollisionShape*>(&sphere) : &box);
		objects[i].setWorldTransform(
		    btTransform(btQuaternion(btVector3(0, 1, 0), btScalar(0.1 * i)),
		                btVector3(btScalar(inside(rng)), btScalar(inside(rng)), btScalar(inside(rng)))));
		w.world.addCollisionObject(&objects[i]);
	}
	const int rayCount = 10000;
	std::vector<btVector3> from, to;
	for (int r = 0; r < rayCount; ++r)
	{
		from.push_back(btVector3(btScalar(inside(rng)), btScalar(inside(rng)), btScalar(-40)));
		to.push_back(btVector3(btScalar(inside(rng)), btScalar(inside(rng)), btScalar(40)));
	}
	long long hits = 0, rays = 0;
	for (auto _ : state)
	{
		for (int r = 0; r < rayCount; ++r)
		{
			btCollisionWorld::ClosestRayResultCallback cb(from[r], to[r]);
			w.world.rayTest(from[r], to[r], cb);
			hits += cb.hasHit() ? 1 : 0;
		}
		rays += rayCount;
	}
	for (size_t i = 0; i < objects.size(); ++i) w.world.removeCollisionObject(&objects[i]);
	state.SetItemsProcessed(rays);
	state.counters["hitRate"] = rays ? double(hits) / double(rays) : 0;
	state.SetLabel("1,000 spheres and boxes, btDbvtBroadphase, rays/s");
}
BENCHMARK(BM_RayWorldConvexObjects)->Unit(benchmark::kMillisecond);
}  // namespace
