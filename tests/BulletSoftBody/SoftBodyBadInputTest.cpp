// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bad input to soft bodies (docs/bad-input.md, "Soft bodies"): an assert in builds with asserts, the
// documented result and a warning without them.

#include <gtest/gtest.h>

#include <limits>

#include "BulletDynamics/Dynamics/DynamicsWorldTestUtil.h"  // WarningCounter
#include "SoftBodyTestUtil.h"

using caliber_test::SoftTestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kNaN = std::numeric_limits<btScalar>::quiet_NaN();
const btScalar kInf = std::numeric_limits<btScalar>::infinity();

btSoftBody* twoNodeBody(btSoftBodyWorldInfo& info)
{
	const btVector3 x[2] = {btVector3(0, 1, 0), btVector3(1, 1, 0)};
	return new btSoftBody(&info, 2, x, 0);
}
}  // namespace

TEST(SoftBodyBadInput, NonFiniteNodePositionOrBadMassGivesAFixedNode)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> body(twoNodeBody(info));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(body->appendNode(btVector3(kNaN, 0, 0), 1), "non-finite position");
	EXPECT_DEATH(body->appendNode(btVector3(0, 0, 0), -1), "negative or non-finite mass");
#else
	WarningCounter warnings;
	body->appendNode(btVector3(kNaN, 0, 0), 1);
	body->appendNode(btVector3(2, 0, 0), kInf);
	ASSERT_EQ(body->m_nodes.size(), 4);
	EXPECT_EQ(body->m_nodes[2].m_x, btVector3(0, 0, 0));
	EXPECT_EQ(body->m_nodes[2].m_im, 0);
	EXPECT_EQ(body->m_nodes[3].m_im, 0);
	EXPECT_EQ(warnings.count(), 2);
#endif
}

TEST(SoftBodyBadInput, DegenerateFacesAndBadLinksAreNotAdded)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> body(twoNodeBody(info));
	body->appendNode(btVector3(0, 2, 0), 1);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(body->appendFace(0, 0, 1), "degenerate face");
	EXPECT_DEATH(body->appendFace(0, 1, 7), "degenerate face");
	EXPECT_DEATH(body->appendLink(1, 1), "same node");
	EXPECT_DEATH(body->appendLink(0, 9), "out of range");
	EXPECT_DEATH(body->appendTetra(0, 1, 2, 2), "degenerate tetra");
#else
	WarningCounter warnings;
	body->appendFace(0, 0, 1);
	body->appendFace(0, 1, 7);
	body->appendLink(1, 1);
	body->appendLink(0, 9);
	body->appendTetra(0, 1, 2, 2);
	EXPECT_EQ(body->m_faces.size(), 0);
	EXPECT_EQ(body->m_links.size(), 0);
	EXPECT_EQ(body->m_tetras.size(), 0);
	EXPECT_EQ(warnings.count(), 5);
#endif
	// A collinear face is legal (a cloth may fold flat); it adds nothing to normals and is never hit.
	body->appendNode(btVector3(2, 1, 0), 1);
	body->appendFace(0, 1, 3);
	body->updateNormals();
	EXPECT_EQ(body->m_nodes[0].m_n, btVector3(0, 0, 0));
	btSoftBody::sRayCast hit;
	EXPECT_FALSE(body->rayTest(btVector3(btScalar(0.5), 5, 0), btVector3(btScalar(0.5), -5, 0), hit));
}

TEST(SoftBodyBadInput, ZeroOrNonFiniteMassIsRejected)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> body(twoNodeBody(info));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(body->setTotalMass(0), "mass must be positive");
	EXPECT_DEATH(body->setTotalMass(kNaN), "mass must be positive");
	EXPECT_DEATH(body->setMass(5, 1), "out of range");
	EXPECT_DEATH(body->setVolumeMass(1), "must have tetras");
#else
	WarningCounter warnings;
	body->setTotalMass(0);
	body->setTotalMass(kNaN);
	body->setMass(5, 1);
	body->setVolumeMass(1);
	EXPECT_EQ(body->getTotalMass(), 2);  // unchanged: one kilogram per node
	EXPECT_EQ(warnings.count(), 4);
