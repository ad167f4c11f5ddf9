// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDbvtBroadphase: two btDbvt trees, fat boxes, pair search only for proxies whose box changed.
//
// The invariant kept by collide(): the cache holds exactly the filtered pairs whose tree boxes overlap.
// A pair's status can only change when one of its two boxes changes, and every box change queues the
// proxy (stage DYNAMIC_SET / FIXED_SET). collide() therefore (1) queries both trees with each queued
// proxy's box and adds what it finds, (2) drops the pairs of queued proxies whose boxes no longer
// overlap, and (3) marks the queued proxies up to date. Pairs of two proxies that did not move are
// neither searched nor checked.

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"

#include <atomic>
#include <cstdio>
#include <new>
#include <typeinfo>

#include "BulletCollision/BroadphaseCollision/btDbvtAabbFastPath.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBoxWalk.h"
#include "BulletCollision/BroadphaseCollision/btPairCacheUtil.h"
#include "BulletCollision/BroadphaseCollision/btDbvtProxyIds.h"
#include "BulletCollision/BroadphaseCollision/btDbvtRayWalk.h"
#include "BulletCollision/BroadphaseCollision/btDbvtRefit.h"
#include "BulletCollision/BroadphaseCollision/btDbvtQueries.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "LinearMath/btAabbUtil2.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btSideTable.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/TaskScheduler/btParallelChunks.h"

btScalar gDbvtMargin = btScalar(0.05);

namespace
{
// Levels above its old place from which a moved dynamic leaf is re-inserted (see the constructor).
const int kDynamicLookahead = 4;

SIMD_FORCE_INLINE btDbvtProxy* proxyOfLeaf(const btDbvtNode* leaf) { return static_cast<btDbvtProxy*>(leaf->data); }

SIMD_FORCE_INLINE bool isPending(const btDbvtProxy* proxy) { return proxy->stage != btDbvtBroadphase::STAGECOUNT; }

// Tree query policy of the pair search: adds (proxy, other) for every leaf the query box overlaps. When
// both proxies are pending, both searches find the pair; only the one with the lower id adds it.
struct PairSearchPolicy
{
	btDbvtProxy* proxy;
	btOverlappingPairCache* cache;

	void Process(const btDbvtNode* leaf)
	{
		btDbvtProxy* other = proxyOfLeaf(leaf);
		if (other == proxy) return;
		if (isPending(other) && other->m_uniqueId < proxy->m_uniqueId) return;
		cache->addOverlappingPair(proxy, other);
	}
};

// Puts the proxy at the head of stage list `stage`.
void linkProxy(btDbvtBroadphase& broadphase, btDbvtProxy* proxy, int stage)
{
	btDbvtProxy*& root = broadphase.m_stageRoots[stage];
	proxy->stage = stage;
	proxy->links[0] = 0;
	proxy->links[1] = root;
	if (root) root->links[0] = proxy;
	root = proxy;
}

// Takes the proxy out of its stage list.
void unlinkProxy(btDbvtBroadphase& broadphase, btDbvtProxy* proxy)
{
	if (proxy->links[0])
		proxy->links[0]->links[1] = proxy->links[1];
	else
		broadphase.m_stageRoots[proxy->stage] = proxy->links[1];
	if (proxy->links[1]) proxy->links[1]->links[0] = proxy->links[0];
	proxy->links[0] = proxy->links[1] = 0;
}

// Queues a moved proxy's pair search (and counts a fixed move for the fixed tree's re-optimisation).
SIMD_FORCE_INLINE void queueProxy(btDbvtBroadphase& broadphase, btDbvtProxy* proxy)
{
	const int tree = caliber::dbvtTreeOf(*proxy);
	if (tree == btDbvtBroadphase::FIXED_SET) ++broadphase.m_fixedleft;
	if (!isPending(proxy))
	{
		unlinkProxy(broadphase, proxy);
		linkProxy(broadphase, proxy, tree);
	}
	broadphase.m_needcleanup = true;
}

// What setAabb does before the tree: stores the proxy's AABB; false when it still fits in the fat box, else
// true with the new tree box (fat, and stretched along the move) in box.
SIMD_FORCE_INLINE bool storeAabbAndFatBox(const btDbvtBroadphase& broadphase, btDbvtProxy* proxy,
                                          const btVector3& aabbMin, const btVector3& aabbMax, btDbvtVolume& box)
{
	box = btDbvtVolume::FromMM(aabbMin, aabbMax);
	const btVector3 displacement = box.Center() - (proxy->m_aabbMin + proxy->m_aabbMax) * btScalar(0.5);
	proxy->m_aabbMin = aabbMin;
	proxy->m_aabbMax = aabbMax;
	if (proxy->leaf->volume.Contain(box)) return false;  // still inside its fat box: pairs cannot change
	box.Expand(btVector3(gDbvtMargin, gDbvtMargin, gDbvtMargin));
	box.SignedExpand(displacement * broadphase.m_prediction);
	return true;
}

// Moves the proxy's tree box to `box` and queues its pair search. A moving leaf still next to its sibling is
// refitted in place (the common case: most of a pile or a ragdoll moves together), others are re-inserted.
// Returns true when the leaf was re-inserted, false when it was refitted in place.
bool moveLeaf(btDbvtBroadphase& broadphase, btDbvtProxy* proxy, btDbvtVolume& box)
{
	const int tree = caliber::dbvtTreeOf(*proxy);
	const bool reinserted = tree != btDbvtBroadphase::DYNAMIC_SET || !caliber::refitLeafNearSibling(proxy->leaf, box);
	if (reinserted) broadphase.m_sets[tree].update(proxy->leaf, box);
	queueProxy(broadphase, proxy);
	return reinserted;
}

// The pair search's query stack on the C++ stack: one entry per fork on the walk's path, so trees up to 64
// levels deep never spill to the heap.
const int kPairQueryInlineStack = 64;

// Adds the pairs of one pending proxy with every proxy whose box overlaps its box.
void searchPairs(btDbvtBroadphase& broadphase, btDbvtProxy* proxy)
{
	PairSearchPolicy policy;
	policy.proxy = proxy;
	policy.cache = broadphase.m_paircache;
	const btDbvtVolume& box = proxy->leaf->volume;
	btDbvt& dynamicSet = broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET];
	btDbvt& fixedSet = broadphase.m_sets[btDbvtBroadphase::FIXED_SET];
	caliber::collideTVInTreeOrder<kPairQueryInlineStack>(dynamicSet.m_root, box, policy);
	caliber::collideTVInTreeOrder<kPairQueryInlineStack>(fixedSet.m_root, box, policy);
}

