// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The link sweeps run on links packed once per step (src/BulletSoftBody/btSoftBodyLinkSweep.h): what the
// user changes between steps (a material's stiffness, a rest length) must reach the next step's sweeps.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "BulletSoftBody/btSoftBody.h"
#include "SoftBodyTestUtil.h"

namespace
{
const btScalar kStep = btScalar(1) / 60;
const double kGravity = 10;

// A 1 kg node on a link of 1 m whose top is fixed, one sweep a step (no substeps), damped to rest.
btSoftBody* hangingLink(btSoftBodyWorldInfo& info)
{
	btSoftBody* body = caliber_test::twoNodeLink(info, btVector3(0, 10, 0), btVector3(0, 9, 0), 0, 1).release();
	info.m_gravity.setValue(0, -btScalar(kGravity), 0);
	body->m_cfg.piterations = 1;
	body->m_cfg.kDP = btScalar(0.05);
	return body;
}

void stepAlone(btSoftBody& body, int frames)
{
	for (int i = 0; i < frames; ++i)
	{
		body.predictMotion(kStep);
		body.solveConstraints();
		body.integrateMotion();
	}
}

double length(const btSoftBody& body) { return double((body.m_nodes[1].m_x - body.m_nodes[0].m_x).length()); }

// The static stretch of the link (docs/soft-bodies.md, "Links"): its spring k = kStep / ((1 - kStep) w h^2)
// with w = 1 / m carries m g, so it stretches g h^2 (1 - kStep) / kStep, whatever the mass (one sweep:
// kStep = kLST).
double expectedStretch(double kLST) { return kGravity * double(kStep) * double(kStep) * (1 - kLST) / kLST; }
}  // namespace

TEST(SoftBodyLinkSweep, StiffnessChangedBetweenStepsReachesTheNextSweeps)
{
	btSoftBodyWorldInfo info;
	btSoftBody* body = hangingLink(info);
	body->m_materials[0]->m_kLST = btScalar(0.1);
	stepAlone(*body, 600);
	// 2%: the damped oscillation (kDP 0.05 a step) has died out far below that in 600 steps.
	EXPECT_NEAR(length(*body) - 1, expectedStretch(0.1), 0.02 * expectedStretch(0.1)) << "kLST 0.1";
	body->m_materials[0]->m_kLST = btScalar(0.5);
	stepAlone(*body, 600);
	EXPECT_NEAR(length(*body) - 1, expectedStretch(0.5), 0.02 * expectedStretch(0.5)) << "kLST 0.5";
	delete body;
}

TEST(SoftBodyLinkSweep, RestLengthChangedBetweenStepsReachesTheNextSweeps)
{
	btSoftBodyWorldInfo info;
	btSoftBody* body = hangingLink(info);
	body->m_materials[0]->m_kLST = btScalar(0.5);
	stepAlone(*body, 300);
	body->m_links[0].m_rl = btScalar(1.5);
	stepAlone(*body, 600);
	EXPECT_NEAR(length(*body) - 1.5, expectedStretch(0.5), 0.02 * expectedStretch(0.5));
	delete body;
}

TEST(SoftBodyLinkSweep, SolveWithoutAPredictionPacksTheLinksItself)
{
	// Two nodes 2 m apart on a link of rest length 1 m: a solve on its own (no predictMotion, no world) pulls
	// them together. kLST 1 (zero compliance) closes a lone link's error in one sweep.
	btSoftBodyWorldInfo info;
	const std::unique_ptr<btSoftBody> owner =
	    caliber_test::twoNodeLink(info, btVector3(0, 0, 0), btVector3(2, 0, 0), 1, 1);
	btSoftBody& body = *owner;
	body.m_links[0].m_rl = 1;
	body.m_materials[0]->m_kLST = 1;
	body.m_cfg.piterations = 1;
	body.m_sst.sdt = kStep;
	body.updateConstants();
	body.solveConstraints();
	// One sweep of a hard link with equal masses puts the nodes at the rest length exactly, up to rounding.
	EXPECT_NEAR(length(body), 1.0, 1e-6);
}
