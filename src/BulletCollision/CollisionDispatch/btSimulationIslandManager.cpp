// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btLoneIslandSink.h"
#include "BulletCollision/CollisionDispatch/btUniteInOrder.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btCountingSortOnThreads.h"
#include "LinearMath/btThreads.h"

#include <atomic>

namespace
{
// The island of a manifold: the tag of whichever body belongs to an island (static ones have -1).
int islandIdOf(const btPersistentManifold* manifold)
{
	const btCollisionObject* body0 = manifold->getBody0();
	const btCollisionObject* body1 = manifold->getBody1();
	const int tag0 = body0 ? body0->getIslandTag() : -1;
	if (tag0 >= 0) return tag0;
	return body1 ? body1->getIslandTag() : -1;
}
}  // namespace

namespace caliber
{
namespace
{
/// The elements findUnions unites for pair (tags[0], tags[1]), or -1 in tags[0] when it unites none.
void unionTagsOf(const btBroadphasePair& pair, int numElements, int* tags)
{
	tags[0] = -1;
	if (!pair.m_pProxy0 || !pair.m_pProxy1) return;
	const btCollisionObject* object0 = static_cast<const btCollisionObject*>(pair.m_pProxy0->m_clientObject);
	const btCollisionObject* object1 = static_cast<const btCollisionObject*>(pair.m_pProxy1->m_clientObject);
	// Static, kinematic and non-responding objects would chain every body resting on them into one
	// island; they only touch islands, never join them.
	if (!object0 || !object1 || !object0->mergesSimulationIslands() || !object1->mergesSimulationIslands()) return;
	const int tag0 = object0->getIslandTag();
	const int tag1 = object1->getIslandTag();
	if (tag0 < 0 || tag0 >= numElements || tag1 < 0 || tag1 >= numElements) return;
	tags[0] = tag0;
	tags[1] = tag1;
}

/// Where each island's manifolds start once grouped, and the grouping's copy of the manifolds: per thread
/// (so that a step allocates nothing once they have grown), not members of the island manager, which
/// Bullet declares without them.
struct IslandGroupingScratch
{
	btAlignedObjectArray<int> bounds;
	btAlignedObjectArray<btPersistentManifold*> ungrouped;
	// The run of lone islands not yet handed to a caliber::LoneIslandSink: their bodies and ids.
	btAlignedObjectArray<btCollisionObject*> loneBodies;
	btAlignedObjectArray<int> loneIds;
	// findUnions's list of the elements each pair unites (filled on the threads).
	btAlignedObjectArray<int> unionTags;
	// Per element of the sorted union-find, whether its object is awake (isActive) after buildIslands, as the
	// sleeping pass on the threads found it; trusted by processIslands only when awakeOwner's
	// buildAndProcessIslands made it and nothing woke an object after the pass (awakeFresh).
	btAlignedObjectArray<unsigned char> awake;
	const btSimulationIslandManager* awakeOwner = nullptr;
	bool awakeFresh = false;
	bool buildingForProcess = false;  // inside buildAndProcessIslands, between its two calls
	bool inUse = false;
	// groupManifoldsByIsland's sort on the threads, and buildIslands' manifold filter on the threads.
	CountingSortScratch manifoldSort;
	CountingSortScratch manifoldFilter;
};

/// buildIslands' manifold filter on the threads, as a counting sort with one key: manifold i is kept (key 0)
/// as the serial loop keeps it (a contact, or empty manifolds not skipped; both bodies; one of them awake; a
/// response needed), and the kept ones keep their order. A manifold where an awake kinematic body pushes
/// would wake the other body, which changes what the later manifolds see: it sets wakes, and the serial
/// loop then runs instead (the filter changes nothing).
struct IslandManifoldKey
{
	btPersistentManifold* const* manifolds;
	btDispatcher* dispatcher;
	bool skipEmpty;
	std::atomic<int>* wakes;
	int operator()(int i) const
	{
		const btPersistentManifold* manifold = manifolds[i];
		if (!manifold || (skipEmpty && manifold->getNumContacts() == 0)) return -1;
		const btCollisionObject* body0 = manifold->getBody0();
		const btCollisionObject* body1 = manifold->getBody1();
		if (!body0 || !body1) return -1;
		const bool awake0 = body0->getActivationState() != ISLAND_SLEEPING;
		const bool awake1 = body1->getActivationState() != ISLAND_SLEEPING;
		if (!awake0 && !awake1) return -1;
		if ((body0->isKinematicObject() && awake0 && body0->hasContactResponse()) ||
		    (body1->isKinematicObject() && awake1 && body1->hasContactResponse()))
			wakes->store(1, std::memory_order_relaxed);
		return dispatcher->needsResponse(body0, body1) ? 0 : -1;
	}
};

struct PlaceIslandManifold
{
	btPersistentManifold* const* manifolds;
	btPersistentManifold** kept;
	void operator()(int i, int, int slot) const { kept[slot] = manifolds[i]; }
};

/// Manifolds worth grouping on the threads (three parallel loops); fewer are grouped on the calling thread.
const int kMinManifoldsOnThreads = 1024;

/// groupManifoldsByIsland's sort on the threads: manifold i's island (-1 for none: left out), with the manifold
/// kept aside for the placement, which rewrites the list.
struct ManifoldIslandKey
{
	btPersistentManifold* const* manifolds;
	btPersistentManifold** ungrouped;
	int numIslands;
	int operator()(int i) const
	{
		btPersistentManifold* manifold = manifolds[i];
		ungrouped[i] = manifold;
		const int islandId = islandIdOf(manifold);
		return islandId < numIslands ? islandId : -1;
	}
};

struct PlaceManifold
{
	btPersistentManifold* const* ungrouped;
	btPersistentManifold** manifolds;
	void operator()(int i, int, int slot) const { manifolds[slot] = ungrouped[i]; }
};

/// Sorts manifolds by island with a counting sort: O(n), and stable, so each island sees its manifolds in
/// the dispatcher's order whatever the number of islands. Manifolds of no valid island are dropped. After
/// it, island i's manifolds are manifolds[bounds[i] .. bounds[i + 1]).
void groupManifoldsByIsland(btAlignedObjectArray<btPersistentManifold*>& manifolds, int numIslands,
                            IslandGroupingScratch& scratch)
{
	btAlignedObjectArray<int>& bounds = scratch.bounds;
	const int numManifolds = manifolds.size();
	const int parts = countingSortParts(numManifolds, kMinManifoldsOnThreads);
	if (parts > 0)
	{
		// The same sort on the threads (the islands' ids read there, a cache miss or two per manifold).
		bounds.resizeNoInitialize(numIslands + 2);
		scratch.ungrouped.resizeNoInitialize(numManifolds);
		ManifoldIslandKey keyOf;
		keyOf.manifolds = &manifolds[0];
		keyOf.ungrouped = &scratch.ungrouped[0];
		keyOf.numIslands = numIslands;
		PlaceManifold place;
		place.ungrouped = &scratch.ungrouped[0];
		place.manifolds = &manifolds[0];
		CountingSortOnThreads<ManifoldIslandKey, PlaceManifold> sort(scratch.manifoldSort, numManifolds, numIslands,
		                                                             parts);
		sort.count(keyOf);
		const int kept = sort.place(place, &bounds[0]);
		bounds[numIslands + 1] = kept;
		manifolds.resize(kept);
		return;
	}
	// Counts go two places up, so that after the prefix sum bounds[i + 1] is island i's first slot, and
	// after the placement, which advances it, the first slot of island i + 1.
	bounds.resize(0);
	bounds.resize(numIslands + 2, 0);
	for (int i = 0; i < numManifolds; ++i)
	{
		const int islandId = islandIdOf(manifolds[i]);
		if (islandId >= 0 && islandId < numIslands) ++bounds[islandId + 2];
	}
	for (int i = 2; i < numIslands + 2; ++i) bounds[i] += bounds[i - 1];
	scratch.ungrouped.resize(0);
	for (int i = 0; i < numManifolds; ++i) scratch.ungrouped.push_back(manifolds[i]);
	manifolds.resize(bounds[numIslands + 1]);
	for (int i = 0; i < numManifolds; ++i)
	{
		btPersistentManifold* manifold = scratch.ungrouped[i];
		const int islandId = islandIdOf(manifold);
		if (islandId < 0 || islandId >= numIslands) continue;
		manifolds[bounds[islandId + 1]++] = manifold;
	}
}

/// Pairs per task of the union pass's filter on the threads, and the fewest pairs worth a loop.
const int kPairsPerUnionTask = 512;

/// The union pass's filter on the threads: for each pair of the cache, the two elements findUnions unites
/// (tags[2 i], tags[2 i + 1]), or -1 in tags[2 i] when the pair unites nothing. Each pair writes only its
/// own two slots, so any split of the loop gives the same list; the unions are then made from it in pair
/// order on the calling thread, as the serial pass makes them.
struct UnionTagsOfPairs : public btIParallelForBody
{
	const btBroadphasePair* pairs;
	int numElements;
	int* tags;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int i = iBegin; i < iEnd; ++i) unionTagsOf(pairs[i], numElements, tags + 2 * i);
	}
};

