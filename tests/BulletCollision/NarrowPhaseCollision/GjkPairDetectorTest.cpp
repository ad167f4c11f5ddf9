// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btMinkowskiPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "NarrowPhaseTestUtil.h"

using caliber_narrowphase_test::isFinite;
using caliber_narrowphase_test::Random;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// Placements are within a few units. GJK stops once its distance bounds agree to 256 ulps (relative),
// and polytopes and points (box, capsule and sphere cores) are reached exactly, so results carry only
// rounding of a few hundred operations on values of order 10.
const btScalar kDistanceTolerance = btScalar(2048) * SIMD_EPSILON * btScalar(10);
// EPA on polytopes ends on an exact face; its witnesses come from barycentric weights on that face.
const btScalar kPenetrationTolerance = btScalar(4096) * SIMD_EPSILON * btScalar(10);

struct Query
{
	btPointCollector result;
	int lastUsedMethod = 0;
};

Query closestPoints(const btConvexShape& a, const btTransform& ta, const btConvexShape& b, const btTransform& tb,
                    btConvexPenetrationDepthSolver* depthSolver = nullptr)
{
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkPairDetector detector(&a, &b, &simplex, depthSolver ? depthSolver : &epa);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = ta;
	input.m_transformB = tb;
	Query query;
	detector.getClosestPoints(input, query.result, nullptr);
	query.lastUsedMethod = detector.m_lastUsedMethod;
	return query;
}

btTransform at(const btVector3& origin) { return btTransform(btQuaternion::getIdentity(), origin); }
}  // namespace

TEST(GjkPairDetector, SeparatedSpheresGiveCentreDistanceLessRadii)
{
	Random rng(101);
	for (int trial = 0; trial < 200; ++trial)
	{
		const btScalar ra = rng.uniform(btScalar(0.1), 2), rb = rng.uniform(btScalar(0.1), 2);
		btSphereShape a(ra), b(rb);
		const btVector3 cb = rng.vector(3);
		const btVector3 ca = cb + rng.unitVector() * (ra + rb + rng.uniform(btScalar(0.01), 3));
		const Query q = closestPoints(a, btTransform(rng.rotation(), ca), b, at(cb));
		ASSERT_TRUE(q.result.m_hasResult) << trial;
		const btVector3 n = (ca - cb).normalized();
		EXPECT_NEAR(q.result.m_distance, (ca - cb).length() - ra - rb, kDistanceTolerance) << trial;
		EXPECT_TRUE(vectorsNear(q.result.m_normalOnBInWorld, n, kDistanceTolerance)) << trial;
		EXPECT_TRUE(vectorsNear(q.result.m_pointInWorld, cb + n * rb, kDistanceTolerance)) << trial;
	}
}

TEST(GjkPairDetector, OverlappingSpheresGiveNegativeDistanceAndNormalFromBToA)
{
	Random rng(102);
	for (int trial = 0; trial < 200; ++trial)
	{
		const btScalar ra = rng.uniform(btScalar(0.2), 2), rb = rng.uniform(btScalar(0.2), 2);
		btSphereShape a(ra), b(rb);
		const btVector3 cb = rng.vector(3);
		const btScalar gap = rng.uniform(btScalar(0.05), btScalar(0.95)) * (ra + rb);
		const btVector3 ca = cb + rng.unitVector() * gap;
		const Query q = closestPoints(a, at(ca), b, at(cb));
		ASSERT_TRUE(q.result.m_hasResult) << trial;
		const btVector3 n = (ca - cb).normalized();
		EXPECT_NEAR(q.result.m_distance, gap - ra - rb, kDistanceTolerance) << trial;
		EXPECT_LT(q.result.m_distance, 0) << trial;
		EXPECT_TRUE(vectorsNear(q.result.m_normalOnBInWorld, n, kDistanceTolerance)) << trial;
		EXPECT_TRUE(vectorsNear(q.result.m_pointInWorld, cb + n * rb, kDistanceTolerance)) << trial;
	}
}

