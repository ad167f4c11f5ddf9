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
// Affinity (off by default, caliber::setNarrowphaseAffinity; docs/threading.md says why): the Mt solver notes, per
// manifold, the thread that wrote its impulses back (btManifoldOwners.h); the next parallel narrowphase lays its pairs
// out so that the pool's contiguous block of chunks for a thread holds the pairs whose manifolds that thread wrote,
// then the pairs with no known owner where room is left. Each chunk's log also notes the pair of each entry, and when
// the layout is not pair order the logs are replayed sorted by pair, so the array operations are the serial
// narrowphase's whatever the layout.
//
// A soft body's pairs are not independent: each writes the body's own contact lists. The chunks skip
// them, and the calling thread runs them after the replay, in pair order. They make no manifolds and
// read nothing the other pairs write, so the result is the serial narrowphase's.
#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"

#include <algorithm>
#include <atomic>
#include <new>

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btManifoldAllocation.h"
#include "BulletCollision/CollisionDispatch/btManifoldOwners.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btPoolAllocator.h"
#include "LinearMath/btScratchArray.h"
#include "LinearMath/btSideTable.h"

namespace
{
typedef btAlignedObjectArray<btPersistentManifold*> ManifoldOpLog;
typedef btAlignedObjectArray<int> PairLog;  // per log entry, its pair

struct PairHint
{
	const btBroadphaseProxy* proxy0;
	const btBroadphaseProxy* proxy1;
	int manifold;
};

// The dispatcher's Caliber-only state (beside Bullet's class), kept from step to step.
struct NarrowphaseAffinity
{
	// Per manifold index: the thread that last wrote it (caliber::kNoManifoldOwner: unknown). Follows the
	// manifolds through the array's swaps; entries past its end are unknown.
	btAlignedObjectArray<unsigned char> owners;
	// Per pair index, from the last parallel narrowphase: the pair's proxies and the index of its first
	// manifold (-1: none). Used only while the pair at that index has the same proxies; a manifold index
	// moved since by a release's swap is a wrong hint, never a wrong result.
	btAlignedObjectArray<PairHint> pairHints;
	btAlignedObjectArray<int> order;         // the pairs in the chunks' order
	btAlignedObjectArray<int> pairBlock;     // per pair: its taker's block, -1 when to be placed where room is
	btAlignedObjectArray<PairLog> pairLogs;  // per chunk, beside m_batchManifoldsPtr
	btAlignedObjectArray<unsigned long long> replayKeys;  // pair << 32 | entry, sorted
	btAlignedObjectArray<btPersistentManifold*> replayEntries;
};

caliber::SideTable<NarrowphaseAffinity>& affinityTable() { return caliber::sideTable<NarrowphaseAffinity>(); }

// The owners' table after the array's swap-remove of index (last moved into it).
void ownersAfterRelease(btAlignedObjectArray<unsigned char>& owners, int index, int last)
{
	if (index < 0 || last < 0) return;
	if (last < owners.size())
	{
		if (index < last) owners[index] = owners[last];
		owners.resize(last);
	}
	else if (index < owners.size())
		owners[index] = caliber::kNoManifoldOwner;
}

// The narrowphase's cut into chunks (dispatchAllCollisionPairs).
const int kChunksPerThread = 8;
const int kMinPairsPerChunk = 4;

// The log of the chunk this thread is running, and the dispatcher it belongs to (a worker never runs
// two dispatchers' chunks at once: nested loops run serially on their caller).
thread_local ManifoldOpLog* t_chunkLog = 0;
thread_local PairLog* t_chunkPairLog = 0;
thread_local int t_chunkPair = 0;  // the pair whose near callback runs
thread_local const btCollisionDispatcherMt* t_chunkDispatcher = 0;
thread_local btManifoldArray* t_pairManifolds = 0;  // getAllContactManifolds' scratch, per thread

struct ChunkScope
{
	ChunkScope(ManifoldOpLog* log, PairLog* pairLog, const btCollisionDispatcherMt* dispatcher)
	    : m_previousLog(t_chunkLog),
	      m_previousPairLog(t_chunkPairLog),
	      m_previousPair(t_chunkPair),
	      m_previousDispatcher(t_chunkDispatcher)
	{
		t_chunkLog = log;
		t_chunkPairLog = pairLog;
		t_chunkDispatcher = dispatcher;
	}
	~ChunkScope()
	{
		t_chunkLog = m_previousLog;
		t_chunkPairLog = m_previousPairLog;
		t_chunkPair = m_previousPair;
		t_chunkDispatcher = m_previousDispatcher;
	}
	ManifoldOpLog* m_previousLog;
	PairLog* m_previousPairLog;
	int m_previousPair;
	const btCollisionDispatcherMt* m_previousDispatcher;
};

// The index of pair's first manifold (-1: none yet in the array).
int firstManifoldIndex(const btBroadphasePair& pair)
{
	if (!pair.m_algorithm) return -1;
	if (!t_pairManifolds)
	{
		thread_local btManifoldArray manifolds;
		t_pairManifolds = &manifolds;
	}
	t_pairManifolds->resize(0);
	pair.m_algorithm->getAllContactManifolds(*t_pairManifolds);
	return t_pairManifolds->size() ? (*t_pairManifolds)[0]->m_index1a : -1;
}

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
	btAlignedObjectArray<PairLog>* pairLogs;
	const int* order;                  ///< the pairs in the chunks' order
	PairHint* pairHints;               ///< per pair: its first manifold's index, for the next step's layout
	std::atomic<bool>* softPairsLeft;  ///< set when a chunk skipped a soft body's pair
	int grainSize;                     // pairs per chunk
	int numPairs;