#endif
	// Every node fixed: there is nothing to give mass to (a warning, no assert: the call is legal).
	WarningCounter fixedWarnings;
	body->setMass(0, 0);
	body->setMass(1, 0);
	body->setTotalMass(3);
	EXPECT_EQ(body->getTotalMass(), 0);
	EXPECT_EQ(fixedWarnings.count(), 1);
}

TEST(SoftBodyBadInput, MakersGiveAnEmptyBodyForInputWithNoBody)
{
	SoftTestWorld w;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1),
	                                            btVector3(1, 0, 1), 1, 5, 0, true),
	             "resolution below 2");
	EXPECT_DEATH(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 0, 0), btVector3(1, 0, 0), -3, 0),
	             "negative resolution");
	EXPECT_DEATH(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, 0, 0), btVector3(1, 1, 1), 3),
	             "fewer than 4 points");
	EXPECT_DEATH(btSoftBodyHelpers::CreateFromTriMesh(w.info(), 0, 0, 0), "no triangles");
#else
	WarningCounter warnings;
	btSoftBody* bodies[4] = {btSoftBodyHelpers::CreatePatch(w.info(), btVector3(0, 0, 0), btVector3(1, 0, 0),
	                                                        btVector3(0, 0, 1), btVector3(1, 0, 1), 1, 5, 0, true),
	                         btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 0, 0), btVector3(1, 0, 0), -3, 0),
	                         btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, 0, 0), btVector3(1, 1, 1), 3),
	                         btSoftBodyHelpers::CreateFromTriMesh(w.info(), 0, 0, 0)};
	EXPECT_EQ(warnings.count(), 4);
	for (btSoftBody* b : bodies)
	{
		ASSERT_NE(b, nullptr);
		EXPECT_EQ(b->m_nodes.size(), 0);
		EXPECT_EQ(b->m_materials.size(), 1);  // programs may set m_materials[0] right away
		w.addSoft(b);
	}
	w.step(5);
#endif
	// A body without nodes is legal: it steps, collides with nothing and has no volume.
	WarningCounter stepWarnings;
	btSoftBody* empty = w.addSoft(new btSoftBody(&w.info()));
	w.addGround();
	w.step(5);
	EXPECT_EQ(empty->getVolume(), 0);
	EXPECT_EQ(stepWarnings.count(), 0);
}

TEST(SoftBodyBadInput, AnchorToABodyRemovedFromTheWorldIsDropped)
{
	SoftTestWorld w;
	btSoftBody* rope = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 5, 0), btVector3(0, 4, 0), 3, 1));
	btRigidBody* box = w.addRigid(1, btVector3(0, btScalar(3.9), 0), w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)));
	rope->appendAnchor(rope->m_nodes.size() - 1, box);
	w.step(5);
	w.world().removeRigidBody(box);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.step(1), "anchored rigid body was removed");
#else
	WarningCounter warnings;
	w.step(1);
	EXPECT_EQ(rope->m_anchors.size(), 0);
	EXPECT_EQ(rope->m_nodes[rope->m_nodes.size() - 1].m_battach, 0);
	EXPECT_EQ(warnings.count(), 1);
	w.step(5);
	EXPECT_EQ(warnings.count(), 1);
#endif
}

TEST(SoftBodyBadInput, BadAnchorsAreNotAdded)
{
	SoftTestWorld w;
	btSoftBody* rope = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 5, 0), btVector3(0, 4, 0), 3, 1));
	btRigidBody* box = w.addRigid(1, btVector3(0, 3, 0), w.shape<btBoxShape>(btVector3(0.1, 0.1, 0.1)));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(rope->appendAnchor(0, nullptr), "null body");
	EXPECT_DEATH(rope->appendAnchor(99, box), "out of range");
	EXPECT_DEATH(rope->appendAnchor(1, box, btVector3(kNaN, 0, 0)), "non-finite pivot");
#else
	WarningCounter warnings;
	rope->appendAnchor(0, nullptr);
	rope->appendAnchor(99, box);
	rope->appendAnchor(1, box, btVector3(kNaN, 0, 0));
	EXPECT_EQ(rope->m_anchors.size(), 0);
	EXPECT_EQ(warnings.count(), 3);
#endif
}

