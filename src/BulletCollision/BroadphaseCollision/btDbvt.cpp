// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/BroadphaseCollision/btDbvtRefit.h"

#include <algorithm>
#include <new>

#include "LinearMath/btSideTable.h"

// Design (see docs, "btDbvt"):
// - Nodes come from blocks owned by the tree and are recycled through a free list (Bullet's m_free, linked
//   through parent), so that a tree in steady state (as many inserts as removes) never allocates. Leaves
//   never move in memory. btDbvt declares only Bullet's members: the blocks are listed in a side table
//   (looked up when the free list runs dry and when the tree drops its nodes, never per insert), the
//   insertion's search stack lives on the C++ stack and the rebuilds' arrays are per thread.
// - Insertion chooses the sibling that minimises the total surface area added to the tree: the area of
//   the new parent plus the growth of every ancestor. The search is a branch and bound over the whole
//   tree: a subtree is skipped when even a perfect fit inside it (the leaf's own area plus the growth
//   its ancestors already incur) cannot beat the best sibling found so far.
// - Removal replaces the leaf's parent by the leaf's sibling and refits the ancestors, stopping at the
//   first one whose box does not change.

namespace
{
/// Half the surface area of a box: the cost insertion minimises (the factor 2 changes no decision).
SIMD_FORCE_INLINE btScalar halfArea(const btDbvtVolume& v)
{
	const btVector3 l = v.Lengths();
	return l.x() * l.y() + l.y() * l.z() + l.z() * l.x();
}

SIMD_FORCE_INLINE btDbvtVolume merged(const btDbvtVolume& a, const btDbvtVolume& b)
{
	btDbvtVolume r;
	Merge(a, b, r);
	return r;
}

/// The volume stored for a leaf: NaN anywhere asserts and gives the empty box (inverted, so it merges
/// as nothing and overlaps nothing); infinities assert and are clamped to +-BT_LARGE_FLOAT.
btDbvtVolume sanitizedVolume(const btDbvtVolume& v)
{
	// x - x is 0 for a finite x and NaN for an infinity or a NaN, so the sum of the six is 0 exactly when
	// every bound is finite: one test on the common path (every moved leaf passes here).
	const btVector3& mins = v.Mins();
	const btVector3& maxs = v.Maxs();
	const btScalar finiteTest = ((mins.x() - mins.x()) + (mins.y() - mins.y())) + ((mins.z() - mins.z()) +
	                            (maxs.x() - maxs.x())) + ((maxs.y() - maxs.y()) + (maxs.z() - maxs.z()));
	if (btLikely(finiteTest == btScalar(0))) return v;
	bool hasNaN = false;
	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar lo = v.Mins()[axis], hi = v.Maxs()[axis];
		hasNaN |= (lo != lo) || (hi != hi);
	}
	btAssert(false && "btDbvt: non-finite leaf volume");
	const btScalar big = btScalar(BT_LARGE_FLOAT);
	if (hasNaN) return btDbvtVolume::FromMM(btVector3(big, big, big), btVector3(-big, -big, -big));
	btVector3 lo = v.Mins(), hi = v.Maxs();
	for (int axis = 0; axis < 3; ++axis)
	{
		lo[axis] = btMax(-big, btMin(big, lo[axis]));
		hi[axis] = btMax(-big, btMin(big, hi[axis]));
	}
	return btDbvtVolume::FromMM(lo, hi);
}

SIMD_FORCE_INLINE int indexOfChild(const btDbvtNode* node) { return node->parent->childs[1] == node ? 1 : 0; }
}  // namespace

