// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btQuaternion.h"

#include "BulletCollision/CollisionDispatch/ManifoldPointCompare.h"

namespace
{
// Float precision of the transform round trips below.
const btScalar kTolerance = btScalar(1e-5);

struct ManifoldResultFixture : public ::testing::Test
{
	btSphereShape shape{btScalar(1)};
	btCollisionObject object0, object1;
	void SetUp() override
	{
		object0.setCollisionShape(&shape);
		object1.setCollisionShape(&shape);
		object0.setWorldTransform(btTransform(btQuaternion(btVector3(0, 0, 1), btScalar(0.4)), btVector3(0, 1, 0)));
		object1.setWorldTransform(btTransform(btQuaternion(btVector3(1, 0, 0), btScalar(-0.7)), btVector3(0, -1, 0)));
	}
};

int gCallbackCalls = 0;
const btCollisionObjectWrapper* gCallbackWrap0 = 0;
bool recordingCallback(btManifoldPoint& cp, const btCollisionObjectWrapper* colObj0Wrap, int, int,
                       const btCollisionObjectWrapper*, int, int)
{
	++gCallbackCalls;
	gCallbackWrap0 = colObj0Wrap;
	cp.m_combinedFriction = btScalar(0.123);
	return true;
}
}  // namespace

TEST_F(ManifoldResultFixture, CombinesMaterialsLikeBullet)
{
	object0.setFriction(btScalar(0.5));
	object1.setFriction(btScalar(0.4));
	object0.setRestitution(btScalar(0.3));
	object1.setRestitution(btScalar(0.5));
	object0.setRollingFriction(btScalar(0.1));
	object1.setSpinningFriction(btScalar(0.2));
	btPersistentManifold manifold(&object0, &object1, 0, btScalar(0.1), btScalar(BT_LARGE_FLOAT));
	btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), -1, -1);
	btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), -1, -1);
	btManifoldResult result(&w0, &w1);
	result.setPersistentManifold(&manifold);
	result.addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), btScalar(-0.01));
	ASSERT_EQ(manifold.getNumContacts(), 1);
	const btManifoldPoint& pt = manifold.getContactPoint(0);
	EXPECT_NEAR(pt.m_combinedFriction, 0.5 * 0.4, kTolerance);
	EXPECT_NEAR(pt.m_combinedRestitution, 0.3 * 0.5, kTolerance);
	EXPECT_NEAR(pt.m_combinedRollingFriction, 0.1 * 0.4 + 0.5 * 0.0, kTolerance);
	EXPECT_NEAR(pt.m_combinedSpinningFriction, 0.0 * 0.4 + 0.5 * 0.2, kTolerance);
	EXPECT_EQ(pt.m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING, 0);
	// Friction directions are orthonormal to the normal.
	EXPECT_NEAR(pt.m_lateralFrictionDir1.dot(pt.m_normalWorldOnB), 0, kTolerance);
	EXPECT_NEAR(pt.m_lateralFrictionDir1.length(), 1, kTolerance);

	object0.setFriction(btScalar(5));
	object1.setFriction(btScalar(5));
	EXPECT_EQ(btManifoldResult::calculateCombinedFriction(&object0, &object1), btScalar(10)) << "capped at 10";
}

TEST_F(ManifoldResultFixture, StiffnessAndDampingCombineWhenFlagged)
{
	object0.setContactStiffnessAndDamping(btScalar(1000), btScalar(0.2));
	object1.setContactStiffnessAndDamping(btScalar(3000), btScalar(0.5));
	btPersistentManifold manifold(&object0, &object1, 0, btScalar(0.1), btScalar(BT_LARGE_FLOAT));
	btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), -1, -1);
	btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), -1, -1);
	btManifoldResult result(&w0, &w1);
	result.setPersistentManifold(&manifold);
	result.addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), btScalar(-0.01));
	ASSERT_EQ(manifold.getNumContacts(), 1);
	const btManifoldPoint& pt = manifold.getContactPoint(0);
	EXPECT_TRUE(pt.m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING);
	// Springs in series: 1 / (1/1000 + 1/3000) = 750.
	EXPECT_NEAR(pt.m_combinedContactStiffness1, 750, 1e-2);
	EXPECT_NEAR(pt.m_combinedContactDamping1, 0.7, kTolerance);
}

