// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "LinearMath/btTransformUtil.h"
#include "NarrowPhaseTestUtil.h"

using caliber_narrowphase_test::isFinite;
using caliber_narrowphase_test::Random;
using caliber_narrowphase_test::vectorsNear;

namespace
{
enum class CastKind
{
	Subsimplex,
	Gjk,
	Continuous
};

const char* kindName(CastKind kind)
{
	switch (kind)
	{
		case CastKind::Subsimplex:
			return "Subsimplex";
		case CastKind::Gjk:
			return "Gjk";
		default:
			return "Continuous";
	}
}

// The documented stopping distances (docs, "Convex casts and ray callbacks"): the subsimplex cast stops
// with the moving point within sqrt(m_subSimplexCastEpsilon) of the Minkowski difference, the
// conservative advancement casts once the distance is within 1e-3 (float) / 1e-6 (double).
#ifdef BT_USE_DOUBLE_PRECISION
const btScalar kAdvancementTolerance = btScalar(1e-6);
#else
const btScalar kAdvancementTolerance = btScalar(1e-3);
#endif
// GJK ends when its distance bounds agree to 256 ulps of values of order 10 (the scenes' size), and the
// cast adds a few more roundings; this covers the distances those produce.
const btScalar kRounding = btScalar(512) * SIMD_EPSILON * btScalar(10);

btScalar stopDistance(CastKind kind)
{
	return kind == CastKind::Subsimplex ? btSqrt(btScalar(MAX_CONVEX_CAST_EPSILON)) : kAdvancementTolerance;
}

// Every cast stops short of the exact contact (it never passes it), by at most the stop distance over
// the speed at which the gap closes; rounding may put it a little past.
::testing::AssertionResult fractionNear(CastKind kind, btScalar fraction, btScalar exact, btScalar closingSpeed)
{
	const btScalar below = (stopDistance(kind) + kRounding) / closingSpeed;
	const btScalar above = kRounding / closingSpeed;
	if (fraction >= exact - below && fraction <= exact + above) return ::testing::AssertionSuccess();
	return ::testing::AssertionFailure() << kindName(kind) << ": fraction " << fraction << ", exact " << exact
	                                     << ", allowed [" << exact - below << ", " << exact + above << "]";
}

bool runCast(CastKind kind, const btConvexShape& a, const btConvexShape& b, const btTransform& fromA,
             const btTransform& toA, const btTransform& fromB, const btTransform& toB, btConvexCast::CastResult& result)
{
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	switch (kind)
	{
		case CastKind::Subsimplex:
		{
			btSubsimplexConvexCast cast(&a, &b, &simplex);
			return cast.calcTimeOfImpact(fromA, toA, fromB, toB, result);
		}
		case CastKind::Gjk:
		{
			btGjkConvexCast cast(&a, &b, &simplex);
			return cast.calcTimeOfImpact(fromA, toA, fromB, toB, result);
		}
		default:
		{
			btContinuousConvexCollision cast(&a, &b, &simplex, &epa);
			return cast.calcTimeOfImpact(fromA, toA, fromB, toB, result);
		}
	}
}

btTransform at(const btVector3& origin) { return btTransform(btQuaternion::getIdentity(), origin); }
btTransform at(const btQuaternion& rotation, const btVector3& origin) { return btTransform(rotation, origin); }

// Smallest t in [0, 1] with |p + t v| = radius, or -1 (p is A's centre relative to B's, v the relative motion).
btScalar sphereSphereTimeOfImpact(const btVector3& p, const btVector3& v, btScalar radius)
{
	const double a = v.dot(v), b = p.dot(v), c = double(p.dot(p)) - double(radius) * radius;
	const double disc = b * b - a * c;
	if (a <= 0 || disc < 0) return -1;
	const double t = (-b - std::sqrt(disc)) / a;
	return (t >= 0 && t <= 1) ? btScalar(t) : btScalar(-1);
}

class ConvexCastKindTest : public ::testing::TestWithParam<CastKind>
{
};

INSTANTIATE_TEST_SUITE_P(AllCasts, ConvexCastKindTest,
                         ::testing::Values(CastKind::Subsimplex, CastKind::Gjk, CastKind::Continuous),
                         [](const ::testing::TestParamInfo<CastKind>& info) { return kindName(info.param); });
}  // namespace