namespace caliber
{
namespace
{
/// The node blocks of one tree, freed with the tree's nodes.
struct DbvtNodeBlocks
{
	btAlignedObjectArray<btDbvtNode*> blocks;
	/// The number of nodes of the next block: twice the last, up to 4096.
	int nextBlockSize = 64;
	~DbvtNodeBlocks()
	{
		for (int i = 0; i < blocks.size(); ++i) btAlignedFree(blocks[i]);
	}
};

/// An entry of the insertion's branch-and-bound stack: a node, what its ancestors would grow by, and the
/// half area of its union with the new leaf.
struct InsertCandidate
{
	btDbvtNode* node;
	btScalar inheritedCost;
	btScalar mergedArea;
};

/// The rebuilds' arrays, kept per thread so that repeated optimize calls do not allocate.
struct RebuildScratch
{
	btAlignedObjectArray<btDbvtNode*> leaves;
	btAlignedObjectArray<btScalar> costs;
	btAlignedObjectArray<int> partners;
};

RebuildScratch& rebuildScratch()
{
	static thread_local RebuildScratch scratch;
	return scratch;
}

/// Frees every node of tree at once (its blocks) and empties it.
void releaseAllNodes(btDbvt& tree)
{
	sideTable<DbvtNodeBlocks>().release(&tree);
	tree.m_root = 0;
	tree.m_free = 0;
	tree.m_leaves = 0;
	tree.m_opath = 0;
	tree.m_lkhd = -1;
}

/// The alignment of the node blocks: a cache line.
const int kNodeBlockAlignment = 64;

/// A node off the tree's free list (a new block when the list is empty), unlinked.
btDbvtNode* allocateNode(btDbvt& tree)
{
	if (!tree.m_free)
	{
		// Few allocations while a tree grows; the side table is only looked up here.
		DbvtNodeBlocks& owned = sideTable<DbvtNodeBlocks>().acquire(&tree);
		const int count = owned.nextBlockSize;
		owned.nextBlockSize = btMin(owned.nextBlockSize * 2, 4096);
		// Blocks start on a cache line: a node (64 bytes in float builds) then fills one line instead of
		// straddling two, so a walk that tests a node's box and then follows its children reads one line.
		btDbvtNode* block = static_cast<btDbvtNode*>(btAlignedAlloc(sizeof(btDbvtNode) * count, kNodeBlockAlignment));
		owned.blocks.push_back(block);
		for (int i = count - 1; i >= 0; --i)
		{
			btDbvtNode* node = new (&block[i]) btDbvtNode;
			node->parent = tree.m_free;
			tree.m_free = node;
		}
	}
	btDbvtNode* node = tree.m_free;
	tree.m_free = node->parent;
	node->parent = 0;
	node->childs[0] = 0;
	node->childs[1] = 0;
	return node;
}

/// Puts node back on the tree's free list (linked through parent, as Bullet's m_free).
SIMD_FORCE_INLINE void freeNode(btDbvt& tree, btDbvtNode* node)
{
	node->childs[0] = 0;
	node->childs[1] = 0;
	node->parent = tree.m_free;
	tree.m_free = node;
}

/// The rotation of rotateSaving with the boxes read through volumeOf(node) and childVolume(node, child), and a
/// veto: when mayOpen(opened) is false for the child the best swap would open, nothing changes and the answer
/// is false (the replay of moves above the subtrees, whose boxes of subtree roots live in a view).
template <class Save, class VolumeOf, class ChildVolume, class MayOpen>
SIMD_FORCE_INLINE bool rotateThrough(btDbvtNode* node, Save save, VolumeOf volumeOf, ChildVolume childVolume,
                                     MayOpen mayOpen)
{
	// Swapping a child of `node` with a grandchild under its other child keeps node's box and changes the
	// box of that other child only; take the swap that shrinks it most (Catto, "Dynamic AABB trees", 2019).
	btScalar bestGain = 0;
	int bestChild = -1, bestGrandChild = -1;
	for (int c = 0; c < 2; ++c)
	{
		const btDbvtNode* stay = node->childs[c];  // the child moved down
		const btDbvtNode* opened = node->childs[1 - c];
		if (opened->isleaf()) continue;
		const btScalar openedArea = halfArea(volumeOf(opened));
		for (int g = 0; g < 2; ++g)
		{
			// stay swaps with opened->childs[g]; opened then holds stay and opened->childs[1 - g].
			const btScalar gain = openedArea - halfArea(merged(volumeOf(stay), childVolume(opened, 1 - g)));
			if (gain > bestGain)
			{
				bestGain = gain;
				bestChild = c;
				bestGrandChild = g;
			}
		}
	}
	if (bestChild < 0) return true;
	btDbvtNode* down = node->childs[bestChild];
	btDbvtNode* opened = node->childs[1 - bestChild];
	if (!mayOpen(opened)) return false;
	btDbvtNode* up = opened->childs[bestGrandChild];
	save(node);
	save(up);
	save(opened);
	save(down);
	node->childs[bestChild] = up;
	up->parent = node;
	opened->childs[bestGrandChild] = down;
	down->parent = opened;
	Merge(volumeOf(opened->childs[0]), volumeOf(opened->childs[1]), opened->volume);
	return true;
}

/// save(n) is called before each node rotate changes (a no-op for the tree's own operations; the moves within
/// a subtree keep what they change, see moveLeafWithinSubtree).
template <class Save>
SIMD_FORCE_INLINE void rotateSaving(btDbvtNode* node, Save save)
{
	rotateThrough(
	    node, save, [](const btDbvtNode* n) -> const btDbvtVolume& { return n->volume; },
	    [](const btDbvtNode* n, int child) -> const btDbvtVolume& { return n->childs[child]->volume; },
	    [](const btDbvtNode*) { return true; });
}

void rotate(btDbvtNode* node)
{
	rotateSaving(node, [](btDbvtNode*) {});
}

/// The state of the search for a new leaf's sibling: the best so far and what bounds the rest.
struct SiblingSearch
{
	btDbvtVolume box;
	btScalar leafArea;
	btDbvtNode* start;
	btDbvtNode* best;
	btScalar bestCost;
};

/// visitCandidate for a leaf: takes it if it is the best so far.
SIMD_FORCE_INLINE void visitLeaf(SiblingSearch& search, const InsertCandidate& candidate)
{
	if (search.leafArea + candidate.inheritedCost >= search.bestCost && candidate.node != search.start) return;
	const btScalar cost = candidate.mergedArea + candidate.inheritedCost;
	if (cost < search.bestCost)
	{
		search.bestCost = cost;
		search.best = candidate.node;
	}
}

/// One step of the branch and bound: takes candidate if it is the best so far and pushes its children
/// that could still hold a better sibling (the nearer one last, so that it is searched first). A child
/// that is a leaf and would be popped next is visited at once instead: the same visits in the same order,
/// without the stack.
template <class Push>
SIMD_FORCE_INLINE void visitCandidate(SiblingSearch& search, const InsertCandidate& candidate, Push push)
{
	// Even a perfect fit under this node costs leafArea plus what its ancestors grow by.
	if (search.leafArea + candidate.inheritedCost >= search.bestCost && candidate.node != search.start) return;
	btDbvtNode* node = candidate.node;
	const btScalar cost = candidate.mergedArea + candidate.inheritedCost;
	if (cost < search.bestCost)
	{
		search.bestCost = cost;
		search.best = node;
	}
	if (node->isleaf()) return;
	const btScalar childInherited = candidate.inheritedCost + (candidate.mergedArea - halfArea(node->volume));
	if (search.leafArea + childInherited < search.bestCost)
	{
		// The child whose union with the leaf is smaller on top: a good sibling is found early and bounds
		// the rest of the search.
		const btScalar area0 = halfArea(merged(search.box, node->childs[0]->volume));
		const btScalar area1 = halfArea(merged(search.box, node->childs[1]->volume));
		const int nearer = area1 < area0 ? 1 : 0;
		const InsertCandidate later = {node->childs[1 - nearer], childInherited, nearer ? area0 : area1};
		const InsertCandidate sooner = {node->childs[nearer], childInherited, nearer ? area1 : area0};
		if (!sooner.node->isleaf())
		{
			push(later);
			push(sooner);
			return;
		}
		// sooner would be popped next and, a leaf, push nothing; then later would be popped.
		visitLeaf(search, sooner);
		if (later.node->isleaf())
			visitLeaf(search, later);
		else
			push(later);
	}
}

/// The search continued on a heap stack, for trees deeper than the inline stack of bestSibling.
btDbvtNode* finishSearchOnHeap(SiblingSearch& search, const InsertCandidate* pending, int count)
{
	btAlignedObjectArray<InsertCandidate> stack;
	for (int i = 0; i < count; ++i) stack.push_back(pending[i]);
	while (stack.size() > 0)
	{
		const InsertCandidate candidate = stack[stack.size() - 1];
		stack.pop_back();
		visitCandidate(search, candidate, [&stack](const InsertCandidate& c) { stack.push_back(c); });
	}
	return search.best;
}

/// The sibling for a leaf with this box under start of least cost (area of the new parent + growth of the
/// ancestors), by a depth-first branch and bound. The stack holds at most one entry per level plus one,
/// so it lives in a local array (kept in registers and cache, nothing shared between threads); only trees
/// deeper than it continue on the heap.
btDbvtNode* bestSibling(btDbvtNode* start, const btDbvtVolume& box)
{
	const int kInline = 64;
	SiblingSearch search;
	search.box = box;
	search.leafArea = halfArea(box);
	search.start = start;
	search.best = start;
	search.bestCost = halfArea(merged(box, start->volume));
	InsertCandidate stack[kInline];
	int size = 0;
	const InsertCandidate first = {start, btScalar(0), search.bestCost};
	stack[size++] = first;
	while (size > 0)
	{
		if (size > kInline - 2) return finishSearchOnHeap(search, stack, size);
		const InsertCandidate candidate = stack[--size];
		visitCandidate(search, candidate, [&stack, &size](const InsertCandidate& c) { stack[size++] = c; });
	}
	return search.best;
}

/// Links leaf into the tree, searching for its sibling under start (the root when start is null).
void insertLeaf(btDbvt& tree, btDbvtNode* start, btDbvtNode* leaf)
{
	if (!tree.m_root)
	{
		tree.m_root = leaf;
		leaf->parent = 0;
		return;
	}
	const btDbvtVolume& box = leaf->volume;
	btDbvtNode* best = bestSibling(start ? start : tree.m_root, box);

	// A new parent takes the sibling's place and adopts sibling and leaf.
	btDbvtNode* oldParent = best->parent;
	btDbvtNode* parent = allocateNode(tree);
	parent->parent = oldParent;
	Merge(box, best->volume, parent->volume);
	parent->childs[0] = best;
	parent->childs[1] = leaf;
	if (oldParent)
		oldParent->childs[indexOfChild(best)] = parent;
	else
		tree.m_root = parent;
	best->parent = parent;
	leaf->parent = parent;

	// Grow the ancestors until one already contains the leaf (the ones above it contain it too), and try a
	// rotation at each: cost-based insertion alone degenerates towards a list for sorted input.
	rotate(parent);
	for (btDbvtNode* node = oldParent; node; node = node->parent)
	{
		if (node->volume.Contain(box)) break;
		Merge(node->childs[0]->volume, node->childs[1]->volume, node->volume);
		rotate(node);
	}
}

/// Unlinks leaf (its parent goes to the free list); returns the node where a re-insertion may start.
btDbvtNode* removeLeaf(btDbvt& tree, btDbvtNode* leaf)
{
	if (leaf == tree.m_root)
	{
		tree.m_root = 0;
		return 0;
	}
	btDbvtNode* parent = leaf->parent;
	btDbvtNode* sibling = parent->childs[1 - indexOfChild(leaf)];
	btDbvtNode* grandParent = parent->parent;
	leaf->parent = 0;
	if (!grandParent)
	{
		tree.m_root = sibling;
		sibling->parent = 0;
		freeNode(tree, parent);
		return tree.m_root;
	}
	grandParent->childs[indexOfChild(parent)] = sibling;
	sibling->parent = grandParent;
	freeNode(tree, parent);
	// Shrink the ancestors; once a box does not change, none above it does.
	for (btDbvtNode* node = grandParent; node; node = node->parent)
	{
		const btDbvtVolume previous = node->volume;
		Merge(node->childs[0]->volume, node->childs[1]->volume, node->volume);
		if (!NotEqual(previous, node->volume)) break;
	}
	return grandParent;
}

/// The node `lookahead` levels above start (the root for a negative lookahead; null stays null).
btDbvtNode* reinsertionStart(btDbvt& tree, btDbvtNode* start, int lookahead)
{
	if (!start) return 0;
	if (lookahead < 0) return tree.m_root;
	for (int i = 0; i < lookahead && start->parent; ++i) start = start->parent;
	return start;
}

void reinsertLeaf(btDbvt& tree, btDbvtNode* leaf, int lookahead)
{
	btDbvtNode* start = removeLeaf(tree, leaf);
	insertLeaf(tree, reinsertionStart(tree, start, lookahead), leaf);
}
}  // namespace
}  // namespace caliber

