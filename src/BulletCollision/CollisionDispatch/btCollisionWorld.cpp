// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <typeinfo>

#include "BulletCollision/BroadphaseCollision/btDbvtAabbFastPath.h"
#include "BulletCollision/CollisionDispatch/btAabbChunkPrologue.h"
#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "BulletCollision/CollisionShapes/btShapeGuards.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btIDebugDraw.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btSideTable.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btWarningHook.h"

#if defined(__SSE2__) || defined(__x86_64__)
#include <emmintrin.h>
#endif

// The world's bookkeeping: objects, proxies, AABBs and the discrete collision step. The queries live in
// btCollisionWorldRayTest.cpp, btCollisionWorldConvexSweep.cpp and btCollisionWorldContactTest.cpp, debug
// drawing in btCollisionWorldDebugDraw.cpp.

namespace
{
// Squared AABB diagonal above which a moving object is taken out of the simulation (Bullet's limit: a
// box a million units across has left any sensible scene, and broadphases lose precision there).
const btScalar kMaxAabbExtentSquared = btScalar(1e12);

// True when index names collisionObject in objects (the O(1) membership test the world array index allows).
bool isInWorldArray(const btAlignedObjectArray<btCollisionObject*>& objects, const btCollisionObject* collisionObject)
{
	const int index = collisionObject->getWorldArrayIndex();
	return index >= 0 && index < objects.size() && objects[index] == collisionObject;
}

// The object's world AABB as the broadphase keeps it: the shape's AABB grown by the contact breaking
// threshold (so that contacts are found just before touching). Returns false when the transform or the
// resulting box is not finite (the box is then left unusable).
bool computeBroadphaseAabb(const btCollisionObject* colObj, bool useContinuous, btVector3& aabbMin, btVector3& aabbMax)
{
	const btTransform& worldTransform = colObj->getWorldTransform();
	if (!caliber::isFinite(worldTransform)) return false;
	const btCollisionShape* shape = colObj->getCollisionShape();
	shape->getAabb(worldTransform, aabbMin, aabbMax);
	const btVector3 threshold(gContactBreakingThreshold, gContactBreakingThreshold, gContactBreakingThreshold);
	aabbMin -= threshold;
	aabbMax += threshold;

	// Moving rigid bodies also cover their pose at the end of the step, so that continuous collision
	// detection finds the pairs they sweep through.
	if (useContinuous && colObj->getInternalType() == btCollisionObject::CO_RIGID_BODY &&
	    !colObj->isStaticOrKinematicObject() && caliber::isFinite(colObj->getInterpolationWorldTransform()))
	{
		btVector3 endMin, endMax;
		shape->getAabb(colObj->getInterpolationWorldTransform(), endMin, endMax);
		endMin -= threshold;
		endMax += threshold;
		aabbMin.setMin(endMin);
		aabbMax.setMax(endMax);
	}
	return caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
}

// The worlds that have given the "AABB overflow" warning: each world gives it once. Kept here rather than
// in btCollisionWorld so that the class has Bullet's members only; it is touched only when an object
// overflows and when a world that warned is destroyed, so a locked list is enough.
class AabbOverflowReports
{
public:
	// True the first time it is asked for world (until forget(world)).
	bool firstFor(const btCollisionWorld* world)
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		if (m_worlds.findLinearSearch(world) < m_worlds.size()) return false;
		m_worlds.push_back(world);
		return true;
	}
	// A destroyed world's address may be reused by a new world, which must warn again.
	void forget(const btCollisionWorld* world)
	{
		std::lock_guard<std::mutex> lock(m_mutex);
		m_worlds.remove(world);
	}

private:
	std::mutex m_mutex;
	btAlignedObjectArray<const btCollisionWorld*> m_worlds;
};

// Never destroyed, so that a world destroyed during static destruction can still forget itself.
AabbOverflowReports& aabbOverflowReports()
{
	static AabbOverflowReports* reports = new AabbOverflowReports;
	return *reports;
}
// One object's new box, computed on any thread (status: 0 no update, 1 box ready, 2 overflow, 3 stored in the
// dbvt proxy, 4 stored and the new tree box in aabbMin / aabbMax).
struct PendingAabb
{
	btVector3 aabbMin, aabbMax;
	int status;
};