TEST(GjkPairDetector, ConcentricSpheresUseTheDepthSolver)
{
	btSphereShape a(1), b(btScalar(0.5));
	const Query q = closestPoints(a, at(btVector3(1, 2, 3)), b, at(btVector3(1, 2, 3)));
	ASSERT_TRUE(q.result.m_hasResult);
	EXPECT_EQ(q.lastUsedMethod, 3);
	// EPA on the Minkowski sum of two concentric spheres (a sphere of radius 1.5, every direction equally
	// deep) refines the whole polytope evenly: 128 vertices give faces of edge ~0.5 R, whose sagitta
	// h^2 / 8R is ~3% of R. Allow 5% of R; the depth can only be underestimated (faces lie inside).
	EXPECT_NEAR(q.result.m_distance, -1.5, 0.075);
	EXPECT_GE(q.result.m_distance, btScalar(-1.5) - kPenetrationTolerance);
	EXPECT_NEAR(q.result.m_normalOnBInWorld.length(), 1, kDistanceTolerance);
}

TEST(GjkPairDetector, SphereBoxDistanceMatchesClosestPointOnBox)
{
	Random rng(103);
	for (int trial = 0; trial < 300; ++trial)
	{
		const btVector3 h(rng.uniform(btScalar(0.1), 2), rng.uniform(btScalar(0.1), 2), rng.uniform(btScalar(0.1), 2));
		btBoxShape box(h);
		box.setMargin(0);  // a sharp box, so that the analytic answer is the clamp below
		const btScalar r = rng.uniform(btScalar(0.1), 1);
		btSphereShape sphere(r);
		const btTransform tb = rng.transform(2);
		const btVector3 c = tb(rng.vector(4));
		const btVector3 onBox = caliber_narrowphase_test::closestPointOnBox(h, tb, c);
		const btScalar centreDistance = (c - onBox).length();
		if (centreDistance < btScalar(0.05)) continue;  // centre inside or on the box: see the EPA test
		const Query q = closestPoints(sphere, at(c), box, tb);
		ASSERT_TRUE(q.result.m_hasResult) << trial;
		EXPECT_NEAR(q.result.m_distance, centreDistance - r, kDistanceTolerance) << trial;
		EXPECT_TRUE(vectorsNear(q.result.m_pointInWorld, onBox, kDistanceTolerance)) << trial;
		EXPECT_TRUE(vectorsNear(q.result.m_normalOnBInWorld, (c - onBox) / centreDistance, kDistanceTolerance))
		    << trial;
	}
}

TEST(GjkPairDetector, SphereCentreInsideBoxPenetratesThroughNearestFace)
{
	btBoxShape box(btVector3(2, 1, 3));
	box.setMargin(0);
	btSphereShape sphere(btScalar(0.5));
	// Centre 0.2 below the top face (y = 1): depth 0.7 through +y.
	const Query q =
	    closestPoints(sphere, at(btVector3(btScalar(0.3), btScalar(0.8), -btScalar(0.4))), box, at(btVector3(0, 0, 0)));
	ASSERT_TRUE(q.result.m_hasResult);
	EXPECT_NEAR(q.result.m_distance, -0.7, kPenetrationTolerance);
	EXPECT_TRUE(vectorsNear(q.result.m_normalOnBInWorld, btVector3(0, 1, 0), kPenetrationTolerance));
	// The sphere's curved surface meets a flat face: a depth error delta (EPA stops at 256 SIMD_EPSILON,
	// relative) moves the witness sideways by up to sqrt(2 R delta) with R <= 1.
	EXPECT_TRUE(vectorsNear(q.result.m_pointInWorld, btVector3(btScalar(0.3), 1, -btScalar(0.4)),
	                        btSqrt(btScalar(512) * SIMD_EPSILON)));
}

