// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "BulletCollision/CollisionDispatch/btBoxBoxDetector.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/NarrowPhaseCollision/NarrowPhaseTestUtil.h"

using caliber_narrowphase_test::boxBoxDistance;
using caliber_narrowphase_test::boxBoxSatDepth;
using caliber_narrowphase_test::boxCorners;
using caliber_narrowphase_test::isFinite;
using caliber_narrowphase_test::Random;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// Coordinates stay below about 20 (scene transforms within 8, boxes up to 5); clipping and the frame
// changes are a few dozen operations each, so a few hundred ulps of 20 cover rounding in float.
const btScalar kTol = btScalar(400) * SIMD_EPSILON * btScalar(20);

struct ContactPoint
{
	btVector3 normal;
	btVector3 point;
	btScalar depth;
};

struct Collector : public btDiscreteCollisionDetectorInterface::Result
{
	std::vector<ContactPoint> points;
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3& normal, const btVector3& point, btScalar depth) override
	{
		points.push_back({normal, point, depth});
	}
};

Collector collide(const btBoxShape& a, const btTransform& ta, const btBoxShape& b, const btTransform& tb,
                  btScalar maxDistance = btScalar(BT_LARGE_FLOAT), bool swap = false)
{
	btBoxBoxDetector detector(&a, &b);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = ta;
	input.m_transformB = tb;
	if (maxDistance < btScalar(BT_LARGE_FLOAT)) input.m_maximumDistanceSquared = maxDistance * maxDistance;
	Collector out;
	detector.getClosestPoints(input, out, nullptr, swap);
	return out;
}

// Index of the expected point closest to p, so that order does not matter.
int nearestIndex(const std::vector<btVector3>& expected, const btVector3& p)
{
	int best = 0;
	for (int i = 1; i < int(expected.size()); ++i)
		if ((expected[i] - p).length2() < (expected[best] - p).length2()) best = i;
	return best;
}

// Checks that the points match the expected set one to one.
void expectPointSet(const Collector& out, const std::vector<btVector3>& expected, btScalar tolerance)
{
	ASSERT_EQ(out.points.size(), expected.size());
	std::vector<int> used(expected.size(), 0);
	for (const ContactPoint& c : out.points)
	{
		const int i = nearestIndex(expected, c.point);
		EXPECT_TRUE(vectorsNear(c.point, expected[i], tolerance));
		++used[i];
	}
	for (int u : used) EXPECT_EQ(u, 1);
}

// Overlap of the two boxes' projections on a unit axis, from their corners (independent of the detector).
btScalar projectedOverlap(const btVector3& ha, const btTransform& ta, const btVector3& hb, const btTransform& tb,
                          const btVector3& axis)
{
	btVector3 ca[8], cb[8];
	boxCorners(ha, ta, ca);
	boxCorners(hb, tb, cb);
	btScalar minA = BT_LARGE_FLOAT, maxA = -BT_LARGE_FLOAT, minB = BT_LARGE_FLOAT, maxB = -BT_LARGE_FLOAT;
	for (int i = 0; i < 8; ++i)
	{
		minA = btMin(minA, ca[i].dot(axis));
		maxA = btMax(maxA, ca[i].dot(axis));
		minB = btMin(minB, cb[i].dot(axis));
		maxB = btMax(maxB, cb[i].dot(axis));
	}
	return btMin(maxA - minB, maxB - minA);
}

btTransform rotatedAboutY(btScalar angle, const btVector3& origin)
{
	return btTransform(btQuaternion(btVector3(0, 1, 0), angle), origin);
}
}  // namespace

