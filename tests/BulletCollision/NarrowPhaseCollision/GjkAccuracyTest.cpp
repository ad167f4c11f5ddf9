// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Regression tests for GJK's accuracy on curved shapes (the defect the libccd cross-check found in
// float: wrong depths and normals on shallow cylinder and cone contacts). The causes: the simplex's
// closest point lost precision on clustered vertices; GJK stopped when a support point came within
// the equal-vertex threshold (1e-2 units in float) of a vertex; GJK accepted |v| ~ 1e-6 as converged
// although the cores overlapped; and a stalled GJK kept a closest point worse than the previous one.
// References are closed forms or long double, independent of libccd; the random cylinder test fails
// on the old code with errors of 4e-2 (see docs/collision-shapes-and-narrowphase.md).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpa2.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h"
#include "BulletCollision/NarrowPhaseCollision/btPointCollector.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "NarrowPhaseTestUtil.h"

using caliber_narrowphase_test::Random;

namespace
{
typedef long double Wide;

struct WideVector
{
	Wide x, y, z;
};

WideVector wide(const btVector3& v) { return WideVector{Wide(v.x()), Wide(v.y()), Wide(v.z())}; }
WideVector add(const WideVector& a, const WideVector& b) { return WideVector{a.x + b.x, a.y + b.y, a.z + b.z}; }
WideVector sub(const WideVector& a, const WideVector& b) { return WideVector{a.x - b.x, a.y - b.y, a.z - b.z}; }
WideVector scale(const WideVector& a, Wide s) { return WideVector{a.x * s, a.y * s, a.z * s}; }
Wide dot(const WideVector& a, const WideVector& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

/// Closest point to the origin on segment ab, in long double.
WideVector closestOnSegment(const WideVector& a, const WideVector& b)
{
	const WideVector ab = sub(b, a);
	const Wide l2 = dot(ab, ab);
	const Wide t = l2 > 0 ? std::min(Wide(1), std::max(Wide(0), -dot(a, ab) / l2)) : Wide(0);
	return add(a, scale(ab, t));
}

/// Closest point to the origin on triangle abc, in long double: the plane's foot point when it lies
/// inside (solving the 2x2 normal equations), else the best of the three edges.
WideVector closestOnTriangle(const WideVector& a, const WideVector& b, const WideVector& c)
{
	const WideVector e1 = sub(b, a), e2 = sub(c, a);
	const Wide m11 = dot(e1, e1), m12 = dot(e1, e2), m22 = dot(e2, e2);
	const Wide r1 = -dot(a, e1), r2 = -dot(a, e2);
	const Wide det = m11 * m22 - m12 * m12;
	if (det > 0)
	{
		const Wide s = (r1 * m22 - r2 * m12) / det, t = (m11 * r2 - m12 * r1) / det;
		if (s >= 0 && t >= 0 && s + t <= 1) return add(a, add(scale(e1, s), scale(e2, t)));
	}
	const WideVector candidates[3] = {closestOnSegment(a, b), closestOnSegment(b, c), closestOnSegment(a, c)};
	WideVector best = candidates[0];
	for (const WideVector& p : candidates)
		if (dot(p, p) < dot(best, best)) best = p;
	return best;
}

/// A triangle like GJK's near convergence on a curved surface: two vertices a few thousandths of a unit
/// apart at distance ~1 from the origin and a third vertex far away on the other side. Odd calls give a
/// sliver whose plane passes 0.005 to 0.05 from the origin with the foot point inside (GJK's last
/// simplex on a shallow contact), even calls a randomly tilted one.
void clusteredTriangle(Random& rng, btVector3* w, int call)
{
	const btVector3 normal = rng.unitVector();
	btVector3 tangent = normal.cross(rng.unitVector());
	tangent.normalize();
	const btVector3 across = normal.cross(tangent);
	const btVector3 foot = normal * rng.uniform(btScalar(0.005), btScalar(0.05));
	if (call % 2)
	{
		const btScalar halfWidth = rng.uniform(btScalar(5e-4), btScalar(5e-3));
		const btVector3 far = tangent * rng.uniform(btScalar(0.5), btScalar(1.5));
		w[0] = foot + far + across * halfWidth;
		w[1] = foot + far - across * halfWidth;
		w[2] = foot - tangent * rng.uniform(btScalar(0.5), btScalar(1.5)) + across * (halfWidth * rng.uniform(-1, 1));
		return;
	}
	const btVector3 base = foot + tangent * rng.uniform(-1, 1);
	w[0] = base + rng.unitVector() * rng.uniform(btScalar(0.5), btScalar(1.5));
	w[1] = w[0] + rng.unitVector() * rng.uniform(btScalar(1e-3), btScalar(1e-2));
	w[2] = base - (w[0] - base) + rng.unitVector() * rng.uniform(btScalar(0.01), btScalar(0.1));
}

// The closest point of a triangle with two nearly coincident vertices is as accurate as the vertex
// coordinates allow: within 8 ulps of the triangle's size of the long double answer on the same
// (float) vertices. (The float Voronoi arithmetic it replaces was off by up to ~40 ulps, ~5e-6.) In
// double builds the arithmetic has no spare precision: the sliver's conditioning (size / width up
// to ~1e4 here) times double rounding allows 1e-12 of the size more.
TEST(GjkAccuracy, SimplexClosestPointOfClusteredTriangleMatchesLongDouble)
{
	Random rng(4401);
	double worst = 0;
	for (int i = 0; i < 2000; ++i)
	{
		btVector3 w[3];
		clusteredTriangle(rng, w, i);
		btVoronoiSimplexSolver simplex;
		for (int k = 0; k < 3; ++k) simplex.addVertex(w[k], w[k], btVector3(0, 0, 0));
		btVector3 v;
		ASSERT_TRUE(simplex.closest(v));
		const WideVector reference = closestOnTriangle(wide(w[0]), wide(w[1]), wide(w[2]));
		const WideVector error = sub(wide(v), reference);
		const btScalar size = btMax(w[0].length(), btMax(w[1].length(), w[2].length()));
		const double e = double(std::sqrt(dot(error, error)));
		worst = std::max(worst, e / double(size));
		EXPECT_LE(e, (8 * double(SIMD_EPSILON) + 1e-12) * double(size)) << "triangle " << i;
	}
	std::printf("[gjk-accuracy] clustered triangles: worst closest-point error %.3g ulps of the size\n",
	            worst / double(SIMD_EPSILON));
}

// Adding a vertex to a simplex can only bring its closest point nearer the origin (the new simplex
// holds the old one); rounding may make it worse by a few ulps of the coordinates, no more.
TEST(GjkAccuracy, AddingAVertexNeverMovesTheClosestPointAway)
{
	Random rng(4402);
	for (int i = 0; i < 2000; ++i)
	{
		btVector3 w[3];
		clusteredTriangle(rng, w, i);
		btVoronoiSimplexSolver simplex;
		simplex.addVertex(w[0], w[0], btVector3(0, 0, 0));
		simplex.addVertex(w[2], w[2], btVector3(0, 0, 0));
		btVector3 before, after;
		ASSERT_TRUE(simplex.closest(before));
		simplex.addVertex(w[1], w[1], btVector3(0, 0, 0));
		ASSERT_TRUE(simplex.closest(after));
		const btScalar size = btMax(w[0].length(), btMax(w[1].length(), w[2].length()));
		EXPECT_LE(after.length(), before.length() + btScalar(8) * SIMD_EPSILON * size)
		    << "triangle " << i << ": " << before.length() << " -> " << after.length();
	}
}

/// Two cylinders (along y, margin 0.04 inside their dimensions) crossed at right angles, B turned to lie
/// along x and placed at distance d along z from A, the pair then moved by a random rigid motion. The
/// closest points lie on the two curved sides, so the signed distance is d - rA - rB, along z; when
/// overlapping, pushing apart along z costs rA + rB - d, along x rA + hB and along y hA + rB, both larger.
struct CrossedCylinders
{
	btScalar radiusA, radiusB, halfHeight;
	btTransform poseA, poseB;
	btVector3 normalOnB;  // from B towards A
};

CrossedCylinders crossedCylinders(Random& rng, btScalar signedDistance)
{
	CrossedCylinders c;
	c.radiusA = rng.uniform(btScalar(0.25), btScalar(0.5));
	c.radiusB = rng.uniform(btScalar(0.25), btScalar(0.5));
	c.halfHeight = btScalar(0.8);
	const btTransform motion = rng.transform(btScalar(2));
	btTransform localB(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI),
	                   btVector3(0, 0, c.radiusA + c.radiusB + signedDistance));
	c.poseA = motion;
	c.poseB = motion * localB;
	c.normalOnB = motion.getBasis() * btVector3(0, 0, -1);
	return c;
}

double angleDegrees(const btVector3& u, const btVector3& v)
{
	const double cosine = double(u.dot(v)) / std::sqrt(double(u.length2()) * double(v.length2()));
	return std::acos(std::max(-1.0, std::min(1.0, cosine))) * 57.29577951308232;
}

// Crossed cylinders from 0.02 apart to 0.12 deep: through the margins (GJK on the cores, the case that
// failed) into overlapping cores (EPA). Tolerances are the cross-check's: depth within 1e-3 of
// max(depth, 0.1) (EPA's stopping rule), normal within 1 degree (a depth error e on a side of radius
// r ~ 0.3 leaves the normal free by sqrt(2 e / r), under a degree for e = 1e-4).
TEST(GjkAccuracy, CrossedCylindersGiveClosedFormDistanceAndNormalThroughTheMargins)
{
	Random rng(4403);
	double worstDistance = 0, worstAngle = 0;
	int failures = 0;
	for (int i = 0; i < 600; ++i)
	{
		const btScalar signedDistance = btScalar(0.02) - btScalar(0.14) * btScalar(i % 60) / btScalar(59);
		const CrossedCylinders c = crossedCylinders(rng, signedDistance);
		const btCylinderShape a(btVector3(c.radiusA, c.halfHeight, c.radiusA));
		const btCylinderShape b(btVector3(c.radiusB, c.halfHeight, c.radiusB));
		btVoronoiSimplexSolver simplex;
		btGjkEpaPenetrationDepthSolver depthSolver;
		btGjkPairDetector detector(&a, &b, &simplex, &depthSolver);
		btDiscreteCollisionDetectorInterface::ClosestPointInput input;
		input.m_transformA = c.poseA;
		input.m_transformB = c.poseB;
		btPointCollector result;
		detector.getClosestPoints(input, result, nullptr);
		ASSERT_TRUE(result.m_hasResult) << "case " << i;
		const double distanceError = std::fabs(double(result.m_distance - signedDistance));
		const double angle = angleDegrees(result.m_normalOnBInWorld, c.normalOnB);
		worstDistance = std::max(worstDistance, distanceError);
		worstAngle = std::max(worstAngle, angle);
		const double tolerance = 1e-3 * std::max(0.1, -double(signedDistance));
		if ((distanceError > tolerance || angle > 1.0) && ++failures <= 5)
			ADD_FAILURE() << "case " << i << ": distance " << result.m_distance << " (closed form " << signedDistance
			              << "), normal " << angle << " deg off; GJK stop " << detector.m_degenerateSimplex
			              << ", method " << detector.m_lastUsedMethod;
	}
	std::printf("[gjk-accuracy] crossed cylinders: worst distance error %.3g, worst normal %.3g deg\n", worstDistance,
	            worstAngle);
}

// btGjkEpaSolver2 on the same pairs, penetrating ones only: the same depth and normal.
TEST(GjkAccuracy, CrossedCylindersGiveClosedFormDepthWithGjkEpaSolver2)
{
	Random rng(4404);
	for (int i = 0; i < 300; ++i)
	{
		const btScalar signedDistance = -btScalar(0.005) - btScalar(0.115) * btScalar(i % 30) / btScalar(29);
		const CrossedCylinders c = crossedCylinders(rng, signedDistance);
		const btCylinderShape a(btVector3(c.radiusA, c.halfHeight, c.radiusA));
		const btCylinderShape b(btVector3(c.radiusB, c.halfHeight, c.radiusB));
		btGjkEpaSolver2::sResults results;
		ASSERT_TRUE(
		    btGjkEpaSolver2::Penetration(&a, c.poseA, &b, c.poseB, c.poseB.getOrigin() - c.poseA.getOrigin(), results))
		    << "case " << i;
		const btVector3 diff = results.witnesses[1] - results.witnesses[0];
		EXPECT_NEAR(double(diff.length()), -double(signedDistance), 1e-3 * std::max(0.1, -double(signedDistance)))
		    << "case " << i;
		EXPECT_LT(angleDegrees(diff, c.normalOnB), 1.0) << "case " << i;
	}
}

WideVector normalized(const WideVector& v) { return scale(v, 1 / std::sqrt(dot(v, v))); }

/// A cylinder along its local y axis as the exact geometry Caliber's GJK sees: a core cylinder of
/// radius r - m and half height h - m swept by a sphere of radius m (the margin).
struct CylinderGeometry
{
	Wide radius, halfHeight, margin;
	btTransform pose;

