// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_DYNAMIC_BOUNDING_VOLUME_TREE_H
#define BT_DYNAMIC_BOUNDING_VOLUME_TREE_H

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btAabbUtil2.h"

// Spellings Bullet's users and Bullet-derived code may use.
#define DBVT_INLINE SIMD_FORCE_INLINE
#define DBVT_VIRTUAL virtual
#define DBVT_VIRTUAL_DTOR(a) \
	virtual ~a() {}
#define DBVT_PREFIX template <typename T>
#define DBVT_IPOLICY T& policy
#define DBVT_CHECKTYPE

/// An axis-aligned box stored as its two corners: the volume of every node of a btDbvt.
ATTRIBUTE_ALIGNED16(struct)
btDbvtAabbMm
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An uninitialised box (use one of the From* factories).
	DBVT_INLINE btDbvtAabbMm() {}
	/// The centre (mins + maxs) / 2.
	DBVT_INLINE btVector3 Center() const { return (mi + mx) * btScalar(0.5); }
	/// The side lengths maxs - mins.
	DBVT_INLINE btVector3 Lengths() const { return mx - mi; }
	/// The half side lengths.
	DBVT_INLINE btVector3 Extents() const { return (mx - mi) * btScalar(0.5); }
	/// The lower corner.
	DBVT_INLINE const btVector3& Mins() const { return mi; }
	/// The upper corner.
	DBVT_INLINE const btVector3& Maxs() const { return mx; }
	/// The box of centre c and half extents e.
	static inline btDbvtAabbMm FromCE(const btVector3& c, const btVector3& e);
	/// The cube of centre c and half side r.
	static inline btDbvtAabbMm FromCR(const btVector3& c, btScalar r);
	/// The box of corners mi and mx.
	static inline btDbvtAabbMm FromMM(const btVector3& mi, const btVector3& mx);
	/// The smallest box around n points (n <= 0 asserts and gives the point box at the origin).
	static inline btDbvtAabbMm FromPoints(const btVector3* pts, int n);
	/// The smallest box around the n points pointed to (n <= 0 asserts and gives the point box at the origin).
	static inline btDbvtAabbMm FromPoints(const btVector3** ppts, int n);
	/// Grows the box by e on every side.
	DBVT_INLINE void Expand(const btVector3& e)
	{
		mi -= e;
		mx += e;
	}
	/// Grows the box only on the side each component of e points to (a swept box for a displacement e).
	DBVT_INLINE void SignedExpand(const btVector3& e)
	{
		for (int axis = 0; axis < 3; ++axis)
		{
			if (e[axis] > btScalar(0))
				mx[axis] += e[axis];
			else
				mi[axis] += e[axis];
		}
	}
	/// True when a lies inside this box (touching faces included).
	DBVT_INLINE bool Contain(const btDbvtAabbMm& a) const
	{
		return mi.x() <= a.mi.x() && mi.y() <= a.mi.y() && mi.z() <= a.mi.z() && mx.x() >= a.mx.x() &&
		       mx.y() >= a.mx.y() && mx.z() >= a.mx.z();
	}
	/// The side of the plane dot(n, p) + o = 0 the box lies on: +1 entirely on the non-negative side, -1
	/// entirely on the negative side, 0 across it. s holds the signs of n: bit i is set when n[i] >= 0.
	DBVT_INLINE int Classify(const btVector3& n, btScalar o, int s) const
	{
		btVector3 lowest, highest;  // the corners of least and greatest dot(n, p)
		for (int axis = 0; axis < 3; ++axis)
		{
			const bool positive = ((s >> axis) & 1) != 0;
			lowest[axis] = positive ? mi[axis] : mx[axis];
			highest[axis] = positive ? mx[axis] : mi[axis];
		}
		if (btDot(n, highest) + o < btScalar(0)) return -1;
		if (btDot(n, lowest) + o >= btScalar(0)) return +1;
		return 0;
	}
	/// The least dot(v, p) over the box; signs holds the signs of v (bit i set when v[i] >= 0).
	DBVT_INLINE btScalar ProjectMinimum(const btVector3& v, unsigned signs) const
	{
		const btVector3 corner(((signs >> 0) & 1) ? mi.x() : mx.x(), ((signs >> 1) & 1) ? mi.y() : mx.y(),
		                       ((signs >> 2) & 1) ? mi.z() : mx.z());
		return btDot(corner, v);
	}
	/// True when the boxes overlap or touch.
	DBVT_INLINE friend bool Intersect(const btDbvtAabbMm& a, const btDbvtAabbMm& b);
	/// True when point b lies in box a (faces included).
	DBVT_INLINE friend bool Intersect(const btDbvtAabbMm& a, const btVector3& b);
	/// A distance between the boxes' centres (twice their L1 distance), cheap for choosing the nearer box.
	DBVT_INLINE friend btScalar Proximity(const btDbvtAabbMm& a, const btDbvtAabbMm& b);
	/// 0 when a is nearer to o than b (by Proximity), else 1.
	DBVT_INLINE friend int Select(const btDbvtAabbMm& o, const btDbvtAabbMm& a, const btDbvtAabbMm& b);
	/// r = the smallest box containing a and b (r may alias a or b).
	DBVT_INLINE friend void Merge(const btDbvtAabbMm& a, const btDbvtAabbMm& b, btDbvtAabbMm& r);
	/// True when any corner coordinate differs.
	DBVT_INLINE friend bool NotEqual(const btDbvtAabbMm& a, const btDbvtAabbMm& b);
	/// The lower corner, writable.
	DBVT_INLINE btVector3& tMins() { return mi; }
	/// The upper corner, writable.
	DBVT_INLINE btVector3& tMaxs() { return mx; }