	// The loop runs over chunk numbers (chunk c: order[c grainSize] .. order[(c + 1) grainSize - 1]), so
	// that a scheduler that cuts loops its own way (Bullet's interface allows any split) never gives two
	// calls pairs of one chunk, whose log the second would clear.
	void forLoop(int chunkBegin, int chunkEnd) const override
	{
		btNearCallback nearCallback = dispatcher->getNearCallback();
		bool skipped = false;
		for (int chunk = chunkBegin; chunk < chunkEnd; ++chunk)
		{
			ManifoldOpLog& log = (*logs)[chunk];
			PairLog& pairLog = (*pairLogs)[chunk];
			log.resize(0);
			pairLog.resize(0);
			ChunkScope scope(&log, &pairLog, dispatcher);
			const int end = btMin(numPairs, (chunk + 1) * grainSize);
			for (int k = chunk * grainSize; k < end; ++k)
			{
				const int i = order ? order[k] : k;
				if (involvesSoftBody(pairs[i]))
				{
					skipped = true;
					if (pairHints) pairHints[i].manifold = -1;
					continue;
				}
				t_chunkPair = i;
				(*nearCallback)(pairs[i], *dispatcher, *info);
				if (!pairHints) continue;
				PairHint& hint = pairHints[i];
				hint.proxy0 = pairs[i].m_pProxy0;
				hint.proxy1 = pairs[i].m_pProxy1;
				hint.manifold = firstManifoldIndex(pairs[i]);
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
	void* memory = caliber::allocateManifoldMemory(m_persistentManifoldPoolAllocator,
	                                               !(m_dispatcherFlags & CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION));
	if (!memory) return 0;
	btPersistentManifold* manifold =
	    new (memory) btPersistentManifold(body0, body1, 0, thresholds.breaking, thresholds.processing);
	manifold->m_index1a = -1;  // not in the array until the replay
	t_chunkLog->push_back(manifold);
	t_chunkPairLog->push_back(t_chunkPair);
	return manifold;
}

void btCollisionDispatcherMt::releaseManifold(btPersistentManifold* manifold)
{
	if (!m_batchUpdating || t_chunkDispatcher != this || !t_chunkLog)
	{
		// The owners follow the array's swap (a pair's removal between steps).
		const bool live = manifold && manifold->m_index1a >= 0 && manifold->m_index1a < m_manifoldsPtr.size() &&
		                  m_manifoldsPtr[manifold->m_index1a] == manifold;
		const int index = live ? manifold->m_index1a : -1;
		const int last = m_manifoldsPtr.size() - 1;
		btCollisionDispatcher::releaseManifold(manifold);
		if (live)
			if (NarrowphaseAffinity* affinity = affinityTable().find(this))
				ownersAfterRelease(affinity->owners, index, last);
		return;
	}
	if (!manifold) return;
	clearManifold(manifold);
	t_chunkLog->push_back(manifold);
	t_chunkPairLog->push_back(t_chunkPair);
}

namespace
{
// Lays the pairs out for the pool's blocks (each taker's contiguous share of the chunks, the calling
// thread's first): a pair whose manifold a thread wrote last goes into that thread's block while it has
// room, the others fill what is left in pair order. Returns false when that is pair order.
bool layOutPairs(NarrowphaseAffinity& affinity, const btBroadphasePair* pairs, int numPairs, int chunkPairs,
                 int numChunks, int threads)
{
	caliber::resizeScratch(affinity.order, numPairs);
	int* order = &affinity.order[0];
	const int takers = btMin(threads, numChunks);
	const int known = btMin(affinity.pairHints.size(), numPairs);
	if (takers < 2 || known == 0)
	{
		for (int i = 0; i < numPairs; ++i) order[i] = i;
		return false;
	}
	const int caller = int(btGetCurrentThreadIndex());
	int cursor[BT_MAX_THREAD_COUNT], end[BT_MAX_THREAD_COUNT];
	for (int t = 0; t < takers; ++t)
	{
		cursor[t] = int((long long)numChunks * t / takers) * chunkPairs;
		end[t] = btMin(numPairs, int((long long)numChunks * (t + 1) / takers) * chunkPairs);
	}
	caliber::resizeScratch(affinity.pairBlock, numPairs);
	int* block = &affinity.pairBlock[0];
	const PairHint* hints = &affinity.pairHints[0];
	const unsigned char* owners = affinity.owners.size() ? &affinity.owners[0] : 0;
	const int numOwners = affinity.owners.size();
	bool moved = false;
	for (int i = 0; i < numPairs; ++i)
	{
		const int m = (i < known && hints[i].proxy0 == pairs[i].m_pProxy0 && hints[i].proxy1 == pairs[i].m_pProxy1)
		                  ? hints[i].manifold
		                  : -1;
		const int owner = (m >= 0 && m < numOwners) ? owners[m] : caliber::kNoManifoldOwner;
		int b = -1;
		if (owner != caliber::kNoManifoldOwner) b = owner == caller ? 0 : 1 + (owner + takers - 2) % (takers - 1);
		if (b >= 0 && cursor[b] < end[b])
		{
			moved |= cursor[b] != i;
			order[cursor[b]++] = i;
		}
		else
			b = -1;
		block[i] = b;
	}
	int t = 0;
	for (int i = 0; i < numPairs; ++i)
	{
		if (block[i] >= 0) continue;
		while (cursor[t] >= end[t]) ++t;
		moved |= cursor[t] != i;
		order[cursor[t]++] = i;
	}
	return moved;
}
}  // namespace

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
	NarrowphaseAffinity& affinity = affinityTable().acquire(this);
	if (affinity.pairLogs.size() < numChunks) affinity.pairLogs.resize(numChunks);
	btBroadphasePair* pairs = pairCache->getOverlappingPairArrayPtr();
	const bool affine = caliber::narrowphaseAffinity();
	bool laidOut = false;
	if (affine)
	{
		laidOut = layOutPairs(affinity, pairs, numPairs, chunkPairs, numChunks, threads);
		const PairHint noHint = {0, 0, -1};
		affinity.pairHints.resize(numPairs, noHint);
	}
	else
		affinity.pairHints.resize(0);  // no stale hints when it is turned on again

	NarrowphaseChunks chunks;
	chunks.dispatcher = this;
	chunks.pairs = pairs;
	chunks.info = &info;
	chunks.logs = &m_batchManifoldsPtr;
	chunks.pairLogs = &affinity.pairLogs;
	chunks.order = laidOut ? &affinity.order[0] : 0;
	chunks.pairHints = affine ? &affinity.pairHints[0] : 0;
	chunks.grainSize = chunkPairs;
	chunks.numPairs = numPairs;
	std::atomic<bool> softPairsLeft(false);
	chunks.softPairsLeft = &softPairsLeft;
	m_batchUpdating = true;
	btParallelFor(0, numChunks, 1, chunks);
	m_batchUpdating = false;

	// The serial narrowphase's array operations, in its order: pair by pair, each pair's in its own order
	// (all in one chunk's log). In pair order already when the layout is; otherwise sorted by pair.
	auto replayOne = [this](btPersistentManifold* manifold, btAlignedObjectArray<unsigned char>& owners)
	{
		if (manifold->m_index1a == -1)
		{
			manifold->m_index1a = m_manifoldsPtr.size();
			m_manifoldsPtr.push_back(manifold);
			return;
		}
		const int index = manifold->m_index1a;
		const int last = m_manifoldsPtr.size() - 1;
		btCollisionDispatcher::releaseManifold(manifold);
		ownersAfterRelease(owners, index, last);
	};
	btAlignedObjectArray<btPersistentManifold*>& entries = affinity.replayEntries;
	entries.resize(0);
	if (laidOut)
	{
		btAlignedObjectArray<unsigned long long>& keys = affinity.replayKeys;
		keys.resize(0);
		for (int c = 0; c < numChunks; ++c)
		{
			const ManifoldOpLog& log = m_batchManifoldsPtr[c];
			const PairLog& pairLog = affinity.pairLogs[c];
			for (int k = 0; k < log.size(); ++k)
			{
				keys.push_back((unsigned long long)(unsigned)pairLog[k] << 32 | (unsigned)entries.size());
				entries.push_back(log[k]);
			}
		}
		if (keys.size()) std::sort(&keys[0], &keys[0] + keys.size());
		for (int k = 0; k < keys.size(); ++k) replayOne(entries[int(keys[k] & 0xffffffffu)], affinity.owners);
	}
	else
		for (int c = 0; c < numChunks; ++c)
		{
			const ManifoldOpLog& log = m_batchManifoldsPtr[c];
			for (int k = 0; k < log.size(); ++k) replayOne(log[k], affinity.owners);
		}
	// Manifolds made since: no owner yet.
	affinity.owners.resize(m_manifoldsPtr.size(), caliber::kNoManifoldOwner);
	if (!softPairsLeft.load()) return;
	btNearCallback nearCallback = getNearCallback();
	for (int i = 0; i < numPairs; ++i)
		if (involvesSoftBody(pairs[i])) (*nearCallback)(pairs[i], *this, info);
}

namespace caliber
{
namespace
{
std::atomic<bool> g_narrowphaseAffinity(false);
}

void setNarrowphaseAffinity(bool on) { g_narrowphaseAffinity.store(on, std::memory_order_relaxed); }

bool narrowphaseAffinity() { return g_narrowphaseAffinity.load(std::memory_order_relaxed); }

ManifoldOwnerWriter manifoldOwnerWriter(btDispatcher* dispatcher)
{
	ManifoldOwnerWriter writer;
	if (!dispatcher || !narrowphaseAffinity()) return writer;
	NarrowphaseAffinity* affinity = affinityTable().find(dispatcher);
	if (!affinity || affinity->owners.size() == 0) return writer;
	writer.count = btMin(affinity->owners.size(), dispatcher->getNumManifolds());
	if (writer.count == 0) return writer;
	writer.owners = &affinity->owners[0];
	writer.live = dispatcher->getInternalManifoldPointer();
	return writer;
}

int manifoldOwner(const btDispatcher* dispatcher, const btPersistentManifold* manifold)
{
	if (!dispatcher || !manifold) return -1;
	NarrowphaseAffinity* affinity = affinityTable().find(dispatcher);
	const int index = manifold->m_index1a;
	if (!affinity || index < 0 || index >= affinity->owners.size() || index >= dispatcher->getNumManifolds() ||
	    const_cast<btDispatcher*>(dispatcher)->getManifoldByIndexInternal(index) != manifold)
		return -1;
	const unsigned char owner = affinity->owners[index];
	return owner == kNoManifoldOwner ? -1 : int(owner);
}

void releaseManifoldOwners(const btDispatcher* dispatcher) { affinityTable().release(dispatcher); }
}  // namespace caliber
