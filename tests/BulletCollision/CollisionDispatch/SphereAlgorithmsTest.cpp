// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Sphere-sphere, sphere-box and sphere-triangle algorithms against analytic closest points.
#include <gtest/gtest.h>

#include "../NarrowPhaseCollision/NarrowPhaseTestUtil.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "TestDispatcher.h"

using caliber_dispatch_test::PairFixture;
using caliber_dispatch_test::TestDispatcher;
using caliber_narrowphase_test::Random;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// Distances and points are computed from O(1) coordinates in a few float operations.
const btScalar kTolerance = btScalar(2e-5);

bool manifoldIsFinite(const btPersistentManifold* manifold)
{
	for (int i = 0; i < manifold->getNumContacts(); ++i)
	{
		const btManifoldPoint& pt = manifold->getContactPoint(i);
		if (!caliber_narrowphase_test::isFinite(pt.m_positionWorldOnA) ||
		    !caliber_narrowphase_test::isFinite(pt.m_positionWorldOnB) ||
		    !caliber_narrowphase_test::isFinite(pt.m_normalWorldOnB) || !btIsFinite(pt.m_distance1))
			return false;
	}
	return true;
}
}  // namespace

TEST(SphereAlgorithms, SphereSphereDepthAndNormalMatchAnalytic)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	Random random(11);
	for (int trial = 0; trial < 100; ++trial)
	{
		btSphereShape sphere0(random.uniform(btScalar(0.1), btScalar(2)));
		btSphereShape sphere1(random.uniform(btScalar(0.1), btScalar(2)));
		const btVector3 c1 = random.vector(5);
		const btVector3 direction = random.unitVector();
		// Centres from deep overlap to just beyond the breaking threshold.
		const btScalar gap =
		    random.uniform(-btScalar(0.8), btScalar(0.1)) * btMin(sphere0.getRadius(), sphere1.getRadius());
		const btVector3 c0 = c1 + direction * (sphere0.getRadius() + sphere1.getRadius() + gap);
		PairFixture pair(dispatcher, &sphere0, btTransform(random.rotation(), c0), &sphere1,
		                 btTransform(random.rotation(), c1));
		btPersistentManifold* manifold = pair.process();
		ASSERT_NE(manifold, nullptr);
		const bool expectContact = gap <= manifold->getContactBreakingThreshold();
		ASSERT_EQ(manifold->getNumContacts(), expectContact ? 1 : 0) << "gap " << gap;
		if (!expectContact) continue;
		const btManifoldPoint& pt = manifold->getContactPoint(0);
		EXPECT_NEAR(pt.getDistance(), gap, kTolerance * 10);
		EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, direction, kTolerance * 10));
		EXPECT_TRUE(vectorsNear(pt.getPositionWorldOnB(), c1 + direction * sphere1.getRadius(), kTolerance * 10));
		EXPECT_TRUE(vectorsNear(pt.getPositionWorldOnA(), c0 - direction * sphere0.getRadius(), kTolerance * 10));
		// A second frame keeps exactly one point.
		manifold = pair.process();
		EXPECT_EQ(manifold->getNumContacts(), 1);
	}
}

