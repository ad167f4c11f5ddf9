// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/TaskScheduler/btChunkedScheduler.h"

#include "LinearMath/btWarningHook.h"

namespace caliber
{
void ChunkedScheduler::setNumThreads(int numThreads)
{
	if (insideParallelBody())
	{
		btReportWarning("btITaskScheduler::setNumThreads: called inside a parallel loop; ignored");
		return;
	}
	std::lock_guard<std::mutex> dispatch(m_dispatchMutex);
	m_numThreads = numThreads < 1 ? 1 : (numThreads > getMaxNumThreads() ? getMaxNumThreads() : numThreads);
	threadCountChanged();
}

bool ChunkedScheduler::takeDispatch(const ChunkPlan& plan)
{
	if (plan.count <= 1 || insideParallelBody() || !m_dispatchMutex.try_lock()) return false;
	if (m_numThreads > 1) return true;
	m_dispatchMutex.unlock();
	return false;
}

void ChunkedScheduler::parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body)
{
	const ChunkPlan plan = ChunkPlan::of(iBegin, iEnd, grainSize);
	if (!takeDispatch(plan))
	{
		runChunksSerially(plan, body);
		return;
	}
	struct ForChunk : ChunkTask
	{
		const ChunkPlan& plan;
		const btIParallelForBody& body;
		ForChunk(const ChunkPlan& p, const btIParallelForBody& b) : plan(p), body(b) {}
		void run(int chunk) const override
		{
			int chunkBegin, chunkEnd;
			plan.range(chunk, chunkBegin, chunkEnd);
			body.forLoop(chunkBegin, chunkEnd);
		}
	};
	beginThreadsRunning();
	runChunks(plan.count, ForChunk(plan, body));
	endThreadsRunning();
	m_dispatchMutex.unlock();
}

btScalar ChunkedScheduler::parallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body)
{
	const ChunkPlan plan = ChunkPlan::of(iBegin, iEnd, grainSize);
	if (!takeDispatch(plan)) return sumChunksSerially(plan, body);
	m_partials.resize(plan.count);
	struct SumChunk : ChunkTask
	{
		const ChunkPlan& plan;
		const btIParallelSumBody& body;
		btScalar* partials;
		SumChunk(const ChunkPlan& p, const btIParallelSumBody& b, btScalar* s) : plan(p), body(b), partials(s) {}
		void run(int chunk) const override
		{
			int chunkBegin, chunkEnd;
			plan.range(chunk, chunkBegin, chunkEnd);
			partials[chunk] = body.sumLoop(chunkBegin, chunkEnd);
		}
	};
	beginThreadsRunning();
	runChunks(plan.count, SumChunk(plan, body, &m_partials[0]));
	endThreadsRunning();
	// In chunk order, whatever thread ran which chunk: the same bits at every thread count.
	btScalar sum = btScalar(0);
	for (int k = 0; k < plan.count; ++k) sum += m_partials[k];
	m_dispatchMutex.unlock();
	return sum;
}
}  // namespace caliber
