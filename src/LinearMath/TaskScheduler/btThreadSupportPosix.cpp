// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btThreadSupportInterface on POSIX threads (std::thread): one mailbox per worker, guarded by its own
// mutex and condition variable. The stack size of the construction info is not applied: the system's
// default stack is larger than Bullet's 64 KiB default and safer for physics code.
#include "LinearMath/TaskScheduler/btThreadSupportInterface.h"

#include "LinearMath/btScalar.h"

#if defined(BT_THREADSAFE) && BT_THREADSAFE
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "LinearMath/btThreads.h"
#include "LinearMath/btWarningHook.h"

namespace
{
class MutexCriticalSection : public btCriticalSection
{
public:
	void lock() override { m_mutex.lock(); }
	void unlock() override { m_mutex.unlock(); }

private:
	std::mutex m_mutex;
};

class PosixThreadSupport : public btThreadSupportInterface
{
public:
	explicit PosixThreadSupport(const ConstructionInfo& info) : m_function(info.m_userThreadFunc)
	{
		const int hardware = int(std::thread::hardware_concurrency());
		m_logicalProcessors = hardware < 1 ? 1 : hardware;
		int workers = m_logicalProcessors - 1;
		if (workers < 1) workers = 1;
		if (workers > int(BT_MAX_THREAD_COUNT) - 1) workers = int(BT_MAX_THREAD_COUNT) - 1;
		for (int i = 0; i < workers; ++i)
		{
			m_workers.emplace_back(new Worker());
			Worker* worker = m_workers.back().get();
			worker->thread = std::thread([this, worker] { workerMain(*worker); });
		}
	}

	~PosixThreadSupport() override
	{
		for (auto& worker : m_workers)
		{
			{
				std::lock_guard<std::mutex> lock(worker->mutex);
				worker->quit = true;
			}
			worker->changed.notify_all();
		}
		for (auto& worker : m_workers) worker->thread.join();
	}

	int getNumWorkerThreads() const override { return int(m_workers.size()); }
	int getCacheFriendlyNumThreads() const override { return m_logicalProcessors; }
	int getLogicalToPhysicalCoreRatio() const override { return 1; }

	void runTask(int threadIndex, void* userData) override
	{
		if (threadIndex < 0 || threadIndex >= int(m_workers.size()))
		{
			btReportWarning("btThreadSupportInterface::runTask: no worker with that index; the task is not run");
			return;
		}
		Worker& worker = *m_workers[threadIndex];
		std::unique_lock<std::mutex> lock(worker.mutex);
		worker.changed.wait(lock, [&] { return !worker.busy; });
		worker.task = userData;
		worker.busy = true;
		lock.unlock();
		worker.changed.notify_all();
	}

	void waitForAllTasks() override
	{
		for (auto& worker : m_workers)
		{
			std::unique_lock<std::mutex> lock(worker->mutex);
			worker->changed.wait(lock, [&] { return !worker->busy; });
		}
	}

	btCriticalSection* createCriticalSection() override { return new MutexCriticalSection(); }
	void deleteCriticalSection(btCriticalSection* criticalSection) override { delete criticalSection; }

private:
	struct Worker
	{
		std::thread thread;
		std::mutex mutex;
		std::condition_variable changed;  // a task arrived, a task finished, or quit
		void* task = 0;
		bool busy = false;
		bool quit = false;
	};

	void workerMain(Worker& worker)
	{
		for (;;)
		{
			std::unique_lock<std::mutex> lock(worker.mutex);
			worker.changed.wait(lock, [&] { return worker.busy || worker.quit; });
			if (!worker.busy) return;  // quit with no task left
			void* task = worker.task;
			lock.unlock();
			m_function(task);
			lock.lock();
			worker.busy = false;
			lock.unlock();
			worker.changed.notify_all();
		}
	}

	ThreadFunc m_function;
	int m_logicalProcessors;
	std::vector<std::unique_ptr<Worker>> m_workers;
};
}  // namespace

btThreadSupportInterface* btThreadSupportInterface::create(const ConstructionInfo& info)
{
	if (!info.m_userThreadFunc)
	{
		btReportWarning("btThreadSupportInterface::create: the construction info has no thread function");
		return 0;
	}
	return new PosixThreadSupport(info);
}
#else
btThreadSupportInterface* btThreadSupportInterface::create(const ConstructionInfo&) { return 0; }
#endif
