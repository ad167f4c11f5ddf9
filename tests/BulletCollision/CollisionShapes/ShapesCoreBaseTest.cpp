// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Tests of the shape base classes and of btBroadphaseProxy's classification helpers.

#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConcaveShape.h"
#include "BulletCollision/CollisionShapes/btConvexInternalShape.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "BulletCollision/CollisionShapes/ShapesCoreTestUtil.h"

using namespace shapes_core_test;

namespace
{
// A segment from -halfLength to +halfLength on x: the smallest convex shape with a non-trivial support.
class SegmentShape : public btConvexInternalShape
{
public:
	explicit SegmentShape(btScalar halfLength)
	{
		m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE;
		m_implicitShapeDimensions.setValue(halfLength, 0, 0);
	}
	btVector3 localGetSupportingVertexWithoutMargin(const btVector3& vec) const override
	{
		const btScalar h = m_implicitShapeDimensions.x() * m_localScaling.x();
		return btVector3(vec.x() >= 0 ? h : -h, 0, 0);
	}
	void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* vectors, btVector3* out,
	                                                       int count) const override
	{
		for (int i = 0; i < count; ++i) out[i] = localGetSupportingVertexWithoutMargin(vectors[i]);
	}
	void calculateLocalInertia(btScalar, btVector3& inertia) const override { inertia.setValue(0, 0, 0); }
	const char* getName() const override { return "SEGMENT"; }
};
}  // namespace

TEST(BroadphaseProxyTest, EnumValuesMatchBulletOrder)
{
	EXPECT_EQ(0, BOX_SHAPE_PROXYTYPE);
	EXPECT_EQ(4, CONVEX_HULL_SHAPE_PROXYTYPE);
	EXPECT_EQ(7, IMPLICIT_CONVEX_SHAPES_START_HERE);
	EXPECT_EQ(8, SPHERE_SHAPE_PROXYTYPE);
	EXPECT_EQ(10, CAPSULE_SHAPE_PROXYTYPE);
	EXPECT_EQ(11, CONE_SHAPE_PROXYTYPE);
	EXPECT_EQ(13, CYLINDER_SHAPE_PROXYTYPE);
	EXPECT_EQ(19, CUSTOM_CONVEX_SHAPE_TYPE);
	EXPECT_EQ(20, CONCAVE_SHAPES_START_HERE);
	EXPECT_EQ(21, TRIANGLE_MESH_SHAPE_PROXYTYPE);
	EXPECT_EQ(24, TERRAIN_SHAPE_PROXYTYPE);
	EXPECT_EQ(27, EMPTY_SHAPE_PROXYTYPE);
	EXPECT_EQ(28, STATIC_PLANE_PROXYTYPE);
	EXPECT_EQ(29, CUSTOM_CONCAVE_SHAPE_TYPE);
	EXPECT_EQ(29, SDF_SHAPE_PROXYTYPE);
	EXPECT_EQ(30, CONCAVE_SHAPES_END_HERE);
	EXPECT_EQ(31, COMPOUND_SHAPE_PROXYTYPE);
	EXPECT_EQ(32, SOFTBODY_SHAPE_PROXYTYPE);
	EXPECT_EQ(35, INVALID_SHAPE_PROXYTYPE);
	EXPECT_EQ(36, MAX_BROADPHASE_COLLISION_TYPES);
}

