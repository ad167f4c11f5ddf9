// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The task-scheduler API of LinearMath/btThreads.h: every scheduler that this build has, at several
// thread counts, must run each index of a loop exactly once, give sums with the same bits, keep thread
// indices unique, run nested loops serially, clamp thread counts, and survive misuse.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <map>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "LinearMath/TaskScheduler/btThreadSupportInterface.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btWarningHook.h"

namespace
{
const int kThreadCounts[] = {1, 2, 3, 4, 8};

// Counts warnings from any thread while it lives.
class WarningCount
{
public:
	WarningCount() { btSetWarningHook(&WarningCount::hook, this); }
	~WarningCount() { btSetWarningHook(0, 0); }
	int count() const { return m_count.load(); }

private:
	static void hook(const char*, void* self) { ++static_cast<WarningCount*>(self)->m_count; }
	std::atomic<int> m_count{0};
};

// The schedulers of this build: the sequential one, a new thread pool (when thread-safe), OpenMP and
// TBB (when built).
struct Schedulers
{
	std::unique_ptr<btITaskScheduler> pool{btCreateDefaultTaskScheduler()};
	std::vector<btITaskScheduler*> all;

	Schedulers()
	{
		all.push_back(btGetSequentialTaskScheduler());
		if (pool) all.push_back(pool.get());
		if (btGetOpenMPTaskScheduler()) all.push_back(btGetOpenMPTaskScheduler());
		if (btGetTBBTaskScheduler()) all.push_back(btGetTBBTaskScheduler());
	}
};

struct CountVisits : public btIParallelForBody
{
	std::vector<std::atomic<int>>* visits;
	int offset;
	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) ++(*visits)[i - offset];
	}
};

struct HarmonicSum : public btIParallelSumBody
{
	btScalar sumLoop(int iBegin, int iEnd) const override
	{
		btScalar sum = 0;
		for (int i = iBegin; i < iEnd; ++i) sum += btScalar(1) / btScalar(i + 1);
		return sum;
	}
};

struct IndexSum : public btIParallelSumBody
{
	btScalar sumLoop(int iBegin, int iEnd) const override
	{
		btScalar sum = 0;
		for (int i = iBegin; i < iEnd; ++i) sum += btScalar(i);
		return sum;
	}
};
}  // namespace

TEST(Threads, BuildIsThreadSafeAsDeclared)
{
	// BT_THREADSAFE reaches users exactly when the library has its thread pool.
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
	ASSERT_NE(pool.get(), nullptr);
	EXPECT_STREQ(pool->getName(), "ThreadPool");
	EXPECT_GE(pool->getNumThreads(), 1);
#else
	EXPECT_EQ(btCreateDefaultTaskScheduler(), nullptr);
#endif
	EXPECT_EQ(btGetPPLTaskScheduler(), nullptr);
	EXPECT_STREQ(btGetSequentialTaskScheduler()->getName(), "Sequential");
	EXPECT_EQ(btGetTaskScheduler(), btGetSequentialTaskScheduler());  // the default, never null
}

TEST(Threads, ParallelForCoversEachIndexExactlyOnce)
{
	Schedulers schedulers;
	// (begin, end, grain): empty and reversed ranges, grains below 1, of 1, larger than the range,
	// dividing it and not, negative starts.
	const int cases[][3] = {{0, 0, 1},    {5, 5, 3},     {10, 3, 2},  {-7, -20, 1}, {0, 1, 1},   {0, 1000, 1},
	                        {0, 1000, 7}, {3, 1003, 64}, {0, 17, 0},  {0, 17, -5},  {-50, 50, 9}, {0, 5, 1000},
	                        {0, 4096, 64}, {1, 2, 100}};
	for (btITaskScheduler* scheduler : schedulers.all)
		for (int threads : kThreadCounts)
		{
			scheduler->setNumThreads(threads);
			for (const auto& c : cases)
			{
				const int begin = c[0], end = c[1], grain = c[2];
				const int lo = std::min(begin, end) - 3, hi = std::max(begin, end) + 3;
				std::vector<std::atomic<int>> visits(hi - lo);
				CountVisits body;
				body.visits = &visits;
				body.offset = lo;
				scheduler->parallelFor(begin, end, grain, body);
				for (int i = lo; i < hi; ++i)
				{
					const int expected = (i >= begin && i < end) ? 1 : 0;
					ASSERT_EQ(visits[i - lo].load(), expected)
					    << scheduler->getName() << " threads " << threads << " range [" << begin << ", " << end
					    << ") grain " << grain << " index " << i;
				}
			}
		}
}