// The pair search on the task scheduler's threads: each chunk of pending proxies queries the trees (which
// nothing changes meanwhile) and lists what it finds, proxy by proxy in tree order; the calling thread
// then adds the lists in chunk order. The cache sees the same additions in the same order as in the
// serial search, so it ends the same, whatever the thread count.
const int kProxiesPerSearchTask = 32;
// Fewer pending proxies than this are searched serially (a loop on the threads costs about a microsecond).
const int kMinProxiesForParallelSearch = 128;

// A chunk's list, padded so that two chunks' array headers (written at every push by different threads)
// never share a cache line.
struct ChunkLists
{
	btAlignedObjectArray<btDbvtProxy*> found;  // proxy, other, proxy, other, ...
	char padding[128];
};

// A task's part of the parallel tree moves (moveProxiesToFatBoxes), padded like ChunkLists.
struct SubtreeTask
{
	caliber::DbvtUndoLog log;
	btAlignedObjectArray<int> moves;                  // the moves it made, in order
	btAlignedObjectArray<int> marks;                  // the log's size before each
	btAlignedObjectArray<caliber::DbvtTopStep> tops;  // what each leaves to the nodes above the subtrees
	btAlignedObjectArray<btDbvtProxy*> proxies;       // DbvtMoveRound: each move's proxy
	char padding[128];
};

// The broadphase's state that Bullet's class does not declare (one side-table entry per broadphase).
struct PairSearchScratch
{
	// Destroyed proxies, kept (linked through links[1], leaf null) for reuse by createProxy: a second
	// destroyProxy or a setAabb of a destroyed proxy is then caught instead of touching freed memory.
	btDbvtProxy* freeProxies = 0;
	btAlignedObjectArray<btDbvtProxy*> pending;
	btAlignedObjectArray<ChunkLists> chunks;
	// moveProxiesToFatBoxes: each move's subtree (-1: it runs alone) and each subtree task's undo log and
	// the moves it made (with the log's size before each).
	btAlignedObjectArray<int> moveSubtrees;
	btAlignedObjectArray<SubtreeTask> subtreeTasks;
	caliber::DbvtUndoLog topLog;     // the replayed steps above the subtrees of the current move
	caliber::DbvtTopView roundView;  // DbvtMoveRound's
};

struct PairListPolicy
{
	btDbvtProxy* proxy;
	btAlignedObjectArray<btDbvtProxy*>* found;
	// Set when the cache is exactly btHashedOverlappingPairCache without a filter callback: adding a pair it
	// already holds, or one the default group test refuses, changes nothing, so such pairs are left off the
	// list here (the cache is only read while the lists are made) and the calling thread adds only new ones.
	btHashedOverlappingPairCache* plainCache;

	void Process(const btDbvtNode* leaf)
	{
		btDbvtProxy* other = proxyOfLeaf(leaf);
		if (other == proxy) return;
		if (isPending(other) && other->m_uniqueId < proxy->m_uniqueId) return;  // as PairSearchPolicy
		if (plainCache && (!caliber::groupMaskAccepts(proxy, other) ||
		                   plainCache->btHashedOverlappingPairCache::findPair(proxy, other) != 0))
			return;
		found->push_back(proxy);
		found->push_back(other);
	}
};

// Loops over chunk numbers (each chunk a fixed run of kProxiesPerSearchTask pending proxies), so a
// scheduler may split the loop anywhere without two threads sharing a chunk's list.
struct ListPairs : public btIParallelForBody
{
	const btDbvt* dynamicSet;
	const btDbvt* fixedSet;
	PairSearchScratch* scratch;
	btHashedOverlappingPairCache* plainCache;  // see PairListPolicy

	void forLoop(int chunkBegin, int chunkEnd) const override
	{
		const int numPending = scratch->pending.size();
		for (int chunk = chunkBegin; chunk < chunkEnd; ++chunk)
		{
			btAlignedObjectArray<btDbvtProxy*>& found = scratch->chunks[chunk].found;
			found.resize(0);
			PairListPolicy policy;
			policy.found = &found;
			policy.plainCache = plainCache;
			const int end = btMin(numPending, (chunk + 1) * kProxiesPerSearchTask);
			for (int i = chunk * kProxiesPerSearchTask; i < end; ++i)
			{
				policy.proxy = scratch->pending[i];
				const btDbvtVolume& box = policy.proxy->leaf->volume;
				caliber::collideTVInTreeOrder<kPairQueryInlineStack>(dynamicSet->m_root, box, policy);
				caliber::collideTVInTreeOrder<kPairQueryInlineStack>(fixedSet->m_root, box, policy);
			}
		}
	}
};

// A pair is stale when its tree boxes no longer overlap; only pairs with a pending proxy can have become
// stale since the last collide (onlyPending), unless pairs were added to the cache by hand.
SIMD_FORCE_INLINE bool isStalePair(const btBroadphasePair& pair, bool onlyPending)
{
	const btDbvtProxy* proxy0 = static_cast<const btDbvtProxy*>(pair.m_pProxy0);
	const btDbvtProxy* proxy1 = static_cast<const btDbvtProxy*>(pair.m_pProxy1);
	if (onlyPending && !isPending(proxy0) && !isPending(proxy1)) return false;
	return !Intersect(proxy0->leaf->volume, proxy1->leaf->volume);
}

