// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"

#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btLoneIslandSink.h"
#include "BulletCollision/CollisionDispatch/btUniteInOrder.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btThreads.h"

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
	bool inUse = false;
};

/// Sorts manifolds by island with a counting sort: O(n), and stable, so each island sees its manifolds in
/// the dispatcher's order whatever the number of islands. Manifolds of no valid island are dropped. After
/// it, island i's manifolds are manifolds[bounds[i] .. bounds[i + 1]).
void groupManifoldsByIsland(btAlignedObjectArray<btPersistentManifold*>& manifolds, int numIslands,
                            IslandGroupingScratch& scratch)
{
	btAlignedObjectArray<int>& bounds = scratch.bounds;
	const int numManifolds = manifolds.size();
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
/// appends each awake one's object and island id to loneBodies / loneIds (numLone of them so far) and
/// returns the element after the run (start itself when element start is not a lone island). In a loop
/// of its own, so that the walk over thousands of lone bodies keeps its few values in registers.
int gatherLoneRun(const btElement* elements, int start, int numElements, const int* bounds,
                  btCollisionObject* const* objects, int numObjects, btCollisionObject** loneBodies, int* loneIds,
                  int& numLone)
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
		if (!object->isActive()) continue;
		loneBodies[n] = object;
		loneIds[n] = islandId;
		++n;
	}
	numLone = n;
	return i;
}

/// buildIslands' sleeping pass over the run of lone islands (one element each) from element start of the
/// sorted union-find: each body sleeps unless it must stay awake. Returns the element after the run (start
/// itself when element start's island has more elements). A loop of its own, as gatherLoneRun.
int sleepLoneRun(const btElement* elements, int start, int numElements, btCollisionObject* const* objects,
                 int numObjects)
{
	int i = start;
	while (i < numElements)
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
	int index = 0;
	for (int i = 0; i < objects.size(); ++i)
	{
		btCollisionObject* object = objects[i];
		if (!object->isStaticOrKinematicObject())
			object->setIslandTag(index++);
		else
			object->setIslandTag(-1);
		object->setCompanionId(-1);
		object->setHitFraction(btScalar(1));
	}
	initUnionFind(index);
	findUnions(dispatcher, colWorld);
}

void btSimulationIslandManager::storeIslandActivationState(btCollisionWorld* world)
{
	btAssert(world);
	if (!world) return;
	btCollisionObjectArray& objects = world->getCollisionObjectArray();
	const int numElements = m_unionFind.getNumElements();
	btElement* elements = numElements ? &m_unionFind.getElement(0) : 0;
	int index = 0;
	for (int i = 0; i < objects.size(); ++i)
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
	int islandEnd = 0;
	for (int islandStart = 0; islandStart < numElements; islandStart = islandEnd)
	{
		// Lone bodies (most of a scene of falling bodies): the two passes below in one, run by run (each
		// sleeps unless it must stay awake).
		islandEnd = caliber::sleepLoneRun(elements, islandStart, numElements, objectArray, numObjects);
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
		// A moving kinematic object belongs to no island but must wake what it pushes.
		if (body0->isKinematicObject() && awake0 && body0->hasContactResponse()) body1->activate();
		if (body1->isKinematicObject() && awake1 && body1->hasContactResponse()) body0->activate();
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
	int islandEnd = 0;
	btCollisionObject* const* objectArray = numObjects ? &objects[0] : 0;
	for (int islandStart = 0; islandStart < numElements; islandStart = islandEnd)
	{
		if (loneSink)
		{
			islandEnd = caliber::gatherLoneRun(elements, islandStart, numElements, bounds, objectArray, numObjects,
			                                   loneBodies, loneIds, numLone);
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
			if (object->isActive()) islandSleeping = false;
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
	buildIslands(dispatcher, collisionWorld);
	processIslands(dispatcher, collisionWorld, callback);
}