TEST_F(ManifoldResultFixture, PointsGoToTheManifoldsBodyOrder)
{
	// The manifold is (object1, object0); the result is fed in (object0, object1) order.
	btPersistentManifold manifold(&object1, &object0, 0, btScalar(0.1), btScalar(BT_LARGE_FLOAT));
	btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), 3, 7);
	btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), 5, 9);
	btManifoldResult result(&w0, &w1);
	result.setPersistentManifold(&manifold);
	const btVector3 normal(0, 0, 1), pointOnB(0.2, 0.1, -0.3);
	const btScalar depth(-0.02);
	result.addContactPoint(normal, pointOnB, depth);
	ASSERT_EQ(manifold.getNumContacts(), 1);
	const btManifoldPoint& pt = manifold.getContactPoint(0);
	// A is the manifold's body 0 (object1): the point on A is pointOnB + normal * depth.
	const btVector3 pointOnA = pointOnB + normal * depth;
	EXPECT_LT((object1.getWorldTransform()(pt.m_localPointA) - pointOnA).length(), kTolerance);
	EXPECT_LT((object0.getWorldTransform()(pt.m_localPointB) - pointOnB).length(), kTolerance);
	EXPECT_LT((pt.m_positionWorldOnA - pointOnA).length(), kTolerance);
	EXPECT_EQ(pt.m_partId0, 5);
	EXPECT_EQ(pt.m_index0, 9);
	EXPECT_EQ(pt.m_partId1, 3);
	EXPECT_EQ(pt.m_index1, 7);
}

TEST_F(ManifoldResultFixture, ContactAddedCallbackRunsOnlyWithCustomMaterialFlag)
{
	gCallbackCalls = 0;
	ContactAddedCallback saved = gContactAddedCallback;
	gContactAddedCallback = recordingCallback;
	btPersistentManifold manifold(&object0, &object1, 0, btScalar(0.1), btScalar(BT_LARGE_FLOAT));
	btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), -1, -1);
	btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), -1, -1);
	btManifoldResult result(&w0, &w1);
	result.setPersistentManifold(&manifold);
	result.addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), btScalar(-0.01));
	EXPECT_EQ(gCallbackCalls, 0);
	object1.setCollisionFlags(object1.getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
	result.addContactPoint(btVector3(0, 1, 0), btVector3(0.5, 0, 0), btScalar(-0.01));
	gContactAddedCallback = saved;
	EXPECT_EQ(gCallbackCalls, 1);
	EXPECT_EQ(gCallbackWrap0, &w0);
	ASSERT_EQ(manifold.getNumContacts(), 2);
	EXPECT_EQ(manifold.getContactPoint(1).m_combinedFriction, btScalar(0.123)) << "the callback may edit the point";
}

TEST_F(ManifoldResultFixture, PointsBeyondBreakingThresholdAreIgnored)
{
	btPersistentManifold manifold(&object0, &object1, 0, btScalar(0.1), btScalar(BT_LARGE_FLOAT));
	btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), -1, -1);
	btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), -1, -1);
	btManifoldResult result(&w0, &w1);
	result.setPersistentManifold(&manifold);
	result.addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), btScalar(0.11));
	EXPECT_EQ(manifold.getNumContacts(), 0);
	result.m_closestPointDistanceThreshold = btScalar(0.05);
	result.addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), btScalar(0.11));
	EXPECT_EQ(manifold.getNumContacts(), 1) << "closest-point queries widen the reach";
	btManifoldResult noManifold(&w0, &w1);
	noManifold.addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), btScalar(-1));  // must not crash
}