// Lists the stale pairs of the cache's array in fixed chunks of pairs, one list per chunk (read in chunk
// order afterwards, so the list is the array's order whatever the thread count). The loop runs over chunk
// numbers, so a scheduler may split it anywhere without two threads sharing a chunk.
const int kPairsPerStaleTask = 1024;

struct ListStalePairs : public btIParallelForBody
{
	const btBroadphasePair* pairs;
	int count;
	PairSearchScratch* scratch;
	bool onlyPending;

	void forLoop(int chunkBegin, int chunkEnd) const override
	{
		for (int c = chunkBegin; c < chunkEnd; ++c)
		{
			btAlignedObjectArray<btDbvtProxy*>& found = scratch->chunks[c].found;
			found.resize(0);
			const int end = btMin(count, (c + 1) * kPairsPerStaleTask);
			for (int i = c * kPairsPerStaleTask; i < end; ++i)
			{
				if (!isStalePair(pairs[i], onlyPending)) continue;
				found.push_back(static_cast<btDbvtProxy*>(pairs[i].m_pProxy0));
				found.push_back(static_cast<btDbvtProxy*>(pairs[i].m_pProxy1));
			}
		}
	}
};

// Removes the stale pairs: a scan of the cache's array (on the scheduler's threads when it is long) lists
// them, then they are removed in array order on this thread. The scan only reads the proxies and their
// leaves; the removals (which move the array's last pair into the hole and release algorithms) stay serial.
void removeStalePairs(btDbvtBroadphase& broadphase, PairSearchScratch& scratch, bool onlyPending,
                      btDispatcher* dispatcher)
{
	btOverlappingPairCache* cache = broadphase.m_paircache;
	const btBroadphasePairArray& pairs = cache->getOverlappingPairArray();
	const int count = pairs.size();
	if (count == 0) return;
	const int chunks = (count + kPairsPerStaleTask - 1) / kPairsPerStaleTask;
	if (scratch.chunks.size() < chunks) scratch.chunks.resize(chunks);
	ListStalePairs list;
	list.pairs = &pairs[0];
	list.count = count;
	list.scratch = &scratch;
	list.onlyPending = onlyPending;
	btParallelFor(0, chunks, 1, list);
	for (int c = 0; c < chunks; ++c)
	{
		const btAlignedObjectArray<btDbvtProxy*>& found = scratch.chunks[c].found;
		for (int k = 0; k < found.size(); k += 2) cache->removeOverlappingPair(found[k], found[k + 1], dispatcher);
	}
}

// aabbTest: the trees prune with the fat boxes; the proxy's own AABB decides.
struct AabbQueryPolicy
{
	btVector3 queryMin;
	btVector3 queryMax;
	btBroadphaseAabbCallback* callback;

	void Process(const btDbvtNode* leaf)
	{
		const btDbvtProxy* proxy = proxyOfLeaf(leaf);
		if (TestAabbAgainstAabb2(queryMin, queryMax, proxy->m_aabbMin, proxy->m_aabbMax)) callback->process(proxy);
	}
};

// rayTest: the trees prune with the fat boxes (grown by the swept box), nearer boxes first; the proxy's
// own AABB decides. The callback's m_lambda_max is read for every box and proxy, so a closest-hit callback
// that shortens the ray prunes the rest.
struct RayLeafVisitor
{
	const caliber::DbvtRay* ray;
	btBroadphaseRayCallback* callback;

	void operator()(const btDbvtNode* leaf) const
	{
		const btDbvtProxy* proxy = proxyOfLeaf(leaf);
		btScalar enter;
		if (ray->hits(proxy->m_aabbMin, proxy->m_aabbMax, callback->m_lambda_max, enter)) callback->process(proxy);
	}
};

// The parallel tree moves (moveProxiesToFatBoxes). The dynamic tree's nodes kSubtreeDepth levels below the
// root head the subtrees; a task per subtree makes the moves of its leaves in order, within it
// (caliber::moveLeafWithinSubtreeDeferringTop), while the other tasks do theirs: they touch different nodes
// and read none another task changes. What a move would do above its subtree's root (the removal's shrink
// going on up, the growth going past it) is recorded, and the calling thread replays those steps on the
// few nodes above the subtrees in move order after the loop (caliber::replayDbvtTopStep). A move that
// needs a node outside its subtree otherwise (its removal or insertion replaces the subtree's root, its
// re-insertion starts above it) lowers the round's bound to its index, as does, in the replay, a move whose
// rotation above the subtrees would swap a node out of a subtree; the moves at or after the bound that some
// task made anyway are undone, that move runs alone, and the next round starts after it. No task waits for
// another, so any scheduler (one that runs the tasks one after the other included) ends with the serial
// tree.
const int kSubtreeDepth = 2;
const int kMaxSubtrees = 1 << kSubtreeDepth;
// The depth of DbvtMoveRound's subtrees: more subtrees than two threads, so that a thread done with its
// subtrees takes another's.
const int kRoundSubtreeDepth = 2;
static_assert((1 << kRoundSubtreeDepth) <= caliber::DbvtMoveRound::kMaxSubtrees, "DbvtMoveRound's arrays");
static_assert((1 << kRoundSubtreeDepth) <= caliber::DbvtTopView::kMaxSubtrees, "DbvtTopView's arrays");
// Fewer moves than this run in order on the calling thread (a round costs a parallel loop and a walk from
// each leaf to its subtree).
const int kMinMovesPerRound = 32;

// A move made the serial way (moveProxyToFatBox).
SIMD_FORCE_INLINE void moveInOrder(btDbvtBroadphase& broadphase, const caliber::DbvtProxyMove& move)
{
	caliber::moveProxyToFatBox(broadphase, move.proxy, move.fatMin, move.fatMax);
}