TEST_P(ConvexCastKindTest, MovingSpheresHitAtRootOfDistanceEquation)
{
	const CastKind kind = GetParam();
	Random rng(7001);
	for (int trial = 0; trial < 100; ++trial)
	{
		const btScalar ra = rng.uniform(btScalar(0.2), 1.5), rb = rng.uniform(btScalar(0.2), 1.5);
		const btScalar radius = ra + rb;
		btSphereShape a(ra), b(rb);
		const btVector3 centreB = rng.vector(5);
		const btVector3 p = rng.unitVector() * (radius + rng.uniform(btScalar(0.5), 3));
		// Aim within half the contact radius of B's centre: the impact is never grazing (cos >= 0.86).
		btVector3 aim = rng.vector(1);
		aim = aim.safeNormalize() * rng.uniform(0, btScalar(0.5) * radius);
		const btVector3 relativeMotion = (aim - p) * rng.uniform(btScalar(1.05), 2);
		const btVector3 motionB = rng.vector(2);
		const btVector3 motionA = relativeMotion + motionB;
		const btScalar exact = sphereSphereTimeOfImpact(p, relativeMotion, radius);
		ASSERT_GE(exact, 0);
		// Speed at which the gap closes at the contact, the component of the motion along the normal.
		const btVector3 contactNormal = (p + relativeMotion * exact).normalized();
		const btScalar closingSpeed = -contactNormal.dot(relativeMotion);

		const btTransform fromA = at(rng.rotation(), centreB + p), fromB = at(rng.rotation(), centreB);
		btTransform toA = fromA, toB = fromB;
		toA.getOrigin() += motionA;
		toB.getOrigin() += motionB;
		btConvexCast::CastResult result;
		ASSERT_TRUE(runCast(kind, a, b, fromA, toA, fromB, toB, result)) << "trial " << trial;
		EXPECT_TRUE(fractionNear(kind, result.m_fraction, exact, closingSpeed)) << "trial " << trial;
		// Every cast reports the closest points of the reported pose: the normal is the centre line there
		// (sphere cores are points, so only rounding of values of order 10 enters), the point is on B.
		const btVector3 centreAAtHit = fromA.getOrigin() + motionA * result.m_fraction;
		const btVector3 centreBAtHit = fromB.getOrigin() + motionB * result.m_fraction;
		const btVector3 expectedNormal = (centreAAtHit - centreBAtHit).normalized();
		const btScalar normalTolerance = kRounding * 10;
		EXPECT_TRUE(vectorsNear(result.m_normal, expectedNormal, normalTolerance)) << "trial " << trial;
		EXPECT_NEAR((result.m_hitPoint - centreBAtHit).length(), rb, kRounding * 10) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_hitTransformA.getOrigin(), centreAAtHit, kRounding * 10));
		EXPECT_TRUE(vectorsNear(result.m_hitTransformB.getOrigin(), centreBAtHit, kRounding * 10));
	}
}

TEST_P(ConvexCastKindTest, SphereOntoRotatedBoxFaceHitsAtGapOverDistance)
{
	const CastKind kind = GetParam();
	Random rng(7002);
	for (int trial = 0; trial < 50; ++trial)
	{
		const btVector3 half(rng.uniform(btScalar(0.5), 2), rng.uniform(btScalar(0.5), 2),
		                     rng.uniform(btScalar(0.5), 2));
		btBoxShape box(half);
		const btScalar r = rng.uniform(btScalar(0.1), 1);
		btSphereShape sphere(r);
		const btTransform boxPose = rng.transform(5);
		// Sphere above the +y face, over its interior so that the face is what it meets.
		const btScalar gap = rng.uniform(btScalar(0.1), 2);
		const btVector3 localStart(rng.uniform(-btScalar(0.8), btScalar(0.8)) * half.x(), half.y() + r + gap,
		                           rng.uniform(-btScalar(0.8), btScalar(0.8)) * half.z());
		const btScalar travel = gap * rng.uniform(btScalar(1.2), 3);
		const btVector3 faceNormal = boxPose.getBasis().getColumn(1);
		const btTransform fromA = at(boxPose(localStart)), toA = at(boxPose(localStart) - faceNormal * travel);
		btConvexCast::CastResult result;
		ASSERT_TRUE(runCast(kind, sphere, box, fromA, toA, boxPose, boxPose, result)) << "trial " << trial;
		EXPECT_TRUE(fractionNear(kind, result.m_fraction, gap / travel, travel)) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_normal, faceNormal, btScalar(1e-3))) << "trial " << trial;
		// The point on B lies on the face.
		const btVector3 localHit = boxPose.invXform(result.m_hitPoint);
		EXPECT_NEAR(localHit.y(), half.y(), stopDistance(kind) + kRounding) << "trial " << trial;
	}
}