// Per world, reused from step to step.
struct CollisionWorldScratch
{
	btAlignedObjectArray<PendingAabb> pending;
	// The pipelined box updates' chunk states (see AabbPipeline): 0 free, 1 taken, 2 computed.
	std::unique_ptr<std::atomic<int>[]> chunkStates;
	int chunkCapacity = 0;
	// The subtree of each object's leaf in the parallel tree moves (BoxesAndSubtreeMoves), -1 for none.
	btAlignedObjectArray<int> subtreeOfObject;
	btAlignedObjectArray<const btDbvtNode*> walkStack;
	caliber::DbvtMoveRound moveRound;
	// The last two pipelined updateAabbs' weighted tree moves ([0] the last; moveWeight) and the last one's
	// count of boxes stored in proxies: the prologue's hand-over decision (handPrologueToBoxLoop).
	long long lastMoveWeights[2] = {0, 0};
	int lastBoxes = 0;
};

}  // namespace

btCollisionWorld::btCollisionWorld(btDispatcher* dispatcher, btBroadphaseInterface* broadphasePairCache,
                                   btCollisionConfiguration* collisionConfiguration)
    : m_dispatcher1(dispatcher),
      m_broadphasePairCache(broadphasePairCache),
      m_debugDrawer(0),
      m_forceUpdateAllAabbs(true)
{
	(void)collisionConfiguration;
	btAssert(dispatcher && "btCollisionWorld: null dispatcher");
	btAssert(broadphasePairCache && "btCollisionWorld: null broadphase");
}

btCollisionWorld::~btCollisionWorld()
{
	aabbOverflowReports().forget(this);
	caliber::sideTable<CollisionWorldScratch>().release(this);
	// The objects belong to the user and may outlive the world; their proxies belong to the broadphase,
	// which may be reused, so they go now.
	for (int i = 0; i < m_collisionObjects.size(); i++)
	{
		btCollisionObject* collisionObject = m_collisionObjects[i];
		btBroadphaseProxy* proxy = collisionObject->getBroadphaseHandle();
		if (proxy && m_broadphasePairCache)
		{
			m_broadphasePairCache->getOverlappingPairCache()->cleanProxyFromPairs(proxy, m_dispatcher1);
			m_broadphasePairCache->destroyProxy(proxy, m_dispatcher1);
		}
		collisionObject->setBroadphaseHandle(0);
		collisionObject->setWorldArrayIndex(-1);
	}
}

void btCollisionWorld::addCollisionObject(btCollisionObject* collisionObject, int collisionFilterGroup,
                                          int collisionFilterMask)
{
	btAssert(collisionObject && "btCollisionWorld::addCollisionObject: null object");
	if (!collisionObject) return;
	btAssert(collisionObject->getCollisionShape() && "btCollisionWorld::addCollisionObject: object without shape");
	if (!collisionObject->getCollisionShape()) return;
	const bool alreadyAdded = isInWorldArray(m_collisionObjects, collisionObject);
	btAssert(!alreadyAdded && "btCollisionWorld::addCollisionObject: object added twice");
	if (alreadyAdded) return;

	collisionObject->setWorldArrayIndex(m_collisionObjects.size());
	m_collisionObjects.push_back(collisionObject);

	btVector3 aabbMin, aabbMax;
	const bool finite = computeBroadphaseAabb(collisionObject, false, aabbMin, aabbMax);
	btAssert(finite && "btCollisionWorld::addCollisionObject: non-finite transform or AABB");
	if (!finite || !m_broadphasePairCache)
	{
		// Kept in the world (so that remove works) but without a proxy: no pairs, no query hits.
		collisionObject->setBroadphaseHandle(0);
		collisionObject->forceActivationState(DISABLE_SIMULATION);
		return;
	}
	const int shapeType = collisionObject->getCollisionShape()->getShapeType();
	btBroadphaseProxy* proxy = m_broadphasePairCache->createProxy(
	    aabbMin, aabbMax, shapeType, collisionObject, collisionFilterGroup, collisionFilterMask, m_dispatcher1);
	collisionObject->setBroadphaseHandle(proxy);
	// A broadphase that refuses the proxy (a full btAxisSweep3 pool) has asserted; the object stays in the
	// world like one with a non-finite AABB.
	if (!proxy) collisionObject->forceActivationState(DISABLE_SIMULATION);
}