struct MoveWithinSubtrees : public btIParallelForBody
{
	btDbvt* tree;
	const btDbvtNode* const* subtrees;
	const caliber::DbvtProxyMove* moves;
	const int* moveSubtrees;
	int begin;
	std::atomic<int>* bound;
	SubtreeTask* tasks;

	void forLoop(int taskBegin, int taskEnd) const override
	{
		for (int task = taskBegin; task < taskEnd; ++task)
		{
			SubtreeTask& scratch = tasks[task];
			scratch.log.resize(0);
			scratch.moves.resize(0);
			scratch.marks.resize(0);
			scratch.tops.resize(0);
			for (int i = begin;; ++i)
			{
				// The bound only falls; a move at or after its final value is undone afterwards.
				if (i >= bound->load(std::memory_order_relaxed)) break;
				if (moveSubtrees[i] != task) continue;
				const int mark = scratch.log.size();
				btDbvtProxy* proxy = static_cast<btDbvtProxy*>(moves[i].proxy);
				const btDbvtVolume box = btDbvtVolume::FromMM(moves[i].fatMin, moves[i].fatMax);
				caliber::DbvtTopStep top;
				if (!caliber::moveLeafWithinSubtreeDeferringTop(*tree, subtrees[task], proxy->leaf, box, scratch.log,
				                                                top))
				{
					int current = bound->load(std::memory_order_relaxed);
					while (i < current && !bound->compare_exchange_weak(current, i, std::memory_order_relaxed))
					{
					}
					break;
				}
				scratch.moves.push_back(i);
				scratch.marks.push_back(mark);
				scratch.tops.push_back(top);
			}
		}
	}
};

// The nodes kSubtreeDepth levels below the root (a leaf at that depth or above heads no subtree: its entry
// is 0); returns their count.
int findSubtrees(const btDbvt& tree, const btDbvtNode** subtrees, btDbvtNode** topNodes, int& numTopNodes,
                 int depth = kSubtreeDepth)
{
	int count = 1;
	numTopNodes = 0;
	subtrees[0] = tree.m_root;
	for (int level = 0; level < depth; ++level)
	{
		for (int k = count - 1; k >= 0; --k)
		{
			const btDbvtNode* node = subtrees[k];
			if (node && node->isinternal()) topNodes[numTopNodes++] = const_cast<btDbvtNode*>(node);
			subtrees[2 * k] = node && node->isinternal() ? node->childs[0] : 0;
			subtrees[2 * k + 1] = node && node->isinternal() ? node->childs[1] : 0;
		}
		count *= 2;
	}
	for (int k = 0; k < count; ++k)
		if (subtrees[k] && subtrees[k]->isleaf()) subtrees[k] = 0;
	return count;
}

// The subtree of a dynamic leaf, -1 when it heads none (too close to the root).
int subtreeOf(const btDbvtNode* leaf, const btDbvtNode* const subtrees[kMaxSubtrees], int count)
{
	int depth = 0;
	for (const btDbvtNode* node = leaf; node->parent; node = node->parent) ++depth;
	if (depth <= kSubtreeDepth) return -1;
	const btDbvtNode* head = leaf;
	for (int i = depth - kSubtreeDepth; i > 0; --i) head = head->parent;
	for (int k = 0; k < count; ++k)
		if (subtrees[k] == head) return k;
	return -1;
}

bool finiteAabb(const btVector3& aabbMin, const btVector3& aabbMax)
{
	return caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
}
}  // namespace

btDbvtBroadphase::btDbvtBroadphase(btOverlappingPairCache* paircache)
    : m_paircache(paircache),
      m_prediction(btScalar(1)),
      m_stageCurrent(0),
      m_fupdates(1),
      m_dupdates(1),
      m_cupdates(10),
      m_newpairs(0),
      m_fixedleft(0),
      m_updates_call(0),
      m_updates_done(0),
      m_updates_ratio(0),
      m_pid(0),
      m_cid(0),
      m_gid(0),
      m_releasepaircache(paircache == 0),
      m_deferedcollide(false),
      m_needcleanup(false)
{
	if (!m_paircache)
	{
		void* memory = btAlignedAlloc(sizeof(btHashedOverlappingPairCache), 16);
		m_paircache = new (memory) btHashedOverlappingPairCache();
	}
	for (int i = 0; i <= STAGECOUNT; ++i) m_stageRoots[i] = 0;
	m_rayTestStacks.resize(1);
	// A moved leaf is re-inserted from a few levels above its old place: a moving object rarely goes far
	// in one step, and a search of that subtree costs a fraction of a search from the root (10,000 moving
	// boxes: about half the step time). The incremental optimisation repairs what this misses.
	m_sets[DYNAMIC_SET].m_lkhd = kDynamicLookahead;
}

btDbvtBroadphase::~btDbvtBroadphase()
{
	// Proxies the user did not destroy are freed here (their pairs die with the cache or stay in a cache
	// the user owns, as in Bullet).
	for (int stage = 0; stage <= STAGECOUNT; ++stage)
	{
		btDbvtProxy* proxy = m_stageRoots[stage];
		while (proxy)
		{
			btDbvtProxy* next = proxy->links[1];
			proxy->~btDbvtProxy();
			btAlignedFree(proxy);
			proxy = next;
		}
		m_stageRoots[stage] = 0;
	}
	btDbvtProxy*& freeProxies = caliber::sideTable<PairSearchScratch>().acquire(this).freeProxies;
	while (freeProxies)
	{
		btDbvtProxy* next = freeProxies->links[1];
		freeProxies->~btDbvtProxy();
		btAlignedFree(freeProxies);
		freeProxies = next;
	}
	caliber::sideTable<PairSearchScratch>().release(this);
	if (m_releasepaircache)
	{
		m_paircache->~btOverlappingPairCache();
		btAlignedFree(m_paircache);
	}
}

