// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDbvt: building a tree of 10k leaves, moving them every frame (broadphase-style fat updates), the
// self-overlap pairs (collideTT), box queries (collideTV) and ray casts. Sanity figures: tree depth,
// pairs per frame, hits per query, so that speed is never bought with a broken tree.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"

namespace
{
const int kLeafCount = 10000;
// Boxes of half size 0.5..1.5 in a cube of side 100: a few overlaps per box, like a busy scene.
const btScalar kWorldHalfSize = 50;

struct Body
{
	btVector3 centre;
	btVector3 half;
	btVector3 velocity;
	btDbvtNode* leaf;
};

std::vector<Body> makeBodies(unsigned seed)
{
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> pos(-kWorldHalfSize, kWorldHalfSize), size(0.5, 1.5), vel(-1, 1);
	std::vector<Body> bodies(kLeafCount);
	for (Body& b : bodies)
	{
		b.centre = btVector3(btScalar(pos(rng)), btScalar(pos(rng)), btScalar(pos(rng)));
		b.half = btVector3(btScalar(size(rng)), btScalar(size(rng)), btScalar(size(rng)));
		b.velocity = btVector3(btScalar(vel(rng)), btScalar(vel(rng)), btScalar(vel(rng)));
		b.leaf = 0;
	}
	return bodies;
}

void fill(btDbvt& tree, std::vector<Body>& bodies)
{
	for (size_t i = 0; i < bodies.size(); ++i)
		bodies[i].leaf = tree.insert(btDbvtVolume::FromCE(bodies[i].centre, bodies[i].half), &bodies[i]);
}

struct PairCounter : btDbvt::ICollide
{
	using btDbvt::ICollide::Process;
	long long pairs = 0;
	void Process(const btDbvtNode*, const btDbvtNode*) override { ++pairs; }
};

struct LeafCounter : btDbvt::ICollide
{
	using btDbvt::ICollide::Process;
	long long leaves = 0;
	void Process(const btDbvtNode*) override { ++leaves; }
};

void BM_DbvtInsert10k(benchmark::State& state)
{
	std::vector<Body> bodies = makeBodies(1);
	int depth = 0;
	for (auto _ : state)
	{
		btDbvt tree;
		fill(tree, bodies);
		depth = btDbvt::maxdepth(tree.m_root);
		benchmark::DoNotOptimize(tree.m_root);
	}
	state.SetItemsProcessed(state.iterations() * kLeafCount);
	state.counters["depth"] = depth;
}
BENCHMARK(BM_DbvtInsert10k)->Unit(benchmark::kMillisecond);

// Every body moves by velocity * dt each frame; the leaf is re-inserted only when the motion leaves its
// fat box (margin 0.2 plus the displacement on the side of motion), as the dbvt broadphase does.
void BM_DbvtUpdateRandomMotion(benchmark::State& state)
{
	std::vector<Body> bodies = makeBodies(2);
	btDbvt tree;
	fill(tree, bodies);
	const btScalar dt = btScalar(1) / 60;
	long long moved = 0, frames = 0;
	for (auto _ : state)
	{
		for (Body& b : bodies)
		{
			b.centre += b.velocity * dt;
			for (int a = 0; a < 3; ++a)
				if (btFabs(b.centre[a]) > kWorldHalfSize) b.velocity[a] = -b.velocity[a];
			btDbvtVolume box = btDbvtVolume::FromCE(b.centre, b.half);
			moved += tree.update(b.leaf, box, b.velocity * (dt * 4), btScalar(0.2)) ? 1 : 0;
		}
		++frames;
	}
	state.SetItemsProcessed(state.iterations() * kLeafCount);
	state.counters["reinserted_per_frame"] = frames ? double(moved) / double(frames) : 0;
	state.counters["depth"] = btDbvt::maxdepth(tree.m_root);
}
BENCHMARK(BM_DbvtUpdateRandomMotion)->Unit(benchmark::kMillisecond);

void BM_DbvtCollideTTSelf(benchmark::State& state)
{
	std::vector<Body> bodies = makeBodies(3);
	btDbvt tree;
	fill(tree, bodies);
	PairCounter counter;
	for (auto _ : state)
	{
		counter.pairs = 0;
		tree.collideTT(tree.m_root, tree.m_root, counter);
	}
	state.SetItemsProcessed(state.iterations() * kLeafCount);
	state.counters["pairs"] = double(counter.pairs);
}
BENCHMARK(BM_DbvtCollideTTSelf)->Unit(benchmark::kMillisecond);

void BM_DbvtCollideTV(benchmark::State& state)
{
	std::vector<Body> bodies = makeBodies(4);
	btDbvt tree;
	fill(tree, bodies);
	std::mt19937 rng(5);
	std::uniform_real_distribution<double> pos(-kWorldHalfSize, kWorldHalfSize);
	std::vector<btDbvtVolume> queries;
	for (int i = 0; i < 1024; ++i)
		queries.push_back(
		    btDbvtVolume::FromCR(btVector3(btScalar(pos(rng)), btScalar(pos(rng)), btScalar(pos(rng))), 2));
	LeafCounter counter;
	size_t next = 0;
	for (auto _ : state)
	{
		tree.collideTV(tree.m_root, queries[next], counter);
		next = (next + 1) % queries.size();
	}
	state.SetItemsProcessed(state.iterations());
	state.counters["hits_per_query"] = state.iterations() ? double(counter.leaves) / double(state.iterations()) : 0;
}
BENCHMARK(BM_DbvtCollideTV);

void BM_DbvtRayTest(benchmark::State& state)
{
	std::vector<Body> bodies = makeBodies(6);
	btDbvt tree;
	fill(tree, bodies);
	std::mt19937 rng(7);
	std::uniform_real_distribution<double> pos(-kWorldHalfSize, kWorldHalfSize);
	std::vector<btVector3> ends;
	for (int i = 0; i < 2048; ++i)
		ends.push_back(btVector3(btScalar(pos(rng)), btScalar(pos(rng)), btScalar(pos(rng))));
	LeafCounter counter;
	size_t next = 0;
	for (auto _ : state)
	{
		btDbvt::rayTest(tree.m_root, ends[next], ends[next + 1], counter);
		next = (next + 2) % ends.size();
	}
	state.SetItemsProcessed(state.iterations());
	state.counters["hits_per_ray"] = state.iterations() ? double(counter.leaves) / double(state.iterations()) : 0;
}
BENCHMARK(BM_DbvtRayTest);
}  // namespace