TEST(BroadphaseProxyTest, ClassificationFollowsTypeRanges)
{
	EXPECT_TRUE(btBroadphaseProxy::isPolyhedral(BOX_SHAPE_PROXYTYPE));
	EXPECT_FALSE(btBroadphaseProxy::isPolyhedral(SPHERE_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isConvex(CYLINDER_SHAPE_PROXYTYPE));
	EXPECT_FALSE(btBroadphaseProxy::isConvex(TRIANGLE_MESH_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isConcave(TRIANGLE_MESH_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isConcave(STATIC_PLANE_PROXYTYPE));
	EXPECT_FALSE(btBroadphaseProxy::isConcave(CONCAVE_SHAPES_START_HERE));
	EXPECT_FALSE(btBroadphaseProxy::isConcave(CONCAVE_SHAPES_END_HERE));
	EXPECT_FALSE(btBroadphaseProxy::isConcave(COMPOUND_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isNonMoving(TERRAIN_SHAPE_PROXYTYPE));
	EXPECT_FALSE(btBroadphaseProxy::isNonMoving(GIMPACT_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isCompound(COMPOUND_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isSoftBody(SOFTBODY_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isInfinite(STATIC_PLANE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isConvex2d(BOX_2D_SHAPE_PROXYTYPE));
	EXPECT_TRUE(btBroadphaseProxy::isConvex2d(CONVEX_2D_SHAPE_PROXYTYPE));
	EXPECT_FALSE(btBroadphaseProxy::isConvex2d(BOX_SHAPE_PROXYTYPE));
}

TEST(BroadphaseProxyTest, PairStoresLowerUidFirstAndComparesByProxies)
{
	btBroadphaseProxy a(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, btBroadphaseProxy::DefaultFilter,
	                    btBroadphaseProxy::AllFilter);
	btBroadphaseProxy b;
	a.m_uniqueId = 7;
	b.m_uniqueId = 3;
	const btBroadphasePair ab(a, b), ba(b, a);
	EXPECT_EQ(&b, ab.m_pProxy0);
	EXPECT_EQ(&a, ab.m_pProxy1);
	EXPECT_TRUE(ab == ba);
	EXPECT_EQ(nullptr, ab.m_algorithm);
	EXPECT_EQ(7, a.getUid());
	EXPECT_EQ(-1, int(btBroadphaseProxy::AllFilter));

	btBroadphaseProxy c;
	c.m_uniqueId = 9;
	const btBroadphasePair ac(a, c);
	btBroadphasePairSortPredicate before;
	// Descending by the first id: (7, 9) sorts before (3, 7).
	EXPECT_TRUE(before(ac, ab));
	EXPECT_FALSE(before(ab, ac));
	EXPECT_FALSE(before(ab, ba));
}

TEST(ConvexInternalShapeTest, DefaultsAreBulletsAndClassificationComesFromType)
{
	SegmentShape segment(1);
	EXPECT_EQ(CONVEX_DISTANCE_MARGIN, segment.getMargin());
	EXPECT_EQ(btVector3(1, 1, 1), segment.getLocalScaling());
	EXPECT_TRUE(segment.isConvex());
	EXPECT_FALSE(segment.isConcave());
	EXPECT_FALSE(segment.isPolyhedral());
	EXPECT_EQ(-1, segment.getUserIndex());
	EXPECT_EQ(-1, segment.getUserIndex2());
	EXPECT_EQ(nullptr, segment.getUserPointer());
	int marker = 0;
	segment.setUserPointer(&marker);
	segment.setUserIndex(4);
	segment.setUserIndex2(5);
	EXPECT_EQ(&marker, segment.getUserPointer());
	EXPECT_EQ(4, segment.getUserIndex());
	EXPECT_EQ(5, segment.getUserIndex2());
	EXPECT_EQ(0, segment.getNumPreferredPenetrationDirections());
}

TEST(ConvexInternalShapeTest, SupportWithMarginIsCorePlusMarginAlongUnitDirection)
{
	SegmentShape segment(2);
	segment.setMargin(btScalar(0.5));
	Random random(11);
	for (int i = 0; i < 100; ++i)
	{
		const btVector3 dir = random.vector(3);
		if (dir.length2() < btScalar(0.01)) continue;
		const btVector3 expected =
		    segment.localGetSupportingVertexWithoutMargin(dir) + btScalar(0.5) * dir.normalized();
		EXPECT_TRUE(vectorsNear(expected, segment.localGetSupportingVertex(dir), kRoundingTolerance * 4));
		EXPECT_TRUE(vectorsNear(expected, segment.localGetSupportVertexNonVirtual(dir), kRoundingTolerance * 4));
	}
}

TEST(ConvexInternalShapeTest, ZeroAndNanDirectionsGiveFiniteSurfacePoint)
{
	SegmentShape segment(2);
	segment.setMargin(btScalar(0.5));
	const btScalar nan = BT_NAN;
	// The documented stand-in direction is (-1, -1, -1): the far end -2 on x, plus the margin along it.
	const btVector3 expected = btVector3(-2, 0, 0) + btScalar(0.5) * btVector3(-1, -1, -1).normalized();
	EXPECT_TRUE(vectorsNear(expected, segment.localGetSupportingVertex(btVector3(0, 0, 0)), kRoundingTolerance));
	EXPECT_TRUE(vectorsNear(expected, segment.localGetSupportingVertex(btVector3(nan, 0, 0)), kRoundingTolerance));
	EXPECT_TRUE(vectorsNear(expected, segment.localGetSupportVertexNonVirtual(btVector3(0, 0, 0)), kRoundingTolerance));
}

TEST(ConvexInternalShapeTest, AabbSlowIsTightBoxOfMarginShape)
{
	SegmentShape segment(2);
	segment.setMargin(btScalar(0.25));
	Random random(12);
	for (int i = 0; i < 50; ++i)
	{
		const btTransform t = random.transform();
		btVector3 aabbMin, aabbMax;
		segment.getAabb(t, aabbMin, aabbMax);
		// The segment's world end points, grown by the margin sphere, give the exact box.
		const btVector3 p0 = t(btVector3(-2, 0, 0)), p1 = t(btVector3(2, 0, 0));
		btVector3 expectedMin = p0, expectedMax = p0;
		expectedMin.setMin(p1);
		expectedMax.setMax(p1);
		const btVector3 grow(btScalar(0.25), btScalar(0.25), btScalar(0.25));
		// Tolerance: rounding of a transform of a point of size ~5.
		EXPECT_TRUE(vectorsNear(expectedMin - grow, aabbMin, kRoundingTolerance * 8));
		EXPECT_TRUE(vectorsNear(expectedMax + grow, aabbMax, kRoundingTolerance * 8));
	}
}

TEST(ConvexInternalShapeTest, ProjectGivesOrderedIntervalAndWitnesses)
{
	SegmentShape segment(2);
	segment.setMargin(0);
	const btTransform t(btQuaternion::getIdentity(), btVector3(1, 0, 0));
	btScalar minProj, maxProj;
	btVector3 witnessMin, witnessMax;
	segment.project(t, btVector3(1, 0, 0), minProj, maxProj, witnessMin, witnessMax);
	EXPECT_NEAR(-1, minProj, kRoundingTolerance);
	EXPECT_NEAR(3, maxProj, kRoundingTolerance);
	EXPECT_TRUE(vectorsNear(btVector3(-1, 0, 0), witnessMin, kRoundingTolerance));
	EXPECT_TRUE(vectorsNear(btVector3(3, 0, 0), witnessMax, kRoundingTolerance));
}

TEST(ConvexInternalShapeTest, BoundingSphereAndMotionDiscComeFromLocalAabb)
{
	SegmentShape segment(3);
	segment.setMargin(0);
	btVector3 center;
	btScalar radius;
	segment.getBoundingSphere(center, radius);
	EXPECT_TRUE(vectorsNear(btVector3(0, 0, 0), center, kRoundingTolerance));
	EXPECT_NEAR(3, radius, kRoundingTolerance * 4);
	EXPECT_NEAR(3, segment.getAngularMotionDisc(), kRoundingTolerance * 4);
	EXPECT_NEAR(btScalar(1.5), segment.getContactBreakingThreshold(btScalar(0.5)), kRoundingTolerance * 4);
}

TEST(ConvexInternalShapeTest, BoxBoundingSphereIsTheSphereAroundItsLocalAabb)
{
	// The box's own bounding sphere must be the base class's (the sphere around the margin-inclusive
	// local bounding box): the contact breaking threshold and the speculative reach depend on it.
	btBoxShape box(btVector3(1, 2, 3));
	box.setMargin(btScalar(0.25));
	btVector3 aabbMin, aabbMax;
	box.getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
	btVector3 center;
	btScalar radius;
	box.getBoundingSphere(center, radius);
	EXPECT_TRUE(vectorsNear((aabbMin + aabbMax) * btScalar(0.5), center, kRoundingTolerance));
	// The corners are at (1, 2, 3) (the margin lies inside the half extents): radius sqrt(14).
	EXPECT_NEAR(btSqrt(btScalar(14)), radius, kRoundingTolerance * 4);
	EXPECT_NEAR((aabbMax - aabbMin).length() * btScalar(0.5), radius, kRoundingTolerance * 4);
	EXPECT_NEAR(btSqrt(btScalar(14)), box.getAngularMotionDisc(), kRoundingTolerance * 4);
}

TEST(ConvexInternalShapeTest, TemporalAabbGrowsTowardsMotionAndByRotation)
{
	SegmentShape segment(1);
	segment.setMargin(0);
	btVector3 aabbMin, aabbMax;
	segment.calculateTemporalAabb(btTransform::getIdentity(), btVector3(2, -3, 0), btVector3(0, 0, 0), btScalar(0.5),
	                              aabbMin, aabbMax);
	EXPECT_TRUE(vectorsNear(btVector3(-1, btScalar(-1.5), 0), aabbMin, kRoundingTolerance));
	EXPECT_TRUE(vectorsNear(btVector3(2, 0, 0), aabbMax, kRoundingTolerance));
	// Angular speed 2 for 0.5 s with disc 1 grows every side by 1.
	segment.calculateTemporalAabb(btTransform::getIdentity(), btVector3(0, 0, 0), btVector3(0, 2, 0), btScalar(0.5),
	                              aabbMin, aabbMax);
	EXPECT_TRUE(vectorsNear(btVector3(-2, -1, -1), aabbMin, kRoundingTolerance * 4));
	EXPECT_TRUE(vectorsNear(btVector3(2, 1, 1), aabbMax, kRoundingTolerance * 4));
}

TEST(ConvexInternalShapeTest, TemporalAabbIgnoresNanVelocity)
{
	SegmentShape segment(1);
	segment.setMargin(0);
	btVector3 aabbMin, aabbMax;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(segment.calculateTemporalAabb(btTransform::getIdentity(), btVector3(BT_NAN, 0, 0), btVector3(0, 0, 0),
	                                           1, aabbMin, aabbMax),
	             "assertion failed");
#else
	segment.calculateTemporalAabb(btTransform::getIdentity(), btVector3(BT_NAN, 0, 0), btVector3(0, BT_NAN, 0), 1,
	                              aabbMin, aabbMax);
	EXPECT_TRUE(vectorsNear(btVector3(-1, 0, 0), aabbMin, kRoundingTolerance));
	EXPECT_TRUE(vectorsNear(btVector3(1, 0, 0), aabbMax, kRoundingTolerance));
#endif
}

TEST(ConvexInternalShapeTest, LocalScalingIsMadePositive)
{
	SegmentShape segment(1);
	segment.setLocalScaling(btVector3(-2, 3, btScalar(-0.5)));
	EXPECT_EQ(btVector3(2, 3, btScalar(0.5)), segment.getLocalScaling());
	EXPECT_EQ(btVector3(2, 3, btScalar(0.5)), segment.getLocalScalingNV());
}

TEST(ConvexInternalShapeTest, NonFiniteScalingIsIgnored)
{
	SegmentShape segment(1);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(segment.setLocalScaling(btVector3(BT_NAN, 1, 1)), "assertion failed");
#else
	segment.setLocalScaling(btVector3(BT_NAN, 1, 1));
	EXPECT_EQ(btVector3(1, 1, 1), segment.getLocalScaling());
#endif
}

TEST(ConvexInternalShapeTest, NegativeMarginBecomesZero)
{
	SegmentShape segment(1);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(segment.setMargin(-1), "assertion failed");
	EXPECT_DEATH(segment.setMargin(BT_NAN), "assertion failed");
#else
	segment.setMargin(-1);
	EXPECT_EQ(btScalar(0), segment.getMargin());
	segment.setMargin(BT_NAN);
	EXPECT_EQ(btScalar(0), segment.getMarginNV());
#endif
}

TEST(ConvexInternalShapeTest, SafeMarginOnlyLowersTheMargin)
{
	SegmentShape segment(1);
	segment.setSafeMargin(btVector3(btScalar(0.1), 1, 1));
	EXPECT_NEAR(btScalar(0.01), segment.getMargin(), kRoundingTolerance);
	segment.setSafeMargin(btScalar(100));
	EXPECT_NEAR(btScalar(0.01), segment.getMargin(), kRoundingTolerance);
}

TEST(ConvexInternalShapeTest, NanTransformGivesOverflowAabb)
{
	SegmentShape segment(1);
	btTransform t = btTransform::getIdentity();
	t.getOrigin().setX(BT_NAN);
	btVector3 aabbMin, aabbMax;
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(segment.getAabb(t, aabbMin, aabbMax), "assertion failed");
#else
	segment.getAabb(t, aabbMin, aabbMax);
	EXPECT_EQ(btVector3(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT), aabbMin);
	EXPECT_EQ(btVector3(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), aabbMax);
#endif
}

TEST(ConcaveShapeTest, MarginDefaultsToZeroAndRejectsNegative)
{
	class Flat : public btConcaveShape
	{
	public:
		Flat() { m_shapeType = CUSTOM_CONCAVE_SHAPE_TYPE; }
		void processAllTriangles(btTriangleCallback*, const btVector3&, const btVector3&) const override {}
		void getAabb(const btTransform&, btVector3& aabbMin, btVector3& aabbMax) const override
		{
			aabbMin.setValue(0, 0, 0);
			aabbMax.setValue(0, 0, 0);
		}
		void setLocalScaling(const btVector3&) override {}
		const btVector3& getLocalScaling() const override { return m_scaling; }
		void calculateLocalInertia(btScalar, btVector3& inertia) const override { inertia.setValue(0, 0, 0); }
		const char* getName() const override { return "FLAT"; }
		btVector3 m_scaling = btVector3(1, 1, 1);
	};
	Flat flat;
	EXPECT_EQ(btScalar(0), flat.getMargin());
	EXPECT_TRUE(flat.isConcave());
	EXPECT_TRUE(flat.isNonMoving());
	flat.setMargin(btScalar(0.1));
	EXPECT_EQ(btScalar(0.1), flat.getMargin());
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(flat.setMargin(-1), "assertion failed");
#else
	flat.setMargin(-1);
	EXPECT_EQ(btScalar(0), flat.getMargin());
#endif
}
