// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Convex-plane, box-box and convex-convex algorithms: full manifolds in one frame and agreement with GJK.
#include <gtest/gtest.h>

#include "../NarrowPhaseCollision/NarrowPhaseTestUtil.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "TestDispatcher.h"

using caliber_dispatch_test::PairFixture;
using caliber_dispatch_test::TestDispatcher;
using caliber_narrowphase_test::Random;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// Contacts of unit-sized shapes computed with a handful of float operations.
const btScalar kTolerance = btScalar(1e-4);

// For each of the expected corner points, some manifold point lies on it (on body A).
void expectCornersCovered(const btPersistentManifold* manifold, const btVector3* corners, int numCorners,
                          btScalar tolerance)
{
	for (int c = 0; c < numCorners; ++c)
	{
		btScalar best = BT_LARGE_FLOAT;
		for (int i = 0; i < manifold->getNumContacts(); ++i)
			best = btMin(best, (manifold->getContactPoint(i).getPositionWorldOnA() - corners[c]).length());
		EXPECT_LT(best, tolerance) << "corner " << c << " (" << corners[c].x() << ", " << corners[c].y() << ", "
		                           << corners[c].z() << ") has no contact point";
	}
}

btTransform at0(btScalar x) { return btTransform(btQuaternion::getIdentity(), btVector3(x, 0, 0)); }

btConvexHullShape* makeHullBox(const btVector3& h)
{
	btConvexHullShape* hull = new btConvexHullShape();
	for (int i = 0; i < 8; ++i)
		hull->addPoint(btVector3((i & 1) ? -h.x() : h.x(), (i & 2) ? -h.y() : h.y(), (i & 4) ? -h.z() : h.z()), false);
	hull->recalcLocalAabb();
	return hull;
}

// The closest points from a GJK detector made for this one query (no state from earlier queries).
btPointCollector freshClosestPoints(const btConvexShape* a, const btTransform& ta, const btConvexShape* b,
                                    const btTransform& tb)
{
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkPairDetector gjk(a, b, &simplex, &epa);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = ta;
	input.m_transformB = tb;
	btPointCollector reference;
	gjk.getClosestPoints(input, reference, 0);
	return reference;
}
}  // namespace

TEST(ConvexAlgorithms, BoxRestingOnPlaneGetsFourCornersInFirstFrame)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	const btVector3 halfExtents(1, btScalar(0.5), btScalar(0.75));
	btBoxShape box(halfExtents);
	const btVector3 planeNormal = btVector3(btScalar(0.2), 1, btScalar(-0.1)).normalized();
	btStaticPlaneShape plane(planeNormal, btScalar(0.3));
	Random random(21);
	for (int trial = 0; trial < 20; ++trial)
	{
		// The box's local y axis along the plane normal, spun randomly about it, 0.01 into the plane.
		const btScalar penetration = btScalar(0.01);
		const btQuaternion align = shortestArcQuat(btVector3(0, 1, 0), planeNormal);
		const btQuaternion spin(planeNormal, random.uniform(-SIMD_PI, SIMD_PI));
		const btVector3 onPlane =
		    planeNormal * btScalar(0.3) + random.vector(2) - planeNormal * random.vector(2).dot(planeNormal);
		const btVector3 centre = onPlane - planeNormal * planeNormal.dot(onPlane - planeNormal * btScalar(0.3)) +
		                         planeNormal * (halfExtents.y() - penetration);
		const btTransform boxTransform(spin * align, centre);
		const bool boxFirst = (trial % 2) == 0;
		PairFixture pair(dispatcher, boxFirst ? static_cast<btCollisionShape*>(&box) : &plane,
		                 boxFirst ? boxTransform : btTransform::getIdentity(),
		                 boxFirst ? static_cast<btCollisionShape*>(&plane) : &box,
		                 boxFirst ? btTransform::getIdentity() : boxTransform);
		btPersistentManifold* manifold = pair.process();
		ASSERT_NE(manifold, nullptr);
		ASSERT_EQ(manifold->getNumContacts(), 4) << "trial " << trial;
		EXPECT_EQ(manifold->getBody0(), boxFirst ? &pair.m_object0 : &pair.m_object1) << "manifold is (convex, plane)";
		btVector3 corners[4];
		for (int c = 0; c < 4; ++c)
			corners[c] = boxTransform(btVector3((c & 1) ? -halfExtents.x() : halfExtents.x(), -halfExtents.y(),
			                                    (c & 2) ? -halfExtents.z() : halfExtents.z()));
		expectCornersCovered(manifold, corners, 4, kTolerance * 10);
		for (int i = 0; i < 4; ++i)
		{
			const btManifoldPoint& pt = manifold->getContactPoint(i);
			EXPECT_NEAR(pt.getDistance(), -penetration, kTolerance);
			EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, planeNormal, kTolerance));
			EXPECT_NEAR(planeNormal.dot(pt.getPositionWorldOnB()), btScalar(0.3), kTolerance) << "point on the plane";
		}
	}
}

