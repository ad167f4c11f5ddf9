// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"
#include "NarrowPhaseTestUtil.h"

using caliber_narrowphase_test::Random;
using caliber_narrowphase_test::vectorsNear;

namespace
{
struct RayHit
{
	btVector3 normal;
	btScalar fraction;
	int partId;
	int triangleIndex;
};

// Records every hit; returns the hit's fraction (keep only closer hits) or, with keepAll, the current
// limit (keep every hit).
class RecordingRayCallback : public btTriangleRaycastCallback
{
public:
	RecordingRayCallback(const btVector3& from, const btVector3& to, unsigned int flags = 0, bool keepAll = false)
	    : btTriangleRaycastCallback(from, to, flags), m_keepAll(keepAll)
	{
	}
	btScalar reportHit(const btVector3& hitNormalLocal, btScalar hitFraction, int partId, int triangleIndex) override
	{
		m_hits.push_back({hitNormalLocal, hitFraction, partId, triangleIndex});
		return m_keepAll ? m_hitFraction : hitFraction;
	}
	std::vector<RayHit> m_hits;
	bool m_keepAll;
};

// Moller-Trumbore in double precision, written independently of the callback: hit fraction t and
// barycentric (u, v) of the segment from -> to against the triangle, or false when parallel.
struct Reference
{
	bool crossesPlane;
	double t, u, v;
};

Reference mollerTrumbore(const btVector3* tri, const btVector3& from, const btVector3& to)
{
	const double o[3] = {from.x(), from.y(), from.z()};
	double d[3], e1[3], e2[3];
	for (int i = 0; i < 3; ++i)
	{
		d[i] = double(to[i]) - double(from[i]);
		e1[i] = double(tri[1][i]) - double(tri[0][i]);
		e2[i] = double(tri[2][i]) - double(tri[0][i]);
	}
	auto cross = [](const double* a, const double* b, double* c)
	{
		c[0] = a[1] * b[2] - a[2] * b[1];
		c[1] = a[2] * b[0] - a[0] * b[2];
		c[2] = a[0] * b[1] - a[1] * b[0];
	};
	auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
	double p[3], q[3], s[3];
	cross(d, e2, p);
	const double det = dot(e1, p);
	Reference r{false, 0, 0, 0};
	if (std::fabs(det) < 1e-12) return r;
	for (int i = 0; i < 3; ++i) s[i] = o[i] - double(tri[0][i]);
	r.u = dot(s, p) / det;
	cross(s, e1, q);
	r.v = dot(d, q) / det;
	r.t = dot(e2, q) / det;
	r.crossesPlane = true;
	return r;
}

btVector3 unitNormal(const btVector3* tri) { return (tri[1] - tri[0]).cross(tri[2] - tri[0]).normalized(); }

// Float rounding of a plane distance of points a few units away, relative to the ray length.
const btScalar kFractionTolerance = btScalar(64) * SIMD_EPSILON * btScalar(10);

class RecordingConvexcastCallback : public btTriangleConvexcastCallback
{
public:
	using btTriangleConvexcastCallback::btTriangleConvexcastCallback;
	btScalar reportHit(const btVector3& hitNormalLocal, const btVector3& hitPointLocal, btScalar hitFraction,
	                   int partId, int triangleIndex) override
	{
		m_normals.push_back(hitNormalLocal);
		m_points.push_back(hitPointLocal);
		m_fractions.push_back(hitFraction);
		m_ids.push_back(partId * 1000 + triangleIndex);
		return hitFraction;
	}
	std::vector<btVector3> m_normals, m_points;
	std::vector<btScalar> m_fractions;
	std::vector<int> m_ids;
};
}  // namespace

