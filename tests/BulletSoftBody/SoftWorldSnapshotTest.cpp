// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Snapshot and restore of soft-rigid worlds (Caliber/SoftWorldSnapshot.h): after a restore, stepping on
// repeats the steps that followed the save bit for bit, in the same world and in a fresh copy of it; a
// changed topology and other misuse are refused with a clear error and leave the world unchanged.
#include <gtest/gtest.h>

#include <string.h>

#include <functional>
#include <string>
#include <vector>

#include "BulletSoftBody/SoftBodyTestUtil.h"
#include "Caliber/SoftWorldSnapshot.h"

using namespace caliber_test;

namespace
{
// Every node's position and velocity and every rigid body's pose and velocities, as bytes.
void record(btSoftRigidDynamicsWorld& world, std::vector<unsigned char>& trace)
{
	auto put = [&](const void* p, size_t n)
	{
		const unsigned char* b = static_cast<const unsigned char*>(p);
		trace.insert(trace.end(), b, b + n);
	};
	for (int i = 0; i < world.getNumCollisionObjects(); ++i)
	{
		const btCollisionObject* o = world.getCollisionObjectArray()[i];
		put(&o->getWorldTransform(), sizeof(btTransform));
		if (const btRigidBody* r = btRigidBody::upcast(o))
		{
			put(&r->getLinearVelocity(), sizeof(btVector3));
			put(&r->getAngularVelocity(), sizeof(btVector3));
		}
		const int state = o->getActivationState();
		put(&state, sizeof(state));
	}
	for (int s = 0; s < world.getSoftBodyArray().size(); ++s)
	{
		const btSoftBody* b = world.getSoftBodyArray()[s];
		for (int i = 0; i < b->m_nodes.size(); ++i)
		{
			put(b->m_nodes[i].m_x.m_floats, 3 * sizeof(btScalar));
			put(b->m_nodes[i].m_v.m_floats, 3 * sizeof(btScalar));
		}
	}
}

std::vector<std::vector<unsigned char>> run(SoftTestWorld& w, int steps)
{
	std::vector<std::vector<unsigned char>> out;
	for (int i = 0; i < steps; ++i)
	{
		w.step(1);
		out.emplace_back();
		record(w.world(), out.back());
	}
	return out;
}

int firstDifference(const std::vector<std::vector<unsigned char>>& a, const std::vector<std::vector<unsigned char>>& b)
{
	for (size_t i = 0; i < a.size() && i < b.size(); ++i)
		if (a[i] != b[i]) return int(i);
	return a.size() == b.size() ? -1 : int(std::min(a.size(), b.size()));
}

typedef std::function<void(SoftTestWorld&)> Scene;

// A cloth pinned at two corners with a box dropped onto it and air drag: node contacts, corner-face
// contacts, tethers, aerodynamics.
void clothAndBox(SoftTestWorld& w)
{
	w.addGround();
	btSoftBody* cloth =
	    w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(-2, 3, -2), btVector3(2, 3, -2),
	                                             btVector3(-2, 3, 2), btVector3(2, 3, 2), 9, 9, 1 + 2, true));
	cloth->m_cfg.piterations = 4;
	cloth->m_cfg.kDG = 0.2;
	cloth->m_cfg.aeromodel = btSoftBody::eAeroModel::V_TwoSided;
	cloth->setTotalMass(2);
	w.addRigid(1, btVector3(0.3, 4.5, 0.2), w.shape<btBoxShape>(btVector3(0.4, 0.4, 0.4)));
}

// A pressurised ball of inextensible links (the gas as a volume constraint with the skin's rest volume)
// next to a volume-preserving one, falling onto the ground and onto each other (VF_SS).
void balls(SoftTestWorld& w)
{
	w.addGround();
	btSoftBody* a = w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, 2, 0), btVector3(1, 1, 1), 96));
	a->m_cfg.kPR = 2500;
	a->m_cfg.collisions |= btSoftBody::fCollision::VF_SS;
	a->setTotalMass(1, true);
	btSoftBody* b =
	    w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0.4, 5, 0.2), btVector3(0.8, 0.8, 0.8), 64));
	b->m_materials[0]->m_kLST = 0.4;
	b->m_cfg.kVC = 20;
	b->m_cfg.kMT = 0.05;
	b->setPose(true, true);
	b->setTotalMass(1, true);
}