TEST(ConvexAlgorithms, HullRestingOnPlaneCountsItsMargin)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btConvexHullShape* hull = makeHullBox(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	const btScalar margin = hull->getMargin();
	btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
	// Core corners 0.5 below the centre, plus the margin: the surface is 0.5 + margin below.
	const btScalar penetration = btScalar(0.005);
	PairFixture pair(dispatcher, hull,
	                 btTransform(btQuaternion::getIdentity(), btVector3(3, btScalar(0.5) + margin - penetration, 1)),
	                 &plane, btTransform::getIdentity());
	btPersistentManifold* manifold = pair.process();
	ASSERT_EQ(manifold->getNumContacts(), 4);
	for (int i = 0; i < 4; ++i) EXPECT_NEAR(manifold->getContactPoint(i).getDistance(), -penetration, kTolerance);
	delete hull;
}

TEST(ConvexAlgorithms, CylinderOnPlaneGetsRimPointsWithMultipoint)
{
	btDefaultCollisionConfiguration config;
	config.setPlaneConvexMultipointIterations(4, 4);
	TestDispatcher dispatcher(&config);
	btCylinderShape cylinder(btVector3(btScalar(0.5), 1, btScalar(0.5)));
	btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
	PairFixture pair(dispatcher, &cylinder, btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.99), 0)),
	                 &plane, btTransform::getIdentity());
	btPersistentManifold* manifold = pair.process();
	ASSERT_GE(manifold->getNumContacts(), 3) << "tilted supports should find several rim points";
	for (int i = 0; i < manifold->getNumContacts(); ++i)
	{
		const btManifoldPoint& pt = manifold->getContactPoint(i);
		// Every point is a real point of the bottom disc: depth 0.01, radius at most 0.5.
		EXPECT_NEAR(pt.getDistance(), -0.01, kTolerance);
		const btVector3 p = pt.getPositionWorldOnA();
		EXPECT_LE(btSqrt(p.x() * p.x() + p.z() * p.z()), btScalar(0.5) + kTolerance);
	}
}

TEST(ConvexAlgorithms, BoxRestingOnBoxGetsFourPointsInFirstFrame)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btBoxShape top(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	btBoxShape bottom(btVector3(2, btScalar(0.5), 2));
	const btScalar penetration = btScalar(0.01);
	const btTransform topTransform(btQuaternion(btVector3(0, 1, 0), btScalar(0.3)),
	                               btVector3(btScalar(0.2), 1 - penetration, btScalar(-0.1)));
	PairFixture pair(dispatcher, &top, topTransform, &bottom, btTransform::getIdentity());
	btPersistentManifold* manifold = pair.process();
	ASSERT_EQ(manifold->getNumContacts(), 4);
	btVector3 corners[4];
	for (int c = 0; c < 4; ++c)
		corners[c] = topTransform(btVector3((c & 1) ? -btScalar(0.5) : btScalar(0.5), -btScalar(0.5),
		                                    (c & 2) ? -btScalar(0.5) : btScalar(0.5)));
	expectCornersCovered(manifold, corners, 4, kTolerance * 10);
	for (int i = 0; i < 4; ++i)
	{
		EXPECT_NEAR(manifold->getContactPoint(i).getDistance(), -penetration, kTolerance);
		EXPECT_TRUE(vectorsNear(manifold->getContactPoint(i).m_normalWorldOnB, btVector3(0, 1, 0), kTolerance));
	}
}

