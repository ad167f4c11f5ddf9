// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btDbvt: random insert/update/remove sequences checked against brute force after every operation, the
// tree invariants, the rebuilds, clone, write, the queries (TV, TT, ray, k-DOP, OCL, TU) and bad input.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBoxWalk.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"

namespace
{
using shapes_core_test::Random;

// A leaf of the reference model: its id is stored in the leaf's data pointer.
struct RefLeaf
{
	btDbvtNode* node;
	btDbvtVolume box;
	bool alive;
};

void* idToData(int id) { return reinterpret_cast<void*>(static_cast<size_t>(id + 1)); }
int dataToId(const btDbvtNode* leaf) { return static_cast<int>(reinterpret_cast<size_t>(leaf->data)) - 1; }

btDbvtVolume randomBox(Random& rng, btScalar range = 50)
{
	const btVector3 half(rng.uniform(btScalar(0.1), 5), rng.uniform(btScalar(0.1), 5), rng.uniform(btScalar(0.1), 5));
	return btDbvtVolume::FromCE(rng.vector(range), half);
}

// Independent overlap test (touching counts, as in Bullet).
bool boxesOverlap(const btDbvtVolume& a, const btDbvtVolume& b)
{
	for (int i = 0; i < 3; ++i)
		if (a.Mins()[i] > b.Maxs()[i] || b.Mins()[i] > a.Maxs()[i]) return false;
	return true;
}

// Segment from -> to against the box grown by `grow` on every side (negative shrinks), in double.
bool segmentTouchesBox(const btVector3& from, const btVector3& to, const btDbvtVolume& box, double grow)
{
	double t0 = 0, t1 = 1;
	for (int a = 0; a < 3; ++a)
	{
		const double f = from[a], d = double(to[a]) - double(from[a]);
		const double lo = double(box.Mins()[a]) - grow, hi = double(box.Maxs()[a]) + grow;
		if (d == 0)
		{
			if (f < lo || f > hi) return false;
			continue;
		}
		double ta = (lo - f) / d, tb = (hi - f) / d;
		if (ta > tb) std::swap(ta, tb);
		t0 = std::max(t0, ta);
		t1 = std::min(t1, tb);
		if (t0 > t1) return false;
	}
	return true;
}

struct LeafCollector : btDbvt::ICollide
{
	using btDbvt::ICollide::Process;
	std::vector<int> ids;
	void Process(const btDbvtNode* leaf) override { ids.push_back(dataToId(leaf)); }
	std::set<int> set() const { return std::set<int>(ids.begin(), ids.end()); }
};

struct PairCollector : btDbvt::ICollide
{
	using btDbvt::ICollide::Process;
	std::set<std::pair<int, int>> pairs;
	int calls = 0;
	bool sameTree = true;
	void Process(const btDbvtNode* a, const btDbvtNode* b) override
	{
		++calls;
		const int ia = dataToId(a), ib = dataToId(b);
		pairs.insert(sameTree ? std::make_pair(std::min(ia, ib), std::max(ia, ib)) : std::make_pair(ia, ib));
	}
};

std::string describe(const std::set<int>& s)
{
	std::string out = "{";
	for (int v : s) out += std::to_string(v) + " ";
	return out + "}";
}

// Walks the whole tree and checks: parent links, internal boxes equal to the union of their children,
// 2n - 1 nodes, leaf count, and that the leaves are exactly the live reference leaves with their boxes.
::testing::AssertionResult treeIsConsistent(const btDbvt& tree, const std::vector<RefLeaf>& ref)
{
	int expectedLeaves = 0;
	for (const RefLeaf& r : ref) expectedLeaves += r.alive ? 1 : 0;
	if (tree.m_leaves != expectedLeaves)
		return ::testing::AssertionFailure() << "m_leaves " << tree.m_leaves << " != " << expectedLeaves;
	if (!tree.m_root)
		return expectedLeaves == 0 ? ::testing::AssertionSuccess() : ::testing::AssertionFailure() << "no root";
	if (tree.m_root->parent) return ::testing::AssertionFailure() << "root has a parent";
	std::vector<const btDbvtNode*> stack(1, tree.m_root);
	int nodes = 0, leaves = 0;
	std::set<int> seen;
	while (!stack.empty())
	{
		const btDbvtNode* n = stack.back();
		stack.pop_back();
		if (++nodes > 2 * expectedLeaves) return ::testing::AssertionFailure() << "too many nodes (cycle?)";
		if (n->isleaf())
		{
			++leaves;
			const int id = dataToId(n);
			if (id < 0 || id >= int(ref.size()) || !ref[id].alive || ref[id].node != n)
				return ::testing::AssertionFailure() << "unexpected leaf id " << id;
			if (NotEqual(n->volume, ref[id].box))
				return ::testing::AssertionFailure() << "leaf " << id << " box changed";
			if (!seen.insert(id).second) return ::testing::AssertionFailure() << "leaf " << id << " twice";
			continue;
		}
		for (int c = 0; c < 2; ++c)
		{
			const btDbvtNode* child = n->childs[c];
			if (!child) return ::testing::AssertionFailure() << "internal node without child " << c;
			if (child->parent != n) return ::testing::AssertionFailure() << "bad parent link";
			if (!n->volume.Contain(child->volume)) return ::testing::AssertionFailure() << "parent misses child";
			stack.push_back(child);
		}
		btDbvtVolume u;
		Merge(n->childs[0]->volume, n->childs[1]->volume, u);
		if (NotEqual(u, n->volume)) return ::testing::AssertionFailure() << "internal box not the tight union";
	}
	if (leaves != expectedLeaves)
		return ::testing::AssertionFailure() << "leaves " << leaves << " != " << expectedLeaves;
	if (nodes != 2 * expectedLeaves - 1) return ::testing::AssertionFailure() << "nodes " << nodes;
	if (btDbvt::countLeaves(tree.m_root) != expectedLeaves) return ::testing::AssertionFailure() << "countLeaves";
	return ::testing::AssertionSuccess();
}

// collideTV, collideTVNoStackAlloc, self collideTT and rayTest against brute force on the reference.
::testing::AssertionResult queriesMatchBruteForce(btDbvt& tree, const std::vector<RefLeaf>& ref, Random& rng)
{
	btNodeStack stack;
	for (int q = 0; q < 8; ++q)
	{
		const btDbvtVolume query = randomBox(rng, 40);
		std::set<int> expected;
		for (int i = 0; i < int(ref.size()); ++i)
			if (ref[i].alive && boxesOverlap(ref[i].box, query)) expected.insert(i);
		LeafCollector tv, tvNoAlloc;
		tree.collideTV(tree.m_root, query, tv);
		tree.collideTVNoStackAlloc(tree.m_root, query, stack, tvNoAlloc);
		if (tv.set() != expected || tv.ids.size() != expected.size())
			return ::testing::AssertionFailure() << "collideTV " << describe(tv.set()) << " vs " << describe(expected);
		if (tvNoAlloc.set() != expected) return ::testing::AssertionFailure() << "collideTVNoStackAlloc differs";
	}
	PairCollector tt;
	tree.collideTT(tree.m_root, tree.m_root, tt);
	std::set<std::pair<int, int>> expectedPairs;
	for (int i = 0; i < int(ref.size()); ++i)
		for (int j = i + 1; j < int(ref.size()); ++j)
			if (ref[i].alive && ref[j].alive && boxesOverlap(ref[i].box, ref[j].box)) expectedPairs.insert({i, j});
	if (tt.pairs != expectedPairs || tt.calls != int(expectedPairs.size()))
		return ::testing::AssertionFailure() << "collideTT: " << tt.calls << " calls, " << tt.pairs.size()
		                                     << " pairs, expected " << expectedPairs.size();
	for (int q = 0; q < 8; ++q)
	{
		const btVector3 from = rng.vector(60);
		btVector3 to = rng.vector(60);
		if (q % 4 == 0) to[q % 3] = from[q % 3];  // a direction with an exactly zero component
		LeafCollector ray;
		btDbvt::rayTest(tree.m_root, from, to, ray);
		const std::set<int> got = ray.set();
		// Float rounding of the slab test: a box grazed within 1e-3 (coordinates up to ~60) may go either way.
		for (int i = 0; i < int(ref.size()); ++i)
		{
			if (!ref[i].alive) continue;
			const bool surely = segmentTouchesBox(from, to, ref[i].box, -1e-3);
			const bool maybe = segmentTouchesBox(from, to, ref[i].box, 1e-3);
			if (surely && !got.count(i)) return ::testing::AssertionFailure() << "rayTest missed leaf " << i;
			if (!maybe && got.count(i)) return ::testing::AssertionFailure() << "rayTest reported leaf " << i;
		}
		if (ray.ids.size() != got.size()) return ::testing::AssertionFailure() << "rayTest reported a leaf twice";
	}
	return ::testing::AssertionSuccess();
}

int insertRandom(btDbvt& tree, std::vector<RefLeaf>& ref, Random& rng)
{
	RefLeaf r;
	r.box = randomBox(rng);
	r.alive = true;
	const int id = int(ref.size());
	r.node = tree.insert(r.box, idToData(id));
	ref.push_back(r);
	return id;
}

int randomAlive(const std::vector<RefLeaf>& ref, Random& rng)
{
	std::vector<int> alive;
	for (int i = 0; i < int(ref.size()); ++i)
		if (ref[i].alive) alive.push_back(i);
	if (alive.empty()) return -1;
	return alive[std::min(int(alive.size()) - 1, int(rng.uniform(0, btScalar(alive.size()))))];
}

void buildRandomTree(btDbvt& tree, std::vector<RefLeaf>& ref, Random& rng, int count)
{
	for (int i = 0; i < count; ++i) insertRandom(tree, ref, rng);
}
}  // namespace

