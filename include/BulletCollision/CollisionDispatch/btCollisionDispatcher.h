// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION__DISPATCHER_H
#define BT_COLLISION__DISPATCHER_H

/// btCollisionDispatcher: the standard dispatcher, with a collision matrix and a replaceable near callback.

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionCreateFunc.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btAlignedObjectArray.h"

class btCollisionConfiguration;
class btCollisionDispatcher;
class btOverlappingPairCache;
class btPoolAllocator;
struct btBroadphasePair;
struct btCollisionObjectWrapper;

/// Kept for source compatibility: the collision matrix is always a table of create functions.
#define USE_DISPATCH_REGISTRY_ARRAY 1

/// The function run for every overlapping pair by dispatchAllCollisionPairs (the manual's third way of
/// filtering: install your own, and call btCollisionDispatcher::defaultNearCallback for pairs you keep).
typedef void (*btNearCallback)(btBroadphasePair& collisionPair, btCollisionDispatcher& dispatcher,
                               const btDispatcherInfo& dispatchInfo);

/// Finds the algorithm of each pair of shape types through a collision matrix filled from a
/// btCollisionConfiguration (users may override entries for their own shapes), owns the persistent
/// manifolds (taken from the configuration's pool) and runs the near callback over the pairs of a
/// pair cache.
class btCollisionDispatcher : public btDispatcher
{
protected:
	/// DispatcherFlags bits.
	int m_dispatcherFlags;
	/// Live manifolds; each manifold's m_index1a is its index here.
	btAlignedObjectArray<btPersistentManifold*> m_manifoldsPtr;
	/// A spare result for subclasses written for Bullet; the dispatcher itself does not use it (each
	/// algorithm call writes through a btManifoldResult of its own).
	btManifoldResult m_defaultManifoldResult;
	/// Function run for every overlapping pair.
	btNearCallback m_nearCallback;
	/// Pool algorithms are allocated from (the configuration's).
	btPoolAllocator* m_collisionAlgorithmPoolAllocator;
	/// Pool manifolds are allocated from (the configuration's).
	btPoolAllocator* m_persistentManifoldPoolAllocator;
	/// Contact algorithm factory of each pair of shape types.
	btCollisionAlgorithmCreateFunc* m_doubleDispatchContactPoints[MAX_BROADPHASE_COLLISION_TYPES]
	                                                             [MAX_BROADPHASE_COLLISION_TYPES];
	/// Closest-points algorithm factory of each pair of shape types.
	btCollisionAlgorithmCreateFunc* m_doubleDispatchClosestPoints[MAX_BROADPHASE_COLLISION_TYPES]
	                                                             [MAX_BROADPHASE_COLLISION_TYPES];
	/// Where the pools and the default factories come from.
	btCollisionConfiguration* m_collisionConfiguration;

public:
	/// Bits of getDispatcherFlags.
	enum DispatcherFlags
	{
		/// needsCollision also accepts pairs of two static (or two inactive) objects.
		CD_STATIC_STATIC_REPORTED = 1,
		/// Breaking thresholds scale with the shapes' size (getContactBreakingThreshold); on by default.
		CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD = 2,
		/// When the manifold pool is full, getNewManifold returns null instead of using the heap.
		CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION = 4
	};

	/// The DispatcherFlags bits.
	int getDispatcherFlags() const { return m_dispatcherFlags; }
	/// Sets the DispatcherFlags bits.
	void setDispatcherFlags(int flags) { m_dispatcherFlags = flags; }

	/// Uses createFunc for contact generation between shapes of types proxyType0 and proxyType1 (in that
	/// order; register both orders for an asymmetric pair). Types out of range or a null factory assert
	/// and are ignored in release.
	void registerCollisionCreateFunc(int proxyType0, int proxyType1, btCollisionAlgorithmCreateFunc* createFunc);
	/// Uses createFunc for closest-point queries between shapes of types proxyType0 and proxyType1.
	void registerClosestPointsCreateFunc(int proxyType0, int proxyType1, btCollisionAlgorithmCreateFunc* createFunc);

