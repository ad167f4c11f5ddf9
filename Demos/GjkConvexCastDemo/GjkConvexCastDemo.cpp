// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// GjkConvexCastDemo: time of impact of two moving convex shapes, headless. A box and a sphere fly
// towards each other; btGjkConvexCast, btSubsimplexConvexCast and btContinuousConvexCollision each
// find when they first touch, the contact normal and the contact point. The answers are compared with
// the analytic ones worked out below, and a second motion that passes the box by must report no hit.
// The demo exits 1 when a cast disagrees with the analytic answer. --png draws the head-on motion: the
// box and the sphere where they first touch (the analytic time of impact), faint where they start and
// end, and the centres' paths as lines; the pass-by path in grey (docs/demos.md).

#include "DemoPictures.h"
#include "DemoPrograms.h"
#include "ShapeMesher.h"
#include "WorldScene.h"
#include "btBulletCollisionCommon.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h"

#include <stdio.h>

namespace
{
/// How far before the exact contact a cast may stop (MAX_CONVEX_CAST_EPSILON is this squared, and the
/// conservative-advancement casts stop at the same distance; docs/convex-casts-and-ray-callbacks.md).
#ifdef BT_USE_DOUBLE_PRECISION
const btScalar kStopDistance = btScalar(1e-6);
#else
const btScalar kStopDistance = btScalar(1e-3);
#endif

/// The motion of the scene: where each shape starts and ends.
struct Motion
{
	btTransform fromA, toA, fromB, toB;
};

btTransform at(btScalar x, btScalar y, btScalar z)
{
	return btTransform(btQuaternion::getIdentity(), btVector3(x, y, z));
}

/// Runs one cast; prints its answer and returns whether it matches the expectation. When expectHit is
/// false, the cast must miss.
bool runCast(const char* name, btConvexCast& cast, const Motion& motion, bool expectHit, btScalar expectedFraction,
             const btVector3& expectedNormal, const btVector3& expectedPoint, btScalar closingSpeed)
{
	btConvexCast::CastResult result;
	const bool hit = cast.calcTimeOfImpact(motion.fromA, motion.toA, motion.fromB, motion.toB, result);
	if (!hit)
	{
		printf("  %-28s no hit\n", name);
		if (expectHit)
		{
			printf("  WRONG: expected a hit at fraction %.6f\n", double(expectedFraction));
		}
		return !expectHit;
	}
	printf("  %-28s fraction %.6f  normal (%6.3f %6.3f %6.3f)  point (%7.4f %7.4f %7.4f)\n", name,
	       double(result.m_fraction), double(result.m_normal.x()), double(result.m_normal.y()),
	       double(result.m_normal.z()), double(result.m_hitPoint.x()), double(result.m_hitPoint.y()),
	       double(result.m_hitPoint.z()));
	if (!expectHit)
	{
		printf("  WRONG: expected no hit\n");
		return false;
	}
	// A cast stops up to kStopDistance before the contact, i.e. kStopDistance / closingSpeed early in
	// fraction; twice that plus a little covers rounding. The point moves with the shapes, so its
	// tolerance is the same gap plus the margin GJK may leave (kStopDistance again).
	const btScalar fractionError = expectedFraction - result.m_fraction;
	const bool fractionGood = fractionError >= -btScalar(1e-5) &&
	                          fractionError <= btScalar(2) * kStopDistance / closingSpeed + btScalar(1e-5);
	const bool normalGood = result.m_normal.dot(expectedNormal) >= btScalar(0.999);
	const bool pointGood = (result.m_hitPoint - expectedPoint).length() <= btScalar(4) * kStopDistance + btScalar(1e-4);
	if (!fractionGood || !normalGood || !pointGood)
	{
		printf("  WRONG: expected fraction %.6f, normal (%.3f %.3f %.3f), point (%.4f %.4f %.4f)\n",
		       double(expectedFraction), double(expectedNormal.x()), double(expectedNormal.y()),
		       double(expectedNormal.z()), double(expectedPoint.x()), double(expectedPoint.y()),
		       double(expectedPoint.z()));
		return false;
	}
	return true;
}

/// Runs the three casts on one motion.
bool runAllCasts(const btConvexShape& box, const btConvexShape& sphere, const Motion& motion, bool expectHit,
                 btScalar expectedFraction, const btVector3& expectedNormal, const btVector3& expectedPoint,
                 btScalar closingSpeed)
{
	btVoronoiSimplexSolver simplex;
	btGjkEpaPenetrationDepthSolver epa;
	btGjkConvexCast gjkCast(&box, &sphere, &simplex);
	btSubsimplexConvexCast subsimplexCast(&box, &sphere, &simplex);
	btContinuousConvexCollision continuousCast(&box, &sphere, &simplex, &epa);
	bool good = runCast("btGjkConvexCast", gjkCast, motion, expectHit, expectedFraction, expectedNormal, expectedPoint,
	                    closingSpeed);
	good = runCast("btSubsimplexConvexCast", subsimplexCast, motion, expectHit, expectedFraction, expectedNormal,
	               expectedPoint, closingSpeed) &&
	       good;
	good = runCast("btContinuousConvexCollision", continuousCast, motion, expectHit, expectedFraction, expectedNormal,
	               expectedPoint, closingSpeed) &&
	       good;
	return good;
}
}  // namespace