void btCollisionWorld::removeCollisionObject(btCollisionObject* collisionObject)
{
	btAssert(collisionObject && "btCollisionWorld::removeCollisionObject: null object");
	if (!collisionObject) return;
	const bool inWorld = isInWorldArray(m_collisionObjects, collisionObject);
	btAssert(inWorld && "btCollisionWorld::removeCollisionObject: object is not in this world");
	if (!inWorld) return;

	btBroadphaseProxy* proxy = collisionObject->getBroadphaseHandle();
	if (proxy && m_broadphasePairCache)
	{
		m_broadphasePairCache->getOverlappingPairCache()->cleanProxyFromPairs(proxy, m_dispatcher1);
		m_broadphasePairCache->destroyProxy(proxy, m_dispatcher1);
	}
	collisionObject->setBroadphaseHandle(0);

	// Swap with the last object so that removal is O(1); the moved object learns its new index.
	const int index = collisionObject->getWorldArrayIndex();
	const int last = m_collisionObjects.size() - 1;
	m_collisionObjects.swap(index, last);
	m_collisionObjects.pop_back();
	if (index < m_collisionObjects.size()) m_collisionObjects[index]->setWorldArrayIndex(index);
	collisionObject->setWorldArrayIndex(-1);
}

void btCollisionWorld::refreshBroadphaseProxy(btCollisionObject* collisionObject)
{
	btAssert(collisionObject && "btCollisionWorld::refreshBroadphaseProxy: null object");
	if (!collisionObject || !m_broadphasePairCache) return;
	btBroadphaseProxy* proxy = collisionObject->getBroadphaseHandle();
	if (!proxy) return;
	const int group = proxy->m_collisionFilterGroup;
	const int mask = proxy->m_collisionFilterMask;
	m_broadphasePairCache->getOverlappingPairCache()->cleanProxyFromPairs(proxy, m_dispatcher1);
	m_broadphasePairCache->destroyProxy(proxy, m_dispatcher1);
	collisionObject->setBroadphaseHandle(0);

	btVector3 aabbMin, aabbMax;
	if (!computeBroadphaseAabb(collisionObject, false, aabbMin, aabbMax)) return;
	const int shapeType = collisionObject->getCollisionShape()->getShapeType();
	collisionObject->setBroadphaseHandle(
	    m_broadphasePairCache->createProxy(aabbMin, aabbMax, shapeType, collisionObject, group, mask, m_dispatcher1));
}

void btCollisionWorld::updateSingleAabb(btCollisionObject* colObj)
{
	btAssert(colObj && "btCollisionWorld::updateSingleAabb: null object");
	if (!colObj || !colObj->getCollisionShape()) return;

	btVector3 aabbMin, aabbMax;
	const bool finiteTransform = caliber::isFinite(colObj->getWorldTransform());
	btAssert(finiteTransform && "btCollisionWorld::updateSingleAabb: non-finite world transform");
	const bool finite =
	    finiteTransform && computeBroadphaseAabb(colObj, m_dispatchInfo.m_useContinuous, aabbMin, aabbMax);

	// Static and kinematic objects may be as large as the user likes; a moving object whose box has blown
	// up has left the scene (or its simulation diverged), so it stops taking part instead of stalling the
	// broadphase and everything else.
	const bool acceptable =
	    finite && (colObj->isStaticOrKinematicObject() || (aabbMax - aabbMin).length2() < kMaxAabbExtentSquared);
	if (acceptable)
	{
		if (colObj->getBroadphaseHandle() && m_broadphasePairCache)
			m_broadphasePairCache->setAabb(colObj->getBroadphaseHandle(), aabbMin, aabbMax, m_dispatcher1);
		return;
	}

	colObj->forceActivationState(DISABLE_SIMULATION);
	if (aabbOverflowReports().firstFor(this))
	{
		const char* message =
		    "Caliber: overflow in AABB (non-finite or huge), object removed from simulation (DISABLE_SIMULATION)\n";
		btReportWarning(message, m_debugDrawer);
	}
}

