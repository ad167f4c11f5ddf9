// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The groups of soft bodies whose position solves may run at once (btSoftBodySolveGroups.h): bodies whose
// solves write the same thing share a group, bodies that only read the same thing do not. The scene test
// with threads is SoftBodyThreads.SolveGroupsGiveTheBitsOfOneThreadAtAnyThreadCountAndSplit.

#include <gtest/gtest.h>

#include <vector>

#include "BulletSoftBody/btSoftBodySolveGroups.h"
#include "SoftBodyTestUtil.h"

using caliber_test::SoftTestWorld;

namespace
{
btSoftBody* smallPatch(SoftTestWorld& w, btScalar x, bool add = true)
{
	return w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(x, 1, 0), btVector3(x + 1, 1, 0),
	                                                btVector3(x, 1, 1), btVector3(x + 1, 1, 1), 3, 3, 0, true),
	                 add);
}

// A soft-soft contact of body's first node with the other body's face k (as the VF_SS search records it).
void touchFace(btSoftBody& body, btSoftBody& other, int k)
{
	btSoftBody::SContact c;
	c.m_node = &body.m_nodes[0];
	c.m_face = &other.m_faces[k];
	c.m_weights.setValue(1, 0, 0);
	c.m_normal.setValue(0, 1, 0);
	c.m_margin = btScalar(0.01);
	c.m_friction = 0;
	c.m_cfm[0] = 1;
	c.m_cfm[1] = 0;
	body.m_scontacts.push_back(c);
}

// A node contact of body's first node with object (as the soft-rigid search records it).
void touchObject(btSoftBody& body, btCollisionObject* object)
{
	btSoftBody::RContact c;
	c.m_node = &body.m_nodes[0];
	c.m_cti.m_colObj = object;
	c.m_cti.m_normal.setValue(0, 1, 0);
	c.m_cti.m_offset = 0;
	body.m_rcontacts.push_back(c);
}

std::vector<std::vector<int>> groupsOf(const caliber::SoftSolveGroups& g)
{
	std::vector<std::vector<int>> out;
	for (int k = 0; k < g.groupCount(); ++k)
		out.push_back(std::vector<int>(&g.members[0] + g.starts[k], &g.members[0] + g.starts[k + 1]));
	return out;
}
}  // namespace

TEST(SoftBodySolveGroups, BodiesWritingTheSameNodesOrRigidBodyShareAGroupAndReadersDoNot)
{
	SoftTestWorld w;
	btRigidBody* ground = w.addGround();
	btRigidBody* kinematic = w.addRigid(0, btVector3(0, 3, 0), w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)));
	kinematic->setCollisionFlags(kinematic->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
	btRigidBody* box = w.addRigid(1, btVector3(0, 5, 0), w.shape<btBoxShape>(btVector3(0.2, 0.2, 0.2)));
	std::vector<btSoftBody*> bodies;
	for (int i = 0; i < 7; ++i) bodies.push_back(smallPatch(w, btScalar(2 * i)));
	btSoftBody* outsider = smallPatch(w, 20, false);  // not in the solver's set
	// Every body touches the static ground and the kinematic box: read only, no group is joined by them.
	for (btSoftBody* b : bodies)
	{
		touchObject(*b, ground);
		touchObject(*b, kinematic);
	}
	// 0 and 3 press on the faces of 2, which sleeps (not solved): they both move its nodes.
	touchFace(*bodies[0], *bodies[2], 0);
	touchFace(*bodies[3], *bodies[2], bodies[2]->m_faces.size() - 1);
	// 1 and 4 press on the faces of a body outside the set: one stand-in joins them.
	touchFace(*bodies[1], *outsider, 1);
	touchFace(*bodies[4], *outsider, 2);
	// 5 and 6 move the same dynamic box: 6 through a contact, 5 through an anchor.
	touchObject(*bodies[6], box);
	bodies[5]->appendAnchor(bodies[5]->m_nodes.size() - 1, box);
	const std::vector<char> solve = {1, 1, 0, 1, 1, 1, 1};
	caliber::SoftSolveGroups g;
	caliber::findSoftSolveGroups(&bodies[0], solve.data(), 7, g);
	const std::vector<std::vector<int>> expected = {{0, 3}, {1, 4}, {5, 6}};
	EXPECT_EQ(groupsOf(g), expected);
	// 3 alone touching 2: 0 and 3 apart again (the groups follow this step's contacts).
	bodies[0]->m_scontacts.resize(0);
	caliber::findSoftSolveGroups(&bodies[0], solve.data(), 7, g);
	const std::vector<std::vector<int>> apart = {{0}, {1, 4}, {3}, {5, 6}};
	EXPECT_EQ(groupsOf(g), apart);
}
