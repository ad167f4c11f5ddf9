// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Tests of the primitive shapes: support points and AABBs against brute force over sampled surfaces,
// analytic and Monte Carlo inertia, local scaling, margins and classification (bad input:
// ShapesCoreDegenerateTest.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
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

// Shape cases and brute-force helpers live in ShapesCoreCases.h.

// ---- support points ------------------------------------------------------------------------------

TEST(ShapesCoreTest, SupportPointMaximisesDotProductOverSampledSurface)
{
	Random random(101);
	for (const ShapeCase& c : makeShapeCases())
	{
		SCOPED_TRACE(c.label);
		for (int i = 0; i < 200; ++i)
		{
			const btVector3 dir = random.unitVector();
			const btScalar bruteCore = bruteForceMax(c.coreSamples, dir);
			const btVector3 core = c.shape->localGetSupportingVertexWithoutMargin(dir);
			// The exact support beats every sample (up to rounding) and the samples come within the
			// sampling error of it.
			EXPECT_GE(core.dot(dir), bruteCore - kShapeRounding);
			EXPECT_LE(core.dot(dir), bruteCore + c.samplingError + kShapeRounding);
			// With margin: the core grown by a sphere of radius margin.
			const btVector3 full = c.shape->localGetSupportingVertex(dir);
			EXPECT_GE(full.dot(dir), bruteCore + c.margin - kShapeRounding);
			EXPECT_LE(full.dot(dir), bruteCore + c.margin + c.samplingError + kShapeRounding);
			// Both lie on their surfaces.
			EXPECT_NEAR(0, c.distanceToCore(core), kShapeRounding);
			EXPECT_NEAR(c.margin, c.distanceToCore(full), kShapeRounding);
		}
	}
}

TEST(ShapesCoreTest, BoxSupportIsCornerOfFullBoxAndCoreCornerWithoutMargin)
{
	const btVector3 halfExtents(1, 2, btScalar(0.5));
	btBoxShape box(halfExtents);
	const btScalar m = box.getMargin();
	std::vector<btVector3> fullCorners, coreCorners;
	for (int i = 0; i < 8; ++i)
	{
		btVector3 v;
		box.getVertex(i, v);
		fullCorners.push_back(v);
		coreCorners.push_back(v - btVector3(v.x() > 0 ? m : -m, v.y() > 0 ? m : -m, v.z() > 0 ? m : -m));
	}
	Random random(102);
	for (int i = 0; i < 200; ++i)
	{
		const btVector3 dir = random.unitVector();
		EXPECT_NEAR(bruteForceMax(fullCorners, dir), box.localGetSupportingVertex(dir).dot(dir), kShapeRounding);
		EXPECT_NEAR(bruteForceMax(coreCorners, dir), box.localGetSupportingVertexWithoutMargin(dir).dot(dir),
		            kShapeRounding);
	}
}

TEST(ShapesCoreTest, BatchedSupportMatchesSingleSupport)
{
	Random random(103);
	std::vector<btVector3> dirs(16), out(16);
	for (btVector3& d : dirs) d = random.unitVector();
	std::vector<ShapeCase> cases = makeShapeCases();
	ShapeCase boxCase;
	boxCase.label = "box";
	boxCase.shape = std::make_shared<btBoxShape>(btVector3(1, 2, 3));
	cases.push_back(boxCase);
	for (const ShapeCase& c : cases)
	{
		SCOPED_TRACE(c.label);
		c.shape->batchedUnitVectorGetSupportingVertexWithoutMargin(dirs.data(), out.data(), 16);
		for (int i = 0; i < 16; ++i)
			EXPECT_TRUE(vectorsNear(c.shape->localGetSupportingVertexWithoutMargin(dirs[i]), out[i], 0));
	}
}

TEST(ShapesCoreTest, NonVirtualEntryPointsMatchVirtualOnes)
{
	Random random(104);
	std::vector<ShapeCase> cases = makeShapeCases();
	ShapeCase boxCase;
	boxCase.label = "box";
	boxCase.shape = std::make_shared<btBoxShape>(btVector3(1, 2, 3));
	cases.push_back(boxCase);
	for (const ShapeCase& c : cases)
	{
		SCOPED_TRACE(c.label);
		EXPECT_EQ(c.shape->getMargin(), c.shape->getMarginNonVirtual());
		for (int i = 0; i < 20; ++i)
		{
			const btVector3 dir = random.unitVector();
			EXPECT_TRUE(vectorsNear(c.shape->localGetSupportingVertexWithoutMargin(dir),
			                        c.shape->localGetSupportVertexWithoutMarginNonVirtual(dir), kShapeRounding));
			const btTransform t = random.transform();
			btVector3 min0, max0, min1, max1;
			c.shape->getAabb(t, min0, max0);
			c.shape->getAabbNonVirtual(t, min1, max1);
			EXPECT_TRUE(vectorsNear(min0, min1, 0));
			EXPECT_TRUE(vectorsNear(max0, max1, 0));
		}
	}
}