TEST(TriangleRaycastCallback, RandomRaysAgreeWithMollerTrumbore)
{
	Random rng(8101);
	int hits = 0, misses = 0;
	for (int trial = 0; trial < 4000; ++trial)
	{
		btVector3 tri[3] = {rng.vector(3), rng.vector(3), rng.vector(3)};
		// A segment through the triangle's neighbourhood: both ends random, biased across its plane.
		const btVector3 centre = (tri[0] + tri[1] + tri[2]) / 3;
		const btVector3 from = centre + rng.vector(4), to = centre + rng.vector(4);
		const Reference ref = mollerTrumbore(tri, from, to);
		const btVector3 normal = unitNormal(tri);
		const btScalar area2 = (tri[1] - tri[0]).cross(tri[2] - tri[0]).length();
		// Skip cases the reference cannot decide robustly: near an edge, an end on the plane, slivers
		// or nearly parallel rays.
		const double margin = 1e-3;
		if (area2 < btScalar(0.05) || !ref.crossesPlane) continue;
		if (std::fabs(ref.u) < margin || std::fabs(ref.v) < margin || std::fabs(1 - ref.u - ref.v) < margin) continue;
		if (std::fabs(ref.t) < margin || std::fabs(ref.t - 1) < margin) continue;
		if (std::fabs(double(normal.dot((to - from).normalized()))) < 1e-2) continue;
		const bool expectHit = ref.t > 0 && ref.t < 1 && ref.u > 0 && ref.v > 0 && ref.u + ref.v < 1;

		RecordingRayCallback callback(from, to);
		callback.processTriangle(tri, 3, trial);
		ASSERT_EQ(callback.m_hits.size(), expectHit ? 1u : 0u)
		    << "trial " << trial << " t " << ref.t << " u " << ref.u << " v " << ref.v;
		if (!expectHit)
		{
			EXPECT_EQ(callback.m_hitFraction, btScalar(1));
			++misses;
			continue;
		}
		++hits;
		const RayHit& hit = callback.m_hits[0];
		EXPECT_NEAR(hit.fraction, btScalar(ref.t), kFractionTolerance) << "trial " << trial;
		EXPECT_EQ(callback.m_hitFraction, hit.fraction);
		EXPECT_EQ(hit.partId, 3);
		EXPECT_EQ(hit.triangleIndex, trial);
		// Unit normal facing the ray's start.
		const btVector3 facing = normal.dot(from - tri[0]) > 0 ? normal : -normal;
		EXPECT_TRUE(vectorsNear(hit.normal, facing, btScalar(1e-5))) << "trial " << trial;
	}
	// The sample must exercise both outcomes.
	EXPECT_GT(hits, 200);
	EXPECT_GT(misses, 200);
}

TEST(TriangleRaycastCallback, BackfaceFilterAndNormalFlags)
{
	btVector3 tri[3] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0)};  // normal +z
	const btVector3 above(btScalar(0.25), btScalar(0.25), 1), below(btScalar(0.25), btScalar(0.25), -3);
	{
		// Front face: normal +z, fraction 1/4.
		RecordingRayCallback cb(above, below, btTriangleRaycastCallback::kF_FilterBackfaces);
		cb.processTriangle(tri, 0, 0);
		ASSERT_EQ(cb.m_hits.size(), 1u);
		EXPECT_NEAR(cb.m_hits[0].fraction, btScalar(0.25), kFractionTolerance);
		EXPECT_TRUE(vectorsNear(cb.m_hits[0].normal, btVector3(0, 0, 1), 0));
	}
	{
		// Back face filtered.
		RecordingRayCallback cb(below, above, btTriangleRaycastCallback::kF_FilterBackfaces);
		cb.processTriangle(tri, 0, 0);
		EXPECT_TRUE(cb.m_hits.empty());
		EXPECT_EQ(cb.m_hitFraction, btScalar(1));
	}
	{
		// Back face hit: normal flipped towards the ray start (-z).
		RecordingRayCallback cb(below, above);
		cb.processTriangle(tri, 0, 0);
		ASSERT_EQ(cb.m_hits.size(), 1u);
		EXPECT_NEAR(cb.m_hits[0].fraction, btScalar(0.75), kFractionTolerance);
		EXPECT_TRUE(vectorsNear(cb.m_hits[0].normal, btVector3(0, 0, -1), 0));
	}
	{
		// Back face hit keeping the triangle's own normal.
		RecordingRayCallback cb(below, above, btTriangleRaycastCallback::kF_KeepUnflippedNormal);
		cb.processTriangle(tri, 0, 0);
		ASSERT_EQ(cb.m_hits.size(), 1u);
		EXPECT_TRUE(vectorsNear(cb.m_hits[0].normal, btVector3(0, 0, 1), 0));
	}
	{
		// Ends on the plane, or parallel in the plane: no hit.
		RecordingRayCallback cb(btVector3(btScalar(0.25), btScalar(0.25), 0), below);
		cb.processTriangle(tri, 0, 0);
		RecordingRayCallback parallel(btVector3(-1, btScalar(0.2), 0), btVector3(2, btScalar(0.2), 0));
		parallel.processTriangle(tri, 0, 0);
		EXPECT_TRUE(cb.m_hits.empty());
		EXPECT_TRUE(parallel.m_hits.empty());
	}
}

