// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// ThreadsBench: Google Benchmark over the default task scheduler (btCreateDefaultTaskScheduler), the
// costs that decide how well a step's stages scale: a loop's round trip with nothing to do, and
// per-body loops of the sizes a step has (3000 items, 64 per chunk, from a few to a hundred
// microseconds of work), run as a step runs them, three stages in a row over the same data. Compare the
// items per second of threads:1 and threads:2 for the scaling on this machine.

#include "LinearMath/btThreads.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

namespace
{
btITaskScheduler* poolWith(int threads)
{
	static btITaskScheduler* pool = btCreateDefaultTaskScheduler();
	if (!pool) return 0;
	btSetTaskScheduler(pool);
	pool->setNumThreads(threads);
	return pool;
}

// Each item: `work` dependent square roots on its own value (compute, not memory, bound).
struct ItemWork : public btIParallelForBody
{
	float* items;
	int work;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			float x = items[i];
			for (int k = 0; k < work; ++k) x = std::sqrt(x + 1.0f);
			items[i] = x;
		}
	}
};

struct NoWork : public btIParallelForBody
{
	void forLoop(int, int) const override {}
};

// A loop of two chunks that do nothing: what posting, taking part and joining cost.
void BM_EmptyLoop(benchmark::State& state)
{
	if (!poolWith(int(state.range(0))))
	{
		state.SkipWithError("library built without CALIBER_THREADSAFE: no thread pool");
		return;
	}
	NoWork body;
	for (auto _ : state) btParallelFor(0, 2, 1, body);
	state.SetItemsProcessed(state.iterations());
	btSetTaskScheduler(btGetSequentialTaskScheduler());
}

// Three per-body stages in a row over 3000 items in chunks of 64 (the world's per-body loops).
void BM_PerBodyStages(benchmark::State& state)
{
	if (!poolWith(int(state.range(0))))
	{
		state.SkipWithError("library built without CALIBER_THREADSAFE: no thread pool");
		return;
	}
	const int kItems = 3000;
	std::vector<float> items(kItems, 1.0f);
	ItemWork body;
	body.items = items.data();
	body.work = int(state.range(1));
	for (auto _ : state)
		for (int stage = 0; stage < 3; ++stage) btParallelFor(0, kItems, 64, body);
	benchmark::DoNotOptimize(items.data());
	state.SetItemsProcessed(state.iterations() * 3 * kItems);
	btSetTaskScheduler(btGetSequentialTaskScheduler());
}
}  // namespace

BENCHMARK(BM_EmptyLoop)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(BM_PerBodyStages)
    ->ArgNames({"threads", "work"})
    ->ArgsProduct({{1, 2}, {4, 20, 100}})
    ->UseRealTime();

BENCHMARK_MAIN();