/// From element start of the sorted union-find, the run of lone islands (one element and no manifold):
/// appends each awake one's object and island id to loneBodies / loneIds (numLone of them so far; awake, when
/// not null, says per element whether its object is awake, without reading the object) and
/// returns the element after the run (start itself when element start is not a lone island). In a loop
/// of its own, so that the walk over thousands of lone bodies keeps its few values in registers.
int gatherLoneRun(const btElement* elements, int start, int numElements, const int* bounds,
                  btCollisionObject* const* objects, int numObjects, const unsigned char* awake,
                  btCollisionObject** loneBodies, int* loneIds, int& numLone)
{
	int n = numLone;
	int i = start;
	while (i < numElements)
	{
		const int islandId = elements[i].m_id;
		if (islandId < 0 || islandId >= numElements || bounds[islandId + 1] != bounds[islandId]) break;
		if (i + 1 < numElements && elements[i + 1].m_id == islandId) break;
		const int objectIndex = elements[i].m_sz;
		++i;
		if (objectIndex < 0 || objectIndex >= numObjects) continue;
		btCollisionObject* object = objects[objectIndex];
		if (awake ? !awake[i - 1] : !object->isActive()) continue;
		loneBodies[n] = object;
		loneIds[n] = islandId;
		++n;
	}
	numLone = n;
	return i;
}