namespace
{
// The prologue set for the next updateAabbs on this thread (caliber::setAabbChunkPrologue), and whether an
// updateAabbs took it.
thread_local const btCollisionWorld* t_prologueWorld = 0;
thread_local const caliber::AabbChunkPrologue* t_prologue = 0;
thread_local bool t_prologueTaken = false;

// The prologue set for world, now taken (null when none was set for it).
const caliber::AabbChunkPrologue* takePrologue(const btCollisionWorld* world)
{
	if (!t_prologue || t_prologueWorld != world) return 0;
	const caliber::AabbChunkPrologue* prologue = t_prologue;
	t_prologue = 0;
	t_prologueTaken = true;
	return prologue;
}
}  // namespace

void caliber::setAabbChunkPrologue(const btCollisionWorld* world, const AabbChunkPrologue* prologue)
{
	t_prologueWorld = prologue ? world : 0;
	t_prologue = prologue;
	t_prologueTaken = false;
}

bool caliber::takeAabbChunkPrologueDone(const btCollisionWorld* world)
{
	const bool taken = t_prologueTaken && t_prologueWorld == world;
	t_prologueWorld = 0;
	t_prologue = 0;
	t_prologueTaken = false;
	return taken;
}

namespace
{
// Objects per task of the parallel box computation.
const int kObjectsPerTask = 128;

struct ComputeAabbs : public btIParallelForBody
{
	btCollisionObject* const* objects;
	PendingAabb* pending;
	bool forceAll;
	bool useContinuous;
	// Set when the world's broadphase is exactly btDbvtBroadphase: a box still inside its fat box is stored
	// here (status 3), as setAabb would store it, and the calling thread only counts it; a box that left it
	// is stored too, and its new tree box replaces it in `pending` (status 4): the calling thread only moves
	// the leaf.
	const btDbvtBroadphase* dbvt;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i)
		{
			const btCollisionObject* colObj = objects[i];
			PendingAabb& box = pending[i];
			box.status = 0;
			if (!(forceAll || (colObj->isActive() && !colObj->isStaticObject())) || !colObj->getCollisionShape())
				continue;
			const bool finite = computeBroadphaseAabb(colObj, useContinuous, box.aabbMin, box.aabbMax);
			const bool acceptable = finite && (colObj->isStaticOrKinematicObject() ||
			                                   (box.aabbMax - box.aabbMin).length2() < kMaxAabbExtentSquared);
			box.status = acceptable ? 1 : 2;
			btBroadphaseProxy* proxy = objects[i]->getBroadphaseHandle();
			// A destroyed proxy (null leaf) goes to setAabb, which reports it.
			if (acceptable && dbvt && proxy && static_cast<const btDbvtProxy*>(proxy)->leaf)
				box.status =
				    caliber::storeAabbOrFatBox(*dbvt, proxy, box.aabbMin, box.aabbMax, box.aabbMin, box.aabbMax) ? 4
				                                                                                                 : 3;
		}
	}
};

// Objects per chunk of the pipelined box updates: small, so that the tree moves start early.
const int kObjectsPerPipelinedChunk = 32;
// Pauses (a few microseconds: about what a chunk's boxes take) before a wait for a chunk yields the core.
const int kSpinsBeforeYield = 256;

#if defined(__SSE2__) || defined(__x86_64__)
SIMD_FORCE_INLINE void pipelinePause() { _mm_pause(); }
#else
SIMD_FORCE_INLINE void pipelinePause() {}
#endif

// The boxes of the dbvt broadphase's objects and its tree moves, overlapped. Task 0 walks the objects in
// order and makes their broadphase updates (the tree moves, which depend on the ones before them, so
// stay in object order on one thread); tasks 1.. compute the boxes and fat boxes of one chunk of objects
// each. Task 0 takes each chunk it reaches: if no thread has taken it yet, it computes the chunk itself;
// if one has, it waits for that thread, which is computing it. So the tree moves run while the other
// threads compute the boxes of the objects after them, whatever the scheduler runs where and in what order
// (with one thread, task 0 computes every chunk as it goes). A chunk's boxes read only its objects and
// their own leaves' volumes, which only their own tree moves write: the moves of earlier objects (links
// and inner nodes of the tree, the proxies' stage lists) touch nothing a box computation reads.
struct AabbPipeline : public btIParallelForBody
{
	ComputeAabbs compute;
	std::atomic<int>* chunkStates;
	int numObjects;
	int numChunks;
	int firstHelperTask;  // in [1, numChunks]
	btDbvtBroadphase* dbvt;
	// The work each chunk's objects need before their boxes (caliber::setAabbChunkPrologue), or null.
	const caliber::AabbChunkPrologue* prologue;
	// Written by task 0 only, read after the loop: where it stopped (an object it leaves to the calling
	// thread, or numObjects) and how many boxes it counted as stored.
	mutable int appliedEnd;
	mutable unsigned storedOnThreads;
	mutable int moved;       // the tree moves task 0 made
	mutable int reinserted;  // of them, the re-insertions

