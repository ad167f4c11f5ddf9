// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_AXIS_SWEEP_3_INTERNAL_H
#define BT_AXIS_SWEEP_3_INTERNAL_H

#include "BulletCollision/BroadphaseCollision/btBroadphaseInterface.h"
#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

class btDbvtBroadphase;

/// Sweep and prune over three axes with AABBs quantised to BP_FP_INT_TYPE inside fixed world bounds
/// (the engine of btAxisSweep3 and bt32BitAxisSweep3). Each axis keeps the sorted list of all min and
/// max edges; moving a box moves its edges by insertion sort, and every time a min edge passes a max
/// edge the pair is added to or removed from the pair cache at once, inside setAabb.
///
/// Quantisation: a coordinate is clamped to the world bounds and scaled onto [0, handleSentinel - 1];
/// min edges are rounded down to even values, max edges to odd ones, so a min and a max edge never tie
/// and touching boxes overlap. Overlap is therefore decided on the grid: never missed, but pairs up to
/// one grid cell apart are reported too (unQuantize gives the boxes actually compared).
///
/// Instantiated for unsigned short and unsigned int only (in the library).
template <typename BP_FP_INT_TYPE>
class btAxisSweep3Internal : public btBroadphaseInterface
{
protected:
	/// Mask that clears the max-edge bit of a quantised value.
	BP_FP_INT_TYPE m_bpHandleMask;
	/// Position of the upper sentinel edge; quantised values stay below it.
	BP_FP_INT_TYPE m_handleSentinel;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// One end of one box on one axis: its quantised position (odd for a max edge) and its handle.
	class Edge
	{
	public:
		BP_FP_INT_TYPE m_pos;
		BP_FP_INT_TYPE m_handle;

		BP_FP_INT_TYPE IsMax() const { return BP_FP_INT_TYPE(m_pos & 1); }
	};

	/// The proxy of one box: the indices of its edges in each axis' edge list.
	class Handle : public btBroadphaseProxy
	{
	public:
		BT_DECLARE_ALIGNED_ALLOCATOR();

		BP_FP_INT_TYPE m_minEdges[3];
		BP_FP_INT_TYPE m_maxEdges[3];
		/// The box's proxy in the ray-cast accelerator (0 without one).
		btBroadphaseProxy* m_dbvtProxy;

		/// A free handle keeps the next free one in m_minEdges[0].
		void SetNextFree(BP_FP_INT_TYPE next) { m_minEdges[0] = next; }
		BP_FP_INT_TYPE GetNextFree() const { return m_minEdges[0]; }
	};

protected:
	btVector3 m_worldAabbMin;
	btVector3 m_worldAabbMax;
	/// Grid cells per world unit, per axis.
	btVector3 m_quantize;

	/// Handles in use (not counting the sentinel handle 0).
	BP_FP_INT_TYPE m_numHandles;
	/// Size of m_pHandles, the sentinel handle 0 included.
	BP_FP_INT_TYPE m_maxHandles;
	Handle* m_pHandles;
	/// Head of the free-handle list (0 when the pool is full).
	BP_FP_INT_TYPE m_firstFreeHandle;

	/// Per axis, 2 * m_maxHandles edges: the two sentinels and two per handle in use, sorted by position.
	Edge* m_pEdges[3];
	void* m_pEdgesRawPtr[3];

	btOverlappingPairCache* m_pairCache;
	/// Told of every pair added and removed, besides the cache.
	btOverlappingPairCallback* m_userPairCallback;
	bool m_ownsPairCache;
	int m_invalidPair;

	/// A btDbvtBroadphase mirroring the boxes for rayTest and aabbTest (0 when disabled).
	btDbvtBroadphase* m_raycastAccelerator;
	btOverlappingPairCache* m_nullPairCache;
	/// Set once a box had to be clamped to the world bounds, so that the warning is printed once.
	bool m_warnedOutsideBounds;
	/// m_quantize in double: the 32-bit grid has more cells than a float counts exactly.
	double m_quantizeScale[3];
	/// Pairs found stale by calculateOverlappingPairs (kept to avoid an allocation per step).
	btAlignedObjectArray<btBroadphasePair> m_stalePairs;

	BP_FP_INT_TYPE allocHandle();
	void freeHandle(BP_FP_INT_TYPE handle);

	/// True when the boxes of two handles overlap on both axes other than `axis` (edge order decides).
	bool testOverlap2D(const Handle* handle0, const Handle* handle1, int axis1, int axis2);