// Clusters: a soft block hanging by a linear joint from a rigid box held by an anchor chain, with an
// angular joint to the world and cluster collisions with the ground (CL_RS), plus a rope anchored to the box.
void clustersAndJoints(SoftTestWorld& w)
{
	w.addGround();
	btRigidBody* box = w.addRigid(2, btVector3(0, 4, 0), w.shape<btBoxShape>(btVector3(0.3, 0.3, 0.3)));
	btSoftBody* ball =
	    w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, 2.5, 0), btVector3(0.7, 0.7, 0.7), 48));
	ball->m_cfg.collisions = btSoftBody::fCollision::CL_RS;
	ball->setTotalMass(1);
	ball->generateClusters(4);
	btSoftBody::LJoint::Specs ls;
	ls.position = btVector3(0, 3.3, 0);
	ls.erp = 0.5;
	ball->appendLinearJoint(ls, ball->m_clusters[0], btSoftBody::Body(box));
	btSoftBody::AJoint::Specs as;
	as.axis = btVector3(0, 1, 0);
	ball->appendAngularJoint(as, btSoftBody::Body());
	btSoftBody* rope =
	    w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 4, 0), btVector3(2, 4, 0), 12, 0));
	rope->setTotalMass(0.5);
	rope->appendAnchor(0, box);
	box->setLinearVelocity(btVector3(1, 0, 0.5));
}

// Moves every soft node of a fresh world before a restore (which overwrites positions): a late joiner whose
// bodies were built from another shape, so that caches built from the shape (the skin's rest volume, the
// tethers) differ unless the snapshot holds them.
void squash(SoftTestWorld& w)
{
	for (int s = 0; s < w.world().getSoftBodyArray().size(); ++s)
	{
		btSoftBody* b = w.world().getSoftBodyArray()[s];
		for (int i = 0; i < b->m_nodes.size(); ++i) b->m_nodes[i].m_x *= btVector3(1, btScalar(0.8), 1);
	}
}

// Saves after warm-up steps, records steps, restores into the same world, into a fresh one and into a fresh
// one whose soft bodies were squashed first, and checks that all repeat the record bit for bit.
void checkRollback(const Scene& build, int warmup, int steps)
{
	SoftTestWorld w;
	build(w);
	w.step(warmup);
	// A push the user added for the next step is part of the state (the nodes' accumulated forces).
	for (int s = 0; s < w.world().getSoftBodyArray().size(); ++s)
		w.world().getSoftBodyArray()[s]->addForce(btVector3(btScalar(0.3), 0, btScalar(-0.2)));
	btAlignedObjectArray<unsigned char> snapshot;
	caliber::SnapshotError error;
	ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), snapshot, &error)) << error.message;
	const std::vector<std::vector<unsigned char>> first = run(w, steps);
	ASSERT_TRUE(caliber::restoreSoftWorldState(w.world(), &snapshot[0], size_t(snapshot.size()), &error))
	    << error.message;
	EXPECT_TRUE(caliber::compareSoftWorldState(w.world(), &snapshot[0], size_t(snapshot.size())));
	const std::vector<std::vector<unsigned char>> again = run(w, steps);
	EXPECT_EQ(firstDifference(first, again), -1) << "same world: the steps after the restore differ";

	SoftTestWorld fresh;
	build(fresh);
	ASSERT_TRUE(caliber::restoreSoftWorldState(fresh.world(), &snapshot[0], size_t(snapshot.size()), &error))
	    << error.message;
	const std::vector<std::vector<unsigned char>> copy = run(fresh, steps);
	EXPECT_EQ(firstDifference(first, copy), -1) << "fresh world: the steps after the restore differ";

	SoftTestWorld late;
	build(late);
	squash(late);
	ASSERT_TRUE(caliber::restoreSoftWorldState(late.world(), &snapshot[0], size_t(snapshot.size()), &error))
	    << error.message;
	EXPECT_EQ(firstDifference(first, run(late, steps)), -1)
	    << "squashed fresh world: the steps after the restore differ";
}
}  // namespace

TEST(SoftWorldSnapshot, ClothWithAFallingBoxRepeatsBitForBitAfterRestore) { checkRollback(clothAndBox, 40, 240); }

TEST(SoftWorldSnapshot, PressurisedAndVolumeBallsRepeatBitForBitAfterRestore) { checkRollback(balls, 50, 200); }

TEST(SoftWorldSnapshot, ClustersJointsAndAnchorsRepeatBitForBitAfterRestore)
{
	checkRollback(clustersAndJoints, 30, 300);
}

TEST(SoftWorldSnapshot, SavedBeforeTheFirstStepRepeatsBitForBit) { checkRollback(balls, 0, 120); }

TEST(SoftWorldSnapshot, RestoringTwiceAndAfterManyStepsGivesTheSameSteps)
{
	SoftTestWorld w;
	clothAndBox(w);
	w.step(20);
	btAlignedObjectArray<unsigned char> snapshot;
	ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), snapshot));
	const std::vector<std::vector<unsigned char>> first = run(w, 60);
	w.step(300);
	ASSERT_TRUE(caliber::restoreSoftWorldState(w.world(), &snapshot[0], size_t(snapshot.size())));
	ASSERT_TRUE(caliber::restoreSoftWorldState(w.world(), &snapshot[0], size_t(snapshot.size())));
	EXPECT_EQ(firstDifference(first, run(w, 60)), -1);
}