TEST(GjkPairDetector, BoxBoxDistanceMatchesBruteForceFeatures)
{
	Random rng(104);
	int tested = 0;
	for (int trial = 0; trial < 400; ++trial)
	{
		const btVector3 ha(rng.uniform(btScalar(0.2), 1), rng.uniform(btScalar(0.2), 1), rng.uniform(btScalar(0.2), 1));
		const btVector3 hb(rng.uniform(btScalar(0.2), 1), rng.uniform(btScalar(0.2), 1), rng.uniform(btScalar(0.2), 1));
		btBoxShape a(ha), b(hb);
		a.setMargin(0);
		b.setMargin(0);
		// Half the trials axis-aligned, half rotated.
		const btTransform ta = (trial % 2) ? rng.transform(4) : at(rng.vector(4));
		const btTransform tb = (trial % 2) ? rng.transform(4) : at(rng.vector(4));
		const btScalar expected = caliber_narrowphase_test::boxBoxDistance(ha, ta, hb, tb);
		if (expected < btScalar(0.01)) continue;  // overlapping or touching: the depth tests cover those
		++tested;
		const Query q = closestPoints(a, ta, b, tb);
		ASSERT_TRUE(q.result.m_hasResult) << trial;
		EXPECT_NEAR(q.result.m_distance, expected, kDistanceTolerance) << trial;
		// The reported point lies on B's surface and the point distance*normal away lies on A's.
		const btVector3 onB = q.result.m_pointInWorld;
		const btVector3 onA = onB + q.result.m_normalOnBInWorld * q.result.m_distance;
		EXPECT_TRUE(vectorsNear(caliber_narrowphase_test::closestPointOnBox(hb, tb, onB), onB, kDistanceTolerance));
		EXPECT_TRUE(vectorsNear(caliber_narrowphase_test::closestPointOnBox(ha, ta, onA), onA, kDistanceTolerance));
	}
	EXPECT_GT(tested, 200);
}

TEST(GjkPairDetector, BoxBoxFaceOverlapGivesSmallestAxisOverlap)
{
	btBoxShape a(btVector3(1, 1, 1)), b(btVector3(2, btScalar(0.5), 2));
	a.setMargin(0);
	b.setMargin(0);
	// A's bottom at y = 0.3, B's top at y = 0.5: depth 0.2 along +y; x and z overlap far more.
	const Query q =
	    closestPoints(a, at(btVector3(btScalar(0.25), btScalar(1.3), btScalar(-0.5))), b, at(btVector3(0, 0, 0)));
	ASSERT_TRUE(q.result.m_hasResult);
	EXPECT_NEAR(q.result.m_distance, -0.2, kPenetrationTolerance);
	EXPECT_TRUE(vectorsNear(q.result.m_normalOnBInWorld, btVector3(0, 1, 0), kPenetrationTolerance));
	EXPECT_NEAR(q.result.m_pointInWorld.y(), 0.5, kPenetrationTolerance);
}

TEST(GjkPairDetector, BoxMarginIsSubtractedFromCoreDistance)
{
	// With the default margin the core is the shrunk box and the full box is the same size: the face
	// distance is unchanged.
	btBoxShape a(btVector3(1, 1, 1)), b(btVector3(1, 1, 1));
	ASSERT_GT(a.getMargin(), 0);
	const Query q = closestPoints(a, at(btVector3(0, 3, 0)), b, at(btVector3(0, 0, 0)));
	ASSERT_TRUE(q.result.m_hasResult);
	EXPECT_NEAR(q.result.m_distance, 1, kDistanceTolerance);
	EXPECT_TRUE(vectorsNear(q.result.m_normalOnBInWorld, btVector3(0, 1, 0), kDistanceTolerance));
}

TEST(GjkPairDetector, CapsuleCapsuleDistanceIsSegmentDistanceLessRadii)
{
	Random rng(105);
	int tested = 0;
	for (int trial = 0; trial < 300; ++trial)
	{
		const btScalar ra = rng.uniform(btScalar(0.1), btScalar(0.6)), rb = rng.uniform(btScalar(0.1), btScalar(0.6));
		const btScalar la = rng.uniform(btScalar(0.1), 2), lb = rng.uniform(btScalar(0.1), 2);
		btCapsuleShape a(ra, la), b(rb, lb);
		const btTransform ta = rng.transform(3), tb = rng.transform(3);
		const btVector3 upA = ta.getBasis().getColumn(1) * (la / 2), upB = tb.getBasis().getColumn(1) * (lb / 2);
		const btScalar segment = caliber_narrowphase_test::segmentSegmentDistance(
		    ta.getOrigin() - upA, ta.getOrigin() + upA, tb.getOrigin() - upB, tb.getOrigin() + upB);
		if (segment < btScalar(0.01)) continue;  // crossing segments: no unique normal
		++tested;
		const Query q = closestPoints(a, ta, b, tb);
		ASSERT_TRUE(q.result.m_hasResult) << trial;
		EXPECT_NEAR(q.result.m_distance, segment - ra - rb, kDistanceTolerance) << trial;
	}
	EXPECT_GT(tested, 250);
}