	/// max over the shape of x . n for a world unit direction n, in long double.
	Wide supportHeight(const WideVector& n) const
	{
		const btMatrix3x3& r = pose.getBasis();
		WideVector local{0, 0, 0};  // basis^T n
		for (int i = 0; i < 3; ++i)
		{
			local.x += Wide(r[i].x()) * (i == 0 ? n.x : i == 1 ? n.y : n.z);
			local.y += Wide(r[i].y()) * (i == 0 ? n.x : i == 1 ? n.y : n.z);
			local.z += Wide(r[i].z()) * (i == 0 ? n.x : i == 1 ? n.y : n.z);
		}
		const Wide radial = std::sqrt(local.x * local.x + local.z * local.z);
		return dot(wide(pose.getOrigin()), n) + (halfHeight - margin) * std::fabs(local.y) +
		       (radius - margin) * radial + margin;
	}
};

/// h_A(n) + h_B(-n): the support function of A - B along n, whose minimum over unit n is the
/// penetration depth (and minus the distance when apart).
Wide differenceSupport(const CylinderGeometry& a, const CylinderGeometry& b, const WideVector& n)
{
	return a.supportHeight(n) + b.supportHeight(scale(n, -1));
}

/// Lowers value = differenceSupport(n) from the start direction by a pattern search in the tangent
/// plane with probe directions turned by a pseudo-random angle each round (a fixed set of directions
/// stalls in the creased valleys that the cylinders' rims make), in long double.
void descend(const CylinderGeometry& a, const CylinderGeometry& b, WideVector& n, Wide& value)
{
	unsigned state = 12345u;
	for (Wide step = Wide(0.03); step > Wide(1e-10);)
	{
		const WideVector helper = std::fabs(n.x) < Wide(0.6) ? WideVector{1, 0, 0} : WideVector{0, 1, 0};
		const WideVector u = normalized(WideVector{n.y * helper.z - n.z * helper.y, n.z * helper.x - n.x * helper.z,
		                                           n.x * helper.y - n.y * helper.x});
		const WideVector v{n.y * u.z - n.z * u.y, n.z * u.x - n.x * u.z, n.x * u.y - n.y * u.x};
		state = state * 1664525u + 1013904223u;
		const Wide offset = Wide(state >> 8) / Wide(1 << 24) * Wide(0.5235987755982988);
		bool improved = false;
		for (int k = 0; k < 12; ++k)
		{
			const Wide angle = offset + Wide(0.5235987755982988) * Wide(k);
			const WideVector candidate =
			    normalized(add(n, add(scale(u, step * std::cos(angle)), scale(v, step * std::sin(angle)))));
			const Wide candidateValue = differenceSupport(a, b, candidate);
			if (candidateValue < value)
			{
				value = candidateValue;
				n = candidate;
				improved = true;
			}
		}
		if (!improved) step *= Wide(0.5);
	}
}

/// The lowest differenceSupport found from a dense direction grid (Fibonacci sphere) and from start.
Wide searchMinimum(const CylinderGeometry& a, const CylinderGeometry& b, const WideVector& start)
{
	WideVector best = start;
	Wide bestValue = differenceSupport(a, b, best);
	WideVector gridBest = best;
	Wide gridValue = bestValue;
	const int gridSize = 1000;
	for (int i = 0; i < gridSize; ++i)
	{
		const Wide z = 1 - (2 * Wide(i) + 1) / Wide(gridSize);
		const Wide ring = std::sqrt(std::max(Wide(0), 1 - z * z));
		const Wide phi = Wide(2.399963229728653) * Wide(i);
		const WideVector n{ring * std::cos(phi), ring * std::sin(phi), z};
		const Wide value = differenceSupport(a, b, n);
		if (value < gridValue)
		{
			gridValue = value;
			gridBest = n;
		}
	}
	descend(a, b, best, bestValue);
	descend(a, b, gridBest, gridValue);
	return std::min(bestValue, gridValue);
}

// Randomly posed cylinder pairs from 0.02 apart to 0.12 deep (through the margins, where the float
// GJK on the cores used to stop early, into overlapping cores), on the exact core-plus-margin geometry
// in long double: the depth along the reported normal is the reported depth (the normal is the one
// the distance belongs to), and no direction found by a search started from a dense grid and from the
// reported normal needs less (the normal is minimal). Both within the cross-check's depth tolerance,
// 1e-3 of max(depth, 0.1); on a curved side a normal 1 degree off costs r (1 - cos 1deg) ~ 5e-5 there,
// on a rim or cap edge r sin 1deg ~ 5e-3.
TEST(GjkAccuracy, RandomCylinderPairsReportMinimalSelfConsistentNormals)
{
	Random rng(4406);
	int compared = 0, failures = 0;
	double worstSelf = 0, worstBeaten = 0;
	while (compared < 120)
	{
		const btScalar rA = rng.uniform(btScalar(0.2), btScalar(0.7)), hA = rng.uniform(btScalar(0.2), btScalar(0.8));
		const btScalar rB = rng.uniform(btScalar(0.2), btScalar(0.7)), hB = rng.uniform(btScalar(0.2), btScalar(0.8));
		const btCylinderShape a(btVector3(rA, hA, rA)), b(btVector3(rB, hB, rB));
		const btTransform poseA(rng.rotation(), rng.vector(btScalar(0.5)));
		btTransform poseB(rng.rotation(), poseA.getOrigin());
		const btScalar reach = btSqrt(rA * rA + hA * hA) + btSqrt(rB * rB + hB * hB);
		poseB.setOrigin(poseA.getOrigin() + rng.unitVector() * (reach * rng.uniform(btScalar(0.4), btScalar(1))));
		btVoronoiSimplexSolver simplex;
		btGjkEpaPenetrationDepthSolver depthSolver;
		btGjkPairDetector detector(&a, &b, &simplex, &depthSolver);
		btDiscreteCollisionDetectorInterface::ClosestPointInput input;
		input.m_transformA = poseA;
		input.m_transformB = poseB;
		btPointCollector result;
		detector.getClosestPoints(input, result, nullptr);
		ASSERT_TRUE(result.m_hasResult) << "pair " << compared;
		const double distance = double(result.m_distance);
		if (distance > 0.02 || distance < -0.12) continue;
		++compared;
		const CylinderGeometry ga{Wide(rA), Wide(hA), Wide(a.getMargin()), poseA};
		const CylinderGeometry gb{Wide(rB), Wide(hB), Wide(b.getMargin()), poseB};
		// The normal on B points towards A: A - B is pushed apart along n = -normal.
		const btVector3& normal = result.m_normalOnBInWorld;
		const WideVector n = normalized(WideVector{-Wide(normal.x()), -Wide(normal.y()), -Wide(normal.z())});
		const double alongNormal = double(differenceSupport(ga, gb, n));
		const double minimum = double(searchMinimum(ga, gb, n));
		const double tolerance = 1e-3 * std::max(0.1, -distance);
		const double self = std::fabs(alongNormal + distance), beaten = alongNormal - minimum;
		worstSelf = std::max(worstSelf, self);
		worstBeaten = std::max(worstBeaten, beaten);
		if ((self > tolerance || beaten > tolerance) && ++failures <= 5)
			ADD_FAILURE() << "pair " << compared << ": distance " << distance << ", depth along its normal "
			              << alongNormal << ", smallest depth found " << minimum << "; GJK stop "
			              << detector.m_degenerateSimplex << ", method " << detector.m_lastUsedMethod;
	}
	std::printf(
	    "[gjk-accuracy] random cylinder pairs: worst |distance + depth along normal| %.3g, normal beaten by %.3g\n",
	    worstSelf, worstBeaten);
	EXPECT_EQ(failures, 0);
}

// Cores that overlap by a few thousandths are not "touching": GJK must not accept a closest point of
// length ~1e-6 whose lower bound is far below zero. The depth is then the margins plus the overlap.
TEST(GjkAccuracy, SlightlyOverlappingCoresGiveMarginsPlusOverlap)
{
	Random rng(4405);
	for (int i = 0; i < 200; ++i)
	{
		// Margins 0.04 + 0.04: cores overlapping by 0.0005 to 0.005.
		const btScalar signedDistance = -btScalar(0.08) - rng.uniform(btScalar(0.0005), btScalar(0.005));
		const CrossedCylinders c = crossedCylinders(rng, signedDistance);
		const btCylinderShape a(btVector3(c.radiusA, c.halfHeight, c.radiusA));
		const btCylinderShape b(btVector3(c.radiusB, c.halfHeight, c.radiusB));
		btVoronoiSimplexSolver simplex;
		btGjkEpaPenetrationDepthSolver depthSolver;
		btGjkPairDetector detector(&a, &b, &simplex, &depthSolver);
		btDiscreteCollisionDetectorInterface::ClosestPointInput input;
		input.m_transformA = c.poseA;
		input.m_transformB = c.poseB;
		btPointCollector result;
		detector.getClosestPoints(input, result, nullptr);
		ASSERT_TRUE(result.m_hasResult) << "case " << i;
		// EPA's accuracy at this depth (see above): 1e-3 of 0.1.
		EXPECT_NEAR(double(result.m_distance), double(signedDistance), 1e-4)
		    << "case " << i << ": GJK stop " << detector.m_degenerateSimplex << ", method "
		    << detector.m_lastUsedMethod;
	}
}
}  // namespace