// ---- AABBs ---------------------------------------------------------------------------------------

TEST(ShapesCoreTest, AabbContainsSampledSurfaceAndIsTight)
{
	Random random(105);
	for (const ShapeCase& c : makeShapeCases())
	{
		SCOPED_TRACE(c.label);
		for (int trial = 0; trial < 50; ++trial)
		{
			const btTransform t = random.transform();
			btVector3 aabbMin, aabbMax;
			c.shape->getAabb(t, aabbMin, aabbMax);
			for (int axis = 0; axis < 3; ++axis)
			{
				// The farthest sampled surface point along +-axis is a world core sample plus the margin.
				btScalar hi = -SIMD_INFINITY, lo = SIMD_INFINITY;
				for (const btVector3& p : c.coreSamples)
				{
					const btScalar w = t(p)[axis];
					hi = btMax(hi, w);
					lo = btMin(lo, w);
				}
				hi += c.margin;
				lo -= c.margin;
				EXPECT_GE(aabbMax[axis], hi - kShapeRounding);
				EXPECT_LE(aabbMin[axis], lo + kShapeRounding);
				EXPECT_LE(aabbMax[axis], hi + c.samplingError + kShapeRounding);
				EXPECT_GE(aabbMin[axis], lo - c.samplingError - kShapeRounding);
			}
		}
	}
}

TEST(ShapesCoreTest, BoxAabbIsBoxOfRotatedCorners)
{
	btBoxShape box(btVector3(1, 2, btScalar(0.5)));
	Random random(106);
	for (int trial = 0; trial < 50; ++trial)
	{
		const btTransform t = random.transform();
		btVector3 aabbMin, aabbMax;
		box.getAabb(t, aabbMin, aabbMax);
		btVector3 lo(SIMD_INFINITY, SIMD_INFINITY, SIMD_INFINITY), hi(-SIMD_INFINITY, -SIMD_INFINITY, -SIMD_INFINITY);
		for (int i = 0; i < 8; ++i)
		{
			btVector3 v;
			box.getVertex(i, v);
			lo.setMin(t(v));
			hi.setMax(t(v));
		}
		EXPECT_TRUE(vectorsNear(lo, aabbMin, kShapeRounding));
		EXPECT_TRUE(vectorsNear(hi, aabbMax, kShapeRounding));
	}
}

// ---- inertia -------------------------------------------------------------------------------------

TEST(ShapesCoreTest, InertiaMatchesAnalyticFormulas)
{
	const btScalar mass = 3;
	btVector3 inertia;
	// Relative rounding of a handful of products.
	const btScalar tol = kShapeRounding;

	btSphereShape sphere(2);
	sphere.calculateLocalInertia(mass, inertia);
	EXPECT_TRUE(vectorsNear(btVector3(1, 1, 1) * (btScalar(0.4) * mass * 4), inertia, tol * 10));

	btBoxShape box(btVector3(1, 2, 3));
	box.calculateLocalInertia(mass, inertia);
	// Sides 2, 4, 6: m (b^2 + c^2) / 12.
	EXPECT_TRUE(
	    vectorsNear(btVector3(mass * (16 + 36) / 12, mass * (4 + 36) / 12, mass * (4 + 16) / 12), inertia, tol * 40));

	btCylinderShape cylinder(btVector3(1, 2, 1));
	cylinder.calculateLocalInertia(mass, inertia);
	// r = 1, H = 4: across m (3 + 16) / 12, axial m / 2.
	EXPECT_TRUE(vectorsNear(btVector3(mass * 19 / 12, mass / 2, mass * 19 / 12), inertia, tol * 20));

	btCylinderShapeX cylinderX(btVector3(2, 1, 1));
	cylinderX.calculateLocalInertia(mass, inertia);
	EXPECT_TRUE(vectorsNear(btVector3(mass / 2, mass * 19 / 12, mass * 19 / 12), inertia, tol * 20));

	btConeShapeZ cone(1, 2);
	cone.calculateLocalInertia(mass, inertia);
	// About the centre of mass: across 3/20 m r^2 + 3/80 m h^2, axial 3/10 m r^2.
	const btScalar coneAcross = mass * (btScalar(0.15) + btScalar(0.0375) * 4);
	EXPECT_TRUE(vectorsNear(btVector3(coneAcross, coneAcross, btScalar(0.3) * mass), inertia, tol * 10));

	btCapsuleShape capsule(1, 2);
	capsule.calculateLocalInertia(mass, inertia);
	// r = 1, cylinder length 2: volumes 2 pi and 4/3 pi, so 3/5 and 2/5 of the mass.
	const double mc = 0.6 * mass, ms = 0.4 * mass;
	const double axial = mc * 0.5 + ms * 0.4;
	const double across = mc * (0.25 + 4.0 / 12.0) + ms * (0.4 + 1.0 + 0.75);
	EXPECT_TRUE(vectorsNear(btVector3(btScalar(across), btScalar(axial), btScalar(across)), inertia, tol * 20));
}

