// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btGetOpenMPTaskScheduler's scheduler (built with CALIBER_OPENMP): the chunks of a loop shared out by an
// OpenMP loop. Chunks and the order of a sum's partials are those of every scheduler (btParallelChunks.h,
// btChunkedScheduler.h).
#include "LinearMath/TaskScheduler/btParallelChunks.h"

#ifdef CALIBER_HAVE_OPENMP
#include <omp.h>

#include "LinearMath/TaskScheduler/btChunkedScheduler.h"

namespace
{
class OpenMPScheduler : public caliber::ChunkedScheduler
{
public:
	OpenMPScheduler() : caliber::ChunkedScheduler("OpenMP") { setNumThreads(omp_get_max_threads()); }

protected:
	void runChunks(int count, const ChunkTask& task) override
	{
#pragma omp parallel for schedule(dynamic, 1) num_threads(getNumThreads())
		for (int k = 0; k < count; ++k)
		{
			caliber::ParallelBodyScope scope;
			task.run(k);
		}
	}
};
}  // namespace

btITaskScheduler* caliber::openMPScheduler()
{
	static OpenMPScheduler* scheduler = new OpenMPScheduler();  // owned by the library, never destroyed
	return scheduler;
}
#else
btITaskScheduler* caliber::openMPScheduler() { return 0; }
#endif