TEST(Threads, ParallelSumHasTheSameBitsForEverySchedulerAndThreadCount)
{
	// Sums of integers below 2^24 are exact in float; the harmonic sum is not, so equal bits there show
	// that every scheduler adds the same chunk partials in the same order.
	Schedulers schedulers;
	const btScalar reference = btGetSequentialTaskScheduler()->parallelSum(0, 10000, 37, HarmonicSum());
	for (btITaskScheduler* scheduler : schedulers.all)
		for (int threads : kThreadCounts)
		{
			scheduler->setNumThreads(threads);
			EXPECT_EQ(scheduler->parallelSum(0, 4000, 13, IndexSum()), btScalar(4000.0 * 3999.0 / 2.0))
			    << scheduler->getName() << " " << threads;
			EXPECT_EQ(scheduler->parallelSum(0, 10000, 37, HarmonicSum()), reference)
			    << scheduler->getName() << " " << threads;
			EXPECT_EQ(scheduler->parallelSum(9, 3, 4, IndexSum()), btScalar(0));  // reversed: empty
			EXPECT_EQ(scheduler->parallelSum(0, 10, 0, IndexSum()), btScalar(45));  // grain 0 counts as 1
		}
}

namespace
{
struct RecordThreadIndex : public btIParallelForBody
{
	std::mutex* mutex;
	std::map<unsigned, std::thread::id>* threadOfIndex;
	std::atomic<int>* conflicts;
	std::atomic<int>* outOfRange;
	void forLoop(int, int) const override
	{
		const unsigned index = btGetCurrentThreadIndex();
		if (index >= BT_MAX_THREAD_COUNT) ++*outOfRange;
		std::lock_guard<std::mutex> lock(*mutex);
		auto inserted = threadOfIndex->insert(std::make_pair(index, std::this_thread::get_id()));
		if (!inserted.second && inserted.first->second != std::this_thread::get_id()) ++*conflicts;
		for (const auto& entry : *threadOfIndex)
			if (entry.first != index && entry.second == std::this_thread::get_id()) ++*conflicts;
	}
};
}  // namespace

TEST(Threads, ThreadIndexIsUniqueAndBelowTheMaximumInsideLoops)
{
	EXPECT_EQ(btGetCurrentThreadIndex(), 0u);
	EXPECT_TRUE(btIsMainThread());
	Schedulers schedulers;
	for (btITaskScheduler* scheduler : schedulers.all)
		for (int threads : kThreadCounts)
		{
			scheduler->setNumThreads(threads);
			std::mutex mutex;
			std::map<unsigned, std::thread::id> threadOfIndex;
			std::atomic<int> conflicts(0), outOfRange(0);
			RecordThreadIndex body;
			body.mutex = &mutex;
			body.threadOfIndex = &threadOfIndex;
			body.conflicts = &conflicts;
			body.outOfRange = &outOfRange;
			scheduler->parallelFor(0, 2000, 1, body);
			EXPECT_EQ(conflicts.load(), 0) << scheduler->getName() << " " << threads;
			EXPECT_EQ(outOfRange.load(), 0);
			EXPECT_LE(int(threadOfIndex.size()), scheduler->getNumThreads());
		}
	// A thread of the program's own gets an index other than the main thread's.
	unsigned otherIndex = 0;
	bool otherIsMain = true;
	std::thread other([&] {
		otherIndex = btGetCurrentThreadIndex();
		otherIsMain = btIsMainThread();
	});
	other.join();
	EXPECT_NE(otherIndex, 0u);
	EXPECT_LT(otherIndex, BT_MAX_THREAD_COUNT);
	EXPECT_FALSE(otherIsMain);
}

namespace
{
struct LockedIncrement : public btIParallelForBody
{
	btSpinMutex* mutex;
	long long* counter;
	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			btMutexLock(mutex);
			const long long read = *counter;
			*counter = read + 1;  // a lost update would show without the lock
			btMutexUnlock(mutex);
		}
	}
};
}  // namespace

