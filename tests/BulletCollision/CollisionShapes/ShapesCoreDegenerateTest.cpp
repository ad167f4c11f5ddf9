// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bad input to the primitive shapes: each case asserts in assert builds and has a documented, finite
// result in release builds.

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btEmptyShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/ShapesCoreCases.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"

using namespace shapes_core_test;

// ---- degenerate input ----------------------------------------------------------------------------

TEST(ShapesCoreTest, ZeroSizeShapesArePointsWithoutNan)
{
	btBoxShape box(btVector3(0, 0, 0));
	btSphereShape sphere(0);
	btCapsuleShape capsule(0, 0);
	btCylinderShape cylinder(btVector3(0, 0, 0));
	btConeShape cone(0, 0);
	const btConvexInternalShape* shapes[] = {&box, &sphere, &capsule, &cylinder, &cone};
	const btTransform t(btQuaternion(btVector3(1, 1, 0).normalized(), 1), btVector3(1, 2, 3));
	for (const btConvexInternalShape* shape : shapes)
	{
		SCOPED_TRACE(shape->getName());
		btVector3 aabbMin, aabbMax, inertia;
		shape->getAabb(t, aabbMin, aabbMax);
		// Cones keep their default margin (outside the dimensions); the others have margin 0.
		const btScalar m = shape->getMargin();
		EXPECT_TRUE(vectorsNear(btVector3(1, 2, 3) - btVector3(m, m, m), aabbMin, kShapeRounding));
		EXPECT_TRUE(vectorsNear(btVector3(1, 2, 3) + btVector3(m, m, m), aabbMax, kShapeRounding));
		shape->calculateLocalInertia(1, inertia);
		EXPECT_TRUE(isFiniteVector(inertia));
		EXPECT_TRUE(isFiniteVector(shape->localGetSupportingVertex(btVector3(1, 2, 3))));
		EXPECT_TRUE(isFiniteVector(shape->localGetSupportingVertexWithoutMargin(btVector3(0, 0, 0))));
	}
	btVector3 inertia;
	box.calculateLocalInertia(1, inertia);
	EXPECT_EQ(btVector3(0, 0, 0), inertia);
}

TEST(ShapesCoreTest, ZeroAndNanDirectionsGiveFiniteSupportPoints)
{
	for (const ShapeCase& c : makeShapeCases())
	{
		SCOPED_TRACE(c.label);
		const btVector3 bad[] = {btVector3(0, 0, 0), btVector3(BT_NAN, 1, 0), btVector3(BT_INFINITY, 0, 0)};
		for (const btVector3& dir : bad)
		{
			const btVector3 full = c.shape->localGetSupportingVertex(dir);
			EXPECT_TRUE(isFiniteVector(full));
			EXPECT_TRUE(isFiniteVector(c.shape->localGetSupportingVertexWithoutMargin(dir)));
			EXPECT_TRUE(isFiniteVector(c.shape->localGetSupportVertexNonVirtual(dir)));
			// The documented stand-in direction (-1, -1, -1) gives a point of the surface.
			EXPECT_NEAR(c.margin, c.distanceToCore(full), kShapeRounding);
		}
	}
	btBoxShape box(btVector3(1, 2, 3));
	EXPECT_EQ(btVector3(-1, -2, -3), box.localGetSupportingVertex(btVector3(BT_NAN, 0, BT_NAN)));
}

TEST(ShapesCoreTest, NanTransformGivesOverflowAabbForEveryShape)
{
	std::vector<ShapeCase> cases = makeShapeCases();
	ShapeCase boxCase;
	boxCase.label = "box";
	boxCase.shape = std::make_shared<btBoxShape>(btVector3(1, 2, 3));
	cases.push_back(boxCase);
	btTransform t = btTransform::getIdentity();
	t.getBasis()[1].setY(BT_NAN);
	for (const ShapeCase& c : cases)
	{
		SCOPED_TRACE(c.label);
		btVector3 aabbMin, aabbMax;
#if CALIBER_ASSERTS_ENABLED
		EXPECT_DEATH(c.shape->getAabb(t, aabbMin, aabbMax), "assertion failed");
#else
		c.shape->getAabb(t, aabbMin, aabbMax);
		EXPECT_EQ(btVector3(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT), aabbMin);
		EXPECT_EQ(btVector3(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), aabbMax);
#endif
	}
	btEmptyShape empty;
	btVector3 aabbMin, aabbMax;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(empty.getAabb(t, aabbMin, aabbMax), "assertion failed");
#else
	empty.getAabb(t, aabbMin, aabbMax);
	EXPECT_EQ(btVector3(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), aabbMax);
#endif
}