namespace
{
/// refitLeafNearSibling's test: the leaf, at its new box, is still close enough to its sibling.
SIMD_FORCE_INLINE bool staysNearSibling(const btDbvtNode* leaf, const btDbvtVolume& fitted)
{
	const btDbvtNode* sibling = leaf->parent->childs[1 - indexOfChild(leaf)];
	return !(halfArea(merged(fitted, sibling->volume)) >
	         caliber::kDbvtRefitSiblingSlack * (halfArea(fitted) + halfArea(sibling->volume)));
}

/// A move within one subtree: the tree, the subtree's root, and the log every changed node is saved to.
struct SubtreeMove
{
	btDbvt* tree;
	const btDbvtNode* subtree;
	caliber::DbvtUndoLog* log;
	caliber::DbvtTopStep* top;  // null: a step above the subtree is a reason to stop; else it is recorded

	void save(btDbvtNode* node) const
	{
		caliber::DbvtSavedNode saved;
		saved.node = node;
		saved.contents = *node;
		log->push_back(saved);
	}
};

/// The growth loops of the insertion (with a rotation at each grown node) and of the refit (without),
/// from node `from` up: false when the serial loop would change a node above the subtree (its parent
/// does not contain box), which this leaves untouched.
bool growAncestorsWithin(const SubtreeMove& move, btDbvtNode* from, const btDbvtVolume& box, bool rotateEach)
{
	for (btDbvtNode* node = from; node; node = node->parent)
	{
		if (node->volume.Contain(box)) return true;
		move.save(node);
		Merge(node->childs[0]->volume, node->childs[1]->volume, node->volume);
		if (rotateEach) caliber::rotateSaving(node, [&move](btDbvtNode* n) { move.save(n); });
		// The serial loop's next step reads the box of the subtree's parent, which no move within a subtree
		// changes: it stops there, or it would grow that node (with top: the growth goes on there later).
		if (node == move.subtree)
		{
			if (!move.top) return node->parent->volume.Contain(box);
			move.top->grows = true;
			move.top->grownBox = box;
			move.top->rotates = rotateEach;
			return true;
		}
	}
	return true;
}

/// btDbvt::update(leaf, box) (removal, then re-insertion from m_lkhd levels above) within the subtree.
bool updateWithin(const SubtreeMove& move, btDbvtNode* leaf, const btDbvtVolume& box)
{
	// The removal (removeLeaf). A leaf whose parent is the subtree's root would replace that root.
	btDbvtNode* parent = leaf->parent;
	if (parent == move.subtree) return false;
	btDbvtNode* sibling = parent->childs[1 - indexOfChild(leaf)];
	btDbvtNode* grandParent = parent->parent;
	move.save(leaf);
	move.save(grandParent);
	move.save(sibling);
	move.save(parent);
	leaf->parent = 0;
	grandParent->childs[indexOfChild(parent)] = sibling;
	sibling->parent = grandParent;
	// The parent would go to the free list and be the next node taken from it, by the insertion below: it
	// is kept aside instead (the free list is the tree's, shared by every subtree).
	btDbvtNode* spare = parent;
	spare->childs[0] = 0;
	spare->childs[1] = 0;
	spare->parent = 0;
	for (btDbvtNode* node = grandParent; node; node = node->parent)
	{
		const btDbvtVolume previous = node->volume;
		move.save(node);
		Merge(node->childs[0]->volume, node->childs[1]->volume, node->volume);
		if (!NotEqual(previous, node->volume)) break;
		// The serial loop would go on with the subtree's parent, whose other children other moves change
		// (with top: it goes on there later).
		if (node == move.subtree)
		{
			if (!move.top) return false;
			move.top->shrinks = true;
			move.top->shrunk = node->volume;
			break;
		}
	}
	leaf->volume = sanitizedVolume(box);

	// The start of the re-insertion (reinsertionStart): climbing above the subtree's root leaves it.
	btDbvtNode* start = grandParent;
	const int lookahead = move.tree->m_lkhd;
	if (lookahead < 0) return false;
	for (int i = 0; i < lookahead && start->parent; ++i)
	{
		if (start == move.subtree) return false;
		start = start->parent;
	}

	// The insertion (insertLeaf); a sibling that is the subtree's root would put the new parent above it.
	const btDbvtVolume& leafBox = leaf->volume;
	btDbvtNode* best = caliber::bestSibling(start, leafBox);
	if (best == move.subtree) return false;
	btDbvtNode* oldParent = best->parent;
	btDbvtNode* newParent = spare;
	newParent->parent = oldParent;
	Merge(leafBox, best->volume, newParent->volume);
	newParent->childs[0] = best;
	newParent->childs[1] = leaf;
	move.save(oldParent);
	move.save(best);
	oldParent->childs[indexOfChild(best)] = newParent;
	best->parent = newParent;
	leaf->parent = newParent;
	caliber::rotateSaving(newParent, [&move](btDbvtNode* n) { move.save(n); });
	return growAncestorsWithin(move, oldParent, leafBox, true);
}
}  // namespace

