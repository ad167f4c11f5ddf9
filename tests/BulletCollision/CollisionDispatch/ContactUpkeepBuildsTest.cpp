// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btManifoldResult::addContactPoint and btPersistentManifold::refreshContactPoints' first pass run an AVX2
// build on processors that have it (btManifoldResultBuilds.h, btPersistentManifoldBuilds.h): the same
// operations in the same order, so the baseline build must store the same points bit for bit. The public
// calls run only the build chosen at load, so without these tests the baseline build would never run on an
// AVX2 machine. Each test runs both builds on copies of the same manifold and compares every field.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionDispatch/btManifoldResultBuilds.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifoldBuilds.h"
#include "LinearMath/btQuaternion.h"

#include "BulletCollision/CollisionDispatch/ManifoldPointCompare.h"

namespace
{
using caliber_test::expectSamePoint;
using caliber_test::sameBits;

void expectSameManifold(const btPersistentManifold& a, const btPersistentManifold& b, int trial)
{
	ASSERT_EQ(a.getNumContacts(), b.getNumContacts()) << trial;
	for (int i = 0; i < a.getNumContacts(); ++i) expectSamePoint(a.getContactPoint(i), b.getContactPoint(i), trial);
}

btScalar halfFriction(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return btScalar(0.5) * body0->getFriction() + body1->getFriction();
}

// A scale drawn from a wide range (tiny, ordinary and large magnitudes), so that the products and sums
// round differently from trial to trial.
btScalar wideScale(std::mt19937& random)
{
	static const btScalar scales[] = {btScalar(1e-6), btScalar(1e-3), btScalar(0.1), btScalar(1),
	                                  btScalar(7.3),  btScalar(1e3),  btScalar(1e5)};
	return scales[random() % (sizeof(scales) / sizeof(scales[0]))];
}

btTransform randomTransform(std::mt19937& random, std::uniform_real_distribution<float>& unit)
{
	const btVector3 axis = btVector3(unit(random), unit(random), unit(random) + btScalar(1.5)).normalized();
	return btTransform(btQuaternion(axis, btScalar(3) * unit(random)),
	                   btVector3(unit(random), unit(random), unit(random)) * wideScale(random));
}
}  // namespace

