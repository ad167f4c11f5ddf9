// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBody::refine: new nodes on an implicit function's zero set, the faces split to match, mass kept,
// and with cut the body split in two along the set; plus its bad input (docs/bad-input.md).

#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "BulletDynamics/Dynamics/DynamicsWorldTestUtil.h"  // WarningCounter
#include "SoftBodyTestUtil.h"

using caliber_test::SoftTestWorld;
using caliber_test::WarningCounter;

namespace
{
// The signed distance to a circle (a cylinder about y) of radius r centred at c: positive outside.
struct Circle : btSoftBody::ImplicitFn
{
	btVector3 c;
	btScalar r;
	Circle(const btVector3& centre, btScalar radius) : c(centre), r(radius) {}
	btScalar Eval(const btVector3& x) override { return btVector3(x.x() - c.x(), 0, x.z() - c.z()).length() - r; }
};

// The signed distance to the plane x = at: positive on the +x side.
struct PlaneX : btSoftBody::ImplicitFn
{
	btScalar at;
	explicit PlaneX(btScalar x) : at(x) {}
	btScalar Eval(const btVector3& x) override { return x.x() - at; }
};

struct NotFinite : btSoftBody::ImplicitFn
{
	btScalar Eval(const btVector3&) override { return std::numeric_limits<btScalar>::quiet_NaN(); }
};

// Rounding bound of a body's total mass after refine: every node's mass is inverted twice and scaled,
// and the total sums them (a few epsilons per node).
btScalar massTolerance(const btSoftBody& s, btScalar mass) { return 4 * btScalar(s.m_nodes.size()) * SIMD_EPSILON * mass; }

// A 2 x 2 m cloth in the y = 1 plane, n x n nodes, with the given fixed corners.
btSoftBody* cloth(btSoftBodyWorldInfo& info, int n, int fixeds)
{
	return btSoftBodyHelpers::CreatePatch(info, btVector3(-1, 1, -1), btVector3(1, 1, -1), btVector3(-1, 1, 1),
	                                      btVector3(1, 1, 1), n, n, fixeds, true);
}

// The pieces of a body: connected components of its nodes through links (each node's component label).
std::vector<int> components(const btSoftBody& s, int& count)
{
	std::vector<int> parent(size_t(s.m_nodes.size()));
	std::iota(parent.begin(), parent.end(), 0);
	auto find = [&parent](int i)
	{
		while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
		return i;
	};
	const btSoftBody::Node* base = &s.m_nodes[0];
	for (int i = 0; i < s.m_links.size(); ++i)
		parent[size_t(find(int(s.m_links[i].m_n[0] - base)))] = find(int(s.m_links[i].m_n[1] - base));
	std::set<int> roots;
	std::vector<int> label(parent.size());
	for (size_t i = 0; i < parent.size(); ++i) roots.insert(label[i] = find(int(i)));
	count = int(roots.size());
	return label;
}

btScalar faceArea(const btSoftBody& s)
{
	btScalar a = 0;
	for (int i = 0; i < s.m_faces.size(); ++i)
	{
		const btSoftBody::Face& f = s.m_faces[i];
		a += (f.m_n[1]->m_x - f.m_n[0]->m_x).cross(f.m_n[2]->m_x - f.m_n[0]->m_x).length() / 2;
	}
	return a;
}

// The face edges whose ends lie on different sides of ifn (where refine must put a node).
int crossingFaceEdges(const btSoftBody& s, btSoftBody::ImplicitFn& ifn)
{
	std::set<std::pair<const void*, const void*>> edges;
	for (int i = 0; i < s.m_faces.size(); ++i)
		for (int k = 0; k < 3; ++k)
		{
			const btSoftBody::Node* a = s.m_faces[i].m_n[k];
			const btSoftBody::Node* b = s.m_faces[i].m_n[(k + 1) % 3];
			if ((ifn.Eval(a->m_x) > 0) != (ifn.Eval(b->m_x) > 0)) edges.insert(std::make_pair(btMin(a, b), btMax(a, b)));
		}
	return int(edges.size());
}
}  // namespace

