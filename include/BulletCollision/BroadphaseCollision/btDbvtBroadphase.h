// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DBVT_BROADPHASE_H
#define BT_DBVT_BROADPHASE_H

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"

/// Margin added on every side of a proxy's AABB when its tree box is rebuilt, so that small moves stay
/// inside the box and leave the tree and the pairs untouched (world units; default 0.05).
extern btScalar gDbvtMargin;

/// A proxy of btDbvtBroadphase: its leaf in one of the two trees and its place in a stage list.
struct btDbvtProxy : public btBroadphaseProxy
{
	/// The tree leaf; its volume is the enlarged ("fat") AABB that pairs are computed from.
	btDbvtNode* leaf;
	/// Previous and next proxy in the stage list (see btDbvtBroadphase::m_stageRoots).
	btDbvtProxy* links[2];
	/// The stage list holding the proxy: DYNAMIC_SET or FIXED_SET while its pairs must be searched,
	/// STAGECOUNT once they are up to date. (Which tree holds the leaf is the parity of m_uniqueId: even
	/// for DYNAMIC_SET, odd for FIXED_SET.)
	int stage;

	/// A proxy for userPtr with the given AABB and filtering, not yet in a tree.
	btDbvtProxy(const btVector3& aabbMin, const btVector3& aabbMax, void* userPtr, int collisionFilterGroup,
	            int collisionFilterMask)
	    : btBroadphaseProxy(aabbMin, aabbMax, userPtr, collisionFilterGroup, collisionFilterMask),
	      leaf(0),
	      stage(0)
	{
		links[0] = links[1] = 0;
	}
};

/// An array of dbvt proxies.
typedef btAlignedObjectArray<btDbvtProxy*> btDbvtProxyArray;

/// The default broadphase: two dynamic AABB trees (btDbvt), one for moving proxies and one for fixed
/// ones (filter group StaticFilter at creation). A proxy's tree box is its AABB grown by gDbvtMargin and,
/// in the direction it moved, by m_prediction times its last displacement; setAabb touches the tree only
/// when the new AABB leaves that box. calculateOverlappingPairs searches pairs only for proxies whose
/// box changed (one tree query each), removes their pairs whose boxes separated, and re-inserts a few
/// leaves to keep the trees balanced. After it, the cache holds exactly the filtered pairs whose tree
/// boxes overlap: every pair whose AABBs overlap is present, and every present pair's boxes overlap.
struct btDbvtBroadphase : public btBroadphaseInterface
{
	/// Indices of the two trees; STAGECOUNT is the stage of proxies whose pairs are up to date.
	enum
	{
		DYNAMIC_SET = 0,
		FIXED_SET = 1,
		STAGECOUNT = 2
	};

	/// The trees: m_sets[DYNAMIC_SET] for moving proxies, m_sets[FIXED_SET] for static ones.
	btDbvt m_sets[2];
	/// Heads of the stage lists: [DYNAMIC_SET] and [FIXED_SET] hold proxies of that tree whose box changed
	/// since the last collide (pair search pending); [STAGECOUNT] holds every other proxy.
	btDbvtProxy* m_stageRoots[STAGECOUNT + 1];
	/// The pair cache (owned when m_releasepaircache).
	btOverlappingPairCache* m_paircache;
	/// How far ahead of its motion a moved box is grown, in units of the last displacement (default 1).
	btScalar m_prediction;
	/// Number of collide calls so far.
	int m_stageCurrent;
	/// Percentage of the fixed tree's leaves re-inserted per collide while it has changes to absorb.
	int m_fupdates;
	/// Percentage of the dynamic tree's leaves re-inserted per collide (plus one).
	int m_dupdates;
	/// Kept for source compatibility (Bullet's cleanup percentage): every stale pair is removed each step.
	int m_cupdates;
	/// Pairs added by the last collide.
	int m_newpairs;
	/// Fixed-tree re-insertions still owed after static proxies were added or moved.
	int m_fixedleft;
	/// setAabb calls since the last collide.
	unsigned m_updates_call;
	/// setAabb calls since the last collide that had to move a tree box.
	unsigned m_updates_done;
	/// m_updates_done / m_updates_call of the last collide (0 without calls).
	btScalar m_updates_ratio;
	/// Leaf re-insertions done by the incremental optimisation so far.
	int m_pid;
	/// Kept for source compatibility (Bullet's cleanup cursor; always 0).
	int m_cid;
	/// Number of proxies made (since the last resetPool); a proxy's unique id is twice its number, plus
	/// one in the fixed tree.
	int m_gid;
	/// True when the broadphase created the cache and deletes it.
	bool m_releasepaircache;
	/// Kept for source compatibility: pair search always waits for calculateOverlappingPairs.
	bool m_deferedcollide;
	/// True when some proxy's box changed since the last collide.
	bool m_needcleanup;
	/// Traversal stacks of rayTest (one; kept between calls so that rays allocate nothing).
	btAlignedObjectArray<btAlignedObjectArray<const btDbvtNode*>> m_rayTestStacks;

