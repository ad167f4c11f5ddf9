// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The dependencies of a coloured solve's batches: each body's batches in colour order (a counting sort by
// body, on the calling thread), then each batch's neighbours in its bodies' lists (on the threads).
#include "BulletDynamics/ConstraintSolver/btBatchDependencies.h"

#include <atomic>

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
	assignScratch(m_marks, kDependencyChunks * 2 * numBatches, -1);
	if (numBatches == 0) return;
	ListDependencies list;
	list.dependencies = this;
	list.numBatches = numBatches;
	btParallelFor(0, kDependencyChunks, 1, list);
}

void caliber::BatchDependencies::listBatches(int batchBegin, int batchEnd, int chunk)
{
	const int numItems = 2 * m_numBatches;
	int* marks = &m_marks[chunk * numItems];
	for (int b = batchBegin; b < batchEnd; ++b)
	{
		int* lists[kNumSweeps];
		int counts[kNumSweeps] = {0, 0, 0, 0};
		for (int s = 0; s < kNumSweeps; ++s) lists[s] = &m_lists[s][2 * m_manifoldBegin[b]];
		// An item is listed once per batch and sweep: its mark holds the last (batch, sweep) that listed it.
		auto add = [&](int sweep, int item)
		{
			const int mark = b * kNumSweeps + sweep;
			if (marks[item] == mark) return;
			// A mark from an earlier sweep of this batch is overwritten; the item may then be listed again for
			// a later sweep, which is right: the sweeps' lists are separate.
			marks[item] = mark;
			lists[sweep][counts[sweep]++] = item;
		};
		for (int s = 0; s < kNumSweeps; ++s)
			for (int p = m_manifoldBegin[b]; p < m_manifoldBegin[b + 1]; ++p)
				for (int side = 0; side < 2; ++side)
				{
					const int entry = m_entry[2 * p + side];
					if (entry < 0) continue;
					const int body = m_ends[m_order[p] * m_stride + side];
					const int first = m_bodyStart[body], last = m_bodyStart[body + 1] - 1;
					const int previous = entry > first ? m_bodyBatches[entry - 1] : -1;
					const int next = entry < last ? m_bodyBatches[entry + 1] : -1;
					switch (s)
					{
						case kForwardNormal:
							if (previous >= 0) add(s, previous);
							break;
						case kForwardFriction:
							add(s, previous >= 0 ? m_numBatches + previous : m_bodyBatches[last]);
							break;
						case kBackwardNormal:
							if (next >= 0) add(s, next);
							break;
						default:
							add(s, next >= 0 ? m_numBatches + next : m_bodyBatches[first]);
							break;
					}
				}
		for (int s = 0; s < kNumSweeps; ++s) m_count[s * m_numBatches + b] = counts[s];
	}
}
