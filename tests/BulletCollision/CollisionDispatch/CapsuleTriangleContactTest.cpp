// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// A capsule against one mesh triangle in closed form (caliber::capsuleTriangleContact): both ends of a
// capsule lying on the face, the edge's point beside it, and distances checked against an independent
// double-precision minimisation over random poses; crossing cores and slivers are left to GJK.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "BulletCollision/CollisionDispatch/btCapsuleTriangleContact.h"

namespace
{
struct Point
{
	btVector3 normal;
	btVector3 onTriangle;
	btScalar distance;
};

struct Recorder : public btDiscreteCollisionDetectorInterface::Result
{
	std::vector<Point> points;
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3& normal, const btVector3& onTriangle, btScalar distance) override
	{
		points.push_back(Point{normal, onTriangle, distance});
	}
	btScalar closest() const
	{
		btScalar best = BT_LARGE_FLOAT;
		for (const Point& p : points) best = btMin(best, p.distance);
		return best;
	}
};

struct V
{
	double x, y, z;
};
V v(const btVector3& a) { return V{double(a.x()), double(a.y()), double(a.z())}; }
V operator-(V a, V b) { return V{a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator+(V a, V b) { return V{a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator*(V a, double s) { return V{a.x * s, a.y * s, a.z * s}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(V a) { return std::sqrt(dot(a, a)); }

V cross(V a, V b) { return V{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }

double pointSegmentDistance(V p, V a, V b)
{
	const V ab = b - a;
	const double t = std::max(0.0, std::min(1.0, dot(p - a, ab) / dot(ab, ab)));
	return length(a + ab * t - p);
}

// Distance from p to the triangle in double precision, the textbook way (not the closed form's prism
// clipping): the foot of the perpendicular when it is inside (all three edge tests agree), else the
// nearest edge.
double pointTriangleDistance(V p, V a, V b, V c)
{
	const V n = cross(b - a, c - a);
	const double nn = dot(n, n);
	const V foot = p - n * (dot(p - a, n) / nn);
	const bool inside = dot(cross(b - a, foot - a), n) >= 0 && dot(cross(c - b, foot - b), n) >= 0 &&
	                    dot(cross(a - c, foot - c), n) >= 0;
	if (inside) return length(p - foot);
	return std::min(pointSegmentDistance(p, a, b), std::min(pointSegmentDistance(p, b, c), pointSegmentDistance(p, c, a)));
}

// The distance from the segment to the triangle: the distance to a convex set is convex along the
// segment, so a ternary search over the segment of the point-triangle distance finds it.
double segmentTriangleDistance(V p0, V p1, V a, V b, V c)
{
	double lo = 0, hi = 1;
	auto at = [&](double s) { return pointTriangleDistance(p0 + (p1 - p0) * s, a, b, c); };
	for (int i = 0; i < 60; ++i)
	{
		const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
		if (at(m1) < at(m2))
			hi = m2;
		else
			lo = m1;
	}
	return at(0.5 * (lo + hi));
}

const btScalar kReach = btScalar(0.1);
}  // namespace

TEST(CapsuleTriangleContact, CapsuleLyingOnAFaceGetsBothEndsAtTheirHeight)
{
	btTriangleShape triangle(btVector3(-10, 0, -10), btVector3(-10, 0, 30), btVector3(30, 0, -10));
	triangle.setMargin(0);
	btCapsuleShapeX capsule(btScalar(0.3), btScalar(1.0));
	// Lying along x, tilted so that its ends are 0.02 and 0.04 above the floor.
	const btScalar tilt = btAsin(btScalar(0.02));
	const btTransform at(btQuaternion(btVector3(0, 0, 1), tilt), btVector3(btScalar(0.2), btScalar(0.33), btScalar(0.1)));
	Recorder out;
	EXPECT_EQ(caliber::capsuleTriangleContact(capsule, at, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 2u);
	const btScalar expected[2] = {btScalar(0.02), btScalar(0.04)};
	for (int i = 0; i < 2; ++i)
	{
		// Float rounding of positions of order 1.
		EXPECT_NEAR(out.points[i].distance, expected[i], 1e-5) << "end " << i;
		EXPECT_NEAR(out.points[i].normal.y(), 1, 1e-6);
		EXPECT_NEAR(out.points[i].onTriangle.y(), 0, 1e-5) << "the point is on the triangle's surface";
	}
	// The two points are the core's ends seen from below: 1 m apart along x (cos of a 0.02 tilt).
	EXPECT_NEAR((out.points[1].onTriangle - out.points[0].onTriangle).length(), btScalar(1.0) * btCos(tilt), 1e-4);
}

TEST(CapsuleTriangleContact, CapsuleBesideAnEdgeGetsTheEdgePointOnly)
{
	btTriangleShape triangle(btVector3(0, 0, 0), btVector3(0, 0, 1), btVector3(1, 0, 0));
	triangle.setMargin(0);
	btCapsuleShapeZ capsule(btScalar(0.25), btScalar(0.5));
	// The core runs along z at x = -0.3, y = 0.1: beyond the edge x = 0, its closest point on the triangle
	// is on that edge, sqrt(0.3^2 + 0.1^2) from the core.
	const btTransform at(btQuaternion::getIdentity(), btVector3(btScalar(-0.3), btScalar(0.1), btScalar(0.5)));
	Recorder out;
	EXPECT_EQ(caliber::capsuleTriangleContact(capsule, at, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 1u);
	EXPECT_NEAR(out.points[0].distance, btSqrt(btScalar(0.1)) - btScalar(0.25), 1e-5);
	EXPECT_NEAR(out.points[0].onTriangle.x(), 0, 1e-6);
	EXPECT_NEAR(out.points[0].normal.x(), btScalar(-0.3) / btSqrt(btScalar(0.1)), 1e-5);
}

TEST(CapsuleTriangleContact, CapsuleOutOfReachReportsNothing)
{
	btTriangleShape triangle(btVector3(0, 0, 0), btVector3(0, 0, 1), btVector3(1, 0, 0));
	triangle.setMargin(0);
	btCapsuleShape capsule(btScalar(0.25), btScalar(0.5));
	Recorder out;
	// Above the face by 0.25 + reach + 1 cm; and beside it by as much.
	const btTransform above(btQuaternion::getIdentity(), btVector3(btScalar(0.2), btScalar(0.86), btScalar(0.2)));
	EXPECT_EQ(caliber::capsuleTriangleContact(capsule, above, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleOutOfReach);
	// Beside the edge x = 0, core from y = 0.05 up: sqrt(0.36^2 + 0.05^2) = 0.363 > 0.25 + reach.
	const btTransform beside(btQuaternion::getIdentity(), btVector3(btScalar(-0.36), btScalar(0.3), btScalar(0.2)));
	EXPECT_EQ(caliber::capsuleTriangleContact(capsule, beside, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleOutOfReach);
	EXPECT_TRUE(out.points.empty());
}

TEST(CapsuleTriangleContact, CoreThroughTheTriangleOrASliverIsLeftToGjk)
{
	btTriangleShape triangle(btVector3(0, 0, 0), btVector3(0, 0, 1), btVector3(1, 0, 0));
	triangle.setMargin(0);
	btCapsuleShape capsule(btScalar(0.25), btScalar(0.5));
	Recorder out;
	const btTransform through(btQuaternion::getIdentity(), btVector3(btScalar(0.2), btScalar(0.1), btScalar(0.2)));
	EXPECT_EQ(caliber::capsuleTriangleContact(capsule, through, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	btTriangleShape sliver(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(2, 0, 0));
	const btTransform above(btQuaternion::getIdentity(), btVector3(btScalar(0.5), btScalar(0.3), 0));
	EXPECT_EQ(caliber::capsuleTriangleContact(capsule, above, sliver, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	EXPECT_TRUE(out.points.empty());
}

TEST(CapsuleTriangleContact, ClosestPointMatchesAnIndependentMinimumOverRandomPoses)
{
	std::mt19937 random(11);
	std::uniform_real_distribution<double> unit(0, 1);
	auto uniform = [&](double lo, double hi) { return btScalar(lo + (hi - lo) * unit(random)); };
	auto direction = [&]()
	{
		const double z = 2 * unit(random) - 1, phi = 2 * M_PI * unit(random), r = std::sqrt(1 - z * z);
		return btVector3(btScalar(r * std::cos(phi)), btScalar(r * std::sin(phi)), btScalar(z));
	};
	btCapsuleShape capsule(btScalar(0.2), btScalar(0.8));
	int touching = 0, apart = 0, leftToGjk = 0, exact = 0;
	for (int trial = 0; trial < 400; ++trial)
	{
		// A triangle with a margin, and a capsule posed near it.
		const btVector3 a = direction() * uniform(0.3, 1), b = direction() * uniform(0.3, 1), c = direction() * uniform(0.3, 1);
		btTriangleShape triangle(a, b, c);
		const btScalar margin = trial % 2 ? btScalar(0.04) : btScalar(0);
		triangle.setMargin(margin);
		const btTransform pose(btQuaternion(direction(), uniform(0, 2 * M_PI)),
		                       (a + b + c) / 3 + direction() * uniform(0.2, 1.0));
		Recorder out;
		const caliber::TriangleFaceOutcome outcome =
		    caliber::capsuleTriangleContact(capsule, pose, triangle, btTransform::getIdentity(), kReach, out);
		const btVector3 axis = pose.getBasis().getColumn(1) * capsule.getHalfHeight();
		const double core = segmentTriangleDistance(v(pose.getOrigin() - axis), v(pose.getOrigin() + axis), v(a), v(b), v(c));
		const double expected = core - double(capsule.getRadius()) - double(margin);
		if (outcome == caliber::kTriangleNeedsGjk)
		{
			// Only for a core that meets the plane or a sliver; the random triangles are not slivers.
			EXPECT_TRUE(out.points.empty());
			++leftToGjk;
			continue;
		}
		// The search's own error is ~1e-7; the closed form's float rounding ~1e-6 of sizes of order 1.
		const double tolerance = 2e-5;
		if (expected > double(kReach) + tolerance)
		{
			EXPECT_TRUE(out.points.empty()) << "trial " << trial << ": apart by " << expected;
			++apart;
			continue;
		}
		if (expected < double(kReach) - tolerance)
		{
			ASSERT_FALSE(out.points.empty()) << "trial " << trial << ": within reach at " << expected;
			// Exact, except that an edge nearer than the face by less than 2 mm is not reported (the face
			// points hold the capsule; see kEdgeCloserBy): then the closest is up to 2 mm shallower.
			EXPECT_GE(double(out.closest()), expected - tolerance) << "trial " << trial;
			EXPECT_LE(double(out.closest()), expected + 0.002 + tolerance) << "trial " << trial;
			exact += std::fabs(double(out.closest()) - expected) <= tolerance;
			++touching;
		}
		for (const Point& p : out.points)
		{
			// No point is deeper than the true gap, each normal is a unit vector, and each point lies on
			// the triangle's grown surface: within margin of the triangle.
			EXPECT_GE(double(p.distance), expected - tolerance) << "trial " << trial;
			EXPECT_NEAR(p.normal.length(), 1, 1e-5);
			EXPECT_NEAR(pointTriangleDistance(v(p.onTriangle), v(a), v(b), v(c)), double(margin), tolerance)
			    << "trial " << trial;
		}
	}
	// The poses cover all three cases (counts printed on failure).
	EXPECT_GT(touching, 50) << touching << " touching, " << apart << " apart, " << leftToGjk << " left to GJK";
	EXPECT_GT(apart, 50);
	EXPECT_GT(leftToGjk, 10);
	// The 2 mm allowance is the exception: nearly every touching pose is exact.
	EXPECT_GE(exact, touching * 9 / 10) << exact << " of " << touching << " exact";
}
