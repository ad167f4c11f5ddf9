// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Parts of btSoftBody's API the other tests do not reach (the audit of issue 19): setTotalDensity, rotate,
// upcast, setSolver and the wind velocity.

#include <gtest/gtest.h>

#include "SoftBodyTestUtil.h"

using caliber_test::SoftTestWorld;

TEST(SoftBodyApi, TotalDensityGivesTheMassOfTheVolume)
{
	// Bullet's meaning: the mass is the density times the closed body's volume.
	SoftTestWorld w;
	btSoftBody* b =
	    w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(0, 0, 0), btVector3(1, 2, 1), 128), false);
	b->setTotalDensity(500);
	EXPECT_NEAR(b->getTotalMass(), 500 * b->getVolume(), 1e-4 * 500 * b->getVolume());
	EXPECT_GT(b->getVolume(), 0.5 * 4 / 3.0 * SIMD_PI * 2);  // the hull of an ellipsoid of volume 8.4 m^3
}

TEST(SoftBodyApi, RotateTurnsEveryNodeAboutTheOriginKeepingTheVolume)
{
	SoftTestWorld w;
	btSoftBody* b =
	    w.addSoft(btSoftBodyHelpers::CreateEllipsoid(w.info(), btVector3(3, 0, 0), btVector3(1, 2, 1), 128), false);
	const btScalar volume = b->getVolume();
	std::vector<btVector3> before;
	for (int i = 0; i < b->m_nodes.size(); ++i) before.push_back(b->m_nodes[i].m_x);
	const btQuaternion q(btVector3(0, 0, 1), SIMD_HALF_PI);
	b->rotate(q);
	for (int i = 0; i < b->m_nodes.size(); ++i)
		EXPECT_LT((b->m_nodes[i].m_x - quatRotate(q, before[size_t(i)])).length(), 1e-5);
	EXPECT_NEAR(b->getVolume(), volume, 1e-5 * volume);  // a rigid turn keeps the volume
}

TEST(SoftBodyApi, UpcastFindsSoftBodiesOnly)
{
	SoftTestWorld w;
	btSoftBody* b = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 0, 0), btVector3(1, 0, 0), 4, 0));
	btRigidBody* r = w.addRigid(1, btVector3(0, 5, 0), w.shape<btSphereShape>(btScalar(0.5)));
	const btCollisionObject* asObject = b;
	EXPECT_EQ(btSoftBody::upcast(asObject), b);
	EXPECT_EQ(btSoftBody::upcast(static_cast<const btCollisionObject*>(r)), nullptr);
	btCollisionObject* mutableObject = b;
	EXPECT_EQ(btSoftBody::upcast(mutableObject), b);
}

TEST(SoftBodyApi, SetSolverKeepsThePositionSolversForEitherPreset)
{
	// Caliber has no velocity pass: both presets run anchors, rigid contacts, soft contacts and links.
	SoftTestWorld w;
	btSoftBody* b = w.addSoft(btSoftBodyHelpers::CreateRope(w.info(), btVector3(0, 0, 0), btVector3(1, 0, 0), 4, 1));
	for (auto preset : {btSoftBody::eSolverPresets::Positions, btSoftBody::eSolverPresets::Velocities})
	{
		b->setSolver(preset);
		ASSERT_EQ(b->m_cfg.m_psequence.size(), 4);
		EXPECT_EQ(b->m_cfg.m_psequence[3], btSoftBody::ePSolver::Linear);
		EXPECT_EQ(b->m_cfg.m_vsequence.size(), 0);
	}
	w.step(30);
	// The rope still holds: every link within 2% of its rest length while hanging from its fixed end.
	for (int i = 0; i < b->m_links.size(); ++i)
	{
		const btSoftBody::Link& l = b->m_links[i];
		EXPECT_NEAR((l.m_n[0]->m_x - l.m_n[1]->m_x).length(), l.m_rl, 0.02 * l.m_rl);
	}
}

TEST(SoftBodyApi, WindCarriesAFreeSheetTowardsItsSpeed)
{
	// A free 1 m^2 sheet of 1 kg, facing a 5 m/s wind in zero gravity, drag kDG = 1 on the node areas
	// (V_Point): m dv/dt = kDG rho A (w - v)^2 / 2, so v(t) = w - 1 / (1 / w + k t) with k = kDG rho A / (2 m)
	// = 0.6 per m (rho = 1.2 kg/m^3): 4.29 m/s after 2 s. The forces are taken at each step's starting
	// velocity: within 2% at 60 Hz.
	SoftTestWorld w(btVector3(0, 0, 0));
	btSoftBody* b = w.addSoft(btSoftBodyHelpers::CreatePatch(w.info(), btVector3(0, 0, 0), btVector3(0, 1, 0),
	                                                         btVector3(0, 0, 1), btVector3(0, 1, 1), 5, 5, 0, true));
	b->setTotalMass(1);
	b->m_cfg.kDG = 1;
	b->m_cfg.aeromodel = btSoftBody::eAeroModel::V_Point;
	w.info().air_density = btScalar(1.2);
	b->setWindVelocity(btVector3(5, 0, 0));
	w.step(120);
	btVector3 v(0, 0, 0);
	for (int i = 0; i < b->m_nodes.size(); ++i) v += b->m_nodes[i].m_v / btScalar(b->m_nodes.size());
	const btScalar expected = 5 - 1 / (btScalar(0.2) + btScalar(0.6) * 2);
	EXPECT_NEAR(v.x(), expected, 0.02 * expected);
	EXPECT_NEAR(v.y(), 0, 1e-3);
	EXPECT_NEAR(v.z(), 0, 1e-3);
}