private:
	btVector3 mi, mx;
};

/// The bounding volume type of btDbvt.
typedef btDbvtAabbMm btDbvtVolume;

/// A node of a btDbvt: internal nodes own two children, leaves carry the user's data (childs[1] == 0).
struct btDbvtNode
{
	/// The node's box: the user's box for a leaf, the union of the children's boxes for an internal node.
	btDbvtVolume volume;
	/// The parent node, 0 for the root.
	btDbvtNode* parent;
	/// True for a leaf.
	DBVT_INLINE bool isleaf() const { return childs[1] == 0; }
	/// True for an internal node.
	DBVT_INLINE bool isinternal() const { return !isleaf(); }
	union
	{
		/// The two children of an internal node.
		btDbvtNode* childs[2];
		/// The user's pointer of a leaf.
		void* data;
		/// The user's integer of a leaf (shares storage with data).
		int dataAsInt;
	};
};

/// A stack of nodes the caller keeps between queries (collideTVNoStackAlloc, rayTestInternal).
typedef btAlignedObjectArray<const btDbvtNode*> btNodeStack;

namespace caliber
{
/// A stack that lives on the C++ stack up to InlineCapacity entries and moves to the heap beyond
/// (static queries allocate nothing unless the tree is unusually deep). Internal to btDbvt's queries and
/// its own walks (not a member of btDbvt: Bullet's class has no such type).
template <typename E, int InlineCapacity>
struct DbvtLocalStack
{
	/// The entries while they fit.
	E m_inline[InlineCapacity];
	/// The entries once they no longer fit in m_inline.
	btAlignedObjectArray<E> m_heap;
	/// m_inline or the heap array's storage.
	E* m_data;
	/// The number of entries.
	int m_size;
	/// The room in m_data.
	int m_capacity;
	/// An empty stack.
	DbvtLocalStack() : m_data(m_inline), m_size(0), m_capacity(InlineCapacity) {}
	/// Pushes value (moving to the heap when full).
	DBVT_INLINE void push(const E& value)
	{
		if (m_size == m_capacity) grow();
		m_data[m_size++] = value;
	}
	/// Pops the top entry (the stack must not be empty).
	DBVT_INLINE E pop() { return m_data[--m_size]; }
	/// True when there is no entry.
	DBVT_INLINE bool empty() const { return m_size == 0; }
	/// Doubles the room, moving the entries to the heap array.
	void grow()
	{
		const int capacity = m_capacity * 2;
		if (m_data == m_inline)
		{
			m_heap.resize(capacity);
			for (int i = 0; i < m_size; ++i) m_heap[i] = m_inline[i];
		}
		else
			m_heap.resize(capacity);
		m_data = &m_heap[0];
		m_capacity = capacity;
	}
};
}  // namespace caliber