// The same contacts, into copies of the same manifold, through the baseline and the AVX2 build: the same
// points in the same slots, every field. Varied as AddContactPointStoresWhatReplaceOrAddManifoldPointWould
// varies them (body order, materials, stiffness and anchor flags, a custom friction callback, matches and
// misses), and also full manifolds (the replacement choice), contacts beyond the breaking threshold, and
// poses and points from tiny to large magnitudes.
TEST(ContactUpkeepBuilds, AddContactPointStoresTheSamePointsInBothBuilds)
{
	if (!caliber::addContactPointUsesAvx2())
		GTEST_SKIP() << "no AVX2 build of addContactPoint on this processor or build";
	std::mt19937 random(2811);
	std::uniform_real_distribution<float> unit(-1, 1);
	btSphereShape shape(btScalar(1));
	btCollisionObject object0, object1;
	object0.setCollisionShape(&shape);
	object1.setCollisionShape(&shape);
	const CalculateCombinedCallback savedFriction = gCalculateCombinedFrictionCallback;
	int replaced = 0, added = 0, ignored = 0, full = 0;
	for (int trial = 0; trial < 4000; ++trial)
	{
		object0.setWorldTransform(randomTransform(random, unit));
		object1.setWorldTransform(randomTransform(random, unit));
		object0.setFriction(btScalar(0.5) + btScalar(0.5) * unit(random));
		object1.setFriction(btScalar(0.5) + btScalar(0.5) * unit(random));
		object0.setRestitution(btScalar(0.5) + btScalar(0.5) * unit(random));
		object1.setRestitution(btScalar(0.5) + btScalar(0.5) * unit(random));
		object0.setRollingFriction(btScalar(0.05) * (btScalar(1) + unit(random)));
		object1.setSpinningFriction(btScalar(0.05) * (btScalar(1) + unit(random)));
		object0.setCollisionFlags(0);
		object1.setCollisionFlags(0);
		if (trial % 3 == 0) object0.setContactStiffnessAndDamping(btScalar(1000), btScalar(0.2));
		if (trial % 5 == 0)
			object1.setCollisionFlags(object1.getCollisionFlags() | btCollisionObject::CF_HAS_FRICTION_ANCHOR);
		gCalculateCombinedFrictionCallback = trial % 7 == 0 ? halfFriction : savedFriction;
		const bool swapped = trial % 2 == 1;
		const btCollisionObject* bodyA = swapped ? &object1 : &object0;
		const btCollisionObject* bodyB = swapped ? &object0 : &object1;

		const btScalar scale = wideScale(random);
		const btScalar threshold = btScalar(0.05) * scale;
		btPersistentManifold baseline(bodyA, bodyB, 0, threshold, btScalar(BT_LARGE_FLOAT));
		const int stored = trial % 5;  // 4: a full manifold, so a new point replaces one of them
		for (int i = 0; i < stored; ++i)
		{
			btManifoldPoint point(btVector3(unit(random), unit(random), unit(random)) * scale,
			                      btVector3(unit(random), unit(random), unit(random)) * scale, btVector3(0, 1, 0),
			                      btScalar(0.01) * scale * unit(random));
			point.m_appliedImpulse = btScalar(1 + i) * unit(random);
			point.m_prevRHS = btScalar(2 + i);
			point.m_appliedImpulseLateral1 = btScalar(3 + i) * unit(random);
			point.m_appliedImpulseLateral2 = btScalar(4 + i) * unit(random);
			caliber_test::setDistinctSolverFields(point, i);
			baseline.addManifoldPoint(point);
		}
		btPersistentManifold avx2 = baseline;

		// A contact near a stored point (a match), anywhere (usually a miss) or beyond the threshold.
		const btVector3 normal = btVector3(unit(random), btScalar(1), unit(random)).normalized();
		btScalar depth = btScalar(0.02) * scale * unit(random);
		if (trial % 11 == 5) depth = threshold * btScalar(1.5);
		btVector3 pointOnB = btVector3(unit(random), unit(random), unit(random)) * scale;
		if (stored > 0 && trial % 4 != 3)
		{
			const btManifoldPoint& near = baseline.getContactPoint(trial % stored);
			const btVector3 pointOnA = bodyA->getWorldTransform()(near.m_localPointA) +
			                           btVector3(unit(random), unit(random), unit(random)) * (btScalar(0.01) * scale);
			pointOnB = pointOnA - normal * depth;
		}

		btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), 3, 7);
		btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), 5, 9);
		btManifoldResult result(&w0, &w1);
		result.setPersistentManifold(&baseline);
		caliber::addContactPointIn(result, normal, pointOnB, depth, false);
		result.setPersistentManifold(&avx2);
		caliber::addContactPointIn(result, normal, pointOnB, depth, true);
		expectSameManifold(baseline, avx2, trial);

		// What happened: a point added, the new point written over a stored one (in a full manifold, the
		// replacement choice), or nothing (beyond the threshold).
		bool written = false;
		for (int i = 0; i < baseline.getNumContacts(); ++i)
			written = written || sameBits(baseline.getContactPoint(i).m_positionWorldOnB, pointOnB);
		if (baseline.getNumContacts() > stored)
			++added;
		else if (!written)
			++ignored;
		else if (stored == 4)
			++full;
		else
			++replaced;
	}
	gCalculateCombinedFrictionCallback = savedFriction;
	// Every way was taken many times (not a test that cannot fail).
	EXPECT_GT(added, 500);
	EXPECT_GT(replaced, 500);
	EXPECT_GT(ignored, 200);
	EXPECT_GT(full, 300);
}

