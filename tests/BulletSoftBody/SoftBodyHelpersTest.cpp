// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btSoftBodyHelpers' makers build the topology they document, and the draw functions draw it.

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "SoftBodyTestUtil.h"

namespace
{
// Counts what the drawer receives.
struct CountingDrawer : btIDebugDraw
{
	int lines = 0, triangles = 0, texts = 0;
	int mode = 0;
	void drawLine(const btVector3&, const btVector3&, const btVector3&) override { ++lines; }
	void drawTriangle(const btVector3&, const btVector3&, const btVector3&, const btVector3&, btScalar) override
	{
		++triangles;
	}
	void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
	void reportErrorWarning(const char*) override {}
	void draw3dText(const btVector3&, const char*) override { ++texts; }
	void setDebugMode(int m) override { mode = m; }
	int getDebugMode() const override { return mode; }
};

// Edges of a closed triangle surface: each one is shared by exactly two faces, wound oppositely.
bool isClosedAndConsistentlyWound(const btSoftBody& b)
{
	std::vector<std::pair<int, int>> edges;
	for (int i = 0; i < b.m_faces.size(); ++i)
		for (int k = 0; k < 3; ++k)
			edges.emplace_back(int(b.m_faces[i].m_n[k] - &b.m_nodes[0]),
			                   int(b.m_faces[i].m_n[(k + 1) % 3] - &b.m_nodes[0]));
	std::sort(edges.begin(), edges.end());
	for (const auto& e : edges)
	{
		if (std::count(edges.begin(), edges.end(), e) != 1) return false;  // same direction twice
		if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(e.second, e.first))) return false;
	}
	return true;
}
}  // namespace

TEST(SoftBodyHelpers, RopeHasResPlusTwoNodesAndFixedEnds)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> rope(
	    btSoftBodyHelpers::CreateRope(info, btVector3(0, 0, 0), btVector3(4, 0, 0), 7, 1 + 2));
	ASSERT_EQ(rope->m_nodes.size(), 9);
	EXPECT_EQ(rope->m_links.size(), 8);
	EXPECT_EQ(rope->m_nodes[0].m_im, 0);
	EXPECT_EQ(rope->m_nodes[8].m_im, 0);
	EXPECT_EQ(rope->m_nodes[4].m_x, btVector3(2, 0, 0));
	EXPECT_FLOAT_EQ(rope->m_links[3].m_rl, 0.5f);
}

TEST(SoftBodyHelpers, PatchHasItsGridLinksDiagonalsFacesAndFixedCorners)
{
	btSoftBodyWorldInfo info;
	const int rx = 5, ry = 4;
	std::unique_ptr<btSoftBody> patch(btSoftBodyHelpers::CreatePatch(
	    info, btVector3(0, 0, 0), btVector3(4, 0, 0), btVector3(0, 0, 3), btVector3(4, 0, 3), rx, ry, 1 + 8, true));
	EXPECT_EQ(patch->m_nodes.size(), rx * ry);
	EXPECT_EQ(patch->m_links.size(), (rx - 1) * ry + rx * (ry - 1) + (rx - 1) * (ry - 1));
	EXPECT_EQ(patch->m_faces.size(), 2 * (rx - 1) * (ry - 1));
	EXPECT_EQ(patch->m_nodes[0].m_im, 0);
	EXPECT_EQ(patch->m_nodes[rx * ry - 1].m_im, 0);
	EXPECT_GT(patch->m_nodes[rx - 1].m_im, 0);
	// Faces face the same way: corner10 - corner00 across corner01 - corner00 is -y.
	patch->updateNormals();
	for (int i = 0; i < patch->m_faces.size(); ++i) EXPECT_NEAR(patch->m_faces[i].m_normal.y(), -1, 1e-6);
	std::vector<float> uv(12 * (rx - 1) * (ry - 1));
	std::unique_ptr<btSoftBody> textured(btSoftBodyHelpers::CreatePatchUV(info, btVector3(0, 0, 0), btVector3(4, 0, 0),
	                                                                      btVector3(0, 0, 3), btVector3(4, 0, 3), rx,
	                                                                      ry, 0, false, &uv[0]));
	EXPECT_EQ(textured->m_faces.size(), 2 * (rx - 1) * (ry - 1));
	for (float t : uv)
	{
		EXPECT_GE(t, 0.f);
		EXPECT_LE(t, 1.f);
	}
}

TEST(SoftBodyHelpers, EllipsoidIsAClosedHullWithTheEllipsoidsVolume)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> ball(
	    btSoftBodyHelpers::CreateEllipsoid(info, btVector3(1, 2, 3), btVector3(1, 2, 1), 400));
	EXPECT_EQ(ball->m_nodes.size(), 400);  // every point on an ellipsoid is a hull vertex
	EXPECT_TRUE(isClosedAndConsistentlyWound(*ball));
	// Euler: V - E + F = 2 for a closed sphere-like surface.
	EXPECT_EQ(ball->m_nodes.size() - ball->m_links.size() + ball->m_faces.size(), 2);
	// The inscribed polyhedron of 400 points holds about 1% less than 4/3 pi a b c.
	const btScalar exact = btScalar(4) / 3 * SIMD_PI * 2;
	EXPECT_GT(ball->getVolume(), 0.97 * exact);
	EXPECT_LT(ball->getVolume(), exact);
	EXPECT_NEAR(ball->evaluateCom().distance(btVector3(1, 2, 3)), 0, 0.02);
}