TEST(ConvexAlgorithms, PolyhedralHullsGetFullManifoldByClipping)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btConvexHullShape* top = makeHullBox(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	btConvexHullShape* bottom = makeHullBox(btVector3(2, btScalar(0.5), 2));
	ASSERT_TRUE(top->initializePolyhedralFeatures());
	ASSERT_TRUE(bottom->initializePolyhedralFeatures());
	const btScalar margins = top->getMargin() + bottom->getMargin();
	const btScalar penetration = btScalar(0.01);
	for (int sat = 0; sat < 2; ++sat)
	{
		const btTransform topTransform(btQuaternion(btVector3(0, 1, 0), btScalar(0.5)),
		                               btVector3(btScalar(-0.3), 1 + margins - penetration, btScalar(0.4)));
		PairFixture pair(dispatcher, top, topTransform, bottom, btTransform::getIdentity());
		pair.m_enableSat = sat == 1;
		btPersistentManifold* manifold = pair.process();
		ASSERT_EQ(manifold->getNumContacts(), 4) << "sat " << sat;
		for (int i = 0; i < 4; ++i)
		{
			// Depth with the margins put back agrees with GJK's (margin-inclusive) distance.
			EXPECT_NEAR(manifold->getContactPoint(i).getDistance(), -penetration, btScalar(1e-3));
			EXPECT_TRUE(vectorsNear(manifold->getContactPoint(i).m_normalWorldOnB, btVector3(0, 1, 0), btScalar(1e-3)));
		}
	}
	delete top;
	delete bottom;
}

TEST(ConvexAlgorithms, ConvexConvexAgreesWithGjkPairDetector)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	Random random(31);
	btCapsuleShape capsule(btScalar(0.4), btScalar(1.2));
	btConeShape cone(btScalar(0.6), btScalar(1.5));
	btCylinderShape cylinder(btVector3(btScalar(0.5), btScalar(0.7), btScalar(0.5)));
	btConvexShape* shapes[3] = {&capsule, &cone, &cylinder};
	int contacts = 0;
	for (int trial = 0; trial < 60; ++trial)
	{
		btConvexShape* a = shapes[trial % 3];
		btConvexShape* b = shapes[(trial / 3) % 3];
		const btTransform ta = random.transform(btScalar(0.2));
		const btTransform tb(random.rotation(),
		                     ta.getOrigin() + random.unitVector() * random.uniform(btScalar(0.5), btScalar(2)));

		// Independent run of the detector the algorithm is built on.
		const btPointCollector reference = freshClosestPoints(a, ta, b, tb);

		PairFixture pair(dispatcher, a, ta, b, tb);
		btPersistentManifold* manifold = pair.process();
		ASSERT_NE(manifold, nullptr);
		const bool expectContact =
		    reference.m_hasResult && reference.m_distance <= manifold->getContactBreakingThreshold();
		ASSERT_EQ(manifold->getNumContacts(), expectContact ? 1 : 0) << "reference distance " << reference.m_distance;
		if (!expectContact) continue;
		++contacts;
		const btManifoldPoint& pt = manifold->getContactPoint(0);
		// Same detector, same inputs: only float noise separates them.
		EXPECT_NEAR(pt.getDistance(), reference.m_distance, btScalar(1e-4));
		EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, reference.m_normalOnBInWorld, btScalar(1e-3)));
		EXPECT_TRUE(vectorsNear(pt.getPositionWorldOnB(), reference.m_pointInWorld, btScalar(1e-3)));
	}
	EXPECT_GT(contacts, 20);
}