namespace
{
bool moveWithin(btDbvt& tree, const btDbvtNode* subtree, btDbvtNode* leaf, const btDbvtVolume& box,
                caliber::DbvtUndoLog& log, caliber::DbvtTopStep* top)
{
	const int mark = log.size();
	SubtreeMove move;
	move.tree = &tree;
	move.subtree = subtree;
	move.log = &log;
	move.top = top;
	if (top)
	{
		top->shrinks = false;
		top->grows = false;
		top->rotates = false;
	}
	bool inside;
	const btDbvtVolume fitted = sanitizedVolume(box);
	if (staysNearSibling(leaf, fitted))
	{
		// refitLeafNearSibling
		move.save(leaf);
		leaf->volume = fitted;
		inside = growAncestorsWithin(move, leaf->parent, fitted, false);
	}
	else
	{
		inside = updateWithin(move, leaf, box);
	}
	if (!inside)
	{
		caliber::undoDbvtChanges(log, mark);
		return false;
	}
	if (top)
	{
		top->after = subtree->volume;
		top->childs[0] = subtree->childs[0]->volume;
		top->childs[1] = subtree->childs[1]->volume;
	}
	return true;
}
}  // namespace

bool caliber::moveLeafWithinSubtree(btDbvt& tree, const btDbvtNode* subtree, btDbvtNode* leaf, const btDbvtVolume& box,
                                    DbvtUndoLog& log)
{
	return moveWithin(tree, subtree, leaf, box, log, 0);
}

