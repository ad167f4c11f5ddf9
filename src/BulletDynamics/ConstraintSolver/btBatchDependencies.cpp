// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The dependencies of a coloured solve's batches: each body's batches in colour order (a counting sort by
// body, on the calling thread), then each batch's neighbours in its bodies' lists (on the threads).
#include "BulletDynamics/ConstraintSolver/btBatchDependencies.h"

#include <atomic>

#include "BulletDynamics/ConstraintSolver/btBatchedConstraints.h"
#include "LinearMath/btScratchArray.h"
#include "LinearMath/btThreads.h"

namespace
{
std::atomic<bool> g_colourSweepBarriers(false);

// Fixed chunks of the batches, each with its own marks (so the lists do not depend on the scheduler's split).
const int kDependencyChunks = 8;

struct ListDependencies : public btIParallelForBody
{
	caliber::BatchDependencies* dependencies;
	int numBatches;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int chunk = iBegin; chunk < iEnd; ++chunk)
			dependencies->listBatches(int(static_cast<long long>(numBatches) * chunk / kDependencyChunks),
			                          int(static_cast<long long>(numBatches) * (chunk + 1) / kDependencyChunks), chunk);
	}
};
}  // namespace

void caliber::setColourSweepBarriers(bool enabled) { g_colourSweepBarriers.store(enabled, std::memory_order_relaxed); }
bool caliber::colourSweepBarriers() { return g_colourSweepBarriers.load(std::memory_order_relaxed); }

void caliber::BatchDependencies::build(const int* manifoldBegin, int numBatches, const int* order, const int* ends,
                                       int stride, int numBodies, int fixedBodyId)
{
	sortBodies(manifoldBegin, numBatches, order, ends, stride, numBodies, fixedBodyId);
	listAll();
}

void caliber::BatchDependencies::sortBodies(const int* manifoldBegin, int numBatches, const int* order,
                                            const int* ends, int stride, int numBodies, int fixedBodyId)
{
	btAssert(numBatches >= 0 && numBodies >= 0);
	m_numBatches = numBatches;
	m_fixedBodyId = fixedBodyId;
	m_stride = stride;
	m_order = order;
	m_ends = ends;
	resizeScratch(m_manifoldBegin, numBatches + 1);
	for (int b = 0; b <= numBatches; ++b) m_manifoldBegin[b] = manifoldBegin[b];
	const int numPlaces = numBatches > 0 ? manifoldBegin[numBatches] : 0;
	// Each body's batches in batch order: a counting sort of the manifolds' ends, taken in order.
	assignScratch(m_bodyStart, numBodies + 1, 0);
	resizeScratch(m_entry, 2 * numPlaces);
	for (int p = 0; p < numPlaces; ++p)
		for (int side = 0; side < 2; ++side)
		{
			const int body = ends[order[p] * stride + side];
			btAssert(body >= 0 && body < numBodies);
			if (body != fixedBodyId) ++m_bodyStart[body + 1];
		}
	for (int body = 0; body < numBodies; ++body) m_bodyStart[body + 1] += m_bodyStart[body];
	resizeScratch(m_bodyBatches, m_bodyStart[numBodies]);
	for (int b = 0; b < numBatches; ++b)
		for (int p = manifoldBegin[b]; p < manifoldBegin[b + 1]; ++p)
			for (int side = 0; side < 2; ++side)
			{
				const int body = ends[order[p] * stride + side];
				if (body == fixedBodyId)
				{
					m_entry[2 * p + side] = -1;
					continue;
				}
				// m_bodyStart[body] runs ahead as the body's entries are written; set back below.
				m_entry[2 * p + side] = m_bodyStart[body];
				m_bodyBatches[m_bodyStart[body]++] = b;
			}
	for (int body = numBodies; body > 0; --body) m_bodyStart[body] = m_bodyStart[body - 1];
	m_bodyStart[0] = 0;
	for (int s = 0; s < kNumSweeps; ++s) resizeScratch(m_lists[s], 2 * numPlaces);
	resizeScratch(m_count, kNumSweeps * numBatches);
	assignScratch(m_marks, kDependencyChunks * kNumSweeps * 2 * numBatches, -1);
}

void caliber::BatchDependencies::listAll()
{
	if (m_numBatches == 0) return;
	ListDependencies list;
	list.dependencies = this;
	list.numBatches = m_numBatches;
	btParallelFor(0, kDependencyChunks, 1, list);
}