TEST(GjkPairDetector, PointsBeyondTheMaximumDistanceAreNotReported)
{
	btSphereShape a(1), b(1);
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkPairDetector detector(&a, &b, &simplex, &epa);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = at(btVector3(5, 0, 0));
	input.m_transformB = at(btVector3(0, 0, 0));
	input.m_maximumDistanceSquared = 2 * 2;  // the spheres are 3 apart
	btPointCollector far;
	detector.getClosestPoints(input, far, nullptr);
	EXPECT_FALSE(far.m_hasResult);
	input.m_maximumDistanceSquared = 4 * 4;
	btPointCollector near;
	detector.getClosestPoints(input, near, nullptr);
	ASSERT_TRUE(near.m_hasResult);
	EXPECT_NEAR(near.m_distance, 3, kDistanceTolerance);
	EXPECT_TRUE(vectorsNear(detector.getCachedSeparatingAxis(), btVector3(1, 0, 0), kDistanceTolerance));
	EXPECT_NEAR(detector.getCachedSeparatingDistance(), 3, kDistanceTolerance);
}

TEST(GjkPairDetector, StartingAxisRejectsOnlyPairsBeyondTheMaximumDistance)
{
	// A box over a triangle, their margins 0.04 and 0.03 apart from the cores. Along the exact starting
	// axis (the triangle's normal) the first support step's lower bound equals the core distance, so a
	// bound that left out the margins or the axis's length would reject the pair just inside the limit.
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	box.setMargin(btScalar(0.04));
	btTriangleShape triangle(btVector3(-2, 0, -2), btVector3(-2, 0, 2), btVector3(2, 0, 0));
	triangle.setMargin(btScalar(0.03));
	const btScalar maxDistance = btScalar(0.3);
	const btScalar startLengths[] = {btScalar(1), btScalar(10), btScalar(0.1)};
	for (btScalar startLength : startLengths)
	{
		for (int side = 0; side < 2; ++side)
		{
			// Just inside and just outside the maximum, with the box above or below the triangle.
			const btScalar gaps[] = {maxDistance - btScalar(1e-3), maxDistance + btScalar(1e-3)};
			for (int g = 0; g < 2; ++g)
			{
				const btScalar sign = side == 0 ? btScalar(1) : btScalar(-1);
				btVoronoiSimplexSolver simplex;
				btGjkEpaPenetrationDepthSolver epa;
				btGjkPairDetector detector(&box, &triangle, &simplex, &epa);
				detector.setCachedSeperatingAxis(btVector3(0, sign * startLength, 0));
				btDiscreteCollisionDetectorInterface::ClosestPointInput input;
				// The box's full half height is 0.5 (btBoxShape keeps its margin inside).
				input.m_transformA = at(btVector3(btScalar(0.2), sign * (btScalar(0.5) + btScalar(0.03) + gaps[g]), 0));
				input.m_transformB = at(btVector3(0, 0, 0));
				input.m_maximumDistanceSquared = maxDistance * maxDistance;
				btPointCollector result;
				detector.getClosestPoints(input, result, nullptr);
				if (g == 0)
				{
					ASSERT_TRUE(result.m_hasResult) << "start length " << startLength << " side " << side;
					EXPECT_NEAR(result.m_distance, gaps[g], kDistanceTolerance);
					EXPECT_TRUE(vectorsNear(result.m_normalOnBInWorld, btVector3(0, sign, 0), kDistanceTolerance));
				}
				else
				{
					EXPECT_FALSE(result.m_hasResult)
					    << "start length " << startLength << " side " << side << " distance " << result.m_distance;
				}
			}
		}
	}
}

