// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The demos' drawing of soft bodies (Demos/Common/SoftBodyScene, through addWorld): what a cloth and a
// rope become in a Scene, where the camera's framing goes, and what bad nodes do.

#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "BulletSoftBody/btSoftBodyHelpers.h"
#include "BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h"
#include "BulletSoftBody/btSoftRigidDynamicsWorld.h"
#include "SoftBodyScene.h"
#include "WorldScene.h"
#include "btBulletDynamicsCommon.h"

using namespace caliber::demo;

namespace
{
struct SoftWorld
{
	btSoftBodyRigidBodyCollisionConfiguration config;
	btCollisionDispatcher dispatcher{&config};
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSoftRigidDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
	btBoxShape groundShape{btVector3(50, 1, 50)};
	std::unique_ptr<btRigidBody> ground;
	std::unique_ptr<btSoftBody> soft;

	SoftWorld()
	{
		btTransform at;
		at.setIdentity();
		at.setOrigin(btVector3(0, -1, 0));
		ground.reset(new btRigidBody(0, 0, &groundShape));
		ground->setWorldTransform(at);
		world.addRigidBody(ground.get());
	}
	void add(btSoftBody* body)
	{
		soft.reset(body);
		world.addSoftBody(body);
	}
	~SoftWorld()
	{
		if (soft) world.removeSoftBody(soft.get());
		world.removeRigidBody(ground.get());
	}
};

bool insideBox(const btVector3& p, const btVector3& lo, const btVector3& hi)
{
	for (int a = 0; a < 3; ++a)
		if (p[a] < lo[a] - btScalar(1e-6) || p[a] > hi[a] + btScalar(1e-6)) return false;
	return true;
}
}  // namespace

// A resx x resy patch has 2 (resx - 1)(resy - 1) faces; each becomes one triangle on its nodes, and the
// camera frames the cloth's nodes, not the 100 m ground (a soft body keeps the static flag every
// btCollisionObject starts with, yet it moves).
TEST(DemoSoftBodyScene, PatchFacesBecomeTrianglesAndTheClothIsFramed)
{
	SoftWorld w;
	const btScalar y = 3;
	w.add(btSoftBodyHelpers::CreatePatch(w.world.getWorldInfo(), btVector3(-1, y, -1), btVector3(1, y, -1),
	                                     btVector3(-1, y, 1), btVector3(1, y, 1), 5, 4, 0, true));
	Scene scene;
	WorldStyle style;
	style.debugMode = 0;
	EXPECT_EQ(addWorld(scene, w.world, style), 0);  // nothing undrawable
	// The ground is a box: 12 triangles; the cloth adds its 2 * 4 * 3 faces.
	ASSERT_EQ(int(scene.triangles().size()), 12 + 2 * 4 * 3);
	EXPECT_TRUE(scene.lines().empty());  // a body with faces draws no links
	int onCloth = 0;
	for (const SceneTriangle& t : scene.triangles())
		if (t.corner[0].y() == y && t.corner[1].y() == y && t.corner[2].y() == y) ++onCloth;
	EXPECT_EQ(onCloth, 24);
	ASSERT_TRUE(scene.hasFocus());
	EXPECT_NEAR(double(scene.focusMin().x()), -1, 1e-6);
	EXPECT_NEAR(double(scene.focusMax().z()), 1, 1e-6);
	EXPECT_NEAR(double(scene.focusMin().y()), double(y), 1e-6);
}

// A rope has no faces: its res + 1 segments are drawn as lines (bending links, which would only double
// the drawing, are left out), and its nodes are framed.
TEST(DemoSoftBodyScene, RopeLinksBecomeLinesWithoutBendingLinks)
{
	SoftWorld w;
	btSoftBody* rope =
	    btSoftBodyHelpers::CreateRope(w.world.getWorldInfo(), btVector3(0, 4, 0), btVector3(3, 4, 0), 8, 1);
	ASSERT_GT(rope->generateBendingConstraints(2), 0);
	w.add(rope);
	Scene scene;
	const int added = addSoftBody(scene, *rope, btVector3(1, 0, 0));
	EXPECT_EQ(added, 9);
	EXPECT_EQ(int(scene.lines().size()), 9);
	EXPECT_TRUE(scene.triangles().empty());
	btVector3 lo, hi;
	ASSERT_TRUE(softBodyNodeBounds(*rope, lo, hi));
	for (const SceneLine& line : scene.lines())
	{
		EXPECT_TRUE(insideBox(line.from, lo, hi));
		EXPECT_TRUE(insideBox(line.to, lo, hi));
	}
	EXPECT_NEAR(double(hi.x() - lo.x()), 3, 1e-5);
}

// Bad input: a NaN node is dropped with its faces (counted by the Scene), the framing ignores it, and a
// body without nodes adds nothing and has no bounds.
TEST(DemoSoftBodyScene, NonFiniteNodesAreSkippedAndEmptyBodiesHaveNoBounds)
{
	SoftWorld w;
	btSoftBody* patch = btSoftBodyHelpers::CreatePatch(w.world.getWorldInfo(), btVector3(0, 1, 0), btVector3(1, 1, 0),
	                                                   btVector3(0, 1, 1), btVector3(1, 1, 1), 2, 2, 0, false);
	patch->m_nodes[0].m_x.setX(std::numeric_limits<btScalar>::quiet_NaN());
	Scene scene;
	addSoftBody(scene, *patch, btVector3(0, 1, 0));
	EXPECT_EQ(int(scene.triangles().size()) + scene.skippedNonFinite(), 2);
	EXPECT_GE(scene.skippedNonFinite(), 1);
	btVector3 lo, hi;
	ASSERT_TRUE(softBodyNodeBounds(*patch, lo, hi));
	EXPECT_TRUE(isFinite(lo) && isFinite(hi));
	EXPECT_EQ(lo.x(), btScalar(0));
	delete patch;

	btSoftBody empty(&w.world.getWorldInfo());
	Scene none;
	EXPECT_EQ(addSoftBody(none, empty, btVector3(0, 0, 1)), 0);
	EXPECT_FALSE(softBodyNodeBounds(empty, lo, hi));
}