void caliber::BatchDependencies::listBatches(int batchBegin, int batchEnd, int chunk)
{
	const int numItems = 2 * m_numBatches;
	// Per sweep and item: the last batch that listed the item in that sweep (an item is listed once).
	int* marks = &m_marks[chunk * kNumSweeps * numItems];
	int* forwardNormalMarks = marks;
	int* forwardFrictionMarks = marks + numItems;
	int* backwardNormalMarks = marks + 2 * numItems;
	int* backwardFrictionMarks = marks + 3 * numItems;
	for (int b = batchBegin; b < batchEnd; ++b)
	{
		const int place = 2 * m_manifoldBegin[b];
		int* forwardNormal = &m_lists[kForwardNormal][place];
		int* forwardFriction = &m_lists[kForwardFriction][place];
		int* backwardNormal = &m_lists[kBackwardNormal][place];
		int* backwardFriction = &m_lists[kBackwardFriction][place];
		int numForwardNormal = 0, numForwardFriction = 0, numBackwardNormal = 0, numBackwardFriction = 0;
		for (int p = m_manifoldBegin[b]; p < m_manifoldBegin[b + 1]; ++p)
			for (int side = 0; side < 2; ++side)
			{
				const int entry = m_entry[2 * p + side];
				if (entry < 0) continue;
				const int body = m_ends[m_order[p] * m_stride + side];
				const int first = m_bodyStart[body], last = m_bodyStart[body + 1] - 1;
				// Forwards: the body's batch before this one, or for the friction pass the body's last batch.
				int item = entry > first ? m_bodyBatches[entry - 1] : -1;
				if (item >= 0 && forwardNormalMarks[item] != b)
				{
					forwardNormalMarks[item] = b;
					forwardNormal[numForwardNormal++] = item;
				}
				item = item >= 0 ? m_numBatches + item : m_bodyBatches[last];
				if (forwardFrictionMarks[item] != b)
				{
					forwardFrictionMarks[item] = b;
					forwardFriction[numForwardFriction++] = item;
				}
				// Backwards: the body's batch after this one, or for the friction pass the body's first batch.
				item = entry < last ? m_bodyBatches[entry + 1] : -1;
				if (item >= 0 && backwardNormalMarks[item] != b)
				{
					backwardNormalMarks[item] = b;
					backwardNormal[numBackwardNormal++] = item;
				}
				item = item >= 0 ? m_numBatches + item : m_bodyBatches[first];
				if (backwardFrictionMarks[item] != b)
				{
					backwardFrictionMarks[item] = b;
					backwardFriction[numBackwardFriction++] = item;
				}
			}
		m_count[kForwardNormal * m_numBatches + b] = numForwardNormal;
		m_count[kForwardFriction * m_numBatches + b] = numForwardFriction;
		m_count[kBackwardNormal * m_numBatches + b] = numBackwardNormal;
		m_count[kBackwardFriction * m_numBatches + b] = numBackwardFriction;
	}
}

// Cut by batch count instead (until 28 Nov), the first task took the larger half of every colour of an odd
// number of batches and the whole of every colour of one batch: 59 % of pyramid_jolt's rows and 63 % of
// stack1000's at two threads, and the other task waited for it colour after colour.
void caliber::listSweepItems(const btBatchedConstraints& batched, bool reverse, int numThreads,
                             btAlignedObjectArray<SweepItem>& items, btAlignedObjectArray<int>& itemOfBatch)
{
	const int numBatches = batched.m_batches.size();
	const int numPhases = batched.m_phases.size();
	const int tasks = btMin(btMax(numThreads, 1), int(BT_MAX_THREAD_COUNT));
	items.resize(0);
	caliber::resizeScratch(itemOfBatch, 2 * numBatches);
	auto rowsOf = [&batched](int batch)
	{ return static_cast<long long>(batched.m_batches[batch].end - batched.m_batches[batch].begin); };
	// Each batch's task, cut once, for the forward sweep's normal pass; kept meanwhile in the friction pass's
	// half of itemOfBatch. Both passes and both directions take the same cut, so that a batch, with its rows
	// and bodies, stays with one thread in every sweep of a solve (cut again for each, the balance carried from
	// colour to colour moved the cuts by a batch or so between them).
	int* const taskOfBatch = numBatches > 0 ? &itemOfBatch[numBatches] : nullptr;
	long long rowsOfTask[BT_MAX_THREAD_COUNT] = {};
	for (int k = 0; k < numPhases; ++k)
	{
		const btBatchedConstraints::Range& phase = batched.m_phases[batched.m_phaseOrder[k]];
		if (phase.end - phase.begin < tasks)
		{
			for (int b = phase.begin; b < phase.end; ++b)
			{
				int fewest = 0;
				for (int t = 1; t < tasks; ++t)
					if (rowsOfTask[t] < rowsOfTask[fewest]) fewest = t;
				taskOfBatch[b] = fewest;
				rowsOfTask[fewest] += rowsOf(b);
			}
			continue;
		}
		// The tasks' rows after the colour (each task's share of them is total / tasks).
		long long total = 0;
		for (int t = 0; t < tasks; ++t) total += rowsOfTask[t];
		for (int b = phase.begin; b < phase.end; ++b) total += rowsOf(b);
		int b = phase.begin;
		for (int t = 0; t < tasks; ++t)
		{
			const int first = b;
			if (t == tasks - 1)
				b = phase.end;
			else
			{
				long long taken = 0;
				while (b < phase.end && (2 * (rowsOfTask[t] + taken) + rowsOf(b)) * tasks < 2 * total)
					taken += rowsOf(b++);
			}
			for (int c = first; c < b; ++c)
			{
				taskOfBatch[c] = t;
				rowsOfTask[t] += rowsOf(c);
			}
		}
	}
	// The items: in each colour, the batches of one task in a row (one item per batch in a colour of fewer
	// batches than tasks, as they were handed out one by one).
	for (int pass = 0; pass < 2; ++pass)
		for (int k = 0; k < numPhases; ++k)
		{
			const btBatchedConstraints::Range& phase =
			    batched.m_phases[batched.m_phaseOrder[reverse ? numPhases - 1 - k : k]];
			const bool single = phase.end - phase.begin < tasks;
			for (int b = phase.begin; b < phase.end;)
			{
				// The friction pass reads each batch's task from the normal pass's item (its slot now holds items).
				auto taskOf = [&](int batch) { return pass == 0 ? taskOfBatch[batch] : items[itemOfBatch[batch]].run; };
				SweepItem item;
				item.pass = pass;
				item.batchBegin = b;
				item.run = taskOf(b);
				do
					++b;
				while (!single && b < phase.end && taskOf(b) == item.run);
				item.batchEnd = b;
				for (int c = item.batchBegin; c < item.batchEnd; ++c) itemOfBatch[pass * numBatches + c] = items.size();
				items.push_back(item);
			}
		}
}
