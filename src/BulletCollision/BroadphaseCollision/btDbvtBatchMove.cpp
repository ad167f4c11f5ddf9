// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// caliber::moveProxiesToFatBoxes: the moves of many proxies' leaves, with the refits of the dynamic tree on
// the task scheduler's threads, leaving every node exactly as the moves one by one in order would.
//
// Most moved leaves are refitted in place (refitLeafNearSibling): the leaf's volume, then its ancestors until
// one already contains it. The tree is cut at depth kSubtreeDepth into subtrees; a refit that stops inside
// its subtree reads and writes nothing outside it, so refits in different subtrees commute, and each
// subtree's refits run in order on some thread. Three things need care:
// - A refit that grows the subtree's root would go on into the nodes above, which all subtrees share: the
//   thread stops at the root and notes the root's volume and the leaf's box ("escape"); the calling thread
//   then replays the escapes in the moves' order, setting the root to the noted volume before growing the
//   nodes above, so each of those nodes sees the volumes it would have seen one move at a time. (Refits
//   inside a subtree never change its root, so the roots change only at escapes.)
// - A leaf that left its sibling is re-inserted, which may read or restructure a larger part of the tree. Its
//   subtree's thread stops there and the calling thread does the rest of that subtree's moves in order;
//   before a re-insertion that reaches into other subtrees, those undo (from a log of every volume changed)
//   the refits their threads did for later moves, which are then redone in order on the calling thread.
// - The calling thread does every move the threads did not, and the stage-list bookkeeping of every move,
//   in the moves' order.

#include <new>

#include "BulletCollision/BroadphaseCollision/btDbvtAabbFastPath.h"
#include "BulletCollision/BroadphaseCollision/btDbvtProxyIds.h"
#include "BulletCollision/BroadphaseCollision/btDbvtRefit.h"
#include "LinearMath/btThreads.h"

namespace
{
// The cut: up to 2^kSubtreeDepth subtrees, enough for two or three threads to share out evenly.
const int kSubtreeDepth = 4;
const int kSubtrees = 1 << kSubtreeDepth;
// Fewer moves than this go one by one (a loop on the threads costs about a microsecond).
const int kMinMovesForThreads = 256;
const int kMovesPerFindTask = 256;

struct Escape
{
	int move;
	btDbvtVolume rootVolume;  // the subtree root's volume right after this move's refit
	btDbvtVolume fitted;      // the leaf's new volume
};

// One subtree's work, padded so that two threads' array headers never share a cache line.
struct SubtreeWork
{
	btDbvtNode* root;
	btDbvtVolume originalRootVolume;
	btAlignedObjectArray<int> moves;  // the moves of its leaves, ascending
	int done;                         // moves[0, done) are applied
	btAlignedObjectArray<caliber::DbvtVolumeChange> changes;
	btAlignedObjectArray<Escape> escapes;
	int nextEscape;
	char padding[128];
};

struct BatchScratch
{
	btAlignedObjectArray<int> subtreeOf;  // per move: its subtree, or -1 (fixed tree, or a leaf above the cut)
	btAlignedObjectArray<int> rank;       // per move: its place in its subtree's list
	SubtreeWork subtrees[kSubtrees];
};

BatchScratch& batchScratch()
{
	static thread_local BatchScratch scratch;
	return scratch;
}

SIMD_FORCE_INLINE btDbvtNode* leafOf(const caliber::DbvtMove& move)
{
	return static_cast<btDbvtProxy*>(move.proxy)->leaf;
}

// Each move's subtree: the child choices of its leaf's ancestors at depths 1 to kSubtreeDepth, as bits.
struct FindSubtrees : public btIParallelForBody
{
	const caliber::DbvtMove* moves;
	int* subtreeOf;