/// buildIslands' sleeping pass over the run of lone islands (one element each) from element start of the
/// sorted union-find, up to element stop at most: each body sleeps unless it must stay awake. Returns the
/// element after the run (start itself when element start's island has more elements). A loop of its own, as
/// gatherLoneRun.
int sleepLoneRun(const btElement* elements, int start, int stop, int numElements, btCollisionObject* const* objects,
                 int numObjects)
{
	int i = start;
	while (i < stop)
	{
		const int islandId = elements[i].m_id;
		if (i + 1 < numElements && elements[i + 1].m_id == islandId) break;
		const int objectIndex = elements[i].m_sz;
		++i;
		if (objectIndex < 0 || objectIndex >= numObjects) continue;
		btCollisionObject* object = objects[objectIndex];
		if (object->getIslandTag() != islandId) continue;
		const int state = object->getActivationState();
		if (state != ACTIVE_TAG && state != DISABLE_DEACTIVATION) object->setActivationState(ISLAND_SLEEPING);
	}
	return i;
}

IslandGroupingScratch& threadIslandGroupingScratch()
{
	static thread_local IslandGroupingScratch scratch;
	return scratch;
}

/// Objects per task of the island stage's per-object passes on the threads (the tags of
/// updateActivationState and storeIslandActivationState, buildIslands' sleeping pass), and the fewest
/// objects worth the loops (4 chunks). boxes3000 has 3001 objects, ragdolls136 about 3000.
const int kObjectsPerIslandTask = 256;

bool objectPassesOnThreads(int numObjects)
{
	const btITaskScheduler* scheduler = btGetTaskScheduler();
	return numObjects >= 4 * kObjectsPerIslandTask && scheduler && scheduler->getNumThreads() > 1 &&
	       !btThreadsAreRunning();
}

/// Where each chunk of kObjectsPerIslandTask objects starts numbering its simulated objects (those that are
/// neither static nor kinematic: the serial passes' running index), chunkStart[c] for chunk c and the total
/// at the end. Kept from step to step (the objects seldom change), and checked by every chunk that uses it.
struct ObjectChunkStarts
{
	btAlignedObjectArray<int> chunkStart;
};

ObjectChunkStarts& threadObjectChunkStarts()
{
	static thread_local ObjectChunkStarts starts;
	return starts;
}

int numObjectChunks(int numObjects) { return (numObjects + kObjectsPerIslandTask - 1) / kObjectsPerIslandTask; }

/// Counts chunk c's simulated objects into counts[c + 1].
struct CountSimulatedObjects : public btIParallelForBody
{
	btCollisionObject* const* objects;
	int numObjects;
	int* counts;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int c = iBegin; c < iEnd; ++c)
		{
			const int end = btMin(numObjects, (c + 1) * kObjectsPerIslandTask);
			int count = 0;
			for (int i = c * kObjectsPerIslandTask; i < end; ++i) count += objects[i]->isStaticOrKinematicObject() ? 0 : 1;
			counts[c + 1] = count;
		}
	}
};