TEST_P(ConvexCastKindTest, BoxesFaceOnHitAtGapOverClosingSpeed)
{
	const CastKind kind = GetParam();
	Random rng(7003);
	for (int trial = 0; trial < 50; ++trial)
	{
		const btVector3 halfA(rng.uniform(btScalar(0.2), 1), rng.uniform(btScalar(0.2), 1),
		                      rng.uniform(btScalar(0.2), 1));
		const btVector3 halfB(rng.uniform(btScalar(1), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(1), 2));
		btBoxShape a(halfA), b(halfB);
		// Both boxes share a random rotation; A sits above B's +y face, over its interior.
		const btQuaternion rotation = rng.rotation();
		const btMatrix3x3 basis(rotation);
		const btVector3 up = basis.getColumn(1);
		const btScalar gap = rng.uniform(btScalar(0.1), 1);
		const btVector3 lateral(rng.uniform(-1, 1) * (halfB.x() - halfA.x()), 0,
		                        rng.uniform(-1, 1) * (halfB.z() - halfA.z()));
		const btVector3 centreB = rng.vector(5);
		const btVector3 centreA = centreB + basis * (lateral + btVector3(0, halfA.y() + halfB.y() + gap, 0));
		// Both move towards each other, with the same sideways drift.
		const btScalar downA = gap * rng.uniform(btScalar(0.3), 2), upB = gap * rng.uniform(btScalar(0.3), 1);
		const btVector3 drift = basis * btVector3(rng.uniform(-btScalar(0.1), btScalar(0.1)), 0, 0);
		const btTransform fromA = at(rotation, centreA), toA = at(rotation, centreA - up * downA + drift);
		const btTransform fromB = at(rotation, centreB), toB = at(rotation, centreB + up * upB + drift);
		const btScalar closing = downA + upB;
		btConvexCast::CastResult result;
		const bool hit = runCast(kind, a, b, fromA, toA, fromB, toB, result);
		if (closing < gap)
		{
			EXPECT_FALSE(hit) << "trial " << trial << ": the boxes stop short of each other";
			continue;
		}
		ASSERT_TRUE(hit) << "trial " << trial;
		EXPECT_TRUE(fractionNear(kind, result.m_fraction, gap / closing, closing)) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_normal, up, btScalar(1e-3))) << "trial " << trial;
	}
}

TEST_P(ConvexCastKindTest, PointRayEntersBoxAtSlabFraction)
{
	// The world's ray test casts a zero-radius sphere. Expected entry by the slab method in the box's
	// frame; only entries through a face's flat part count (the box's edges are rounded by its margin).
	const CastKind kind = GetParam();
	Random rng(7007);
	btSphereShape point(0);
	int checked = 0;
	for (int trial = 0; trial < 200; ++trial)
	{
		const btVector3 half(rng.uniform(btScalar(0.5), 2), rng.uniform(btScalar(0.5), 2),
		                     rng.uniform(btScalar(0.5), 2));
		btBoxShape box(half);
		const btScalar m = box.getMargin();
		const btTransform pose = rng.transform(5);
		const btVector3 fromLocal = rng.unitVector() * rng.uniform(4, 6);
		const btVector3 toLocal = rng.vector(btScalar(0.5)) * btScalar(2) - fromLocal * btScalar(0.5);
		const btVector3 d = toLocal - fromLocal;
		double entry = 0, exit = 1;
		int entryAxis = -1;
		for (int i = 0; i < 3; ++i)
		{
			const double t0 = (-double(half[i]) - fromLocal[i]) / d[i], t1 = (double(half[i]) - fromLocal[i]) / d[i];
			const double lo = std::min(t0, t1), hi = std::max(t0, t1);
			if (lo > entry)
			{
				entry = lo;
				entryAxis = i;
			}
			exit = std::min(exit, hi);
		}
		if (entryAxis < 0 || entry > exit) continue;
		const btVector3 entryPoint = fromLocal + d * btScalar(entry);
		bool onFlat = true;
		for (int i = 0; i < 3; ++i)
			if (i != entryAxis && btFabs(entryPoint[i]) > half[i] - m - btScalar(0.01)) onFlat = false;
		if (!onFlat) continue;
		++checked;
		const btTransform from(btQuaternion::getIdentity(), pose(fromLocal)),
		    to(btQuaternion::getIdentity(), pose(toLocal));
		btConvexCast::CastResult result;
		ASSERT_TRUE(runCast(kind, point, box, from, to, pose, pose, result)) << "trial " << trial;
		btVector3 faceNormal(0, 0, 0);
		faceNormal[entryAxis] = fromLocal[entryAxis] > 0 ? btScalar(1) : btScalar(-1);
		const btScalar closing = -faceNormal.dot(d);
		EXPECT_TRUE(fractionNear(kind, result.m_fraction, btScalar(entry), closing)) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_normal, pose.getBasis() * faceNormal, btScalar(1e-3))) << "trial " << trial;
	}
	EXPECT_GT(checked, 50);
}

TEST_P(ConvexCastKindTest, HullsFaceOnMatchBoxes)
{
	// A convex hull of a box's corners (margin outside) behaves like a box grown by the margin.
	const CastKind kind = GetParam();
	const btScalar corners[8][3] = {{-1, -1, -1}, {1, -1, -1}, {-1, 1, -1}, {1, 1, -1},
	                                {-1, -1, 1},  {1, -1, 1},  {-1, 1, 1},  {1, 1, 1}};
	btConvexHullShape hull;
	for (const auto& c : corners) hull.addPoint(btVector3(c[0], c[1], c[2]));
	hull.setMargin(btScalar(0.05));
	btSphereShape sphere(btScalar(0.5));
	const btTransform fromA = at(btVector3(0, 4, 0)), toA = at(btVector3(0, -1, 0));
	btConvexCast::CastResult result;
	ASSERT_TRUE(runCast(kind, sphere, hull, fromA, toA, at(btVector3(0, 0, 0)), at(btVector3(0, 0, 0)), result));
	// Contact when the centre is at 1 + 0.05 + 0.5.
	EXPECT_TRUE(fractionNear(kind, result.m_fraction, (btScalar(4) - btScalar(1.55)) / 5, 5));
	EXPECT_TRUE(vectorsNear(result.m_normal, btVector3(0, 1, 0), btScalar(1e-3)));
}

