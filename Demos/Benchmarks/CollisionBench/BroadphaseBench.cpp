// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Broadphases: every object moves every frame (setAabb for all, then calculateOverlappingPairs).
// Each broadphase runs 1,000 and 10,000 objects. Items = objects updated per second. Sanity figures:
// pairs in the cache after the last frame, and for the dbvt the fraction of setAabb calls that had to
// move a tree box.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btAxisSweep3.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btSimpleBroadphase.h"

namespace
{
struct MovingBox
{
	btVector3 centre;
	btVector3 half;
	btVector3 velocity;
	btBroadphaseProxy* proxy;
};

// Boxes of half size 0.5..1.5 at 10,000 per 100^3 (a few neighbours each, like a busy scene), moving at
// up to 3 units per second in 60 Hz frames and bouncing off the walls.
std::vector<MovingBox> makeBoxes(int count, unsigned seed)
{
	const double halfSize = 50.0 * std::cbrt(double(count) / 10000.0);
	std::mt19937 rng(seed);
	std::uniform_real_distribution<double> pos(-halfSize, halfSize), size(0.5, 1.5), vel(-3, 3);
	std::vector<MovingBox> boxes(static_cast<size_t>(count));
	for (MovingBox& b : boxes)
	{
		b.centre = btVector3(btScalar(pos(rng)), btScalar(pos(rng)), btScalar(pos(rng)));
		b.half = btVector3(btScalar(size(rng)), btScalar(size(rng)), btScalar(size(rng)));
		b.velocity = btVector3(btScalar(vel(rng)), btScalar(vel(rng)), btScalar(vel(rng)));
		b.proxy = 0;
	}
	return boxes;
}

void addAll(btBroadphaseInterface& broadphase, std::vector<MovingBox>& boxes)
{
	for (size_t i = 0; i < boxes.size(); ++i)
	{
		MovingBox& b = boxes[i];
		b.proxy = broadphase.createProxy(b.centre - b.half, b.centre + b.half, BOX_SHAPE_PROXYTYPE, &b,
		                                 btBroadphaseProxy::DefaultFilter, btBroadphaseProxy::AllFilter, 0);
	}
	broadphase.calculateOverlappingPairs(0);
}

void stepAll(btBroadphaseInterface& broadphase, std::vector<MovingBox>& boxes, btScalar worldHalfSize)
{
	const btScalar dt = btScalar(1) / 60;
	for (MovingBox& b : boxes)
	{
		b.centre += b.velocity * dt;
		for (int a = 0; a < 3; ++a)
			if (btFabs(b.centre[a]) > worldHalfSize) b.velocity[a] = -b.velocity[a];
		broadphase.setAabb(b.proxy, b.centre - b.half, b.centre + b.half, 0);
	}
	broadphase.calculateOverlappingPairs(0);
}

btScalar worldHalfSizeFor(int count) { return btScalar(50.0 * std::cbrt(double(count) / 10000.0)); }

// btSimpleBroadphase: its all-pairs test is O(n^2), so 10,000 objects cost about 100 times 1,000;
// it runs both sizes so that every broadphase has a 10,000-object figure.
void BM_SimpleBroadphaseMove(benchmark::State& state)
{
	const int count = int(state.range(0));
	std::vector<MovingBox> boxes = makeBoxes(count, 1);
	btSimpleBroadphase broadphase(count);
	addAll(broadphase, boxes);
	for (auto _ : state) stepAll(broadphase, boxes, worldHalfSizeFor(count));
	state.SetItemsProcessed(state.iterations() * count);
	state.counters["pairs"] = broadphase.getOverlappingPairCache()->getNumOverlappingPairs();
}
BENCHMARK(BM_SimpleBroadphaseMove)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// btDbvtBroadphase with the argument's number of objects.
void BM_DbvtBroadphaseMove(benchmark::State& state)
{
	const int count = int(state.range(0));
	std::vector<MovingBox> boxes = makeBoxes(count, 2);
	btDbvtBroadphase broadphase;
	addAll(broadphase, boxes);
	double ratio = 0;
	long long frames = 0;
	for (auto _ : state)
	{
		stepAll(broadphase, boxes, worldHalfSizeFor(count));
		ratio += double(broadphase.m_updates_ratio);
		++frames;
	}
	state.SetItemsProcessed(state.iterations() * count);
	state.counters["pairs"] = broadphase.getOverlappingPairCache()->getNumOverlappingPairs();
	state.counters["tree_update_fraction"] = frames ? ratio / double(frames) : 0;
	state.counters["depth"] = btDbvt::maxdepth(broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET].m_root);
}
BENCHMARK(BM_DbvtBroadphaseMove)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// The same 10,000-object scene with 9,000 of them static (StaticFilter, never moved): the common case of
// a few movers in a large level.
void BM_DbvtBroadphaseMove1kAmong10kStatic(benchmark::State& state)
{
	const int count = 10000;
	const int moving = 1000;
	std::vector<MovingBox> boxes = makeBoxes(count, 3);
	btDbvtBroadphase broadphase;
	for (size_t i = 0; i < boxes.size(); ++i)
	{
		MovingBox& b = boxes[i];
		const bool isStatic = int(i) >= moving;
		b.proxy = broadphase.createProxy(
		    b.centre - b.half, b.centre + b.half, BOX_SHAPE_PROXYTYPE, &b,
		    isStatic ? int(btBroadphaseProxy::StaticFilter) : int(btBroadphaseProxy::DefaultFilter),
		    isStatic ? int(btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter)
		             : int(btBroadphaseProxy::AllFilter),
		    0);
	}
	broadphase.calculateOverlappingPairs(0);
	std::vector<MovingBox> movers(boxes.begin(), boxes.begin() + moving);
	for (auto _ : state) stepAll(broadphase, movers, worldHalfSizeFor(count));
	state.SetItemsProcessed(state.iterations() * moving);
	state.counters["pairs"] = broadphase.getOverlappingPairCache()->getNumOverlappingPairs();
}
BENCHMARK(BM_DbvtBroadphaseMove1kAmong10kStatic)->Unit(benchmark::kMillisecond);

// Sweep and prune, 16- and 32-bit, world bounds a little larger than the scene (boxes bounce inside it);
// the ray accelerator is off, as it only serves queries and would add a tree update per move.
template <typename Sweep, typename IntType>
void BM_AxisSweepMove(benchmark::State& state)
{
	const int count = int(state.range(0));
	std::vector<MovingBox> boxes = makeBoxes(count, 4);
	const btScalar half = worldHalfSizeFor(count) + btScalar(5);
	Sweep broadphase(btVector3(-half, -half, -half), btVector3(half, half, half), IntType(count + 1), 0, true);
	addAll(broadphase, boxes);
	for (auto _ : state) stepAll(broadphase, boxes, worldHalfSizeFor(count));
	state.SetItemsProcessed(state.iterations() * count);
	state.counters["pairs"] = broadphase.getOverlappingPairCache()->getNumOverlappingPairs();
}
BENCHMARK_TEMPLATE(BM_AxisSweepMove, btAxisSweep3, unsigned short)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_AxisSweepMove, bt32BitAxisSweep3, unsigned int)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
}  // namespace