/// updateActivationState's pass over the objects, chunk by chunk: each simulated object's tag is its index
/// among the simulated objects (chunkStart[c] plus those before it in its chunk), every other object's -1.
/// A chunk whose count of simulated objects is not the one chunkStart says sets wrongStarts (and the
/// calling thread then makes the serial pass); every chunk writes only its own objects.
struct NumberSimulatedObjects : public btIParallelForBody
{
	btCollisionObject* const* objects;
	int numObjects;
	const int* chunkStart;
	std::atomic<int>* wrongStarts;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int c = iBegin; c < iEnd; ++c)
		{
			const int end = btMin(numObjects, (c + 1) * kObjectsPerIslandTask);
			int index = chunkStart[c];
			for (int i = c * kObjectsPerIslandTask; i < end; ++i)
			{
				btCollisionObject* object = objects[i];
				object->setIslandTag(object->isStaticOrKinematicObject() ? -1 : index++);
				object->setCompanionId(-1);
				object->setHitFraction(btScalar(1));
			}
			if (index != chunkStart[c + 1]) wrongStarts->store(1, std::memory_order_relaxed);
		}
	}
};

/// The root of element x without changing the union-find (the serial pass's finds halve the paths; the
/// roots are the same, and sortIslands, which flattens every path, leaves the same elements either way).
int rootOf(const btElement* elements, int x)
{
	while (elements[x].m_id != x) x = elements[x].m_id;
	return x;
}

/// storeIslandActivationState's pass over the objects, chunk by chunk: each simulated object's tag becomes
/// its island (the root of its element) and its element's m_sz the object's index. Each chunk writes only its
/// own objects and their elements' m_sz, and reads the elements' m_id, which nothing writes here. A chunk
/// whose count disagrees with chunkStart sets wrongStarts, as above.
struct StoreIslandTags : public btIParallelForBody
{
	btCollisionObject* const* objects;
	int numObjects;
	btElement* elements;
	int numElements;
	const int* chunkStart;
	std::atomic<int>* wrongStarts;

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int c = iBegin; c < iEnd; ++c)
		{
			const int end = btMin(numObjects, (c + 1) * kObjectsPerIslandTask);
			int index = chunkStart[c];
			// Stale starts (another world's numbering, or objects changed since it) could send two chunks to
			// the same element: a chunk writes only inside its own range, and one that overruns it is wrong.
			const int elementEnd = btMin(numElements, chunkStart[c + 1]);
			for (int i = c * kObjectsPerIslandTask; i < end; ++i)
			{
				btCollisionObject* object = objects[i];
				if (!object->isStaticOrKinematicObject() && index < elementEnd)
				{
					object->setIslandTag(rootOf(elements, index));
					elements[index].m_sz = i;
					object->setCompanionId(-1);
					++index;
				}
				else
				{
					if (!object->isStaticOrKinematicObject()) ++index;
					object->setIslandTag(-1);
					object->setCompanionId(-2);
				}
			}
			if (index != chunkStart[c + 1]) wrongStarts->store(1, std::memory_order_relaxed);
		}
	}
};

/// buildIslands' sleeping decision for the island of elements [start, end) of the sorted union-find: the
/// whole island sleeps when none of its objects must stay awake; otherwise its sleeping objects want to
/// sleep again (and their timers restart).
void settleIsland(const btElement* elements, int start, int end, btCollisionObject* const* objects, int numObjects)
{
	const int islandId = elements[start].m_id;
	bool allSleeping = true;
	for (int e = start; e < end; ++e)
	{
		const int objectIndex = elements[e].m_sz;
		if (objectIndex < 0 || objectIndex >= numObjects) continue;
		const btCollisionObject* object = objects[objectIndex];
		if (object->getIslandTag() != islandId) continue;
		const int state = object->getActivationState();
		if (state == ACTIVE_TAG || state == DISABLE_DEACTIVATION) allSleeping = false;
	}
	for (int e = start; e < end; ++e)
	{
		const int objectIndex = elements[e].m_sz;
		if (objectIndex < 0 || objectIndex >= numObjects) continue;
		btCollisionObject* object = objects[objectIndex];
		if (object->getIslandTag() != islandId) continue;
		if (allSleeping)
		{
			object->setActivationState(ISLAND_SLEEPING);
		}
		else if (object->getActivationState() == ISLAND_SLEEPING)
		{
			object->setActivationState(WANTS_DEACTIVATION);
			object->setDeactivationTime(btScalar(0));
		}
	}
}

/// buildIslands' sleeping pass on the threads: chunk c of kObjectsPerIslandTask elements settles every island
/// that starts in it (running past the chunk's end to the island's end). An island's objects are its own, so
/// the islands may be settled in any order with the serial pass's states.
struct SettleIslands : public btIParallelForBody
{
	const btElement* elements;
	int numElements;
	btCollisionObject* const* objects;
	int numObjects;
	unsigned char* awake;  // per element: whether its object is awake after the pass