TEST(SoftBodyRefine, WithoutCutNewNodesLieOnTheZeroSet)
{
	// A circle of radius 0.6 through a 2 m cloth of 11 x 11 nodes (links 0.2 m). Refining puts one node on
	// each face edge the circle crosses, within the bisection's reach of the circle: the accuracy is a
	// fraction of the edge (at most 0.2 sqrt 2 m), the distance function changes by at most the distance
	// moved, so |f| <= 1e-4 x 0.283 m / 2 = 1.4e-5 m, plus rounding (float: 1e-6 of 1 m).
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> c(cloth(info, 11, 0));
	c->setTotalMass(2);
	Circle circle(btVector3(btScalar(0.05), 0, btScalar(-0.03)), btScalar(0.6));
	const int nodes = c->m_nodes.size(), expected = crossingFaceEdges(*c, circle);
	const btScalar area = faceArea(*c);
	ASSERT_GT(expected, 20);
	c->refine(&circle, btScalar(1e-4), false);
	ASSERT_EQ(c->m_nodes.size(), nodes + expected);
	for (int i = nodes; i < c->m_nodes.size(); ++i) EXPECT_NEAR(circle.Eval(c->m_nodes[i].m_x), 0, 2e-5) << i;
	// Splitting a flat face into three keeps its area; the mass is kept; the cloth stays one piece.
	EXPECT_NEAR(faceArea(*c), area, 1e-5 * area);
	EXPECT_NEAR(c->getTotalMass(), 2, massTolerance(*c, 2));
	int pieces = 0;
	components(*c, pieces);
	EXPECT_EQ(pieces, 1);
	// Every face edge lies on one side now: no face edge crosses the circle by more than the new nodes'
	// distance to it.
	for (int i = 0; i < c->m_faces.size(); ++i)
	{
		btScalar lo = BT_LARGE_FLOAT, hi = -BT_LARGE_FLOAT;
		for (int k = 0; k < 3; ++k)
		{
			lo = btMin(lo, circle.Eval(c->m_faces[i].m_n[k]->m_x));
			hi = btMax(hi, circle.Eval(c->m_faces[i].m_n[k]->m_x));
		}
		EXPECT_TRUE(lo > -2e-5 || hi < 2e-5) << "face " << i << " spans " << lo << " .. " << hi;
	}
}

TEST(SoftBodyRefine, CutSplitsAClothIntoTwoPiecesKeepingTheMass)
{
	// A cloth fixed at one corner (x = -1), cut along x = 0.13: two pieces; mass kept. In the world, the piece
	// with no fixed node falls freely: after 30 steps of h, each cut into 4 substeps (one per sweep), its centre
	// fell g t (t + h / 4) / 2 (t = 0.5 s, the solver's integration), while the fixed piece hangs from its corner.
	SoftTestWorld w;
	btSoftBody* c = w.addSoft(cloth(w.info(), 11, 1));
	c->setTotalMass(2);
	c->m_cfg.piterations = 4;
	PlaneX plane(btScalar(0.13));
	const int nodes = c->m_nodes.size(), crossing = crossingFaceEdges(*c, plane);
	c->refine(&plane, btScalar(1e-4), true);
	EXPECT_EQ(c->m_nodes.size(), nodes + 2 * crossing);  // each node on the cut doubled
	EXPECT_NEAR(c->getTotalMass(), 2, massTolerance(*c, 2));
	int pieces = 0;
	const std::vector<int> label = components(*c, pieces);
	ASSERT_EQ(pieces, 2);
	// Each piece lies on its own side of the plane (within the bisection's accuracy).
	std::map<int, std::pair<btScalar, btScalar>> range;
	for (int i = 0; i < c->m_nodes.size(); ++i)
	{
		auto it = range.emplace(label[size_t(i)], std::make_pair(btScalar(BT_LARGE_FLOAT), btScalar(-BT_LARGE_FLOAT))).first;
		it->second.first = btMin(it->second.first, plane.Eval(c->m_nodes[i].m_x));
		it->second.second = btMax(it->second.second, plane.Eval(c->m_nodes[i].m_x));
	}
	for (const auto& r : range) EXPECT_TRUE(r.second.first > -3e-5 || r.second.second < 3e-5);
	// The free piece's centre of mass, before and after 30 steps.
	const int fixedPiece = label[0];
	auto freeCentre = [&]()
	{
		btVector3 com(0, 0, 0);
		btScalar m = 0;
		for (int i = 0; i < c->m_nodes.size(); ++i)
			if (label[size_t(i)] != fixedPiece)
			{
				com += c->m_nodes[i].m_x / c->m_nodes[i].m_im;
				m += 1 / c->m_nodes[i].m_im;
			}
		return com / m;
	};
	const btScalar y0 = freeCentre().y();
	w.step(30);
	EXPECT_NEAR(freeCentre().y(), y0 - btScalar(10 * 0.5 * (0.5 + 1.0 / 240) / 2), 1e-3);
	EXPECT_GT(c->m_nodes[0].m_x.y(), btScalar(0.99));  // the fixed corner holds its piece
}