TEST(Dbvt, RandomInsertUpdateRemoveKeepsInvariantsAndQueriesExact)
{
	for (unsigned seed : {1u, 2u, 3u})
	{
		Random rng(seed);
		btDbvt tree;
		tree.m_lkhd = seed == 3 ? 2 : -1;  // one run re-inserts from two levels above the old place
		std::vector<RefLeaf> ref;
		for (int op = 0; op < 600; ++op)
		{
			const btScalar choice = rng.uniform(0, 1);
			const int victim = randomAlive(ref, rng);
			if (choice < 0.4 || victim < 0)
				insertRandom(tree, ref, rng);
			else if (choice < 0.6)
			{
				// Small random motion, as in a broadphase.
				btDbvtVolume moved =
				    btDbvtVolume::FromCE(ref[victim].box.Center() + rng.vector(2), ref[victim].box.Extents());
				tree.update(ref[victim].node, moved);
				ref[victim].box = moved;
			}
			else if (choice < 0.7)
			{
				btDbvtVolume target = randomBox(rng);
				const btVector3 velocity = rng.vector(1);
				const btScalar margin = rng.uniform(0, btScalar(0.5));
				const bool contained = ref[victim].box.Contain(target);
				const bool moved = tree.update(ref[victim].node, target, velocity, margin);
				EXPECT_EQ(moved, !contained);
				if (moved) ref[victim].box = target;
			}
			else if (choice < 0.75)
				tree.update(ref[victim].node, int(rng.uniform(-1, 3)));  // re-insert with some lookahead
			else
			{
				tree.remove(ref[victim].node);
				ref[victim].alive = false;
			}
			ASSERT_TRUE(treeIsConsistent(tree, ref)) << "seed " << seed << " op " << op;
			if (op % 50 == 49)
			{
				ASSERT_TRUE(queriesMatchBruteForce(tree, ref, rng)) << "seed " << seed << " op " << op;
			}
		}
	}
}

