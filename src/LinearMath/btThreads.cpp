// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btThreads.h"

#include <thread>

void btSpinMutex::lock()
{
	// Test before exchanging, so that waiting threads read a shared line instead of fighting over it.
	for (;;)
	{
		if (tryLock()) return;
		while (mLock.load(std::memory_order_relaxed) != 0) std::this_thread::yield();
	}
}

void btSpinMutex::unlock() { mLock.store(0, std::memory_order_release); }

bool btSpinMutex::tryLock() { return mLock.exchange(1, std::memory_order_acquire) == 0; }