TEST(GjkPairDetector, AQueryEndedBeyondTheMaximumLeavesItsSeparatingAxis)
{
	// Boxes 3 apart along x with a maximum of 1: the query ends on an axis that proves them apart. That
	// axis is left as the cached one, so the same query from it ends at the first support step, where
	// the default start (0, 1, 0) proves nothing.
	btBoxShape a(btVector3(1, 1, 1)), b(btVector3(1, 1, 1));
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkPairDetector detector(&a, &b, &simplex, &epa);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = btTransform(btQuaternion(btVector3(0, 1, 1), btScalar(0.3)), btVector3(5, btScalar(0.5), 0));
	input.m_transformB = at(btVector3(0, 0, 0));
	input.m_maximumDistanceSquared = 1;
	btPointCollector first;
	detector.getClosestPoints(input, first, nullptr);
	EXPECT_FALSE(first.m_hasResult);
	EXPECT_GT(detector.m_curIter, 0) << "the default start axis does not separate the boxes";
	const btVector3 axis = detector.getCachedSeparatingAxis();
	ASSERT_GT(axis.length2(), btScalar(0));
	// The axis points from B towards A and separates the full boxes by more than the maximum.
	const btVector3 unit = axis.normalized();
	const btScalar gap =
	    input.m_transformA(a.localGetSupportingVertex(-unit * input.m_transformA.getBasis())).dot(unit) -
	    input.m_transformB(b.localGetSupportingVertex(unit * input.m_transformB.getBasis())).dot(unit);
	EXPECT_GT(gap, btScalar(1)) << "axis " << axis.x() << " " << axis.y() << " " << axis.z();
	btPointCollector second;
	detector.getClosestPoints(input, second, nullptr);
	EXPECT_FALSE(second.m_hasResult);
	EXPECT_EQ(detector.m_curIter, 0) << "started from the separating axis, the first support step ends the query";
}

TEST(GjkPairDetector, MinkowskiSamplingSolverGivesExactFaceDepthForBoxes)
{
	btBoxShape a(btVector3(1, 1, 1)), b(btVector3(2, btScalar(0.5), 2));
	a.setMargin(0);
	b.setMargin(0);
	btMinkowskiPenetrationDepthSolver sampling;
	// Cores overlap by 0.2 along y; the box axes are among the sampled directions.
	const Query q =
	    closestPoints(a, at(btVector3(btScalar(0.25), btScalar(1.3), 0)), b, at(btVector3(0, 0, 0)), &sampling);
	ASSERT_TRUE(q.result.m_hasResult);
	EXPECT_NEAR(q.result.m_distance, -0.2, kPenetrationTolerance);
	EXPECT_TRUE(vectorsNear(q.result.m_normalOnBInWorld, btVector3(0, 1, 0), kPenetrationTolerance));
}

TEST(GjkPairDetector, ZeroSizeSpheresAreSeparatedPointsOrNoContact)
{
	btSphereShape a(0), b(0);
	const Query apart = closestPoints(a, at(btVector3(1, 2, 2)), b, at(btVector3(0, 0, 0)));
	ASSERT_TRUE(apart.result.m_hasResult);
	EXPECT_NEAR(apart.result.m_distance, 3, kDistanceTolerance);
	// Documented: two coincident points have no penetration normal; nothing is reported.
	const Query same = closestPoints(a, at(btVector3(1, 2, 2)), b, at(btVector3(1, 2, 2)));
	EXPECT_FALSE(same.result.m_hasResult);
	EXPECT_TRUE(isFinite(same.result.m_normalOnBInWorld));
}

TEST(GjkPairDetectorDeathTest, NonFiniteTransformAssertsOrReportsNothing)
{
	btSphereShape a(1), b(1);
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkPairDetector detector(&a, &b, &simplex, &epa);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = at(btVector3(BT_NAN, 0, 0));
	input.m_transformB = at(btVector3(0, 0, 0));
	btPointCollector result;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(detector.getClosestPoints(input, result, nullptr), "assertion failed");
#else
	detector.getClosestPoints(input, result, nullptr);
	EXPECT_FALSE(result.m_hasResult);
	EXPECT_EQ(detector.m_lastUsedMethod, -1);
	EXPECT_TRUE(isFinite(detector.getCachedSeparatingAxis()));
#endif
}

