// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The multithreaded dispatcher: the narrowphase over pairs in chunks on the task scheduler's threads,
// with the same bits as the serial narrowphase.
//
// Pairs are independent (each has its own algorithm and manifolds); what they share is the
// dispatcher's manifold array, whose order decides the solver's order. So while chunks run, new and
// released manifolds are only written into their chunk's log (m_batchManifoldsPtr[chunk]); afterwards
// the logs are replayed in chunk order on the calling thread, which performs exactly the array
// operations the serial narrowphase performs, in the same order. A log entry is a creation when the
// manifold is not in the array yet (m_index1a == -1, set when it is made), a release otherwise; a
// manifold made and released in one chunk appears twice, and the first entry puts it in the array.
// Released manifolds are cleared at once (their contact callbacks run on the worker) but destroyed at
// the replay, so no memory is reused while chunks run.
//
// A soft body's pairs are not independent: each writes the body's own contact lists. The chunks skip
// them, and the calling thread runs them after the replay, in pair order. They make no manifolds and
// read nothing the other pairs write, so the result is the serial narrowphase's.
#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"

#include <atomic>
#include <new>

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldAllocation.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btPoolAllocator.h"

namespace
{
typedef btAlignedObjectArray<btPersistentManifold*> ManifoldOpLog;

// The narrowphase's cut into chunks (dispatchAllCollisionPairs).
const int kChunksPerThread = 8;
const int kMinPairsPerChunk = 4;

// The log of the chunk this thread is running, and the dispatcher it belongs to (a worker never runs
// two dispatchers' chunks at once: nested loops run serially on their caller).
thread_local ManifoldOpLog* t_chunkLog = 0;
thread_local const btCollisionDispatcherMt* t_chunkDispatcher = 0;

struct ChunkScope
{
	ChunkScope(ManifoldOpLog* log, const btCollisionDispatcherMt* dispatcher)
	    : m_previousLog(t_chunkLog), m_previousDispatcher(t_chunkDispatcher)
	{
		t_chunkLog = log;
		t_chunkDispatcher = dispatcher;
	}
	~ChunkScope()
	{
		t_chunkLog = m_previousLog;
		t_chunkDispatcher = m_previousDispatcher;
	}
	ManifoldOpLog* m_previousLog;
	const btCollisionDispatcherMt* m_previousDispatcher;
};

bool isSoftBody(const btBroadphaseProxy* proxy)
{
	const btCollisionObject* object = proxy ? static_cast<const btCollisionObject*>(proxy->m_clientObject) : 0;
	return object && object->getInternalType() == btCollisionObject::CO_SOFT_BODY;
}

bool involvesSoftBody(const btBroadphasePair& pair) { return isSoftBody(pair.m_pProxy0) || isSoftBody(pair.m_pProxy1); }

struct NarrowphaseChunks : public btIParallelForBody
{
	btCollisionDispatcherMt* dispatcher;
	btBroadphasePair* pairs;
	const btDispatcherInfo* info;
	btAlignedObjectArray<ManifoldOpLog>* logs;
	std::atomic<bool>* softPairsLeft;  ///< set when a chunk skipped a soft body's pair
	int grainSize;  // pairs per chunk
	int numPairs;

	// The loop runs over chunk numbers (chunk c: pairs [c grainSize, (c + 1) grainSize)), so that a
	// scheduler that cuts loops its own way (Bullet's interface allows any split) never gives two calls
	// pairs of one chunk, whose log the second would clear.
	void forLoop(int chunkBegin, int chunkEnd) const override
	{
		btNearCallback nearCallback = dispatcher->getNearCallback();
		bool skipped = false;
		for (int chunk = chunkBegin; chunk < chunkEnd; ++chunk)
		{
			ManifoldOpLog& log = (*logs)[chunk];
			log.resize(0);
			ChunkScope scope(&log, dispatcher);
			const int end = btMin(numPairs, (chunk + 1) * grainSize);
			for (int i = chunk * grainSize; i < end; ++i)
			{
				if (involvesSoftBody(pairs[i]))
				{
					skipped = true;
					continue;
				}
				(*nearCallback)(pairs[i], *dispatcher, *info);
			}
		}
		if (skipped) softPairsLeft->store(true, std::memory_order_relaxed);
	}
};
}  // namespace

btCollisionDispatcherMt::btCollisionDispatcherMt(btCollisionConfiguration* config, int grainSize)
    : btCollisionDispatcher(config), m_batchUpdating(false), m_grainSize(grainSize < 1 ? 1 : grainSize)
{
}