TEST(ConvexAlgorithms, ConvexConvexStartingWhereTheLastStepEndedAgreesWithAFreshStart)
{
	// A pair's GJK starts from the axis its last step ended on. One pair is moved to unrelated placements
	// step after step (so that the axis it starts from is often wrong, even opposite), and must give what
	// a fresh detector gives at each placement.
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	Random random(57);
	btCapsuleShape capsule(btScalar(0.4), btScalar(1.2));
	btCylinderShape cylinder(btVector3(btScalar(0.5), btScalar(0.7), btScalar(0.5)));
	btConvexHullShape* hull = makeHullBox(btVector3(btScalar(0.6), btScalar(0.3), btScalar(0.45)));
	btConvexShape* shapes[3] = {&capsule, &cylinder, hull};
	for (int pairing = 0; pairing < 3; ++pairing)
	{
		btConvexShape* a = shapes[pairing];
		btConvexShape* b = shapes[(pairing + 1) % 3];
		PairFixture pair(dispatcher, a, btTransform::getIdentity(), b, btTransform::getIdentity());
		int contacts = 0, separated = 0;
		for (int step = 0; step < 80; ++step)
		{
			const btTransform ta = random.transform(btScalar(0.2));
			const btTransform tb(random.rotation(),
			                     ta.getOrigin() + random.unitVector() * random.uniform(btScalar(0.5), btScalar(2)));
			const btPointCollector reference = freshClosestPoints(a, ta, b, tb);

			pair.m_object0.setWorldTransform(ta);
			pair.m_object1.setWorldTransform(tb);
			btPersistentManifold* manifold = pair.process();
			ASSERT_NE(manifold, nullptr);
			const bool expectContact =
			    reference.m_hasResult && reference.m_distance <= manifold->getContactBreakingThreshold();
			ASSERT_EQ(manifold->getNumContacts(), expectContact ? 1 : 0)
			    << "pairing " << pairing << " step " << step << " reference distance " << reference.m_distance;
			if (!expectContact)
			{
				++separated;
				continue;
			}
			++contacts;
			const btManifoldPoint& pt = manifold->getContactPoint(0);
			// Each run stops once GJK's bounds agree to a relative gap of 256 ulps, which on curved shapes
			// leaves its normal free by sqrt(2 * 256 * epsilon) (~0.008 rad in float), or once a support
			// point repeats a vertex within 1e-6 of the coordinates' size (~4 here), an angle of 1e-6 * 4 /
			// 0.4 on the smallest radius, 0.4 (the bound in double builds). Two runs from different starts
			// may differ by twice the sum. The distances differ by the gap itself.
			const btScalar normalTolerance =
			    btScalar(2) * (btSqrt(btScalar(2 * 256) * SIMD_EPSILON) + btScalar(1e-6) * btScalar(4) / btScalar(0.4));
			EXPECT_NEAR(pt.getDistance(), reference.m_distance, btScalar(1e-4)) << "pairing " << pairing;
			EXPECT_TRUE(vectorsNear(pt.m_normalWorldOnB, reference.m_normalOnBInWorld, normalTolerance))
			    << "pairing " << pairing << " step " << step;
			manifold->clearManifold();
		}
		EXPECT_GT(contacts, 20) << "pairing " << pairing;
		EXPECT_GT(separated, 10) << "pairing " << pairing;
	}
	delete hull;
}

TEST(ConvexAlgorithms, ConvexConvexMultipointAddsPointsOfTheSameContact)
{
	btDefaultCollisionConfiguration config;
	config.setConvexConvexMultipointIterations(4, 4);
	TestDispatcher dispatcher(&config);
	btCylinderShape cylinder(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	btCapsuleShape capsule(btScalar(0.3), btScalar(2));
	// A capsule lying flat (axis along x) on top of a cylinder's flat face.
	const btTransform capsuleTransform(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI), btVector3(0, btScalar(0.79), 0));
	PairFixture pair(dispatcher, &capsule, capsuleTransform, &cylinder, btTransform::getIdentity());
	btPersistentManifold* manifold = pair.process();
	ASSERT_GE(manifold->getNumContacts(), 2);
	for (int i = 0; i < manifold->getNumContacts(); ++i)
	{
		EXPECT_NEAR(manifold->getContactPoint(i).getDistance(), -0.01, btScalar(2e-3));
		EXPECT_NEAR(manifold->getContactPoint(i).getPositionWorldOnB().y(), 0.5, btScalar(2e-3));
	}
}