btBroadphaseProxy* btDbvtBroadphase::createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int shapeType,
                                                 void* userPtr, int collisionFilterGroup, int collisionFilterMask,
                                                 btDispatcher* dispatcher)
{
	(void)shapeType;
	(void)dispatcher;
	const bool finite = finiteAabb(aabbMin, aabbMax);
	btAssert(finite && "btDbvtBroadphase::createProxy: non-finite AABB");
	if (!finite) return 0;
	void* memory;
	btDbvtProxy*& freeProxies = caliber::sideTable<PairSearchScratch>().acquire(this).freeProxies;
	if (freeProxies)
	{
		btDbvtProxy* recycled = freeProxies;
		freeProxies = recycled->links[1];
		recycled->~btDbvtProxy();
		memory = recycled;
	}
	else
	{
		memory = btAlignedAlloc(sizeof(btDbvtProxy), 16);
	}
	btDbvtProxy* proxy = new (memory) btDbvtProxy(aabbMin, aabbMax, userPtr, collisionFilterGroup, collisionFilterMask);
	const int tree = (collisionFilterGroup & btBroadphaseProxy::StaticFilter) ? FIXED_SET : DYNAMIC_SET;
	proxy->m_uniqueId = caliber::dbvtProxyId(++m_gid, tree);
	btDbvtVolume box = btDbvtVolume::FromMM(aabbMin, aabbMax);
	// Moving proxies start with the margin (their first small move then costs nothing); static ones get
	// their exact box, which keeps the fixed tree tight.
	if (tree == DYNAMIC_SET)
		box.Expand(btVector3(gDbvtMargin, gDbvtMargin, gDbvtMargin));
	else
		++m_fixedleft;
	proxy->leaf = m_sets[tree].insert(box, proxy);
	linkProxy(*this, proxy, tree);
	m_needcleanup = true;
	return proxy;
}

void btDbvtBroadphase::destroyProxy(btBroadphaseProxy* absproxy, btDispatcher* dispatcher)
{
	if (!absproxy) return;
	btDbvtProxy* proxy = static_cast<btDbvtProxy*>(absproxy);
	btAssert(proxy->leaf && "btDbvtBroadphase::destroyProxy: proxy already destroyed");
	if (!proxy->leaf) return;
	m_sets[caliber::dbvtTreeOf(*proxy)].remove(proxy->leaf);
	unlinkProxy(*this, proxy);
	m_paircache->removeOverlappingPairsContainingProxy(proxy, dispatcher);
	btDbvtProxy*& freeProxies = caliber::sideTable<PairSearchScratch>().acquire(this).freeProxies;
	proxy->leaf = 0;
	proxy->links[0] = 0;
	proxy->links[1] = freeProxies;
	freeProxies = proxy;
}

void btDbvtBroadphase::setAabb(btBroadphaseProxy* absproxy, const btVector3& aabbMin, const btVector3& aabbMax,
                               btDispatcher* dispatcher)
{
	(void)dispatcher;
	btAssert(absproxy && "btDbvtBroadphase::setAabb: null proxy");
	if (!absproxy) return;
	const bool finite = finiteAabb(aabbMin, aabbMax);
	btAssert(finite && "btDbvtBroadphase::setAabb: non-finite AABB");
	if (!finite) return;
	btDbvtProxy* proxy = static_cast<btDbvtProxy*>(absproxy);
	btAssert(proxy->leaf && "btDbvtBroadphase::setAabb: proxy was destroyed");
	if (!proxy->leaf) return;
	++m_updates_call;
	btDbvtVolume box;
	if (!storeAabbAndFatBox(*this, proxy, aabbMin, aabbMax, box)) return;
	++m_updates_done;
	moveLeaf(*this, proxy, box);
}

bool caliber::storeAabbOrFatBox(const btDbvtBroadphase& broadphase, btBroadphaseProxy* proxy, const btVector3& aabbMin,
                                const btVector3& aabbMax, btVector3& fatMin, btVector3& fatMax)
{
	btDbvtVolume box;
	if (!storeAabbAndFatBox(broadphase, static_cast<btDbvtProxy*>(proxy), aabbMin, aabbMax, box)) return false;
	fatMin = box.Mins();
	fatMax = box.Maxs();
	return true;
}

bool caliber::moveProxyToFatBox(btDbvtBroadphase& broadphase, btBroadphaseProxy* proxy, const btVector3& fatMin,
                                const btVector3& fatMax)
{
	++broadphase.m_updates_done;
	btDbvtVolume box = btDbvtVolume::FromMM(fatMin, fatMax);
	return moveLeaf(broadphase, static_cast<btDbvtProxy*>(proxy), box);
}