TEST(SphereAlgorithms, SphereBoxMatchesClosestPointOnBox)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	Random random(12);
	const btVector3 halfExtents(1, btScalar(0.5), 2);
	btBoxShape box(halfExtents);
	int faceCases = 0, edgeCases = 0, cornerCases = 0, insideCases = 0;
	for (int trial = 0; trial < 400; ++trial)
	{
		btSphereShape sphere(random.uniform(btScalar(0.05), btScalar(0.6)));
		const btTransform boxTransform = random.transform(3);
		const btScalar reach = sphere.getRadius() + btScalar(0.05);
		const btVector3 local(random.uniform(-halfExtents.x() - reach, halfExtents.x() + reach),
		                      random.uniform(-halfExtents.y() - reach, halfExtents.y() + reach),
		                      random.uniform(-halfExtents.z() - reach, halfExtents.z() + reach));
		const btVector3 centre = boxTransform(local);
		// Reference: outside, the clamped point; inside, the nearest face plane.
		int clampedAxes = 0;
		for (int i = 0; i < 3; ++i) clampedAxes += btFabs(local[i]) > halfExtents[i] ? 1 : 0;
		btVector3 expectedPoint, expectedNormal;
		btScalar expectedDistance;
		if (clampedAxes > 0)
		{
			expectedPoint = caliber_narrowphase_test::closestPointOnBox(halfExtents, boxTransform, centre);
			const btScalar d = (centre - expectedPoint).length();
			if (d < btScalar(1e-3)) continue;  // normal ill-defined this close to the surface
			expectedNormal = (centre - expectedPoint) / d;
			expectedDistance = d - sphere.getRadius();
			(clampedAxes == 1 ? faceCases : clampedAxes == 2 ? edgeCases : cornerCases)++;
		}
		else
		{
			int axis = 0;
			btScalar best = BT_LARGE_FLOAT;
			for (int i = 0; i < 3; ++i)
			{
				const btScalar gap = halfExtents[i] - btFabs(local[i]);
				if (gap < best)
				{
					best = gap;
					axis = i;
				}
			}
			btVector3 localNormal(0, 0, 0);
			localNormal[axis] = local[axis] < 0 ? btScalar(-1) : btScalar(1);
			btVector3 localPoint = local;
			localPoint[axis] = localNormal[axis] * halfExtents[axis];
			expectedPoint = boxTransform(localPoint);
			expectedNormal = boxTransform.getBasis() * localNormal;
			expectedDistance = -best - sphere.getRadius();
			++insideCases;
		}

		const bool sphereFirst = (trial % 2) == 0;
		PairFixture pair(dispatcher, sphereFirst ? static_cast<btCollisionShape*>(&sphere) : &box,
		                 sphereFirst ? btTransform(random.rotation(), centre) : boxTransform,
		                 sphereFirst ? static_cast<btCollisionShape*>(&box) : &sphere,
		                 sphereFirst ? boxTransform : btTransform(random.rotation(), centre));
		btPersistentManifold* manifold = pair.process();
		ASSERT_NE(manifold, nullptr);
		const bool expectContact = expectedDistance <= manifold->getContactBreakingThreshold();
		ASSERT_EQ(manifold->getNumContacts(), expectContact ? 1 : 0) << "distance " << expectedDistance;
		if (!expectContact) continue;
		// The manifold is always (sphere, box): A is the sphere, B the box.
		EXPECT_EQ(manifold->getBody0(), sphereFirst ? &pair.m_object0 : &pair.m_object1);
		const btManifoldPoint& pt = manifold->getContactPoint(0);
		EXPECT_NEAR(pt.getDistance(), expectedDistance, kTolerance * 10);
		EXPECT_TRUE(vectorsNear(pt.getPositionWorldOnB(), expectedPoint, kTolerance * 10));
		EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, expectedNormal, btScalar(1e-3)));
	}
	EXPECT_GT(faceCases, 10);
	EXPECT_GT(edgeCases, 10);
	EXPECT_GT(cornerCases, 3);
	EXPECT_GT(insideCases, 10);
}

TEST(SphereAlgorithms, SphereTriangleFaceEdgeAndVertexRegions)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btTriangleShape triangle(btVector3(0, 0, 0), btVector3(2, 0, 0), btVector3(0, 2, 0));
	btSphereShape sphere(btScalar(0.5));
	const btTransform triangleTransform(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.8)),
	                                    btVector3(1, -2, 0.5));
	struct Case
	{
		btVector3 centre;   // in the triangle's frame
		btVector3 closest;  // closest point of the triangle, analytic
	};
	const Case cases[] = {
	    {btVector3(0.5, 0.5, 0.3), btVector3(0.5, 0.5, 0)},   // face, front
	    {btVector3(0.5, 0.5, -0.3), btVector3(0.5, 0.5, 0)},  // face, back (two-sided)
	    {btVector3(1, -0.3, 0.1), btVector3(1, 0, 0)},        // edge v0-v1
	    {btVector3(1.2, 1.2, 0.1), btVector3(1, 1, 0)},       // edge v1-v2
	    {btVector3(-0.2, -0.2, 0.2), btVector3(0, 0, 0)},     // vertex v0
	    {btVector3(2.2, -0.1, -0.1), btVector3(2, 0, 0)},     // vertex v1
	};
	for (const Case& c : cases)
	{
		for (int order = 0; order < 2; ++order)
		{
			const btVector3 centreWorld = triangleTransform(c.centre);
			const btTransform sphereTransform(btQuaternion::getIdentity(), centreWorld);
			PairFixture pair(dispatcher, order == 0 ? static_cast<btCollisionShape*>(&sphere) : &triangle,
			                 order == 0 ? sphereTransform : triangleTransform,
			                 order == 0 ? static_cast<btCollisionShape*>(&triangle) : &sphere,
			                 order == 0 ? triangleTransform : sphereTransform);
			btPersistentManifold* manifold = pair.process();
			ASSERT_NE(manifold, nullptr);
			ASSERT_EQ(manifold->getNumContacts(), 1);
			const btManifoldPoint& pt = manifold->getContactPoint(0);
			const btVector3 closestWorld = triangleTransform(c.closest);
			const btScalar d = (centreWorld - closestWorld).length();
			const btVector3 towardsSphere = (centreWorld - closestWorld) / d;
			EXPECT_NEAR(pt.getDistance(), d - sphere.getRadius(), kTolerance * 10);
			if (order == 0)
			{
				EXPECT_TRUE(vectorsNear(pt.getPositionWorldOnB(), closestWorld, kTolerance * 10));
				EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, towardsSphere, kTolerance * 10));
			}
			else
			{
				// (triangle, sphere): B is the sphere, the normal points at the triangle.
				EXPECT_TRUE(vectorsNear(pt.getPositionWorldOnA(), closestWorld, kTolerance * 10));
				EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, -towardsSphere, kTolerance * 10));
			}
		}
	}
}