	bool take(int chunk) const
	{
		int expected = 0;
		return chunkStates[chunk].compare_exchange_strong(expected, 1, std::memory_order_acq_rel);
	}

	void computeChunk(int chunk) const
	{
		const int begin = chunk * kObjectsPerPipelinedChunk;
		const int end = btMin(numObjects, (chunk + 1) * kObjectsPerPipelinedChunk);
		if (prologue) prologue->prepareObjects(begin, end);
		compute.forLoop(begin, end);
		chunkStates[chunk].store(2, std::memory_order_release);
	}

	// The chunk is being computed by the thread that took it. On a busy machine that thread may have lost
	// its core (perhaps to this one): after a short spin, this thread yields.
	void waitForChunk(int chunk) const
	{
		for (int spin = 0; chunkStates[chunk].load(std::memory_order_acquire) != 2; ++spin)
		{
			if (spin < kSpinsBeforeYield)
				pipelinePause();
			else
				std::this_thread::yield();
		}
	}

	void applyInOrder() const
	{
		for (int chunk = 0; chunk < numChunks; ++chunk)
		{
			if (take(chunk))
				computeChunk(chunk);
			else
				waitForChunk(chunk);
			const int end = btMin(numObjects, (chunk + 1) * kObjectsPerPipelinedChunk);
			for (int i = chunk * kObjectsPerPipelinedChunk; i < end; ++i)
			{
				const PendingAabb& box = compute.pending[i];
				if (box.status == 0) continue;
				if (box.status == 3)
				{
					++storedOnThreads;
					continue;
				}
				if (box.status != 4)
				{
					// A destroyed proxy or an overflow: the calling thread goes on from here, as without
					// the pipeline (its report and quarantine).
					appliedEnd = i;
					return;
				}
				++storedOnThreads;
				++moved;
				if (caliber::moveProxyToFatBox(*dbvt, compute.objects[i]->getBroadphaseHandle(), box.aabbMin,
				                               box.aabbMax))
					++reinserted;
			}
		}
		appliedEnd = numObjects;
	}

	// The chunk of task (1..numChunks): task firstHelperTask has chunk 0, the tasks after it the next chunks,
	// and the tasks before it the last ones. Only an order: every chunk belongs to one task. The thread
	// pool gives its first helper the tasks from about numTasks / threads on (docs/threading.md), so the
	// helper starts with the objects task 0 needs first, and the calling thread, busy with task 0, holds
	// the chunks needed last.
	int chunkOfTask(int task) const
	{
		const int chunk = task - firstHelperTask;
		return chunk >= 0 ? chunk : chunk + numChunks;
	}

	void forLoop(int taskBegin, int taskEnd) const override
	{
		for (int task = taskBegin; task < taskEnd; ++task)
		{
			if (task == 0)
			{
				applyInOrder();
				continue;
			}
			const int chunk = chunkOfTask(task);
			if (take(chunk)) computeChunk(chunk);
		}
	}
};
// The boxes and the tree moves in one loop, the moves on several threads (caliber::DbvtMoveRound). Task k
// walks the objects in order as AabbPipeline's task 0 does, taking each chunk of objects it reaches (its
// boxes computed by this task if no task has taken it yet, else waited for), and makes the moves of the
// objects whose leaves lie in subtree k of the dynamic tree; so the first task to reach a chunk computes
// it, and the moves of different subtrees run at once. The first object that must be updated in order (an
// overflow, a destroyed proxy, a leaf in no subtree, a move that needs a node outside its subtree) lowers
// the bound: no task moves an object at or after it, and the calling thread goes on from it in order after
// the loop. A task waits only for a chunk another task is computing, so any scheduler finishes the loop.
struct BoxesAndSubtreeMoves : public btIParallelForBody
{
	AabbPipeline chunks;  // its chunk states and box computation (take, computeChunk, waitForChunk)
	const caliber::DbvtMoveRound* round;
	const int* subtreeOfObject;
	std::atomic<int>* bound;