void caliber::moveProxiesToFatBoxes(btDbvtBroadphase& broadphase, const DbvtProxyMove* moves, int count,
                                    DbvtParallelMoveStats* stats)
{
	DbvtParallelMoveStats unused;
	DbvtParallelMoveStats& counts = stats ? *stats : unused;
	btITaskScheduler* scheduler = btGetTaskScheduler();
	btDbvt& tree = broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET];
	if (count < kMinMovesPerRound || !scheduler || scheduler->getNumThreads() < 2 || tree.m_lkhd < 0 ||
	    caliber::insideParallelBody())
	{
		for (int i = 0; i < count; ++i) moveInOrder(broadphase, moves[i]);
		counts.movesAlone += count;
		return;
	}
	PairSearchScratch& scratch = caliber::sideTable<PairSearchScratch>().acquire(&broadphase);
	scratch.moveSubtrees.resizeNoInitialize(count);
	if (scratch.subtreeTasks.size() < kMaxSubtrees) scratch.subtreeTasks.resize(kMaxSubtrees);
	int next = 0;
	while (next < count)
	{
		const btDbvtNode* subtrees[kMaxSubtrees];
		btDbvtNode* topNodes[kMaxSubtrees];
		int numTopNodes;
		const int numSubtrees = findSubtrees(tree, subtrees, topNodes, numTopNodes);
		int alone = next;  // the first move that runs alone
		for (; alone < count; ++alone)
		{
			const btDbvtProxy* proxy = static_cast<const btDbvtProxy*>(moves[alone].proxy);
			const int subtree = caliber::dbvtTreeOf(*proxy) == btDbvtBroadphase::DYNAMIC_SET
			                        ? subtreeOf(proxy->leaf, subtrees, numSubtrees)
			                        : -1;
			if (subtree < 0) break;
			scratch.moveSubtrees[alone] = subtree;
		}
		int end = alone;
		if (alone - next >= kMinMovesPerRound)
		{
			std::atomic<int> bound(alone);
			MoveWithinSubtrees body;
			body.tree = &tree;
			body.subtrees = subtrees;
			body.moves = moves;
			body.moveSubtrees = &scratch.moveSubtrees[0];
			body.begin = next;
			body.bound = &bound;
			body.tasks = &scratch.subtreeTasks[0];
			caliber::DbvtTopView view;
			view.start(subtrees, numSubtrees);
			btParallelFor(0, numSubtrees, 1, body);
			end = bound.load();
			// The steps above the subtrees, in move order (a move whose step cannot be replayed ends the round
			// there: its top changes are undone here, its subtree changes with the others' below).
			int made[kMaxSubtrees] = {0};
			scratch.topLog.resize(0);
			for (int i = next; i < end; ++i)
			{
				const int task = scratch.moveSubtrees[i];
				SubtreeTask& done = scratch.subtreeTasks[task];
				btAssert(done.moves[made[task]] == i);
				if (!caliber::replayDbvtTopStep(view, task, done.tops[made[task]], scratch.topLog))
				{
					caliber::undoDbvtChanges(scratch.topLog, 0);
					++counts.topStops;
					end = i;
					break;
				}
				scratch.topLog.resize(0);
				++made[task];
			}
			// Undo what the tasks did at or after the bound (each task's moves are in order: one undo each).
			for (int task = 0; task < numSubtrees; ++task)
			{
				SubtreeTask& done = scratch.subtreeTasks[task];
				for (int k = 0; k < done.moves.size(); ++k)
				{
					if (done.moves[k] < end) continue;
					caliber::undoDbvtChanges(done.log, done.marks[k]);
					counts.movesUndone += done.moves.size() - k;
					break;
				}
			}
			// An undone subtree root gets back the parent it had when the round began; the replayed
			// rotations above the subtrees may have given it another.
			for (int k = 0; k < numTopNodes; ++k)
			{
				topNodes[k]->childs[0]->parent = topNodes[k];
				topNodes[k]->childs[1]->parent = topNodes[k];
			}
			++counts.rounds;
			counts.movesOnThreads += end - next;
			// What moveProxyToFatBox does besides the tree, in order.
			for (int i = next; i < end; ++i)
			{
				++broadphase.m_updates_done;
				queueProxy(broadphase, static_cast<btDbvtProxy*>(moves[i].proxy));
			}
		}
		else
		{
			for (int i = next; i < end; ++i) moveInOrder(broadphase, moves[i]);
			counts.movesAlone += end - next;
		}
		if (end < count)
		{
			moveInOrder(broadphase, moves[end]);
			++counts.movesAlone;
		}
		next = end + 1;
	}
}

namespace
{
std::atomic<bool> gSubtreeMovesInWorld(false);
}  // namespace

bool caliber::subtreeMovesInWorld() { return gSubtreeMovesInWorld.load(std::memory_order_relaxed); }

void caliber::setSubtreeMovesInWorld(bool on) { gSubtreeMovesInWorld.store(on, std::memory_order_relaxed); }

bool caliber::DbvtMoveRound::begin(btDbvtBroadphase& broadphase)
{
	m_broadphase = &broadphase;
	m_numSubtrees = 0;
	btDbvt& tree = broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET];
	if (tree.m_lkhd < 0 || !tree.m_root) return false;
	PairSearchScratch& scratch = caliber::sideTable<PairSearchScratch>().acquire(&broadphase);
	m_scratch = &scratch;
	const int count = findSubtrees(tree, m_subtrees, m_topNodes, m_numTopNodes, kRoundSubtreeDepth);
	bool any = false;
	for (int k = 0; k < count; ++k) any |= m_subtrees[k] != 0;
	if (!any) return false;
	m_numSubtrees = count;
	if (scratch.subtreeTasks.size() < count) scratch.subtreeTasks.resize(count);
	for (int k = 0; k < count; ++k)
	{
		SubtreeTask& task = scratch.subtreeTasks[k];
		task.log.resize(0);
		task.moves.resize(0);
		task.marks.resize(0);
		task.tops.resize(0);
		task.proxies.resize(0);
	}
	scratch.roundView.start(m_subtrees, count);
	return true;
}

bool caliber::DbvtMoveRound::moveWithin(int subtree, int slot, btBroadphaseProxy* proxy, const btVector3& fatMin,
                                        const btVector3& fatMax) const
{
	btAssert(subtree >= 0 && subtree < m_numSubtrees && m_subtrees[subtree]);
	SubtreeTask& task = static_cast<PairSearchScratch*>(m_scratch)->subtreeTasks[subtree];
	btAssert(task.moves.size() == 0 || task.moves[task.moves.size() - 1] < slot);
	const int mark = task.log.size();
	caliber::DbvtTopStep top;
	const btDbvtVolume box = btDbvtVolume::FromMM(fatMin, fatMax);
	if (!caliber::moveLeafWithinSubtreeDeferringTop(m_broadphase->m_sets[btDbvtBroadphase::DYNAMIC_SET],
	                                                m_subtrees[subtree], static_cast<btDbvtProxy*>(proxy)->leaf, box,
	                                                task.log, top))
		return false;
	task.moves.push_back(slot);
	task.marks.push_back(mark);
	task.tops.push_back(top);
	task.proxies.push_back(static_cast<btDbvtProxy*>(proxy));
	return true;
}

