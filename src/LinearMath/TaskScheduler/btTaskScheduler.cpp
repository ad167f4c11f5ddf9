// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCreateDefaultTaskScheduler's scheduler: a persistent pool of std::threads. A loop is posted as one
// job; the calling thread and the workers take its chunks from a shared counter until none is left.
// Idle workers spin briefly (loops in a step follow each other closely) and then sleep on a condition
// variable. Which thread runs a chunk varies from run to run; what a chunk is does not
// (btParallelChunks.h), and sums are added in chunk order. The posting thread waits only for the workers
// that joined the job, not for every helper it was posted to: a worker that wakes after the chunks are
// all taken finds the job closed and leaves it alone, so a helper descheduled by a busy machine (or
// still asleep) costs a loop nothing.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btWarningHook.h"

#if defined(__SSE2__) || defined(__x86_64__)
#include <emmintrin.h>
#define CALIBER_CPU_PAUSE() _mm_pause()
#else
#define CALIBER_CPU_PAUSE() ((void)0)
#endif

#if defined(BT_THREADSAFE) && BT_THREADSAFE
namespace
{
// About 50-100 microseconds of pauses: longer than the gap between two loops of one step.
const int kSpinsBeforeSleep = 2000;
// Then, when every thread of the pool can have a core of its own, a worker keeps polling (yielding the
// core to anyone who wants it) for up to 2 ms before it sleeps: a step's serial stretches (the tree
// updates, island building, the solver's set-up) often last longer than the pauses, and a worker woken
// from sleep comes too late for the next loop, which the posting thread then runs alone. The Mt world
// hints at the end of its step (sleepWorkerThreadsHint), and the workers go to sleep at once.
const std::chrono::microseconds kAwakeAfterLoop(2000);

class ThreadPoolScheduler : public btITaskScheduler
{
public:
	ThreadPoolScheduler() : btITaskScheduler("ThreadPool")
	{
		const unsigned hardware = std::thread::hardware_concurrency();
		m_hardwareThreads = hardware == 0 ? 1 : int(hardware);
		setNumThreads(m_hardwareThreads);
	}

	~ThreadPoolScheduler() override
	{
		caliber::forgetTaskScheduler(this);
		{
			std::lock_guard<std::mutex> lock(m_sleepMutex);
			m_quit.store(true, std::memory_order_release);
		}
		m_wake.notify_all();
		for (std::thread& worker : m_workers) worker.join();
	}

	int getMaxNumThreads() const override { return int(BT_MAX_THREAD_COUNT); }
	int getNumThreads() const override { return m_numThreads.load(std::memory_order_relaxed); }

	void setNumThreads(int numThreads) override
	{
		if (caliber::insideParallelBody())
		{
			btReportWarning("btITaskScheduler::setNumThreads: called inside a parallel loop; ignored");
			return;
		}
		const int wanted = numThreads < 1 ? 1 : (numThreads > getMaxNumThreads() ? getMaxNumThreads() : numThreads);
		// Not while a loop of another thread runs: the workers' count is part of the posted job.
		std::lock_guard<std::mutex> dispatch(m_dispatchMutex);
		// Workers are made when first needed and kept; surplus ones sleep.
		while (int(m_workers.size()) < wanted - 1)
		{
			try
			{
				// The worker starts from the present post (none can be made while the dispatch lock is held):
				// read later, in the new thread, it could already be the next job's, which it would then miss.
				const int slot = int(m_workers.size());
				const unsigned long long seen = m_posted.load(std::memory_order_relaxed);
				m_workers.emplace_back([this, slot, seen] { workerMain(slot, seen); });
			}
			catch (const std::system_error&)
			{
				btReportWarning("btITaskScheduler::setNumThreads: the system refused a new thread; running with fewer");
				break;
			}
		}
		m_numThreads.store(int(m_workers.size()) + 1 < wanted ? int(m_workers.size()) + 1 : wanted,
		                   std::memory_order_relaxed);
	}

	void parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body) override
	{
		const caliber::ChunkPlan plan = caliber::ChunkPlan::of(iBegin, iEnd, grainSize);
		if (!takeDispatch(plan))
		{
			caliber::runChunksSerially(plan, body);
			return;
		}
		m_forBody = &body;
		m_sumBody = 0;
		run(plan);
		m_dispatchMutex.unlock();
	}

