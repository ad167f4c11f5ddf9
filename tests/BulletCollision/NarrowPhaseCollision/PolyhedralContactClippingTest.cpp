// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "BulletCollision/NarrowPhaseCollision/btPolyhedralContactClipping.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "NarrowPhaseTestUtil.h"

using caliber_narrowphase_test::boxBoxDistance;
using caliber_narrowphase_test::boxBoxSatDepth;
using caliber_narrowphase_test::Random;
using caliber_narrowphase_test::vectorsNear;

namespace
{
// Coordinates stay below about 20 (scene transforms within 8, shapes up to 5); SAT projections and
// clipping are a few dozen operations each, so a few hundred ulps of 20 cover rounding in float.
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

// A convex hull shape with its polyhedral features built from the given points.
struct Hull
{
	btConvexHullShape shape;
	explicit Hull(const std::vector<btVector3>& points)
	{
		for (const btVector3& p : points) shape.addPoint(p);
		shape.setMargin(0);
		shape.initializePolyhedralFeatures();
	}
	const btConvexPolyhedron& poly() const { return *shape.getConvexPolyhedron(); }
};

std::vector<btVector3> boxPoints(const btVector3& h)
{
	std::vector<btVector3> points;
	for (int i = 0; i < 8; ++i)
		points.push_back(btVector3((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z()));
	return points;
}

// Overlap of two world point sets' projections on a unit axis (negative when apart), by brute force.
btScalar worldOverlap(const std::vector<btVector3>& a, const std::vector<btVector3>& b, const btVector3& axis)
{
	btScalar minA = BT_LARGE_FLOAT, maxA = -BT_LARGE_FLOAT, minB = BT_LARGE_FLOAT, maxB = -BT_LARGE_FLOAT;
	for (const btVector3& p : a)
	{
		minA = btMin(minA, p.dot(axis));
		maxA = btMax(maxA, p.dot(axis));
	}
	for (const btVector3& p : b)
	{
		minB = btMin(minB, p.dot(axis));
		maxB = btMax(maxB, p.dot(axis));
	}
	return btMin(maxA - minB, maxB - minA);
}

std::vector<btVector3> placed(const std::vector<btVector3>& points, const btTransform& t)
{
	std::vector<btVector3> world;
	for (const btVector3& p : points) world.push_back(t(p));
	return world;
}

btScalar projectedOverlap(const std::vector<btVector3>& a, const btTransform& ta, const std::vector<btVector3>& b,
                          const btTransform& tb, const btVector3& axis)
{
	return worldOverlap(placed(a, ta), placed(b, tb), axis);
}

// Overlap when A is moved along +axis to separate (A lies on the positive side of B along axis).
btScalar overlapMovingAAlong(const std::vector<btVector3>& a, const btTransform& ta, const std::vector<btVector3>& b,
                             const btTransform& tb, const btVector3& axis)
{
	btScalar minA = BT_LARGE_FLOAT, maxB = -BT_LARGE_FLOAT;
	for (const btVector3& p : a) minA = btMin(minA, ta(p).dot(axis));
	for (const btVector3& p : b) maxB = btMax(maxB, tb(p).dot(axis));
	return maxB - minA;
}

// All candidate axes of two polyhedra: world face normals and edge cross products (brute-force set).
std::vector<btVector3> candidateAxes(const btConvexPolyhedron& a, const btTransform& ta, const btConvexPolyhedron& b,
                                     const btTransform& tb)
{
	std::vector<btVector3> axes;
	for (int f = 0; f < a.m_faces.size(); ++f)
		axes.push_back(ta.getBasis() *
		               btVector3(a.m_faces[f].m_plane[0], a.m_faces[f].m_plane[1], a.m_faces[f].m_plane[2]));
	for (int f = 0; f < b.m_faces.size(); ++f)
		axes.push_back(tb.getBasis() *
		               btVector3(b.m_faces[f].m_plane[0], b.m_faces[f].m_plane[1], b.m_faces[f].m_plane[2]));
	for (int i = 0; i < a.m_uniqueEdges.size(); ++i)
		for (int j = 0; j < b.m_uniqueEdges.size(); ++j)
		{
			const btVector3 c = (ta.getBasis() * a.m_uniqueEdges[i]).cross(tb.getBasis() * b.m_uniqueEdges[j]);
			if (c.length2() > btScalar(1e-6)) axes.push_back(c.normalized());
		}
	return axes;
}

int nearestIndex(const std::vector<btVector3>& expected, const btVector3& p)
{
	int best = 0;
	for (int i = 1; i < int(expected.size()); ++i)
		if ((expected[i] - p).length2() < (expected[best] - p).length2()) best = i;
	return best;
}

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

btScalar angleBetween(const btVector3& a, const btVector3& b)
{
	return btAcos(btMax(btScalar(-1), btMin(btScalar(1), a.normalized().dot(b.normalized()))));
}
}  // namespace

// A small box hull resting on a big one with penetration d: the SAT axis is the up direction (from B
// towards A), and clipping gives exactly the 4 bottom corners of the small box on B's top face with
// depth -d; also rotated about the vertical and under random rigid transforms of the whole scene.
TEST(PolyhedralContactClipping, RestingBoxHullGivesFourCornersWithDepth)
{
	Random rng(3);
	const btVector3 smallHalf(btScalar(0.5), btScalar(0.3), btScalar(0.4));
	const Hull small(boxPoints(smallHalf)), big(boxPoints(btVector3(5, 1, 5)));
	btVertexArray scratch1, scratch2;
	for (int trial = 0; trial < 60; ++trial)
	{
		const btScalar d = rng.uniform(btScalar(0.001), btScalar(0.1));
		const btScalar yaw = trial == 0 ? btScalar(0) : rng.uniform(-SIMD_PI, SIMD_PI);
		const btTransform scene = trial < 2 ? btTransform::getIdentity() : rng.transform(8);
		const btTransform tb = scene * btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0));
		const btTransform ta =
		    scene * btTransform(btQuaternion(btVector3(0, 1, 0), yaw),
		                        btVector3(rng.uniform(-1, 1), smallHalf.y() - d, rng.uniform(-1, 1)));
		const btVector3 up = scene.getBasis().getColumn(1);
		btVector3 sep;
		Collector satOut;
		ASSERT_TRUE(btPolyhedralContactClipping::findSeparatingAxis(small.poly(), big.poly(), ta, tb, sep, satOut));
		EXPECT_TRUE(vectorsNear(sep, up, kTol)) << "trial " << trial;
		EXPECT_TRUE(satOut.points.empty()) << "a face axis reports no edge point";

