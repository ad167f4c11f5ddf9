// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btBvhTriangleMeshShape on a 100 x 100 height-field grid (20,000 triangles): building the tree
// (quantized and not), box queries of about a character's size, and ray casts from above. Sanity figures:
// node count, triangles per query and ray hits per cast, so that speed is never bought with a broken tree.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "BulletCollision/BroadphaseCollision/QuantizedBvhAccess.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"

namespace
{
const int kGridSize = 100;  // quads per side: 2 * 100 * 100 = 20,000 triangles

struct Grid
{
	std::vector<btScalar> vertices;
	std::vector<int> indices;
	btTriangleIndexVertexArray mesh;

	Grid()
	{
		for (int j = 0; j <= kGridSize; ++j)
			for (int i = 0; i <= kGridSize; ++i)
			{
				vertices.push_back(btScalar(i));
				vertices.push_back(btScalar(j));
				vertices.push_back(btScalar(2 * std::sin(0.1 * i) * std::cos(0.13 * j)));
			}
		for (int j = 0; j < kGridSize; ++j)
			for (int i = 0; i < kGridSize; ++i)
			{
				const int v00 = j * (kGridSize + 1) + i, v10 = v00 + 1, v01 = v00 + kGridSize + 1, v11 = v01 + 1;
				const int quad[6] = {v00, v10, v11, v00, v11, v01};
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
	}
};

Grid& grid()
{
	static Grid g;
	return g;
}

struct CountingCallback : btTriangleCallback
{
	long long triangles = 0;
	void processTriangle(btVector3*, int, int) override { ++triangles; }
};

void BM_BvhBuild(benchmark::State& state)
{
	const bool quantized = state.range(0) != 0;
	int nodes = 0;
	for (auto _ : state)
	{
		btBvhTriangleMeshShape shape(&grid().mesh, quantized);
		nodes = caliber::bvhNodeCount(*shape.getOptimizedBvh());
		benchmark::DoNotOptimize(nodes);
	}
	state.SetItemsProcessed(state.iterations() * 2 * kGridSize * kGridSize);
	state.counters["nodes"] = nodes;
	state.SetLabel(quantized ? "quantized, triangles/s" : "unquantized, triangles/s");
}

void BM_BvhAabbQuery(benchmark::State& state)
{
	const bool quantized = state.range(0) != 0;
	btBvhTriangleMeshShape shape(&grid().mesh, quantized);
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> pos(0, kGridSize);
	std::vector<btVector3> centres(1024);
	for (btVector3& c : centres) c = btVector3(btScalar(pos(rng)), btScalar(pos(rng)), 0);
	const btVector3 half(1, 1, 2);  // about a character's size: a handful of triangles
	CountingCallback counter;
	size_t q = 0;
	for (auto _ : state)
	{
		const btVector3& c = centres[q++ & 1023];
		shape.processAllTriangles(&counter, c - half, c + half);
	}
	state.SetItemsProcessed(state.iterations());
	state.counters["triangles/query"] = double(counter.triangles) / double(state.iterations());
	state.SetLabel(quantized ? "quantized, queries/s" : "unquantized, queries/s");
}

void BM_BvhRaycast(benchmark::State& state)
{
	const bool quantized = state.range(0) != 0;
	btBvhTriangleMeshShape shape(&grid().mesh, quantized);
	std::mt19937 rng(9);
	std::uniform_real_distribution<double> pos(0, kGridSize);
	std::vector<std::pair<btVector3, btVector3>> rays(1024);
	for (auto& r : rays)
	{
		// Slanted rays from above the terrain to below it, about 10 units long horizontally.
		const btVector3 from(btScalar(pos(rng)), btScalar(pos(rng)), 5);
		r = std::make_pair(from, from + btVector3(btScalar(pos(rng) / 10 - 5), btScalar(pos(rng) / 10 - 5), -10));
	}
	CountingCallback counter;
	size_t q = 0;
	for (auto _ : state)
	{
		const auto& r = rays[q++ & 1023];
		shape.performRaycast(&counter, r.first, r.second);
	}
	state.SetItemsProcessed(state.iterations());
	state.counters["candidates/ray"] = double(counter.triangles) / double(state.iterations());
	state.SetLabel(quantized ? "quantized, rays/s" : "unquantized, rays/s");
}
}  // namespace

BENCHMARK(BM_BvhBuild)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhAabbQuery)->Arg(0)->Arg(1);
BENCHMARK(BM_BvhRaycast)->Arg(0)->Arg(1);