namespace
{
// Monte Carlo second moments of a solid given by an inside test, sampled uniformly in a box. Returns
// per-axis estimates of m * E[r_perp^2] about center and their standard errors.
struct MonteCarloInertia
{
	btVector3 inertia, standardError, centroid;
};

MonteCarloInertia monteCarloInertia(const std::function<bool(double, double, double)>& inside, double extent,
                                    double mass, const double center[3], unsigned seed, int samples)
{
	std::mt19937 engine(seed);
	std::uniform_real_distribution<double> coordinate(-extent, extent);
	double sum[3] = {0, 0, 0}, sumSq[3] = {0, 0, 0}, centroid[3] = {0, 0, 0};
	int count = 0;
	for (int i = 0; i < samples; ++i)
	{
		const double p[3] = {coordinate(engine), coordinate(engine), coordinate(engine)};
		if (!inside(p[0], p[1], p[2])) continue;
		++count;
		const double d[3] = {p[0] - center[0], p[1] - center[1], p[2] - center[2]};
		for (int axis = 0; axis < 3; ++axis)
		{
			const int a = (axis + 1) % 3, b = (axis + 2) % 3;
			const double value = d[a] * d[a] + d[b] * d[b];
			sum[axis] += value;
			sumSq[axis] += value * value;
			centroid[axis] += p[axis];
		}
	}
	MonteCarloInertia result;
	result.inertia.setZero();
	result.standardError.setZero();
	result.centroid.setZero();
	for (int axis = 0; axis < 3; ++axis)
	{
		const double mean = sum[axis] / count;
		const double variance = sumSq[axis] / count - mean * mean;
		result.inertia[axis] = btScalar(mass * mean);
		result.standardError[axis] = btScalar(mass * std::sqrt(variance / count));
		result.centroid[axis] = btScalar(centroid[axis] / count);
	}
	return result;
}
}  // namespace

TEST(ShapesCoreTest, CapsuleInertiaMatchesMonteCarloIntegration)
{
	const double r = 0.6, halfHeight = 0.9, mass = 2;
	btCapsuleShape capsule{btScalar(r), btScalar(2 * halfHeight)};
	btVector3 inertia;
	capsule.calculateLocalInertia(btScalar(mass), inertia);
	const double center[3] = {0, 0, 0};
	const auto inside = [&](double x, double y, double z)
	{
		const double cy = std::max(-halfHeight, std::min(halfHeight, y));
		return x * x + (y - cy) * (y - cy) + z * z <= r * r;
	};
	const MonteCarloInertia mc = monteCarloInertia(inside, halfHeight + r, mass, center, 2024u, 400000);
	for (int axis = 0; axis < 3; ++axis)
	{
		// Five standard errors of the estimate (a false failure chance below 1e-6 for a fixed seed anyway).
		EXPECT_NEAR(mc.inertia[axis], inertia[axis], 5 * mc.standardError[axis])
		    << "axis " << axis << " standard error " << mc.standardError[axis];
	}
}