TEST(Dbvt, RemovingEveryLeafEmptiesTheTreeAndReusesNodes)
{
	Random rng(11);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 100);
	for (int i = 0; i < 100; ++i)
	{
		tree.remove(ref[i].node);
		ref[i].alive = false;
		ASSERT_TRUE(treeIsConsistent(tree, ref));
	}
	EXPECT_TRUE(tree.empty());
	EXPECT_EQ(btDbvt::maxdepth(tree.m_root), 0);
	// The freed nodes come back first: a second fill of the same size takes nodes from the free list only.
	const btDbvtNode* freeHead = tree.m_free;
	EXPECT_NE(freeHead, nullptr);
	btDbvtNode* leaf = tree.insert(randomBox(rng), 0);
	EXPECT_EQ(leaf, freeHead);
}

// The ray and pair walks read a node's box and then its child links: a node that straddles two cache lines
// costs them two reads from memory. Every node of a tree of several blocks (in use or free) spans the
// fewest 64-byte lines its size allows.
TEST(Dbvt, EveryNodeSpansTheFewestCacheLinesItsSizeAllows)
{
	Random rng(23);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 3000);  // blocks of 64, 128, ... nodes: several allocations
	for (int i = 0; i < 3000; i += 3)
	{
		tree.remove(ref[i].node);
		ref[i].alive = false;
	}
	const size_t line = 64;
	const size_t size = sizeof(btDbvtNode);
	const size_t fewest = (size + line - 1) / line;
	auto linesSpanned = [&](const btDbvtNode* node)
	{
		const size_t first = reinterpret_cast<size_t>(node) / line;
		const size_t last = (reinterpret_cast<size_t>(node) + size - 1) / line;
		return last - first + 1;
	};
	int checked = 0;
	std::vector<const btDbvtNode*> stack(1, tree.m_root);
	while (!stack.empty())
	{
		const btDbvtNode* node = stack.back();
		stack.pop_back();
		EXPECT_EQ(linesSpanned(node), fewest) << "node at " << static_cast<const void*>(node);
		++checked;
		if (node->isinternal())
		{
			stack.push_back(node->childs[0]);
			stack.push_back(node->childs[1]);
		}
	}
	for (const btDbvtNode* node = tree.m_free; node; node = node->parent)
	{
		EXPECT_EQ(linesSpanned(node), fewest) << "free node at " << static_cast<const void*>(node);
		++checked;
	}
	EXPECT_GE(checked, 2 * 3000 - 1);
}

TEST(Dbvt, RebuildsKeepLeavesInvariantsAndQueries)
{
	Random rng(5);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 300);
	tree.optimizeIncremental(50);
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	ASSERT_TRUE(queriesMatchBruteForce(tree, ref, rng));
	tree.optimizeIncremental(-1);
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	tree.optimizeTopDown(16);
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	ASSERT_TRUE(queriesMatchBruteForce(tree, ref, rng));
	// A median split halves the leaves at every level above the groups of 16 built bottom-up.
	const int depthTopDown = btDbvt::maxdepth(tree.m_root);
	EXPECT_LE(depthTopDown, 5 + 16) << "depth " << depthTopDown;
	tree.optimizeTopDown();
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	tree.optimizeBottomUp();
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	ASSERT_TRUE(queriesMatchBruteForce(tree, ref, rng));
	// Rebuilding twice, then moving leaves, still works on the rebuilt tree.
	for (int i = 0; i < 50; ++i)
	{
		btDbvtVolume moved = randomBox(rng);
		tree.update(ref[i].node, moved);
		ref[i].box = moved;
	}
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	ASSERT_TRUE(queriesMatchBruteForce(tree, ref, rng));
}

TEST(Dbvt, InsertionKeepsTreeShallowForRandomAndSortedInput)
{
	// Cost-based insertion has no balance guarantee; these bounds (about 3 log2 n) catch a tree that
	// degenerates towards a list (depth ~ n).
	for (int sorted = 0; sorted < 2; ++sorted)
	{
		Random rng(21);
		btDbvt tree;
		const int n = 2000;
		for (int i = 0; i < n; ++i)
		{
			const btVector3 centre = sorted ? btVector3(btScalar(i), 0, 0) : rng.vector(100);
			tree.insert(btDbvtVolume::FromCR(centre, btScalar(0.5)), 0);
		}
		const int depth = btDbvt::maxdepth(tree.m_root);
		EXPECT_LE(depth, 3 * 11) << (sorted ? "sorted" : "random") << " input: depth " << depth;
	}
}