TEST(ShapesCoreTest, NegativeSizesAreMadePositive)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btBoxShape(btVector3(-1, 2, 3)), "assertion failed");
	EXPECT_DEATH(btSphereShape(-1), "assertion failed");
	EXPECT_DEATH(btCapsuleShape(1, -2), "assertion failed");
	EXPECT_DEATH(btCylinderShape(btVector3(1, -2, 1)), "assertion failed");
	EXPECT_DEATH(btConeShape(-1, 2), "assertion failed");
#else
	EXPECT_TRUE(
	    vectorsNear(btVector3(1, 2, 3), btBoxShape(btVector3(-1, 2, 3)).getHalfExtentsWithMargin(), kShapeRounding));
	EXPECT_EQ(btScalar(1), btSphereShape(-1).getRadius());
	EXPECT_EQ(btScalar(1), btCapsuleShape(1, -2).getHalfHeight());
	EXPECT_TRUE(vectorsNear(btVector3(1, 2, 1), btCylinderShape(btVector3(1, -2, 1)).getHalfExtentsWithMargin(),
	                        kShapeRounding));
	EXPECT_EQ(btScalar(1), btConeShape(-1, 2).getRadius());
#endif
}

TEST(ShapesCoreTest, NanSizesBecomeZero)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btSphereShape(BT_NAN), "assertion failed");
	EXPECT_DEATH(btBoxShape(btVector3(BT_NAN, 1, 1)), "assertion failed");
#else
	btSphereShape sphere(BT_NAN);
	EXPECT_EQ(btScalar(0), sphere.getRadius());
	btBoxShape box(btVector3(BT_NAN, 1, 1));
	EXPECT_EQ(btScalar(0), box.getHalfExtentsWithMargin().x());
	btVector3 aabbMin, aabbMax;
	box.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	EXPECT_TRUE(isFiniteVector(aabbMin) && isFiniteVector(aabbMax));
#endif
}

TEST(ShapesCoreTest, BadMassGivesZeroInertia)
{
	btBoxShape box(btVector3(1, 1, 1));
	btVector3 inertia(1, 1, 1);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(box.calculateLocalInertia(-1, inertia), "assertion failed");
	EXPECT_DEATH(btSphereShape(1).calculateLocalInertia(BT_NAN, inertia), "assertion failed");
#else
	box.calculateLocalInertia(-1, inertia);
	EXPECT_EQ(btVector3(0, 0, 0), inertia);
	inertia.setValue(1, 1, 1);
	btConeShape(1, 1).calculateLocalInertia(BT_NAN, inertia);
	EXPECT_EQ(btVector3(0, 0, 0), inertia);
#endif
	// Zero mass (a static body) is valid and gives zero inertia.
	box.calculateLocalInertia(0, inertia);
	EXPECT_EQ(btVector3(0, 0, 0), inertia);
}

TEST(ShapesCoreTest, ZeroPlaneNormalBecomesXAxis)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btStaticPlaneShape(btVector3(0, 0, 0), 1), "assertion failed");
#else
	btStaticPlaneShape plane(btVector3(0, 0, 0), 1);
	EXPECT_EQ(btVector3(1, 0, 0), plane.getPlaneNormal());
#endif
}

TEST(ShapesCoreTest, InvalidBoxFeatureIndicesAssert)
{
	btBoxShape box(btVector3(1, 2, 3));
	btVector3 v;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(box.getPreferredPenetrationDirection(6, v), "assertion failed");
	EXPECT_DEATH(box.getEdge(-1, v, v), "assertion failed");
#else
	box.getPreferredPenetrationDirection(6, v);
	EXPECT_EQ(btVector3(0, 0, 0), v);
	btVector3 a, b, a0, b0;
	box.getEdge(-1, a, b);
	box.getEdge(0, a0, b0);
	EXPECT_EQ(a0, a);
	EXPECT_EQ(b0, b);
#endif
}