	void forLoop(int iBegin, int iEnd) const override
	{
		for (int c = iBegin; c < iEnd; ++c)
		{
			const int chunkEnd = btMin(numElements, (c + 1) * kObjectsPerIslandTask);
			int start = c * kObjectsPerIslandTask;
			// The island under way at the chunk's start belongs to the chunk it started in.
			while (start > 0 && start < chunkEnd && elements[start].m_id == elements[start - 1].m_id) ++start;
			const int first = start;
			while (start < chunkEnd)
			{
				// Runs of lone islands (most of a scene of falling bodies) in sleepLoneRun's loop.
				int end = sleepLoneRun(elements, start, chunkEnd, numElements, objects, numObjects);
				if (end != start)
				{
					start = end;
					continue;
				}
				end = start + 1;
				while (end < numElements && elements[end].m_id == elements[start].m_id) ++end;
				settleIsland(elements, start, end, objects, numObjects);
				start = end;
			}
			// The chunk's islands' elements (start is now past the last one), their objects just read.
			for (int e = first; e < start; ++e)
			{
				const int objectIndex = elements[e].m_sz;
				awake[e] = objectIndex >= 0 && objectIndex < numObjects && objects[objectIndex]->isActive() ? 1 : 0;
			}
		}
	}
};
}  // namespace
}  // namespace caliber

btSimulationIslandManager::btSimulationIslandManager() : m_splitIslands(true) {}

btSimulationIslandManager::~btSimulationIslandManager() {}

void btSimulationIslandManager::initUnionFind(int n) { m_unionFind.reset(n); }

void btSimulationIslandManager::findUnions(btDispatcher* dispatcher, btCollisionWorld* colWorld)
{
	(void)dispatcher;
	btAssert(colWorld);
	if (!colWorld || !colWorld->getPairCache()) return;
	btOverlappingPairCache* pairCache = colWorld->getPairCache();
	const int numPairs = pairCache->getNumOverlappingPairs();
	if (numPairs == 0) return;
	const btBroadphasePair* pairs = pairCache->getOverlappingPairArrayPtr();
	const int numElements = m_unionFind.getNumElements();
	const btITaskScheduler* scheduler = btGetTaskScheduler();
	if (numPairs < 2 * caliber::kPairsPerUnionTask || !scheduler || scheduler->getNumThreads() <= 1 ||
	    btThreadsAreRunning())
	{
		int tags[2];
		for (int i = 0; i < numPairs; ++i)
		{
			caliber::unionTagsOf(pairs[i], numElements, tags);
			if (tags[0] >= 0) m_unionFind.unite(tags[0], tags[1]);
		}
		return;
	}
	// The pairs' objects are read on the threads (a cache miss or two per pair); the unions, whose result
	// depends on their order, are made here in pair order.
	caliber::IslandGroupingScratch& scratch = caliber::threadIslandGroupingScratch();
	btAlignedObjectArray<int>& tags = scratch.unionTags;
	tags.resizeNoInitialize(2 * numPairs);
	caliber::UnionTagsOfPairs filter;
	filter.pairs = pairs;
	filter.numElements = numElements;
	filter.tags = &tags[0];
	btParallelFor(0, numPairs, caliber::kPairsPerUnionTask, filter);
	caliber::uniteInOrder(m_unionFind, &tags[0], numPairs);
}

void btSimulationIslandManager::updateActivationState(btCollisionWorld* colWorld, btDispatcher* dispatcher)
{
	btAssert(colWorld);
	if (!colWorld) return;
	btCollisionObjectArray& objects = colWorld->getCollisionObjectArray();
	const int numObjects = objects.size();
	int index = 0;
	if (caliber::objectPassesOnThreads(numObjects))
	{
		// On the threads, chunk by chunk, each chunk numbering from where the last step's count says it starts;
		// when a chunk finds another count (objects added, removed or made static), the chunks are counted
		// first and numbered again.
		btAlignedObjectArray<int>& chunkStart = caliber::threadObjectChunkStarts().chunkStart;
		const int numChunks = caliber::numObjectChunks(numObjects);
		std::atomic<int> wrongStarts(chunkStart.size() == numChunks + 1 ? 0 : 1);
		caliber::NumberSimulatedObjects number;
		number.objects = &objects[0];
		number.numObjects = numObjects;
		number.wrongStarts = &wrongStarts;
		if (!wrongStarts.load())
		{
			number.chunkStart = &chunkStart[0];
			btParallelFor(0, numChunks, 1, number);
		}
		if (wrongStarts.load())
		{
			chunkStart.resize(numChunks + 1);
			chunkStart[0] = 0;
			caliber::CountSimulatedObjects count;
			count.objects = &objects[0];
			count.numObjects = numObjects;
			count.counts = &chunkStart[0];
			btParallelFor(0, numChunks, 1, count);
			for (int c = 0; c < numChunks; ++c) chunkStart[c + 1] += chunkStart[c];
			wrongStarts.store(0);
			number.chunkStart = &chunkStart[0];
			btParallelFor(0, numChunks, 1, number);
			btAssert(!wrongStarts.load());
		}
		index = chunkStart[numChunks];
	}
	else
	{
		for (int i = 0; i < numObjects; ++i)
		{
			btCollisionObject* object = objects[i];
			if (!object->isStaticOrKinematicObject())
				object->setIslandTag(index++);
			else
				object->setIslandTag(-1);
			object->setCompanionId(-1);
			object->setHitFraction(btScalar(1));
		}
	}
	initUnionFind(index);
	findUnions(dispatcher, colWorld);
}

