// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/BroadphaseCollision/btAxisSweep3Internal.h"

#include <cstdint>
#include <cstdio>
#include <limits>
#include <new>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "LinearMath/btAabbUtil2.h"
#include "LinearMath/btAlignedObject.h"
#include "LinearMath/btWarningHook.h"

namespace
{
bool finiteBox(const btVector3& aabbMin, const btVector3& aabbMax)
{
	return caliber::isFinite(aabbMin) && caliber::isFinite(aabbMax);
}

int nextAxis(int axis) { return axis == 2 ? 0 : axis + 1; }

// Whether pointer lies in [begin, end), compared as addresses (pointers into different arrays may
// not be compared with < directly).
template <typename T>
bool pointsInto(const void* pointer, const T* begin, const T* end)
{
	const uintptr_t address = reinterpret_cast<uintptr_t>(pointer);
	return address >= reinterpret_cast<uintptr_t>(begin) && address < reinterpret_cast<uintptr_t>(end);
}
}  // namespace

template <typename BP_FP_INT_TYPE>
btAxisSweep3Internal<BP_FP_INT_TYPE>::btAxisSweep3Internal(const btVector3& worldAabbMin, const btVector3& worldAabbMax,
                                                           BP_FP_INT_TYPE handleMask, BP_FP_INT_TYPE handleSentinel,
                                                           BP_FP_INT_TYPE maxHandles, btOverlappingPairCache* pairCache,
                                                           bool disableRaycastAccelerator)
    : m_bpHandleMask(handleMask),
      m_handleSentinel(handleSentinel),
      m_worldAabbMin(worldAabbMin),
      m_worldAabbMax(worldAabbMax),
      m_numHandles(0),
      m_maxHandles(0),
      m_pHandles(0),
      m_firstFreeHandle(0),
      m_pairCache(pairCache),
      m_userPairCallback(0),
      m_ownsPairCache(false),
      m_invalidPair(0),
      m_raycastAccelerator(0),
      m_nullPairCache(0),
      m_warnedOutsideBounds(false)
{
	// Bounds that give no grid are repaired per axis: a non-finite end becomes 0 (min) or min + 1 (max),
	// reversed ends are swapped, and an empty axis gets unit size.
	for (int axis = 0; axis < 3; ++axis)
	{
		btScalar lo = m_worldAabbMin[axis];
		btScalar hi = m_worldAabbMax[axis];
		const bool usable = btIsFinite(lo) && btIsFinite(hi) && lo < hi;
		btAssert(usable && "btAxisSweep3: world bounds must be finite with min < max on every axis");
		if (usable) continue;
		if (!btIsFinite(lo)) lo = 0;
		if (!btIsFinite(hi)) hi = lo + btScalar(1);
		if (hi < lo) btSwap(lo, hi);
		if (!(lo < hi)) hi = lo + btScalar(1);
		m_worldAabbMin[axis] = lo;
		m_worldAabbMax[axis] = hi;
	}
	// The grid has handleSentinel - 1 cells per axis; the sentinel position stays above every box.
	for (int axis = 0; axis < 3; ++axis)
	{
		m_quantizeScale[axis] = double(BP_FP_INT_TYPE(m_handleSentinel - 1)) /
		                        (double(m_worldAabbMax[axis]) - double(m_worldAabbMin[axis]));
		m_quantize[axis] = btScalar(m_quantizeScale[axis]);
	}

	// Edge indices are BP_FP_INT_TYPE too, so two edges per handle (the sentinel's included) must fit.
	const size_t largestIndex = size_t(std::numeric_limits<BP_FP_INT_TYPE>::max());
	const size_t maxUsable = largestIndex / 2 - 1;
	btAssert(maxHandles >= 1 && size_t(maxHandles) <= maxUsable && "btAxisSweep3: maxHandles out of range");
	size_t usableHandles = size_t(maxHandles);
	if (usableHandles < 1) usableHandles = 1;
	if (usableHandles > maxUsable) usableHandles = maxUsable;
	m_maxHandles = BP_FP_INT_TYPE(usableHandles + 1);

	m_pHandles = caliber::alignedNewArray<Handle>(size_t(m_maxHandles));
	for (int axis = 0; axis < 3; ++axis)
	{
		m_pEdgesRawPtr[axis] = btAlignedAlloc(sizeof(Edge) * size_t(m_maxHandles) * 2, 16);
		m_pEdges[axis] = static_cast<Edge*>(m_pEdgesRawPtr[axis]);
	}
	resetPool(0);

	if (!m_pairCache)
	{
		m_pairCache = caliber::alignedNew<btHashedOverlappingPairCache>();
		m_ownsPairCache = true;
	}
	if (!disableRaycastAccelerator)
	{
		// A dynamic tree answers rays and box queries in log time; it needs no pairs of its own.
		m_nullPairCache = caliber::alignedNew<btNullPairCache>();
		m_raycastAccelerator = caliber::alignedNew<btDbvtBroadphase>(m_nullPairCache);
	}
}