TEST(ShapesCoreTest, ConeInertiaIsAboutCentreOfMassQuarterHeightBelowOrigin)
{
	const double r = 0.8, h = 1.6, mass = 2;
	btConeShape cone{btScalar(r), btScalar(h)};
	btVector3 inertia;
	cone.calculateLocalInertia(btScalar(mass), inertia);
	// Solid cone: apex at +h/2, base at -h/2.
	const auto inside = [&](double x, double y, double z)
	{
		if (y < -h / 2 || y > h / 2) return false;
		const double allowed = r * (h / 2 - y) / h;
		return x * x + z * z <= allowed * allowed;
	};
	const double center[3] = {0, -h / 4, 0};
	const MonteCarloInertia mc = monteCarloInertia(inside, h / 2, mass, center, 2025u, 400000);
	// The sample centroid confirms the documented centre of mass (tolerance: a few standard errors of a
	// mean of ~100k points spread over ~h).
	EXPECT_NEAR(-h / 4, mc.centroid.y(), 0.01);
	for (int axis = 0; axis < 3; ++axis)
	{
		EXPECT_NEAR(mc.inertia[axis], inertia[axis], 5 * mc.standardError[axis])
		    << "axis " << axis << " standard error " << mc.standardError[axis];
	}
}

// ---- local scaling -------------------------------------------------------------------------------

TEST(ShapesCoreTest, LocalScalingScalesDimensions)
{
	const btVector3 scaling(2, 3, 4);
	btSphereShape sphere(btScalar(0.5));
	sphere.setLocalScaling(scaling);
	EXPECT_NEAR(1, sphere.getRadius(), kShapeRounding);
	EXPECT_NEAR(1, sphere.getMargin(), kShapeRounding);

	btBoxShape box(btVector3(1, 1, 1));
	box.setLocalScaling(scaling);
	EXPECT_TRUE(vectorsNear(btVector3(2, 3, 4), box.getHalfExtentsWithMargin(), kShapeRounding));
	box.setLocalScaling(btVector3(1, 1, 1));
	EXPECT_TRUE(vectorsNear(btVector3(1, 1, 1), box.getHalfExtentsWithMargin(), kShapeRounding));

	btCapsuleShape capsule(btScalar(0.5), 2);
	capsule.setLocalScaling(btVector3(2, 3, 2));
	EXPECT_NEAR(1, capsule.getRadius(), kShapeRounding);
	EXPECT_NEAR(3, capsule.getHalfHeight(), kShapeRounding);
	EXPECT_NEAR(1, capsule.getMargin(), kShapeRounding);

	btCylinderShapeZ cylinder(btVector3(1, 1, 2));
	cylinder.setLocalScaling(scaling);
	EXPECT_TRUE(vectorsNear(btVector3(2, 3, 8), cylinder.getHalfExtentsWithMargin(), kShapeRounding));
	EXPECT_NEAR(2, cylinder.getRadius(), kShapeRounding);

	btConeShape cone(1, 2);
	cone.setLocalScaling(scaling);
	// Height by the up (y) scale, radius by the mean of the x and z scales.
	EXPECT_NEAR(6, cone.getHeight(), kShapeRounding);
	EXPECT_NEAR(3, cone.getRadius(), kShapeRounding);
	EXPECT_TRUE(vectorsNear(btVector3(0, 3, 0), cone.localGetSupportingVertexWithoutMargin(btVector3(0, 1, 0)),
	                        kShapeRounding));
}

TEST(ShapesCoreTest, NegativeScalingActsAsItsAbsoluteValue)
{
	btBoxShape box(btVector3(1, 1, 1));
	box.setLocalScaling(btVector3(-2, 1, 1));
	EXPECT_EQ(btVector3(2, 1, 1), box.getLocalScaling());
	EXPECT_TRUE(vectorsNear(btVector3(2, 1, 1), box.getHalfExtentsWithMargin(), kShapeRounding));
}

// ---- margins -------------------------------------------------------------------------------------