TEST(Threads, SpinMutexProtectsACounterUnderContention)
{
	btSpinMutex mutex;
	long long counter = 0;
	{
		std::vector<std::thread> threads;
		for (int t = 0; t < 4; ++t)
			threads.emplace_back([&] {
				for (int i = 0; i < 20000; ++i)
				{
					mutex.lock();
					++counter;
					mutex.unlock();
				}
			});
		for (std::thread& thread : threads) thread.join();
	}
	EXPECT_EQ(counter, 80000);
	EXPECT_TRUE(mutex.tryLock());
	EXPECT_FALSE(mutex.tryLock());
	mutex.unlock();

	Schedulers schedulers;
	for (btITaskScheduler* scheduler : schedulers.all)
	{
		scheduler->setNumThreads(4);
		counter = 0;
		LockedIncrement body;
		body.mutex = &mutex;
		body.counter = &counter;
		scheduler->parallelFor(0, 50000, 16, body);
		EXPECT_EQ(counter, 50000) << scheduler->getName();
	}
}

TEST(Threads, SetNumThreadsClampsToOneAndTheMaximum)
{
	Schedulers schedulers;
	for (btITaskScheduler* scheduler : schedulers.all)
	{
		scheduler->setNumThreads(0);
		EXPECT_EQ(scheduler->getNumThreads(), 1) << scheduler->getName();
		scheduler->setNumThreads(-3);
		EXPECT_EQ(scheduler->getNumThreads(), 1) << scheduler->getName();
		scheduler->setNumThreads(100000);
		EXPECT_EQ(scheduler->getNumThreads(), scheduler->getMaxNumThreads()) << scheduler->getName();
		EXPECT_LE(scheduler->getMaxNumThreads(), int(BT_MAX_THREAD_COUNT));
		scheduler->setNumThreads(2);
		EXPECT_EQ(scheduler->getNumThreads(), std::min(2, scheduler->getMaxNumThreads()));
	}
}

namespace
{
struct NestedLoops : public btIParallelForBody
{
	btITaskScheduler* scheduler;
	std::vector<std::atomic<int>>* visits;
	std::atomic<int>* foreignThreads;
	struct Inner : public btIParallelForBody
	{
		std::thread::id outerThread;
		std::vector<std::atomic<int>>* visits;
		std::atomic<int>* foreignThreads;
		int row;
		void forLoop(int iBegin, int iEnd) const override
		{
			if (std::this_thread::get_id() != outerThread) ++*foreignThreads;
			for (int i = iBegin; i < iEnd; ++i) ++(*visits)[row * 100 + i];
		}
	};
	void forLoop(int iBegin, int iEnd) const override
	{
		for (int row = iBegin; row < iEnd; ++row)
		{
			Inner inner;
			inner.outerThread = std::this_thread::get_id();
			inner.visits = visits;
			inner.foreignThreads = foreignThreads;
			inner.row = row;
			scheduler->parallelFor(0, 100, 3, inner);
		}
	}
};
}  // namespace

TEST(Threads, NestedLoopRunsSeriallyInTheCallingThread)
{
	Schedulers schedulers;
	for (btITaskScheduler* scheduler : schedulers.all)
		for (int threads : {2, 4})
		{
			scheduler->setNumThreads(threads);
			std::vector<std::atomic<int>> visits(16 * 100);
			std::atomic<int> foreignThreads(0);
			NestedLoops outer;
			outer.scheduler = scheduler;
			outer.visits = &visits;
			outer.foreignThreads = &foreignThreads;
			scheduler->parallelFor(0, 16, 1, outer);
			EXPECT_EQ(foreignThreads.load(), 0) << scheduler->getName();
			for (int i = 0; i < 1600; ++i) ASSERT_EQ(visits[i].load(), 1) << scheduler->getName() << " " << i;
		}
}

TEST(Threads, SetTaskSchedulerSwitchesAndNullRestoresTheSequentialOne)
{
	Schedulers schedulers;
	for (btITaskScheduler* scheduler : schedulers.all)
	{
		btSetTaskScheduler(scheduler);
		EXPECT_EQ(btGetTaskScheduler(), scheduler);
		EXPECT_EQ(btParallelSum(0, 100, 7, IndexSum()), btScalar(4950));
	}
	btSetTaskScheduler(0);
	EXPECT_EQ(btGetTaskScheduler(), btGetSequentialTaskScheduler());
}

namespace
{
struct SetSchedulerInside : public btIParallelForBody
{
	btITaskScheduler* other;
	void forLoop(int, int) const override
	{
		btSetTaskScheduler(other);
		other->setNumThreads(3);
	}
};
}  // namespace

