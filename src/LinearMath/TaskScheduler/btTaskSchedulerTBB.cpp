// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGetTBBTaskScheduler's scheduler (built with CALIBER_TBB, Debian libtbb-dev): the chunks of a loop
// shared out by tbb::parallel_for inside a task arena of the chosen thread count. Chunks and the order
// of a sum's partials are those of every scheduler (btParallelChunks.h).
#include "LinearMath/TaskScheduler/btParallelChunks.h"

#ifdef CALIBER_HAVE_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <memory>
#include <mutex>

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btWarningHook.h"

namespace
{
class TBBScheduler : public btITaskScheduler
{
public:
	TBBScheduler() : btITaskScheduler("TBB"), m_numThreads(1)
	{
		setNumThreads(tbb::this_task_arena::max_concurrency());
	}

	int getMaxNumThreads() const override { return int(BT_MAX_THREAD_COUNT); }
	int getNumThreads() const override { return m_numThreads; }
	void setNumThreads(int numThreads) override
	{
		if (caliber::insideParallelBody())
		{
			btReportWarning("btITaskScheduler::setNumThreads: called inside a parallel loop; ignored");
			return;
		}
		std::lock_guard<std::mutex> dispatch(m_dispatchMutex);
		m_numThreads = numThreads < 1 ? 1 : (numThreads > getMaxNumThreads() ? getMaxNumThreads() : numThreads);
		m_arena.reset(new tbb::task_arena(m_numThreads));
	}

	void parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body) override
	{
		const caliber::ChunkPlan plan = caliber::ChunkPlan::of(iBegin, iEnd, grainSize);
		if (!takeDispatch(plan))
		{
			caliber::runChunksSerially(plan, body);
			return;
		}
		caliber::beginThreadsRunning();
		m_arena->execute([&] {
			tbb::parallel_for(tbb::blocked_range<int>(0, plan.count, 1), [&](const tbb::blocked_range<int>& r) {
				caliber::ParallelBodyScope scope;
				for (int k = r.begin(); k != r.end(); ++k)
				{
					int chunkBegin, chunkEnd;
					plan.range(k, chunkBegin, chunkEnd);
					body.forLoop(chunkBegin, chunkEnd);
				}
			});
		});
		caliber::endThreadsRunning();
		m_dispatchMutex.unlock();
	}

	btScalar parallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body) override
	{
		const caliber::ChunkPlan plan = caliber::ChunkPlan::of(iBegin, iEnd, grainSize);
		if (!takeDispatch(plan)) return caliber::sumChunksSerially(plan, body);
		m_partials.resize(plan.count);
		btScalar* partials = &m_partials[0];
		caliber::beginThreadsRunning();
		m_arena->execute([&] {
			tbb::parallel_for(tbb::blocked_range<int>(0, plan.count, 1), [&](const tbb::blocked_range<int>& r) {
				caliber::ParallelBodyScope scope;
				for (int k = r.begin(); k != r.end(); ++k)
				{
					int chunkBegin, chunkEnd;
					plan.range(k, chunkBegin, chunkEnd);
					partials[k] = body.sumLoop(chunkBegin, chunkEnd);
				}
			});
		});
		caliber::endThreadsRunning();
		btScalar sum = btScalar(0);
		for (int k = 0; k < plan.count; ++k) sum += partials[k];
		m_dispatchMutex.unlock();
		return sum;
	}

private:
	// As the thread pool: one loop at a time; nested, single-chunk or concurrent loops run serially.
	bool takeDispatch(const caliber::ChunkPlan& plan)
	{
		if (plan.count <= 1 || caliber::insideParallelBody() || !m_dispatchMutex.try_lock()) return false;
		if (m_numThreads > 1) return true;
		m_dispatchMutex.unlock();
		return false;
	}

	int m_numThreads;
	std::unique_ptr<tbb::task_arena> m_arena;
	btAlignedObjectArray<btScalar> m_partials;
	std::mutex m_dispatchMutex;
};
}  // namespace

btITaskScheduler* caliber::tbbScheduler()
{
	static TBBScheduler* scheduler = new TBBScheduler();  // owned by the library, never destroyed
	return scheduler;
}
#else
btITaskScheduler* caliber::tbbScheduler() { return 0; }
#endif