TEST(TriangleRaycastCallback, ReturnValueShrinksToClosestHit)
{
	// Ten parallel triangles across the ray at z = 1..10, given in a shuffled order.
	Random rng(8102);
	std::vector<int> order = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
	std::shuffle(order.begin(), order.end(), std::mt19937(8103));
	const btVector3 from(btScalar(0.2), btScalar(0.2), 0), to(btScalar(0.2), btScalar(0.2), 20);
	RecordingRayCallback closest(from, to), all(from, to, 0, true);
	for (int k : order)
	{
		const btScalar z = btScalar(k + 1) + rng.uniform(-btScalar(0.2), btScalar(0.2)) * 0;
		btVector3 tri[3] = {btVector3(-1, -1, z), btVector3(2, -1, z), btVector3(-1, 2, z)};
		closest.processTriangle(tri, 0, k);
		all.processTriangle(tri, 0, k);
	}
	EXPECT_NEAR(closest.m_hitFraction, btScalar(1) / 20, kFractionTolerance);
	// Every reported hit improved on the previous one.
	for (size_t i = 1; i < closest.m_hits.size(); ++i)
		EXPECT_LT(closest.m_hits[i].fraction, closest.m_hits[i - 1].fraction);
	ASSERT_FALSE(closest.m_hits.empty());
	EXPECT_EQ(closest.m_hits.back().triangleIndex, 0);
	// Returning the current limit keeps every hit.
	EXPECT_EQ(all.m_hits.size(), 10u);
	EXPECT_EQ(all.m_hitFraction, btScalar(1));
}

TEST(TriangleRaycastCallback, RaysThroughSharedEdgeHitAtLeastOneTriangle)
{
	// A quad split along its diagonal: rays through points exactly on the diagonal must not slip
	// between the two triangles.
	Random rng(8105);
	btVector3 first[3] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(1, 1, 0)};
	btVector3 second[3] = {btVector3(0, 0, 0), btVector3(1, 1, 0), btVector3(0, 1, 0)};
	for (int trial = 0; trial < 500; ++trial)
	{
		const btScalar s = rng.uniform(btScalar(0.01), btScalar(0.99));
		const btVector3 onEdge(s, s, 0);
		const btVector3 tilt(rng.uniform(-1, 1), rng.uniform(-1, 1), 0);
		RecordingRayCallback cb(onEdge + btVector3(0, 0, 1) + tilt, onEdge - btVector3(0, 0, 1) - tilt, 0, true);
		cb.processTriangle(first, 0, 0);
		cb.processTriangle(second, 0, 1);
		EXPECT_GE(cb.m_hits.size(), 1u) << "trial " << trial << " s " << s;
	}
}

TEST(TriangleRaycastCallback, DegenerateTrianglesNeverHit)
{
	const btVector3 from(btScalar(0.3), btScalar(0.1), 1), to(btScalar(0.3), btScalar(0.1), -1);
	btVector3 collinear[3] = {btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(2, 0, 0)};
	btVector3 repeated[3] = {btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(1, 1, 0)};
	btVector3 point[3] = {btVector3(btScalar(0.3), btScalar(0.1), 0), btVector3(btScalar(0.3), btScalar(0.1), 0),
	                      btVector3(btScalar(0.3), btScalar(0.1), 0)};
	// A sliver whose width is far below float rounding of its length.
	btVector3 sliver[3] = {btVector3(-1, 0, 0), btVector3(1, 0, 0), btVector3(0, btScalar(1e-9), 0)};
	RecordingRayCallback cb(from, to);
	cb.processTriangle(collinear, 0, 0);
	cb.processTriangle(repeated, 0, 1);
	cb.processTriangle(point, 0, 2);
	cb.processTriangle(sliver, 0, 3);
	EXPECT_TRUE(cb.m_hits.empty());
	EXPECT_EQ(cb.m_hitFraction, btScalar(1));
}

TEST(TriangleRaycastCallback, NonFiniteInputAssertsOrNeverHits)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	btVector3 good[3] = {btVector3(-1, -1, 0), btVector3(1, -1, 0), btVector3(0, 1, 0)};
	btVector3 bad[3] = {btVector3(-1, -1, 0), btVector3(1, nan, 0), btVector3(0, 1, 0)};
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(
	    {
		    RecordingRayCallback cb(btVector3(0, 0, 1), btVector3(0, 0, -1));
		    cb.processTriangle(bad, 0, 0);
	    },
	    "assertion failed");
	EXPECT_DEATH(
	    {
		    RecordingRayCallback cb(btVector3(0, 0, nan), btVector3(0, 0, -1));
		    cb.processTriangle(good, 0, 0);
	    },
	    "assertion failed");