TEST(ShapesCoreTest, BoxAndCylinderMarginLiesInsideDimensions)
{
	btBoxShape box(btVector3(1, 2, 3));
	EXPECT_NEAR(CONVEX_DISTANCE_MARGIN, box.getMargin(), kShapeRounding);
	EXPECT_TRUE(vectorsNear(btVector3(1, 2, 3), box.getHalfExtentsWithMargin(), kShapeRounding));
	const btScalar m = CONVEX_DISTANCE_MARGIN;
	EXPECT_TRUE(vectorsNear(btVector3(1 - m, 2 - m, 3 - m), box.getHalfExtentsWithoutMargin(), kShapeRounding));

	// setMargin keeps the outer size.
	box.setMargin(btScalar(0.2));
	EXPECT_TRUE(vectorsNear(btVector3(1, 2, 3), box.getHalfExtentsWithMargin(), kShapeRounding));
	EXPECT_TRUE(vectorsNear(btVector3(btScalar(0.8), btScalar(1.8), btScalar(2.8)), box.getHalfExtentsWithoutMargin(),
	                        kShapeRounding));

	// A thin box gets a tenth of its thickness as margin.
	btBoxShape thin(btVector3(1, btScalar(0.1), 1));
	EXPECT_NEAR(btScalar(0.01), thin.getMargin(), kShapeRounding);

	// A margin larger than the box is clamped to the smallest half extent: the size is kept.
	thin.setMargin(1);
	EXPECT_NEAR(btScalar(0.1), thin.getMargin(), kShapeRounding);
	EXPECT_TRUE(vectorsNear(btVector3(1, btScalar(0.1), 1), thin.getHalfExtentsWithMargin(), kShapeRounding));
	EXPECT_GE(thin.getHalfExtentsWithoutMargin().y(), btScalar(0));

	btCylinderShape cylinder(btVector3(1, 2, 1));
	EXPECT_NEAR(CONVEX_DISTANCE_MARGIN, cylinder.getMargin(), kShapeRounding);
	EXPECT_TRUE(vectorsNear(btVector3(1, 2, 1), cylinder.getHalfExtentsWithMargin(), kShapeRounding));
	EXPECT_NEAR(1, cylinder.getRadius(), kShapeRounding);
	cylinder.setMargin(btScalar(0.3));
	EXPECT_TRUE(vectorsNear(btVector3(1, 2, 1), cylinder.getHalfExtentsWithMargin(), kShapeRounding));
	// The outermost point along the axis stays at the half height.
	EXPECT_NEAR(2, cylinder.localGetSupportingVertex(btVector3(0, 1, 0)).y(), kShapeRounding);
}

TEST(ShapesCoreTest, SphereAndCapsuleMarginIsRadius)
{
	btSphereShape sphere(btScalar(1.25));
	EXPECT_EQ(btScalar(1.25), sphere.getMargin());
	sphere.setMargin(btScalar(0.1));
	EXPECT_EQ(btScalar(1.25), sphere.getMargin());

	btCapsuleShapeX capsule(btScalar(0.3), 2);
	EXPECT_EQ(btScalar(0.3), capsule.getMargin());
	capsule.setMargin(btScalar(0.1));
	EXPECT_EQ(btScalar(0.3), capsule.getMargin());
	EXPECT_EQ(0, capsule.getUpAxis());
	EXPECT_EQ(btScalar(1), capsule.getHalfHeight());
}

TEST(ShapesCoreTest, ConeMarginLiesOutsideDimensions)
{
	btConeShape cone(1, 2);
	EXPECT_EQ(CONVEX_DISTANCE_MARGIN, cone.getMargin());
	EXPECT_NEAR(1 + CONVEX_DISTANCE_MARGIN, cone.localGetSupportingVertex(btVector3(0, 1, 0)).y(), kShapeRounding);
	cone.setRadius(2);
	cone.setHeight(4);
	EXPECT_EQ(btScalar(2), cone.getRadius());
	EXPECT_EQ(btScalar(4), cone.getHeight());
	EXPECT_TRUE(vectorsNear(btVector3(2, -2, 0), cone.localGetSupportingVertexWithoutMargin(btVector3(1, -1, 0)),
	                        kShapeRounding));
	EXPECT_EQ(1, cone.getConeUpIndex());
	cone.setConeUpIndex(2);
	EXPECT_EQ(2, cone.getConeUpIndex());
	EXPECT_TRUE(vectorsNear(btVector3(0, 0, 2), cone.localGetSupportingVertexWithoutMargin(btVector3(0, 0, 1)),
	                        kShapeRounding));
}

// ---- classification ------------------------------------------------------------------------------