// A small box A resting on a big box B with penetration d: 4 points at the corners of A's bottom face
// (on B's top face), depth -d, normal up (from B towards A); also rotated about the vertical and with
// the whole scene moved by random rigid transforms.
TEST(BoxBoxDetector, RestingBoxGivesFourBottomCornersWithDepth)
{
	Random rng(7);
	const btVector3 groundHalf(5, 1, 5), boxHalf(btScalar(0.5), btScalar(0.3), btScalar(0.4));
	btBoxShape ground(groundHalf), box(boxHalf);
	for (int trial = 0; trial < 60; ++trial)
	{
		const btScalar d = trial == 0 ? btScalar(0.01) : rng.uniform(btScalar(0.001), btScalar(0.1));
		const btScalar yaw = trial == 0 ? btScalar(0) : rng.uniform(-SIMD_PI, SIMD_PI);
		const btTransform scene = trial < 2 ? btTransform::getIdentity() : rng.transform(8);
		const btTransform tb = scene * btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0));
		const btTransform ta =
		    scene * rotatedAboutY(yaw, btVector3(rng.uniform(-1, 1), boxHalf.y() - d, rng.uniform(-1, 1)));
		std::vector<btVector3> expected;
		for (int i = 0; i < 4; ++i)
		{
			// Bottom corner of A dropped onto B's top face (the point on B).
			const btVector3 corner =
			    ta(btVector3((i & 1) ? boxHalf.x() : -boxHalf.x(), -boxHalf.y(), (i & 2) ? boxHalf.z() : -boxHalf.z()));
			expected.push_back(corner + scene.getBasis().getColumn(1) * d);
		}
		const Collector out = collide(box, ta, ground, tb);
		expectPointSet(out, expected, kTol);
		for (const ContactPoint& c : out.points)
		{
			EXPECT_NEAR(c.depth, -d, kTol) << "trial " << trial;
			EXPECT_TRUE(vectorsNear(c.normal, scene.getBasis().getColumn(1), kTol));
		}
		// Swapped roles: the ground is A; points are now on the small box (its bottom corners), normal down.
		std::vector<btVector3> corners;
		for (int i = 0; i < 4; ++i) corners.push_back(expected[i] - scene.getBasis().getColumn(1) * d);
		const Collector swapped = collide(ground, tb, box, ta);
		expectPointSet(swapped, corners, kTol);
		for (const ContactPoint& c : swapped.points)
		{
			EXPECT_NEAR(c.depth, -d, kTol);
			EXPECT_TRUE(vectorsNear(c.normal, -scene.getBasis().getColumn(1), kTol));
		}
		// swapResults reports the first query as if the pair were (B, A): the same as the swapped query.
		const Collector flagged = collide(box, ta, ground, tb, btScalar(BT_LARGE_FLOAT), true);
		expectPointSet(flagged, corners, kTol);
		for (const ContactPoint& c : flagged.points)
			EXPECT_TRUE(vectorsNear(c.normal, -scene.getBasis().getColumn(1), kTol));
	}
}

// Two equal boxes stacked face on face and turned a few milliradians about the vertical, as boxes at rest
// in a stack are: the contact is the face contact (4 points, normal up). An edge pair of the two top/
// bottom faces is then nearly parallel, and its axis coincides with the face normal: |a_i x b_j|^2
// computed as 1 - cos^2 cancels to noise there and let that edge axis win about a third of the time.
TEST(BoxBoxDetector, StackedBoxesTurnedSlightlyKeepTheFaceContact)
{
	Random rng(23);
	const btVector3 half(1, 1, 1);
	btBoxShape upper(half), lower(half);
	for (int trial = 0; trial < 400; ++trial)
	{
		const btScalar d = rng.uniform(btScalar(0.005), btScalar(0.01));
		const btScalar yaw = rng.uniform(btScalar(0.0005), btScalar(0.003)) * (trial % 2 ? 1 : -1);
		const btTransform scene = rng.transform(8);
		const btTransform tb = scene * btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0));
		const btTransform ta = scene * rotatedAboutY(yaw, btVector3(rng.uniform(btScalar(-0.2), btScalar(0.2)), 3 - d,
		                                                            rng.uniform(btScalar(-0.2), btScalar(0.2))));
		const Collector out = collide(upper, ta, lower, tb);
		ASSERT_EQ(out.points.size(), 4u) << "trial " << trial << " yaw " << yaw;
		for (const ContactPoint& c : out.points)
		{
			EXPECT_TRUE(vectorsNear(c.normal, scene.getBasis().getColumn(1), kTol)) << "trial " << trial;
			// Corners sink by d, less the yaw's sub-micrometre effect on the footprint.
			EXPECT_NEAR(c.depth, -d, btScalar(1e-4)) << "trial " << trial;
		}
	}
}