	/// Uses paircache when given (the caller keeps ownership), else creates and owns a
	/// btHashedOverlappingPairCache. The cache must return the stored pair when an existing pair is added.
	btDbvtBroadphase(btOverlappingPairCache* paircache = 0);
	~btDbvtBroadphase() override;

	/// Searches the pairs of proxies whose boxes changed, removes their stale pairs, optimises the trees.
	void collide(btDispatcher* dispatcher);
	/// Rebuilds both trees top-down (for a good tree after loading a scene).
	void optimize();

	/// A new proxy (pairs appear at the next calculateOverlappingPairs). A non-finite AABB asserts and
	/// returns 0; the caller must not use the object in this broadphase.
	btBroadphaseProxy* createProxy(const btVector3& aabbMin, const btVector3& aabbMax, int shapeType, void* userPtr,
	                               int collisionFilterGroup, int collisionFilterMask,
	                               btDispatcher* dispatcher) override;
	/// Removes the proxy, its leaf and its pairs now. 0 is ignored.
	void destroyProxy(btBroadphaseProxy* proxy, btDispatcher* dispatcher) override;
	/// Stores the AABB; moves the tree box only when the AABB left it. A non-finite AABB asserts and is
	/// ignored (the proxy keeps its previous AABB).
	void setAabb(btBroadphaseProxy* proxy, const btVector3& aabbMin, const btVector3& aabbMax,
	             btDispatcher* dispatcher) override;
	/// Reports every proxy whose AABB, grown by [aabbMin, aabbMax], the ray hits within the callback's
	/// m_lambda_max (the trees prune with the boxes, each proxy is then tested against its own AABB).
	void rayTest(const btVector3& rayFrom, const btVector3& rayTo, btBroadphaseRayCallback& rayCallback,
	             const btVector3& aabbMin = btVector3(0, 0, 0), const btVector3& aabbMax = btVector3(0, 0, 0)) override;
	/// Reports every proxy whose AABB overlaps [aabbMin, aabbMax].
	void aabbTest(const btVector3& aabbMin, const btVector3& aabbMax, btBroadphaseAabbCallback& callback) override;
	/// The proxy's AABB as last set.
	void getAabb(btBroadphaseProxy* proxy, btVector3& aabbMin, btVector3& aabbMax) const override;
	/// collide(dispatcher).
	void calculateOverlappingPairs(btDispatcher* dispatcher) override;
	/// The pair cache.
	btOverlappingPairCache* getOverlappingPairCache() override { return m_paircache; }
	/// The pair cache.
	const btOverlappingPairCache* getOverlappingPairCache() const override { return m_paircache; }
	/// The union of both trees' boxes (zero when empty).
	void getBroadphaseAabb(btVector3& aabbMin, btVector3& aabbMax) const override;
	/// Prints the trees' sizes and depths and the pair count.
	void printStats() override;
	/// When no proxy is left, empties the trees and restarts ids and counters.
	void resetPool(btDispatcher* dispatcher) override;

	/// Removes every pair whose tree boxes do not overlap (a full pass; collide already keeps the cache
	/// exact, so this is only needed after pairs were added to the cache by hand).
	void performDeferredRemoval(btDispatcher* dispatcher);

	/// Sets m_prediction (negative values are treated as 0).
	void setVelocityPrediction(btScalar prediction)
	{
		m_prediction = prediction > btScalar(0) ? prediction : btScalar(0);
	}
	/// m_prediction.
	btScalar getVelocityPrediction() const { return m_prediction; }

	/// Sets the AABB and makes the tree box exactly that AABB (no margin, no prediction), even when it fits
	/// in the old box; pairs follow at the next collide.
	void setAabbForceUpdate(btBroadphaseProxy* absproxy, const btVector3& aabbMin, const btVector3& aabbMax,
	                        btDispatcher* dispatcher);

	/// Bullet's self benchmark; Caliber's lives in Demos/Benchmarks/CollisionBench/BroadphaseBench.cpp.
	static void benchmark(btBroadphaseInterface*) {}

private:
	btDbvtBroadphase(const btDbvtBroadphase&);
	btDbvtBroadphase& operator=(const btDbvtBroadphase&);
};

#endif  // BT_DBVT_BROADPHASE_H