void btSimulationIslandManager::storeIslandActivationState(btCollisionWorld* world)
{
	btAssert(world);
	if (!world) return;
	btCollisionObjectArray& objects = world->getCollisionObjectArray();
	const int numObjects = objects.size();
	const int numElements = m_unionFind.getNumElements();
	btElement* elements = numElements ? &m_unionFind.getElement(0) : 0;
	if (numElements && caliber::objectPassesOnThreads(numObjects))
	{
		// On the threads with the chunks' starts updateActivationState counted (checked by each chunk; the
		// serial pass below when a chunk disagrees, which rewrites every object and element it wrote).
		const btAlignedObjectArray<int>& chunkStart = caliber::threadObjectChunkStarts().chunkStart;
		const int numChunks = caliber::numObjectChunks(numObjects);
		if (chunkStart.size() == numChunks + 1)
		{
			std::atomic<int> wrongStarts(0);
			caliber::StoreIslandTags store;
			store.objects = &objects[0];
			store.numObjects = numObjects;
			store.elements = elements;
			store.numElements = numElements;
			store.chunkStart = &chunkStart[0];
			store.wrongStarts = &wrongStarts;
			btParallelFor(0, numChunks, 1, store);
			if (!wrongStarts.load()) return;
		}
	}
	int index = 0;
	for (int i = 0; i < numObjects; ++i)
	{
		btCollisionObject* object = objects[i];
		if (!object->isStaticOrKinematicObject() && index < numElements)
		{
			object->setIslandTag(caliber::findWithHalving(elements, index));
			// The unions are done, so the set sizes are no longer needed: m_sz now says which object the
			// element stands for, which survives the sort in sortIslands.
			elements[index].m_sz = i;
			object->setCompanionId(-1);
			++index;
		}
		else
		{
			object->setIslandTag(-1);
			object->setCompanionId(-2);
		}
	}
}