/// The dynamic AABB tree: a binary tree of boxes whose leaves can be inserted, moved and removed at any
/// time, used by the dbvt broadphase and the compound shape. Insertion picks the sibling that adds the
/// least surface area to the tree (branch and bound over the whole tree); see docs for the design.
/// Leaf nodes keep their address for their whole life, so callers may hold btDbvtNode pointers.
struct btDbvt
{
	/// A pair of nodes on the tree-tree stack.
	struct sStkNN
	{
		/// The node from the first tree.
		const btDbvtNode* a;
		/// The node from the second tree.
		const btDbvtNode* b;
		/// An uninitialised pair.
		sStkNN() {}
		/// The pair (na, nb).
		sStkNN(const btDbvtNode* na, const btDbvtNode* nb) : a(na), b(nb) {}
	};
	/// A node and the mask of planes it is known to lie inside.
	struct sStkNP
	{
		/// The node.
		const btDbvtNode* node;
		/// Bit i set: the node lies inside plane i.
		int mask;
		/// An uninitialised entry.
		sStkNP() {}
		/// The entry (n, m).
		sStkNP(const btDbvtNode* n, unsigned m) : node(n), mask(static_cast<int>(m)) {}
	};
	/// A node, its plane mask and its sort value (collideOCL).
	struct sStkNPS
	{
		/// The node.
		const btDbvtNode* node;
		/// Bit i set: the node lies inside plane i.
		int mask;
		/// The sort value (least projection on the sort axis).
		btScalar value;
		/// An uninitialised entry.
		sStkNPS() {}
		/// The entry (n, m, v).
		sStkNPS(const btDbvtNode* n, unsigned m, btScalar v) : node(n), mask(static_cast<int>(m)), value(v) {}
	};
	/// A source node and the parent of its copy (clone).
	struct sStkCLN
	{
		/// The source node.
		const btDbvtNode* node;
		/// The parent of its copy.
		btDbvtNode* parent;
		/// The entry (n, p).
		sStkCLN(const btDbvtNode* n, btDbvtNode* p) : node(n), parent(p) {}
	};

	/// The callbacks of the queries; override the ones a query calls.
	struct ICollide
	{
		DBVT_VIRTUAL_DTOR(ICollide)
		/// A pair of overlapping leaves (collideTT).
		DBVT_VIRTUAL void Process(const btDbvtNode*, const btDbvtNode*) {}
		/// A leaf (or node, for enumNodes) the query found.
		DBVT_VIRTUAL void Process(const btDbvtNode*) {}
		/// A leaf and its sort value (collideOCL); calls Process(node) by default.
		DBVT_VIRTUAL void Process(const btDbvtNode* n, btScalar) { Process(n); }
		/// Whether to visit this node and its subtree (collideTU, collideOCL).
		DBVT_VIRTUAL bool Descent(const btDbvtNode*) { return true; }
		/// Whether the leaves under this node may all be reported (kept for Bullet's interface).
		DBVT_VIRTUAL bool AllLeaves(const btDbvtNode*) { return true; }
	};
	/// Receives the tree from write(): Prepare once, then one call per node.
	struct IWriter
	{
		virtual ~IWriter() {}
		/// Called first with the root and the number of nodes.
		virtual void Prepare(const btDbvtNode* root, int numnodes) = 0;
		/// An internal node, its index, its parent's index (-1 for the root) and its children's indices.
		virtual void WriteNode(const btDbvtNode*, int index, int parent, int child0, int child1) = 0;
		/// A leaf, its index and its parent's index (-1 for the root).
		virtual void WriteLeaf(const btDbvtNode*, int index, int parent) = 0;
	};
	/// Called by clone() for every leaf of the copy (to fix its data).
	struct IClone
	{
		virtual ~IClone() {}
		/// A leaf of the copy, its data copied from the source.
		virtual void CloneLeaf(btDbvtNode*) {}
	};