int caliber::demo::gjkConvexCastDemo(int argc, char** argv)
{
	caliber::demo::DemoPictures pictures(argc, argv, "GjkConvexCastDemo");
	if (!pictures.ok()) return pictures.exitCode();

	// A: a unit box (half extents 1, its margin is inside them) moving from x = -4 to x = 0.
	// B: a sphere of radius 0.5 moving from x = 4 to x = 0, 0.3 above the box's centre line (its
	// contact point stays on the box's face, so the first contact is face against sphere).
	btBoxShape box(btVector3(1, 1, 1));
	btSphereShape sphere(btScalar(0.5));
	const btScalar sphereHeight = btScalar(0.3);
	const Motion headOn = {at(-4, 0, 0), at(0, 0, 0), at(4, sphereHeight, 0), at(0, sphereHeight, 0)};

	// Analytic answer: the box's face starts at x = -3, the sphere's left side at x = 3.5, a gap of 6.5;
	// both move 4 towards each other, closing 8 per unit fraction, so they touch at 6.5 / 8 = 0.8125.
	// Then the box's face and the sphere's left side are both at x = -3 + 4 * 0.8125 = 0.25; the normal
	// points from B (the sphere) towards A (the box), i.e. -x, and the point on B is (0.25, 0.3, 0).
	const btScalar closingSpeed = btScalar(8);
	const btScalar toi = btScalar(6.5) / closingSpeed;
	const btVector3 normal(-1, 0, 0);
	const btVector3 point(btScalar(0.25), sphereHeight, 0);

	printf("1. Box from x=-4 to 0, sphere (r=0.5) from x=4 to 0 at height 0.3: analytic TOI %.6f\n", double(toi));
	bool good = runAllCasts(box, sphere, headOn, true, toi, normal, point, closingSpeed);

	// The sphere now passes 2 above the box's centre: its lowest point stays at y = 1.5 > 1, a miss.
	const Motion passBy = {at(-4, 0, 0), at(0, 0, 0), at(4, 2, 0), at(0, 2, 0)};
	printf("2. The same motion with the sphere at height 2 passes over the box: no hit expected\n");
	good = runAllCasts(box, sphere, passBy, false, 0, normal, point, closingSpeed) && good;

	printf(good ? "All casts agree with the analytic time of impact.\n" : "MISMATCH (see above)\n");
	if (pictures.wanted())
	{
		caliber::demo::Scene scene;
		caliber::demo::MeshStyle boxStyle, sphereStyle, faint;
		boxStyle.color = caliber::demo::paletteColor(1);
		sphereStyle.color = caliber::demo::paletteColor(0);
		faint.color = btVector3(0.85f, 0.86f, 0.9f);
		// At the time of impact: both have moved toi of the way from their start to their end.
		const btVector3 boxAtToi = headOn.fromA.getOrigin().lerp(headOn.toA.getOrigin(), toi);
		const btVector3 sphereAtToi = headOn.fromB.getOrigin().lerp(headOn.toB.getOrigin(), toi);
		caliber::demo::addShape(scene, &box, at(boxAtToi.x(), boxAtToi.y(), boxAtToi.z()), boxStyle);
		caliber::demo::addShape(scene, &sphere, at(sphereAtToi.x(), sphereAtToi.y(), sphereAtToi.z()), sphereStyle);
		caliber::demo::addShape(scene, &box, headOn.fromA, faint);
		caliber::demo::addShape(scene, &sphere, headOn.fromB, faint);
		scene.addLine(headOn.fromA.getOrigin(), headOn.toA.getOrigin(), boxStyle.color * btScalar(0.6));
		scene.addLine(headOn.fromB.getOrigin(), headOn.toB.getOrigin(), sphereStyle.color * btScalar(0.6));
		scene.addLine(passBy.fromB.getOrigin(), passBy.toB.getOrigin(), btVector3(0.5f, 0.5f, 0.5f));
		scene.addPoint(point, btVector3(0.9f, 0.1f, 0.1f));
		pictures.setViewDirection(btVector3(-0.3f, -0.35f, -1));
		pictures.capture(scene);
	}
	return pictures.finish(good ? 0 : 1);
}