	btScalar parallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body) override
	{
		const caliber::ChunkPlan plan = caliber::ChunkPlan::of(iBegin, iEnd, grainSize);
		if (!takeDispatch(plan)) return caliber::sumChunksSerially(plan, body);
		m_forBody = 0;
		m_sumBody = &body;
		m_partials.resize(plan.count);  // grows to the largest loop seen, then stays
		run(plan);
		btScalar sum = btScalar(0);
		for (int k = 0; k < plan.count; ++k) sum += m_partials[k];
		m_dispatchMutex.unlock();
		return sum;
	}

	void sleepWorkerThreadsHint() override { m_sleepHint.store(true, std::memory_order_relaxed); }

	// caliber::wakeWorkerThreadsHint: sleeping workers go back to waiting awake (pauses, then polls), as
	// after a loop. Only when polling workers cannot take the cores from the posting thread.
	void wakeWorkers()
	{
		if (getNumThreads() <= 1 || getNumThreads() > m_hardwareThreads) return;
		m_sleepHint.store(false, std::memory_order_relaxed);
		if (m_sleepers.load(std::memory_order_acquire) == 0) return;  // nobody to wake: no lock, no system call
		{
			std::lock_guard<std::mutex> lock(m_sleepMutex);
			m_wakes.fetch_add(1, std::memory_order_relaxed);
		}
		m_wake.notify_all();
	}

