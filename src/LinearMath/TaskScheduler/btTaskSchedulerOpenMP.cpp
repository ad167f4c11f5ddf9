// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGetOpenMPTaskScheduler's scheduler (built with CALIBER_OPENMP): the chunks of a loop shared out by an
// OpenMP loop. Chunks and the order of a sum's partials are those of every scheduler (btParallelChunks.h).
#include "LinearMath/TaskScheduler/btParallelChunks.h"

#ifdef CALIBER_HAVE_OPENMP
#include <omp.h>

#include <mutex>

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btWarningHook.h"

namespace
{
class OpenMPScheduler : public btITaskScheduler
{
public:
	OpenMPScheduler() : btITaskScheduler("OpenMP"), m_numThreads(1) { setNumThreads(omp_get_max_threads()); }

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
#pragma omp parallel for schedule(dynamic, 1) num_threads(m_numThreads)
		for (int k = 0; k < plan.count; ++k)
		{
			caliber::ParallelBodyScope scope;
			int chunkBegin, chunkEnd;
			plan.range(k, chunkBegin, chunkEnd);
			body.forLoop(chunkBegin, chunkEnd);
		}
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
#pragma omp parallel for schedule(dynamic, 1) num_threads(m_numThreads)
		for (int k = 0; k < plan.count; ++k)
		{
			caliber::ParallelBodyScope scope;
			int chunkBegin, chunkEnd;
			plan.range(k, chunkBegin, chunkEnd);
			partials[k] = body.sumLoop(chunkBegin, chunkEnd);
		}
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
	btAlignedObjectArray<btScalar> m_partials;
	std::mutex m_dispatchMutex;
};
}  // namespace

btITaskScheduler* caliber::openMPScheduler()
{
	static OpenMPScheduler* scheduler = new OpenMPScheduler();  // owned by the library, never destroyed
	return scheduler;
}
#else
btITaskScheduler* caliber::openMPScheduler() { return 0; }
#endif
