// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_THREADS_H
#define BT_THREADS_H

/// Bullet 2.89's threading API: thread indices, a spin mutex, parallel-for and parallel-sum bodies,
/// and the task-scheduler interface with its backends. Contract and guarantees: docs/threading.md.

#include "LinearMath/btScalar.h"

/// The most threads a scheduler runs (the calling thread included); thread indices are below it.
const unsigned int BT_MAX_THREAD_COUNT = 64;

/// True on the main thread (the one that loaded the library), whose index is 0.
bool btIsMainThread();
/// True while a scheduler runs a parallel loop on more than one thread.
bool btThreadsAreRunning();
/// This thread's index: 0 on the main thread, unique among live threads and < BT_MAX_THREAD_COUNT.
unsigned int btGetCurrentThreadIndex();
/// Bullet's reset of the index counter; Caliber recycles indices as threads end, so it does nothing.
void btResetThreadIndexCounter();

/// A small lock that spins (and then yields) instead of sleeping; for short critical sections.
class btSpinMutex
{
	int mLock;

public:
	btSpinMutex() { mLock = 0; }
	/// Waits until the lock is free and takes it.
	void lock();
	/// Releases the lock.
	void unlock();
	/// Takes the lock if it is free; true when taken.
	bool tryLock();
};

/// Locks mutex when the library is thread-safe (BT_THREADSAFE), else does nothing.
SIMD_FORCE_INLINE void btMutexLock(btSpinMutex* mutex)
{
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	mutex->lock();
#else
	(void)mutex;
#endif
}

/// Unlocks mutex when the library is thread-safe, else does nothing.
SIMD_FORCE_INLINE void btMutexUnlock(btSpinMutex* mutex)
{
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	mutex->unlock();
#else
	(void)mutex;
#endif
}

/// Tries to lock mutex when the library is thread-safe (true when taken); always true otherwise.
SIMD_FORCE_INLINE bool btMutexTryLock(btSpinMutex* mutex)
{
#if defined(BT_THREADSAFE) && BT_THREADSAFE
	return mutex->tryLock();
#else
	(void)mutex;
	return true;
#endif
}

/// The body of a parallel loop: forLoop runs indices [iBegin, iEnd), possibly on another thread.
class btIParallelForBody
{
public:
	virtual ~btIParallelForBody() {}
	/// Processes indices [iBegin, iEnd).
	virtual void forLoop(int iBegin, int iEnd) const = 0;
};

/// The body of a parallel sum: sumLoop returns the sum over indices [iBegin, iEnd).
class btIParallelSumBody
{
public:
	virtual ~btIParallelSumBody() {}
	/// Returns the sum over indices [iBegin, iEnd).
	virtual btScalar sumLoop(int iBegin, int iEnd) const = 0;
};

/// A task scheduler: runs parallel loops on its threads (see docs/threading.md for the contract).
class btITaskScheduler
{
public:
	/// name is kept by pointer (a string literal).
	btITaskScheduler(const char* name);
	virtual ~btITaskScheduler() {}
	/// The scheduler's name ("Sequential", "ThreadPool", "OpenMP", "TBB").
	const char* getName() const { return m_name; }

	/// The most threads setNumThreads accepts.
	virtual int getMaxNumThreads() const = 0;
	/// The threads parallel loops run on, the calling thread included.
	virtual int getNumThreads() const = 0;
	/// Sets the thread count, clamped to [1, getMaxNumThreads()].
	virtual void setNumThreads(int numThreads) = 0;
	/// Calls body.forLoop on the chunks [iBegin + k grainSize, ...) of [iBegin, iEnd), each once.
	virtual void parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body) = 0;
	/// The sum of body.sumLoop over the same chunks, added in chunk order (the same at any thread count).
	virtual btScalar parallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body) = 0;
	/// A hint that no parallel loop comes soon: idle workers stop spinning and sleep.
	virtual void sleepWorkerThreadsHint() {}

	/// Called by btSetTaskScheduler when this scheduler becomes the current one.
	virtual void activate();
	/// Called by btSetTaskScheduler when another scheduler replaces this one.
	virtual void deactivate();

protected:
	const char* m_name;
	unsigned int m_savedThreadCounter;
	bool m_isActive;
};

/// Makes ts the scheduler btParallelFor and the Mt classes use (0: the sequential one). Main thread only,
/// outside parallel loops; otherwise a warning and nothing changes.
void btSetTaskScheduler(btITaskScheduler* ts);
/// The current scheduler; the sequential one until btSetTaskScheduler is called. Never 0.
btITaskScheduler* btGetTaskScheduler();
/// The scheduler that runs every loop on the calling thread (owned by the library).
btITaskScheduler* btGetSequentialTaskScheduler();
/// A new thread-pool scheduler (the caller deletes it); 0 when the library is not thread-safe.
btITaskScheduler* btCreateDefaultTaskScheduler();
/// The OpenMP scheduler (owned by the library); 0 unless built with CALIBER_OPENMP.
btITaskScheduler* btGetOpenMPTaskScheduler();
/// The TBB scheduler (owned by the library); 0 unless built with CALIBER_TBB.
btITaskScheduler* btGetTBBTaskScheduler();
/// Microsoft PPL is not supported: always 0.
btITaskScheduler* btGetPPLTaskScheduler();

/// parallelFor on the current scheduler.
void btParallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body);
/// parallelSum on the current scheduler.
btScalar btParallelSum(int iBegin, int iEnd, int grainSize, const btIParallelSumBody& body);

#endif  // BT_THREADS_H
