// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The margin-shrunk hull shape: hull plus margin is the hull of the given corners.
#include <gtest/gtest.h>

#include "HullShapes/MarginHullShape.h"

namespace
{
btAlignedObjectArray<btVector3> boxCorners(const btVector3& half)
{
	btAlignedObjectArray<btVector3> corners;
	for (int i = 0; i < 8; ++i)
		corners.push_back(
		    btVector3((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(), (i & 4) ? half.z() : -half.z()));
	return corners;
}
}  // namespace

// A 2 m cube: the default margin (0.04) is used, and the support point with margin along each axis is
// the face of the cube, 1 m out.
TEST(MarginHullShape, HullPlusMarginHasTheCornersFaces)
{
	std::unique_ptr<btConvexHullShape> shape = caliber::makeMarginHullShape(boxCorners(btVector3(1, 1, 1)));
	ASSERT_NE(shape, nullptr);
	EXPECT_FLOAT_EQ(shape->getMargin(), btScalar(0.04));
	EXPECT_NEAR(shape->localGetSupportingVertex(btVector3(1, 0, 0)).x(), 1, 1e-5);
	EXPECT_NEAR(shape->localGetSupportingVertex(btVector3(0, 0, -1)).z(), -1, 1e-5);
}

// A plate 1 cm thick (inner radius 5 mm): the margin shrinks to a quarter of that, and the plate keeps its
// thickness (with the default margin it would be 8 cm thicker).
TEST(MarginHullShape, ThinPiecesGetASmallerMarginAndKeepTheirThickness)
{
	std::unique_ptr<btConvexHullShape> shape =
	    caliber::makeMarginHullShape(boxCorners(btVector3(1, 1, btScalar(0.005))));
	ASSERT_NE(shape, nullptr);
	EXPECT_NEAR(shape->getMargin(), 0.00125, 1e-6);
	EXPECT_NEAR(shape->localGetSupportingVertex(btVector3(0, 0, 1)).z(), 0.005, 1e-5);
}

TEST(MarginHullShape, FlatOrTooFewCornersGiveNoShape)
{
	EXPECT_EQ(caliber::makeMarginHullShape(boxCorners(btVector3(1, 1, 0))), nullptr);
	btAlignedObjectArray<btVector3> three;
	three.push_back(btVector3(0, 0, 0));
	three.push_back(btVector3(1, 0, 0));
	three.push_back(btVector3(0, 1, 0));
	EXPECT_EQ(caliber::makeMarginHullShape(three), nullptr);
	EXPECT_EQ(caliber::makeMarginHullShape(btAlignedObjectArray<btVector3>()), nullptr);
}