bool caliber::moveLeafWithinSubtreeDeferringTop(btDbvt& tree, const btDbvtNode* subtree, btDbvtNode* leaf,
                                                const btDbvtVolume& box, DbvtUndoLog& log, DbvtTopStep& top)
{
	return moveWithin(tree, subtree, leaf, box, log, &top);
}

void caliber::DbvtTopView::start(const btDbvtNode* const* subtreeRoots, int numSubtrees)
{
	btAssert(numSubtrees <= kMaxSubtrees);
	count = numSubtrees;
	for (int k = 0; k < numSubtrees; ++k)
	{
		roots[k] = subtreeRoots[k];
		if (!roots[k]) continue;
		boxes[k] = roots[k]->volume;
		childs[k][0] = roots[k]->childs[0]->volume;
		childs[k][1] = roots[k]->childs[1]->volume;
	}
}

namespace
{
/// The replay of a move's steps above the subtrees (replayDbvtTopStep): the serial loops of removeLeaf,
/// insertLeaf (with rotateSaving) and refitLeafNearSibling above the subtree's root, each subtree root's
/// box and its children's taken from the view (the live ones are the round's last).
struct TopReplay
{
	caliber::DbvtTopView* view;
	caliber::DbvtUndoLog* log;

	int subtreeIndex(const btDbvtNode* node) const
	{
		for (int k = 0; k < view->count; ++k)
			if (view->roots[k] == node) return k;
		return -1;
	}

	const btDbvtVolume& volumeOf(const btDbvtNode* node) const
	{
		const int k = subtreeIndex(node);
		return k < 0 ? node->volume : view->boxes[k];
	}

	const btDbvtVolume& childVolume(const btDbvtNode* node, int child) const
	{
		const int k = subtreeIndex(node);
		return k < 0 ? volumeOf(node->childs[child]) : view->childs[k][child];
	}

	void save(btDbvtNode* node) const
	{
		caliber::DbvtSavedNode saved;
		saved.node = node;
		saved.contents = *node;
		log->push_back(saved);
	}

