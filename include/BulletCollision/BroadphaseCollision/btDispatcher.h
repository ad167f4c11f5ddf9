// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DISPATCHER_H
#define BT_DISPATCHER_H

/// btDispatcher: the interface that finds collision algorithms for pairs and owns contact manifolds.

#include "LinearMath/btScalar.h"

class btCollisionAlgorithm;
struct btBroadphaseProxy;
class btRigidBody;
class btCollisionObject;
class btOverlappingPairCache;
struct btCollisionObjectWrapper;
class btPersistentManifold;
class btPoolAllocator;
class btStackAlloc;
class btIDebugDraw;

/// Per-step settings handed to every collision algorithm.
struct btDispatcherInfo
{
	/// How pairs are processed: discrete (contacts now) or continuous (time of impact).
	enum DispatchFunc
	{
		/// Closest points at the current transforms.
		DISPATCH_DISCRETE = 1,
		/// Time of impact over the step.
		DISPATCH_CONTINUOUS
	};

	/// Bullet's defaults: discrete dispatch, EPA on, CCD penetration 0.04.
	btDispatcherInfo()
	    : m_timeStep(btScalar(0)),
	      m_stepCount(0),
	      m_dispatchFunc(DISPATCH_DISCRETE),
	      m_timeOfImpact(btScalar(1)),
	      m_useContinuous(true),
	      m_debugDraw(0),
	      m_enableSatConvex(false),
	      m_enableSPU(true),
	      m_useEpa(true),
	      m_allowedCcdPenetration(btScalar(0.04)),
	      m_useConvexConservativeDistanceUtil(false),
	      m_convexConservativeDistanceThreshold(btScalar(0)),
	      m_deterministicOverlappingPairs(false),
	      m_stackAllocator(0)
	{
	}

	/// Length of the step being simulated (seconds).
	btScalar m_timeStep;
	/// Number of the current step.
	int m_stepCount;
	/// A DispatchFunc value.
	int m_dispatchFunc;
	/// Smallest time of impact found during continuous dispatch (written by the algorithms).
	mutable btScalar m_timeOfImpact;
	/// Whether continuous collision detection is used.
	bool m_useContinuous;
	/// Debug drawer for the algorithms (may be null).
	btIDebugDraw* m_debugDraw;
	/// Asks convex-convex to use polyhedral clipping (SAT) when the shapes have polyhedral features.
	bool m_enableSatConvex;
	/// Kept for source compatibility; Caliber has no SPU path.
	bool m_enableSPU;
	/// Kept for source compatibility: EPA is the default penetration solver.
	bool m_useEpa;
	/// Penetration allowed by continuous collision detection.
	btScalar m_allowedCcdPenetration;
	/// Kept for source compatibility (conservative-advancement distance caching).
	bool m_useConvexConservativeDistanceUtil;
	/// Kept for source compatibility.
	btScalar m_convexConservativeDistanceThreshold;
	/// Sort overlapping pairs before dispatch so that results do not depend on insertion order.
	bool m_deterministicOverlappingPairs;
	/// Scratch allocator of Bullet 2.7x; unused by Caliber's algorithms (kept for source compatibility).
	btStackAlloc* m_stackAllocator;
};

/// What an algorithm is looked up for: contact generation or closest-point queries.
enum ebtDispatcherQueryType
{
	/// Algorithms that fill persistent manifolds during the simulation.
	BT_CONTACT_POINT_ALGORITHMS = 1,
	/// Algorithms used by closest-point queries (contactPairTest and friends).
	BT_CLOSEST_POINT_ALGORITHMS = 2
};

/// Finds the algorithm of each pair, runs the narrowphase over the overlapping pairs and owns the
/// persistent manifolds and the memory of the algorithms.
class btDispatcher
{
public:
	/// Dispatchers are deleted through base pointers.
	virtual ~btDispatcher();

	/// A new algorithm for the pair (allocated through allocateCollisionAlgorithm), sharing
	/// sharedManifold when it is not null.
	virtual btCollisionAlgorithm* findAlgorithm(const btCollisionObjectWrapper* body0Wrap,
	                                            const btCollisionObjectWrapper* body1Wrap,
	                                            btPersistentManifold* sharedManifold,
	                                            ebtDispatcherQueryType queryType) = 0;

	/// A new, empty manifold between two objects.
	virtual btPersistentManifold* getNewManifold(const btCollisionObject* b0, const btCollisionObject* b1) = 0;
	/// Destroys a manifold obtained from getNewManifold.
	virtual void releaseManifold(btPersistentManifold* manifold) = 0;
	/// Removes every point of a manifold.
	virtual void clearManifold(btPersistentManifold* manifold) = 0;

	/// True when the narrowphase should run for the pair.
	virtual bool needsCollision(const btCollisionObject* body0, const btCollisionObject* body1) = 0;
	/// True when contacts between the pair should produce a response.
	virtual bool needsResponse(const btCollisionObject* body0, const btCollisionObject* body1) = 0;

	/// Runs the narrowphase over every pair of the cache.
	virtual void dispatchAllCollisionPairs(btOverlappingPairCache* pairCache, const btDispatcherInfo& dispatchInfo,
	                                       btDispatcher* dispatcher) = 0;

	/// Number of live manifolds.
	virtual int getNumManifolds() const = 0;
	/// Manifold at index.
	virtual btPersistentManifold* getManifoldByIndexInternal(int index) = 0;
	/// The array of live manifolds (may be null when there is none).
	virtual btPersistentManifold** getInternalManifoldPointer() = 0;
	/// The pool manifolds are allocated from.
	virtual btPoolAllocator* getInternalManifoldPool() = 0;
	/// The pool manifolds are allocated from.
	virtual const btPoolAllocator* getInternalManifoldPool() const = 0;

	/// Memory for an algorithm of size bytes (from the algorithm pool when it fits).
	virtual void* allocateCollisionAlgorithm(int size) = 0;
	/// Returns memory from allocateCollisionAlgorithm (the caller runs the destructor first).
	virtual void freeCollisionAlgorithm(void* ptr) = 0;
};

#endif  // BT_DISPATCHER_H
