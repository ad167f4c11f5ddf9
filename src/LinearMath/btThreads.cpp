// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Thread indices, the spin mutex, the current scheduler and the sequential scheduler. The thread pool
// and the optional backends live in TaskScheduler/.
#include "LinearMath/btThreads.h"

#include <atomic>
#include <mutex>
#include <thread>

#include "LinearMath/TaskScheduler/btParallelChunks.h"
#include "LinearMath/btWarningHook.h"

#if defined(__SSE2__) || defined(__x86_64__)
#include <emmintrin.h>
#define CALIBER_CPU_PAUSE() _mm_pause()
#else
#define CALIBER_CPU_PAUSE() ((void)0)
#endif

namespace
{
// ---- thread indices -------------------------------------------------------------------------------
// The thread that runs static initialisation (the one that starts main) is the main thread, index 0.
// Other threads take the lowest free index on first use and give it back when they end, so indices stay
// unique among live threads and below BT_MAX_THREAD_COUNT however many threads come and go.
const std::thread::id gMainThread = std::this_thread::get_id();

struct IndexAllocator
{
	std::mutex mutex;
	unsigned long long used = 1;  // bit i: index i is taken; 0 belongs to the main thread
	bool warned = false;
};
static_assert(BT_MAX_THREAD_COUNT <= 64, "the index allocator keeps one bit per index in 64 bits");

IndexAllocator& indexAllocator()
{
	// Never destroyed: threads may end (and give their index back) during static destruction.
	static IndexAllocator* allocator = new IndexAllocator();
	return *allocator;
}

struct ThreadIndexSlot
{
	int index = -1;
	bool owned = false;  // false for the main thread and for threads sharing the last index
	~ThreadIndexSlot()
	{
		if (!owned) return;
		IndexAllocator& allocator = indexAllocator();
		std::lock_guard<std::mutex> lock(allocator.mutex);
		allocator.used &= ~(1ull << index);
	}
};
thread_local ThreadIndexSlot tThreadIndex;

int takeThreadIndex(bool& owned)
{
	owned = false;
	if (std::this_thread::get_id() == gMainThread) return 0;
	IndexAllocator& allocator = indexAllocator();
	std::lock_guard<std::mutex> lock(allocator.mutex);
	for (int i = 1; i < int(BT_MAX_THREAD_COUNT); ++i)
	{
		if (allocator.used & (1ull << i)) continue;
		allocator.used |= 1ull << i;
		owned = true;
		return i;
	}
	// More live threads asked for an index than BT_MAX_THREAD_COUNT: they share the last one.
	if (!allocator.warned)
	{
		allocator.warned = true;
		btReportWarning("btGetCurrentThreadIndex: more than BT_MAX_THREAD_COUNT live threads; the extra threads "
		                "share index BT_MAX_THREAD_COUNT - 1");
	}
	return int(BT_MAX_THREAD_COUNT) - 1;
}

// ---- nesting and running state ----------------------------------------------------------------------
thread_local int tParallelBodyDepth = 0;
std::atomic<int> gLoopsOnThreads(0);

// ---- the sequential scheduler ----------------------------------------------------------------------
class SequentialScheduler : public btITaskScheduler
{
public:
	SequentialScheduler() : btITaskScheduler("Sequential") {}
	int getMaxNumThreads() const override { return 1; }
	int getNumThreads() const override { return 1; }
	void setNumThreads(int) override {}
	void parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body) override
	{
		caliber::runChunksSerially(caliber::ChunkPlan::of(iBegin, iEnd, grainSize), body);
	}
	btScalar parallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body) override
	{
		return caliber::sumChunksSerially(caliber::ChunkPlan::of(iBegin, iEnd, grainSize), body);
	}
};

SequentialScheduler& sequentialScheduler()
{
	static SequentialScheduler* scheduler = new SequentialScheduler();  // never destroyed (see above)
	return *scheduler;
}

// The current scheduler; 0 stands for the sequential one, so no static initialisation order matters.
std::atomic<btITaskScheduler*> gCurrentScheduler(nullptr);
}  // namespace

bool btIsMainThread() { return btGetCurrentThreadIndex() == 0; }

bool btThreadsAreRunning() { return gLoopsOnThreads.load(std::memory_order_acquire) > 0; }

unsigned int btGetCurrentThreadIndex()
{
	if (tThreadIndex.index < 0) tThreadIndex.index = takeThreadIndex(tThreadIndex.owned);
	return unsigned(tThreadIndex.index);
}

