// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_OVERLAPPING_PAIR_CALLBACK_H
#define BT_OVERLAPPING_PAIR_CALLBACK_H

class btDispatcher;
struct btBroadphaseProxy;
struct btBroadphasePair;

/// Receives pair additions and removals from a broadphase. The pair caches implement it, and a ghost
/// pair callback (btGhostPairCallback) implements it to mirror the pairs of ghost objects.
class btOverlappingPairCallback
{
protected:
	btOverlappingPairCallback() {}

public:
	virtual ~btOverlappingPairCallback() {}

	/// Records that the two proxies' AABBs started to overlap; returns the stored pair (or 0 if filtered out).
	virtual btBroadphasePair* addOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1) = 0;

	/// Forgets the pair of the two proxies (in either order); returns the pair's user info (m_internalInfo1).
	virtual void* removeOverlappingPair(btBroadphaseProxy* proxy0, btBroadphaseProxy* proxy1,
	                                    btDispatcher* dispatcher) = 0;

	/// Forgets every pair that contains the proxy (called before the proxy is destroyed).
	virtual void removeOverlappingPairsContainingProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) = 0;
};

#endif  // BT_OVERLAPPING_PAIR_CALLBACK_H