TEST(Dbvt, InsertionIntoATreeDeeperThanItsSearchStackStillFindsTheBestSibling)
{
	// The sibling search keeps about one pending node per level in a local array and continues on the heap
	// in deeper trees. A caterpillar tree of 100 unit boxes along x (each internal node: one leaf and the
	// rest) is 100 levels deep; a new box equal to the deepest leaf's adds the least area as that leaf's
	// sibling (area 3 and no ancestor grows; every other sibling's union is longer), so a search that
	// stopped at the array's end would pick a shallower node.
	const int n = 100;
	btDbvt tree;
	std::vector<RefLeaf> ref;
	for (int i = 0; i < n; ++i)
	{
		const btDbvtVolume box = btDbvtVolume::FromMM(btVector3(btScalar(i), 0, 0), btVector3(btScalar(i + 1), 1, 1));
		ref.push_back({tree.insert(box, idToData(i)), box, true});
	}
	// Relink the tree's own internal nodes into the caterpillar.
	std::vector<btDbvtNode*> internals, stack(1, tree.m_root);
	while (!stack.empty())
	{
		btDbvtNode* node = stack.back();
		stack.pop_back();
		if (node->isleaf()) continue;
		internals.push_back(node);
		stack.push_back(node->childs[0]);
		stack.push_back(node->childs[1]);
	}
	ASSERT_EQ(int(internals.size()), n - 1);
	for (int i = n - 2; i >= 0; --i)
	{
		btDbvtNode* node = internals[i];
		btDbvtNode* rest = i == n - 2 ? ref[n - 1].node : internals[i + 1];
		node->childs[0] = ref[i].node;
		node->childs[1] = rest;
		ref[i].node->parent = node;
		rest->parent = node;
		Merge(ref[i].node->volume, rest->volume, node->volume);
	}
	tree.m_root = internals[0];
	tree.m_root->parent = 0;
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	ASSERT_EQ(btDbvt::maxdepth(tree.m_root), n);

	const btDbvtVolume box = ref[n - 1].box;
	btDbvtNode* leaf = tree.insert(box, idToData(n));
	ref.push_back({leaf, box, true});
	ASSERT_TRUE(treeIsConsistent(tree, ref));
	const btDbvtNode* parent = leaf->parent;
	ASSERT_NE(parent, nullptr);
	const btDbvtNode* sibling = parent->childs[parent->childs[0] == leaf ? 1 : 0];
	EXPECT_EQ(sibling, ref[n - 1].node) << "sibling is leaf " << (sibling->isleaf() ? dataToId(sibling) : -1);
}

TEST(Dbvt, CollideTTBetweenTwoTreesMatchesBruteForce)
{
	Random rng(7);
	btDbvt a, b;
	std::vector<RefLeaf> ra, rb;
	buildRandomTree(a, ra, rng, 150);
	buildRandomTree(b, rb, rng, 120);
	PairCollector tt;
	tt.sameTree = false;
	a.collideTT(a.m_root, b.m_root, tt);
	std::set<std::pair<int, int>> expected;
	for (int i = 0; i < int(ra.size()); ++i)
		for (int j = 0; j < int(rb.size()); ++j)
			if (boxesOverlap(ra[i].box, rb[j].box)) expected.insert({i, j});
	EXPECT_EQ(tt.pairs, expected);
	EXPECT_EQ(tt.calls, int(expected.size()));
	PairCollector persistent;
	persistent.sameTree = false;
	a.collideTTpersistentStack(a.m_root, b.m_root, persistent);
	EXPECT_EQ(persistent.pairs, expected);
}

TEST(Dbvt, RayTestInternalWithSweptBoxMatchesBruteForce)
{
	Random rng(8);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 200);
	btAlignedObjectArray<const btDbvtNode*> stack;
	for (int q = 0; q < 20; ++q)
	{
		const btVector3 from = rng.vector(60), to = rng.vector(60);
		const btVector3 half(1, btScalar(0.5), 2);
		const btScalar length = (to - from).length();
		const btVector3 dir = (to - from) / length;
		btVector3 inverse;
		unsigned signs[3];
		for (int a = 0; a < 3; ++a)
		{
			inverse[a] = dir[a] == 0 ? btScalar(BT_LARGE_FLOAT) : 1 / dir[a];
			signs[a] = inverse[a] < 0;
		}
		LeafCollector hits;
		tree.rayTestInternal(tree.m_root, from, to, inverse, signs, length, -half, half, stack, hits);
		const std::set<int> got = hits.set();
		for (int i = 0; i < int(ref.size()); ++i)
		{
			btDbvtVolume grown = ref[i].box;
			grown.Expand(half);
			const bool surely = segmentTouchesBox(from, to, grown, -1e-3);
			const bool maybe = segmentTouchesBox(from, to, grown, 1e-3);
			EXPECT_TRUE(!surely || got.count(i)) << "query " << q << " missed " << i;
			EXPECT_TRUE(maybe || !got.count(i)) << "query " << q << " extra " << i;
		}
	}
}

TEST(Dbvt, ZeroLengthRayFindsBoxesContainingThePoint)
{
	Random rng(9);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 200);
	for (int q = 0; q < 20; ++q)
	{
		const btVector3 p = rng.vector(40);
		LeafCollector hits;
		btDbvt::rayTest(tree.m_root, p, p, hits);
		std::set<int> expected;
		for (int i = 0; i < int(ref.size()); ++i)
			if (Intersect(ref[i].box, p)) expected.insert(i);
		EXPECT_EQ(hits.set(), expected);
	}
}

namespace
{
// max over the box corners of dot(n, p) + o, and min of dot(axis, p), in double.
double maxPlaneValue(const btDbvtVolume& b, const btVector3& n, btScalar o)
{
	double best = -1e300;
	for (int c = 0; c < 8; ++c)
	{
		double v = o;
		for (int a = 0; a < 3; ++a) v += double(n[a]) * double(((c >> a) & 1) ? b.Maxs()[a] : b.Mins()[a]);
		best = std::max(best, v);
	}
	return best;
}

struct OclCollector : btDbvt::ICollide
{
	using btDbvt::ICollide::Process;
	std::vector<int> ids;
	std::vector<btScalar> values;
	void Process(const btDbvtNode* leaf, btScalar value) override
	{
		ids.push_back(dataToId(leaf));
		values.push_back(value);
	}
};
}  // namespace