TEST_F(ManifoldResultFixture, NonFiniteContactIsIgnored)
{
	btPersistentManifold manifold(&object0, &object1, 0, btScalar(0.1), btScalar(BT_LARGE_FLOAT));
	btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), -1, -1);
	btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), -1, -1);
	btManifoldResult result(&w0, &w1);
	result.setPersistentManifold(&manifold);
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(result.addContactPoint(btVector3(0, nan, 0), btVector3(0, 0, 0), btScalar(-0.01)), "assertion failed");
#else
	result.addContactPoint(btVector3(0, nan, 0), btVector3(0, 0, 0), btScalar(-0.01));
	result.addContactPoint(btVector3(0, 1, 0), btVector3(0, 0, 0), nan);
	EXPECT_EQ(manifold.getNumContacts(), 0);
#endif
}

namespace
{
using caliber_test::expectSamePoint;
using caliber_test::sameBits;

btScalar halfFriction(const btCollisionObject* body0, const btCollisionObject* body1)
{
	return btScalar(0.5) * body0->getFriction() + body1->getFriction();
}
}  // namespace

// addContactPoint must leave the manifold as Bullet's documented sequence does: build the point (local
// points from the bodies' transforms, world points, the four combined materials through the global
// callbacks, stiffness and damping when flagged, the friction anchor flag, part and index ids in the
// manifold's body order), then getCacheEntry, and replaceContactPoint for a match or addManifoldPoint with
// btPlaneSpace1's directions otherwise. The stored points start with every field set (impulses, CFM, ERP,
// motion, user data, friction directions, flags), so a field that the replacement forgot to keep or to
// reset shows. Varied: body order, materials, flags, a custom friction callback, matches and misses.
TEST_F(ManifoldResultFixture, AddContactPointStoresWhatReplaceOrAddManifoldPointWould)
{
	std::mt19937 random(1128);
	std::uniform_real_distribution<float> unit(-1, 1);
	const CalculateCombinedCallback savedFriction = gCalculateCombinedFrictionCallback;
	int replaced = 0, added = 0;
	for (int trial = 0; trial < 3000; ++trial)
	{
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

		const btScalar threshold(0.05);
		btPersistentManifold manifold(bodyA, bodyB, 0, threshold, btScalar(BT_LARGE_FLOAT));
		const int stored = 1 + trial % 4;
		for (int i = 0; i < stored; ++i)
		{
			btManifoldPoint point(btVector3(unit(random), unit(random), unit(random)) * btScalar(0.5),
			                      btVector3(unit(random), unit(random), unit(random)), btVector3(0, 1, 0),
			                      btScalar(-0.01));
			point.m_appliedImpulse = btScalar(1 + i);
			point.m_prevRHS = btScalar(2 + i);
			point.m_appliedImpulseLateral1 = btScalar(3 + i);
			point.m_appliedImpulseLateral2 = btScalar(4 + i);
			caliber_test::setDistinctSolverFields(point, i);
			manifold.addManifoldPoint(point);
		}
		btPersistentManifold reference = manifold;

		// A contact near a stored point (a match) or anywhere (usually a miss).
		const btVector3 normal = btVector3(unit(random), btScalar(1), unit(random)).normalized();
		const btScalar depth = btScalar(0.02) * unit(random);
		btVector3 pointOnB = btVector3(unit(random), unit(random), unit(random));
		if (trial % 4 != 3)
		{
			const btManifoldPoint& near = manifold.getContactPoint(trial % stored);
			const btVector3 pointOnA = bodyA->getWorldTransform()(near.m_localPointA) +
			                           btVector3(unit(random), unit(random), unit(random)) * btScalar(0.01);
			pointOnB = pointOnA - normal * depth;
		}

		btCollisionObjectWrapper w0(0, &shape, &object0, object0.getWorldTransform(), 3, 7);
		btCollisionObjectWrapper w1(0, &shape, &object1, object1.getWorldTransform(), 5, 9);
		btManifoldResult result(&w0, &w1);
		result.setPersistentManifold(&manifold);
		result.addContactPoint(normal, pointOnB, depth);

		// The reference, step by step through the manifold's own API.
		const btVector3 pointOnA = pointOnB + normal * depth;
		btManifoldPoint expected(bodyA->getWorldTransform().invXform(pointOnA),
		                         bodyB->getWorldTransform().invXform(pointOnB), normal, depth);
		expected.m_positionWorldOnA = pointOnA;
		expected.m_positionWorldOnB = pointOnB;
		expected.m_combinedFriction = gCalculateCombinedFrictionCallback(&object0, &object1);
		expected.m_combinedRestitution = gCalculateCombinedRestitutionCallback(&object0, &object1);
		expected.m_combinedRollingFriction = gCalculateCombinedRollingFrictionCallback(&object0, &object1);
		expected.m_combinedSpinningFriction = gCalculateCombinedSpinningFrictionCallback(&object0, &object1);
		const int flags = object0.getCollisionFlags() | object1.getCollisionFlags();
		if (flags & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING)
		{
			expected.m_combinedContactDamping1 = gCalculateCombinedContactDampingCallback(&object0, &object1);
			expected.m_combinedContactStiffness1 = gCalculateCombinedContactStiffnessCallback(&object0, &object1);
			expected.m_contactPointFlags |= BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING;
		}
		if (flags & btCollisionObject::CF_HAS_FRICTION_ANCHOR)
			expected.m_contactPointFlags |= BT_CONTACT_FLAG_FRICTION_ANCHOR;
		expected.m_partId0 = swapped ? 5 : 3;
		expected.m_partId1 = swapped ? 3 : 5;
		expected.m_index0 = swapped ? 9 : 7;
		expected.m_index1 = swapped ? 7 : 9;
		const int match = reference.getCacheEntry(expected);
		if (match >= 0)
		{
			reference.replaceContactPoint(expected, match);
			++replaced;
		}
		else
		{
			btPlaneSpace1(expected.m_normalWorldOnB, expected.m_lateralFrictionDir1, expected.m_lateralFrictionDir2);
			reference.addManifoldPoint(expected);
			++added;
		}
		ASSERT_EQ(manifold.getNumContacts(), reference.getNumContacts()) << trial;
		for (int i = 0; i < manifold.getNumContacts(); ++i)
			expectSamePoint(manifold.getContactPoint(i), reference.getContactPoint(i), trial);
	}
	gCalculateCombinedFrictionCallback = savedFriction;
	// Both ways were taken many times (not a test that cannot fail).
	EXPECT_GT(replaced, 1000);
	EXPECT_GT(added, 300);
}

TEST(CollisionObjectWrapper, ReferencesItsTransformsAndKeepsIdentifiers)
{
	btSphereShape shape(1);
	btCollisionObject object;
	btTransform world(btQuaternion::getIdentity(), btVector3(1, 2, 3));
	const btTransform pre(btQuaternion::getIdentity(), btVector3(0, 1, 0));
	btCollisionObjectWrapper plain(0, &shape, &object, world, 4, 5);
	btCollisionObjectWrapper child(&plain, &shape, &object, world, pre, -1, 2);
	EXPECT_EQ(plain.m_preTransform, nullptr);
	EXPECT_EQ(child.m_preTransform, &pre);
	EXPECT_EQ(child.m_parent, &plain);
	EXPECT_EQ(plain.m_partId, 4);
	EXPECT_EQ(plain.m_index, 5);
	EXPECT_EQ(plain.getCollisionShape(), &shape);
	EXPECT_EQ(plain.getCollisionObject(), &object);
	world.setOrigin(btVector3(7, 8, 9));
	EXPECT_EQ(plain.getWorldTransform().getOrigin(), btVector3(7, 8, 9)) << "the transform is referenced";
}