// A box tilted about a horizontal axis over a big box: one point per bottom corner, at the corner's
// horizontal position on the ground, with depth equal to the corner height (computed from the rotation);
// a zero distance limit keeps only the corners below the ground.
TEST(BoxBoxDetector, TiltedBoxDepthsAreCornerHeights)
{
	Random rng(11);
	const btVector3 groundHalf(6, 1, 6), boxHalf(btScalar(0.6), btScalar(0.25), btScalar(0.45));
	btBoxShape ground(groundHalf), box(boxHalf);
	for (int trial = 0; trial < 60; ++trial)
	{
		const btScalar tilt = rng.uniform(btScalar(0.01), btScalar(0.15));
		const btQuaternion rotation = btQuaternion(btVector3(0, 1, 0), rng.uniform(-SIMD_PI, SIMD_PI)) *
		                              btQuaternion(btVector3(1, 0, btScalar(0.3)).normalized(), tilt);
		const btTransform scene = trial == 0 ? btTransform::getIdentity() : rng.transform(6);
		btTransform local(rotation, btVector3(rng.uniform(-2, 2), 0, rng.uniform(-2, 2)));
		// Lift so that the lowest bottom corner is at -0.03.
		btScalar lowest = BT_LARGE_FLOAT;
		btVector3 bottom[4];
		for (int i = 0; i < 4; ++i)
		{
			bottom[i] = local(
			    btVector3((i & 1) ? boxHalf.x() : -boxHalf.x(), -boxHalf.y(), (i & 2) ? boxHalf.z() : -boxHalf.z()));
			lowest = btMin(lowest, bottom[i].y());
		}
		const btScalar lift = btScalar(-0.03) - lowest;
		local.getOrigin() += btVector3(0, lift, 0);
		std::vector<btVector3> expectedAll, expectedBelow;
		std::vector<btScalar> heightsAll;
		for (int i = 0; i < 4; ++i)
		{
			const btScalar height = bottom[i].y() + lift;
			const btVector3 onGround = scene(btVector3(bottom[i].x(), 0, bottom[i].z()));
			expectedAll.push_back(onGround);
			heightsAll.push_back(height);
			if (height <= 0) expectedBelow.push_back(onGround);
		}
		const btTransform ta = scene * local;
		const btTransform tb = scene * btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0));
		const Collector all = collide(box, ta, ground, tb);
		expectPointSet(all, expectedAll, kTol);
		for (const ContactPoint& c : all.points)
		{
			EXPECT_NEAR(c.depth, heightsAll[nearestIndex(expectedAll, c.point)], kTol) << "trial " << trial;
			EXPECT_TRUE(vectorsNear(c.normal, scene.getBasis().getColumn(1), kTol));
		}
		const Collector below = collide(box, ta, ground, tb, 0);
		expectPointSet(below, expectedBelow, kTol);
	}
}

// Two long boxes turned 45 degrees about their long axes so that a ridge of each faces the other, the
// ridges crossing at a random angle: one point on B's ridge, depth = the signed gap between the ridges
// along the vertical (their lines' distance), compared with a brute-force segment distance when apart.
TEST(BoxBoxDetector, CrossingEdgesGiveOnePointWithSegmentDistance)
{
	Random rng(23);
	const btVector3 halfA(3, btScalar(0.5), btScalar(0.5)), halfB(btScalar(0.5), btScalar(0.5), 3);
	btBoxShape boxA(halfA), boxB(halfB);
	const btScalar ridge = btScalar(0.5) * btSqrt(btScalar(2));
	for (int trial = 0; trial < 60; ++trial)
	{
		const btScalar gap = rng.uniform(btScalar(-0.2), btScalar(0.2));
		// A's ridge turned from perpendicular to B's by up to 70 degrees (parallel ridges are a face contact).
		const btScalar turn = rng.uniform(btScalar(-1.2), btScalar(1.2));
		const btTransform scene = trial == 0 ? btTransform::getIdentity() : rng.transform(5);
		const btTransform localB(btQuaternion(btVector3(0, 0, 1), SIMD_PI / 4),
		                         btVector3(0, 0, rng.uniform(btScalar(-0.5), btScalar(0.5))));
		const btTransform localA(btQuaternion(btVector3(0, 1, 0), turn) * btQuaternion(btVector3(1, 0, 0), SIMD_PI / 4),
		                         btVector3(rng.uniform(btScalar(-0.5), btScalar(0.5)), 2 * ridge + gap, 0));
		const btTransform ta = scene * localA, tb = scene * localB;
		const Collector out = collide(boxA, ta, boxB, tb);
		ASSERT_EQ(out.points.size(), 1u) << "trial " << trial << " gap " << gap << " turn " << turn;
		const ContactPoint& c = out.points[0];
		EXPECT_NEAR(c.depth, gap, kTol) << "trial " << trial;
		EXPECT_TRUE(vectorsNear(c.normal, scene.getBasis().getColumn(1), kTol));
		// On B's ridge: the line x = 0, y = ridge in the scene frame.
		const btVector3 local = scene.invXform(c.point);
		EXPECT_NEAR(local.x(), 0, kTol);
		EXPECT_NEAR(local.y(), ridge, kTol);
		if (gap > 0)
		{
			// A's ridge: local y = -h, z = +h (turned to the bottom); B's: local x = y = +h (turned to the top).
			const btVector3 ridgeA0 = ta(btVector3(-halfA.x(), -halfA.y(), halfA.z()));
			const btVector3 ridgeA1 = ta(btVector3(halfA.x(), -halfA.y(), halfA.z()));
			const btVector3 ridgeB0 = tb(btVector3(halfB.x(), halfB.y(), -halfB.z()));
			const btVector3 ridgeB1 = tb(btVector3(halfB.x(), halfB.y(), halfB.z()));
			EXPECT_NEAR(c.depth, caliber_narrowphase_test::segmentSegmentDistance(ridgeA0, ridgeA1, ridgeB0, ridgeB1),
			            kTol);
			EXPECT_NEAR(c.depth, boxBoxDistance(halfA, ta, halfB, tb), kTol);
		}
	}
}

