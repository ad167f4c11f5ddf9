// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include "../NarrowPhaseCollision/NarrowPhaseTestUtil.h"
#include "BulletCollision/CollisionDispatch/btCompoundCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "TestDispatcher.h"

using caliber_dispatch_test::PairFixture;
using caliber_dispatch_test::TestDispatcher;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// Exact analytic contacts (plane, spheres) in float.
const btScalar kTolerance = btScalar(1e-4);

btTransform at(btScalar x, btScalar y, btScalar z)
{
	return btTransform(btQuaternion::getIdentity(), btVector3(x, y, z));
}

int totalPoints(btCollisionAlgorithm* algorithm, btManifoldArray& manifolds)
{
	manifolds.resize(0);
	algorithm->getAllContactManifolds(manifolds);
	int points = 0;
	for (int i = 0; i < manifolds.size(); ++i) points += manifolds[i]->getNumContacts();
	return points;
}
}  // namespace

TEST(CompoundAlgorithms, CompoundOfTwoBoxesOnPlaneGetsFourPointsPerChild)
{
	for (int useTree = 0; useTree < 2; ++useTree)
	{
		btDefaultCollisionConfiguration config;
		TestDispatcher dispatcher(&config);
		btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
		btCompoundShape compound(useTree == 1);
		compound.addChildShape(at(-2, 0, 0), &box);
		compound.addChildShape(at(2, 0, 0), &box);
		btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
		PairFixture pair(dispatcher, &compound, at(0, btScalar(0.49), 0), &plane, btTransform::getIdentity());
		pair.process();
		btManifoldArray manifolds;
		EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 8) << "tree " << useTree;
		ASSERT_EQ(manifolds.size(), 2);
		for (int m = 0; m < manifolds.size(); ++m)
		{
			for (int i = 0; i < manifolds[m]->getNumContacts(); ++i)
			{
				const btManifoldPoint& pt = manifolds[m]->getContactPoint(i);
				EXPECT_NEAR(pt.getDistance(), -0.01, kTolerance);
				// The manifold is (child box, plane): the child index is on side 0.
				const int expectedChild = pt.getPositionWorldOnA().x() < 0 ? 0 : 1;
				EXPECT_EQ(pt.m_index0, expectedChild);
			}
		}
	}
}

TEST(CompoundAlgorithms, OnlyTheTouchedChildGetsAnAlgorithmAndItIsReleasedWhenApart)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btSphereShape childSphere(btScalar(0.5));
	btCompoundShape compound;
	for (int i = 0; i < 5; ++i) compound.addChildShape(at(btScalar(2 * i), 0, 0), &childSphere);
	btSphereShape sphere(btScalar(0.5));
	// The other sphere comes first (swapped compound algorithm) and touches child 3 only.
	PairFixture pair(dispatcher, &sphere, at(6, btScalar(0.99), 0), &compound, btTransform::getIdentity());
	const int freeAlgorithms = config.getCollisionAlgorithmPool()->getFreeCount();
	pair.process();
	btManifoldArray manifolds;
	EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 1);
	ASSERT_EQ(manifolds.size(), 1);
	const btManifoldPoint& pt = manifolds[0]->getContactPoint(0);
	EXPECT_NEAR(pt.getDistance(), -0.01, kTolerance);
	EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, btVector3(0, 1, 0), kTolerance));
	EXPECT_EQ(pt.m_index1, 3) << "child index on the compound side";
	EXPECT_EQ(config.getCollisionAlgorithmPool()->getFreeCount(), freeAlgorithms - 1);

	pair.m_object0.setWorldTransform(at(6, 5, 0));
	pair.process();
	EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 0);
	EXPECT_EQ(manifolds.size(), 0);
	EXPECT_EQ(config.getCollisionAlgorithmPool()->getFreeCount(), freeAlgorithms) << "child algorithm released";
}

TEST(CompoundAlgorithms, ChildAlgorithmsAreRebuiltWhenTheCompoundChanges)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btSphereShape childSphere(btScalar(0.5));
	btCompoundShape compound;
	compound.addChildShape(at(0, 0, 0), &childSphere);
	btSphereShape sphere(btScalar(0.5));
	PairFixture pair(dispatcher, &compound, btTransform::getIdentity(), &sphere, at(3, btScalar(0.99), 0));
	pair.process();
	btManifoldArray manifolds;
	EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 0);
	compound.addChildShape(at(3, 0, 0), &childSphere);
	pair.process();
	EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 1);
	compound.removeChildShapeByIndex(1);
	pair.process();
	EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 0);
}

TEST(CompoundAlgorithms, CompoundCompoundPairsTheTouchingChildren)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btSphereShape childSphere(btScalar(0.5));
	btCompoundShape compoundA, compoundB;
	compoundA.addChildShape(at(0, 0, 0), &childSphere);
	compoundA.addChildShape(at(0, 2, 0), &childSphere);
	compoundB.addChildShape(at(0, 0, 0), &childSphere);
	compoundB.addChildShape(at(5, 0, 0), &childSphere);
	// A's child 1 (y = 12) touches B's child 0 (y = 12.99); A's child 0 (y = 10) is far from both.
	const btTransform transformA = at(0, 10, 0);
	const btTransform transformB = at(0, btScalar(12.99), 0);
	PairFixture pair(dispatcher, &compoundA, transformA, &compoundB, transformB);
	pair.process();
	btManifoldArray manifolds;
	EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 1);
	ASSERT_EQ(manifolds.size(), 1);
	const btManifoldPoint& pt = manifolds[0]->getContactPoint(0);
	EXPECT_EQ(pt.m_index0, 1);
	EXPECT_EQ(pt.m_index1, 0);
	// Centres 0.99 apart, radii 0.5 + 0.5: overlap 0.01; the normal points from B (above) towards A.
	EXPECT_NEAR(pt.getDistance(), -0.01, kTolerance * 10);
	EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, btVector3(0, -1, 0), kTolerance));

	// Apart: the pair's algorithm is dropped.
	pair.m_object1.setWorldTransform(at(0, -20, 0));
	pair.process();
	EXPECT_EQ(totalPoints(pair.m_algorithm, manifolds), 0);
	EXPECT_EQ(manifolds.size(), 0);
}