TEST_P(ConvexCastKindTest, ParallelMotionPastObjectMisses)
{
	const CastKind kind = GetParam();
	btSphereShape a(btScalar(0.5)), b(btScalar(1));
	btBoxShape box(btVector3(1, 1, 1));
	btConvexCast::CastResult result;
	result.m_fraction = btScalar(0.75);  // outputs stay untouched on a miss
	// Sphere passing above a sphere, 0.1 clear of it.
	EXPECT_FALSE(runCast(kind, a, b, at(btVector3(-5, 1.6, 0)), at(btVector3(5, 1.6, 0)), at(btVector3(0, 0, 0)),
	                     at(btVector3(0, 0, 0)), result));
	// Box sliding along another box's face, 0.1 above it.
	EXPECT_FALSE(runCast(kind, box, box, at(btVector3(-5, 2.1, 0)), at(btVector3(5, 2.1, 0)), at(btVector3(0, 0, 0)),
	                     at(btVector3(0, 0, 0)), result));
	// Both moving in parallel: no relative motion.
	EXPECT_FALSE(runCast(kind, a, b, at(btVector3(0, 3, 0)), at(btVector3(10, 3, 0)), at(btVector3(0, 0, 0)),
	                     at(btVector3(10, 0, 0)), result));
	// Moving away.
	EXPECT_FALSE(runCast(kind, a, b, at(btVector3(0, 3, 0)), at(btVector3(0, 9, 0)), at(btVector3(0, 0, 0)),
	                     at(btVector3(0, 0, 0)), result));
	// Approaching but stopping short.
	EXPECT_FALSE(runCast(kind, a, b, at(btVector3(0, 3, 0)), at(btVector3(0, 1.6, 0)), at(btVector3(0, 0, 0)),
	                     at(btVector3(0, 0, 0)), result));
	EXPECT_EQ(result.m_fraction, btScalar(0.75));
	EXPECT_EQ(result.m_normal, btVector3(0, 0, 0));
}

TEST_P(ConvexCastKindTest, ZeroMotionHitsOnlyWhenAlreadyInContact)
{
	const CastKind kind = GetParam();
	btSphereShape a(btScalar(0.5)), b(btScalar(1));
	btConvexCast::CastResult result;
	EXPECT_FALSE(runCast(kind, a, b, at(btVector3(0, 2, 0)), at(btVector3(0, 2, 0)), at(btVector3(0, 0, 0)),
	                     at(btVector3(0, 0, 0)), result));
	EXPECT_EQ(result.m_fraction, btScalar(BT_LARGE_FLOAT));
	ASSERT_TRUE(runCast(kind, a, b, at(btVector3(0, 1.2, 0)), at(btVector3(0, 1.2, 0)), at(btVector3(0, 0, 0)),
	                    at(btVector3(0, 0, 0)), result));
	EXPECT_EQ(result.m_fraction, btScalar(0));
	EXPECT_TRUE(vectorsNear(result.m_normal, btVector3(0, 1, 0), btScalar(1e-3)));
}

TEST_P(ConvexCastKindTest, StartingInContactReportsFractionZeroWithContactNormal)
{
	// Documented: shapes that touch or overlap at the start report a hit at fraction 0, whatever the
	// motion, with the start pose's contact normal (from B towards A) and the point on B.
	const CastKind kind = GetParam();
	Random rng(7004);
	for (int trial = 0; trial < 30; ++trial)
	{
		const btScalar ra = rng.uniform(btScalar(0.3), 1), rb = rng.uniform(btScalar(0.3), 1);
		btSphereShape a(ra), b(rb);
		const btVector3 direction = rng.unitVector();
		// Overlapping by up to half the smaller radius, or exactly touching on the first trials.
		const btScalar depth = trial < 3 ? btScalar(0) : rng.uniform(btScalar(0.01), btScalar(0.5) * btMin(ra, rb));
		const btVector3 centreB = rng.vector(3);
		const btTransform fromB = at(centreB), fromA = at(centreB + direction * (ra + rb - depth));
		btTransform toA = fromA;
		toA.getOrigin() += rng.vector(2);
		btConvexCast::CastResult result;
		ASSERT_TRUE(runCast(kind, a, b, fromA, toA, fromB, fromB, result)) << "trial " << trial;
		EXPECT_EQ(result.m_fraction, btScalar(0)) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_normal, direction, btScalar(1e-3))) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_hitPoint, centreB + direction * rb, btScalar(1e-3))) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_hitTransformA.getOrigin(), fromA.getOrigin(), 0));
	}
}