// Random separated pairs: nothing penetrates, no point is closer than the largest separation over the 15
// axes (computed here by projecting corners), and a distance limit below that separation reports nothing.
TEST(BoxBoxDetector, SeparatedBoxesReportNoPenetrationAndRespectTheLimit)
{
	Random rng(31);
	int separatedPairs = 0;
	for (int trial = 0; trial < 400; ++trial)
	{
		const btVector3 ha(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2));
		const btVector3 hb(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2));
		const btTransform ta = rng.transform(3), tb = rng.transform(3);
		const btScalar distance = boxBoxDistance(ha, ta, hb, tb);
		if (!(distance > btScalar(0.01))) continue;
		++separatedPairs;
		btBoxShape a(ha), b(hb);
		// The largest separation over the 15 candidate axes, by brute-force projection.
		btScalar satSeparation = -BT_LARGE_FLOAT;
		for (int i = 0; i < 3; ++i)
		{
			satSeparation = btMax(satSeparation, -projectedOverlap(ha, ta, hb, tb, ta.getBasis().getColumn(i)));
			satSeparation = btMax(satSeparation, -projectedOverlap(ha, ta, hb, tb, tb.getBasis().getColumn(i)));
			for (int j = 0; j < 3; ++j)
			{
				const btVector3 axis = ta.getBasis().getColumn(i).cross(tb.getBasis().getColumn(j));
				if (axis.length2() > btScalar(1e-6))
					satSeparation = btMax(satSeparation, -projectedOverlap(ha, ta, hb, tb, axis.normalized()));
			}
		}
		ASSERT_GT(satSeparation, 0) << "a separating axis exists between disjoint boxes";
		EXPECT_LE(satSeparation, distance + kTol);
		const Collector out = collide(a, ta, b, tb);
		for (const ContactPoint& c : out.points)
		{
			// The detector may prefer a face axis within its 1e-4 size bias of the best edge axis.
			EXPECT_GE(c.depth, satSeparation - kTol - btScalar(1e-3)) << "trial " << trial;
			EXPECT_TRUE(isFinite(c.point));
		}
		EXPECT_TRUE(collide(a, ta, b, tb, satSeparation * btScalar(0.99)).points.empty()) << "trial " << trial;
	}
	EXPECT_GT(separatedPairs, 100);
}

