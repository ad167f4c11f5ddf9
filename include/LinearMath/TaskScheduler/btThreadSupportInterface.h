// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_THREAD_SUPPORT_INTERFACE_H
#define BT_THREAD_SUPPORT_INTERFACE_H

/// Bullet 2.89's low-level worker threads: run one function on a chosen worker with a user pointer,
/// and wait for all of them. Caliber's schedulers do not need it; it is here for programs that use it
/// directly (docs/threading.md). Implemented on POSIX threads; no Win32 implementation yet.

/// A lock made by btThreadSupportInterface::createCriticalSection.
class btCriticalSection
{
public:
	btCriticalSection() {}
	virtual ~btCriticalSection() {}
	/// Waits for and takes the lock.
	virtual void lock() = 0;
	/// Releases the lock.
	virtual void unlock() = 0;
};

/// A set of worker threads, each running the construction info's function on the tasks given to it.
class btThreadSupportInterface
{
public:
	virtual ~btThreadSupportInterface() {}

	/// The number of worker threads (the calling thread not included).
	virtual int getNumWorkerThreads() const = 0;
	/// How many threads fit the machine (its logical processors).
	virtual int getCacheFriendlyNumThreads() const = 0;
	/// Logical processors per physical core (1 when the system does not say).
	virtual int getLogicalToPhysicalCoreRatio() const = 0;
	/// Runs the thread function with userData on worker threadIndex (in [0, getNumWorkerThreads())),
	/// after that worker's previous task has finished.
	virtual void runTask(int threadIndex, void* userData) = 0;
	/// Returns when every worker has finished its task.
	virtual void waitForAllTasks() = 0;

	/// A new lock (delete it with deleteCriticalSection).
	virtual btCriticalSection* createCriticalSection() = 0;
	/// Deletes a lock made by createCriticalSection.
	virtual void deleteCriticalSection(btCriticalSection* criticalSection) = 0;

	/// The function each worker runs on its tasks.
	typedef void (*ThreadFunc)(void* userPtr);

	/// What create needs: a name, the worker function and a stack size (a hint; see docs/threading.md).
	struct ConstructionInfo
	{
		ConstructionInfo(const char* uniqueName, ThreadFunc userThreadFunc, int threadStackSize = 65535)
		    : m_uniqueName(uniqueName), m_userThreadFunc(userThreadFunc), m_threadStackSize(threadStackSize)
		{
		}

		const char* m_uniqueName;
		ThreadFunc m_userThreadFunc;
		int m_threadStackSize;
	};

	/// New worker threads (the caller deletes them); 0 when the library is not thread-safe or
	/// info has no function.
	static btThreadSupportInterface* create(const ConstructionInfo& info);
};

#endif  // BT_THREAD_SUPPORT_INTERFACE_H
