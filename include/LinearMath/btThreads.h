// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_THREADS_H
#define BT_THREADS_H

/// btThreads: Bullet's threading primitives. Today only the spin mutex that btDiscreteDynamicsWorld's
/// subclasses may lock (m_predictiveManifoldsMutex); the task scheduler (btITaskScheduler,
/// btParallelFor, ...) comes with the threading layer (docs/architecture.md, "Layers").

#include "LinearMath/btScalar.h"

#include <atomic>

/// A lock for very short critical sections: lock() spins until the mutex is free. Not recursive.
class btSpinMutex
{
	std::atomic<int> mLock;

public:
	btSpinMutex() : mLock(0) {}
	/// Waits (spinning) until the mutex is free, then holds it.
	void lock();
	/// Releases a mutex this thread holds.
	void unlock();
	/// Holds the mutex if it is free and returns true; returns false at once otherwise.
	bool tryLock();
};

/// mutex->lock().
SIMD_FORCE_INLINE void btMutexLock(btSpinMutex* mutex) { mutex->lock(); }
/// mutex->unlock().
SIMD_FORCE_INLINE void btMutexUnlock(btSpinMutex* mutex) { mutex->unlock(); }
/// mutex->tryLock().
SIMD_FORCE_INLINE bool btMutexTryLock(btSpinMutex* mutex) { return mutex->tryLock(); }

#endif  // BT_THREADS_H