TEST_P(ConvexCastKindTest, BadInputAssertsOrMissesWithResultUntouched)
{
	const CastKind kind = GetParam();
	btSphereShape a(btScalar(0.5)), b(btScalar(1));
	btTransform nanPose = at(btVector3(0, 0, 0));
	nanPose.getOrigin().setY(std::numeric_limits<btScalar>::quiet_NaN());
	const btTransform fromA = at(btVector3(0, 5, 0)), toA = at(btVector3(0, -5, 0)), origin = at(btVector3(0, 0, 0));
	btVoronoiSimplexSolver simplex;
#if CALIBER_ASSERTS_ENABLED
	btConvexCast::CastResult result;
	EXPECT_DEATH(runCast(kind, a, b, nanPose, toA, origin, origin, result), "assertion failed");
	EXPECT_DEATH(runCast(kind, a, b, fromA, toA, origin, nanPose, result), "assertion failed");
	EXPECT_DEATH(
	    {
		    btSubsimplexConvexCast cast(nullptr, &b, &simplex);
		    cast.calcTimeOfImpact(fromA, toA, origin, origin, result);
	    },
	    "assertion failed");
	EXPECT_DEATH(
	    {
		    btContinuousConvexCollision cast(&a, static_cast<const btConvexShape*>(nullptr), &simplex, nullptr);
		    cast.calcTimeOfImpact(fromA, toA, origin, origin, result);
	    },
	    "assertion failed");
#else
	btConvexCast::CastResult result;
	result.m_fraction = btScalar(0.5);
	EXPECT_FALSE(runCast(kind, a, b, nanPose, toA, origin, origin, result));
	EXPECT_FALSE(runCast(kind, a, b, fromA, toA, origin, nanPose, result));
	btSubsimplexConvexCast nullSubsimplex(nullptr, &b, &simplex);
	EXPECT_FALSE(nullSubsimplex.calcTimeOfImpact(fromA, toA, origin, origin, result));
	btGjkConvexCast nullGjk(&a, nullptr, &simplex);
	EXPECT_FALSE(nullGjk.calcTimeOfImpact(fromA, toA, origin, origin, result));
	btContinuousConvexCollision nullContinuous(&a, static_cast<const btConvexShape*>(nullptr), &simplex, nullptr);
	EXPECT_FALSE(nullContinuous.calcTimeOfImpact(fromA, toA, origin, origin, result));
	btContinuousConvexCollision nullSolver(&a, &b, nullptr, nullptr);
	EXPECT_FALSE(nullSolver.calcTimeOfImpact(fromA, toA, origin, origin, result));
	EXPECT_EQ(result.m_fraction, btScalar(0.5));
	EXPECT_EQ(result.m_normal, btVector3(0, 0, 0));
	EXPECT_EQ(result.m_hitPoint, btVector3(0, 0, 0));
#endif
}

