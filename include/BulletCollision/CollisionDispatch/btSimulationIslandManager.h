// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMULATION_ISLAND_MANAGER_H
#define BT_SIMULATION_ISLAND_MANAGER_H

/// btSimulationIslandManager: groups touching dynamic objects into islands that are solved, and put to
/// sleep, together.

#include "BulletCollision/CollisionDispatch/btUnionFind.h"
#include "LinearMath/btAlignedObjectArray.h"

class btCollisionObject;
class btCollisionWorld;
class btDispatcher;
class btPersistentManifold;

/// Builds simulation islands from the overlapping pairs (and whatever else the owner unites, such as
/// constraints), updates sleeping all-or-nothing per island, and hands each awake island's objects and
/// manifolds to a callback. Static and kinematic objects never belong to an island (island tag -1), so
/// a shared static ground does not merge the stacks standing on it.
class btSimulationIslandManager
{
	btUnionFind m_unionFind;
	btAlignedObjectArray<btPersistentManifold*> m_islandmanifold;
	btAlignedObjectArray<btCollisionObject*> m_islandBodies;
	bool m_splitIslands;

public:
	/// Splits islands (one callback per awake island).
	btSimulationIslandManager();
	/// Island managers may be derived from.
	virtual ~btSimulationIslandManager();

	/// n singleton sets.
	void initUnionFind(int n);

	/// The union-find over the non-static objects (element i is the i-th non-static object of the world).
	btUnionFind& getUnionFind() { return m_unionFind; }

	/// Numbers the non-static objects (island tag = union-find element), resets companion ids and hit
	/// fractions, and unites the objects of every overlapping pair that can merge islands.
	virtual void updateActivationState(btCollisionWorld* colWorld, btDispatcher* dispatcher);

	/// Writes each object's island id (its set's root) into its island tag; static and kinematic objects
	/// get -1. Call after every unite of the step.
	virtual void storeIslandActivationState(btCollisionWorld* world);

	/// Unites the objects of every overlapping pair of the world's pair cache when both merge islands.
	void findUnions(btDispatcher* dispatcher, btCollisionWorld* colWorld);

	/// Receives the objects and manifolds of one island.
	struct IslandCallback
	{
		/// Callbacks are deleted through base pointers.
		virtual ~IslandCallback() {}

		/// One island (islandId -1: everything at once, when islands are not split).
		virtual void processIsland(btCollisionObject** bodies, int numBodies, class btPersistentManifold** manifolds,
		                           int numManifolds, int islandId) = 0;
	};

	/// buildIslands then processIslands.
	void buildAndProcessIslands(btDispatcher* dispatcher, btCollisionWorld* collisionWorld, IslandCallback* callback);

	/// Groups the objects by island, puts an island to sleep when none of its objects is ACTIVE_TAG or
	/// DISABLE_DEACTIVATION (else wakes its sleeping objects to WANTS_DEACTIVATION), lets awake kinematic
	/// objects wake what they touch, and collects the manifolds that need a response.
	void buildIslands(btDispatcher* dispatcher, btCollisionWorld* colWorld);

	/// Calls the callback once per island that has an active object (or once with everything when
	/// islands are not split).
	void processIslands(btDispatcher* dispatcher, btCollisionWorld* collisionWorld, IslandCallback* callback);

	/// True when each island gets its own callback.
	bool getSplitIslands() { return m_splitIslands; }
	/// Chooses one callback per island (true) or one callback with every object and manifold (false).
	void setSplitIslands(bool doSplitIslands) { m_splitIslands = doSplitIslands; }
};

#endif  // BT_SIMULATION_ISLAND_MANAGER_H