TEST(ShapesCoreTest, ShapeTypesNamesAndClassification)
{
	struct Expectation
	{
		std::shared_ptr<btCollisionShape> shape;
		int type;
		const char* name;
		bool convex, polyhedral;
	};
	const Expectation expectations[] = {
	    {std::make_shared<btSphereShape>(1), SPHERE_SHAPE_PROXYTYPE, "SPHERE", true, false},
	    {std::make_shared<btBoxShape>(btVector3(1, 1, 1)), BOX_SHAPE_PROXYTYPE, "Box", true, true},
	    {std::make_shared<btCapsuleShape>(1, 1), CAPSULE_SHAPE_PROXYTYPE, "CapsuleShape", true, false},
	    {std::make_shared<btCapsuleShapeX>(1, 1), CAPSULE_SHAPE_PROXYTYPE, "CapsuleX", true, false},
	    {std::make_shared<btCapsuleShapeZ>(1, 1), CAPSULE_SHAPE_PROXYTYPE, "CapsuleZ", true, false},
	    {std::make_shared<btCylinderShape>(btVector3(1, 1, 1)), CYLINDER_SHAPE_PROXYTYPE, "CylinderY", true, false},
	    {std::make_shared<btCylinderShapeX>(btVector3(1, 1, 1)), CYLINDER_SHAPE_PROXYTYPE, "CylinderX", true, false},
	    {std::make_shared<btCylinderShapeZ>(btVector3(1, 1, 1)), CYLINDER_SHAPE_PROXYTYPE, "CylinderZ", true, false},
	    {std::make_shared<btConeShape>(1, 1), CONE_SHAPE_PROXYTYPE, "Cone", true, false},
	    {std::make_shared<btConeShapeX>(1, 1), CONE_SHAPE_PROXYTYPE, "ConeX", true, false},
	    {std::make_shared<btConeShapeZ>(1, 1), CONE_SHAPE_PROXYTYPE, "ConeZ", true, false},
	    {std::make_shared<btStaticPlaneShape>(btVector3(0, 1, 0), 0), STATIC_PLANE_PROXYTYPE, "STATICPLANE", false,
	     false},
	    {std::make_shared<btEmptyShape>(), EMPTY_SHAPE_PROXYTYPE, "Empty", false, false},
	};
	for (const Expectation& e : expectations)
	{
		SCOPED_TRACE(e.name);
		EXPECT_EQ(e.type, e.shape->getShapeType());
		EXPECT_STREQ(e.name, e.shape->getName());
		EXPECT_EQ(e.convex, e.shape->isConvex());
		EXPECT_EQ(!e.convex, e.shape->isConcave());
		EXPECT_EQ(e.polyhedral, e.shape->isPolyhedral());
		EXPECT_EQ(e.type == STATIC_PLANE_PROXYTYPE, e.shape->isInfinite());
		EXPECT_FALSE(e.shape->isCompound());
	}
	EXPECT_EQ(btVector3(1, 0, 0), btConeShapeX(1, 1).getAnisotropicRollingFrictionDirection());
	EXPECT_EQ(btVector3(0, 0, 1), btCapsuleShapeZ(1, 1).getAnisotropicRollingFrictionDirection());
	EXPECT_EQ(btVector3(0, 1, 0), btCylinderShape(btVector3(1, 1, 1)).getAnisotropicRollingFrictionDirection());
}

TEST(ShapesCoreTest, BoxPolyhedralFeaturesDescribeTheFullBox)
{
	btBoxShape box(btVector3(1, 2, 3));
	EXPECT_EQ(8, box.getNumVertices());
	EXPECT_EQ(12, box.getNumEdges());
	EXPECT_EQ(6, box.getNumPlanes());
	for (int i = 0; i < 12; ++i)
	{
		btVector3 a, b;
		box.getEdge(i, a, b);
		// Each edge runs along one axis with the full side length.
		const btVector3 d = (b - a).absolute();
		const btScalar length = d.x() + d.y() + d.z();
		const int axis = d.maxAxis();
		EXPECT_NEAR(2 * box.getHalfExtentsWithMargin()[axis], length, kShapeRounding);
	}
	for (int i = 0; i < 6; ++i)
	{
		btVector3 normal, support;
		box.getPlane(normal, support, i);
		btVector3 preferred;
		box.getPreferredPenetrationDirection(i, preferred);
		EXPECT_EQ(normal, preferred);
		EXPECT_NEAR(box.getHalfExtentsWithMargin()[normal.absolute().maxAxis()], support.dot(normal), kShapeRounding);
		btVector4 plane;
		box.getPlaneEquation(plane, i);
		EXPECT_NEAR(-box.getHalfExtentsWithoutMargin()[normal.absolute().maxAxis()], plane.w(), kShapeRounding);
	}
	EXPECT_TRUE(box.isInside(btVector3(0.9, 1.9, 2.9), 0));
	EXPECT_FALSE(box.isInside(btVector3(0.99, 0, 0), 0));
	EXPECT_TRUE(box.isInside(btVector3(0.99, 0, 0), btScalar(0.1)));
}