	// Insertion-sort moves of one edge; with updateOverlaps, pairs are added or removed as edges pass.
	void sortMinDown(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher, bool updateOverlaps);
	void sortMinUp(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher, bool updateOverlaps);
	void sortMaxDown(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher, bool updateOverlaps);
	void sortMaxUp(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher, bool updateOverlaps);

	void addPair(Handle* handle0, Handle* handle1);
	void removePair(Handle* handle0, Handle* handle1, btDispatcher* dispatcher);

	/// Clamps a box to the world bounds (warning once when it had to).
	void clampToWorld(const btVector3& aabbMin, const btVector3& aabbMax, btVector3& clampedMin,
	                  btVector3& clampedMax);

public:
	/// Boxes inside [worldAabbMin, worldAabbMax] (bigger ones are clamped); handleMask and handleSentinel
	/// set the grid (0xfffe / 0xffff for 16 bits); at most maxHandles boxes (asserted to fit the edge
	/// index type). pairCache 0 makes and owns a btHashedOverlappingPairCache.
	btAxisSweep3Internal(const btVector3& worldAabbMin, const btVector3& worldAabbMax, BP_FP_INT_TYPE handleMask,
	                     BP_FP_INT_TYPE handleSentinel, BP_FP_INT_TYPE maxHandles = 16384,
	                     btOverlappingPairCache* pairCache = 0, bool disableRaycastAccelerator = false);

	virtual ~btAxisSweep3Internal();

	BP_FP_INT_TYPE getNumHandles() const { return m_numHandles; }

	/// Pairs are kept up to date by setAabb; with a deferred-removal cache (btSortedOverlappingPairCache)
	/// the pairs whose boxes no longer overlap are removed here.
	virtual void calculateOverlappingPairs(btDispatcher* dispatcher);

	/// Adds a box; returns its handle index, or 0 when the pool is full or the box is not finite
	/// (asserts in both cases).
	BP_FP_INT_TYPE addHandle(const btVector3& aabbMin, const btVector3& aabbMax, void* pOwner,
	                         int collisionFilterGroup, int collisionFilterMask, btDispatcher* dispatcher);
	/// Removes a box and its pairs; an index that is not in use asserts and is ignored.
	void removeHandle(BP_FP_INT_TYPE handle, btDispatcher* dispatcher);
	/// Moves a box; pairs change at once. A non-finite box asserts and is ignored.
	void updateHandle(BP_FP_INT_TYPE handle, const btVector3& aabbMin, const btVector3& aabbMax,
	                  btDispatcher* dispatcher);

	Handle* getHandle(BP_FP_INT_TYPE index) const { return m_pHandles + index; }

	/// Restores the initial state when no box is left.
	virtual void resetPool(btDispatcher* dispatcher);

	/// Visits every pair of the cache (the cache's processAllOverlappingPairs without a dispatcher).
	void processAllOverlappingPairs(btOverlapCallback* callback);

	virtual btBroadphaseProxy* createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int shapeType,
	                                       void* userPtr, int collisionFilterGroup, int collisionFilterMask,
	                                       btDispatcher* dispatcher);
	virtual void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher);
	virtual void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
	                     btDispatcher* dispatcher);
	/// The box as last set (not quantised, not clamped).
	virtual void getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const;

	/// Through the accelerator when there is one, else over every box.
	virtual void rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
	                     const btVector3& aabbMin = btVector3(0, 0, 0), const btVector3& aabbMax = btVector3(0, 0, 0));
	virtual void aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback);

	/// The grid position of point on each axis: even for isMax 0, odd for isMax 1.
	void quantize(BP_FP_INT_TYPE* out, const btVector3& point, int isMax) const;
	/// The box a proxy occupies on the grid, in world units (what overlap is decided on).
	void unQuantize(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const;

	/// True when the grid boxes of two proxies overlap.
	bool testAabbOverlap(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1);

	virtual btOverlappingPairCache* getOverlappingPairCache() { return m_pairCache; }
	virtual const btOverlappingPairCache* getOverlappingPairCache() const { return m_pairCache; }

	void setOverlappingPairUserCallback(btOverlappingPairCallback* pairCallback)
	{
		m_userPairCallback = pairCallback;
	}
	const btOverlappingPairCallback* getOverlappingPairUserCallback() const { return m_userPairCallback; }

	/// The world bounds.
	virtual void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const;

	virtual void printStats();
};

#endif  // BT_AXIS_SWEEP_3_INTERNAL_H