#else
	RecordingRayCallback cb(btVector3(0, 0, 1), btVector3(0, 0, -1));
	cb.processTriangle(bad, 0, 0);
	RecordingRayCallback nanRay(btVector3(0, 0, nan), btVector3(0, 0, -1));
	nanRay.processTriangle(good, 0, 0);
	EXPECT_TRUE(cb.m_hits.empty());
	EXPECT_TRUE(nanRay.m_hits.empty());
#endif
}

TEST(TriangleConvexcastCallback, SphereSweptOntoFaceHitsAtAnalyticFraction)
{
	// The triangle's margin and the sphere's radius both lie between the centre and the face at contact:
	// t = (h - r - margin) / drop.
	Random rng(8104);
	for (int trial = 0; trial < 30; ++trial)
	{
		btVector3 tri[3] = {btVector3(-2, -2, 0), btVector3(3, -2, 0), btVector3(-2, 3, 0)};
		const btTransform triangleToWorld = rng.transform(5);
		const btScalar r = rng.uniform(btScalar(0.1), btScalar(0.8));
		const btScalar margin = rng.uniform(0, btScalar(0.05));
		btSphereShape sphere(r);
		const btScalar h = rng.uniform(btScalar(1), 3);
		const btScalar drop = h * rng.uniform(btScalar(1.2), 2);
		const btVector3 local(rng.uniform(-1, btScalar(0.5)), rng.uniform(-1, btScalar(0.5)), h);
		const btVector3 up = triangleToWorld.getBasis().getColumn(2);
		const btTransform from(btQuaternion::getIdentity(), triangleToWorld(local));
		const btTransform to(btQuaternion::getIdentity(), triangleToWorld(local) - up * drop);
		RecordingConvexcastCallback cb(&sphere, from, to, triangleToWorld, margin);
		cb.processTriangle(tri, 2, 7);
		ASSERT_EQ(cb.m_fractions.size(), 1u) << "trial " << trial;
		const btScalar exact = (h - r - margin) / drop;
		// The continuous cast stops within its tolerance (1e-3 float, 1e-6 double) before contact.
#ifdef BT_USE_DOUBLE_PRECISION
		const btScalar stop = btScalar(1e-6);
#else
		const btScalar stop = btScalar(1e-3);
#endif
		const btScalar rounding = btScalar(512) * SIMD_EPSILON * btScalar(10);
		EXPECT_GE(cb.m_fractions[0], exact - (stop + rounding) / drop) << "trial " << trial;
		EXPECT_LE(cb.m_fractions[0], exact + rounding / drop) << "trial " << trial;
		EXPECT_EQ(cb.m_hitFraction, cb.m_fractions[0]);
		EXPECT_EQ(cb.m_ids[0], 2007);
		EXPECT_TRUE(vectorsNear(cb.m_normals[0], up, btScalar(1e-3))) << "trial " << trial;
		// The contact point lies on the triangle's surface (its plane grown by the margin), under the centre.
		const btVector3 pointLocal = triangleToWorld.invXform(cb.m_points[0]);
		EXPECT_NEAR(pointLocal.z(), margin, btScalar(2e-3)) << "trial " << trial;
		EXPECT_NEAR(pointLocal.x(), local.x(), btScalar(2e-3)) << "trial " << trial;
		EXPECT_NEAR(pointLocal.y(), local.y(), btScalar(2e-3)) << "trial " << trial;

		// A second, farther triangle does not replace the closer hit.
		btVector3 lower[3] = {tri[0] - btVector3(0, 0, btScalar(0.5)), tri[1] - btVector3(0, 0, btScalar(0.5)),
		                      tri[2] - btVector3(0, 0, btScalar(0.5))};
		cb.processTriangle(lower, 2, 8);
		EXPECT_EQ(cb.m_fractions.size(), 1u);
	}
}

TEST(TriangleConvexcastCallback, SweepMissingTheTriangleReportsNothing)
{
	btVector3 tri[3] = {btVector3(-1, -1, 0), btVector3(1, -1, 0), btVector3(0, 1, 0)};
	btSphereShape sphere(btScalar(0.5));
	const btTransform identity = btTransform::getIdentity();
	// Beside the triangle, sweeping down past it.
	RecordingConvexcastCallback cb(&sphere, btTransform(btQuaternion::getIdentity(), btVector3(5, 0, 2)),
	                               btTransform(btQuaternion::getIdentity(), btVector3(5, 0, -2)), identity,
	                               btScalar(0.01));
	cb.processTriangle(tri, 0, 0);
	EXPECT_TRUE(cb.m_fractions.empty());
	EXPECT_EQ(cb.m_hitFraction, btScalar(1));
}