	void refit(btDbvtNode* node) const
	{
		save(node);
		Merge(volumeOf(node->childs[0]), volumeOf(node->childs[1]), node->volume);
	}

	/// rotateSaving at a node above the subtrees; false when its swap would take a node out of a subtree.
	bool rotate(btDbvtNode* node) const
	{
		return caliber::rotateThrough(
		    node, [this](btDbvtNode* n) { save(n); },
		    [this](const btDbvtNode* n) -> const btDbvtVolume& { return volumeOf(n); },
		    [this](const btDbvtNode* n, int child) -> const btDbvtVolume& { return childVolume(n, child); },
		    [this](const btDbvtNode* opened) { return subtreeIndex(opened) < 0; });
	}
};
}  // namespace

bool caliber::replayDbvtTopStep(DbvtTopView& view, int index, const DbvtTopStep& top, DbvtUndoLog& topLog)
{
	TopReplay replay;
	replay.view = &view;
	replay.log = &topLog;
	btDbvtNode* above = view.roots[index]->parent;
	if (top.shrinks)
	{
		view.boxes[index] = top.shrunk;
		for (btDbvtNode* node = above; node; node = node->parent)
		{
			const btDbvtVolume previous = node->volume;
			replay.refit(node);
			if (!NotEqual(previous, node->volume)) break;
		}
	}
	view.boxes[index] = top.after;
	view.childs[index][0] = top.childs[0];
	view.childs[index][1] = top.childs[1];
	if (top.grows)
	{
		for (btDbvtNode* node = above; node; node = node->parent)
		{
			if (node->volume.Contain(top.grownBox)) break;
			replay.refit(node);
			if (top.rotates && !replay.rotate(node)) return false;
		}
	}
	return true;
}

void caliber::undoDbvtChanges(DbvtUndoLog& log, int mark)
{
	for (int i = log.size() - 1; i >= mark; --i) *log[i].node = log[i].contents;
	log.resize(mark);
}

bool caliber::refitLeafNearSibling(btDbvtNode* leaf, const btDbvtVolume& box)
{
	btDbvtNode* parent = leaf->parent;
	if (!parent) return false;
	const btDbvtVolume fitted = sanitizedVolume(box);
	if (!staysNearSibling(leaf, fitted)) return false;
	leaf->volume = fitted;
	for (btDbvtNode* node = parent; node; node = node->parent)
	{
		if (node->volume.Contain(fitted)) break;
		Merge(node->childs[0]->volume, node->childs[1]->volume, node->volume);
	}
	return true;
}

btDbvt::btDbvt() : m_root(0), m_free(0), m_lkhd(-1), m_leaves(0), m_opath(0) {}

btDbvt::~btDbvt() { caliber::releaseAllNodes(*this); }

void btDbvt::clear()
{
	caliber::releaseAllNodes(*this);
	m_stkStack.clear();
}

btDbvtNode* btDbvt::insert(const btDbvtVolume& box, void* data)
{
	btDbvtNode* leaf = caliber::allocateNode(*this);
	leaf->volume = sanitizedVolume(box);
	leaf->childs[1] = 0;
	leaf->data = data;
	caliber::insertLeaf(*this, m_root, leaf);
	++m_leaves;
	return leaf;
}

void btDbvt::remove(btDbvtNode* leaf)
{
	btAssert(leaf && leaf->isleaf() && "btDbvt::remove: not a leaf");
	if (!leaf || !leaf->isleaf() || !m_root) return;
	caliber::removeLeaf(*this, leaf);
	caliber::freeNode(*this, leaf);
	--m_leaves;
}

void btDbvt::update(btDbvtNode* leaf, int lookahead)
{
	btAssert(leaf && leaf->isleaf() && "btDbvt::update: not a leaf");
	if (!leaf || !leaf->isleaf() || !m_root) return;
	caliber::reinsertLeaf(*this, leaf, lookahead);
}

void btDbvt::update(btDbvtNode* leaf, btDbvtVolume& volume)
{
	btAssert(leaf && leaf->isleaf() && "btDbvt::update: not a leaf");
	if (!leaf || !leaf->isleaf() || !m_root) return;
	btDbvtNode* start = caliber::removeLeaf(*this, leaf);
	leaf->volume = sanitizedVolume(volume);
	caliber::insertLeaf(*this, caliber::reinsertionStart(*this, start, m_lkhd), leaf);
}

bool btDbvt::update(btDbvtNode* leaf, btDbvtVolume& volume, const btVector3& velocity, btScalar margin)
{
	if (leaf && leaf->volume.Contain(volume)) return false;
	volume.Expand(btVector3(margin, margin, margin));
	volume.SignedExpand(velocity);
	update(leaf, volume);
	return true;
}

bool btDbvt::update(btDbvtNode* leaf, btDbvtVolume& volume, const btVector3& velocity)
{
	if (leaf && leaf->volume.Contain(volume)) return false;
	volume.SignedExpand(velocity);
	update(leaf, volume);
	return true;
}