TEST(Dbvt, CollideKdopAndOclReportLeavesInsideEveryHalfSpace)
{
	Random rng(10);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 300);
	for (int q = 0; q < 10; ++q)
	{
		btVector3 normals[4];
		btScalar offsets[4];
		for (int i = 0; i < 4; ++i)
		{
			normals[i] = rng.unitVector();
			offsets[i] = rng.uniform(-10, 30);
		}
		LeafCollector kdop;
		btDbvt::collideKDOP(tree.m_root, normals, offsets, 4, kdop);
		const std::set<int> got = kdop.set();
		std::set<int> expected;  // the leaves that are certainly inside; a band of 1e-3 may go either way
		for (int i = 0; i < int(ref.size()); ++i)
		{
			double worst = 1e300;
			for (int p = 0; p < 4; ++p) worst = std::min(worst, maxPlaneValue(ref[i].box, normals[p], offsets[p]));
			if (worst > 1e-3) expected.insert(i);
			EXPECT_TRUE(worst > -1e-3 || !got.count(i)) << "leaf " << i << " outside a plane by " << worst;
		}
		for (int i : expected) EXPECT_TRUE(got.count(i)) << "k-DOP missed leaf " << i;
		EXPECT_EQ(kdop.ids.size(), got.size());

		const btVector3 axis = rng.unitVector();
		for (int fullsort = 0; fullsort < 2; ++fullsort)
		{
			OclCollector ocl;
			btDbvt::collideOCL(tree.m_root, normals, offsets, axis, 4, ocl, fullsort != 0);
			EXPECT_EQ(std::set<int>(ocl.ids.begin(), ocl.ids.end()), got) << "OCL and k-DOP disagree";
			for (size_t k = 0; k < ocl.ids.size(); ++k)
			{
				// The value is the least projection of the leaf's box on the axis (8 corners, in double).
				double least = 1e300;
				const btDbvtVolume& b = ref[ocl.ids[k]].box;
				for (int c = 0; c < 8; ++c)
				{
					double v = 0;
					for (int a = 0; a < 3; ++a)
						v += double(axis[a]) * double(((c >> a) & 1) ? b.Maxs()[a] : b.Mins()[a]);
					least = std::min(least, v);
				}
				EXPECT_NEAR(double(ocl.values[k]), least, 1e-3);
				if (fullsort && k > 0)
				{
					EXPECT_LE(ocl.values[k - 1], ocl.values[k]) << "not front to back at " << k;
				}
			}
		}
	}
}

TEST(Dbvt, CollideTUAndOclDescendOnlyWhereAllowed)
{
	Random rng(12);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 200);
	// Descent refuses every node whose box centre has x < 0; a leaf is reached iff it and all its ancestors pass.
	struct Guided : btDbvt::ICollide
	{
		using btDbvt::ICollide::Process;
		std::set<int> ids;
		bool Descent(const btDbvtNode* n) override { return n->volume.Center().x() >= 0; }
		void Process(const btDbvtNode* leaf) override { ids.insert(dataToId(leaf)); }
	};
	std::set<int> expected;
	for (int i = 0; i < int(ref.size()); ++i)
	{
		bool reachable = true;
		for (const btDbvtNode* n = ref[i].node; n; n = n->parent) reachable = reachable && n->volume.Center().x() >= 0;
		if (reachable) expected.insert(i);
	}
	Guided tu;
	btDbvt::collideTU(tree.m_root, tu);
	EXPECT_EQ(tu.ids, expected);
	Guided ocl;
	btDbvt::collideOCL(tree.m_root, 0, 0, btVector3(1, 0, 0), 0, ocl);
	EXPECT_EQ(ocl.ids, expected);
}

TEST(Dbvt, EnumerationDepthAndLeafExtraction)
{
	Random rng(13);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 257);
	struct Counter : btDbvt::ICollide
	{
		using btDbvt::ICollide::Process;
		int nodes = 0, leaves = 0;
		void Process(const btDbvtNode* n) override { (n->isleaf() ? leaves : nodes)++; }
	};
	Counter all, leavesOnly;
	btDbvt::enumNodes(tree.m_root, all);
	btDbvt::enumLeaves(tree.m_root, leavesOnly);
	EXPECT_EQ(all.leaves, 257);
	EXPECT_EQ(all.nodes, 256);
	EXPECT_EQ(leavesOnly.leaves, 257);
	EXPECT_EQ(leavesOnly.nodes, 0);
	btAlignedObjectArray<const btDbvtNode*> leaves;
	btDbvt::extractLeaves(tree.m_root, leaves);
	std::set<const btDbvtNode*> extracted;
	for (int i = 0; i < leaves.size(); ++i) extracted.insert(leaves[i]);
	std::set<const btDbvtNode*> expected;
	for (const RefLeaf& r : ref) expected.insert(r.node);
	EXPECT_EQ(extracted, expected);
	// A binary tree of 257 leaves has at least 10 levels (2^8 < 257 leaves need 9 edges).
	const int depth = btDbvt::maxdepth(tree.m_root);
	EXPECT_GE(depth, 10);
	EXPECT_LE(depth, 257);
	btDbvt single;
	single.insert(randomBox(rng), 0);
	EXPECT_EQ(btDbvt::maxdepth(single.m_root), 1);
	EXPECT_EQ(btDbvt::countLeaves(single.m_root), 1);
	EXPECT_EQ(btDbvt::countLeaves(0), 0);
}

