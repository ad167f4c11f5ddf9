// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_BATCH_DEPENDENCIES_H
#define CALIBER_BATCH_DEPENDENCIES_H

// Which earlier batches each batch of a coloured solve waits for (btSequentialImpulseConstraintSolverMt's
// sweep without a wait at the end of every colour): for each of its moving bodies, the batch that touched
// that body last before it in the sweep's order. Why that gives the bits of a wait per colour, and the
// measurements: docs/threading.md, "The wide sweep of a coloured batch" and "Eleventh session".

#include "LinearMath/btAlignedObjectArray.h"

class btBatchedConstraints;

namespace caliber
{
/// One work item of the Mt solver's sweep without a wait per colour: a run of consecutive batches of one
/// colour in one pass (0: normal rows, 1: friction and rolling rows), for one task of the loop.
struct SweepItem
{
	int pass, batchBegin, batchEnd;
	int run;  // the task that runs it first (another takes it only when it needs it or is idle)
};

/// The items of a sweep over batched's colours (its phases in m_phaseOrder, backwards when reverse), normal
/// pass then friction pass, for numThreads tasks (clamped to [1, BT_MAX_THREAD_COUNT]), balanced by rows
/// (a batch's rows: its range). Each colour's batches are cut into at most one run per task, in task order,
/// each task taking batches while their middle row lies below the share every task would have after the
/// colour; a colour of fewer batches than tasks gives each batch to the task with the fewest rows so far
/// (the lowest on a tie). The cut is made once, colour by colour in the forward order, and both passes and
/// both directions take it: a batch has the same task in every sweep of a solve. itemOfBatch[pass *
/// numBatches + batch] is the batch's item. The items depend only on the batches and numThreads.
void listSweepItems(const btBatchedConstraints& batched, bool reverse, int numThreads,
                    btAlignedObjectArray<SweepItem>& items, btAlignedObjectArray<int>& itemOfBatch);

/// Whether the Mt solver's coloured sweep posts one parallel loop per colour and pass, each with its wait
/// at the end (the sweep until 28 Nov), instead of one loop per iteration whose batches wait only for the
/// batches they depend on. The same bits either way; for tests and measurements. Default off.
void setColourSweepBarriers(bool enabled);
/// The switch above.
bool colourSweepBarriers();

/// The dependencies of a coloured solve's batches in the four sweeps an iteration can make.
///
/// A sweep runs the normal rows of every colour, then the friction (and rolling) rows of every colour,
/// colours forwards or backwards. Its work items are (pass, batch), numbered pass * numBatches + batch.
/// An item's dependencies are, for each of its batch's moving bodies, the item that touched that body last
/// before it in the sweep's order (for the first friction item of a body, the last normal item of that
/// body); every item before it that touches one of its bodies is then finished when these are.
class BatchDependencies
{
public:
	/// The four sweeps: the colours forwards or backwards, the normal pass or the friction pass.
	enum Sweep
	{
		kForwardNormal = 0,
		kForwardFriction = 1,
		kBackwardNormal = 2,
		kBackwardFriction = 3,
		kNumSweeps = 4
	};

	/// Lists the dependencies, on the task scheduler's threads. Batch b holds the manifolds
	/// order[manifoldBegin[b]] to order[manifoldBegin[b + 1] - 1]; the batches are numbered in the colours'
	/// order, and no moving body is in two batches of a colour. Manifold m's solver bodies are
	/// ends[m * stride] and ends[m * stride + 1], below numBodies; fixedBodyId (or -1) is the entry that each
	/// batch has its own copy of, a dependency of none.
	void build(const int* manifoldBegin, int numBatches, const int* order, const int* ends, int stride, int numBodies,
	           int fixedBodyId);
	/// build in two halves: sortBodies, each body's batches in order (serial: may run inside a parallel
	/// loop's task, beside other work), then listAll, each batch's lists (a parallel loop). The arrays
	/// sortBodies is given must stay unchanged until listAll has returned.
	void sortBodies(const int* manifoldBegin, int numBatches, const int* order, const int* ends, int stride,
	                int numBodies, int fixedBodyId);
	void listAll();

	/// Batches of the last build.
	int numBatches() const { return m_numBatches; }
	/// Dependencies of the item (sweep's pass, batch) in the sweep, each an item number, none repeated.
	int count(Sweep sweep, int batch) const { return m_count[sweep * m_numBatches + batch]; }
	/// The first of them (count() of them follow).
	const int* list(Sweep sweep, int batch) const { return &m_lists[sweep][2 * m_manifoldBegin[batch]]; }

	/// Lists batches [batchBegin, batchEnd) using chunk's marks (build's parallel part).
	void listBatches(int batchBegin, int batchEnd, int chunk);

private:
	int m_numBatches = 0;
	int m_fixedBodyId = -1;
	int m_stride = 0;
	const int* m_order = nullptr;
	const int* m_ends = nullptr;
	btAlignedObjectArray<int> m_manifoldBegin;      // a copy of build's
	btAlignedObjectArray<int> m_bodyStart;          // per body (and one past the last): its first entry
	btAlignedObjectArray<int> m_bodyBatches;        // each body's batches in order
	btAlignedObjectArray<int> m_entry;              // per manifold end in order: its place in m_bodyBatches (-1: fixed)
	btAlignedObjectArray<int> m_lists[kNumSweeps];  // two places per manifold of a batch: at most two bodies each
	btAlignedObjectArray<int> m_count;              // per sweep and batch
	btAlignedObjectArray<int> m_marks;              // per chunk, sweep and item: the last batch that listed it
};
}  // namespace caliber

#endif
