// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_UNION_FIND_H
#define BT_UNION_FIND_H

/// btUnionFind: disjoint sets over 0..N-1, used to group touching bodies into simulation islands.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

/// Kept for source compatibility: finds always compress paths.
#define USE_PATH_COMPRESSION 1

/// Kept for source compatibility: static and kinematic objects never get a union-find element, and
/// btSimulationIslandManager stores each element's object index in m_sz after the unions are done.
#define STATIC_SIMULATION_ISLAND_OPTIMIZATION 1

/// One element: its parent (the set's root for a root) and, for a root, the size of its set. After
/// sortIslands m_id is the element's root (its island id) and m_sz whatever the owner stored there.
struct btElement
{
	/// Parent element (itself for a root); the island id after sortIslands.
	int m_id;
	/// Set size while uniting (valid on roots); the island manager's object index after the unions.
	int m_sz;
};

/// Disjoint sets with union by size and path halving: unite and find cost near-constant amortised time.
class btUnionFind
{
private:
	btAlignedObjectArray<btElement> m_elements;

public:
	/// No elements.
	btUnionFind();
	/// Frees the elements.
	~btUnionFind();

	/// Replaces m_id of every element with its root and sorts the elements by (root, m_sz), so that each
	/// set is a contiguous run. Destroys the tree structure: call reset before uniting again.
	void sortIslands();

	/// N singleton sets (element i has id i and size 1). A negative N asserts and gives 0 elements.
	void reset(int N);

	/// Number of elements.
	SIMD_FORCE_INLINE int getNumElements() const { return m_elements.size(); }
	/// True when x is the root of its set.
	SIMD_FORCE_INLINE bool isRoot(int x) const { return x == m_elements[x].m_id; }

	/// Element at index.
	btElement& getElement(int index) { return m_elements[index]; }
	/// Element at index.
	const btElement& getElement(int index) const { return m_elements[index]; }

	/// Resizes to N elements without initialising them (reset does both).
	void allocate(int N);
	/// Removes every element.
	void Free();

	/// 1 when p and q are in the same set, else 0 (Bullet's signature).
	int find(int p, int q) { return find(p) == find(q) ? 1 : 0; }

	/// Merges the sets of p and q; the larger set's root becomes the root. Out-of-range indices assert and
	/// are ignored in release.
	void unite(int p, int q);

	/// Root of x's set, halving the path on the way. Out of range asserts and returns x in release.
	int find(int x);
};

#endif  // BT_UNION_FIND_H