btPersistentManifold* btCollisionDispatcherMt::getNewManifold(const btCollisionObject* body0,
                                                              const btCollisionObject* body1)
{
	if (!m_batchUpdating || t_chunkDispatcher != this || !t_chunkLog)
		return btCollisionDispatcher::getNewManifold(body0, body1);
	btAssert(body0 && body1 && body0->getCollisionShape() && body1->getCollisionShape());
	const caliber::ManifoldThresholds thresholds = caliber::manifoldThresholds(
	    body0, body1, (m_dispatcherFlags & CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD) != 0);
	void* memory = caliber::allocateManifoldMemory(
	    m_persistentManifoldPoolAllocator, !(m_dispatcherFlags & CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION));
	if (!memory) return 0;
	btPersistentManifold* manifold =
	    new (memory) btPersistentManifold(body0, body1, 0, thresholds.breaking, thresholds.processing);
	manifold->m_index1a = -1;  // not in the array until the replay
	t_chunkLog->push_back(manifold);
	return manifold;
}

void btCollisionDispatcherMt::releaseManifold(btPersistentManifold* manifold)
{
	if (!m_batchUpdating || t_chunkDispatcher != this || !t_chunkLog)
	{
		btCollisionDispatcher::releaseManifold(manifold);
		return;
	}
	if (!manifold) return;
	clearManifold(manifold);
	t_chunkLog->push_back(manifold);
}

void btCollisionDispatcherMt::dispatchAllCollisionPairs(btOverlappingPairCache* pairCache, const btDispatcherInfo& info,
                                                        btDispatcher* dispatcher)
{
	btAssert(pairCache);
	if (!pairCache) return;
	const int numPairs = pairCache->getNumOverlappingPairs();
	// Serial when there is no second thread or one chunk only, and for the time-of-impact dispatch
	// (every pair lowers the one shared m_timeOfImpact).
	if (btGetTaskScheduler()->getNumThreads() < 2 || numPairs <= m_grainSize || m_batchUpdating ||
	    info.m_dispatchFunc != btDispatcherInfo::DISPATCH_DISCRETE)
	{
		btCollisionDispatcher::dispatchAllCollisionPairs(pairCache, info, dispatcher);
		return;
	}
	if (info.m_deterministicOverlappingPairs) pairCache->sortOverlappingPairs(this);
	// Chunks of at most grainSize pairs, and at least kChunksPerThread per thread when the pairs allow
	// (kMinPairsPerChunk pairs or more each): a step with a few hundred pairs, some of them against a mesh
	// (several times the cost of the others), cut into chunks of 40 gave each thread two or three chunks, and
	// one thread's last chunk decided the end. The cut changes nothing else: each pair runs once, and the
	// chunks' logs are replayed in pair order whatever the cut.
	const int threads = btGetTaskScheduler()->getNumThreads();
	const int wanted = (numPairs + kChunksPerThread * threads - 1) / (kChunksPerThread * threads);
	const int chunkPairs = btMin(m_grainSize, btMax(kMinPairsPerChunk, wanted));
	// Chunk logs keep their capacity from step to step, so the steady state allocates nothing.
	const int numChunks = (numPairs + chunkPairs - 1) / chunkPairs;
	if (m_batchManifoldsPtr.size() < numChunks) m_batchManifoldsPtr.resize(numChunks);

	NarrowphaseChunks chunks;
	chunks.dispatcher = this;
	chunks.pairs = pairCache->getOverlappingPairArrayPtr();
	chunks.info = &info;
	chunks.logs = &m_batchManifoldsPtr;
	chunks.grainSize = chunkPairs;
	chunks.numPairs = numPairs;
	std::atomic<bool> softPairsLeft(false);
	chunks.softPairsLeft = &softPairsLeft;
	m_batchUpdating = true;
	btParallelFor(0, numChunks, 1, chunks);
	m_batchUpdating = false;

	// The serial narrowphase's array operations, in its order.
	for (int c = 0; c < numChunks; ++c)
	{
		const ManifoldOpLog& log = m_batchManifoldsPtr[c];
		for (int k = 0; k < log.size(); ++k)
		{
			btPersistentManifold* manifold = log[k];
			if (manifold->m_index1a == -1)
			{
				manifold->m_index1a = m_manifoldsPtr.size();
				m_manifoldsPtr.push_back(manifold);
			}
			else
			{
				btCollisionDispatcher::releaseManifold(manifold);
			}
		}
	}
	if (!softPairsLeft.load()) return;
	btBroadphasePair* pairs = pairCache->getOverlappingPairArrayPtr();
	btNearCallback nearCallback = getNearCallback();
	for (int i = 0; i < numPairs; ++i)
		if (involvesSoftBody(pairs[i])) (*nearCallback)(pairs[i], *this, info);
}