TEST(Threads, MisuseIsReportedAndIgnored)
{
	Schedulers schedulers;
	if (!schedulers.pool) GTEST_SKIP() << "no thread pool in a library built without CALIBER_THREADSAFE";
	WarningCount warnings;

	// btSetTaskScheduler from another thread: ignored with a warning.
	std::thread other([&] { btSetTaskScheduler(schedulers.pool.get()); });
	other.join();
	EXPECT_EQ(btGetTaskScheduler(), btGetSequentialTaskScheduler());
	EXPECT_EQ(warnings.count(), 1);

	// From inside a loop body: ignored with a warning, as is setNumThreads there.
	schedulers.pool->setNumThreads(2);
	SetSchedulerInside body;
	body.other = schedulers.pool.get();
	btGetSequentialTaskScheduler()->parallelFor(0, 1, 1, body);
	EXPECT_EQ(btGetTaskScheduler(), btGetSequentialTaskScheduler());
	EXPECT_EQ(schedulers.pool->getNumThreads(), 2);
	EXPECT_EQ(warnings.count(), 3);

	// Deleting the current scheduler: the sequential one takes over, with a warning.
	btITaskScheduler* doomed = btCreateDefaultTaskScheduler();
	btSetTaskScheduler(doomed);
	delete doomed;
	EXPECT_EQ(btGetTaskScheduler(), btGetSequentialTaskScheduler());
	EXPECT_EQ(warnings.count(), 4);
	EXPECT_EQ(btParallelSum(0, 10, 1, IndexSum()), btScalar(45));
}

TEST(Threads, WakeHintBetweenSleepHintsAndLoopsKeepsEveryLoopExact)
{
	// caliber::wakeWorkerThreadsHint (which a world gives at the start of its step) wakes the pool's
	// sleeping workers without a loop. Here it comes while the workers are asleep, while they fall
	// asleep, twice in a row and right before a loop or the pool's end, at thread counts below, at and
	// above the machine's: every loop still visits each index once and sums exactly (a woken worker that
	// took the wake for a post would run a stale job, or miss the next one and hang the caller), and
	// ThreadSanitizer checks the hand-over in CI's tsan stage. Other schedulers ignore it.
	Schedulers schedulers;
	const int kCount = 1000;
	for (btITaskScheduler* scheduler : schedulers.all)
		for (int threads : kThreadCounts)
		{
			scheduler->setNumThreads(threads);
			for (int round = 0; round < 12; ++round)
			{
				scheduler->sleepWorkerThreadsHint();
				// Long enough, every few rounds, for the workers' pauses and polls to end and them to sleep.
				if (round % 4 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(4));
				caliber::wakeWorkerThreadsHint(scheduler);
				if (round % 3 == 0) caliber::wakeWorkerThreadsHint(scheduler);
				if (round % 2 == 0) std::this_thread::sleep_for(std::chrono::microseconds(200));
				std::vector<std::atomic<int>> visits(kCount);
				CountVisits body;
				body.visits = &visits;
				body.offset = 0;
				scheduler->parallelFor(0, kCount, 7, body);
				for (int i = 0; i < kCount; ++i)
					ASSERT_EQ(visits[i].load(), 1) << scheduler->getName() << " threads " << threads << " index " << i;
				ASSERT_EQ(scheduler->parallelSum(0, kCount, 13, IndexSum()), btScalar(kCount * (kCount - 1) / 2))
				    << scheduler->getName() << " threads " << threads;
			}
		}
	caliber::wakeWorkerThreadsHint(btGetSequentialTaskScheduler());
	caliber::wakeWorkerThreadsHint(0);
	if (!schedulers.pool) return;
	// A pool deleted right after a hint, its workers asleep or not, ends (its destructor joins them).
	for (int round = 0; round < 4; ++round)
	{
		std::unique_ptr<btITaskScheduler> pool(btCreateDefaultTaskScheduler());
		pool->setNumThreads(2);
		EXPECT_EQ(pool->parallelSum(0, 100, 1, IndexSum()), btScalar(4950));
		pool->sleepWorkerThreadsHint();
		if (round % 2) std::this_thread::sleep_for(std::chrono::milliseconds(4));
		caliber::wakeWorkerThreadsHint(pool.get());
	}
}