TEST(SoftBodyBadInput, SoftBodyAddedTwiceOrRemovedWithoutBeingAddedIsIgnored)
{
	SoftTestWorld w;
	btSoftBody* rope = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 5, 0), btVector3(0, 4, 0), 3, 1));
	btSoftBody* stranger =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 5, 0), btVector3(0, 4, 0), 3, 1), false);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(w.world().addSoftBody(rope), "added twice");
	EXPECT_DEATH(w.world().removeSoftBody(stranger), "not in this world");
#else
	WarningCounter warnings;
	w.world().addSoftBody(rope);
	w.world().removeSoftBody(stranger);
	EXPECT_EQ(w.world().getSoftBodyArray().size(), 1);
	EXPECT_EQ(warnings.count(), 2);
#endif
}

TEST(SoftBodyBadInput, NonFiniteForcesVelocitiesAndMovesAreIgnored)
{
	btSoftBodyWorldInfo info;
	std::unique_ptr<btSoftBody> body(twoNodeBody(info));
	btTransform bad;
	bad.setIdentity();
	bad.setOrigin(btVector3(kNaN, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(body->addForce(btVector3(kInf, 0, 0)), "non-finite force");
	EXPECT_DEATH(body->setVelocity(btVector3(kNaN, 0, 0)), "non-finite velocity");
	EXPECT_DEATH(body->addVelocity(btVector3(0, 0, 0), 7), "out of range");
	EXPECT_DEATH(body->transform(bad), "non-finite transform");
#else
	WarningCounter warnings;
	body->addForce(btVector3(kInf, 0, 0));
	body->setVelocity(btVector3(kNaN, 0, 0));
	body->addVelocity(btVector3(0, 0, 0), 7);
	body->transform(bad);
	EXPECT_EQ(body->m_nodes[0].m_f, btVector3(0, 0, 0));
	EXPECT_EQ(body->m_nodes[0].m_v, btVector3(0, 0, 0));
	EXPECT_EQ(body->m_nodes[1].m_x, btVector3(1, 1, 0));
	EXPECT_EQ(warnings.count(), 4);
#endif
}

TEST(SoftBodyBadInput, NodeStateMadeNonFiniteBehindTheApiIsRepaired)
{
	// No assert: a state written directly (or blown up by absurd settings) is put back, with a warning.
	SoftTestWorld w;
	btSoftBody* rope = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 5, 0), btVector3(1, 5, 0), 3, 1));
	WarningCounter warnings;
	rope->m_nodes[2].m_v.setValue(kNaN, 0, 0);
	w.step(1);
	for (int i = 0; i < rope->m_nodes.size(); ++i)
	{
		EXPECT_TRUE(caliber::isFinite(rope->m_nodes[i].m_x));
		EXPECT_TRUE(caliber::isFinite(rope->m_nodes[i].m_v));
	}
	EXPECT_GE(warnings.count(), 1);
}

TEST(SoftBodyBadInput, MalformedTetGenDataGivesAnEmptyBody)
{
	btSoftBodyWorldInfo info;
	const char* node = "4 3 0 0\n0 0 0 0\n1 1 0 0\n2 0 1 0\n3 0 0 1\n";
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btSoftBodyHelpers::CreateFromTetGenData(info, "1 4 0\n0 0 1 2 9\n", 0, node, false, true, false),
	             "malformed TetGen data");
	EXPECT_DEATH(btSoftBodyHelpers::CreateFromTetGenData(info, "1 4 0\n", 0, "4 2 0 0\n", false, true, false),
	             "malformed TetGen data");
#else
	WarningCounter warnings;
	std::unique_ptr<btSoftBody> badIndex(
	    btSoftBodyHelpers::CreateFromTetGenData(info, "1 4 0\n0 0 1 2 9\n", 0, node, false, true, false));
	std::unique_ptr<btSoftBody> badHeader(
	    btSoftBodyHelpers::CreateFromTetGenData(info, "1 4 0\n", 0, "4 2 0 0\n", false, true, false));
	std::unique_ptr<btSoftBody> noData(btSoftBodyHelpers::CreateFromTetGenData(info, 0, 0, 0, false, true, false));
	EXPECT_EQ(badIndex->m_nodes.size(), 0);
	EXPECT_EQ(badHeader->m_nodes.size(), 0);
	EXPECT_EQ(noData->m_nodes.size(), 0);
	EXPECT_EQ(warnings.count(), 3);
#endif
}