bool btDbvt::update(btDbvtNode* leaf, btDbvtVolume& volume, btScalar margin)
{
	if (leaf && leaf->volume.Contain(volume)) return false;
	volume.Expand(btVector3(margin, margin, margin));
	update(leaf, volume);
	return true;
}

void btDbvt::optimizeIncremental(int passes)
{
	if (passes < 0) passes = m_leaves;
	if (!m_root || passes <= 0) return;
	const int bits = int(sizeof(unsigned) * 8);
	for (int pass = 0; pass < passes; ++pass)
	{
		// The bits of m_opath pick a child at each level, so that successive passes visit different leaves.
		btDbvtNode* node = m_root;
		for (int bit = 0; node->isinternal(); bit = (bit + 1) % bits) node = node->childs[(m_opath >> bit) & 1];
		caliber::reinsertLeaf(*this, node, -1);
		++m_opath;
	}
}

namespace caliber
{
namespace
{
/// Moves the tree's leaves into leaves and its internal nodes to the free list; the tree is left empty.
void collectLeavesFreeInternals(btDbvt& tree, btAlignedObjectArray<btDbvtNode*>& leaves)
{
	leaves.resizeNoInitialize(0);
	if (!tree.m_root) return;
	leaves.reserve(tree.m_leaves);
	DbvtLocalStack<btDbvtNode*, 128> stack;
	stack.push(tree.m_root);
	while (!stack.empty())
	{
		btDbvtNode* node = stack.pop();
		if (node->isinternal())
		{
			stack.push(node->childs[0]);
			stack.push(node->childs[1]);
			freeNode(tree, node);
		}
		else
			leaves.push_back(node);
	}
	tree.m_root = 0;
}

btDbvtNode* buildBottomUp(btDbvt& tree, RebuildScratch& scratch, btDbvtNode** nodes, int count)
{
	// Agglomerative build: repeatedly join the two subtrees whose union has the least area. Each slot keeps
	// its best partner, recomputed only when that partner disappears, which keeps the build near O(n^2).
	if (count <= 0) return 0;
	scratch.costs.resizeNoInitialize(count);
	scratch.partners.resizeNoInitialize(count);
	btScalar* cost = &scratch.costs[0];
	int* partner = &scratch.partners[0];
	const btScalar unset = SIMD_INFINITY;
	auto findPartner = [&](int i)
	{
		cost[i] = unset;
		partner[i] = -1;
		for (int j = 0; j < count; ++j)
		{
			if (j == i || !nodes[j]) continue;
			const btScalar c = halfArea(merged(nodes[i]->volume, nodes[j]->volume));
			if (c < cost[i] || partner[i] < 0)
			{
				cost[i] = c;
				partner[i] = j;
			}
		}
	};
	for (int i = 0; i < count; ++i) findPartner(i);
	for (int alive = count; alive > 1; --alive)
	{
		int i = -1;
		for (int k = 0; k < count; ++k)
			if (nodes[k] && partner[k] >= 0 && (i < 0 || cost[k] < cost[i])) i = k;
		const int j = partner[i];
		btDbvtNode* parent = allocateNode(tree);
		parent->childs[0] = nodes[i];
		parent->childs[1] = nodes[j];
		nodes[i]->parent = parent;
		nodes[j]->parent = parent;
		Merge(nodes[i]->volume, nodes[j]->volume, parent->volume);
		nodes[i] = parent;
		nodes[j] = 0;
		findPartner(i);
		for (int k = 0; k < count; ++k)
		{
			if (!nodes[k] || k == i) continue;
			if (partner[k] == i || partner[k] == j)
				findPartner(k);
			else
			{
				const btScalar c = halfArea(merged(nodes[k]->volume, parent->volume));
				if (c < cost[k])
				{
					cost[k] = c;
					partner[k] = i;
				}
			}
		}
	}
	for (int k = 0; k < count; ++k)
		if (nodes[k]) return nodes[k];
	return 0;
}

btDbvtNode* buildTopDown(btDbvt& tree, RebuildScratch& scratch, btDbvtNode** leaves, int count, int bottomUpThreshold)
{
	if (count == 1) return leaves[0];
	if (count <= bottomUpThreshold) return buildBottomUp(tree, scratch, leaves, count);
	// Split at the median of the centres along the axis where the centres spread most.
	btVector3 lo = leaves[0]->volume.Center(), hi = lo;
	for (int i = 1; i < count; ++i)
	{
		const btVector3 c = leaves[i]->volume.Center();
		lo.setMin(c);
		hi.setMax(c);
	}
	const int axis = (hi - lo).maxAxis();
	const int half = count / 2;
	std::nth_element(
	    leaves, leaves + half, leaves + count,
	    [axis](const btDbvtNode* a, const btDbvtNode* b)
	    { return a->volume.Mins()[axis] + a->volume.Maxs()[axis] < b->volume.Mins()[axis] + b->volume.Maxs()[axis]; });
	btDbvtNode* left = buildTopDown(tree, scratch, leaves, half, bottomUpThreshold);
	btDbvtNode* right = buildTopDown(tree, scratch, leaves + half, count - half, bottomUpThreshold);
	btDbvtNode* parent = allocateNode(tree);
	parent->childs[0] = left;
	parent->childs[1] = right;
	left->parent = parent;
	right->parent = parent;
	Merge(left->volume, right->volume, parent->volume);
	return parent;
}
}  // namespace
}  // namespace caliber

