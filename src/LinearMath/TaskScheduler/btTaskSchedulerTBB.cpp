// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGetTBBTaskScheduler's scheduler (built with CALIBER_TBB, Debian libtbb-dev): the chunks of a loop
// shared out by tbb::parallel_for inside a task arena of the chosen thread count. Chunks and the order
// of a sum's partials are those of every scheduler (btParallelChunks.h, btChunkedScheduler.h).
#include "LinearMath/TaskScheduler/btParallelChunks.h"

#ifdef CALIBER_HAVE_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <memory>

#include "LinearMath/TaskScheduler/btChunkedScheduler.h"

namespace
{
class TBBScheduler : public caliber::ChunkedScheduler
{
public:
	TBBScheduler() : caliber::ChunkedScheduler("TBB") { setNumThreads(tbb::this_task_arena::max_concurrency()); }

protected:
	void threadCountChanged() override { m_arena.reset(new tbb::task_arena(getNumThreads())); }

	void runChunks(int count, const ChunkTask& task) override
	{
		m_arena->execute([&] {
			tbb::parallel_for(tbb::blocked_range<int>(0, count, 1), [&](const tbb::blocked_range<int>& r) {
				caliber::ParallelBodyScope scope;
				for (int k = r.begin(); k != r.end(); ++k) task.run(k);
			});
		});
	}

private:
	std::unique_ptr<tbb::task_arena> m_arena{new tbb::task_arena(1)};  // replaced by setNumThreads
};
}  // namespace

btITaskScheduler* caliber::tbbScheduler()
{
	static TBBScheduler* scheduler = new TBBScheduler();  // owned by the library, never destroyed
	return scheduler;
}
#else
btITaskScheduler* caliber::tbbScheduler() { return 0; }
#endif