		std::vector<btVector3> expected;
		for (int i = 0; i < 4; ++i)
			expected.push_back(ta(btVector3((i & 1) ? smallHalf.x() : -smallHalf.x(), -smallHalf.y(),
			                                (i & 2) ? smallHalf.z() : -smallHalf.z())) +
			                   up * d);
		Collector out;
		btPolyhedralContactClipping::clipHullAgainstHull(sep, small.poly(), big.poly(), ta, tb, -1, 0, scratch1,
		                                                 scratch2, out);
		expectPointSet(out, expected, kTol);
		for (const ContactPoint& c : out.points)
		{
			EXPECT_NEAR(c.depth, -d, kTol) << "trial " << trial;
			EXPECT_TRUE(vectorsNear(c.normal, sep, kTol));
		}
	}
}

// A tetrahedron (B) pointing its tip up into the bottom face of a big box (A) by d: the axis is up and
// clipping reports the tip alone (the other incident-face corners are far above the limit), depth -d.
TEST(PolyhedralContactClipping, TetrahedronTipIntoFaceGivesOnePoint)
{
	Random rng(5);
	const btScalar tipHeight = btScalar(1.2);
	const Hull tetra({btVector3(1, 0, 0), btVector3(btScalar(-0.5), 0, btScalar(0.8660254)),
	                  btVector3(btScalar(-0.5), 0, btScalar(-0.8660254)), btVector3(0, tipHeight, 0)});
	const btVector3 boxHalf(3, btScalar(0.5), 3);
	const Hull box(boxPoints(boxHalf));
	btVertexArray scratch1, scratch2;
	for (int trial = 0; trial < 40; ++trial)
	{
		const btScalar d = rng.uniform(btScalar(0.001), btScalar(0.1));
		const btTransform scene = trial == 0 ? btTransform::getIdentity() : rng.transform(8);
		const btTransform tb =
		    scene * btTransform(btQuaternion(btVector3(0, 1, 0), rng.uniform(-SIMD_PI, SIMD_PI)), btVector3(0, 0, 0));
		const btTransform ta =
		    scene * btTransform(btQuaternion(btVector3(0, 1, 0), rng.uniform(-SIMD_PI, SIMD_PI)),
		                        btVector3(rng.uniform(btScalar(-0.5), btScalar(0.5)), tipHeight - d + boxHalf.y(),
		                                  rng.uniform(btScalar(-0.5), btScalar(0.5))));
		const btVector3 up = scene.getBasis().getColumn(1);
		btVector3 sep;
		Collector satOut;
		ASSERT_TRUE(btPolyhedralContactClipping::findSeparatingAxis(box.poly(), tetra.poly(), ta, tb, sep, satOut));
		EXPECT_TRUE(vectorsNear(sep, up, kTol)) << "trial " << trial;
		Collector out;
		btPolyhedralContactClipping::clipHullAgainstHull(sep, box.poly(), tetra.poly(), ta, tb, -1, btScalar(0.01),
		                                                 scratch1, scratch2, out);
		ASSERT_EQ(out.points.size(), 1u) << "trial " << trial;
		EXPECT_NEAR(out.points[0].depth, -d, kTol);
		EXPECT_TRUE(vectorsNear(out.points[0].point, scene(btVector3(0, tipHeight, 0)), kTol));
	}
}

