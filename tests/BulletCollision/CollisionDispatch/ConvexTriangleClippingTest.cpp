// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The face contact of a box or hull with one triangle (caliber::triangleFaceContact): the clipped face
// over the triangle with exact distances, the outcome that tells the algorithm whether GJK must still
// run, and degenerate input (a zero-area triangle, a hull without points) left to GJK.

#include <gtest/gtest.h>

#include <vector>

#include "BulletCollision/CollisionDispatch/btConvexTriangleClipping.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btConvexPointCloudShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

#include "TriangleContactRecorder.h"

namespace
{
using Point = caliber_test::TrianglePoint;
using Recorder = caliber_test::TriangleContactRecorder;

// A large triangle in the plane y = 0 (its margin 0), covering [-10, 10] in x and z around the origin.
btTriangleShape bigFloorTriangle()
{
	btTriangleShape triangle(btVector3(-10, 0, -10), btVector3(-10, 0, 30), btVector3(30, 0, -10));
	triangle.setMargin(0);
	return triangle;
}

const btScalar kReach = btScalar(0.1);
// Resting contacts (the default breaking threshold): how close a face lying on a triangle's edge is reported.
const btScalar kTouching = btScalar(0.02);
// Float rounding of positions of order 1 (a few ulps, with margin).
const btScalar kTolerance = btScalar(1e-5);
}  // namespace

TEST(ConvexTriangleClipping, BoxOverAFaceGivesItsFourCornersAtTheirExactDistances)
{
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	const btTriangleShape triangle = bigFloorTriangle();
	// Tilted about x by a little: the corners lie at 0.03 +- 0.5 sin(0.01) above the floor.
	const btScalar angle = btScalar(0.01);
	const btTransform at(btQuaternion(btVector3(1, 0, 0), angle),
	                     btVector3(0, btScalar(0.03) + btScalar(0.5) * (btCos(angle) + btSin(angle)), 0));
	Recorder out;
	const caliber::TriangleFaceOutcome outcome =
	    caliber::triangleFaceContact(box, at, triangle, btTransform::getIdentity(), kReach, out);
	EXPECT_EQ(outcome, caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 4u);
	btScalar lowest = BT_LARGE_FLOAT, highest = -BT_LARGE_FLOAT;
	for (const Point& p : out.points)
	{
		EXPECT_NEAR(p.normal.y(), 1, kTolerance);
		EXPECT_NEAR(p.onTriangle.y(), 0, kTolerance);
		lowest = btMin(lowest, p.distance);
		highest = btMax(highest, p.distance);
	}
	// The bottom face's corners: 0.03 for the lowest edge, 0.03 + sin(0.01) (one side across) for the other.
	EXPECT_NEAR(lowest, btScalar(0.03), kTolerance);
	EXPECT_NEAR(highest, btScalar(0.03) + btSin(angle), kTolerance);
}

TEST(ConvexTriangleClipping, FaceIsCutToTheTriangleAndAskForGjkWhenTheLowestCornerIsBeyondAnEdge)
{
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	// The triangle's hypotenuse x + z = 0 crosses the box's bottom face through its centre.
	btTriangleShape triangle(btVector3(-10, 0, -10), btVector3(-10, 0, 10), btVector3(10, 0, -10));
	triangle.setMargin(0);
	// Tilted about the horizontal axis along the hypotenuse so that the corner at (+0.5, +0.5), beyond it,
	// is the lowest.
	const btScalar angle = btScalar(0.05);
	const btTransform at(btQuaternion(btVector3(1, 0, -1).normalized(), angle), btVector3(0, btScalar(0.56), 0));
	Recorder out;
	const caliber::TriangleFaceOutcome outcome =
	    caliber::triangleFaceContact(box, at, triangle, btTransform::getIdentity(), kReach, out);
	EXPECT_EQ(outcome, caliber::kTriangleFacePointsAndGjk);
	ASSERT_GE(out.points.size(), 3u);
	const btVector3 lowestCorner = at(btVector3(btScalar(0.5), btScalar(-0.5), btScalar(0.5)));
	ASSERT_GT(lowestCorner.x() + lowestCorner.z(), btScalar(0.5));
	for (const Point& p : out.points)
	{
		EXPECT_LE(p.onTriangle.x() + p.onTriangle.z(), kTolerance) << "a point beyond the hypotenuse";
		EXPECT_GT(p.distance, lowestCorner.y() + btScalar(0.01)) << "over the triangle the face is higher";
	}
}