	void forLoop(int begin, int end) const override
	{
		for (int i = begin; i < end; ++i)
		{
			subtreeOf[i] = -1;
			if (caliber::dbvtTreeOf(*moves[i].proxy) != btDbvtBroadphase::DYNAMIC_SET) continue;
			const btDbvtNode* node = leafOf(moves[i]);
			int depth = 0;
			for (const btDbvtNode* n = node; n->parent; n = n->parent) ++depth;
			if (depth <= kSubtreeDepth) continue;
			for (int k = depth - kSubtreeDepth; k > 0; --k) node = node->parent;
			int slot = 0;
			for (int bit = 0; bit < kSubtreeDepth; ++bit, node = node->parent)
				slot |= (node->parent->childs[1] == node ? 1 : 0) << bit;
			subtreeOf[i] = slot;
		}
	}
};

// The refits of each subtree's moves in order, up to its first move that needs a re-insertion.
struct RefitSubtrees : public btIParallelForBody
{
	const caliber::DbvtMove* moves;
	BatchScratch* scratch;

	void forLoop(int begin, int end) const override
	{
		for (int s = begin; s < end; ++s)
		{
			SubtreeWork& work = scratch->subtrees[s];
			for (; work.done < work.moves.size(); ++work.done)
			{
				const int m = work.moves[work.done];
				const btDbvtVolume box = btDbvtVolume::FromMM(moves[m].fatMin, moves[m].fatMax);
				Escape escape;
				const caliber::DbvtSubtreeRefit result =
				    caliber::refitLeafInSubtree(leafOf(moves[m]), box, work.root, m, work.changes, escape.fitted);
				if (result == caliber::kDbvtRefitNeedsReinsert) break;
				if (result == caliber::kDbvtRefitThroughRoot)
				{
					escape.move = m;
					escape.rootVolume = work.root->volume;
					work.escapes.push_back(escape);
				}
			}
		}
	}
};

// Undoes, newest first, the subtree's refits of moves after `move`; they count as not done.
void undoMovesAfter(SubtreeWork& work, int move)
{
	while (work.done > 0 && work.moves[work.done - 1] > move)
	{
		const int m = work.moves[work.done - 1];
		while (work.changes.size() > 0 && work.changes[work.changes.size() - 1].move == m)
		{
			const caliber::DbvtVolumeChange& change = work.changes[work.changes.size() - 1];
			change.node->volume = change.previous;
			work.changes.pop_back();
		}
		if (work.escapes.size() > work.nextEscape && work.escapes[work.escapes.size() - 1].move == m)
			work.escapes.pop_back();
		--work.done;
	}
}

// Subtree s's root before the moves.
btDbvtNode* subtreeRoot(const btDbvt& tree, int s)
{
	btDbvtNode* node = tree.m_root;
	for (int level = kSubtreeDepth - 1; level >= 0; --level) node = node->childs[(s >> level) & 1];
	return node;
}

// Whether node is under ancestor (or is it).
bool isUnder(const btDbvtNode* node, const btDbvtNode* ancestor)
{
	for (; node; node = node->parent)
		if (node == ancestor) return true;
	return false;
}

// The re-insertion of move i's leaf, on the calling thread. The removal reads and writes only the leaf's own
// subtree (none of whose later moves were done on the threads) and nodes above the cut, which the threads did
// not touch. The insertion reads and writes only nodes under the first ancestor of its search's start (the
// start included) that contains the leaf: the search stays under the start, and the growth of the ancestors,
// with the rotations that go with it, stops at that ancestor. The subtrees under it that did later moves on
// the threads undo those first (they are then redone in order on this thread). A subtree that still has such
// moves has had no re-insertion, so its root is still the node it started with. lastDone: the latest move
// still done on the threads.
void reinsert(btDbvt& tree, BatchScratch& scratch, int i, int& lastDone, btDbvtNode* leaf, const btDbvtVolume& box)
{
	btDbvtNode* start = caliber::detachLeafForUpdate(tree, leaf, box);
	if (lastDone > i)
	{
		const btDbvtNode* reach = start;
		while (reach && !reach->volume.Contain(leaf->volume)) reach = reach->parent;
		lastDone = -1;
		for (int s = 0; s < kSubtrees; ++s)
		{
			SubtreeWork& work = scratch.subtrees[s];
			if (work.done == 0) continue;
			if (work.moves[work.done - 1] > i && (!reach || isUnder(work.root, reach))) undoMovesAfter(work, i);
			if (work.done > 0) lastDone = btMax(lastDone, work.moves[work.done - 1]);
		}
	}
	caliber::attachLeafUnder(tree, start, leaf);
}
}  // namespace