// Two long box hulls with ridges crossing (as in the box-box test): the winning axis is the ridges'
// cross product and findSeparatingAxis reports the ridge crossing on B with depth minus the overlap.
TEST(PolyhedralContactClipping, CrossingEdgesReportOneEdgePoint)
{
	Random rng(9);
	const btVector3 halfA(3, btScalar(0.5), btScalar(0.5)), halfB(btScalar(0.5), btScalar(0.5), 3);
	const Hull a(boxPoints(halfA)), b(boxPoints(halfB));
	const btScalar ridge = btScalar(0.5) * btSqrt(btScalar(2));
	for (int trial = 0; trial < 40; ++trial)
	{
		const btScalar overlap = rng.uniform(btScalar(0.01), btScalar(0.2));
		const btScalar turn = rng.uniform(btScalar(-1.2), btScalar(1.2));
		const btTransform scene = trial == 0 ? btTransform::getIdentity() : rng.transform(5);
		const btTransform tb = scene * btTransform(btQuaternion(btVector3(0, 0, 1), SIMD_PI / 4), btVector3(0, 0, 0));
		const btTransform ta =
		    scene * btTransform(btQuaternion(btVector3(0, 1, 0), turn) * btQuaternion(btVector3(1, 0, 0), SIMD_PI / 4),
		                        btVector3(rng.uniform(btScalar(-0.5), btScalar(0.5)), 2 * ridge - overlap, 0));
		btVector3 sep;
		Collector satOut;
		ASSERT_TRUE(btPolyhedralContactClipping::findSeparatingAxis(a.poly(), b.poly(), ta, tb, sep, satOut));
		EXPECT_TRUE(vectorsNear(sep, scene.getBasis().getColumn(1), kTol)) << "trial " << trial;
		ASSERT_EQ(satOut.points.size(), 1u);
		EXPECT_NEAR(satOut.points[0].depth, -overlap, kTol);
		const btVector3 local = scene.invXform(satOut.points[0].point);
		EXPECT_NEAR(local.x(), 0, kTol);
		EXPECT_NEAR(local.y(), ridge, kTol);
	}
}