TEST(ConvexTriangleClipping, BoxBeyondReachIsRejectedWithoutPoints)
{
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	const btTriangleShape triangle = bigFloorTriangle();
	Recorder out;
	const btTransform at(btQuaternion::getIdentity(), btVector3(0, btScalar(0.5) + 2 * kReach, 0));
	EXPECT_EQ(caliber::triangleFaceContact(box, at, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleOutOfReach);
	EXPECT_TRUE(out.points.empty());
}

TEST(ConvexTriangleClipping, BoxNearBesideTheTriangleOrDeepInItIsLeftToGjkAndFarBesideIsOutOfReach)
{
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	const btTriangleShape triangle = bigFloorTriangle();
	Recorder out;
	// Beside the triangle (x < -10), 5 cm from its edge: no point of the face lies over it, but the edge is
	// within reach.
	const btTransform beside(btQuaternion::getIdentity(), btVector3(btScalar(-10.55), btScalar(0.52), 0));
	EXPECT_EQ(caliber::triangleFaceContact(box, beside, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	// 50 cm from the edge: the edge's side plane separates them by more than reach.
	const btTransform away(btQuaternion::getIdentity(), btVector3(-11, btScalar(0.52), 0));
	EXPECT_EQ(caliber::triangleFaceContact(box, away, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleOutOfReach);
	// 0.3 m into it: the face normal is not trusted as the way out.
	const btTransform deep(btQuaternion::getIdentity(), btVector3(0, btScalar(0.2), 0));
	EXPECT_EQ(caliber::triangleFaceContact(box, deep, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	EXPECT_TRUE(out.points.empty());
}

namespace
{
// A convex hull of a unit cube's 8 corners.
void addCubeCorners(btConvexHullShape& hull)
{
	for (int corner = 0; corner < 8; ++corner)
		hull.addPoint(
		    btVector3((corner & 1) ? btScalar(0.5) : btScalar(-0.5), (corner & 2) ? btScalar(0.5) : btScalar(-0.5),
		              (corner & 4) ? btScalar(0.5) : btScalar(-0.5)),
		    corner == 7);
}
}  // namespace

TEST(ConvexTriangleClipping, HullOnAFaceGetsItsFaceMovedOutByTheMarginOnAnEdgeTheEdgeAndOnAVertexIsLeftToGjk)
{
	btConvexHullShape hull;
	addCubeCorners(hull);
	const btScalar margin = hull.getMargin();
	const btTriangleShape triangle = bigFloorTriangle();
	Recorder out;
	const btTransform flat(btQuaternion::getIdentity(), btVector3(0, btScalar(0.5) + margin + btScalar(0.02), 0));
	EXPECT_EQ(caliber::triangleFaceContact(hull, flat, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 4u);
	for (const Point& p : out.points) EXPECT_NEAR(p.distance, btScalar(0.02), kTolerance);
	// Turned 45 degrees about z: it stands on an edge along z (2 vertices at x = 0), both ends reported
	// at the edge's height less the margin: 0.75 - sqrt(2)/2 - margin.
	out.points.clear();
	const btTransform onEdge(btQuaternion(btVector3(0, 0, 1), SIMD_PI / 4), btVector3(0, btScalar(0.75), 0));
	EXPECT_EQ(caliber::triangleFaceContact(hull, onEdge, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 2u);
	const btScalar edgeDistance = btScalar(0.75) - btSqrt(btScalar(0.5)) - margin;
	for (const Point& p : out.points)
	{
		EXPECT_NEAR(p.distance, edgeDistance, kTolerance);
		EXPECT_NEAR(p.onTriangle.x(), 0, kTolerance);
		EXPECT_NEAR(btFabs(p.onTriangle.z()), btScalar(0.5), kTolerance);
	}
	// Then tilted 30 degrees about x: one vertex is lowest (the other end of the edge is 0.5 m higher), and
	// the centre lies almost in the upright plane of its edge closest to level: no face or edge to tip onto
	// yet, GJK's point.
	out.points.clear();
	const btTransform onVertex(
	    btQuaternion(btVector3(1, 0, 0), SIMD_PI / 6) * btQuaternion(btVector3(0, 0, 1), SIMD_PI / 4),
	    btVector3(0, btScalar(0.9), 0));
	EXPECT_EQ(caliber::triangleFaceContact(hull, onVertex, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	EXPECT_TRUE(out.points.empty());
}

TEST(ConvexTriangleClipping, HullOnAnEdgeWithItsCentreToOneSideGetsTheFaceItTipsOnto)
{
	btConvexHullShape hull;
	addCubeCorners(hull);
	const btScalar margin = hull.getMargin();
	const btTriangleShape triangle = bigFloorTriangle();
	// Turned 30 degrees about z: the lowest edge is along z, the centre off to one side of it, over the
	// bottom face, which is tilted 30 degrees and which it tips onto. The edge's ends lie at the lowest
	// height, the face's other corners sin(30 degrees) = 0.5 m higher.
	const btScalar turn = SIMD_PI / 6;
	const btScalar lowestEdge = btScalar(0.5) * (btCos(turn) + btSin(turn));
	const btTransform onEdge(btQuaternion(btVector3(0, 0, 1), turn),
	                         btVector3(0, lowestEdge + margin + btScalar(0.01), 0));
	Recorder out;
	// Within a reach of 0.1 m, the edge's ends only.
	EXPECT_EQ(caliber::triangleFaceContact(hull, onEdge, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 2u);
	for (const Point& p : out.points) EXPECT_NEAR(p.distance, btScalar(0.01), kTolerance);
	// Within 1 m (a fast landing's speculative reach), the face's 4 corners, 2 of them 0.5 m higher.
	out.points.clear();
	EXPECT_EQ(caliber::triangleFaceContact(hull, onEdge, triangle, btTransform::getIdentity(), 1, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 4u);
	int high = 0;
	for (const Point& p : out.points) high += btFabs(p.distance - btScalar(0.51)) < btScalar(1e-4);
	EXPECT_EQ(high, 2);
	// Balanced on an edge (turned 45 degrees: the centre straight over it), no face: it tips no way yet.
	out.points.clear();
	const btTransform balanced(btQuaternion(btVector3(0, 0, 1), SIMD_PI / 4), btVector3(0, btScalar(0.75), 0));
	EXPECT_EQ(caliber::triangleFaceContact(hull, balanced, triangle, btTransform::getIdentity(), 1, out),
	          caliber::kTriangleFaceContact);
	EXPECT_EQ(out.points.size(), 2u);
}

TEST(ConvexTriangleClipping, HullEdgeCrossingATriangleEdgeIsCutAtItsSidePlane)
{
	btConvexHullShape hull;
	addCubeCorners(hull);
	btTriangleShape half(btVector3(-20, 0, -10), btVector3(0, 0, 10), btVector3(0, 0, -10));
	half.setMargin(0);
	Recorder out;
	// Standing on an edge along x (turned 45 degrees about x), centred on x = 0: half the edge over the
	// triangle with corners (-20,-10), (0,10), (0,-10), whose side x = 0 cuts it at its middle.
	const btTransform onEdge(btQuaternion(btVector3(1, 0, 0), SIMD_PI / 4), btVector3(0, btScalar(0.75), 0));
	caliber::triangleFaceContact(hull, onEdge, half, btTransform::getIdentity(), kReach, out);
	ASSERT_EQ(out.points.size(), 2u);
	btScalar minX = BT_LARGE_FLOAT, maxX = -BT_LARGE_FLOAT;
	for (const Point& p : out.points)
	{
		minX = btMin(minX, p.onTriangle.x());
		maxX = btMax(maxX, p.onTriangle.x());
		EXPECT_NEAR(p.onTriangle.z(), 0, kTolerance);
	}
	EXPECT_NEAR(minX, btScalar(-0.5), kTolerance);
	EXPECT_NEAR(maxX, 0, kTolerance);
}

TEST(ConvexTriangleClipping, HullWithAPolyhedronGetsItsMostOpposedFaceAlsoWhenTilted)
{
	btConvexHullShape hull;
	addCubeCorners(hull);
	ASSERT_TRUE(hull.initializePolyhedralFeatures());
	const btScalar margin = hull.getMargin();
	const btTriangleShape triangle = bigFloorTriangle();
	Recorder out;
	// Tilted 0.2 rad about z, lowest edge 0.01 above the floor (margin included): of the bottom face's
	// corners, two are at 0.01 and two sin(0.2) = 0.2 m higher, beyond reach (0.1).
	const btScalar angle = btScalar(0.2);
	const btScalar lowestEdge = btScalar(0.5) * (btCos(angle) + btSin(angle));
	const btTransform tilted(btQuaternion(btVector3(0, 0, 1), angle),
	                         btVector3(0, lowestEdge + margin + btScalar(0.01), 0));
	EXPECT_EQ(caliber::triangleFaceContact(hull, tilted, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 2u);
	for (const Point& p : out.points) EXPECT_NEAR(p.distance, btScalar(0.01), kTolerance);
	// With a longer reach the face's far edge, sin(0.2) higher, is reported too.
	out.points.clear();
	EXPECT_EQ(caliber::triangleFaceContact(hull, tilted, triangle, btTransform::getIdentity(), btScalar(0.5), out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 4u);
	int high = 0;
	for (const Point& p : out.points) high += btFabs(p.distance - (btScalar(0.01) + btSin(angle))) < btScalar(1e-4);
	EXPECT_EQ(high, 2);
}

TEST(ConvexTriangleClipping, AfterGjkAFaceNormalIsClippedAnEdgeNormalAddsTheFaceOverTheTriangleAndNoNormalIsLeftToGjk)
{
	btConvexHullShape hull;
	addCubeCorners(hull);
	const btTriangleShape triangle = bigFloorTriangle();
	const btTransform flat(btQuaternion::getIdentity(),
	                       btVector3(0, btScalar(0.5) + hull.getMargin() + btScalar(0.02), 0));
	Recorder out;
	// The face normal, of any length and either sign (the triangle is two-sided): the face.
	EXPECT_EQ(caliber::triangleFaceContactAlongGjkNormal(hull, flat, triangle, btTransform::getIdentity(), kReach,
	                                                     btVector3(0, 3, 0), kTouching, kTouching, out),
	          caliber::kTriangleFaceContact);
	EXPECT_EQ(out.points.size(), 4u);
	out.points.clear();
	// 10 degrees off (an edge's or a vertex's normal): the face's points over the triangle are still
	// reported along the face normal, and GJK's point is wanted too (its edge may be the nearest feature).
	const btVector3 leaning(btSin(btScalar(0.17)), btCos(btScalar(0.17)), 0);
	EXPECT_EQ(caliber::triangleFaceContactAlongGjkNormal(hull, flat, triangle, btTransform::getIdentity(), kReach,
	                                                     leaning, kTouching, kTouching, out),
	          caliber::kTriangleFacePointsAndGjk);
	EXPECT_EQ(out.points.size(), 4u);
	for (const Point& p : out.points) EXPECT_NEAR(p.distance, btScalar(0.02), kTolerance);
	out.points.clear();
	// At rest (a reach no more than twice the breaking threshold): GJK's point alone.
	EXPECT_EQ(caliber::triangleFaceContactAlongGjkNormal(hull, flat, triangle, btTransform::getIdentity(),
	                                                     2 * kTouching, leaning, kTouching, kTouching, out),
	          caliber::kTriangleNeedsGjk);
	EXPECT_TRUE(out.points.empty());
	// Beside the triangle (no point of the face over it): nothing, GJK's point.
	const btTransform beside(btQuaternion::getIdentity(),
	                         btVector3(btScalar(-10.55), btScalar(0.5) + hull.getMargin() + btScalar(0.02), 0));
	EXPECT_EQ(caliber::triangleFaceContactAlongGjkNormal(hull, beside, triangle, btTransform::getIdentity(), kReach,
	                                                     leaning, kTouching, kTouching, out),
	          caliber::kTriangleNeedsGjk);
	// Zero, or not finite (GJK gave no normal): nothing, GJK's point.
	const btVector3 notFinite(0, btScalar(SIMD_INFINITY), 0);
	for (const btVector3& normal : {btVector3(0, 0, 0), notFinite})
		EXPECT_EQ(caliber::triangleFaceContactAlongGjkNormal(hull, flat, triangle, btTransform::getIdentity(), kReach,
		                                                     normal, kTouching, kTouching, out),
		          caliber::kTriangleNeedsGjk);
	EXPECT_TRUE(out.points.empty());
}

TEST(ConvexTriangleClipping, AfterGjkAFaceLyingOnATriangleEdgeGetsTheEdgeUnderItAlongTheFaceNormal)
{
	btConvexHullShape hull;
	addCubeCorners(hull);
	// A triangle sloping down 10 degrees from its edge along z at x = 0 (a ridge), 10 m long.
	const btScalar drop = 10 * btTan(btScalar(0.17));
	btTriangleShape slope(btVector3(0, 0, -10), btVector3(0, 0, 10), btVector3(10, -drop, 0));
	slope.setMargin(0);
	// The cube lying level, centred over the ridge, 5 mm above it (its surface is the corners grown by
	// the margin): GJK's normal is the cube's face normal, straight up.
	const btScalar gap = btScalar(0.005);
	const btTransform over(btQuaternion::getIdentity(), btVector3(0, btScalar(0.5) + hull.getMargin() + gap, 0));
	Recorder out;
	EXPECT_EQ(caliber::triangleFaceContactAlongGjkNormal(hull, over, slope, btTransform::getIdentity(), kReach,
	                                                     btVector3(0, 1, 0), gap, kTouching, out),
	          caliber::kTriangleFaceContact);
	// The ridge's segment under the face: both ends (z = +-0.5), at the gap, with the face's normal. The
	// slope's points farther out under the face are lower, not touching, and not reported.
	ASSERT_EQ(out.points.size(), 2u);
	btScalar minZ = BT_LARGE_FLOAT, maxZ = -BT_LARGE_FLOAT;
	for (const Point& p : out.points)
	{
		EXPECT_NEAR(p.distance, gap, kTolerance);
		EXPECT_NEAR(p.onTriangle.x(), 0, kTolerance);
		EXPECT_NEAR(p.normal.y(), 1, kTolerance);
		minZ = btMin(minZ, p.onTriangle.z());
		maxZ = btMax(maxZ, p.onTriangle.z());
	}
	EXPECT_NEAR(minZ, btScalar(-0.5), kTolerance);
	EXPECT_NEAR(maxZ, btScalar(0.5), kTolerance);
	// Beyond the breaking threshold and closing in fast (a face coming down within a reach of 1 m, not lying
	// on the edge): the face points over the triangle along its normal instead, and GJK's point.
	out.points.clear();
	const btTransform above(btQuaternion::getIdentity(), btVector3(0, btScalar(0.55) + hull.getMargin(), 0));
	EXPECT_EQ(caliber::triangleFaceContactAlongGjkNormal(hull, above, slope, btTransform::getIdentity(), 1,
	                                                     btVector3(0, 1, 0), btScalar(0.05), kTouching, out),
	          caliber::kTriangleFacePointsAndGjk);
	for (const Point& p : out.points) EXPECT_LT(p.normal.y(), btScalar(0.99));
}

TEST(ConvexTriangleClipping, HullOfMorePointsThanAChunkFindsItsFaceWhereverItsPointsAre)
{
	// A 50-sided prism (100 points) along z, its points listed so that the bottom face's four corners come
	// last (beyond the first 64 depths the band test keeps on the stack).
	btConvexHullShape prism;
	const int sides = 50;
	const btScalar radius = 1;
	for (int k = 1; k <= sides; ++k)
	{
		// Side faces between angles (k - 1/2) and (k + 1/2) steps from -y; k = sides (and 0) faces -y.
		const btScalar angle = -SIMD_HALF_PI + (btScalar(k % sides) + btScalar(0.5)) * SIMD_2_PI / btScalar(sides);
		for (int end = 0; end < 2; ++end)
			prism.addPoint(btVector3(radius * btCos(angle), radius * btSin(angle), end ? btScalar(1) : btScalar(-1)),
			               false);
	}
	prism.recalcLocalAabb();
	ASSERT_EQ(prism.getNumPoints(), 100);
	const btScalar apothem = radius * btCos(SIMD_PI / btScalar(sides));
	const btTriangleShape triangle = bigFloorTriangle();
	Recorder out;
	const btTransform lying(btQuaternion::getIdentity(), btVector3(0, apothem + prism.getMargin() + btScalar(0.01), 0));
	EXPECT_EQ(caliber::triangleFaceContact(prism, lying, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	// The bottom face and, the prism being fine, the vertices next to it (1.6 cm higher, within the band of
	// 2 % of its 2 m extent): 4 of them spanning the largest area, the deepest among them, each at its own
	// vertex's height above the floor (1 cm plus its rise above the bottom face) at the ends (z = +-1).
	ASSERT_EQ(out.points.size(), 4u);
	btScalar closest = BT_LARGE_FLOAT;
	for (const Point& p : out.points)
	{
		const btScalar x = p.onTriangle.x();
		const btScalar rise = apothem - btSqrt(radius * radius - x * x);
		EXPECT_NEAR(p.distance, btScalar(0.01) + rise, btScalar(1e-4)) << "vertex at x = " << x;
		EXPECT_NEAR(btFabs(p.onTriangle.z()), 1, kTolerance);
		closest = btMin(closest, p.distance);
	}
	EXPECT_NEAR(closest, btScalar(0.01), kTolerance);
	// Standing on an end cap (50 corners, more than a face keeps): at most 4 points, all 1 cm above.
	out.points.clear();
	const btTransform standing(btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI),
	                           btVector3(0, 1 + prism.getMargin() + btScalar(0.01), 0));
	EXPECT_EQ(caliber::triangleFaceContact(prism, standing, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	EXPECT_EQ(out.points.size(), 4u);
	for (const Point& p : out.points) EXPECT_NEAR(p.distance, btScalar(0.01), kTolerance);
}

TEST(ConvexTriangleClipping, OnlyBoxesHullsAndShapesWithAPolyhedronAreClipped)
{
	btBoxShape box(btVector3(1, 1, 1));
	EXPECT_EQ(caliber::triangleClippingOf(box), caliber::kClipBeforeGjk);
	btConvexHullShape hull;
	addCubeCorners(hull);
	EXPECT_EQ(caliber::triangleClippingOf(hull), caliber::kClipAfterGjk);
	// A point cloud has no face without its polyhedron: GJK's point, as for spheres.
	btVector3 cloudPoints[4] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)};
	btConvexPointCloudShape cloud(cloudPoints, 4, btVector3(1, 1, 1));
	EXPECT_EQ(caliber::triangleClippingOf(cloud), caliber::kNoClipping);
	ASSERT_TRUE(cloud.initializePolyhedralFeatures());
	EXPECT_EQ(caliber::triangleClippingOf(cloud), caliber::kClipAfterGjk);
	btSphereShape sphere(1);
	EXPECT_EQ(caliber::triangleClippingOf(sphere), caliber::kNoClipping);
}

TEST(ConvexTriangleClipping, DegenerateTriangleOrEmptyHullIsLeftToGjkWithoutPoints)
{
	btBoxShape box(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	// All three corners on one line: no normal.
	btTriangleShape line(btVector3(-1, 0, 0), btVector3(0, 0, 0), btVector3(1, 0, 0));
	Recorder out;
	const btTransform at(btQuaternion::getIdentity(), btVector3(0, btScalar(0.51), 0));
	EXPECT_EQ(caliber::triangleFaceContact(box, at, line, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	btConvexHullShape empty;
	EXPECT_EQ(caliber::triangleFaceContact(empty, at, bigFloorTriangle(), btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	EXPECT_TRUE(out.points.empty());
	// Before GJK the same: nothing settled, nothing reported; the degenerate triangle keeps no search (the
	// search along GJK's normal finds it degenerate again), the empty hull's kept search holds no points.
	btConvexHullShape cube;
	addCubeCorners(cube);
	caliber::TriangleFaceSearch search;
	EXPECT_EQ(caliber::hullTriangleFaceContactBeforeGjk(cube, at, line, btTransform::getIdentity(), kReach, out, search),
	          caliber::kTriangleNeedsGjk);
	EXPECT_FALSE(search.done);
	EXPECT_EQ(caliber::hullTriangleFaceContactBeforeGjk(empty, at, bigFloorTriangle(), btTransform::getIdentity(),
	                                                    kReach, out, search),
	          caliber::kTriangleNeedsGjk);
	EXPECT_EQ(search.count, 0);
	EXPECT_TRUE(out.points.empty());
}

TEST(ConvexTriangleClipping, ChoosingFourOfManyPointsKeepsTheCornersOfTheirSpan)
{
	// A 3 x 3 grid of points at equal depth: the four corners span the largest area.
	btVector3 points[9];
	btScalar distances[9];
	for (int i = 0; i < 9; ++i)
	{
		points[i] = btVector3(btScalar(i % 3), 0, btScalar(i / 3));
		distances[i] = 0;
	}
	int chosen[4];
	const int count = caliber::chooseManifoldPoints(points, distances, 9, btVector3(0, 1, 0), chosen);
	ASSERT_EQ(count, 4);
	int cornerMask = 0;
	for (int i = 0; i < count; ++i)
	{
		const int index = chosen[i];
		EXPECT_TRUE(index == 0 || index == 2 || index == 6 || index == 8) << "chose inner point " << index;
		cornerMask |= 1 << index;
	}
	EXPECT_EQ(cornerMask, (1 << 0) | (1 << 2) | (1 << 6) | (1 << 8));
}

namespace
{
// A barrel-like hull: two octagons of radius 0.5 at y = +-0.6 and one of radius 0.7 at y = 0, each rim
// listed twice (duplicates, as Bullet's barrel has).
void addBarrelPoints(btConvexHullShape& hull)
{
	const btScalar ys[3] = {btScalar(-0.6), 0, btScalar(0.6)};
	const btScalar radii[3] = {btScalar(0.5), btScalar(0.7), btScalar(0.5)};
	for (int ring = 0; ring < 3; ++ring)
		for (int copy = 0; copy < (ring == 1 ? 1 : 2); ++copy)
			for (int k = 0; k < 8; ++k)
			{
				const btScalar angle = SIMD_PI / 4 * btScalar(k);
				hull.addPoint(btVector3(radii[ring] * btCos(angle), ys[ring], radii[ring] * btSin(angle)), false);
			}
	hull.recalcLocalAabb();
}

// GJK's distance between the hull and the triangle (margins included), from a detector made for this query;
// BT_LARGE_FLOAT when it reports none.
btScalar gjkDistance(const btConvexHullShape& hull, const btTransform& at, const btTriangleShape& triangle)
{
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkPairDetector gjk(&hull, &triangle, &simplex, &epa);
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = at;
	input.m_transformB = btTransform::getIdentity();
	btPointCollector closest;
	gjk.getClosestPoints(input, closest, 0);
	return closest.m_hasResult ? closest.m_distance : BT_LARGE_FLOAT;
}

bool samePoints(const Recorder& a, const Recorder& b)
{
	if (a.points.size() != b.points.size()) return false;
	for (size_t i = 0; i < a.points.size(); ++i)
		if (!(a.points[i].normal == b.points[i].normal) || !(a.points[i].onTriangle == b.points[i].onTriangle) ||
		    a.points[i].distance != b.points[i].distance)
			return false;
	return true;
}
}  // namespace

// The search before GJK (hullTriangleFaceContactBeforeGjk) settles a pair only where GJK has nothing to add:
// out of reach only when GJK finds the pair farther apart than reach, a face contact only when GJK's distance
// is the closest reported point's (the face normal is the closest direction); otherwise it reports nothing,
// and the search it keeps gives the search along GJK's normal exactly the points it finds without it.
TEST(ConvexTriangleClipping, BeforeGjkAHullIsSettledOnlyWhereGjkAgreesAndItsSearchIsReusedBitForBit)
{
	btConvexHullShape hull;
	addBarrelPoints(hull);
	btTriangleShape triangle(btVector3(-1, 0, -1), btVector3(-1, 0, 2), btVector3(2, 0, -1));
	triangle.setMargin(btScalar(0.01));
	unsigned int seed = 7;
	auto uniform = [&seed](btScalar low, btScalar high) {
		seed = seed * 1664525u + 1013904223u;
		return low + (high - low) * btScalar((seed >> 8) & 0xffff) / btScalar(0xffff);
	};
	int settledOut = 0, settledFace = 0, leftToGjk = 0;
	for (int trial = 0; trial < 1000; ++trial)
	{
		const btVector3 axis = btVector3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
		const btQuaternion turn = axis.length2() > btScalar(0.01) ? btQuaternion(axis.normalized(), uniform(0, SIMD_PI))
		                                                          : btQuaternion::getIdentity();
		const btTransform at(turn, btVector3(uniform(-2, 2), uniform(btScalar(0.4), btScalar(1.2)), uniform(-2, 2)));
		Recorder before;
		caliber::TriangleFaceSearch search;
		const caliber::TriangleFaceOutcome outcome = caliber::hullTriangleFaceContactBeforeGjk(
		    hull, at, triangle, btTransform::getIdentity(), kReach, before, search);
		const btScalar distance = gjkDistance(hull, at, triangle);
		if (outcome == caliber::kTriangleOutOfReach)
		{
			++settledOut;
			EXPECT_TRUE(before.points.empty());
			// GJK on the cores converges to float rounding of sizes of order 1.
			EXPECT_GT(distance, kReach - btScalar(1e-4)) << "trial " << trial;
			continue;
		}
		if (outcome == caliber::kTriangleFaceContact)
		{
			++settledFace;
			ASSERT_FALSE(before.points.empty());
			if (before.closest() >= 0)
			{
				EXPECT_NEAR(distance, before.closest(), btScalar(1e-3)) << "trial " << trial;
			}
			continue;
		}
		++leftToGjk;
		EXPECT_EQ(outcome, caliber::kTriangleNeedsGjk);
		EXPECT_TRUE(before.points.empty());
		// Along the face normal and along a leaning one, with and without the kept search: the same points.
		const btVector3 leaning(btSin(btScalar(0.3)), btCos(btScalar(0.3)), 0);
		for (const btVector3& normal : {btVector3(0, 1, 0), leaning})
		{
			Recorder reused, fresh;
			const caliber::TriangleFaceOutcome withSearch = caliber::triangleFaceContactAlongGjkNormal(
			    hull, at, triangle, btTransform::getIdentity(), kReach, normal, kTouching, kTouching, reused, &search);
			const caliber::TriangleFaceOutcome without = caliber::triangleFaceContactAlongGjkNormal(
			    hull, at, triangle, btTransform::getIdentity(), kReach, normal, kTouching, kTouching, fresh);
			EXPECT_EQ(withSearch, without) << "trial " << trial;
			EXPECT_TRUE(samePoints(reused, fresh)) << "trial " << trial;
		}
	}
	// The poses cover all three cases.
	EXPECT_GT(settledOut, 10);
	EXPECT_GT(settledFace, 10);
	EXPECT_GT(leftToGjk, 10);
}