TEST(SoftWorldSnapshot, ChangedTopologyIsRefusedAndTheWorldIsUnchanged)
{
	SoftTestWorld w;
	clothAndBox(w);
	w.step(10);
	btAlignedObjectArray<unsigned char> snapshot, before;
	ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), snapshot));
	w.step(5);
	btSoftBody* cloth = w.world().getSoftBodyArray()[0];
	struct Change
	{
		const char* what;
		std::function<void()> apply;
	};
	const Change changes[] = {
	    {"a link more", [&] { cloth->appendLink(0, 40); }},
	    {"a node more", [&] { cloth->appendNode(btVector3(0, 5, 0), 1); }},
	    {"a face more", [&] { cloth->appendFace(0, 1, 40); }},
	};
	for (const Change& c : changes)
	{
		c.apply();
		ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), before)) << c.what;
		caliber::SnapshotError error;
		EXPECT_FALSE(caliber::restoreSoftWorldState(w.world(), &snapshot[0], size_t(snapshot.size()), &error))
		    << c.what;
		EXPECT_NE(std::string(error.message).find("topology changed"), std::string::npos)
		    << c.what << ": " << error.message;
		EXPECT_TRUE(caliber::compareSoftWorldState(w.world(), &before[0], size_t(before.size()))) << c.what;
	}
}

TEST(SoftWorldSnapshot, MisuseIsRefusedWithAClearError)
{
	SoftTestWorld w;
	balls(w);
	w.step(5);
	btAlignedObjectArray<unsigned char> snapshot;
	caliber::SnapshotError error;
	// The plain world functions do not know soft bodies.
	EXPECT_FALSE(caliber::saveWorldState(w.world(), snapshot, &error));
	EXPECT_NE(std::string(error.message).find("soft bodies"), std::string::npos) << error.message;
	ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), snapshot, &error));
	EXPECT_FALSE(caliber::restoreWorldState(w.world(), &snapshot[0], size_t(snapshot.size()), &error));
	// A soft body removed: other counts.
	SoftTestWorld fewer;
	balls(fewer);
	fewer.world().removeSoftBody(fewer.world().getSoftBodyArray()[1]);
	EXPECT_FALSE(caliber::restoreSoftWorldState(fewer.world(), &snapshot[0], size_t(snapshot.size()), &error));
	EXPECT_NE(std::string(error.message).find("collision objects"), std::string::npos) << error.message;
	// Truncated anywhere: refused, never read past the end (ASan).
	for (int cut = 0; cut < snapshot.size(); cut += 97)
		EXPECT_FALSE(caliber::restoreSoftWorldState(w.world(), &snapshot[0], size_t(cut), &error)) << cut;
	// The validation mode names the soft body part that differs.
	w.world().getSoftBodyArray()[1]->m_nodes[3].m_v += btVector3(0, 1e-3, 0);
	caliber::SnapshotDifference difference;
	ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), snapshot, &error));
	w.world().getSoftBodyArray()[1]->m_nodes[3].m_v -= btVector3(0, 2e-3, 0);
	EXPECT_FALSE(caliber::compareSoftWorldState(w.world(), &snapshot[0], size_t(snapshot.size()), &difference));
	EXPECT_STREQ(difference.section, "soft body");
	EXPECT_EQ(difference.index, 1);
	EXPECT_STREQ(difference.field, "node m_v");
}

TEST(SoftWorldSnapshot, EveryByteOfTheSoftPartDamagedNeverCrashes)
{
	// Under ASan in CI: a restore of a damaged snapshot either fails with the world unchanged or succeeds;
	// it never reads outside the buffer. Bytes of the soft part (the end of the snapshot), every 5th.
	SoftTestWorld w;
	clustersAndJoints(w);
	w.step(5);
	btAlignedObjectArray<unsigned char> snapshot, rigidOnly, before;
	ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), snapshot));
	ASSERT_TRUE(caliber::saveSoftWorldState(w.world(), before));
	const int softBytes = snapshot.size() / 3;
	int refused = 0;
	for (int k = snapshot.size() - softBytes; k < snapshot.size(); k += 5)
	{
		btAlignedObjectArray<unsigned char> copy = snapshot;
		copy[k] = static_cast<unsigned char>(copy[k] ^ 0x5A);
		caliber::SnapshotError error;
		if (!caliber::restoreSoftWorldState(w.world(), &copy[0], size_t(copy.size()), &error))
		{
			++refused;
			EXPECT_TRUE(caliber::compareSoftWorldState(w.world(), &before[0], size_t(before.size()))) << k;
		}
		else
		{
			ASSERT_TRUE(caliber::restoreSoftWorldState(w.world(), &before[0], size_t(before.size())));
		}
	}
	EXPECT_GT(refused, 0);
}