TEST(SoftBodyHelpers, TriMeshMakesOneLinkPerEdge)
{
	btSoftBodyWorldInfo info;
	const btScalar vertices[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
	const int triangles[] = {0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2};
	std::unique_ptr<btSoftBody> tetra(btSoftBodyHelpers::CreateFromTriMesh(info, vertices, triangles, 4));
	EXPECT_EQ(tetra->m_nodes.size(), 4);
	EXPECT_EQ(tetra->m_links.size(), 6);
	EXPECT_EQ(tetra->m_faces.size(), 4);
	EXPECT_TRUE(isClosedAndConsistentlyWound(*tetra));
	EXPECT_NEAR(tetra->getVolume(), 1.0 / 6, 1e-6);
	const btVector3 hull[] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1),
	                          btVector3(btScalar(0.1), btScalar(0.1), btScalar(0.1))};
	std::unique_ptr<btSoftBody> fromHull(btSoftBodyHelpers::CreateFromConvexHull(info, hull, 5));
	EXPECT_EQ(fromHull->m_nodes.size(), 4);  // the inner point is not on the hull
	EXPECT_NEAR(fromHull->getVolume(), 1.0 / 6, 1e-6);
}

TEST(SoftBodyHelpers, BendingConstraintsLinkNodesTwoApart)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> rope(btSoftBodyHelpers::CreateRope(info, btVector3(0, 0, 0), btVector3(5, 0, 0), 4, 0));
	EXPECT_EQ(rope->generateBendingConstraints(2), 4);  // 0-2, 1-3, 2-4, 3-5
	EXPECT_TRUE(rope->checkLink(0, 2));
	EXPECT_FALSE(rope->checkLink(0, 3));
	// Depth 3 reaches the new 2-apart links too: 0-3, 1-4, 2-5 and, through them, 0-4, 1-5 (the graph now
	// includes the bending links).
	rope->generateBendingConstraints(3);
	EXPECT_TRUE(rope->checkLink(0, 3));
}

TEST(SoftBodyHelpers, DrawDrawsTheFeaturesItIsAskedFor)
{
	caliber_test::SoftTestWorld w;
	btSoftBody* cloth = w.addSoft(btSoftBodyHelpers::CreatePatch(
	    w.info(), btVector3(0, 1, 0), btVector3(1, 1, 0), btVector3(0, 1, 1), btVector3(1, 1, 1), 3, 3, 1, false));
	cloth->appendNote("corner", btVector3(0, 0, 0), &cloth->m_nodes[0]);
	CountingDrawer drawer;
	btSoftBodyHelpers::Draw(cloth, &drawer, fDrawFlags::Links | fDrawFlags::Faces | fDrawFlags::Notes);
	EXPECT_EQ(drawer.lines, cloth->m_links.size());
	EXPECT_EQ(drawer.triangles, cloth->m_faces.size());
	EXPECT_EQ(drawer.texts, 1);
	w.world().setDebugDrawer(&drawer);
	w.world().setDrawFlags(fDrawFlags::Faces);
	drawer.triangles = 0;
	w.world().debugDrawWorld();
	EXPECT_EQ(drawer.triangles, cloth->m_faces.size());
	w.world().setDebugDrawer(0);
}

TEST(SoftBodyHelpers, TetGenDataMakesNodesTetrasLinksAndFaces)
{
	// Two tetras sharing the face (1, 2, 3), numbered from 1 as TetGen often does, with comments.
	const char* node = "# a comment\n5 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1  # the second tip\n";
	const char* ele = "2 4 0\n1 1 2 3 4\n2 2 3 4 5\n";
	const char* face = "2 1\n1 1 2 3 0\n2 2 3 5 1\n";
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> body(btSoftBodyHelpers::CreateFromTetGenData(info, ele, face, node, true, true, false));
	EXPECT_EQ(body->m_nodes.size(), 5);
	EXPECT_EQ(body->m_tetras.size(), 2);
	EXPECT_EQ(body->m_links.size(), 9);  // 6 + 6 tetra edges, 3 shared
	EXPECT_EQ(body->m_faces.size(), 2);
	EXPECT_EQ(body->m_nodes[4].m_x, btVector3(1, 1, 1));
	EXPECT_NEAR(body->m_tetras[0].m_rv, 1.0 / 6, 1e-6);
	// Faces from tetras wind outward for TetGen's positive orientation: the lone tetra's volume is +1/6.
	std::unique_ptr<btSoftBody> one(btSoftBodyHelpers::CreateFromTetGenData(
	    info, "1 4 0\n0 0 1 2 3\n", 0, "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n", false, true, true));
	EXPECT_EQ(one->m_faces.size(), 4);
	EXPECT_NEAR(one->getVolume(), 1.0 / 6, 1e-6);
	one->setVolumeDensity(6);
	EXPECT_NEAR(one->getTotalMass(), 1, 1e-5);
}