// Random penetrating pairs: points are reported, none deeper than the exact penetration depth (the
// smallest overlap over the 15 axes, brute force), and the normal is an axis of (nearly) least overlap.
TEST(BoxBoxDetector, PenetratingBoxesUseTheAxisOfLeastOverlap)
{
	Random rng(37);
	int penetrating = 0;
	for (int trial = 0; trial < 400; ++trial)
	{
		const btVector3 ha(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2));
		const btVector3 hb(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2));
		const btTransform ta = rng.transform(btScalar(1.5)), tb = rng.transform(btScalar(1.5));
		const btScalar depth = boxBoxSatDepth(ha, ta, hb, tb);
		if (!(depth > btScalar(0.01))) continue;
		++penetrating;
		btBoxShape a(ha), b(hb);
		const Collector out = collide(a, ta, b, tb, 0);
		ASSERT_FALSE(out.points.empty()) << "trial " << trial;
		ASSERT_LE(out.points.size(), 4u);
		const btVector3 normal = out.points[0].normal;
		EXPECT_NEAR(normal.length(), 1, kTol);
		// 1e-4 * size: the bias by which the detector prefers face axes.
		EXPECT_NEAR(projectedOverlap(ha, ta, hb, tb, normal), depth, kTol + btScalar(1e-3)) << "trial " << trial;
		// Moving A along the normal separates: the normal points from B towards A.
		const btScalar overlapAfter = projectedOverlap(
		    ha, btTransform(ta.getBasis(), ta.getOrigin() + normal * (depth + btScalar(0.01))), hb, tb, normal);
		EXPECT_LT(overlapAfter, 0) << "trial " << trial;
		for (const ContactPoint& c : out.points)
		{
			EXPECT_GE(c.depth, -depth - kTol - btScalar(1e-3));
			EXPECT_LE(c.depth, 0);
			EXPECT_TRUE(vectorsNear(c.normal, normal, 0));
		}
	}
	EXPECT_GT(penetrating, 100);
}

// More than 4 clip points (a box turned 45 degrees on another of the same footprint gives an octagon):
// the 4 kept are the ones spanning the largest area, found here by brute force over the 8 octagon corners.
TEST(BoxBoxDetector, OctagonClipKeepsTheLargestQuad)
{
	const btVector3 half(1, btScalar(0.5), 1);
	btBoxShape a(half), b(half);
	const btScalar d = btScalar(0.02);
	const btTransform tb = btTransform::getIdentity();
	const btTransform ta = rotatedAboutY(SIMD_PI / 4, btVector3(0, 2 * half.y() - d, 0));
	const Collector out = collide(a, ta, b, tb);
	ASSERT_EQ(out.points.size(), 4u);
	// Octagon corners: the intersection of the two unit squares; a regular octagon of inradius 1.
	btScalar area2 = 0;
	for (int i = 0; i < 4; ++i)
	{
		const btVector3& p = out.points[i].point;
		const btVector3& q = out.points[(i + 1) % 4].point;
		area2 += p.x() * q.z() - q.x() * p.z();
		EXPECT_NEAR(out.points[i].depth, -d, kTol);
		EXPECT_NEAR(btMax(btFabs(p.x()), btFabs(p.z())), 1, kTol) << "on the octagon boundary";
	}
	// The largest quad in a regular octagon of inradius 1 (circumradius R = 1 / cos(pi/8)) is a square
	// on alternate corners: area 2 R^2.
	const btScalar circumradius = btScalar(1) / btCos(SIMD_PI / 8);
	EXPECT_NEAR(btFabs(area2) / 2, 2 * circumradius * circumradius, 100 * kTol);
}

// Degenerate input: a zero-size box is a point and gets one contact; non-finite transforms assert and
// report nothing in release builds.
TEST(BoxBoxDetector, ZeroSizeBoxGivesOnePointAndBadTransformsNone)
{
	btBoxShape point(btVector3(0, 0, 0)), ground(btVector3(2, 1, 2));
	const btTransform tb(btQuaternion::getIdentity(), btVector3(0, -1, 0));
	const btTransform ta(btQuaternion(btVector3(1, 1, 0).normalized(), btScalar(0.3)),
	                     btVector3(btScalar(0.3), btScalar(-0.05), 0));
	const Collector out = collide(point, ta, ground, tb);
	ASSERT_EQ(out.points.size(), 1u);
	EXPECT_NEAR(out.points[0].depth, btScalar(-0.05), kTol);
	EXPECT_TRUE(vectorsNear(out.points[0].point, btVector3(btScalar(0.3), 0, 0), kTol));
	EXPECT_TRUE(vectorsNear(out.points[0].normal, btVector3(0, 1, 0), kTol));
	const Collector reversed = collide(ground, tb, point, ta);
	ASSERT_EQ(reversed.points.size(), 1u);
	EXPECT_NEAR(reversed.points[0].depth, btScalar(-0.05), kTol);

	btTransform bad = ta;
	bad.getOrigin().setX(std::numeric_limits<btScalar>::quiet_NaN());
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(collide(point, bad, ground, tb), "assertion failed");
	EXPECT_DEATH(collide(ground, tb, ground, bad), "assertion failed");
#else
	EXPECT_TRUE(collide(point, bad, ground, tb).points.empty());
	EXPECT_TRUE(collide(ground, tb, ground, bad).points.empty());
#endif
}