	void lowerBound(int i) const
	{
		int current = bound->load(std::memory_order_relaxed);
		while (i < current && !bound->compare_exchange_weak(current, i, std::memory_order_relaxed))
		{
		}
	}

	void walk(int subtree) const
	{
		const ComputeAabbs& compute = chunks.compute;
		for (int chunk = 0; chunk < chunks.numChunks; ++chunk)
		{
			const int begin = chunk * kObjectsPerPipelinedChunk;
			if (begin >= bound->load(std::memory_order_relaxed)) return;
			if (chunks.take(chunk))
				chunks.computeChunk(chunk);
			else
				chunks.waitForChunk(chunk);
			const int end = btMin(chunks.numObjects, begin + kObjectsPerPipelinedChunk);
			for (int i = begin; i < end; ++i)
			{
				const PendingAabb& box = compute.pending[i];
				if (box.status == 0 || box.status == 3) continue;
				if (box.status != 4 || subtreeOfObject[i] < 0)
				{
					lowerBound(i);
					return;
				}
				if (subtreeOfObject[i] != subtree) continue;
				if (i >= bound->load(std::memory_order_relaxed)) return;
				if (!round->moveWithin(subtree, i, compute.objects[i]->getBroadphaseHandle(), box.aabbMin,
				                       box.aabbMax))
				{
					lowerBound(i);
					return;
				}
			}
		}
	}

	void forLoop(int taskBegin, int taskEnd) const override
	{
		for (int task = taskBegin; task < taskEnd; ++task)
			if (round->subtreeRoot(task)) walk(task);
	}
};

// Writes, for each object whose proxy's leaf lies under one of the round's subtrees, that subtree's number
// (the others get -1).
void findSubtreesOfObjects(const caliber::DbvtMoveRound& round, btCollisionObject* const* objects, int numObjects,
                           CollisionWorldScratch& scratch)
{
	scratch.subtreeOfObject.resizeNoInitialize(numObjects);
	for (int i = 0; i < numObjects; ++i) scratch.subtreeOfObject[i] = -1;
	btAlignedObjectArray<const btDbvtNode*>& stack = scratch.walkStack;
	for (int k = 0; k < round.numSubtrees(); ++k)
	{
		if (!round.subtreeRoot(k)) continue;
		stack.resize(0);
		stack.push_back(round.subtreeRoot(k));
		while (stack.size())
		{
			const btDbvtNode* node = stack[stack.size() - 1];
			stack.pop_back();
			if (node->isinternal())
			{
				stack.push_back(node->childs[0]);
				stack.push_back(node->childs[1]);
				continue;
			}
			const btBroadphaseProxy* proxy = static_cast<const btBroadphaseProxy*>(node->data);
			const btCollisionObject* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
			const int index = object ? object->getWorldArrayIndex() : -1;
			// A proxy of another world sharing the broadphase is not this world's to move.
			if (index >= 0 && index < numObjects && objects[index] == object && object->getBroadphaseHandle() == proxy)
				scratch.subtreeOfObject[index] = k;
		}
	}
}

// Instructions, roughly, of a tree re-insertion (moveProxyToFatBox's costly case: removal, a search for the
// new sibling a few levels up, the growth and rotations), of a leaf refitted in place, and of one object's
// prediction and box together; callgrind of the mesh scenes, boxes3000 and ragdolls136 (docs/threading.md,
// "The prediction in the box loop"). Only their ratios matter.
const long long kReinsertionWeight = 1650;
const long long kRefitWeight = 200;
const long long kPredictedBoxWeight = 700;

long long moveWeight(int reinsertions, int refits) { return reinsertions * kReinsertionWeight + refits * kRefitWeight; }