	/// Stack sizes of Bullet's interface (our stacks grow as needed).
	enum
	{
		SIMPLE_STACKSIZE = 64,
		DOUBLE_STACKSIZE = SIMPLE_STACKSIZE * 2
	};

	/// The root node, 0 when the tree is empty.
	btDbvtNode* m_root;
	/// The head of the list of free nodes (linked through parent).
	btDbvtNode* m_free;
	/// The default lookahead of update(leaf, volume): -1 re-inserts from the root.
	int m_lkhd;
	/// The number of leaves.
	int m_leaves;
	/// The path optimizeIncremental follows next (its bits choose children).
	unsigned m_opath;
	/// The stack of collideTT and collideTTpersistentStack, kept between calls.
	btAlignedObjectArray<sStkNN> m_stkStack;

	/// An empty tree.
	btDbvt();
	/// Frees every node.
	~btDbvt();
	/// Removes every leaf and frees every node.
	void clear();
	/// True when the tree has no leaf.
	bool empty() const { return 0 == m_root; }
	/// Rebuilds the tree by greedily pairing the two subtrees whose union is smallest.
	void optimizeBottomUp();
	/// Rebuilds the tree by splitting the leaves at the median of their centres along the widest axis,
	/// down to groups of bu_treshold leaves, which are built bottom-up.
	void optimizeTopDown(int bu_treshold = 128);
	/// Re-inserts `passes` leaves chosen along m_opath (passes < 0: as many as there are leaves).
	void optimizeIncremental(int passes);
	/// Adds a leaf of the given box and data and returns it.
	btDbvtNode* insert(const btDbvtVolume& box, void* data);
	/// Re-inserts the leaf, searching from `lookahead` levels above its old place (-1: from the root).
	void update(btDbvtNode* leaf, int lookahead = -1);
	/// Moves the leaf to a new box.
	void update(btDbvtNode* leaf, btDbvtVolume& volume);
	/// Returns false and changes nothing when the leaf's box contains volume; otherwise grows volume by
	/// margin on every side and by velocity on its side, moves the leaf to it and returns true.
	bool update(btDbvtNode* leaf, btDbvtVolume& volume, const btVector3& velocity, btScalar margin);
	/// update(leaf, volume, velocity, 0).
	bool update(btDbvtNode* leaf, btDbvtVolume& volume, const btVector3& velocity);
	/// update(leaf, volume, (0, 0, 0), margin).
	bool update(btDbvtNode* leaf, btDbvtVolume& volume, btScalar margin);
	/// Removes the leaf and frees it.
	void remove(btDbvtNode* leaf);
	/// Hands every node to iwriter, numbered in breadth-first order (the root is 0).
	void write(IWriter* iwriter) const;
	/// Makes dest a copy of this tree (same shape, boxes and leaf data); iclone may fix each leaf.
	void clone(btDbvt& dest, IClone* iclone = 0) const;
	/// The number of levels under node (a single leaf: 1, no node: 0).
	static int maxdepth(const btDbvtNode* node);
	/// The number of leaves under node.
	static int countLeaves(const btDbvtNode* node);
	/// Appends the leaves under node to leaves.
	static void extractLeaves(const btDbvtNode* node, btAlignedObjectArray<const btDbvtNode*>& leaves);
	/// Bullet's self benchmark; Caliber's lives in Demos/Benchmarks/CollisionBench/DbvtBench.cpp.
	static void benchmark() {}