// The broadphase's pair search adds new pairs in the order its box query finds the leaves, and that order
// is part of the results (the pair cache's order is the narrowphase's and the solver's). The query is a
// depth-first walk that prunes by box only, so it finds exactly the leaves whose boxes touch the query, in
// the tree's own leaf order (childs[1]'s subtree first: enumLeaves' order reversed), whatever was pruned on
// the way. collideTVNoStackAlloc and caliber::collideTVInTreeOrder (the pair search's walk, which tests the
// children before it pushes them) must both give that order; the latter also when its stack outgrows its
// inline array (an inline capacity of 2 here). Checked on trees shaped by insertions, moves and removals.
TEST(Dbvt, BoxQueryFindsTouchingLeavesInTheTreesLeafOrder)
{
	struct Ordered : btDbvt::ICollide
	{
		using btDbvt::ICollide::Process;
		std::vector<int> ids;
		void Process(const btDbvtNode* n) override { ids.push_back(dataToId(n)); }
	};
	for (unsigned seed : {21u, 22u})
	{
		Random rng(seed);
		btDbvt tree;
		tree.m_lkhd = 4;  // as the broadphase's dynamic tree
		std::vector<RefLeaf> ref;
		buildRandomTree(tree, ref, rng, 400);
		for (int op = 0; op < 300; ++op)
		{
			const int victim = randomAlive(ref, rng);
			if (op % 10 == 9)
			{
				tree.remove(ref[victim].node);
				ref[victim].alive = false;
				continue;
			}
			btDbvtVolume moved =
			    btDbvtVolume::FromCE(ref[victim].box.Center() + rng.vector(3), ref[victim].box.Extents());
			tree.update(ref[victim].node, moved);
			ref[victim].box = moved;
		}
		ASSERT_TRUE(treeIsConsistent(tree, ref));
		Ordered leafOrder;
		btDbvt::enumLeaves(tree.m_root, leafOrder);
		std::reverse(leafOrder.ids.begin(), leafOrder.ids.end());
		btNodeStack stack;
		int several = 0;
		for (int q = 0; q < 200; ++q)
		{
			// Queries the size of a leaf (the pair search's) and larger ones.
			const btDbvtVolume query =
			    q % 2 ? randomBox(rng) : btDbvtVolume::FromCE(rng.vector(45), rng.vector(15).absolute());
			std::vector<int> expected;
			for (int id : leafOrder.ids)
				if (boxesOverlap(ref[id].box, query)) expected.push_back(id);
			Ordered found, walked, spilled;
			tree.collideTVNoStackAlloc(tree.m_root, query, stack, found);
			caliber::collideTVInTreeOrder<64>(tree.m_root, query, walked);
			caliber::collideTVInTreeOrder<2>(tree.m_root, query, spilled);
			ASSERT_EQ(found.ids, expected) << "seed " << seed << " query " << q;
			ASSERT_EQ(walked.ids, expected) << "seed " << seed << " query " << q;
			ASSERT_EQ(spilled.ids, expected) << "seed " << seed << " query " << q;
			several += expected.size() > 1 ? 1 : 0;
		}
		// The order is tested on queries that find several leaves, not only on empty or single answers.
		EXPECT_GT(several, 40) << "seed " << seed;
	}
	// The empty tree and a query that misses the root.
	btDbvt empty;
	Ordered none;
	caliber::collideTVInTreeOrder<4>(empty.m_root, btDbvtVolume::FromCR(btVector3(0, 0, 0), 1), none);
	EXPECT_TRUE(none.ids.empty());
}

TEST(Dbvt, CloneGivesIdenticalQueryResults)
{
	Random rng(14);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 200);
	struct CountingClone : btDbvt::IClone
	{
		int leaves = 0;
		void CloneLeaf(btDbvtNode*) override { ++leaves; }
	} counting;
	btDbvt copy;
	copy.insert(randomBox(rng), 0);  // clone replaces whatever dest held
	tree.clone(copy, &counting);
	EXPECT_EQ(counting.leaves, 200);
	EXPECT_EQ(copy.m_leaves, 200);
	EXPECT_EQ(btDbvt::maxdepth(copy.m_root), btDbvt::maxdepth(tree.m_root));
	for (int q = 0; q < 20; ++q)
	{
		const btDbvtVolume query = randomBox(rng, 40);
		LeafCollector original, cloned;
		tree.collideTV(tree.m_root, query, original);
		copy.collideTV(copy.m_root, query, cloned);
		EXPECT_EQ(original.ids, cloned.ids);  // same shape: same order too
	}
	PairCollector a, b;
	tree.collideTT(tree.m_root, tree.m_root, a);
	copy.collideTT(copy.m_root, copy.m_root, b);
	EXPECT_EQ(a.pairs, b.pairs);
	// The copy is independent: clearing the source leaves it intact.
	tree.clear();
	EXPECT_EQ(btDbvt::countLeaves(copy.m_root), 200);
}

TEST(Dbvt, WriteVisitsEveryNodeOnceWithConsistentIndices)
{
	Random rng(15);
	btDbvt tree;
	std::vector<RefLeaf> ref;
	buildRandomTree(tree, ref, rng, 100);
	struct Recorder : btDbvt::IWriter
	{
		int prepared = -1;
		const btDbvtNode* root = 0;
		std::vector<const btDbvtNode*> byIndex;
		std::vector<int> parentIndex, child0, child1;
		void Prepare(const btDbvtNode* r, int n) override
		{
			root = r;
			prepared = n;
			byIndex.assign(n, nullptr);
			parentIndex.assign(n, -2);
			child0.assign(n, -2);
			child1.assign(n, -2);
		}
		void WriteNode(const btDbvtNode* n, int index, int parent, int c0, int c1) override
		{
			ASSERT_TRUE(index >= 0 && index < prepared && !byIndex[index]);
			byIndex[index] = n;
			parentIndex[index] = parent;
			child0[index] = c0;
			child1[index] = c1;
		}
		void WriteLeaf(const btDbvtNode* n, int index, int parent) override
		{
			ASSERT_TRUE(index >= 0 && index < prepared && !byIndex[index]);
			byIndex[index] = n;
			parentIndex[index] = parent;
		}
	} rec;
	tree.write(&rec);
	ASSERT_EQ(rec.prepared, 199);
	EXPECT_EQ(rec.root, tree.m_root);
	std::set<const btDbvtNode*> distinct(rec.byIndex.begin(), rec.byIndex.end());
	EXPECT_EQ(int(distinct.size()), 199);
	EXPECT_EQ(distinct.count(nullptr), 0u);
	for (int i = 0; i < rec.prepared; ++i)
	{
		const btDbvtNode* n = rec.byIndex[i];
		if (!n) continue;
		const btDbvtNode* expectedParent = n == tree.m_root ? nullptr : n->parent;
		const btDbvtNode* writtenParent = rec.parentIndex[i] == -1 ? nullptr : rec.byIndex[rec.parentIndex[i]];
		EXPECT_EQ(writtenParent, expectedParent);
		if (n->isinternal())
		{
			EXPECT_EQ(rec.byIndex[rec.child0[i]], n->childs[0]);
			EXPECT_EQ(rec.byIndex[rec.child1[i]], n->childs[1]);
		}
	}
}