TEST(ContinuousConvexCollision, RotatingCapsuleTipHitsSphereWhereTipDistanceEqualsRadii)
{
	// A capsule along x (segment half length L) spins about z through its centre; a sphere sits beyond
	// the tip's circle. The closest point of the segment is its end e(theta) = L (cos, sin), so the
	// contact angle solves |c - e|^2 = R^2: cos(phi - theta) = (D^2 + L^2 - R^2) / (2 D L).
	Random rng(7005);
	for (int trial = 0; trial < 30; ++trial)
	{
		const btScalar capsuleRadius = rng.uniform(btScalar(0.05), btScalar(0.2));
		const btScalar L = rng.uniform(btScalar(0.8), 2);
		const btScalar sphereRadius = rng.uniform(btScalar(0.1), btScalar(0.5));
		const btScalar R = capsuleRadius + sphereRadius;
		// D^2 >= L^2 + R^2 keeps the segment's closest point at its end; D < L + R lets the tip reach.
		const btScalar reachStart = btSqrt(L * L + R * R);
		const btScalar D = reachStart + rng.uniform(btScalar(0.05), btScalar(0.9)) * (L + R - reachStart);
		const btScalar phi = rng.uniform(btScalar(0.8), btScalar(1.5));
		const btScalar spin = rng.uniform(btScalar(1.6), btScalar(3));  // total turn, less than pi
		const double cosContact = (double(D) * D + double(L) * L - double(R) * R) / (2.0 * D * L);
		const btScalar contactAngle = phi - btScalar(std::acos(cosContact));
		ASSERT_GT(contactAngle, 0);
		ASSERT_LT(contactAngle, spin);

		btCapsuleShapeX capsule(capsuleRadius, 2 * L);
		btSphereShape sphere(sphereRadius);
		const btVector3 centre = rng.vector(3);
		const btVector3 sphereCentre = centre + btVector3(D * btCos(phi), D * btSin(phi), 0);
		const btTransform fromA = at(centre);
		const btTransform toA = at(btQuaternion(btVector3(0, 0, 1), spin), centre);
		btVoronoiSimplexSolver simplex;
		btGjkEpaPenetrationDepthSolver epa;
		btContinuousConvexCollision cast(&capsule, &sphere, &simplex, &epa);
		btConvexCast::CastResult result;
		ASSERT_TRUE(cast.calcTimeOfImpact(fromA, toA, at(sphereCentre), at(sphereCentre), result)) << "trial " << trial;
		// The gap closes at d|c - e|/dtheta = D L sin(phi - theta) / R per radian, times spin per fraction.
		const btScalar closing = D * L * btSin(phi - contactAngle) / R * spin;
		EXPECT_TRUE(fractionNear(CastKind::Continuous, result.m_fraction, contactAngle / spin, closing))
		    << "trial " << trial;
		// The normal runs from the sphere's centre to the tip at the reported pose.
		const btScalar reportedAngle = result.m_fraction * spin;
		const btVector3 tip = centre + L * btVector3(btCos(reportedAngle), btSin(reportedAngle), 0);
		EXPECT_TRUE(vectorsNear(result.m_normal, (tip - sphereCentre).normalized(), btScalar(1e-3)))
		    << "trial " << trial;
		// The reported pose is the rotation by the fraction of the spin about z.
		btVector3 axis;
		btScalar angle;
		btTransformUtil::calculateDiffAxisAngle(fromA, result.m_hitTransformA, axis, angle);
		EXPECT_NEAR(angle, result.m_fraction * spin, btScalar(1e-3)) << "trial " << trial;
	}
}

namespace
{
// Smallest theta in [0, pi/2] at which a box (margin-free half extents a, b about z, corners rounded by
// margin m) rotating about z with its centre at height h first reaches y = 0: a sin + b cos + m = h.
btScalar boxPlaneContactAngle(btScalar a, btScalar b, btScalar m, btScalar h)
{
	const double R = std::sqrt(double(a) * a + double(b) * b), alpha = std::atan2(double(b), double(a));
	return btScalar(std::asin((h - m) / R) - alpha);
}
}  // namespace

TEST(ContinuousConvexCollision, RotatingBoxMeetsPlaneAndFloorBoxAtCornerAngle)
{
	Random rng(7006);
	for (int trial = 0; trial < 30; ++trial)
	{
		const btVector3 half(rng.uniform(btScalar(0.5), btScalar(1.5)), rng.uniform(btScalar(0.2), btScalar(0.5)),
		                     rng.uniform(btScalar(0.2), 1));
		btBoxShape box(half);
		const btScalar m = box.getMargin();
		const btScalar a = half.x() - m, b = half.y() - m;
		// Centre height between the resting height b + m and the corner height at 60 degrees.
		const btScalar h =
		    b + m + rng.uniform(btScalar(0.2), btScalar(0.8)) * (a * btSin(SIMD_PI / 3) + b * btCos(SIMD_PI / 3) - b);
		const btScalar contactAngle = boxPlaneContactAngle(a, b, m, h);
		const btScalar spin = btScalar(SIMD_PI / 3) + rng.uniform(0, btScalar(0.5));
		ASSERT_GT(contactAngle, 0);
		const btVector3 xz(rng.uniform(-5, 5), 0, rng.uniform(-5, 5));
		const btTransform fromA = at(xz + btVector3(0, h, 0));
		// Turning by -spin about z swings the +x end down.
		const btTransform toA = at(btQuaternion(btVector3(0, 0, 1), -spin), xz + btVector3(0, h, 0));
		const btScalar closing = (a * btCos(contactAngle) - b * btSin(contactAngle)) * spin;
		ASSERT_GT(closing, btScalar(0.05));

		btStaticPlaneShape plane(btVector3(0, 1, 0), 0);
		btContinuousConvexCollision planeCast(&box, &plane);
		btConvexCast::CastResult result;
		const btTransform identity = at(btVector3(0, 0, 0));
		ASSERT_TRUE(planeCast.calcTimeOfImpact(fromA, toA, identity, identity, result)) << "trial " << trial;
		EXPECT_TRUE(fractionNear(CastKind::Continuous, result.m_fraction, contactAngle / spin, closing))
		    << "trial " << trial;
		EXPECT_TRUE(vectorsNear(result.m_normal, btVector3(0, 1, 0), btScalar(1e-5)));
		EXPECT_NEAR(result.m_hitPoint.y(), 0, btScalar(1e-5));

		// The same against a large floor box whose top face is y = 0.
		btBoxShape floorBox(btVector3(20, 1, 20));
		btVoronoiSimplexSolver simplex;
		btGjkEpaPenetrationDepthSolver epa;
		btContinuousConvexCollision boxCast(&box, &floorBox, &simplex, &epa);
		btConvexCast::CastResult boxResult;
		const btTransform floorPose = at(btVector3(0, -1, 0));
		ASSERT_TRUE(boxCast.calcTimeOfImpact(fromA, toA, floorPose, floorPose, boxResult)) << "trial " << trial;
		EXPECT_TRUE(fractionNear(CastKind::Continuous, boxResult.m_fraction, contactAngle / spin, closing))
		    << "trial " << trial;
		EXPECT_TRUE(vectorsNear(boxResult.m_normal, btVector3(0, 1, 0), btScalar(1e-3)));
	}
}