	/// policy.Process(node) for every node under root, parents before children.
	DBVT_PREFIX static void enumNodes(const btDbvtNode* root, DBVT_IPOLICY);
	/// policy.Process(leaf) for every leaf under root.
	DBVT_PREFIX static void enumLeaves(const btDbvtNode* root, DBVT_IPOLICY);
	/// policy.Process(a, b) for every pair of overlapping leaves, a under root0 and b under root1. With
	/// root0 == root1 every unordered pair of distinct overlapping leaves is reported once.
	DBVT_PREFIX void collideTT(const btDbvtNode* root0, const btDbvtNode* root1, DBVT_IPOLICY);
	/// collideTT (both keep their stack in m_stkStack).
	DBVT_PREFIX void collideTTpersistentStack(const btDbvtNode* root0, const btDbvtNode* root1, DBVT_IPOLICY);
	/// policy.Process(leaf) for every leaf under root whose box overlaps volume.
	DBVT_PREFIX void collideTV(const btDbvtNode* root, const btDbvtVolume& volume, DBVT_IPOLICY) const;
	/// collideTV with a stack the caller keeps between queries.
	DBVT_PREFIX void collideTVNoStackAlloc(const btDbvtNode* root, const btDbvtVolume& volume, btNodeStack& stack,
	                                       DBVT_IPOLICY) const;
	/// policy.Process(leaf) for every leaf whose box the segment rayFrom -> rayTo touches. A zero-length
	/// segment finds the boxes containing rayFrom; a non-finite one asserts and finds nothing.
	DBVT_PREFIX static void rayTest(const btDbvtNode* root, const btVector3& rayFrom, const btVector3& rayTo,
	                                DBVT_IPOLICY);
	/// The ray rayFrom + t * d, t in [0, lambda_max], against every leaf box grown by the box
	/// [aabbMin, aabbMax] (a swept box); rayDirectionInverse = 1 / d, signs[i] = (rayDirectionInverse[i] < 0).
	DBVT_PREFIX void rayTestInternal(const btDbvtNode* root, const btVector3& rayFrom, const btVector3& rayTo,
	                                 const btVector3& rayDirectionInverse, unsigned int signs[3], btScalar lambda_max,
	                                 const btVector3& aabbMin, const btVector3& aabbMax,
	                                 btAlignedObjectArray<const btDbvtNode*>& stack, DBVT_IPOLICY) const;
	/// policy.Process(leaf) for every leaf whose box reaches the side dot(normals[i], p) + offsets[i] >= 0
	/// of each of the count planes (at most 32; more asserts and only the first 32 are used).
	DBVT_PREFIX static void collideKDOP(const btDbvtNode* root, const btVector3* normals, const btScalar* offsets,
	                                    int count, DBVT_IPOLICY);
	/// collideKDOP in front-to-back order along sortaxis: nodes for which policy.Descent is false are
	/// skipped with their subtree; leaves get policy.Process(leaf, least dot(sortaxis, p) over its box).
	/// fullsort: leaves in globally increasing order; otherwise depth first, nearer child first.
	DBVT_PREFIX static void collideOCL(const btDbvtNode* root, const btVector3* normals, const btScalar* offsets,
	                                   const btVector3& sortaxis, int count, DBVT_IPOLICY, bool fullsort = true);
	/// policy.Process(leaf) for every leaf reached by descending only into nodes with policy.Descent true.
	DBVT_PREFIX static void collideTU(const btDbvtNode* root, DBVT_IPOLICY);

	/// In i[l..h), indices of a sorted by decreasing value, the first position whose value is below v.
	static DBVT_INLINE int nearest(const int* i, const btDbvt::sStkNPS* a, btScalar v, int l, int h)
	{
		while (l < h)
		{
			const int middle = (l + h) >> 1;
			if (a[i[middle]].value >= v)
				l = middle + 1;
			else
				h = middle;
		}
		return h;
	}
	/// Stores value in stock, in a slot from ifree when there is one, and returns its index.
	static DBVT_INLINE int allocate(btAlignedObjectArray<int>& ifree, btAlignedObjectArray<sStkNPS>& stock,
	                                const sStkNPS& value)
	{
		if (ifree.size() > 0)
		{
			const int slot = ifree[ifree.size() - 1];
			ifree.pop_back();
			stock[slot] = value;
			return slot;
		}
		stock.push_back(value);
		return stock.size() - 1;
	}

private:
	btDbvt(const btDbvt&);
	btDbvt& operator=(const btDbvt&);
};

// ---- btDbvtAabbMm ---------------------------------------------------------------------------------------

inline btDbvtAabbMm btDbvtAabbMm::FromCE(const btVector3& c, const btVector3& e)
{
	btDbvtAabbMm box;
	box.mi = c - e;
	box.mx = c + e;
	return box;
}

inline btDbvtAabbMm btDbvtAabbMm::FromCR(const btVector3& c, btScalar r) { return FromCE(c, btVector3(r, r, r)); }