// ---- static plane and empty shape ----------------------------------------------------------------

namespace
{
struct TriangleCollector : public btTriangleCallback
{
	std::vector<btVector3> vertices;
	void processTriangle(btVector3* triangle, int, int) override
	{
		for (int i = 0; i < 3; ++i) vertices.push_back(triangle[i]);
	}
};

bool insideTriangle(const btVector3& p, const btVector3* t, const btVector3& normal, btScalar tolerance)
{
	for (int i = 0; i < 3; ++i)
	{
		const btVector3 edge = t[(i + 1) % 3] - t[i];
		if (edge.cross(p - t[i]).dot(normal) < -tolerance) return false;
	}
	return true;
}
}  // namespace

TEST(ShapesCoreTest, StaticPlaneTrianglesLieInPlaneAndCoverQueryBox)
{
	const btVector3 normal = btVector3(1, 2, -1).normalized();
	btStaticPlaneShape plane(btVector3(2, 4, -2), btScalar(1.5));
	EXPECT_TRUE(vectorsNear(normal, plane.getPlaneNormal(), kShapeRounding));
	EXPECT_EQ(btScalar(1.5), plane.getPlaneConstant());

	const btVector3 aabbMin(-3, -1, 2), aabbMax(1, 2, 4);
	TriangleCollector collector;
	plane.processAllTriangles(&collector, aabbMin, aabbMax);
	ASSERT_EQ(6u, collector.vertices.size());
	// Plane distances scale with the query box size (~5).
	const btScalar tol = kShapeRounding * 16;
	for (const btVector3& v : collector.vertices) EXPECT_NEAR(btScalar(1.5), v.dot(normal), tol);
	for (int t = 0; t < 2; ++t)
	{
		const btVector3* tri = &collector.vertices[3 * t];
		EXPECT_GT((tri[1] - tri[0]).cross(tri[2] - tri[0]).dot(normal), 0) << "counter-clockwise seen from the normal";
	}
	// Every corner of the query box, projected onto the plane, is covered by one of the triangles.
	for (int c = 0; c < 8; ++c)
	{
		const btVector3 corner((c & 1) ? aabbMax.x() : aabbMin.x(), (c & 2) ? aabbMax.y() : aabbMin.y(),
		                       (c & 4) ? aabbMax.z() : aabbMin.z());
		const btVector3 projected = corner - (corner.dot(normal) - btScalar(1.5)) * normal;
		EXPECT_TRUE(insideTriangle(projected, &collector.vertices[0], normal, tol) ||
		            insideTriangle(projected, &collector.vertices[3], normal, tol))
		    << "corner " << c;
	}

	btVector3 aabbLo, aabbHi;
	plane.getAabb(btTransform::getIdentity(), aabbLo, aabbHi);
	EXPECT_EQ(btVector3(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT), aabbLo);
	EXPECT_EQ(btVector3(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT), aabbHi);
	btVector3 inertia(1, 1, 1);
	plane.calculateLocalInertia(1, inertia);
	EXPECT_EQ(btVector3(0, 0, 0), inertia);
	EXPECT_TRUE(plane.isNonMoving());
}

TEST(ShapesCoreTest, EmptyShapeHasPointAabbAndNoTriangles)
{
	btEmptyShape empty;
	const btTransform t(btQuaternion::getIdentity(), btVector3(1, 2, 3));
	btVector3 aabbMin, aabbMax;
	empty.getAabb(t, aabbMin, aabbMax);
	EXPECT_EQ(btVector3(1, 2, 3), aabbMin);
	EXPECT_EQ(btVector3(1, 2, 3), aabbMax);
	TriangleCollector collector;
	empty.processAllTriangles(&collector, btVector3(-10, -10, -10), btVector3(10, 10, 10));
	EXPECT_TRUE(collector.vertices.empty());
	btVector3 inertia(1, 1, 1);
	empty.calculateLocalInertia(1, inertia);
	EXPECT_EQ(btVector3(0, 0, 0), inertia);
}