// Random box pairs: penetrating pairs get the axis of least overlap (the brute-force minimum over the
// 15 axes, projecting corners here), pointing from B towards A; its depth and normal agree with GJK+EPA
// on the same boxes; separated pairs (brute-force distance > 0) give false.
TEST(PolyhedralContactClipping, BoxHullSatMatchesBruteForceAndEpa)
{
	Random rng(13);
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	int penetrating = 0, separated = 0, normalsCompared = 0;
	for (int trial = 0; trial < 160; ++trial)
	{
		const btVector3 ha(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2));
		const btVector3 hb(rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2), rng.uniform(btScalar(0.2), 2));
		const btTransform ta = rng.transform(2), tb = rng.transform(2);
		const std::vector<btVector3> pa = boxPoints(ha), pb = boxPoints(hb);
		const Hull hullA(pa), hullB(pb);
		btVector3 sep;
		Collector satOut;
		const bool overlapping =
		    btPolyhedralContactClipping::findSeparatingAxis(hullA.poly(), hullB.poly(), ta, tb, sep, satOut);
		const btScalar distance = boxBoxDistance(ha, ta, hb, tb);
		if (distance > btScalar(0.01))
		{
			++separated;
			EXPECT_FALSE(overlapping) << "trial " << trial << " distance " << distance;
			continue;
		}
		const btScalar depth = boxBoxSatDepth(ha, ta, hb, tb);
		if (!(depth > btScalar(0.01))) continue;
		++penetrating;
		ASSERT_TRUE(overlapping) << "trial " << trial;
		EXPECT_NEAR(sep.length(), 1, kTol);
		// The edge-axis bias is 1e-5 of the hull sizes (below 1e-4 here).
		EXPECT_NEAR(overlapMovingAAlong(pa, ta, pb, tb, sep), depth, kTol + btScalar(1e-4)) << "trial " << trial;

		// GJK+EPA on the same boxes, with zero margin: a margin would round the box edges and corners for
		// GJK (core + sphere) and make edge and vertex contacts shallower by up to the margin. EPA stops once
		// its face distance is within its relative tolerance; GjkPairDetectorTest bounds its error on
		// polytopes by 4096 ulps of 10, which we use here.
		btBoxShape boxA(ha), boxB(hb);
		boxA.setMargin(0);
		boxB.setMargin(0);
		btGjkPairDetector detector(&boxA, &boxB, &simplex, &epa);
		btDiscreteCollisionDetectorInterface::ClosestPointInput input;
		input.m_transformA = ta;
		input.m_transformB = tb;
		btPointCollector gjk;
		detector.getClosestPoints(input, gjk, nullptr);
		ASSERT_TRUE(gjk.m_hasResult);
		const btScalar epaTolerance = btScalar(4096) * SIMD_EPSILON * btScalar(10);
		EXPECT_NEAR(-gjk.m_distance, depth, epaTolerance + btScalar(1e-4)) << "trial " << trial;
		// Normals agree where the least-overlap axis is unique: the runner-up overlaps 10% more.
		btScalar runnerUp = BT_LARGE_FLOAT;
		for (const btVector3& axis : candidateAxes(hullA.poly(), ta, hullB.poly(), tb))
		{
			if (btFabs(axis.normalized().dot(sep)) > btCos(btScalar(0.05))) continue;
			runnerUp = btMin(runnerUp, projectedOverlap(pa, ta, pb, tb, axis.normalized()));
		}
		if (runnerUp > depth * btScalar(1.1) + btScalar(0.01))
		{
			++normalsCompared;
			EXPECT_LT(angleBetween(sep, gjk.m_normalOnBInWorld), btScalar(0.05)) << "trial " << trial;
		}
	}
	EXPECT_GT(penetrating, 15) << "too few penetrating pairs to mean anything";
	EXPECT_GT(separated, 15);
	EXPECT_GT(normalsCompared, 10);
}