inline btDbvtAabbMm btDbvtAabbMm::FromMM(const btVector3& mi, const btVector3& mx)
{
	btDbvtAabbMm box;
	box.mi = mi;
	box.mx = mx;
	return box;
}

inline btDbvtAabbMm btDbvtAabbMm::FromPoints(const btVector3* pts, int n)
{
	btAssert(n > 0 && pts && "btDbvtAabbMm::FromPoints: no points");
	btDbvtAabbMm box;
	box.mi.setValue(0, 0, 0);
	box.mx.setValue(0, 0, 0);
	if (n <= 0 || !pts) return box;
	box.mi = box.mx = pts[0];
	for (int i = 1; i < n; ++i)
	{
		box.mi.setMin(pts[i]);
		box.mx.setMax(pts[i]);
	}
	return box;
}

inline btDbvtAabbMm btDbvtAabbMm::FromPoints(const btVector3** ppts, int n)
{
	btAssert(n > 0 && ppts && "btDbvtAabbMm::FromPoints: no points");
	btDbvtAabbMm box;
	box.mi.setValue(0, 0, 0);
	box.mx.setValue(0, 0, 0);
	if (n <= 0 || !ppts) return box;
	box.mi = box.mx = *ppts[0];
	for (int i = 1; i < n; ++i)
	{
		box.mi.setMin(*ppts[i]);
		box.mx.setMax(*ppts[i]);
	}
	return box;
}

DBVT_INLINE bool Intersect(const btDbvtAabbMm& a, const btDbvtAabbMm& b)
{
#ifdef BT_USE_SSE
	// All six comparisons at once and one branch on the result: tree walks take this test at every node,
	// and its outcome is too irregular for six early-out branches to predict. A NaN compares false, so a
	// NaN box intersects nothing, as in the scalar form.
	const __m128 ordered =
	    _mm_and_ps(_mm_cmple_ps(a.mi.get128(), b.mx.get128()), _mm_cmpge_ps(a.mx.get128(), b.mi.get128()));
	return (_mm_movemask_ps(ordered) & 7) == 7;
#else
	return a.mi.x() <= b.mx.x() && a.mx.x() >= b.mi.x() && a.mi.y() <= b.mx.y() && a.mx.y() >= b.mi.y() &&
	       a.mi.z() <= b.mx.z() && a.mx.z() >= b.mi.z();
#endif
}

DBVT_INLINE bool Intersect(const btDbvtAabbMm& a, const btVector3& b)
{
	return b.x() >= a.mi.x() && b.y() >= a.mi.y() && b.z() >= a.mi.z() && b.x() <= a.mx.x() && b.y() <= a.mx.y() &&
	       b.z() <= a.mx.z();
}

DBVT_INLINE btScalar Proximity(const btDbvtAabbMm& a, const btDbvtAabbMm& b)
{
	const btVector3 d = (a.mi + a.mx) - (b.mi + b.mx);
	return btFabs(d.x()) + btFabs(d.y()) + btFabs(d.z());
}

DBVT_INLINE int Select(const btDbvtAabbMm& o, const btDbvtAabbMm& a, const btDbvtAabbMm& b)
{
	return Proximity(o, a) < Proximity(o, b) ? 0 : 1;
}

DBVT_INLINE void Merge(const btDbvtAabbMm& a, const btDbvtAabbMm& b, btDbvtAabbMm& r)
{
	btVector3 lo = a.mi, hi = a.mx;
	lo.setMin(b.mi);
	hi.setMax(b.mx);
	r.mi = lo;
	r.mx = hi;
}

DBVT_INLINE bool NotEqual(const btDbvtAabbMm& a, const btDbvtAabbMm& b)
{
	return a.mi.x() != b.mi.x() || a.mi.y() != b.mi.y() || a.mi.z() != b.mi.z() || a.mx.x() != b.mx.x() ||
	       a.mx.y() != b.mx.y() || a.mx.z() != b.mx.z();
}

#include "BulletCollision/BroadphaseCollision/btDbvtQueries.h"

#endif  // BT_DYNAMIC_BOUNDING_VOLUME_TREE_H