void btDbvt::optimizeBottomUp()
{
	if (!m_root) return;
	caliber::RebuildScratch& scratch = caliber::rebuildScratch();
	caliber::collectLeavesFreeInternals(*this, scratch.leaves);
	m_root = caliber::buildBottomUp(*this, scratch, &scratch.leaves[0], scratch.leaves.size());
	m_root->parent = 0;
}

void btDbvt::optimizeTopDown(int bu_treshold)
{
	if (!m_root) return;
	caliber::RebuildScratch& scratch = caliber::rebuildScratch();
	caliber::collectLeavesFreeInternals(*this, scratch.leaves);
	m_root = caliber::buildTopDown(*this, scratch, &scratch.leaves[0], scratch.leaves.size(), btMax(bu_treshold, 1));
	m_root->parent = 0;
}

void btDbvt::write(IWriter* iwriter) const
{
	btAssert(iwriter && "btDbvt::write: null writer");
	if (!iwriter) return;
	// Breadth-first numbering: the children of a node get the next free indices when it is reached, so
	// every index is known before the node is written.
	btAlignedObjectArray<const btDbvtNode*> order;
	btAlignedObjectArray<int> parentOf;
	if (m_root)
	{
		order.push_back(m_root);
		parentOf.push_back(-1);
		for (int i = 0; i < order.size(); ++i)
		{
			if (order[i]->isinternal())
			{
				order.push_back(order[i]->childs[0]);
				parentOf.push_back(i);
				order.push_back(order[i]->childs[1]);
				parentOf.push_back(i);
			}
		}
	}
	iwriter->Prepare(m_root, order.size());
	int nextChild = 1;
	for (int i = 0; i < order.size(); ++i)
	{
		if (order[i]->isinternal())
		{
			iwriter->WriteNode(order[i], i, parentOf[i], nextChild, nextChild + 1);
			nextChild += 2;
		}
		else
			iwriter->WriteLeaf(order[i], i, parentOf[i]);
	}
}

void btDbvt::clone(btDbvt& dest, IClone* iclone) const
{
	btAssert(&dest != this && "btDbvt::clone: a tree cannot be cloned onto itself");
	if (&dest == this) return;
	dest.clear();
	if (!m_root) return;
	// Copy with a stack of (source node, parent of its copy, which child of that parent).
	struct Pending
	{
		const btDbvtNode* source;
		btDbvtNode* parent;
		int childIndex;
	};
	caliber::DbvtLocalStack<Pending, 128> stack;
	Pending first = {m_root, 0, 0};
	stack.push(first);
	while (!stack.empty())
	{
		const Pending p = stack.pop();
		btDbvtNode* copy = caliber::allocateNode(dest);
		copy->volume = p.source->volume;
		copy->parent = p.parent;
		if (p.parent)
			p.parent->childs[p.childIndex] = copy;
		else
			dest.m_root = copy;
		if (p.source->isinternal())
		{
			// Mark as internal until the children are linked.
			copy->childs[0] = copy->childs[1] = copy;
			Pending c1 = {p.source->childs[1], copy, 1};
			Pending c0 = {p.source->childs[0], copy, 0};
			stack.push(c1);
			stack.push(c0);
		}
		else
		{
			copy->childs[0] = p.source->childs[0];  // the whole union: data / dataAsInt
			copy->childs[1] = 0;
			++dest.m_leaves;
			if (iclone) iclone->CloneLeaf(copy);
		}
	}
	dest.m_lkhd = m_lkhd;
}

int btDbvt::maxdepth(const btDbvtNode* node)
{
	if (!node) return 0;
	struct Entry
	{
		const btDbvtNode* node;
		int depth;
	};
	caliber::DbvtLocalStack<Entry, 128> stack;
	Entry first = {node, 1};
	stack.push(first);
	int deepest = 0;
	while (!stack.empty())
	{
		const Entry e = stack.pop();
		deepest = btMax(deepest, e.depth);
		if (e.node->isinternal())
		{
			for (int c = 0; c < 2; ++c)
			{
				Entry child = {e.node->childs[c], e.depth + 1};
				stack.push(child);
			}
		}
	}
	return deepest;
}

int btDbvt::countLeaves(const btDbvtNode* node)
{
	struct Counter : ICollide
	{
		using ICollide::Process;
		int count = 0;
		void Process(const btDbvtNode*) override { ++count; }
	} counter;
	enumLeaves(node, counter);
	return counter.count;
}

void btDbvt::extractLeaves(const btDbvtNode* node, btAlignedObjectArray<const btDbvtNode*>& leaves)
{
	struct Collector : ICollide
	{
		using ICollide::Process;
		btAlignedObjectArray<const btDbvtNode*>* out;
		void Process(const btDbvtNode* leaf) override { out->push_back(leaf); }
	} collector;
	collector.out = &leaves;
	enumLeaves(node, collector);
}