// Whether updateAabbs does its prologue (the prediction) chunk by chunk in the box loop rather than in a
// loop of its own first: only when the tree moves, on one task, would still be the loop's longer side with
// the prologue's work added to the boxes on the other tasks (threads - 1 of them). Judged from counts of
// the last two pipelined steps (boxes, refits, re-insertions), numbers the steps computed, the same at any
// thread count and scheduler; the choice changes only which thread computes what when, not the bits. The
// larger of the two steps' moves, because a body moving steadily leaves its fat box (stretched along its
// motion) every other step: in the mesh scenes the re-insertions go about 990, 2, 990, 2, ... a step, so
// the last step alone would hand the prediction over exactly in the steps with few moves.
bool handPrologueToBoxLoop(const long long lastMoveWeights[2], int lastBoxes, int threads)
{
	const long long moves = btMax(lastMoveWeights[0], lastMoveWeights[1]);
	return moves > 0 && moves * (threads - 1) >= lastBoxes * kPredictedBoxWeight;
}
}  // namespace

void btCollisionWorld::updateAabbs()
{
	BT_PROFILE("updateAabbs");
	const int numObjects = m_collisionObjects.size();
	// A prologue is done chunk by chunk in the tree moves' pipeline only, in the steps handPrologueToBoxLoop
	// picks; every other path and step does it first.
	const caliber::AabbChunkPrologue* prologue = takePrologue(this);
	if (btGetTaskScheduler()->getNumThreads() < 2 || numObjects < 2 * kObjectsPerTask)
	{
		if (prologue) prologue->prepareAll();
		for (int i = 0; i < numObjects; i++)
		{
			btCollisionObject* colObj = m_collisionObjects[i];
			// Static objects got their box when added (and when the user calls updateSingleAabb); sleeping
			// and disabled objects keep theirs.
			if (m_forceUpdateAllAabbs || (colObj->isActive() && !colObj->isStaticObject())) updateSingleAabb(colObj);
		}
		return;
	}
	// With a scheduler: the boxes (the shapes' support work) on its threads, and the broadphase updates in
	// object order, exactly as updateSingleAabb would make them: for the dbvt broadphase itself on one task
	// overlapping the boxes of the later objects (AabbPipeline), or with caliber::subtreeMovesInWorld() on a
	// task per subtree of its dynamic tree (BoxesAndSubtreeMoves), otherwise on this thread after the boxes.
	CollisionWorldScratch& scratch = caliber::sideTable<CollisionWorldScratch>().acquire(this);
	scratch.pending.resizeNoInitialize(numObjects);
	ComputeAabbs compute;
	compute.objects = &m_collisionObjects[0];
	compute.pending = &scratch.pending[0];
	compute.forceAll = m_forceUpdateAllAabbs;
	compute.useContinuous = m_dispatchInfo.m_useContinuous;
	// A user's subclass may do more in setAabb: only the exact class takes the shortcut.
	btDbvtBroadphase* dbvt = m_broadphasePairCache && typeid(*m_broadphasePairCache) == typeid(btDbvtBroadphase)
	                             ? static_cast<btDbvtBroadphase*>(m_broadphasePairCache)
	                             : 0;
	compute.dbvt = dbvt;
	unsigned storedOnThreads = 0;
	int moved = 0;       // tree moves (status 4)
	int reinserted = 0;  // of them, re-insertions
	int applied = 0;
	const bool subtreeMoves = dbvt && caliber::subtreeMovesInWorld() && scratch.moveRound.begin(*dbvt);
	const bool pipelined = dbvt && !subtreeMoves;
	const int threads = btMax(2, btGetTaskScheduler()->getNumThreads());
	if (prologue && !(pipelined && handPrologueToBoxLoop(scratch.lastMoveWeights, scratch.lastBoxes, threads)))
	{
		prologue->prepareAll();
		prologue = 0;
	}
	if (subtreeMoves)
	{
		const int numChunks = (numObjects + kObjectsPerPipelinedChunk - 1) / kObjectsPerPipelinedChunk;
		if (scratch.chunkCapacity < numChunks)
		{
			scratch.chunkStates.reset(new std::atomic<int>[numChunks]);
			scratch.chunkCapacity = numChunks;
		}
		for (int c = 0; c < numChunks; ++c) scratch.chunkStates[c].store(0, std::memory_order_relaxed);
		findSubtreesOfObjects(scratch.moveRound, &m_collisionObjects[0], numObjects, scratch);
		std::atomic<int> bound(numObjects);
		BoxesAndSubtreeMoves loop;
		loop.chunks.compute = compute;
		loop.chunks.chunkStates = scratch.chunkStates.get();
		loop.chunks.numObjects = numObjects;
		loop.chunks.numChunks = numChunks;
		loop.chunks.prologue = 0;
		loop.round = &scratch.moveRound;
		loop.subtreeOfObject = &scratch.subtreeOfObject[0];
		loop.bound = &bound;
		btParallelFor(0, scratch.moveRound.numSubtrees(), 1, loop);
		// The chunks past the bound that no task reached.
		for (int c = 0; c < numChunks; ++c)
			if (scratch.chunkStates[c].load(std::memory_order_acquire) == 0) loop.chunks.computeChunk(c);
		applied = scratch.moveRound.finish(bound.load());
		for (int i = 0; i < applied; ++i)
			if (scratch.pending[i].status >= 3) ++storedOnThreads;
	}
	else if (pipelined)
	{
		// The tree moves overlap the box computation of the objects after them (AabbPipeline).
		const int numChunks = (numObjects + kObjectsPerPipelinedChunk - 1) / kObjectsPerPipelinedChunk;
		if (scratch.chunkCapacity < numChunks)
		{
			scratch.chunkStates.reset(new std::atomic<int>[numChunks]);
			scratch.chunkCapacity = numChunks;
		}
		for (int c = 0; c < numChunks; ++c) scratch.chunkStates[c].store(0, std::memory_order_relaxed);
		AabbPipeline pipeline;
		pipeline.compute = compute;
		pipeline.chunkStates = scratch.chunkStates.get();
		pipeline.numObjects = numObjects;
		pipeline.numChunks = numChunks;
		pipeline.firstHelperTask = btMax(1, btMin(numChunks, (numChunks + 1) / threads));
		pipeline.dbvt = dbvt;
		pipeline.prologue = prologue;
		pipeline.appliedEnd = 0;
		pipeline.storedOnThreads = 0;
		pipeline.moved = 0;
		pipeline.reinserted = 0;
		btParallelFor(0, numChunks + 1, 1, pipeline);
		applied = pipeline.appliedEnd;
		storedOnThreads = pipeline.storedOnThreads;
		moved = pipeline.moved;
		reinserted = pipeline.reinserted;
	}
	else
	{
		btParallelFor(0, numObjects, kObjectsPerTask, compute);
	}
	for (int i = applied; i < numObjects; i++)
	{
		const PendingAabb& box = scratch.pending[i];
		if (box.status == 0) continue;
		if (box.status == 3)
		{
			++storedOnThreads;
			continue;
		}
		btCollisionObject* colObj = m_collisionObjects[i];
		if (box.status == 4)
		{
			// The tree moves stay here, in object order: each re-insertion depends on the ones before it.
			++storedOnThreads;
			++moved;
			if (caliber::moveProxyToFatBox(*dbvt, colObj->getBroadphaseHandle(), box.aabbMin, box.aabbMax))
				++reinserted;
			continue;
		}
		if (box.status == 1)
		{
			if (colObj->getBroadphaseHandle() && m_broadphasePairCache)
				m_broadphasePairCache->setAabb(colObj->getBroadphaseHandle(), box.aabbMin, box.aabbMax, m_dispatcher1);
			continue;
		}
		updateSingleAabb(colObj);  // the overflow: its warning and quarantine, as without a scheduler
	}
	if (dbvt) dbvt->m_updates_call += storedOnThreads;
	if (pipelined)
	{
		scratch.lastMoveWeights[1] = scratch.lastMoveWeights[0];
		scratch.lastMoveWeights[0] = moveWeight(reinserted, moved - reinserted);
		scratch.lastBoxes = static_cast<int>(storedOnThreads);
	}
}

void btCollisionWorld::computeOverlappingPairs()
{
	BT_PROFILE("calculateOverlappingPairs");
	if (m_broadphasePairCache) m_broadphasePairCache->calculateOverlappingPairs(m_dispatcher1);
}

void btCollisionWorld::performDiscreteCollisionDetection()
{
	BT_PROFILE("performDiscreteCollisionDetection");
	updateAabbs();
	computeOverlappingPairs();
	if (m_dispatcher1 && m_broadphasePairCache)
	{
		BT_PROFILE("dispatchAllCollisionPairs");
		m_dispatcher1->dispatchAllCollisionPairs(m_broadphasePairCache->getOverlappingPairCache(), m_dispatchInfo,
		                                         m_dispatcher1);
	}
}