void btResetThreadIndexCounter() {}

// ---- btSpinMutex -----------------------------------------------------------------------------------
// Acquire on taking and release on freeing order the critical section; the relaxed load while waiting
// keeps the cache line shared until the lock looks free.
void btSpinMutex::lock()
{
	for (int attempt = 0;; ++attempt)
	{
		if (__atomic_load_n(&mLock, __ATOMIC_RELAXED) == 0 && tryLock()) return;
		if (attempt < 64)
			CALIBER_CPU_PAUSE();
		else
			std::this_thread::yield();  // the holder may be descheduled: let it run
	}
}

void btSpinMutex::unlock() { __atomic_store_n(&mLock, 0, __ATOMIC_RELEASE); }

bool btSpinMutex::tryLock() { return __atomic_exchange_n(&mLock, 1, __ATOMIC_ACQUIRE) == 0; }

// ---- btITaskScheduler ------------------------------------------------------------------------------
btITaskScheduler::btITaskScheduler(const char* name) : m_name(name), m_savedThreadCounter(0), m_isActive(false) {}

void btITaskScheduler::activate() { m_isActive = true; }

void btITaskScheduler::deactivate() { m_isActive = false; }

void btSetTaskScheduler(btITaskScheduler* ts)
{
	if (!btIsMainThread() || caliber::insideParallelBody())
	{
		btReportWarning("btSetTaskScheduler: called on a worker thread or inside a parallel loop; ignored");
		return;
	}
	btITaskScheduler* previous = btGetTaskScheduler();
	btITaskScheduler* next = ts ? ts : &sequentialScheduler();
	if (previous == next) return;
	previous->deactivate();
	gCurrentScheduler.store(next, std::memory_order_release);
	next->activate();
}

btITaskScheduler* btGetTaskScheduler()
{
	btITaskScheduler* current = gCurrentScheduler.load(std::memory_order_acquire);
	return current ? current : &sequentialScheduler();
}

btITaskScheduler* btGetSequentialTaskScheduler() { return &sequentialScheduler(); }

btITaskScheduler* btCreateDefaultTaskScheduler() { return caliber::createThreadPoolScheduler(); }

btITaskScheduler* btGetOpenMPTaskScheduler() { return caliber::openMPScheduler(); }

btITaskScheduler* btGetTBBTaskScheduler() { return caliber::tbbScheduler(); }

btITaskScheduler* btGetPPLTaskScheduler() { return 0; }

void btParallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body)
{
	btGetTaskScheduler()->parallelFor(iBegin, iEnd, grainSize, body);
}

btScalar btParallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body)
{
	return btGetTaskScheduler()->parallelSum(iBegin, iEnd, grainSize, body);
}

// ---- shared helpers (btParallelChunks.h) -----------------------------------------------------------
bool caliber::insideParallelBody() { return tParallelBodyDepth > 0; }

caliber::ParallelBodyScope::ParallelBodyScope() { ++tParallelBodyDepth; }

caliber::ParallelBodyScope::~ParallelBodyScope() { --tParallelBodyDepth; }

void caliber::runChunksSerially(const ChunkPlan& plan, const btIParallelForBody& body)
{
	ParallelBodyScope scope;
	for (int k = 0; k < plan.count; ++k)
	{
		int chunkBegin, chunkEnd;
		plan.range(k, chunkBegin, chunkEnd);
		body.forLoop(chunkBegin, chunkEnd);
	}
}

btScalar caliber::sumChunksSerially(const ChunkPlan& plan, const btIParallelSumBody& body)
{
	ParallelBodyScope scope;
	btScalar sum = btScalar(0);
	for (int k = 0; k < plan.count; ++k)
	{
		int chunkBegin, chunkEnd;
		plan.range(k, chunkBegin, chunkEnd);
		sum += body.sumLoop(chunkBegin, chunkEnd);
	}
	return sum;
}

void caliber::beginThreadsRunning() { gLoopsOnThreads.fetch_add(1, std::memory_order_acq_rel); }

void caliber::endThreadsRunning() { gLoopsOnThreads.fetch_sub(1, std::memory_order_acq_rel); }

void caliber::forgetTaskScheduler(btITaskScheduler* scheduler)
{
	btITaskScheduler* expected = scheduler;
	if (gCurrentScheduler.compare_exchange_strong(expected, nullptr, std::memory_order_acq_rel))
		btReportWarning("a task scheduler was deleted while it was the current one; the sequential scheduler "
		                "replaces it");
}