TEST(ContinuousConvexCollision, PlaneCastWithTranslationHitsAtHeightOverDrop)
{
	btSphereShape sphere(btScalar(0.5));
	btStaticPlaneShape plane(btVector3(0, 0, 1), btScalar(1));  // z = 1, placed by B's transform
	const btTransform planePose = at(btVector3(0, 0, -1));      // world plane z = 0
	btContinuousConvexCollision cast(&sphere, &plane);
	btConvexCast::CastResult result;
	ASSERT_TRUE(
	    cast.calcTimeOfImpact(at(btVector3(3, 1, 4.5)), at(btVector3(5, 1, -3.5)), planePose, planePose, result));
	EXPECT_TRUE(fractionNear(CastKind::Continuous, result.m_fraction, btScalar(4) / 8, 8));
	EXPECT_TRUE(vectorsNear(result.m_normal, btVector3(0, 0, 1), btScalar(1e-6)));
	// Moving parallel to the plane misses.
	EXPECT_FALSE(cast.calcTimeOfImpact(at(btVector3(0, 0, 2)), at(btVector3(9, 0, 2)), planePose, planePose, result));
}

TEST(ContinuousConvexCollision, AllowedPenetrationLetsShapesSinkThatDeep)
{
	// Face-on boxes: the cast stops when distance + allowed penetration reaches its tolerance, i.e.
	// with the boxes overlapping by the allowed penetration.
	btBoxShape box(btVector3(1, 1, 1));
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btContinuousConvexCollision cast(&box, &box, &simplex, &epa);
	btConvexCast::CastResult result;
	result.m_allowedPenetration = btScalar(0.1);
	const btTransform origin = at(btVector3(0, 0, 0));
	ASSERT_TRUE(cast.calcTimeOfImpact(at(btVector3(0, 3, 0)), at(btVector3(0, 1, 0)), origin, origin, result));
	EXPECT_TRUE(fractionNear(CastKind::Continuous, result.m_fraction, btScalar(1.1) / 2, 2));
}

TEST(ContinuousConvexCollision, NullDepthSolverStillFindsSeparatedStartHits)
{
	// Bullet's ray test builds the cast without a depth solver; separated starts never need one.
	btSphereShape point(0), sphere(btScalar(1));
	btVoronoiSimplexSolver simplex;
	btContinuousConvexCollision cast(&point, &sphere, &simplex, nullptr);
	btConvexCast::CastResult result;
	const btTransform origin = at(btVector3(0, 0, 0));
	ASSERT_TRUE(cast.calcTimeOfImpact(at(btVector3(0, 0, 5)), at(btVector3(0, 0, -5)), origin, origin, result));
	EXPECT_TRUE(fractionNear(CastKind::Continuous, result.m_fraction, btScalar(0.4), 10));
	EXPECT_TRUE(vectorsNear(result.m_normal, btVector3(0, 0, 1), btScalar(1e-3)));
}

namespace
{
struct FailureCountingResult : public btConvexCast::CastResult
{
	void reportFailure(int errNo, int numIterations) override
	{
		m_lastError = errNo;
		m_iterations = numIterations;
	}
	int m_lastError = 0;
	int m_iterations = -1;
};
}  // namespace

TEST(SubsimplexConvexCast, IterationLimitReportsFailureAndMisses)
{
	// An off-centre sphere-sphere cast needs several support planes; with a limit of one step the cast
	// gives up, says so through reportFailure, and reports no hit.
	btSphereShape a(btScalar(0.5)), b(btScalar(1));
	btVoronoiSimplexSolver simplex;
	btSubsimplexConvexCast cast(&a, &b, &simplex);
	FailureCountingResult result;
	result.m_subSimplexCastMaxIterations = 1;
	const btTransform origin = at(btVector3(0, 0, 0));
	EXPECT_FALSE(cast.calcTimeOfImpact(at(btVector3(-5, 1, 0)), at(btVector3(5, 1, 0)), origin, origin, result));
	EXPECT_EQ(result.m_lastError, -1);
	EXPECT_EQ(result.m_iterations, 1);
	EXPECT_EQ(result.m_fraction, btScalar(BT_LARGE_FLOAT));
	// With the default limit the same cast hits where |(-5 + 10 t, 1)| = 1.5.
	FailureCountingResult full;
	ASSERT_TRUE(cast.calcTimeOfImpact(at(btVector3(-5, 1, 0)), at(btVector3(5, 1, 0)), origin, origin, full));
	const btScalar exact = (btScalar(5) - btSqrt(btScalar(1.25))) / 10;
	const btScalar closing = btScalar(10) * btSqrt(btScalar(1.25)) / btScalar(1.5);
	EXPECT_TRUE(fractionNear(CastKind::Subsimplex, full.m_fraction, exact, closing));
	EXPECT_EQ(full.m_lastError, 0);
}