TEST(PointCollector, KeepsTheDeepestPoint)
{
	btPointCollector collector;
	EXPECT_FALSE(collector.m_hasResult);
	collector.addContactPoint(btVector3(0, 1, 0), btVector3(1, 0, 0), btScalar(0.5));
	collector.addContactPoint(btVector3(1, 0, 0), btVector3(2, 0, 0), btScalar(-0.1));
	collector.addContactPoint(btVector3(0, 0, 1), btVector3(3, 0, 0), btScalar(0.2));
	EXPECT_TRUE(collector.m_hasResult);
	EXPECT_EQ(collector.m_distance, btScalar(-0.1));
	EXPECT_EQ(collector.m_pointInWorld, btVector3(2, 0, 0));
	EXPECT_EQ(collector.m_normalOnBInWorld, btVector3(1, 0, 0));
}

namespace
{
struct TestStorageResult : public btStorageResult
{
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
};
}  // namespace

TEST(StorageResult, KeepsTheClosestPoint)
{
	TestStorageResult storage;
	EXPECT_EQ(storage.m_distance, btScalar(BT_LARGE_FLOAT));
	storage.addContactPoint(btVector3(0, 1, 0), btVector3(1, 0, 0), 2);
	storage.addContactPoint(btVector3(1, 0, 0), btVector3(2, 0, 0), 1);
	storage.addContactPoint(btVector3(0, 0, 1), btVector3(3, 0, 0), 3);
	EXPECT_EQ(storage.m_distance, 1);
	EXPECT_EQ(storage.m_closestPointInB, btVector3(2, 0, 0));
	EXPECT_EQ(storage.m_normalOnSurfaceB, btVector3(1, 0, 0));
}

namespace
{
// Owns one shape of each kind the pair stress test draws from.
struct ShapeZoo
{
	btSphereShape sphere{btScalar(0.6)};
	btBoxShape box{btVector3(btScalar(0.5), btScalar(0.7), btScalar(0.3))};
	btCapsuleShape capsule{btScalar(0.3), btScalar(0.8)};
	btCylinderShape cylinder{btVector3(btScalar(0.4), btScalar(0.6), btScalar(0.4))};
	btConeShape cone{btScalar(0.5), btScalar(1.0)};
	btConvexHullShape hull;
	ShapeZoo()
	{
		Random rng(7);
		for (int i = 0; i < 12; ++i) hull.addPoint(rng.vector(btScalar(0.6)));
	}
	const btConvexShape* pick(int i) const
	{
		const btConvexShape* shapes[6] = {&sphere, &box, &capsule, &cylinder, &cone, &hull};
		return shapes[i % 6];
	}
};
}  // namespace

TEST(GjkPairDetector, RandomShapePairsGiveFiniteResultsBoundedBySampling)
{
	ShapeZoo zoo;
	Random rng(106);
	btMinkowskiPenetrationDepthSolver sampling;
	int penetrating = 0;
	for (int trial = 0; trial < 600; ++trial)
	{
		const btConvexShape* a = zoo.pick(trial);
		const btConvexShape* b = zoo.pick(trial / 6);
		const btTransform ta = rng.transform(btScalar(1.2)), tb = rng.transform(btScalar(1.2));
		const Query epa = closestPoints(*a, ta, *b, tb);
		ASSERT_TRUE(epa.result.m_hasResult) << trial;
		EXPECT_TRUE(isFinite(epa.result.m_normalOnBInWorld) && isFinite(epa.result.m_pointInWorld)) << trial;
		EXPECT_TRUE(btIsFinite(epa.result.m_distance)) << trial;
		EXPECT_NEAR(epa.result.m_normalOnBInWorld.length(), 1, kPenetrationTolerance) << trial;
		if (epa.lastUsedMethod != 3) continue;
		++penetrating;
		// EPA's polytope lies inside the Minkowski difference, so its depth never exceeds the true
		// depth; projection overlaps along sampled directions never undercut it. Allow EPA's stopping
		// tolerance (256 SIMD_EPSILON relative, shapes of size ~1).
		const Query sampled = closestPoints(*a, ta, *b, tb, &sampling);
		if (!sampled.result.m_hasResult) continue;
		EXPECT_GE(epa.result.m_distance, sampled.result.m_distance - kPenetrationTolerance) << trial;
	}
	EXPECT_GT(penetrating, 40);  // overlapping cores (the rest overlap in the margins only, or not at all)
}