TEST(Threads, BackToBackTinyLoopsWithLateWorkersRunEachIndexOnce)
{
	// A loop of two or three chunks is often all taken by the calling thread before a worker arrives; the
	// pool then closes the job without waiting for that worker, which must find the job closed and leave
	// it alone: not run a chunk of it again, nor read the next job while the calling thread writes it.
	// Thousands of such loops back to back, some right after a sleep hint (the workers then wake late)
	// and at more threads than processors (the workers then sleep after their pauses), each with a body
	// of its own, must each visit every index once; CI's tsan stage checks the hand-over.
	Schedulers schedulers;
	if (!schedulers.pool) return;
	btITaskScheduler* pool = schedulers.pool.get();
	for (int threads : {2, 3, 8})
	{
		pool->setNumThreads(threads);
		for (int loop = 0; loop < 3000; ++loop)
		{
			if (loop % 97 == 0) pool->sleepWorkerThreadsHint();
			const int count = 2 + loop % 3;
			std::vector<std::atomic<int>> visits(count);
			CountVisits body;
			body.visits = &visits;
			body.offset = 0;
			pool->parallelFor(0, count, 1, body);
			for (int i = 0; i < count; ++i) ASSERT_EQ(visits[i].load(), 1) << threads << " threads, loop " << loop;
			if (loop % 5 == 0)
			{
				ASSERT_EQ(pool->parallelSum(0, count, 1, IndexSum()), btScalar(count * (count - 1) / 2))
				    << threads << " threads, loop " << loop;
			}
		}
	}
}

TEST(Threads, LoopsFromTwoThreadsOnOneSchedulerBothComplete)
{
	// Bullet's schedulers take one caller at a time; here the second caller runs its loop serially.
	Schedulers schedulers;
	for (btITaskScheduler* scheduler : schedulers.all)
	{
		scheduler->setNumThreads(3);
		std::atomic<int> wrong(0);
		auto work = [&] {
			for (int repeat = 0; repeat < 50; ++repeat)
				if (scheduler->parallelSum(0, 3000, 11, IndexSum()) != btScalar(3000.0 * 2999.0 / 2.0)) ++wrong;
		};
		std::thread a(work), b(work);
		a.join();
		b.join();
		EXPECT_EQ(wrong.load(), 0) << scheduler->getName();
	}
}

namespace
{
std::atomic<int> gTasksRun(0);
void countTask(void* userData) { gTasksRun += *static_cast<int*>(userData); }
}  // namespace

TEST(Threads, ThreadSupportRunsTasksOnEachWorker)
{
	btThreadSupportInterface::ConstructionInfo info("ThreadsTest", countTask);
	std::unique_ptr<btThreadSupportInterface> support(btThreadSupportInterface::create(info));
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	ASSERT_NE(support.get(), nullptr);
	const int workers = support->getNumWorkerThreads();
	ASSERT_GE(workers, 1);
	EXPECT_GE(support->getCacheFriendlyNumThreads(), 1);
	int two = 2;
	gTasksRun = 0;
	for (int round = 0; round < 10; ++round)
		for (int i = 0; i < workers; ++i) support->runTask(i, &two);  // waits for the worker's last task
	support->waitForAllTasks();
	EXPECT_EQ(gTasksRun.load(), 10 * workers * 2);

	WarningCount warnings;
	support->runTask(workers, &two);  // no such worker
	support->runTask(-1, &two);
	support->waitForAllTasks();
	EXPECT_EQ(warnings.count(), 2);
	EXPECT_EQ(gTasksRun.load(), 10 * workers * 2);

	btCriticalSection* section = support->createCriticalSection();
	section->lock();
	section->unlock();
	support->deleteCriticalSection(section);

	btThreadSupportInterface::ConstructionInfo noFunction("ThreadsTest", 0);
	EXPECT_EQ(btThreadSupportInterface::create(noFunction), nullptr);
	EXPECT_EQ(warnings.count(), 3);
#else
	EXPECT_EQ(support.get(), nullptr);
#endif
}

