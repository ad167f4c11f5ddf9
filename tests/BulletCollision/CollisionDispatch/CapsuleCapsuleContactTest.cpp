// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Capsule against capsule is computed in closed form (closest points of the core segments); checked
// against an independent minimisation of the segment distance over random poses.

#include <gtest/gtest.h>

#include <cmath>

#include "btBulletCollisionCommon.h"
#include <random>

namespace
{
// The distance between two segments by nested ternary searches: the squared distance is convex in
// (s, t), so its minimum over t is convex in s.
double segmentDistance(const btVector3& p0, const btVector3& p1, const btVector3& q0, const btVector3& q1)
{
	auto distanceAt = [&](double s, double t)
	{
		const btVector3 a = p0 + (p1 - p0) * btScalar(s);
		const btVector3 b = q0 + (q1 - q0) * btScalar(t);
		return double((a - b).length());
	};
	auto bestOverT = [&](double s)
	{
		double lo = 0, hi = 1;
		for (int i = 0; i < 100; ++i)
		{
			const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
			if (distanceAt(s, m1) < distanceAt(s, m2))
				hi = m2;
			else
				lo = m1;
		}
		return distanceAt(s, 0.5 * (lo + hi));
	};
	double lo = 0, hi = 1;
	for (int i = 0; i < 100; ++i)
	{
		const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
		if (bestOverT(m1) < bestOverT(m2))
			hi = m2;
		else
			lo = m1;
	}
	return bestOverT(0.5 * (lo + hi));
}

struct DeepestContact : btCollisionWorld::ContactResultCallback
{
	bool m_found = false;
	btScalar m_distance = 0;
	btVector3 m_normalOnB;
	btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
	                         const btCollisionObjectWrapper*, int, int) override
	{
		if (!m_found || cp.getDistance() < m_distance)
		{
			m_found = true;
			m_distance = cp.getDistance();
			m_normalOnB = cp.m_normalWorldOnB;
		}
		return 0;
	}
};
}  // namespace

TEST(CapsuleCapsuleContact, DistanceMatchesTheSegmentsMinimumOverRandomPoses)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btCollisionWorld world(&dispatcher, &broadphase, &configuration);
	btCapsuleShape capsuleA(btScalar(0.3), btScalar(1.2));
	btCapsuleShapeZ capsuleB(btScalar(0.2), btScalar(0.8));
	btCollisionObject a, b;
	a.setCollisionShape(&capsuleA);
	b.setCollisionShape(&capsuleB);
	world.addCollisionObject(&a);
	world.addCollisionObject(&b);
	std::mt19937 random(7);
	std::uniform_real_distribution<double> unit(0, 1);
	auto uniform = [&](double lo, double hi) { return btScalar(lo + (hi - lo) * unit(random)); };
	auto direction = [&]()
	{
		const double z = 2 * unit(random) - 1, phi = 2 * M_PI * unit(random), r = std::sqrt(1 - z * z);
		return btVector3(btScalar(r * std::cos(phi)), btScalar(r * std::sin(phi)), btScalar(z));
	};
	int checked = 0;
	for (int trial = 0; trial < 300; ++trial)
	{
		btQuaternion qa(direction(), uniform(0, 2 * M_PI));
		btQuaternion qb(direction(), uniform(0, 2 * M_PI));
		const btTransform ta(qa, btVector3(0, 0, 0));
		const btTransform tb(qb, direction() * uniform(0.2, 1.0));
		a.setWorldTransform(ta);
		b.setWorldTransform(tb);
		DeepestContact contact;
		world.contactPairTest(&a, &b, contact);
		const btVector3 axisA = ta.getBasis().getColumn(1) * capsuleA.getHalfHeight();
		const btVector3 axisB = tb.getBasis().getColumn(2) * capsuleB.getHalfHeight();
		const double segments = segmentDistance(ta.getOrigin() - axisA, ta.getOrigin() + axisA, tb.getOrigin() - axisB,
		                                        tb.getOrigin() + axisB);
		const double expected = segments - 0.3 - 0.2;
		if (segments < 1e-3) continue;  // crossing cores: the general algorithm's case
		if (expected > 0.01) continue;  // apart beyond the contact threshold: no point expected
		ASSERT_TRUE(contact.m_found) << "trial " << trial << " expected distance " << expected;
		// Float rounding of the closed form against a double-precision search: 1e-5 of the sizes (~1 m).
		EXPECT_NEAR(contact.m_distance, expected, 2e-5) << "trial " << trial;
		EXPECT_NEAR(contact.m_normalOnB.length(), 1, 1e-5);
		++checked;
	}
	EXPECT_GT(checked, 100) << "enough touching poses were drawn";
	world.removeCollisionObject(&a);  // the objects go before the world that holds them
	world.removeCollisionObject(&b);
}

TEST(CapsuleCapsuleContact, ParallelCapsulesRestOnEachOtherAtTheSumOfTheirRadii)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btCollisionWorld world(&dispatcher, &broadphase, &configuration);
	btCapsuleShapeX capsule(btScalar(0.25), 2);
	btCollisionObject a, b;
	a.setCollisionShape(&capsule);
	b.setCollisionShape(&capsule);
	a.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.49), 0)));
	b.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(btScalar(0.3), 0, 0)));
	world.addCollisionObject(&a);
	world.addCollisionObject(&b);
	DeepestContact contact;
	world.contactPairTest(&a, &b, contact);
	ASSERT_TRUE(contact.m_found);
	// Parallel cores 0.49 apart, radii 0.25 each: 0.01 of overlap, along y.
	EXPECT_NEAR(contact.m_distance, -0.01, 1e-6);
	EXPECT_NEAR(contact.m_normalOnB.y(), 1, 1e-6);
	world.removeCollisionObject(&a);  // the objects go before the world that holds them
	world.removeCollisionObject(&b);
}
