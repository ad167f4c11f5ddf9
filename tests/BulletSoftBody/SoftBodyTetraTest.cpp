// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Tetra volume stiffness (Material::m_kVST): each tetra's volume is an XPBD constraint whose stiffness
// m_kVST defines as m_kLST defines a link's (docs/soft-bodies.md, "Tetra volumes").

#include <gtest/gtest.h>

#include <cmath>

#include "SoftBodyTestUtil.h"

namespace
{
const btScalar kFrame = btScalar(1) / 60;

// One tetra: a fixed base triangle in the plane y = 0 (area 0.5 m^2) and a 1 kg apex 1 m above it, no
// links, so that only the tetra's volume holds the apex up against gravity (10 m/s^2, down).
struct HangingApex
{
	btSoftBodyWorldInfo info;
	btSoftBody* body;
	explicit HangingApex(btScalar kVST, int piterations)
	{
		info.m_gravity.setValue(0, -10, 0);
		const btVector3 x[4] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1), btVector3(0, 1, 0)};
		const btScalar m[4] = {0, 0, 0, 1};
		body = new btSoftBody(&info, 4, x, m);
		body->appendTetra(0, 1, 2, 3);
		body->m_materials[0]->m_kVST = kVST;
		body->m_cfg.piterations = piterations;
		body->m_cfg.kDP = btScalar(0.05);  // damps the oscillation; the equilibrium does not depend on it
	}
	~HangingApex() { delete body; }
	btScalar apexY() const { return body->m_nodes[3].m_x.y(); }
	void step(int frames, btScalar dt)
	{
		for (int i = 0; i < frames; ++i)
		{
			body->predictMotion(dt);
			body->solveConstraints();
			body->integrateMotion();
		}
	}
};

// The sag the documented model predicts. With the base fixed, the apex's volume gradient is the constant
// (base area / 3) along y, so V is linear in the apex height and the constraint a linear spring of
// k = kStep / ((1 - kStep) W h_ref^2) in volume, W = im |grad|^2: the apex settles where
// k dV |grad| = m g, i.e. dy = g h_ref^2 (1 - kStep) / kStep, whatever the base area and the mass.
double predictedSag(double kVST, int piterations)
{
	const double kStep = 1 - std::pow(1 - kVST, piterations);
	const double href = 1.0 / 60;
	return 10 * href * href * (1 - kStep) / kStep;
}
}  // namespace

TEST(SoftBodyTetra, ApexSagsAsTheVolumeStiffnessPredictsAtAnyStepAndSweepCount)
{
	const struct
	{
		btScalar kVST;
		int piterations;
		btScalar dt;
	} cases[] = {{btScalar(0.1), 1, kFrame},
	             {btScalar(0.1), 1, kFrame / 2},
	             {btScalar(0.1), 4, kFrame},
	             {btScalar(0.02), 1, kFrame},
	             {btScalar(0.5), 2, kFrame / 2}};
	for (const auto& c : cases)
	{
		HangingApex apex(c.kVST, c.piterations);
		apex.step(int(4 / c.dt), c.dt);  // 4 s: kDP = 0.05 per step leaves < 1e-4 of the first swing
		const double sag = 1.0 - double(apex.apexY());
		const double expected = predictedSag(double(c.kVST), c.piterations);
		// The equilibrium of the step is exact for this linear constraint; 1% covers the leftover swing and
		// float rounding of positions near 1 m (1e-7 m) against sags of 3e-4 m and more.
		EXPECT_NEAR(sag, expected, 0.01 * expected + 1e-6)
		    << "kVST " << c.kVST << ", piterations " << c.piterations << ", dt " << c.dt;
		// Only the volume holds the apex: it stays above the base's corner (no sideways force).
		EXPECT_NEAR(apex.body->m_nodes[3].m_x.x(), 0, 1e-5);
		EXPECT_NEAR(apex.body->m_nodes[3].m_x.z(), 0, 1e-5);
	}
}

TEST(SoftBodyTetra, FullVolumeStiffnessHoldsTheRestVolumeAndZeroSwitchesItOff)
{
	HangingApex hard(1, 1);
	hard.step(120, kFrame);
	// kVST = 1 is a hard constraint: the apex (whose gradient is constant) is put back exactly each step.
	EXPECT_NEAR(hard.apexY(), 1, 1e-5);

	HangingApex off(0, 1);
	off.step(60, kFrame);
	// No constraint: the apex falls freely (1 s at 10 m/s^2 with 5% of the velocity lost per step: at
	// least 1.5 m, well past the base).
	EXPECT_LT(off.apexY(), -0.5);
}

TEST(SoftBodyTetra, TetraKeepsItsSignedVolumeAndDoesNotTurnInsideOut)
{
	// The apex thrown down at 90 m/s (1.5 m in one step, through the base): a hard tetra keeps its signed rest volume,
	// so the apex ends on its own side of the base (an unsigned volume would let it settle mirrored below).
	HangingApex apex(1, 1);
	apex.body->m_nodes[3].m_v.setValue(0, -90, 0);
	apex.step(60, kFrame);
	EXPECT_GT(apex.apexY(), 0.99);
}

TEST(SoftBodyTetraBadInput, NonFiniteVolumeStiffnessSwitchesTheConstraintOff)
{
	// A NaN kVST (docs/bad-input.md) is treated as no stiffness: no NaN reaches the nodes.
	HangingApex apex(btScalar(NAN), 1);
	apex.step(30, kFrame);
	EXPECT_TRUE(std::isfinite(double(apex.apexY())));
	EXPECT_LT(apex.apexY(), 0.5);  // falls freely, as with kVST = 0 (0.8 m in 0.5 s)
}