template <typename BP_FP_INT_TYPE>
btAxisSweep3Internal<BP_FP_INT_TYPE>::~btAxisSweep3Internal()
{
	// The tree before the pair cache it reports to; edges hold only handle indices.
	caliber::alignedDelete(m_raycastAccelerator);
	caliber::alignedDelete(m_nullPairCache);
	for (void* edges : m_pEdgesRawPtr) btAlignedFree(edges);
	caliber::alignedDeleteArray(m_pHandles, size_t(m_maxHandles));
	if (m_ownsPairCache) caliber::alignedDelete(m_pairCache);
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::resetPool(btDispatcher* dispatcher)
{
	(void)dispatcher;
	if (m_numHandles != 0) return;
	// Handle 0 is the sentinel that owns the two end edges of every axis; the others are free, in order.
	m_firstFreeHandle = m_maxHandles > 1 ? BP_FP_INT_TYPE(1) : BP_FP_INT_TYPE(0);
	for (size_t i = 1; i < size_t(m_maxHandles); ++i)
	{
		m_pHandles[i].m_uniqueId = 0;
		m_pHandles[i].SetNextFree(i + 1 < size_t(m_maxHandles) ? BP_FP_INT_TYPE(i + 1) : BP_FP_INT_TYPE(0));
	}
	Handle& sentinel = m_pHandles[0];
	sentinel.m_uniqueId = 0;
	sentinel.m_clientObject = 0;
	sentinel.m_dbvtProxy = 0;
	for (int axis = 0; axis < 3; ++axis)
	{
		sentinel.m_minEdges[axis] = 0;
		sentinel.m_maxEdges[axis] = 1;
		m_pEdges[axis][0].m_pos = 0;
		m_pEdges[axis][0].m_handle = 0;
		m_pEdges[axis][1].m_pos = m_handleSentinel;
		m_pEdges[axis][1].m_handle = 0;
	}
}

template <typename BP_FP_INT_TYPE>
BP_FP_INT_TYPE btAxisSweep3Internal<BP_FP_INT_TYPE>::allocHandle()
{
	const BP_FP_INT_TYPE handle = m_firstFreeHandle;
	if (handle == 0) return 0;
	m_firstFreeHandle = getHandle(handle)->GetNextFree();
	++m_numHandles;
	return handle;
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::freeHandle(BP_FP_INT_TYPE handle)
{
	Handle* h = getHandle(handle);
	h->m_uniqueId = 0;
	h->m_clientObject = 0;
	h->m_dbvtProxy = 0;
	h->SetNextFree(m_firstFreeHandle);
	m_firstFreeHandle = handle;
	--m_numHandles;
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::quantize(BP_FP_INT_TYPE* out, const btVector3& point, int isMax) const
{
	const double top = double(BP_FP_INT_TYPE(m_handleSentinel - 1));
	for (int axis = 0; axis < 3; ++axis)
	{
		double cell = (double(point[axis]) - double(m_worldAabbMin[axis])) * m_quantizeScale[axis];
		// Clamping in double keeps the conversion defined for any finite input (NaN goes to 0).
		if (!(cell > 0)) cell = 0;
		if (cell > top) cell = top;
		const BP_FP_INT_TYPE floorCell = BP_FP_INT_TYPE(cell);
		// Min edges even, max edges odd: both round down, which keeps the order of any two coordinates,
		// so boxes that overlap or touch always overlap on the grid.
		out[axis] = isMax ? BP_FP_INT_TYPE(floorCell | 1) : BP_FP_INT_TYPE(floorCell & m_bpHandleMask);
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::unQuantize(btBroadphaseProxy* proxy, btVector3& aabbMin,
                                                      btVector3& aabbMax) const
{
	const Handle* handle = static_cast<const Handle*>(proxy);
	for (int axis = 0; axis < 3; ++axis)
	{
		const double lo = double(m_pEdges[axis][handle->m_minEdges[axis]].m_pos);
		const double hi = double(m_pEdges[axis][handle->m_maxEdges[axis]].m_pos);
		aabbMin[axis] = btScalar(double(m_worldAabbMin[axis]) + lo / m_quantizeScale[axis]);
		aabbMax[axis] = btScalar(double(m_worldAabbMin[axis]) + hi / m_quantizeScale[axis]);
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::clampToWorld(const btVector3& aabbMin, const btVector3& aabbMax,
                                                        btVector3& clampedMin, btVector3& clampedMax)
{
	clampedMin = aabbMin;
	clampedMax = aabbMax;
	clampedMin.setMax(m_worldAabbMin);
	clampedMax.setMin(m_worldAabbMax);
	bool clamped = !(clampedMin == aabbMin) || !(clampedMax == aabbMax);
	// A box entirely outside still gets a (flat) box on the boundary, so the object is not lost.
	clampedMin.setMin(m_worldAabbMax);
	clampedMax.setMax(m_worldAabbMin);
	if (clamped && !m_warnedOutsideBounds)
	{
		m_warnedOutsideBounds = true;
		btReportWarning(
		    "Caliber: btAxisSweep3: a box outside the world bounds was clamped to them; objects there may be "
		    "paired although they do not touch\n");
	}
}

template <typename BP_FP_INT_TYPE>
bool btAxisSweep3Internal<BP_FP_INT_TYPE>::testOverlap2D(const Handle* handle0, const Handle* handle1, int axis1,
                                                         int axis2)
{
	// Edge indices order like positions, and a min and a max edge never share a position.
	if (handle0->m_maxEdges[axis1] < handle1->m_minEdges[axis1] ||
	    handle1->m_maxEdges[axis1] < handle0->m_minEdges[axis1])
		return false;
	if (handle0->m_maxEdges[axis2] < handle1->m_minEdges[axis2] ||
	    handle1->m_maxEdges[axis2] < handle0->m_minEdges[axis2])
		return false;
	return true;
}

template <typename BP_FP_INT_TYPE>
bool btAxisSweep3Internal<BP_FP_INT_TYPE>::testAabbOverlap(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1)
{
	const Handle* handle0 = static_cast<const Handle*>(proxy0);
	const Handle* handle1 = static_cast<const Handle*>(proxy1);
	for (int axis = 0; axis < 3; ++axis)
	{
		if (handle0->m_maxEdges[axis] < handle1->m_minEdges[axis] ||
		    handle1->m_maxEdges[axis] < handle0->m_minEdges[axis])
			return false;
	}
	return true;
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::addPair(Handle* handle0, Handle* handle1)
{
	m_pairCache->addOverlappingPair(handle0, handle1);
	if (m_userPairCallback) m_userPairCallback->addOverlappingPair(handle0, handle1);
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::removePair(Handle* handle0, Handle* handle1, btDispatcher* dispatcher)
{
	// A deferred-removal cache drops stale pairs in calculateOverlappingPairs instead.
	if (m_pairCache->hasDeferredRemoval()) return;
	m_pairCache->removeOverlappingPair(handle0, handle1, dispatcher);
	if (m_userPairCallback) m_userPairCallback->removeOverlappingPair(handle0, handle1, dispatcher);
}

// The four moves below swap one edge with its neighbour until the list is sorted again. Passing an edge
// of the other kind changes whether the two boxes overlap on this axis: a min edge going down past a max
// edge (or a max edge going up past a min edge) starts an overlap, the opposite moves end one. The other
// two axes decide whether that makes or breaks a pair.

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::sortMinDown(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher,
                                                       bool updateOverlaps)
{
	(void)dispatcher;
	Edge* edges = m_pEdges[axis];
	Handle* self = getHandle(edges[edge].m_handle);
	const int axis1 = nextAxis(axis), axis2 = nextAxis(axis1);
	size_t index = edge;
	while (index > 0)
	{
		Edge& prev = edges[index - 1];
		if (prev.m_handle == 0 || !(prev.m_pos > edges[index].m_pos)) break;
		Handle* other = getHandle(prev.m_handle);
		if (prev.IsMax())
		{
			if (updateOverlaps && testOverlap2D(self, other, axis1, axis2)) addPair(self, other);
			++other->m_maxEdges[axis];
		}
		else
		{
			++other->m_minEdges[axis];
		}
		--self->m_minEdges[axis];
		btSwap(edges[index], prev);
		--index;
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::sortMinUp(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher,
                                                     bool updateOverlaps)
{
	Edge* edges = m_pEdges[axis];
	Handle* self = getHandle(edges[edge].m_handle);
	const int axis1 = nextAxis(axis), axis2 = nextAxis(axis1);
	size_t index = edge;
	for (;;)
	{
		Edge& next = edges[index + 1];
		if (next.m_handle == 0 || !(next.m_pos < edges[index].m_pos)) break;
		Handle* other = getHandle(next.m_handle);
		if (next.IsMax())
		{
			if (updateOverlaps && testOverlap2D(self, other, axis1, axis2)) removePair(self, other, dispatcher);
			--other->m_maxEdges[axis];
		}
		else
		{
			--other->m_minEdges[axis];
		}
		++self->m_minEdges[axis];
		btSwap(edges[index], next);
		++index;
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::sortMaxDown(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher,
                                                       bool updateOverlaps)
{
	Edge* edges = m_pEdges[axis];
	Handle* self = getHandle(edges[edge].m_handle);
	const int axis1 = nextAxis(axis), axis2 = nextAxis(axis1);
	size_t index = edge;
	while (index > 0)
	{
		Edge& prev = edges[index - 1];
		if (prev.m_handle == 0 || !(prev.m_pos > edges[index].m_pos)) break;
		Handle* other = getHandle(prev.m_handle);
		if (!prev.IsMax())
		{
			if (updateOverlaps && testOverlap2D(self, other, axis1, axis2)) removePair(self, other, dispatcher);
			++other->m_minEdges[axis];
		}
		else
		{
			++other->m_maxEdges[axis];
		}
		--self->m_maxEdges[axis];
		btSwap(edges[index], prev);
		--index;
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::sortMaxUp(int axis, BP_FP_INT_TYPE edge, btDispatcher* dispatcher,
                                                     bool updateOverlaps)
{
	(void)dispatcher;
	Edge* edges = m_pEdges[axis];
	Handle* self = getHandle(edges[edge].m_handle);
	const int axis1 = nextAxis(axis), axis2 = nextAxis(axis1);
	size_t index = edge;
	for (;;)
	{
		Edge& next = edges[index + 1];
		if (next.m_handle == 0 || !(next.m_pos < edges[index].m_pos)) break;
		Handle* other = getHandle(next.m_handle);
		if (!next.IsMax())
		{
			if (updateOverlaps && testOverlap2D(self, other, axis1, axis2)) addPair(self, other);
			--other->m_minEdges[axis];
		}
		else
		{
			--other->m_maxEdges[axis];
		}
		++self->m_maxEdges[axis];
		btSwap(edges[index], next);
		++index;
	}
}

template <typename BP_FP_INT_TYPE>
BP_FP_INT_TYPE btAxisSweep3Internal<BP_FP_INT_TYPE>::addHandle(const btVector3& aabbMin, const btVector3& aabbMax,
                                                               void* pOwner, int collisionFilterGroup,
                                                               int collisionFilterMask, btDispatcher* dispatcher)
{
	const bool finite = finiteBox(aabbMin, aabbMax);
	btAssert(finite && "btAxisSweep3: non-finite AABB");
	if (!finite) return 0;
	const BP_FP_INT_TYPE handleIndex = allocHandle();
	btAssert(handleIndex != 0 && "btAxisSweep3: all handles are in use (raise maxHandles)");
	if (handleIndex == 0) return 0;

	btVector3 clampedMin, clampedMax;
	clampToWorld(aabbMin, aabbMax, clampedMin, clampedMax);
	BP_FP_INT_TYPE minPos[3], maxPos[3];
	quantize(minPos, clampedMin, 0);
	quantize(maxPos, clampedMax, 1);

	Handle* handle = getHandle(handleIndex);
	handle->m_uniqueId = int(handleIndex);
	handle->m_clientObject = pOwner;
	handle->m_collisionFilterGroup = collisionFilterGroup;
	handle->m_collisionFilterMask = collisionFilterMask;
	handle->m_aabbMin = aabbMin;
	handle->m_aabbMax = aabbMax;
	handle->m_dbvtProxy = 0;

	// The new edges go just below the upper sentinel (above every box), then sink into place. Only the
	// last axis makes pairs: by then the other two already hold their final order.
	const size_t oldTop = 2 * size_t(m_numHandles - 1) + 1;  // the upper sentinel's index before the add
	for (int axis = 0; axis < 3; ++axis)
	{
		Edge* edges = m_pEdges[axis];
		edges[oldTop + 2] = edges[oldTop];
		m_pHandles[0].m_maxEdges[axis] = BP_FP_INT_TYPE(oldTop + 2);
		edges[oldTop].m_pos = minPos[axis];
		edges[oldTop].m_handle = handleIndex;
		edges[oldTop + 1].m_pos = maxPos[axis];
		edges[oldTop + 1].m_handle = handleIndex;
		handle->m_minEdges[axis] = BP_FP_INT_TYPE(oldTop);
		handle->m_maxEdges[axis] = BP_FP_INT_TYPE(oldTop + 1);
	}
	for (int axis = 0; axis < 3; ++axis)
	{
		const bool last = axis == 2;
		sortMinDown(axis, handle->m_minEdges[axis], dispatcher, last);
		sortMaxDown(axis, handle->m_maxEdges[axis], dispatcher, last);
	}
	return handleIndex;
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::removeHandle(BP_FP_INT_TYPE handleIndex, btDispatcher* dispatcher)
{
	const bool inUse =
	    handleIndex != 0 && handleIndex < m_maxHandles && getHandle(handleIndex)->m_uniqueId == int(handleIndex);
	btAssert(inUse && "btAxisSweep3: removing a handle that is not in use");
	if (!inUse) return;
	Handle* handle = getHandle(handleIndex);
	// Every pair goes now, deferred-removal cache or not: none may outlive its handle.
	m_pairCache->removeOverlappingPairsContainingProxy(handle, dispatcher);
	if (m_userPairCallback) m_userPairCallback->removeOverlappingPairsContainingProxy(handle, dispatcher);

	// Close the two gaps on each axis (max edge first: it is above the min edge).
	const size_t top = 2 * size_t(m_numHandles) + 1;
	for (int axis = 0; axis < 3; ++axis)
	{
		Edge* edges = m_pEdges[axis];
		const size_t gaps[2] = {handle->m_maxEdges[axis], handle->m_minEdges[axis]};
		size_t end = top;
		for (int g = 0; g < 2; ++g)
		{
			for (size_t i = gaps[g]; i < end; ++i)
			{
				edges[i] = edges[i + 1];
				Handle* moved = getHandle(edges[i].m_handle);
				if (edges[i].IsMax())
					moved->m_maxEdges[axis] = BP_FP_INT_TYPE(i);
				else
					moved->m_minEdges[axis] = BP_FP_INT_TYPE(i);
			}
			--end;
		}
	}
	freeHandle(handleIndex);
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::updateHandle(BP_FP_INT_TYPE handleIndex, const btVector3& aabbMin,
                                                        const btVector3& aabbMax, btDispatcher* dispatcher)
{
	const bool inUse =
	    handleIndex != 0 && handleIndex < m_maxHandles && getHandle(handleIndex)->m_uniqueId == int(handleIndex);
	btAssert(inUse && "btAxisSweep3: updating a handle that is not in use");
	if (!inUse) return;
	const bool finite = finiteBox(aabbMin, aabbMax);
	btAssert(finite && "btAxisSweep3: non-finite AABB");
	if (!finite) return;

	Handle* handle = getHandle(handleIndex);
	handle->m_aabbMin = aabbMin;
	handle->m_aabbMax = aabbMax;
	btVector3 clampedMin, clampedMax;
	clampToWorld(aabbMin, aabbMax, clampedMin, clampedMax);
	BP_FP_INT_TYPE minPos[3], maxPos[3];
	quantize(minPos, clampedMin, 0);
	quantize(maxPos, clampedMax, 1);

	for (int axis = 0; axis < 3; ++axis)
	{
		Edge* edges = m_pEdges[axis];
		const BP_FP_INT_TYPE oldMin = edges[handle->m_minEdges[axis]].m_pos;
		const BP_FP_INT_TYPE oldMax = edges[handle->m_maxEdges[axis]].m_pos;
		edges[handle->m_minEdges[axis]].m_pos = minPos[axis];
		edges[handle->m_maxEdges[axis]].m_pos = maxPos[axis];
		// Grow first, then shrink, so that an edge never has to pass the other edge of its own box.
		if (minPos[axis] < oldMin) sortMinDown(axis, handle->m_minEdges[axis], dispatcher, true);
		if (maxPos[axis] > oldMax) sortMaxUp(axis, handle->m_maxEdges[axis], dispatcher, true);
		if (minPos[axis] > oldMin) sortMinUp(axis, handle->m_minEdges[axis], dispatcher, true);
		if (maxPos[axis] < oldMax) sortMaxDown(axis, handle->m_maxEdges[axis], dispatcher, true);
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::calculateOverlappingPairs(btDispatcher* dispatcher)
{
	if (!m_pairCache->hasDeferredRemoval()) return;
	btBroadphasePairArray& pairs = m_pairCache->getOverlappingPairArray();
	m_stalePairs.resize(0);
	for (int i = 0; i < pairs.size(); ++i)
	{
		if (!testAabbOverlap(pairs[i].m_pProxy0, pairs[i].m_pProxy1)) m_stalePairs.push_back(pairs[i]);
	}
	m_invalidPair = m_stalePairs.size();
	for (int i = 0; i < m_stalePairs.size(); ++i)
	{
		btBroadphaseProxy* proxy0 = m_stalePairs[i].m_pProxy0;
		btBroadphaseProxy* proxy1 = m_stalePairs[i].m_pProxy1;
		m_pairCache->removeOverlappingPair(proxy0, proxy1, dispatcher);
		if (m_userPairCallback) m_userPairCallback->removeOverlappingPair(proxy0, proxy1, dispatcher);
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::processAllOverlappingPairs(btOverlapCallback* callback)
{
	m_pairCache->processAllOverlappingPairs(callback, 0);
}

template <typename BP_FP_INT_TYPE>
btBroadphaseProxy* btAxisSweep3Internal<BP_FP_INT_TYPE>::createProxy(const btVector3& aabbMin, const btVector3& aabbMax,
                                                                     int shapeType, void* userPtr,
                                                                     int collisionFilterGroup, int collisionFilterMask,
                                                                     btDispatcher* dispatcher)
{
	const BP_FP_INT_TYPE handleIndex =
	    addHandle(aabbMin, aabbMax, userPtr, collisionFilterGroup, collisionFilterMask, dispatcher);
	if (handleIndex == 0) return 0;
	Handle* handle = getHandle(handleIndex);
	if (m_raycastAccelerator)
	{
		handle->m_dbvtProxy = m_raycastAccelerator->createProxy(aabbMin, aabbMax, shapeType, userPtr,
		                                                        collisionFilterGroup, collisionFilterMask, dispatcher);
	}
	return handle;
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher)
{
	if (!proxy) return;
	// Handle 0 is the sentinel, never handed out.
	const bool ours = pointsInto(proxy, m_pHandles + 1, m_pHandles + size_t(m_maxHandles));
	btAssert(ours && "btAxisSweep3::destroyProxy: not a proxy of this broadphase");
	if (!ours) return;
	const Handle* handle = static_cast<const Handle*>(proxy);
	const BP_FP_INT_TYPE handleIndex = BP_FP_INT_TYPE(handle - m_pHandles);
	if (handle->m_uniqueId == int(handleIndex) && m_raycastAccelerator && handle->m_dbvtProxy)
		m_raycastAccelerator->destroyProxy(handle->m_dbvtProxy, dispatcher);
	removeHandle(handleIndex, dispatcher);
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin,
                                                   const btVector3& aabbMax, btDispatcher* dispatcher)
{
	btAssert(proxy && "btAxisSweep3::setAabb: null proxy");
	if (!proxy) return;
	const bool ours = pointsInto(proxy, m_pHandles + 1, m_pHandles + size_t(m_maxHandles));
	btAssert(ours && "btAxisSweep3::setAabb: not a proxy of this broadphase");
	if (!ours) return;
	Handle* handle = static_cast<Handle*>(proxy);
	const BP_FP_INT_TYPE handleIndex = BP_FP_INT_TYPE(handle - m_pHandles);
	if (handle->m_uniqueId != int(handleIndex))
	{
		btAssert(!"btAxisSweep3::setAabb: the proxy was destroyed");
		return;
	}
	if (!finiteBox(aabbMin, aabbMax))
	{
		btAssert(!"btAxisSweep3::setAabb: non-finite AABB");
		return;
	}
	updateHandle(handleIndex, aabbMin, aabbMax, dispatcher);
	if (m_raycastAccelerator && handle->m_dbvtProxy)
		m_raycastAccelerator->setAabb(handle->m_dbvtProxy, aabbMin, aabbMax, dispatcher);
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin,
                                                   btVector3& aabbMax) const
{
	btAssert(proxy && "btAxisSweep3::getAabb: null proxy");
	if (!proxy)
	{
		aabbMin.setValue(0, 0, 0);
		aabbMax.setValue(0, 0, 0);
		return;
	}
	aabbMin = proxy->m_aabbMin;
	aabbMax = proxy->m_aabbMax;
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::rayTest(const btVector3& rayFrom, const btVector3& rayTo,
                                                   btBroadphaseRayCallback& rayCallback, const btVector3& aabbMin,
                                                   const btVector3& aabbMax)
{
	if (m_raycastAccelerator)
	{
		m_raycastAccelerator->rayTest(rayFrom, rayTo, rayCallback, aabbMin, aabbMax);
		return;
	}
	// Without the accelerator: every box, in axis-0 order (min edges only, sentinels skipped).
	const Edge* edges = m_pEdges[0];
	const size_t top = 2 * size_t(m_numHandles) + 1;
	for (size_t i = 1; i < top; ++i)
	{
		if (edges[i].IsMax()) continue;
		Handle* handle = getHandle(edges[i].m_handle);
		const btVector3 bounds[2] = {handle->m_aabbMin - aabbMax, handle->m_aabbMax - aabbMin};
		btScalar lambda;
		if (btRayAabb2(rayFrom, rayCallback.m_rayDirectionInverse, rayCallback.m_signs, bounds, lambda, btScalar(0),
		               rayCallback.m_lambda_max))
			rayCallback.process(handle);
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::aabbTest(const btVector3& aabbMin, const btVector3& aabbMax,
                                                    btBroadphaseAabbCallback& callback)
{
	if (m_raycastAccelerator)
	{
		m_raycastAccelerator->aabbTest(aabbMin, aabbMax, callback);
		return;
	}
	const Edge* edges = m_pEdges[0];
	const size_t top = 2 * size_t(m_numHandles) + 1;
	for (size_t i = 1; i < top; ++i)
	{
		if (edges[i].IsMax()) continue;
		Handle* handle = getHandle(edges[i].m_handle);
		if (TestAabbAgainstAabb2(aabbMin, aabbMax, handle->m_aabbMin, handle->m_aabbMax)) callback.process(handle);
	}
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const
{
	aabbMin = m_worldAabbMin;
	aabbMax = m_worldAabbMax;
}

template <typename BP_FP_INT_TYPE>
void btAxisSweep3Internal<BP_FP_INT_TYPE>::printStats()
{
	printf("btAxisSweep3: %u of %u handles in use, %d pairs, ray accelerator %s\n", unsigned(m_numHandles),
	       unsigned(m_maxHandles - 1), m_pairCache->getNumOverlappingPairs(), m_raycastAccelerator ? "on" : "off");
}

template class btAxisSweep3Internal<unsigned short int>;
template class btAxisSweep3Internal<unsigned int>;