TEST(Threads, MoreLiveThreadsThanIndicesShareTheLastIndex)
{
	// 70 threads alive at once: at most 63 distinct indices besides the main thread's; the rest share
	// index 63, with one warning (only the first time in a process).
	WarningCount warnings;
	const int kThreads = 70;
	std::vector<unsigned> indices(kThreads, 0);
	std::mutex mutex;
	std::condition_variable allTaken;
	int taken = 0;
	std::vector<std::thread> threads;
	for (int t = 0; t < kThreads; ++t)
		threads.emplace_back([&, t] {
			indices[t] = btGetCurrentThreadIndex();
			std::unique_lock<std::mutex> lock(mutex);
			if (++taken == kThreads) allTaken.notify_all();
			allTaken.wait(lock, [&] { return taken == kThreads; });  // keep the index until all have one
		});
	for (std::thread& thread : threads) thread.join();
	int atLast = 0;
	for (unsigned index : indices)
	{
		EXPECT_GE(index, 1u);
		EXPECT_LT(index, BT_MAX_THREAD_COUNT);
		atLast += index == BT_MAX_THREAD_COUNT - 1 ? 1 : 0;
	}
	EXPECT_GE(atLast, kThreads - int(BT_MAX_THREAD_COUNT - 2));
	EXPECT_LE(warnings.count(), 1);
	// The indices were given back: a new thread gets a low one again.
	unsigned later = 0;
	std::thread([&] { later = btGetCurrentThreadIndex(); }).join();
	EXPECT_LT(later, BT_MAX_THREAD_COUNT - 1);
}

namespace
{
// Spins for about `micros` microseconds (sleeping would let the scheduler hand the core away, and the
// test wants two threads busy at once).
void busyFor(int micros)
{
	const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(micros);
	while (std::chrono::steady_clock::now() < until)
	{
	}
}

// Counts each index and records which thread ran it; chunks whose first index is a multiple of
// `slowEvery` (or below `slowBelow`) spin for `micros` so that the other takers run out of work and steal.
struct UnevenChunks : public btIParallelForBody
{
	std::vector<std::atomic<int>>* visits;
	std::vector<std::thread::id>* runBy;
	int offset;
	int slowEvery;
	int slowBelow;
	int micros;
	void forLoop(int iBegin, int iEnd) const override
	{
		const bool slow = (slowEvery > 0 && (iBegin - offset) % slowEvery == 0) || iBegin - offset < slowBelow;
		if (slow) busyFor(micros);
		for (int i = iBegin; i < iEnd; ++i)
		{
			++(*visits)[i - offset];
			(*runBy)[i - offset] = std::this_thread::get_id();
		}
	}
};
}  // namespace

TEST(Threads, ContendedChunksWithUnevenWorkRunExactlyOnce)
{
	// Chunks of very different lengths make the takers finish their own blocks at different times and take
	// from the others' blocks: with 1 to 4 threads, no
	// chunks, one, a few and many, and ranges and grains that make no sense, every index runs once and a
	// sum of integers (exact in float below 2^24) comes out exact. CI's tsan stage checks the claims.
	Schedulers schedulers;
	if (!schedulers.pool) return;
	btITaskScheduler* pool = schedulers.pool.get();
	const int cases[][3] = {{0, 0, 1},   {0, 1, 1},    {0, 2, 1},    {0, 3, 1},    {0, 5, 1},
	                        {0, 64, 1},  {0, 1000, 1}, {0, 1000, 3}, {7, 2, 1},    {0, 17, 0},
	                        {0, 17, -4}, {-30, 90, 7}, {0, 9, 1000}, {0, 4099, 64}};
	for (int threads = 1; threads <= 4; ++threads)
	{
		pool->setNumThreads(threads);
		for (const auto& c : cases)
			for (int slowEvery : {0, 3, 5})
			{
				const int begin = c[0], end = c[1], grain = c[2];
				const int lo = std::min(begin, end), hi = std::max(begin, end);
				std::vector<std::atomic<int>> visits(hi - lo + 1);
				std::vector<std::thread::id> runBy(hi - lo + 1);
				UnevenChunks body;
				body.visits = &visits;
				body.runBy = &runBy;
				body.offset = lo;
				body.slowEvery = slowEvery;
				body.slowBelow = slowEvery == 0 ? (hi - lo) / 3 : 0;
				body.micros = 20;
				pool->parallelFor(begin, end, grain, body);
				for (int i = lo; i <= hi; ++i)
					ASSERT_EQ(visits[i - lo].load(), (i >= begin && i < end) ? 1 : 0)
					    << threads << " threads, range [" << begin << ", " << end << ") grain " << grain
					    << " slowEvery " << slowEvery << " index " << i;
			}
		for (int count : {0, 1, 2, 1000, 4000})
		{
			const btScalar expected = btScalar(double(count) * (count - 1) / 2);
			ASSERT_EQ(pool->parallelSum(0, count, 1, IndexSum()), count > 0 ? expected : btScalar(0))
			    << threads << " threads, " << count << " chunks";
		}
	}
}