// refreshContactPoints' first pass in both builds on copies of the same points: the same world points,
// distances and lifetimes, bit for bit, and the same points kept. Points are placed around the breaking
// threshold (along the normal and sideways) so that both verdicts are common, with poses from tiny to large.
TEST(ContactUpkeepBuilds, RefreshContactPointsFirstPassIsTheSameInBothBuilds)
{
	if (!caliber::refreshContactPointsUsesAvx2())
		GTEST_SKIP() << "no AVX2 build of refreshContactPoints on this processor or build";
	std::mt19937 random(1511);
	std::uniform_real_distribution<float> unit(-1, 1);
	int keptPoints = 0, droppedPoints = 0;
	for (int trial = 0; trial < 3000; ++trial)
	{
		const btScalar scale = wideScale(random);
		const btScalar threshold = btScalar(0.02) * scale;
		const btTransform trA = randomTransform(random, unit), trB = randomTransform(random, unit);
		const int count = 1 + trial % MANIFOLD_CACHE_SIZE;
		btManifoldPoint baseline[MANIFOLD_CACHE_SIZE];
		for (int i = 0; i < count; ++i)
		{
			// A point whose world points are about threshold * 2 * unit apart along the normal and sideways.
			const btVector3 normal = btVector3(unit(random), unit(random), btScalar(1)).normalized();
			const btVector3 onB = btVector3(unit(random), unit(random), unit(random)) * scale;
			const btVector3 onA = onB + normal * (btScalar(2) * threshold * unit(random)) +
			                      btVector3(unit(random), unit(random), unit(random)) * (threshold * unit(random));
			baseline[i] = btManifoldPoint(trA.invXform(onA), trB.invXform(onB), normal, btScalar(0));
			baseline[i].m_lifeTime = trial % 9;
		}
		btManifoldPoint avx2[MANIFOLD_CACHE_SIZE];
		for (int i = 0; i < count; ++i) avx2[i] = baseline[i];
		const int keptBaseline = caliber::refreshWorldPointsIn(baseline, count, trA, trB, threshold, false);
		const int keptAvx2 = caliber::refreshWorldPointsIn(avx2, count, trA, trB, threshold, true);
		ASSERT_EQ(keptBaseline, keptAvx2) << trial;
		for (int i = 0; i < count; ++i)
		{
			expectSamePoint(baseline[i], avx2[i], trial);
			if (keptBaseline & (1 << i))
				++keptPoints;
			else
				++droppedPoints;
		}
	}
	// Both verdicts were common (not a test that cannot fail).
	EXPECT_GT(keptPoints, 1000);
	EXPECT_GT(droppedPoints, 1000);
}

// A transform that is not finite leaves the points alone in both builds.
TEST(ContactUpkeepBuilds, RefreshContactPointsFirstPassRejectsANonFiniteTransformInBothBuilds)
{
	btTransform bad = btTransform::getIdentity();
	bad.setOrigin(btVector3(0, std::numeric_limits<btScalar>::quiet_NaN(), 0));
	for (bool avx2 : {false, true})
	{
		btManifoldPoint point(btVector3(1, 2, 3), btVector3(4, 5, 6), btVector3(0, 1, 0), btScalar(0.5));
		point.m_lifeTime = 3;
#if CALIBER_ASSERTS_ENABLED
		EXPECT_DEATH(caliber::refreshWorldPointsIn(&point, 1, bad, btTransform::getIdentity(), btScalar(0.02), avx2),
		             "assertion failed");
#else
		EXPECT_EQ(caliber::refreshWorldPointsIn(&point, 1, bad, btTransform::getIdentity(), btScalar(0.02), avx2), -1);
		EXPECT_EQ(point.m_lifeTime, 3);
		EXPECT_EQ(point.m_distance1, btScalar(0.5));
#endif
	}
}