void btSimulationIslandManager::buildIslands(btDispatcher* dispatcher, btCollisionWorld* collisionWorld)
{
	btAssert(dispatcher && collisionWorld);
	m_islandmanifold.resize(0);
	if (!dispatcher || !collisionWorld) return;
	btCollisionObjectArray& objects = collisionWorld->getCollisionObjectArray();
	const int numObjects = objects.size();

	m_unionFind.sortIslands();
	const int numElements = m_unionFind.getNumElements();

	// Sleeping is all-or-nothing per island: one object that must stay awake keeps the whole island awake,
	// because its contacts would otherwise push bodies that no longer integrate.
	const btElement* elements = numElements ? &m_unionFind.getElement(0) : 0;
	btCollisionObject* const* objectArray = numObjects ? &objects[0] : 0;
	int islandEnd = numElements;
	// A manager working inside another's island callback on this thread leaves that one's flags alone (and
	// settles its islands on this thread).
	caliber::IslandGroupingScratch& scratch = caliber::threadIslandGroupingScratch();
	const bool ownScratch = !scratch.inUse;
	if (ownScratch)
	{
		scratch.awakeOwner = nullptr;
		scratch.awakeFresh = false;
	}
	if (ownScratch && caliber::objectPassesOnThreads(numElements))
	{
		// Island by island on the threads (each island's objects are its own); the tasks also note which
		// objects are awake after it, for processIslands.
		scratch.awake.resizeNoInitialize(numElements);
		caliber::SettleIslands settle;
		settle.elements = elements;
		settle.numElements = numElements;
		settle.objects = objectArray;
		settle.numObjects = numObjects;
		settle.awake = &scratch.awake[0];
		btParallelFor(0, caliber::numObjectChunks(numElements), 1, settle);
		scratch.awakeOwner = this;
		scratch.awakeFresh = scratch.buildingForProcess;
	}
	else
	{
		islandEnd = 0;
	}
	for (int islandStart = islandEnd; islandStart < numElements; islandStart = islandEnd)
	{
		// Lone bodies (most of a scene of falling bodies): the two passes below in one, run by run (each
		// sleeps unless it must stay awake).
		islandEnd = caliber::sleepLoneRun(elements, islandStart, numElements, numElements, objectArray, numObjects);
		if (islandEnd != islandStart) continue;
		const int islandId = elements[islandStart].m_id;
		islandEnd = islandStart + 1;
		while (islandEnd < numElements && elements[islandEnd].m_id == islandId) ++islandEnd;
		bool allSleeping = true;
		for (int e = islandStart; e < islandEnd; ++e)
		{
			const int objectIndex = m_unionFind.getElement(e).m_sz;
			if (objectIndex < 0 || objectIndex >= numObjects) continue;
			const btCollisionObject* object = objects[objectIndex];
			if (object->getIslandTag() != islandId) continue;
			const int state = object->getActivationState();
			if (state == ACTIVE_TAG || state == DISABLE_DEACTIVATION) allSleeping = false;
		}
		for (int e = islandStart; e < islandEnd; ++e)
		{
			const int objectIndex = m_unionFind.getElement(e).m_sz;
			if (objectIndex < 0 || objectIndex >= numObjects) continue;
			btCollisionObject* object = objects[objectIndex];
			if (object->getIslandTag() != islandId) continue;
			if (allSleeping)
			{
				object->setActivationState(ISLAND_SLEEPING);
			}
			else if (object->getActivationState() == ISLAND_SLEEPING)
			{
				object->setActivationState(WANTS_DEACTIVATION);
				object->setDeactivationTime(btScalar(0));
			}
		}
	}

	const int numManifolds = dispatcher->getNumManifolds();
	btPersistentManifold** allManifolds = numManifolds ? dispatcher->getInternalManifoldPointer() : 0;
	const int parts = ownScratch && m_splitIslands && allManifolds
	                      ? caliber::countingSortParts(numManifolds, caliber::kMinManifoldsOnThreads)
	                      : 0;
	if (parts > 0)
	{
		// The filter on the threads (two cache misses or so per manifold, for its bodies); the serial loop
		// below when a kinematic body wakes another.
		std::atomic<int> wakes(0);
		caliber::IslandManifoldKey keyOf;
		keyOf.manifolds = allManifolds;
		keyOf.dispatcher = dispatcher;
		keyOf.skipEmpty = collisionWorld->getDispatchInfo().m_deterministicOverlappingPairs;
		keyOf.wakes = &wakes;
		caliber::CountingSortOnThreads<caliber::IslandManifoldKey, caliber::PlaceIslandManifold> filter(
		    scratch.manifoldFilter, numManifolds, 1, parts);
		filter.count(keyOf);
		if (!wakes.load())
		{
			m_islandmanifold.resizeNoInitialize(numManifolds);
			caliber::PlaceIslandManifold place;
			place.manifolds = allManifolds;
			place.kept = &m_islandmanifold[0];
			m_islandmanifold.resizeNoInitialize(filter.place(place, 0));
			return;
		}
	}
	for (int i = 0; i < numManifolds; ++i)
	{
		btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(i);
		if (!manifold) continue;
		if (collisionWorld->getDispatchInfo().m_deterministicOverlappingPairs && manifold->getNumContacts() == 0)
			continue;
		const btCollisionObject* body0 = manifold->getBody0();
		const btCollisionObject* body1 = manifold->getBody1();
		if (!body0 || !body1) continue;
		const bool awake0 = body0->getActivationState() != ISLAND_SLEEPING;
		const bool awake1 = body1->getActivationState() != ISLAND_SLEEPING;
		if (!awake0 && !awake1) continue;
		// A moving kinematic object belongs to no island but must wake what it pushes (and the flags of the
		// sleeping pass are then stale).
		if (body0->isKinematicObject() && awake0 && body0->hasContactResponse())
		{
			body1->activate();
			if (ownScratch) scratch.awakeFresh = false;
		}
		if (body1->isKinematicObject() && awake1 && body1->hasContactResponse())
		{
			body0->activate();
			if (ownScratch) scratch.awakeFresh = false;
		}
		if (m_splitIslands && dispatcher->needsResponse(body0, body1)) m_islandmanifold.push_back(manifold);
	}
}