TEST(Dbvt, UpdateWithMarginReturnsFalseWhenContained)
{
	btDbvt tree;
	btDbvtNode* other = tree.insert(btDbvtVolume::FromCR(btVector3(10, 0, 0), 1), 0);
	btDbvtNode* leaf = tree.insert(btDbvtVolume::FromMM(btVector3(-1, -1, -1), btVector3(1, 1, 1)), 0);
	(void)other;
	btDbvtVolume inside = btDbvtVolume::FromMM(btVector3(-btScalar(0.5), -1, 0), btVector3(1, btScalar(0.5), 1));
	EXPECT_FALSE(tree.update(leaf, inside, btVector3(1, 0, 0), btScalar(0.1)));
	EXPECT_FALSE(tree.update(leaf, inside, btVector3(1, 0, 0)));
	EXPECT_FALSE(tree.update(leaf, inside, btScalar(0.1)));
	EXPECT_FALSE(NotEqual(leaf->volume, btDbvtVolume::FromMM(btVector3(-1, -1, -1), btVector3(1, 1, 1))));
	// Sticking out: grown by the margin on every side and by the velocity on its side.
	btDbvtVolume outside = btDbvtVolume::FromMM(btVector3(0, 0, 0), btVector3(2, 2, 2));
	EXPECT_TRUE(tree.update(leaf, outside, btVector3(btScalar(0.5), -btScalar(0.25), 0), btScalar(0.125)));
	const btDbvtVolume expected = btDbvtVolume::FromMM(btVector3(-btScalar(0.125), -btScalar(0.375), -btScalar(0.125)),
	                                                   btVector3(btScalar(2.625), btScalar(2.125), btScalar(2.125)));
	EXPECT_FALSE(NotEqual(leaf->volume, expected));
	EXPECT_FALSE(NotEqual(outside, expected));  // the volume argument is updated in place, as in Bullet
	EXPECT_TRUE(tree.m_root->volume.Contain(expected));
}

TEST(Dbvt, VolumeHelpersMatchTheirDefinitions)
{
	const btDbvtVolume a = btDbvtVolume::FromCE(btVector3(1, 2, 3), btVector3(1, 1, 2));
	EXPECT_TRUE(shapes_core_test::vectorsNear(a.Mins(), btVector3(0, 1, 1), 0));
	EXPECT_TRUE(shapes_core_test::vectorsNear(a.Lengths(), btVector3(2, 2, 4), 0));
	const btVector3 pts[3] = {btVector3(1, -2, 0), btVector3(-1, 5, 2), btVector3(0, 0, -3)};
	const btDbvtVolume p = btDbvtVolume::FromPoints(pts, 3);
	EXPECT_TRUE(shapes_core_test::vectorsNear(p.Mins(), btVector3(-1, -2, -3), 0));
	EXPECT_TRUE(shapes_core_test::vectorsNear(p.Maxs(), btVector3(1, 5, 2), 0));
	const btVector3* ptrs[3] = {&pts[0], &pts[1], &pts[2]};
	EXPECT_FALSE(NotEqual(btDbvtVolume::FromPoints(ptrs, 3), p));
	EXPECT_TRUE(Intersect(a, btVector3(0, 1, 1)));  // a corner counts
	EXPECT_FALSE(Intersect(a, btVector3(0, 1, btScalar(0.99))));
	// Plane z + 0.5 >= 0: a (z in [1, 5]) inside, p (z in [-3, 2]) across, a box below outside.
	const btVector3 n(0, 0, 1);
	EXPECT_EQ(a.Classify(n, btScalar(0.5), 7), 1);
	EXPECT_EQ(p.Classify(n, btScalar(0.5), 7), 0);
	EXPECT_EQ(btDbvtVolume::FromCR(btVector3(0, 0, -5), 1).Classify(n, btScalar(0.5), 7), -1);
	// Least of dot((1, -1, 0), q) over a is 0 - 3 = -3.
	EXPECT_EQ(a.ProjectMinimum(btVector3(1, -1, 0), 1 + 4), btScalar(-3));
	btDbvtVolume s = a;
	s.SignedExpand(btVector3(-1, 2, 0));
	EXPECT_TRUE(shapes_core_test::vectorsNear(s.Mins(), btVector3(-1, 1, 1), 0));
	EXPECT_TRUE(shapes_core_test::vectorsNear(s.Maxs(), btVector3(2, 5, 5), 0));
	const btDbvtVolume far = btDbvtVolume::FromCR(btVector3(10, 0, 0), 1);
	const btDbvtVolume nearBox = btDbvtVolume::FromCR(btVector3(2, 2, 2), 1);
	EXPECT_EQ(Select(a, nearBox, far), 0);
	EXPECT_EQ(Select(a, far, nearBox), 1);
}