// Random 20-vertex hulls (points on ellipsoids): findSeparatingAxis agrees with the brute-force
// projection over every candidate axis, both on whether the hulls overlap and on the least overlap.
TEST(PolyhedralContactClipping, RoundHullSatMatchesBruteForce)
{
	Random rng(17);
	btVertexArray scratch1, scratch2;
	int penetrating = 0, edgeWins = 0;
	for (int trial = 0; trial < 40; ++trial)
	{
		std::vector<btVector3> pa, pb;
		const btVector3 ra(rng.uniform(btScalar(0.5), 2), rng.uniform(btScalar(0.5), 2), rng.uniform(btScalar(0.5), 2));
		const btVector3 rb(rng.uniform(btScalar(0.5), 2), rng.uniform(btScalar(0.5), 2), rng.uniform(btScalar(0.5), 2));
		for (int i = 0; i < 20; ++i)
		{
			pa.push_back(rng.unitVector() * ra);
			pb.push_back(rng.unitVector() * rb);
		}
		const Hull hullA(pa), hullB(pb);
		const btTransform ta = rng.transform(1), tb = rng.transform(1);
		btScalar leastOverlap = BT_LARGE_FLOAT;
		const std::vector<btVector3> worldA = placed(pa, ta), worldB = placed(pb, tb);
		for (const btVector3& axis : candidateAxes(hullA.poly(), ta, hullB.poly(), tb))
			leastOverlap = btMin(leastOverlap, worldOverlap(worldA, worldB, axis.normalized()));
		btVector3 sep;
		Collector satOut;
		const bool overlapping =
		    btPolyhedralContactClipping::findSeparatingAxis(hullA.poly(), hullB.poly(), ta, tb, sep, satOut);
		if (leastOverlap < -kTol)
		{
			EXPECT_FALSE(overlapping) << "trial " << trial;
		}
		if (leastOverlap > kTol)
		{
			++penetrating;
			ASSERT_TRUE(overlapping) << "trial " << trial;
			EXPECT_NEAR(overlapMovingAAlong(pa, ta, pb, tb, sep), leastOverlap, kTol + btScalar(1e-4))
			    << "trial " << trial;
			// An edge pair that wins reports its witness point on B with minus the least overlap.
			for (const ContactPoint& c : satOut.points)
			{
				EXPECT_NEAR(c.depth, -leastOverlap, kTol + btScalar(1e-4));
				EXPECT_TRUE(caliber_narrowphase_test::isFinite(c.point));
				EXPECT_TRUE(vectorsNear(c.normal, sep, 0));
			}
			edgeWins += int(satOut.points.size());
			Collector out;
			btPolyhedralContactClipping::clipHullAgainstHull(sep, hullA.poly(), hullB.poly(), ta, tb,
			                                                 -leastOverlap - kTol, 0, scratch1, scratch2, out);
			for (const ContactPoint& c : out.points)
			{
				EXPECT_GE(c.depth, -leastOverlap - kTol);
				EXPECT_LE(c.depth, 0);
			}
		}
	}
	EXPECT_GT(penetrating, 15);
	// The edge-pair branch (Gauss-map path for these hulls) must have been exercised.
	EXPECT_GT(edgeWins, 0) << penetrating << " penetrating pairs";
}

// clipFace keeps the part of a polygon behind a plane: a square cut by x <= 0.5 gives the analytic
// rectangle; a plane behind which it lies entirely keeps it; one in front of it empties it.
TEST(PolyhedralContactClipping, ClipFaceKeepsThePartBehindThePlane)
{
	btVertexArray square, out;
	square.push_back(btVector3(-1, -1, 0));
	square.push_back(btVector3(1, -1, 0));
	square.push_back(btVector3(1, 1, 0));
	square.push_back(btVector3(-1, 1, 0));
	btPolyhedralContactClipping::clipFace(square, out, btVector3(1, 0, 0), btScalar(-0.5));
	ASSERT_EQ(out.size(), 4);
	btScalar area2 = 0;
	for (int i = 0; i < out.size(); ++i)
	{
		EXPECT_LE(out[i].x(), btScalar(0.5));
		area2 += out[i].x() * out[(i + 1) % 4].y() - out[(i + 1) % 4].x() * out[i].y();
	}
	EXPECT_NEAR(area2 / 2, btScalar(3), kTol);
	out.resize(0);
	btPolyhedralContactClipping::clipFace(square, out, btVector3(0, 1, 0), btScalar(-2));
	EXPECT_EQ(out.size(), 4);
	out.resize(0);
	btPolyhedralContactClipping::clipFace(square, out, btVector3(0, 1, 0), btScalar(2));
	EXPECT_EQ(out.size(), 0);
}