int caliber::DbvtMoveRound::finish(int end, DbvtParallelMoveStats* stats)
{
	if (m_numSubtrees == 0) return end;
	PairSearchScratch& scratch = *static_cast<PairSearchScratch*>(m_scratch);
	DbvtTopView& view = scratch.roundView;
	// The kept moves in slot order (a merge of the tasks' lists), each with its steps above the subtrees.
	int made[kMaxSubtrees] = {0};
	scratch.topLog.resize(0);
	for (;;)
	{
		int next = -1;
		for (int k = 0; k < m_numSubtrees; ++k)
		{
			const SubtreeTask& task = scratch.subtreeTasks[k];
			if (made[k] < task.moves.size() && task.moves[made[k]] < end &&
			    (next < 0 || task.moves[made[k]] < scratch.subtreeTasks[next].moves[made[next]]))
				next = k;
		}
		if (next < 0) break;
		SubtreeTask& task = scratch.subtreeTasks[next];
		if (!caliber::replayDbvtTopStep(view, next, task.tops[made[next]], scratch.topLog))
		{
			caliber::undoDbvtChanges(scratch.topLog, 0);
			if (stats) ++stats->topStops;
			end = task.moves[made[next]];
			break;
		}
		scratch.topLog.resize(0);
		// What moveProxyToFatBox does besides the tree.
		++m_broadphase->m_updates_done;
		queueProxy(*m_broadphase, task.proxies[made[next]]);
		++made[next];
	}
	// Undo what the tasks did at or after end (each task's moves are in order: one undo each), then give
	// the subtree roots back the parents the replayed rotations chose.
	int kept = 0;
	for (int k = 0; k < m_numSubtrees; ++k)
	{
		SubtreeTask& task = scratch.subtreeTasks[k];
		kept += made[k];
		if (made[k] < task.moves.size())
		{
			caliber::undoDbvtChanges(task.log, task.marks[made[k]]);
			if (stats) stats->movesUndone += task.moves.size() - made[k];
		}
	}
	for (int k = 0; k < m_numTopNodes; ++k)
	{
		m_topNodes[k]->childs[0]->parent = m_topNodes[k];
		m_topNodes[k]->childs[1]->parent = m_topNodes[k];
	}
	if (stats)
	{
		++stats->rounds;
		stats->movesOnThreads += kept;
	}
	m_numSubtrees = 0;
	return end;
}

void btDbvtBroadphase::setAabbForceUpdate(btBroadphaseProxy* absproxy, const btVector3& aabbMin,
                                          const btVector3& aabbMax, btDispatcher* dispatcher)
{
	(void)dispatcher;
	btAssert(absproxy && "btDbvtBroadphase::setAabbForceUpdate: null proxy");
	if (!absproxy) return;
	const bool finite = finiteAabb(aabbMin, aabbMax);
	btAssert(finite && "btDbvtBroadphase::setAabbForceUpdate: non-finite AABB");
	if (!finite) return;
	btDbvtProxy* proxy = static_cast<btDbvtProxy*>(absproxy);
	btAssert(proxy->leaf && "btDbvtBroadphase::setAabbForceUpdate: proxy was destroyed");
	if (!proxy->leaf) return;
	proxy->m_aabbMin = aabbMin;
	proxy->m_aabbMax = aabbMax;
	btDbvtVolume box = btDbvtVolume::FromMM(aabbMin, aabbMax);
	moveLeaf(*this, proxy, box);
}

void btDbvtBroadphase::getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const
{
	btAssert(proxy && "btDbvtBroadphase::getAabb: null proxy");
	if (!proxy)
	{
		aabbMin.setValue(0, 0, 0);
		aabbMax.setValue(0, 0, 0);
		return;
	}
	aabbMin = proxy->m_aabbMin;
	aabbMax = proxy->m_aabbMax;
}

void btDbvtBroadphase::collide(btDispatcher* dispatcher)
{
	if (m_needcleanup)
	{
		const int pairsBefore = m_paircache->getNumOverlappingPairs();
		PairSearchScratch& search = caliber::sideTable<PairSearchScratch>().acquire(this);
		search.pending.resize(0);
		for (int stage = DYNAMIC_SET; stage < STAGECOUNT; ++stage)
			for (btDbvtProxy* proxy = m_stageRoots[stage]; proxy; proxy = proxy->links[1])
				search.pending.push_back(proxy);
		btITaskScheduler* scheduler = btGetTaskScheduler();
		if (search.pending.size() < kMinProxiesForParallelSearch || !scheduler || scheduler->getNumThreads() < 2)
		{
			for (int i = 0; i < search.pending.size(); ++i) searchPairs(*this, search.pending[i]);
		}
		else
		{
			const int chunks = (search.pending.size() + kProxiesPerSearchTask - 1) / kProxiesPerSearchTask;
			if (search.chunks.size() < chunks) search.chunks.resize(chunks);
			ListPairs list;
			list.dynamicSet = &m_sets[DYNAMIC_SET];
			list.fixedSet = &m_sets[FIXED_SET];
			list.scratch = &search;
			list.plainCache = 0;
			if (typeid(*m_paircache) == typeid(btHashedOverlappingPairCache) &&
			    !m_paircache->getOverlapFilterCallback())
				list.plainCache = static_cast<btHashedOverlappingPairCache*>(m_paircache);
			btParallelFor(0, chunks, 1, list);
			for (int c = 0; c < chunks; ++c)
			{
				const btAlignedObjectArray<btDbvtProxy*>& found = search.chunks[c].found;
				for (int k = 0; k < found.size(); k += 2) m_paircache->addOverlappingPair(found[k], found[k + 1]);
			}
		}
		m_newpairs = m_paircache->getNumOverlappingPairs() - pairsBefore;
		// Pairs found above overlap by construction; only older pairs of moved proxies can be stale.
		if (pairsBefore > 0) removeStalePairs(*this, search, true, dispatcher);
		for (int stage = DYNAMIC_SET; stage < STAGECOUNT; ++stage)
		{
			while (btDbvtProxy* proxy = m_stageRoots[stage])
			{
				unlinkProxy(*this, proxy);
				linkProxy(*this, proxy, STAGECOUNT);
			}
		}
		m_needcleanup = false;
	}
	else
	{
		m_newpairs = 0;
	}

	// A few re-insertions per step keep the dynamic tree close to what a rebuild would give as objects
	// drift; the fixed tree only needs them after it changed.
	const int dynamicPasses = 1 + (m_sets[DYNAMIC_SET].m_leaves * m_dupdates) / 100;
	if (m_sets[DYNAMIC_SET].m_leaves > 1)
	{
		m_sets[DYNAMIC_SET].optimizeIncremental(dynamicPasses);
		m_pid += dynamicPasses;
	}
	if (m_fixedleft > 0 && m_sets[FIXED_SET].m_leaves > 1)
	{
		const int fixedPasses = btMin(m_fixedleft, 1 + (m_sets[FIXED_SET].m_leaves * m_fupdates) / 100);
		m_sets[FIXED_SET].optimizeIncremental(fixedPasses);
		m_fixedleft -= fixedPasses;
		m_pid += fixedPasses;
	}
	else
	{
		m_fixedleft = 0;
	}

	m_updates_ratio = m_updates_call > 0 ? btScalar(m_updates_done) / btScalar(m_updates_call) : btScalar(0);
	m_updates_call = 0;
	m_updates_done = 0;
	++m_stageCurrent;
}