TEST(ConvexAlgorithms, NonFiniteTransformGivesNoPointsForPlaneAndConvex)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btBoxShape box(btVector3(1, 1, 1));
	btCapsuleShape capsule(btScalar(0.5), 1);
	btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
	PairFixture onPlane(dispatcher, &box, btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.99), 0)),
	                    &plane, btTransform::getIdentity());
	PairFixture convex(dispatcher, &capsule, btTransform(btQuaternion::getIdentity(), btVector3(0, 1.5, 0)), &box,
	                   btTransform::getIdentity());
	ASSERT_EQ(onPlane.process()->getNumContacts(), 4);
	ASSERT_EQ(convex.process()->getNumContacts(), 1);
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	onPlane.m_object0.getWorldTransform().getBasis()[1].setX(nan);
	convex.m_object0.getWorldTransform().getOrigin().setZ(nan);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(onPlane.process(), "assertion failed");
	EXPECT_DEATH(convex.process(), "assertion failed");
#else
	EXPECT_EQ(onPlane.process()->getNumContacts(), 0);
	EXPECT_EQ(convex.process()->getNumContacts(), 0);
#endif
}

TEST(ConvexAlgorithms, ZeroSizeBoxGivesFiniteContacts)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btBoxShape point(btVector3(0, 0, 0));
	btBoxShape box(btVector3(1, 1, 1));
	btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
	PairFixture onPlane(dispatcher, &point, btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(-0.01), 0)),
	                    &plane, btTransform::getIdentity());
	PairFixture onBox(dispatcher, &point, btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(0.99), 0)),
	                  &box, btTransform::getIdentity());
	for (PairFixture* pair : {&onPlane, &onBox})
	{
		btPersistentManifold* manifold = pair->process();
		ASSERT_GE(manifold->getNumContacts(), 1);
		for (int i = 0; i < manifold->getNumContacts(); ++i)
		{
			const btManifoldPoint& pt = manifold->getContactPoint(i);
			EXPECT_TRUE(caliber_narrowphase_test::isFinite(pt.m_normalWorldOnB));
			EXPECT_TRUE(btIsFinite(pt.getDistance()));
		}
	}
}

TEST(ConvexAlgorithms, ConvexConvexTimeOfImpactOfSweptSpheres)
{
	btDefaultCollisionConfiguration config;
	TestDispatcher dispatcher(&config);
	btSphereShape ball(btScalar(0.5));
	btBoxShape wall(btVector3(1, 1, 1));
	// The closest-points table maps sphere-box to convex-convex.
	PairFixture pair(dispatcher, &ball, at0(-5), &wall, btTransform::getIdentity(), BT_CLOSEST_POINT_ALGORITHMS);
	pair.m_object0.setInterpolationWorldTransform(at0(5));
	pair.m_object1.setInterpolationWorldTransform(btTransform::getIdentity());
	pair.m_object0.setCcdSweptSphereRadius(btScalar(0.5));
	pair.m_object1.setCcdSweptSphereRadius(btScalar(0.2));
	btDispatcherInfo info;
	// Ball centre reaches the box face (x = -1 - 0.5) after 3.5 of 10 units; the ball against the box's
	// swept sphere (radius 0.2) would only hit at x = -0.7 (fraction 0.43), so 0.35 wins.
	const btScalar fraction = pair.m_algorithm->calculateTimeOfImpact(&pair.m_object0, &pair.m_object1, info, 0);
	// The cast converges to within its tolerance of the surface (a few thousandths of the 10-unit sweep).
	EXPECT_NEAR(fraction, 0.35, 5e-3);
	EXPECT_NEAR(pair.m_object0.getHitFraction(), fraction, 1e-6);
	EXPECT_NEAR(pair.m_object1.getHitFraction(), fraction, 1e-6);

	// Motion below both CCD thresholds: no cast.
	pair.m_object0.setHitFraction(1);
	pair.m_object0.setCcdMotionThreshold(100);
	pair.m_object1.setCcdMotionThreshold(100);
	EXPECT_EQ(pair.m_algorithm->calculateTimeOfImpact(&pair.m_object0, &pair.m_object1, info, 0), btScalar(1));
	EXPECT_EQ(pair.m_object0.getHitFraction(), btScalar(1));
}