void caliber::moveProxiesToFatBoxes(btDbvtBroadphase& broadphase, const DbvtMove* moves, int count)
{
	btDbvt& tree = broadphase.m_sets[btDbvtBroadphase::DYNAMIC_SET];
	btITaskScheduler* scheduler = btGetTaskScheduler();
	if (count < kMinMovesForThreads || !scheduler || scheduler->getNumThreads() < 2 || !tree.m_root)
	{
		for (int i = 0; i < count; ++i) moveProxyToFatBox(broadphase, moves[i].proxy, moves[i].fatMin, moves[i].fatMax);
		return;
	}
	BatchScratch& scratch = batchScratch();
	scratch.subtreeOf.resizeNoInitialize(count);
	scratch.rank.resizeNoInitialize(count);
	FindSubtrees find;
	find.moves = moves;
	find.subtreeOf = &scratch.subtreeOf[0];
	btParallelFor(0, count, kMovesPerFindTask, find);

	for (int s = 0; s < kSubtrees; ++s)
	{
		SubtreeWork& work = scratch.subtrees[s];
		work.moves.resize(0);
		work.done = 0;
		work.changes.resize(0);
		work.escapes.resize(0);
		work.nextEscape = 0;
	}
	for (int i = 0; i < count; ++i)
	{
		const int s = scratch.subtreeOf[i];
		if (s < 0) continue;
		btAlignedObjectArray<int>& list = scratch.subtrees[s].moves;
		scratch.rank[i] = list.size();
		list.push_back(i);
	}
	for (int s = 0; s < kSubtrees; ++s)
	{
		SubtreeWork& work = scratch.subtrees[s];
		if (work.moves.size() == 0) continue;
		work.root = subtreeRoot(tree, s);
		work.originalRootVolume = work.root->volume;
	}
	RefitSubtrees refit;
	refit.moves = moves;
	refit.scratch = &scratch;
	btParallelFor(0, kSubtrees, 1, refit);

	// The roots go back to their volumes before the moves; the escapes set them again in order.
	int lastDone = -1;  // the latest move done on the threads
	for (int s = 0; s < kSubtrees; ++s)
	{
		SubtreeWork& work = scratch.subtrees[s];
		if (work.escapes.size() > 0) work.root->volume = work.originalRootVolume;
		if (work.done > 0) lastDone = btMax(lastDone, work.moves[work.done - 1]);
	}
	for (int i = 0; i < count; ++i)
	{
		btBroadphaseProxy* proxy = moves[i].proxy;
		const int s = scratch.subtreeOf[i];
		if (s >= 0 && scratch.rank[i] < scratch.subtrees[s].done)
		{
			SubtreeWork& work = scratch.subtrees[s];
			if (work.nextEscape < work.escapes.size() && work.escapes[work.nextEscape].move == i)
			{
				const Escape& escape = work.escapes[work.nextEscape++];
				work.root->volume = escape.rootVolume;
				refitAncestorsAbove(work.root->parent, escape.fitted);
			}
		}
		else
		{
			btDbvtVolume box = btDbvtVolume::FromMM(moves[i].fatMin, moves[i].fatMax);
			btDbvtNode* leaf = leafOf(moves[i]);
			const int set = dbvtTreeOf(*proxy);
			if (set != btDbvtBroadphase::DYNAMIC_SET)
				broadphase.m_sets[set].update(leaf, box);
			else if (!refitLeafNearSibling(leaf, box))
				reinsert(tree, scratch, i, lastDone, leaf, box);
		}
		++broadphase.m_updates_done;
		queueMovedProxy(broadphase, proxy);
	}
}