TEST(Dbvt, BoxesIntersectWhenOverlappingOrTouchingOnEveryAxis)
{
	const btDbvtVolume a = btDbvtVolume::FromMM(btVector3(0, 0, 0), btVector3(1, 2, 3));
	// Overlap, containment and touching faces or corners count, in both argument orders.
	const btDbvtVolume overlapping = btDbvtVolume::FromMM(btVector3(btScalar(0.5), 1, 2), btVector3(2, 3, 4));
	const btDbvtVolume inside = btDbvtVolume::FromMM(btVector3(btScalar(0.25), 1, 1), btVector3(btScalar(0.5), 1, 2));
	const btDbvtVolume corner = btDbvtVolume::FromMM(btVector3(1, 2, 3), btVector3(2, 3, 4));
	for (const btDbvtVolume* b : {&overlapping, &inside, &corner})
	{
		EXPECT_TRUE(Intersect(a, *b));
		EXPECT_TRUE(Intersect(*b, a));
	}
	// Apart along any single axis (on either side), while overlapping on the other two: no intersection.
	for (int axis = 0; axis < 3; ++axis)
		for (int side = 0; side < 2; ++side)
		{
			btVector3 shift(0, 0, 0);
			shift[axis] = side ? btScalar(3.01) : btScalar(-3.01);
			const btDbvtVolume apart = btDbvtVolume::FromMM(a.Mins() + shift, a.Maxs() + shift);
			EXPECT_FALSE(Intersect(a, apart)) << "axis " << axis << " side " << side;
			EXPECT_FALSE(Intersect(apart, a)) << "axis " << axis << " side " << side;
		}
	// A NaN in any coordinate of either box: no intersection.
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	for (int axis = 0; axis < 3; ++axis)
	{
		btVector3 low = a.Mins(), high = a.Maxs();
		low[axis] = nan;
		EXPECT_FALSE(Intersect(a, btDbvtVolume::FromMM(low, a.Maxs()))) << "axis " << axis;
		high[axis] = nan;
		EXPECT_FALSE(Intersect(btDbvtVolume::FromMM(a.Mins(), high), a)) << "axis " << axis;
	}
}

TEST(Dbvt, BadInputIsRejected)
{
	btDbvt tree;
	btDbvtNode* good = tree.insert(btDbvtVolume::FromCR(btVector3(0, 0, 0), 1), 0);
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btDbvtVolume nanBox = btDbvtVolume::FromMM(btVector3(nan, 0, 0), btVector3(1, 1, 1));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(tree.insert(nanBox, 0), "assertion failed");
	EXPECT_DEATH(tree.remove(0), "assertion failed");
	EXPECT_DEATH(
	    {
		    LeafCollector c;
		    btDbvt::rayTest(tree.m_root, btVector3(nan, 0, 0), btVector3(1, 0, 0), c);
	    },
	    "assertion failed");
	(void)good;
#else
	// A NaN box is stored as an empty box: never reported, and the other leaves are still found.
	btDbvtNode* bad = tree.insert(nanBox, 0);
	EXPECT_EQ(tree.m_leaves, 2);
	LeafCollector hits;
	tree.collideTV(tree.m_root, btDbvtVolume::FromCR(btVector3(0, 0, 0), 100), hits);
	EXPECT_EQ(hits.ids.size(), 1u);
	EXPECT_TRUE(btIsFinite(tree.m_root->volume.Mins().x()));
	tree.remove(0);  // no-op
	EXPECT_EQ(tree.m_leaves, 2);
	LeafCollector ray;
	btDbvt::rayTest(tree.m_root, btVector3(nan, 0, 0), btVector3(1, 0, 0), ray);
	EXPECT_TRUE(ray.ids.empty());
	tree.remove(bad);
	tree.remove(good);
	EXPECT_TRUE(tree.empty());
#endif
	// Queries on an empty tree find nothing.
	btDbvt empty;
	LeafCollector none;
	empty.collideTV(empty.m_root, btDbvtVolume::FromCR(btVector3(0, 0, 0), 1), none);
	btDbvt::rayTest(empty.m_root, btVector3(0, 0, 0), btVector3(1, 1, 1), none);
	PairCollector pairs;
	empty.collideTT(empty.m_root, empty.m_root, pairs);
	EXPECT_TRUE(none.ids.empty());
	EXPECT_EQ(pairs.calls, 0);
	empty.optimizeTopDown();
	empty.optimizeBottomUp();
	empty.optimizeIncremental(5);
	EXPECT_TRUE(empty.empty());
}

TEST(Dbvt, SortedListHelpersFindPositionAndReuseSlots)
{
	btAlignedObjectArray<btDbvt::sStkNPS> stock;
	btAlignedObjectArray<int> freeSlots;
	const btScalar values[4] = {9, 7, 7, 2};  // decreasing, as nearest expects
	int order[4];
	for (int i = 0; i < 4; ++i) order[i] = btDbvt::allocate(freeSlots, stock, btDbvt::sStkNPS(0, 0u, values[i]));
	EXPECT_EQ(stock.size(), 4);
	// The first position whose value is below v.
	EXPECT_EQ(btDbvt::nearest(order, &stock[0], 10, 0, 4), 0);
	EXPECT_EQ(btDbvt::nearest(order, &stock[0], 7, 0, 4), 3);
	EXPECT_EQ(btDbvt::nearest(order, &stock[0], 5, 0, 4), 3);
	EXPECT_EQ(btDbvt::nearest(order, &stock[0], 1, 0, 4), 4);
	// A freed slot is used again before the stock grows.
	freeSlots.push_back(1);
	EXPECT_EQ(btDbvt::allocate(freeSlots, stock, btDbvt::sStkNPS(0, 0u, 3)), 1);
	EXPECT_EQ(stock[1].value, btScalar(3));
	EXPECT_EQ(stock.size(), 4);
	EXPECT_EQ(freeSlots.size(), 0);
}
