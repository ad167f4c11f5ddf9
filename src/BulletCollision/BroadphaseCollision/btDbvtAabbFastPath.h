// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DBVT_AABB_FAST_PATH_H
#define CALIBER_DBVT_AABB_FAST_PATH_H

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"

namespace caliber
{
/// The first half of btDbvtBroadphase::setAabb for a finite AABB of a live proxy: stores the AABB and
/// returns false when it still fits in the fat box; otherwise stores it too, writes the proxy's new tree
/// box (fat and stretched along the move, as setAabb makes it) to fatMin / fatMax (which may be aabbMin /
/// aabbMax) and returns true, and the caller passes that box to moveProxyToFatBox. It reads the broadphase
/// and writes only this proxy, so the collision world calls it for many objects at once on the task
/// scheduler's threads, and adds the calls to m_updates_call afterwards.
bool storeAabbOrFatBox(const btDbvtBroadphase& broadphase, btBroadphaseProxy* proxy, const btVector3& aabbMin,
                       const btVector3& aabbMax, btVector3& fatMin, btVector3& fatMax);

/// The second half of setAabb for a proxy that left its fat box (storeAabbOrFatBox returned true): moves
/// its leaf to the new tree box and queues its pair search; counts one update done. The caller calls it on
/// one thread, in the order the serial setAabb calls would come, and adds the calls to m_updates_call.
/// Returns true when the leaf was re-inserted (the costly move: a search for its new sibling), false when
/// its box was refitted in place (the collision world weighs its box loop's sides with it).
bool moveProxyToFatBox(btDbvtBroadphase& broadphase, btBroadphaseProxy* proxy, const btVector3& fatMin,
                       const btVector3& fatMax);

/// A proxy that left its fat box and its new tree box (storeAabbOrFatBox's result).
struct DbvtProxyMove
{
	btVector3 fatMin, fatMax;
	btBroadphaseProxy* proxy;
};

/// moveProxyToFatBox for each move, in array order, with the same result (the tree node by node, the stage
/// lists, the counters). With a task scheduler of several threads and enough moves, the moves whose leaves
/// lie in different subtrees a few levels below the dynamic tree's root run on different threads, each
/// subtree's in order, and their steps on the nodes above the subtrees are replayed in move order on the
/// calling thread; a move that needs a node inside another subtree runs alone, in its place in the order.
/// Called by one thread, outside parallel loops, while nothing else uses the broadphase. The collision world
/// does not call it (a separate loop after the boxes loses their overlap with the moves: slower in the mesh
/// scenes); it can make its moves inside its box loop with DbvtMoveRound below. stats, when given, receives
/// what happened.
struct DbvtParallelMoveStats
{
	int rounds = 0;          // parallel loops run
	int movesOnThreads = 0;  // moves kept from those loops
	int movesUndone = 0;     // moves a task made at or after its round's bound, undone
	int movesAlone = 0;      // moves made in order on the calling thread
	int topStops = 0;        // rounds ended by a move whose steps above the subtrees could not be replayed
};
void moveProxiesToFatBoxes(btDbvtBroadphase& broadphase, const DbvtProxyMove* moves, int count,
                           DbvtParallelMoveStats* stats = 0);

/// The parallel tree moves as a loop's tasks make them, for a caller that finds the moves while the loop
/// runs (the collision world's box loop). begin takes the subtrees; a task per subtree then calls
/// moveWithin for the moves of its subtree's leaves, in order of their slots (any increasing numbers, the
/// serial order of the moves); after the loop the calling thread calls finish, which keeps the moves below a
/// slot `end` (replaying their steps above the subtrees in slot order and queueing their pair searches) and
/// undoes the others. Which subtree holds a proxy's leaf does not change during the loop (a move that would
/// change it is refused), so the caller finds it before the loop (subtreeRoot, a walk of the tree).
/// Whether btCollisionWorld::updateAabbs makes the dbvt broadphase's tree moves with DbvtMoveRound inside
/// its box loop (true) or on one task overlapping the boxes (false, the default: by the instruction counts
/// of the mesh scenes the round's overheads, its undo log, the replay and the merge on the calling thread,
/// cost about what the second thread saves; docs/threading.md, "Twelfth session"). Either way the results
/// are the same bits. Process-wide; set it only while no world steps.
bool subtreeMovesInWorld();
void setSubtreeMovesInWorld(bool on);

class DbvtMoveRound
{
public:
	enum
	{
		kMaxSubtrees = 8
	};
	/// False when the moves must be made in order instead (no subtree, or the tree re-inserts from its root).
	/// Called by one thread, outside parallel loops, while nothing else uses the broadphase.
	bool begin(btDbvtBroadphase& broadphase);
	int numSubtrees() const { return m_numSubtrees; }
	/// Null for an entry that heads no subtree (a leaf that high in the tree).
	const btDbvtNode* subtreeRoot(int subtree) const { return m_subtrees[subtree]; }
	/// On subtree `subtree`'s task only, slots increasing: moves the proxy's leaf (in that subtree) to its
	/// fat box as moveProxyToFatBox would, but not its pair search or counter. False, with nothing changed,
	/// when the move needs a node outside the subtree: the round must end before slot.
	bool moveWithin(int subtree, int slot, btBroadphaseProxy* proxy, const btVector3& fatMin,
	                const btVector3& fatMax) const;
	/// After the loop: keeps the moves made at slots below end, in slot order, and undoes the others; returns
	/// the slot where the kept moves end (end, or a move whose steps above the subtrees cannot be replayed,
	/// which the caller then makes in order with the moves after it).
	int finish(int end, DbvtParallelMoveStats* stats = 0);

private:
	btDbvtBroadphase* m_broadphase = 0;
	const btDbvtNode* m_subtrees[kMaxSubtrees];
	btDbvtNode* m_topNodes[kMaxSubtrees];
	int m_numSubtrees = 0;
	int m_numTopNodes = 0;
	void* m_scratch = 0;
};
}  // namespace caliber

#endif  // CALIBER_DBVT_AABB_FAST_PATH_H