TEST(SoftBodyRefine, CutSplitsARopeAtTheCrossing)
{
	// A rope (no faces) along x from 0 to 3 with 4 nodes, cut at x = 1.5: the middle link is split at the
	// plane, doubled, and the rope is two pieces; each half keeps its half of the rest length.
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> rope(
	    btSoftBodyHelpers::CreateRope(info, btVector3(0, 0, 0), btVector3(3, 0, 0), 2, 0));
	rope->setTotalMass(3);
	PlaneX plane(btScalar(1.5));
	rope->refine(&plane, btScalar(1e-5), true);
	ASSERT_EQ(rope->m_nodes.size(), 6);
	ASSERT_EQ(rope->m_links.size(), 4);
	int pieces = 0;
	components(*rope, pieces);
	EXPECT_EQ(pieces, 2);
	btScalar rest = 0;
	for (int i = 0; i < rope->m_links.size(); ++i) rest += rope->m_links[i].m_rl;
	EXPECT_NEAR(rest, 3, 1e-5);
	EXPECT_NEAR(rope->m_nodes[4].m_x.x(), 1.5, 1e-4);
	EXPECT_NEAR(rope->getTotalMass(), 3, massTolerance(*rope, 3));
}

TEST(SoftBodyRefine, ASetThatMissesTheBodyChangesNothing)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> c(cloth(info, 5, 0));
	PlaneX plane(5);
	const int nodes = c->m_nodes.size(), links = c->m_links.size(), faces = c->m_faces.size();
	c->refine(&plane, btScalar(1e-4), true);
	EXPECT_EQ(c->m_nodes.size(), nodes);
	EXPECT_EQ(c->m_links.size(), links);
	EXPECT_EQ(c->m_faces.size(), faces);
}

TEST(SoftBodyBadInput, RefineRejectsNoFunctionBadAccuracyAndBodiesItCannotSplit)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> c(cloth(info, 5, 0));
	std::unique_ptr<btSoftBody> clustered(cloth(info, 5, 0));
	clustered->generateClusters(2);
	PlaneX plane(btScalar(0.1));
	NotFinite nan;
	const int nodes = c->m_nodes.size();
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(c->refine(0, btScalar(1e-4), false), "null implicit function");
	EXPECT_DEATH(c->refine(&plane, 0, false), "accuracy");
	EXPECT_DEATH(c->refine(&nan, btScalar(1e-4), false), "not finite");
	EXPECT_DEATH(clustered->refine(&plane, btScalar(1e-4), false), "tetras or clusters");
	EXPECT_EQ(c->m_nodes.size(), nodes);
#else
	WarningCounter warnings;
	c->refine(0, btScalar(1e-4), false);
	c->refine(&nan, btScalar(1e-4), false);
	clustered->refine(&plane, btScalar(1e-4), false);
	EXPECT_EQ(warnings.count(), 3);
	EXPECT_EQ(c->m_nodes.size(), nodes);
	EXPECT_EQ(clustered->m_nodes.size(), nodes);
	// A nonsense accuracy is replaced by 1e-4 (with a warning): the cut still lands on the plane.
	c->refine(&plane, std::numeric_limits<btScalar>::quiet_NaN(), false);
	EXPECT_EQ(warnings.count(), 4);
	ASSERT_GT(c->m_nodes.size(), nodes);
	for (int i = nodes; i < c->m_nodes.size(); ++i) EXPECT_NEAR(plane.Eval(c->m_nodes[i].m_x), 0, 1e-4);
#endif
}