// The counters grow by the candidate axes of each query: faces of both plus edge pairs (6 + 6 + 3 * 3
// for two boxes), and by the projected ones: at least the first face, and for two aligned boxes (whose
// inner box is the box itself) only axes that improve on the best overlap so far.
TEST(PolyhedralContactClipping, CountersCountCandidateAxes)
{
	const Hull a(boxPoints(btVector3(1, 1, 1))), b(boxPoints(btVector3(1, 1, 1)));
	const btTransform ta = btTransform::getIdentity();
	const btTransform tb(btQuaternion::getIdentity(), btVector3(btScalar(0.5), btScalar(0.3), 0));
	const int expectedBefore = gExpectedNbTests, actualBefore = gActualNbTests;
	btVector3 sep;
	Collector out;
	EXPECT_TRUE(btPolyhedralContactClipping::findSeparatingAxis(a.poly(), b.poly(), ta, tb, sep, out));
	EXPECT_EQ(gExpectedNbTests - expectedBefore, 21);
	// Each projected axis improved the best (the bound is exact here), and the overlaps take only the
	// values 2, 1.7 and 1.5: between 1 and 3 projections, whatever the face order.
	EXPECT_GE(gActualNbTests - actualBefore, 1);
	EXPECT_LE(gActualNbTests - actualBefore, 3);
	// Least overlap: 1.5 along x, moving A towards -x (B's centre is on A's +x side).
	EXPECT_TRUE(vectorsNear(sep, btVector3(-1, 0, 0), kTol));
}

// Bad input: hulls without faces, non-finite transforms and zero normals assert; in release builds
// findSeparatingAxis returns false and clipping reports nothing.
TEST(PolyhedralContactClipping, BadInputAssertsOrReportsNothing)
{
	const Hull box(boxPoints(btVector3(1, 1, 1)));
	btConvexPolyhedron empty;
	btTransform bad = btTransform::getIdentity();
	bad.getOrigin().setY(std::numeric_limits<btScalar>::quiet_NaN());
	const btTransform id = btTransform::getIdentity();
	btVector3 sep(0, 0, 0);
	Collector out;
	btVertexArray s1, s2;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btPolyhedralContactClipping::findSeparatingAxis(empty, box.poly(), id, id, sep, out),
	             "assertion failed");
	EXPECT_DEATH(btPolyhedralContactClipping::findSeparatingAxis(box.poly(), box.poly(), id, bad, sep, out),
	             "assertion failed");
	EXPECT_DEATH(btPolyhedralContactClipping::clipHullAgainstHull(btVector3(0, 0, 0), box.poly(), box.poly(), id, id,
	                                                              -1, 0, s1, s2, out),
	             "assertion failed");
	EXPECT_DEATH(btPolyhedralContactClipping::clipHullAgainstHull(btVector3(0, 1, 0), box.poly(), box.poly(), bad, id,
	                                                              -1, 0, s1, s2, out),
	             "assertion failed");
#else
	EXPECT_FALSE(btPolyhedralContactClipping::findSeparatingAxis(empty, box.poly(), id, id, sep, out));
	EXPECT_FALSE(btPolyhedralContactClipping::findSeparatingAxis(box.poly(), box.poly(), id, bad, sep, out));
	btPolyhedralContactClipping::clipHullAgainstHull(btVector3(0, 0, 0), box.poly(), box.poly(), id, id, -1, 0, s1, s2,
	                                                 out);
	btPolyhedralContactClipping::clipHullAgainstHull(btVector3(0, 1, 0), box.poly(), box.poly(), bad, id, -1, 0, s1, s2,
	                                                 out);
	EXPECT_TRUE(out.points.empty());
#endif
	// An empty face polygon to clip is no contact in every build.
	btVertexArray none, scratch;
	btPolyhedralContactClipping::clipFaceAgainstHull(btVector3(0, 1, 0), box.poly(), id, none, scratch, -1, 0, out);
	EXPECT_TRUE(out.points.empty());
}
