// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_PARALLEL_CHUNKS_H
#define CALIBER_PARALLEL_CHUNKS_H

// What every scheduler shares: the split of a loop into chunks, which depends only on the range and
// the grain size (never on the thread count), and the serial way of running them. A sum adds the
// chunks' partial sums in chunk order, so every scheduler at every thread count gives the same bits.

#include "LinearMath/btThreads.h"

namespace caliber
{
/// The chunks [begin + k grain, min(end, begin + (k + 1) grain)) for k in [0, count).
struct ChunkPlan
{
	int begin;
	int end;
	int grain;
	int count;

	/// An empty or reversed range has no chunks; a grain below 1 counts as 1.
	static ChunkPlan of(int iBegin, int iEnd, int grainSize)
	{
		ChunkPlan plan;
		plan.begin = iBegin;
		plan.end = iEnd;
		plan.grain = grainSize < 1 ? 1 : grainSize;
		const long long length = iEnd > iBegin ? (long long)iEnd - (long long)iBegin : 0;
		plan.count = int((length + plan.grain - 1) / plan.grain);
		return plan;
	}

	/// The bounds of chunk k (computed in 64 bits: begin + k grain may pass INT_MAX before clamping).
	void range(int k, int& chunkBegin, int& chunkEnd) const
	{
		const long long first = (long long)begin + (long long)k * grain;
		const long long last = first + grain;
		chunkBegin = int(first);
		chunkEnd = last < end ? int(last) : end;
	}
};

/// True while this thread runs the body of a parallel loop (a nested loop then runs serially).
bool insideParallelBody();

/// Marks this thread as running a loop body for its lifetime.
class ParallelBodyScope
{
public:
	ParallelBodyScope();
	~ParallelBodyScope();
	ParallelBodyScope(const ParallelBodyScope&) = delete;
	ParallelBodyScope& operator=(const ParallelBodyScope&) = delete;
};

/// Runs every chunk of plan on this thread, in order.
void runChunksSerially(const ChunkPlan& plan, const btIParallelForBody& body);
/// Sums every chunk of plan on this thread, in chunk order.
btScalar sumChunksSerially(const ChunkPlan& plan, const btIParallelSumBody& body);

/// Counts the loops running on several threads (btThreadsAreRunning).
void beginThreadsRunning();
void endThreadsRunning();

/// Called by a scheduler's destructor: if it is the current scheduler, the sequential one replaces it
/// (with a warning), so that nothing calls a deleted scheduler.
void forgetTaskScheduler(btITaskScheduler* scheduler);

/// Wakes the sleeping workers of a thread pool made by btCreateDefaultTaskScheduler without posting a
/// loop, so that they are polling when the next loop comes (a world calls it at the start of its step,
/// before the serial stretch that precedes its first parallel loop: a worker woken by that loop's post
/// comes too late for a short loop). Does nothing for other schedulers, for one thread, and when the
/// pool has more threads than the machine has processors (its workers then sleep between loops).
void wakeWorkerThreadsHint(btITaskScheduler* scheduler);

// The backends (btTaskScheduler.cpp, btTaskSchedulerOpenMP.cpp, btTaskSchedulerTBB.cpp); 0 when not built.
btITaskScheduler* createThreadPoolScheduler();
btITaskScheduler* openMPScheduler();
btITaskScheduler* tbbScheduler();
}  // namespace caliber

#endif  // CALIBER_PARALLEL_CHUNKS_H
