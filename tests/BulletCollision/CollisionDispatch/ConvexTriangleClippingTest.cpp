// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The face contact of a box or hull with one triangle (caliber::triangleFaceContact): the clipped face
// over the triangle with exact distances, the outcome that tells the algorithm whether GJK must still
// run, and degenerate input (a zero-area triangle, a hull without points) left to GJK.

#include <gtest/gtest.h>

#include <vector>

#include "BulletCollision/CollisionDispatch/btConvexTriangleClipping.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"

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
};

// A large triangle in the plane y = 0 (its margin 0), covering [-10, 10] in x and z around the origin.
btTriangleShape bigFloorTriangle()
{
	btTriangleShape triangle(btVector3(-10, 0, -10), btVector3(-10, 0, 30), btVector3(30, 0, -10));
	triangle.setMargin(0);
	return triangle;
}

const btScalar kReach = btScalar(0.1);
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

TEST(ConvexTriangleClipping, HullOnAFaceGetsItsFaceMovedOutByTheMarginAndHullOnAnEdgeIsLeftToGjk)
{
	btConvexHullShape hull;
	for (int corner = 0; corner < 8; ++corner)
		hull.addPoint(btVector3((corner & 1) ? btScalar(0.5) : btScalar(-0.5), (corner & 2) ? btScalar(0.5) : btScalar(-0.5),
		                        (corner & 4) ? btScalar(0.5) : btScalar(-0.5)),
		              corner == 7);
	const btScalar margin = hull.getMargin();
	const btTriangleShape triangle = bigFloorTriangle();
	Recorder out;
	const btTransform flat(btQuaternion::getIdentity(), btVector3(0, btScalar(0.5) + margin + btScalar(0.02), 0));
	EXPECT_EQ(caliber::triangleFaceContact(hull, flat, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleFaceContact);
	ASSERT_EQ(out.points.size(), 4u);
	for (const Point& p : out.points) EXPECT_NEAR(p.distance, btScalar(0.02), kTolerance);
	// Turned 45 degrees about z: it stands on an edge (2 vertices), which is not a face.
	out.points.clear();
	const btTransform onEdge(btQuaternion(btVector3(0, 0, 1), SIMD_PI / 4), btVector3(0, btScalar(0.75), 0));
	EXPECT_EQ(caliber::triangleFaceContact(hull, onEdge, triangle, btTransform::getIdentity(), kReach, out),
	          caliber::kTriangleNeedsGjk);
	EXPECT_TRUE(out.points.empty());
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