private:
	// True when this call may post a job (the dispatch lock is then held). A loop with one chunk or one
	// thread, a nested loop, or a loop while another thread's loop runs goes serially instead.
	bool takeDispatch(const caliber::ChunkPlan& plan)
	{
		if (plan.count <= 1 || getNumThreads() <= 1 || caliber::insideParallelBody()) return false;
		return m_dispatchMutex.try_lock();
	}

	// Posts the job, takes part in it, and returns when every chunk is done.
	void run(const caliber::ChunkPlan& plan)
	{
		m_plan = plan;
		const int helpers = (getNumThreads() - 1 < plan.count - 1) ? getNumThreads() - 1 : plan.count - 1;
		// Each taker owns a contiguous block of the chunks and takes from it first, then from the others'
		// (see runChunks). Blocks depend only on the chunk and taker counts, so a per-body loop gives
		// each thread the same bodies from stage to stage: they stay in its core's cache.
		m_takers = helpers + 1;
		for (int t = 0; t < m_takers; ++t)
		{
			m_blocks[t].next.store(int((long long)plan.count * t / m_takers), std::memory_order_relaxed);
			m_blocks[t].end = int((long long)plan.count * (t + 1) / m_takers);
		}
		m_sleepHint.store(false, std::memory_order_relaxed);
		caliber::beginThreadsRunning();
		// Generation and helper count in one word: a worker decides from one load whether the job is its.
		m_post = ((m_post >> 8) + 1) << 8 | (unsigned long long)helpers;
		m_openJob.store(m_post);
		{
			std::lock_guard<std::mutex> lock(m_sleepMutex);
			m_posted.store(m_post, std::memory_order_release);
		}
		m_wake.notify_all();
		{
			caliber::ParallelBodyScope scope;
			runChunks(0);
		}
		// Every chunk is taken. Closed, the job takes no more workers; those inside finish their chunks.
		// (Sequentially consistent, with the workers' join: either a worker sees the job closed, or this
		// thread sees it inside.)
		m_openJob.store(0);
		for (int spin = 0; m_joinedWorkers.load() != 0; ++spin)
		{
			if (spin < kSpinsBeforeSleep)
				CALIBER_CPU_PAUSE();
			else
				std::this_thread::yield();
		}
		caliber::endThreadsRunning();
	}

	// Taker `taker` runs its own block's chunks, then helps with the others' in turn.
	void runChunks(int taker)
	{
		for (int i = 0; i < m_takers; ++i)
		{
			ChunkBlock& block = m_blocks[(taker + i) % m_takers];
			for (;;)
			{
				// A cheap look first: an exhausted block costs no atomic write on its line.
				if (block.next.load(std::memory_order_relaxed) >= block.end) break;
				const int k = block.next.fetch_add(1, std::memory_order_relaxed);
				if (k >= block.end) break;
				int chunkBegin, chunkEnd;
				m_plan.range(k, chunkBegin, chunkEnd);
				if (m_forBody)
					m_forBody->forLoop(chunkBegin, chunkEnd);
				else
					m_partials[k] = m_sumBody->sumLoop(chunkBegin, chunkEnd);
			}
		}
	}

	// Waits for a post newer than seen (or for the end); returns it.
	unsigned long long waitForPost(unsigned long long seen)
	{
		for (;;)
		{
			unsigned long long posted;
			if (waitAwhileForPost(seen, posted)) return posted;
		}
	}

	// One round of waiting: pauses, polls, then sleep. True with the post (or at the end); false when a
	// wake hint ended the sleep, and the caller waits awake again.
	bool waitAwhileForPost(unsigned long long seen, unsigned long long& result)
	{
		for (int spin = 0; spin < kSpinsBeforeSleep; ++spin)
		{
			const unsigned long long posted = m_posted.load(std::memory_order_acquire);
			if (posted != seen || m_quit.load(std::memory_order_acquire))
			{
				result = posted;
				return true;
			}
			if (m_sleepHint.load(std::memory_order_relaxed)) break;
			CALIBER_CPU_PAUSE();
		}
		if (getNumThreads() <= m_hardwareThreads)
		{
			const auto deadline = std::chrono::steady_clock::now() + kAwakeAfterLoop;
			while (!m_sleepHint.load(std::memory_order_relaxed) && std::chrono::steady_clock::now() < deadline)
			{
				const unsigned long long posted = m_posted.load(std::memory_order_acquire);
				if (posted != seen || m_quit.load(std::memory_order_acquire))
				{
					result = posted;
					return true;
				}
				std::this_thread::yield();
			}
		}
		std::unique_lock<std::mutex> lock(m_sleepMutex);
		const unsigned wakes = m_wakes.load(std::memory_order_relaxed);
		m_sleepers.fetch_add(1, std::memory_order_release);
		m_wake.wait(lock, [&] {
			return m_posted.load(std::memory_order_acquire) != seen || m_quit.load(std::memory_order_acquire) ||
			       m_wakes.load(std::memory_order_relaxed) != wakes;
		});
		m_sleepers.fetch_sub(1, std::memory_order_relaxed);
		result = m_posted.load(std::memory_order_acquire);
		return result != seen || m_quit.load(std::memory_order_acquire);
	}

	void workerMain(int slot, unsigned long long seen)
	{
		btGetCurrentThreadIndex();  // takes this worker's index now, not inside the first loop
		for (;;)
		{
			seen = waitForPost(seen);
			if (m_quit.load(std::memory_order_acquire)) return;
			// Not a helper of this job: it must not touch the job.
			if (slot >= int(seen & 0xff)) continue;
			// Joins only while the job is open (see run): once closed, its chunks are all taken and the
			// posting thread may be writing the next job.
			m_joinedWorkers.fetch_add(1);
			if (m_openJob.load() == seen)
			{
				caliber::ParallelBodyScope scope;
				runChunks(slot + 1);
			}
			m_joinedWorkers.fetch_sub(1, std::memory_order_release);
		}
	}

	std::vector<std::thread> m_workers;
	std::atomic<int> m_numThreads{1};
	int m_hardwareThreads = 1;
	// The job, written by the posting thread before it publishes m_posted.
	caliber::ChunkPlan m_plan = caliber::ChunkPlan::of(0, 0, 1);
	const btIParallelForBody* m_forBody = 0;
	const btIParallelSumBody* m_sumBody = 0;
	btAlignedObjectArray<btScalar> m_partials;
	unsigned long long m_post = 0;  // the posting thread's copy of m_posted
	// Each on a cache line of its own: the threads take chunks from the blocks' cursors while idle workers
	// spin on m_posted, and sharing a line would make each take a cache miss for the other.
	struct alignas(64) ChunkBlock
	{
		std::atomic<int> next{0};
		int end = 0;
	};
	ChunkBlock m_blocks[BT_MAX_THREAD_COUNT];
	int m_takers = 1;
	alignas(64) std::atomic<int> m_joinedWorkers{0};  // workers inside a job's chunks
	std::atomic<unsigned long long> m_openJob{0};      // the post of the job taking workers; 0: none
	alignas(64) std::atomic<unsigned long long> m_posted{0};
	alignas(64) std::atomic<bool> m_sleepHint{false};
	std::atomic<bool> m_quit{false};
	std::atomic<int> m_sleepers{0};    // workers asleep on m_wake (changed under m_sleepMutex)
	std::atomic<unsigned> m_wakes{0};  // wake hints given (changed under m_sleepMutex)
	std::mutex m_sleepMutex;
	std::condition_variable m_wake;
	std::mutex m_dispatchMutex;  // one loop at a time; held from post to completion
};
}  // namespace

btITaskScheduler* caliber::createThreadPoolScheduler() { return new ThreadPoolScheduler(); }

void caliber::wakeWorkerThreadsHint(btITaskScheduler* scheduler)
{
	if (ThreadPoolScheduler* pool = dynamic_cast<ThreadPoolScheduler*>(scheduler)) pool->wakeWorkers();
}
#else
// A library built without CALIBER_THREADSAFE has no thread pool, as Bullet without BT_THREADSAFE.
btITaskScheduler* caliber::createThreadPoolScheduler() { return 0; }
void caliber::wakeWorkerThreadsHint(btITaskScheduler*) {}
#endif