void btSimulationIslandManager::processIslands(btDispatcher* dispatcher, btCollisionWorld* collisionWorld,
                                               IslandCallback* callback)
{
	btAssert(dispatcher && collisionWorld && callback);
	if (!dispatcher || !collisionWorld || !callback) return;
	btCollisionObjectArray& objects = collisionWorld->getCollisionObjectArray();
	const int numObjects = objects.size();

	if (!m_splitIslands)
	{
		callback->processIsland(numObjects ? &objects[0] : 0, numObjects, dispatcher->getInternalManifoldPointer(),
		                        dispatcher->getNumManifolds(), -1);
		return;
	}

	// Each island's manifolds are a range of m_islandmanifold, as in Bullet. A callback that processes the
	// islands of another manager on this thread gets a scratch of its own.
	const int numElements = m_unionFind.getNumElements();
	caliber::IslandGroupingScratch& threadScratch = caliber::threadIslandGroupingScratch();
	caliber::IslandGroupingScratch nestedScratch;
	caliber::IslandGroupingScratch& scratch = threadScratch.inUse ? nestedScratch : threadScratch;
	scratch.inUse = true;
	caliber::groupManifoldsByIsland(m_islandmanifold, numElements, scratch);
	const int* bounds = &scratch.bounds[0];

	// A callback that is also a caliber::LoneIslandSink (the worlds' own) takes the runs of lone islands (one
	// awake body, no manifold: most of a scene of falling bodies) in one call each; the islands around a run
	// go to processIsland, so the sink sees every island in the same order as without the runs.
	caliber::LoneIslandSink* loneSink = dynamic_cast<caliber::LoneIslandSink*>(callback);
	// The run of lone islands is written by index into arrays sized for every element (numLone of them
	// in use), without a push's capacity check each.
	scratch.loneBodies.resizeNoInitialize(loneSink ? numElements : 0);
	scratch.loneIds.resizeNoInitialize(loneSink ? numElements : 0);
	btCollisionObject** loneBodies = loneSink && numElements ? &scratch.loneBodies[0] : 0;
	int* loneIds = loneSink && numElements ? &scratch.loneIds[0] : 0;
	int numLone = 0;
	const btElement* elements = numElements ? &m_unionFind.getElement(0) : 0;
	// Whether each element's object is awake, as buildIslands' pass on the threads left it (when this call is
	// buildAndProcessIslands' and nothing woke an object since): the walk then reads no object.
	const unsigned char* awake = &scratch == &threadScratch && threadScratch.awakeFresh &&
	                                     threadScratch.awakeOwner == this && threadScratch.awake.size() == numElements
	                                 ? &threadScratch.awake[0]
	                                 : 0;
	if (&scratch == &threadScratch) threadScratch.awakeFresh = false;
	int islandEnd = 0;
	btCollisionObject* const* objectArray = numObjects ? &objects[0] : 0;
	for (int islandStart = 0; islandStart < numElements; islandStart = islandEnd)
	{
		if (loneSink)
		{
			islandEnd = caliber::gatherLoneRun(elements, islandStart, numElements, bounds, objectArray, numObjects,
			                                   awake, loneBodies, loneIds, numLone);
			if (islandEnd != islandStart) continue;
		}
		const int islandId = elements[islandStart].m_id;
		const bool validId = islandId >= 0 && islandId < numElements;
		const int first = validId ? bounds[islandId] : 0;
		const int count = validId ? bounds[islandId + 1] - first : 0;
		bool islandSleeping = true;
		m_islandBodies.resize(0);
		for (islandEnd = islandStart; islandEnd < numElements && m_unionFind.getElement(islandEnd).m_id == islandId;
		     ++islandEnd)
		{
			const int objectIndex = m_unionFind.getElement(islandEnd).m_sz;
			if (objectIndex < 0 || objectIndex >= numObjects) continue;
			btCollisionObject* object = objects[objectIndex];
			m_islandBodies.push_back(object);
			if (awake ? awake[islandEnd] != 0 : object->isActive()) islandSleeping = false;
		}
		if (islandSleeping || m_islandBodies.size() == 0) continue;
		if (numLone > 0)
		{
			loneSink->processLoneIslands(loneBodies, loneIds, numLone);
			numLone = 0;
		}
		callback->processIsland(&m_islandBodies[0], m_islandBodies.size(), count ? &m_islandmanifold[first] : 0, count,
		                        islandId);
	}
	if (numLone > 0) loneSink->processLoneIslands(loneBodies, loneIds, numLone);
	scratch.loneBodies.resize(0);
	scratch.loneIds.resize(0);
	scratch.inUse = false;
	m_islandBodies.resize(0);
}

void btSimulationIslandManager::buildAndProcessIslands(btDispatcher* dispatcher, btCollisionWorld* collisionWorld,
                                                       IslandCallback* callback)
{
	// buildIslands' pass on the threads may tell processIslands which objects are awake, only here (a caller of
	// the two could change the objects between them).
	caliber::IslandGroupingScratch& scratch = caliber::threadIslandGroupingScratch();
	const bool ownScratch = !scratch.inUse;
	if (ownScratch) scratch.buildingForProcess = true;
	buildIslands(dispatcher, collisionWorld);
	if (ownScratch) scratch.buildingForProcess = false;
	processIslands(dispatcher, collisionWorld, callback);
}