TEST(GjkConvexCast, AllowedPenetrationLetsShapesSinkThatDeep)
{
	btBoxShape box(btVector3(1, 1, 1));
	btVoronoiSimplexSolver simplex;
	btGjkConvexCast cast(&box, &box, &simplex);
	btConvexCast::CastResult result;
	result.m_allowedPenetration = btScalar(0.1);
	const btTransform origin = at(btVector3(0, 0, 0));
	ASSERT_TRUE(cast.calcTimeOfImpact(at(btVector3(0, 3, 0)), at(btVector3(0, 1, 0)), origin, origin, result));
	EXPECT_TRUE(fractionNear(CastKind::Gjk, result.m_fraction, btScalar(1.1) / 2, 2));
}

namespace
{
// Signed distance (margins included) by btGjkPairDetector with EPA: the oracle of the sampling test.
btScalar signedDistance(const btConvexShape& a, const btTransform& ta, const btConvexShape& b, const btTransform& tb)
{
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkPairDetector detector(&a, &b, &simplex, &epa);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = ta;
	input.m_transformB = tb;
	btPointCollector collector;
	detector.getClosestPoints(input, collector, nullptr);
	return collector.m_hasResult ? collector.m_distance : btScalar(-1);
}

btTransform lerpPose(const btTransform& from, const btTransform& to, btScalar t)
{
	return btTransform(from.getBasis(), from.getOrigin() + (to.getOrigin() - from.getOrigin()) * t);
}
}  // namespace

TEST_P(ConvexCastKindTest, RandomPairsNeverPassFirstContact)
{
	// Box, capsule and hull pairs with random translations: sampled along the motion, the shapes stay
	// apart before the reported fraction and touch (within the stop distance) at it; a miss means they
	// stay apart throughout. The oracle is btGjkPairDetector at the sampled poses.
	const CastKind kind = GetParam();
	Random rng(7008);
	btBoxShape box(btVector3(btScalar(0.6), btScalar(0.4), btScalar(0.3)));
	btCapsuleShape capsule(btScalar(0.3), btScalar(0.8));
	btConvexHullShape hull;
	for (int i = 0; i < 20; ++i) hull.addPoint(rng.unitVector() * btScalar(0.5), false);
	hull.recalcLocalAabb();
	const btConvexShape* shapes[3] = {&box, &capsule, &hull};
	const int samples = 64;
	int hits = 0, misses = 0;
	for (int trial = 0; trial < 90; ++trial)
	{
		const btConvexShape& a = *shapes[trial % 3];
		const btConvexShape& b = *shapes[(trial / 3) % 3];
		const btTransform fromB = rng.transform(2);
		const btTransform fromA(rng.rotation(), fromB.getOrigin() + rng.unitVector() * rng.uniform(2, 4));
		const btVector3 aim = fromB.getOrigin() + rng.vector(btScalar(1.5));
		const btTransform toA(fromA.getBasis(), fromA.getOrigin() + (aim - fromA.getOrigin()) * rng.uniform(1, 2));
		const btTransform toB(fromB.getBasis(), fromB.getOrigin() + rng.vector(btScalar(0.5)));
		if (signedDistance(a, fromA, b, fromB) <= btScalar(0.01)) continue;
		btConvexCast::CastResult result;
		const bool hit = runCast(kind, a, b, fromA, toA, fromB, toB, result);
		const btScalar end = hit ? result.m_fraction : btScalar(1);
		for (int k = 0; k < samples; ++k)
		{
			const btScalar t = end * btScalar(k) / samples;
			EXPECT_GT(signedDistance(a, lerpPose(fromA, toA, t), b, lerpPose(fromB, toB, t)), -kRounding)
			    << kindName(kind) << " trial " << trial << " t " << t;
		}
		if (!hit)
		{
			EXPECT_GT(signedDistance(a, toA, b, toB), -kRounding) << "trial " << trial;
			++misses;
			continue;
		}
		++hits;
		const btScalar atHit = signedDistance(a, lerpPose(fromA, toA, end), b, lerpPose(fromB, toB, end));
		EXPECT_LE(atHit, stopDistance(kind) + kRounding) << kindName(kind) << " trial " << trial;
		EXPECT_GE(atHit, -kRounding) << kindName(kind) << " trial " << trial;
	}
	EXPECT_GT(hits, 20);
	EXPECT_GT(misses, 3);
}
