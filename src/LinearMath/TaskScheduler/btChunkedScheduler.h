// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CHUNKED_SCHEDULER_H
#define CALIBER_CHUNKED_SCHEDULER_H

// What the OpenMP and TBB schedulers share: the thread count, one loop at a time (nested, single-chunk or
// concurrent loops run serially on the calling thread) and sums added in chunk order. A backend only
// says how the chunks of a loop are shared out over its threads.

#include <mutex>

#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
class ChunkedScheduler : public btITaskScheduler
{
public:
	explicit ChunkedScheduler(const char* name) : btITaskScheduler(name) {}

	int getMaxNumThreads() const override { return int(BT_MAX_THREAD_COUNT); }
	int getNumThreads() const override { return m_numThreads; }
	/// Clamped to [1, getMaxNumThreads()]; ignored with a warning inside a loop body.
	void setNumThreads(int numThreads) override;
	void parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body) override;
	btScalar parallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body) override;

protected:
	/// One chunk's work, by chunk index.
	struct ChunkTask
	{
		virtual void run(int chunk) const = 0;

	protected:
		~ChunkTask() = default;
	};
	/// Calls task.run(k) once for every k in [0, count) on up to getNumThreads() threads, each call
	/// inside a ParallelBodyScope, and returns when all have run.
	virtual void runChunks(int count, const ChunkTask& task) = 0;
	/// Told the new thread count, under the dispatch lock (so never while a loop runs).
	virtual void threadCountChanged() {}

private:
	bool takeDispatch(const ChunkPlan& plan);

	int m_numThreads = 1;
	btAlignedObjectArray<btScalar> m_partials;
	std::mutex m_dispatchMutex;
};
}  // namespace caliber

#endif  // CALIBER_CHUNKED_SCHEDULER_H