TEST(SphereAlgorithms, DegenerateSpheresAndBoxesGiveFiniteContacts)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btSphereShape point(0);
	btSphereShape sphere(1);
	btBoxShape box(btVector3(1, 1, 1));
	btBoxShape flat(btVector3(0, 0, 0));
	// Zero-radius sphere inside a box: nearest face at depth -(1 - 0.25).
	PairFixture inBox(dispatcher, &point, btTransform(btQuaternion::getIdentity(), btVector3(0.25, 0, 0)), &box,
	                  btTransform::getIdentity());
	btPersistentManifold* manifold = inBox.process();
	ASSERT_EQ(manifold->getNumContacts(), 1);
	EXPECT_NEAR(manifold->getContactPoint(0).getDistance(), -0.75, kTolerance);
	// Concentric spheres and a sphere centred in a box: finite, with the documented fallback normal.
	PairFixture concentric(dispatcher, &sphere, btTransform::getIdentity(), &sphere, btTransform::getIdentity());
	manifold = concentric.process();
	ASSERT_EQ(manifold->getNumContacts(), 1);
	EXPECT_TRUE(manifoldIsFinite(manifold));
	EXPECT_NEAR(manifold->getContactPoint(0).getDistance(), -2, kTolerance);
	PairFixture centred(dispatcher, &sphere, btTransform::getIdentity(), &box, btTransform::getIdentity());
	manifold = centred.process();
	ASSERT_EQ(manifold->getNumContacts(), 1);
	EXPECT_TRUE(manifoldIsFinite(manifold));
	EXPECT_NEAR(manifold->getContactPoint(0).getDistance(), -2, kTolerance);
	// Zero-size box touched by a sphere.
	PairFixture zeroBox(dispatcher, &sphere, btTransform(btQuaternion::getIdentity(), btVector3(0, 0.99, 0)), &flat,
	                    btTransform::getIdentity());
	manifold = zeroBox.process();
	EXPECT_TRUE(manifoldIsFinite(manifold));
	// Degenerate (collinear) triangle: treated as its edges.
	btTriangleShape sliver(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(2, 0, 0));
	PairFixture onSliver(dispatcher, &sphere, btTransform(btQuaternion::getIdentity(), btVector3(1.5, 0.9, 0)), &sliver,
	                     btTransform::getIdentity());
	manifold = onSliver.process();
	ASSERT_EQ(manifold->getNumContacts(), 1);
	EXPECT_TRUE(manifoldIsFinite(manifold));
	EXPECT_NEAR(manifold->getContactPoint(0).getDistance(), -0.1, kTolerance);
}

TEST(SphereAlgorithms, NonFiniteTransformGivesNoPoints)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btSphereShape sphere(1);
	btBoxShape box(btVector3(1, 1, 1));
	PairFixture pair(dispatcher, &sphere, btTransform(btQuaternion::getIdentity(), btVector3(0, 1.5, 0)), &box,
	                 btTransform::getIdentity());
	ASSERT_EQ(pair.process()->getNumContacts(), 1);
	// setWorldTransform refuses NaN, but the reference getter lets it through; algorithms must cope.
	pair.m_object0.getWorldTransform().getOrigin().setY(std::numeric_limits<btScalar>::quiet_NaN());
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(pair.process(), "assertion failed");
#else
	btPersistentManifold* manifold = pair.process();
	EXPECT_EQ(manifold->getNumContacts(), 0);
#endif
}