void btDbvtBroadphase::calculateOverlappingPairs(btDispatcher* dispatcher) { collide(dispatcher); }

void btDbvtBroadphase::performDeferredRemoval(btDispatcher* dispatcher)
{
	if (m_paircache->getNumOverlappingPairs() == 0) return;
	removeStalePairs(*this, caliber::sideTable<PairSearchScratch>().acquire(this), false, dispatcher);
}

void btDbvtBroadphase::optimize()
{
	m_sets[DYNAMIC_SET].optimizeTopDown();
	m_sets[FIXED_SET].optimizeTopDown();
}

void btDbvtBroadphase::rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
                               const btVector3& aabbMin, const btVector3& aabbMax)
{
	(void)rayTo;  // the callback carries the direction (m_rayDirectionInverse) and the length (m_lambda_max)
	caliber::DbvtRay ray;
	ray.from = rayFrom;
	ray.directionInverse = rayCallback.m_rayDirectionInverse;
	for (int axis = 0; axis < 3; ++axis) ray.signs[axis] = rayCallback.m_signs[axis];
	ray.sweptMin = aabbMin;
	ray.sweptMax = aabbMax;
	ray.prepare();
	RayLeafVisitor visitor = {&ray, &rayCallback};
	const btDbvtNode* roots[2] = {m_sets[DYNAMIC_SET].m_root, m_sets[FIXED_SET].m_root};
	caliber::walkDbvtRayNearestFirst(roots, 2, ray, &rayCallback.m_lambda_max, visitor);
}

void btDbvtBroadphase::aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback)
{
	AabbQueryPolicy policy;
	policy.queryMin = aabbMin;
	policy.queryMax = aabbMax;
	policy.callback = &callback;
	const btDbvtVolume box = btDbvtVolume::FromMM(aabbMin, aabbMax);
	// A stack per call (on the C++ stack): queries may run on several threads at once.
	for (int set = DYNAMIC_SET; set <= FIXED_SET; ++set) m_sets[set].collideTV(m_sets[set].m_root, box, policy);
}

void btDbvtBroadphase::getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const
{
	const btDbvtNode* dynamicRoot = m_sets[DYNAMIC_SET].m_root;
	const btDbvtNode* fixedRoot = m_sets[FIXED_SET].m_root;
	btDbvtVolume bounds;
	if (dynamicRoot && fixedRoot)
		Merge(dynamicRoot->volume, fixedRoot->volume, bounds);
	else if (dynamicRoot)
		bounds = dynamicRoot->volume;
	else if (fixedRoot)
		bounds = fixedRoot->volume;
	else
		bounds = btDbvtVolume::FromCR(btVector3(0, 0, 0), 0);
	aabbMin = bounds.Mins();
	aabbMax = bounds.Maxs();
}

void btDbvtBroadphase::resetPool(btDispatcher* dispatcher)
{
	(void)dispatcher;
	if (m_sets[DYNAMIC_SET].m_leaves + m_sets[FIXED_SET].m_leaves != 0) return;
	m_sets[DYNAMIC_SET].clear();
	m_sets[FIXED_SET].clear();
	m_sets[DYNAMIC_SET].m_lkhd = kDynamicLookahead;  // clear() restores the tree's default
	for (int i = 0; i <= STAGECOUNT; ++i) m_stageRoots[i] = 0;
	m_stageCurrent = 0;
	m_newpairs = 0;
	m_fixedleft = 0;
	m_updates_call = 0;
	m_updates_done = 0;
	m_updates_ratio = 0;
	m_pid = 0;
	m_cid = 0;
	m_gid = 0;
	m_needcleanup = false;
}

void btDbvtBroadphase::printStats()
{
	std::printf("btDbvtBroadphase: %d dynamic (depth %d), %d fixed (depth %d), %d pairs, update ratio %.3f\n",
	            m_sets[DYNAMIC_SET].m_leaves, btDbvt::maxdepth(m_sets[DYNAMIC_SET].m_root), m_sets[FIXED_SET].m_leaves,
	            btDbvt::maxdepth(m_sets[FIXED_SET].m_root), m_paircache->getNumOverlappingPairs(),
	            double(m_updates_ratio));
}