	/// Number of live manifolds.
	int getNumManifolds() const override { return int(m_manifoldsPtr.size()); }
	/// The array of live manifolds, or null when there is none.
	btPersistentManifold** getInternalManifoldPointer() override
	{
		return m_manifoldsPtr.size() ? &m_manifoldsPtr[0] : 0;
	}
	/// Manifold at index; out of range asserts and returns null in release.
	btPersistentManifold* getManifoldByIndexInternal(int index) override
	{
		btAssert(index >= 0 && index < m_manifoldsPtr.size());
		return (index >= 0 && index < m_manifoldsPtr.size()) ? m_manifoldsPtr[index] : 0;
	}
	/// Manifold at index; out of range asserts and returns null in release.
	const btPersistentManifold* getManifoldByIndexInternal(int index) const
	{
		btAssert(index >= 0 && index < m_manifoldsPtr.size());
		return (index >= 0 && index < m_manifoldsPtr.size()) ? m_manifoldsPtr[index] : 0;
	}

	/// A dispatcher using the pools and the algorithm table of collisionConfiguration (not owned; must
	/// outlive the dispatcher). Flags start as CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD.
	btCollisionDispatcher(btCollisionConfiguration* collisionConfiguration);
	/// Releases the manifolds still alive.
	~btCollisionDispatcher() override;

	/// A new, empty manifold between b0 and b1 with the pair's breaking and processing thresholds; from the
	/// pool, or the heap when the pool is full (null then with CD_DISABLE_CONTACTPOOL_DYNAMIC_ALLOCATION).
	btPersistentManifold* getNewManifold(const btCollisionObject* b0, const btCollisionObject* b1) override;
	/// Clears and destroys a manifold from getNewManifold (null is ignored).
	void releaseManifold(btPersistentManifold* manifold) override;
	/// Removes every point of the manifold.
	void clearManifold(btPersistentManifold* manifold) override;

	/// A new algorithm from the collision matrix for the two shapes' types (null when the factory makes
	/// none, or for a null shape or an out-of-range type, which also asserts).
	btCollisionAlgorithm* findAlgorithm(const btCollisionObjectWrapper* body0Wrap,
	                                    const btCollisionObjectWrapper* body1Wrap, btPersistentManifold* sharedManifold,
	                                    ebtDispatcherQueryType queryType) override;

	/// True when at least one object is active (or CD_STATIC_STATIC_REPORTED is set) and each object
	/// accepts the other (checkCollideWith). The manual's fourth way of filtering: override it.
	bool needsCollision(const btCollisionObject* body0, const btCollisionObject* body1) override;
	/// True when both objects respond to contacts and at least one of them is dynamic.
	bool needsResponse(const btCollisionObject* body0, const btCollisionObject* body1) override;

	/// Runs the near callback over every pair of the cache (dispatcher is unused, as in Bullet).
	void dispatchAllCollisionPairs(btOverlappingPairCache* pairCache, const btDispatcherInfo& dispatchInfo,
	                               btDispatcher* dispatcher) override;

	/// Replaces the function run for every pair (null restores defaultNearCallback).
	void setNearCallback(btNearCallback nearCallback);
	/// The function run for every pair.
	btNearCallback getNearCallback() const { return m_nearCallback; }

	/// The standard near callback: when needsCollision accepts the pair, creates its algorithm once and
	/// runs it (discrete: contacts into the manifold; continuous: lowers dispatchInfo.m_timeOfImpact).
	static void defaultNearCallback(btBroadphasePair& collisionPair, btCollisionDispatcher& dispatcher,
	                                const btDispatcherInfo& dispatchInfo);

	/// Memory for an algorithm of size bytes: from the algorithm pool when it fits, else the heap.
	void* allocateCollisionAlgorithm(int size) override;
	/// Returns memory from allocateCollisionAlgorithm to where it came from (null is ignored).
	void freeCollisionAlgorithm(void* ptr) override;

	/// The configuration the dispatcher was built with.
	btCollisionConfiguration* getCollisionConfiguration() { return m_collisionConfiguration; }
	/// The configuration the dispatcher was built with.
	const btCollisionConfiguration* getCollisionConfiguration() const { return m_collisionConfiguration; }
	/// Replaces the configuration reference (the matrix and pools are kept, as in Bullet).
	void setCollisionConfiguration(btCollisionConfiguration* config) { m_collisionConfiguration = config; }

	/// The pool manifolds come from.
	btPoolAllocator* getInternalManifoldPool() override { return m_persistentManifoldPoolAllocator; }
	/// The pool manifolds come from.
	const btPoolAllocator* getInternalManifoldPool() const override { return m_persistentManifoldPoolAllocator; }
};

#endif  // BT_COLLISION__DISPATCHER_H
