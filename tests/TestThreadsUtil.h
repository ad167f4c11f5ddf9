// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TEST_THREADS_UTIL_H
#define CALIBER_TEST_THREADS_UTIL_H

// What the threading tests share: a task scheduler for a scope, and the bits of bodies' states to
// compare between runs at different thread counts.

#include <memory>
#include <vector>

#include "LinearMath/btThreads.h"
#include "LinearMath/btTransform.h"

namespace caliber_test
{
/// The thread pool with `threads` threads as the task scheduler for the scope (a library built without
/// threads has no pool: the sequential scheduler stands in); threads 0 sets none. No scheduler after.
class ScopedTaskScheduler
{
public:
	explicit ScopedTaskScheduler(int threads)
	{
		if (threads <= 0) return;
		m_pool.reset(btCreateDefaultTaskScheduler());
		btITaskScheduler* scheduler = m_pool ? m_pool.get() : btGetSequentialTaskScheduler();
		btSetTaskScheduler(scheduler);
		scheduler->setNumThreads(threads);
	}
	~ScopedTaskScheduler() { btSetTaskScheduler(0); }
	ScopedTaskScheduler(const ScopedTaskScheduler&) = delete;
	ScopedTaskScheduler& operator=(const ScopedTaskScheduler&) = delete;

private:
	std::unique_ptr<btITaskScheduler> m_pool;
};

/// A user's scheduler that reports two threads but runs every loop on the calling thread, cut into uneven
/// pieces that ignore the grain (1, 2, 3, ... items): Bullet's interface allows any split, so no stage may
/// depend on how a loop is cut.
class UnevenSplitScheduler : public btITaskScheduler
{
public:
	UnevenSplitScheduler() : btITaskScheduler("UnevenSplit") {}
	int getMaxNumThreads() const override { return 2; }
	int getNumThreads() const override { return 2; }
	void setNumThreads(int) override {}
	void parallelFor(int iBegin, int iEnd, int, const btIParallelForBody& body) override
	{
		int piece = 1;
		for (int i = iBegin; i < iEnd; i += piece++) body.forLoop(i, btMin(iEnd, i + piece));
	}
	btScalar parallelSum(int iBegin, int iEnd, int, const btIParallelSumBody& body) override
	{
		return body.sumLoop(iBegin, iEnd);
	}
};

/// A user's scheduler that reports two threads and runs a loop's grain-sized chunks on the calling thread
/// from the last to the first: no stage may depend on which chunks of a loop run first.
class LastFirstScheduler : public btITaskScheduler
{
public:
	LastFirstScheduler() : btITaskScheduler("LastFirst") {}
	int getMaxNumThreads() const override { return 2; }
	int getNumThreads() const override { return 2; }
	void setNumThreads(int) override {}
	void parallelFor(int iBegin, int iEnd, int grainSize, const btIParallelForBody& body) override
	{
		const int grain = grainSize < 1 ? 1 : grainSize;
		if (iEnd <= iBegin) return;
		for (int k = (iEnd - iBegin - 1) / grain; k >= 0; --k)
			body.forLoop(iBegin + k * grain, btMin(iEnd, iBegin + (k + 1) * grain));
	}
	btScalar parallelSum(int iBegin, int iEnd, int, const btIParallelSumBody& body) override
	{
		return body.sumLoop(iBegin, iEnd);
	}
};

/// The bits of every body's basis, position and velocities, in order (bodies: pointers or smart pointers
/// to btRigidBody).
template <class Bodies>
std::vector<btScalar> bodyStateBits(const Bodies& bodies)
{
	std::vector<btScalar> bits;
	for (const auto& body : bodies)
	{
		const btTransform& t = body->getWorldTransform();
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c) bits.push_back(t.getBasis()[r][c]);
		for (int c = 0; c < 3; ++c)
		{
			bits.push_back(t.getOrigin()[c]);
			bits.push_back(body->getLinearVelocity()[c]);
			bits.push_back(body->getAngularVelocity()[c]);
		}
	}
	return bits;
}
}  // namespace caliber_test

#endif  // CALIBER_TEST_THREADS_UTIL_H
