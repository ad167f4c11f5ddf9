// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// LinearMathDemo: the math layer at work, headless. It
//   1. spins a body at a constant angular velocity with btTransformUtil::integrateTransform and
//      compares the result with the exact rotation, then recovers the velocities from two frames;
//   2. builds convex hulls of random point clouds with btConvexHullComputer and checks Euler's
//      formula V - E + F = 2 on each;
//   3. profiles both with BT_PROFILE and prints CProfileManager's report.
// It exits 1 if a measured error is out of tolerance, so CI notices when the math breaks. --png draws
// the spinning body's frame every second along its path and the three hulls, each moved next to the
// path's start (docs/demos.md).

#include "LinearMath/btConvexHullComputer.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btTransformUtil.h"
#include "LinearMath/btVector3.h"

#include <stdint.h>
#include <stdio.h>

#include <vector>

#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "DemoPictures.h"
#include "DemoPrograms.h"
#include "ShapeMesher.h"
#include "WorldScene.h"

namespace
{
/// The picture being built (--png), or null.
caliber::demo::Scene* gPicture = nullptr;

/// A small deterministic generator, so every run prints the same numbers.
class DemoRandom
{
public:
	explicit DemoRandom(uint32_t seed) : m_state(seed) {}
	/// Uniform in [lo, hi).
	btScalar uniform(btScalar lo, btScalar hi)
	{
		m_state = m_state * 1664525u + 1013904223u;
		const double unit = double(m_state >> 8) / double(1u << 24);
		return lo + btScalar(unit) * (hi - lo);
	}

private:
	uint32_t m_state;
};

/// Angle in radians of the rotation that takes one orientation to the other. Measured from the
/// vector part of the relative rotation (sin of half the angle), which stays accurate for tiny angles
/// where acos of the dot product would round to zero.
btScalar angleBetween(const btQuaternion& a, const btQuaternion& b)
{
	const btQuaternion relative = a.inverse() * b;
	const btScalar sinHalfAngle =
	    btSqrt(relative.x() * relative.x() + relative.y() * relative.y() + relative.z() * relative.z());
	return btScalar(2.0) * btAsin(sinHalfAngle);
}

/// Part 1: returns true when the integrated motion matches the exact one.
bool demoIntegration()
{
	BT_PROFILE("integration");
	printf("1. Integrating a spinning, drifting body with btTransformUtil::integrateTransform\n");

	const btVector3 spinAxis = btVector3(btScalar(1), btScalar(2), btScalar(2)).normalized();
	const btScalar spinRate = SIMD_2_PI;  // one turn per second
	const btVector3 angularVelocity = spinAxis * spinRate;
	const btVector3 linearVelocity(btScalar(1.5), btScalar(0), btScalar(-0.5));
	const btScalar timeStep = btScalar(1.0 / 60.0);
	const int stepCount = 600;

	btTransform start;
	start.setIdentity();
	start.setOrigin(btVector3(btScalar(0), btScalar(10), btScalar(0)));
	start.setRotation(btQuaternion(btVector3(btScalar(0), btScalar(1), btScalar(0)), btScalar(0.3)));

	btTransform current = start;
	btTransform previous = start;
	for (int step = 0; step < stepCount; ++step)
	{
		BT_PROFILE("integrateTransform");
		previous = current;
		btTransformUtil::integrateTransform(previous, linearVelocity, angularVelocity, timeStep, current);
		if (gPicture && step % 60 == 0)
		{
			// The body's axes (x red, y green, z blue) every half second, through btIDebugDraw::drawTransform.
			caliber::demo::SceneDebugDraw drawer(*gPicture);
			drawer.drawTransform(current, btScalar(1));
			gPicture->addLine(current.getOrigin(), current.getOrigin() + linearVelocity, btVector3(0.6f, 0.6f, 0.6f));
		}
	}

	// For a constant world-space angular velocity the exact orientation is a rotation about the
	// fixed axis by rate * time, applied after the start orientation.
	const btScalar elapsed = timeStep * btScalar(stepCount);
	const btQuaternion exactRotation = btQuaternion(spinAxis, spinRate * elapsed) * start.getRotation();
	const btVector3 exactOrigin = start.getOrigin() + linearVelocity * elapsed;

	const btScalar angleError = angleBetween(current.getRotation(), exactRotation);
	const btScalar originError = (current.getOrigin() - exactOrigin).length();
	printf("   %d steps of %.4f s, %.1f turns about (%.3f, %.3f, %.3f)\n", stepCount, double(timeStep),
	       double(spinRate * elapsed / SIMD_2_PI), double(spinAxis.x()), double(spinAxis.y()), double(spinAxis.z()));
	printf("   orientation error vs exact rotation: %.3g degrees\n", double(btDegrees(angleError)));
	printf("   position error vs exact motion:      %.3g m\n", double(originError));

	btVector3 recoveredLinear, recoveredAngular;
	btTransformUtil::calculateVelocity(previous, current, timeStep, recoveredLinear, recoveredAngular);
	const btScalar linearVelocityError = (recoveredLinear - linearVelocity).length();
	const btScalar angularVelocityError = (recoveredAngular - angularVelocity).length();
	printf("   calculateVelocity from the last two frames: linear (%.4f, %.4f, %.4f), angular (%.4f, %.4f, %.4f)\n",
	       double(recoveredLinear.x()), double(recoveredLinear.y()), double(recoveredLinear.z()),
	       double(recoveredAngular.x()), double(recoveredAngular.y()), double(recoveredAngular.z()));
	printf("   velocity errors: linear %.3g m/s, angular %.3g rad/s\n\n", double(linearVelocityError),
	       double(angularVelocityError));

	// Tolerances sized for single precision accumulated over 600 steps.
	return angleError < btScalar(1e-3) && originError < btScalar(1e-3) && linearVelocityError < btScalar(1e-2) &&
	       angularVelocityError < btScalar(1e-2);
}

/// Builds the hull of the given points and prints its size; returns true when V - E + F = 2.
bool buildAndReportHull(const char* name, const std::vector<btVector3>& points, const btVector3& pictureAt,
                        const btVector3& pictureScale = btVector3(1, 1, 1))
{
	BT_PROFILE("convex hull");
	std::vector<btScalar> coordinates;
	coordinates.reserve(points.size() * 3);
	for (const btVector3& p : points)
	{
		coordinates.push_back(p.x());
		coordinates.push_back(p.y());
		coordinates.push_back(p.z());
	}

	btConvexHullComputer hull;
	hull.compute(coordinates.data(), int(3 * sizeof(btScalar)), int(points.size()), btScalar(0), btScalar(0));
	const int vertexCount = hull.vertices.size();
	const int edgeCount = hull.edges.size() / 2;  // each edge is stored once per direction
	const int faceCount = hull.faces.size();
	const int euler = vertexCount - edgeCount + faceCount;
	printf("   %-28s %5d points -> V = %4d, E = %4d, F = %4d, V - E + F = %d\n", name, int(points.size()), vertexCount,
	       edgeCount, faceCount, euler);
	if (gPicture)
	{
		// Drawn centred at pictureAt and scaled, wherever the cloud itself is.
		btVector3 centre(0, 0, 0);
		for (int i = 0; i < hull.vertices.size(); ++i) centre += hull.vertices[i] / btScalar(hull.vertices.size());
		btConvexHullShape shape;
		for (int i = 0; i < hull.vertices.size(); ++i) shape.addPoint(hull.vertices[i] - centre, false);
		shape.recalcLocalAabb();
		shape.setLocalScaling(pictureScale);
		caliber::demo::MeshStyle style;
		static int colour = 0;
		style.color = caliber::demo::paletteColor(colour++);
		caliber::demo::addShape(*gPicture, &shape, btTransform(btQuaternion::getIdentity(), pictureAt), style);
	}
	return euler == 2;
}

/// Part 2: convex hulls of a few clouds; returns true when every hull is a closed polyhedron.
bool demoConvexHulls()
{
	BT_PROFILE("convex hulls");
	printf("2. Convex hulls with btConvexHullComputer\n");
	DemoRandom random(2026);
	bool allClosed = true;

	std::vector<btVector3> cube;
	for (int i = 0; i < 2000; ++i)
	{
		cube.push_back(btVector3(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1)));
	}
	allClosed &= buildAndReportHull("random points in a cube", cube, btVector3(-3, 10, 3));

	// Every point on a sphere is extreme, so most of them become hull vertices.
	std::vector<btVector3> sphere;
	while (sphere.size() < 500)
	{
		const btVector3 p(random.uniform(-1, 1), random.uniform(-1, 1), random.uniform(-1, 1));
		const btScalar length2 = p.length2();
		if (length2 > btScalar(0.01) && length2 <= btScalar(1)) sphere.push_back(p / btSqrt(length2));
	}
	allClosed &= buildAndReportHull("random points on a sphere", sphere, btVector3(-3, 10, 0));

	// A long thin box far from the origin: hulls must not depend on where the cloud sits.
	std::vector<btVector3> farBox;
	const btVector3 offset(btScalar(1000), btScalar(-2000), btScalar(500));
	for (int i = 0; i < 300; ++i)
	{
		farBox.push_back(offset + btVector3(random.uniform(-20, 20), random.uniform(-1, 1), random.uniform(-1, 1)));
	}
	// Drawn a tenth as long, next to the others.
	allClosed &=
	    buildAndReportHull("thin box far from origin", farBox, btVector3(-3, 10, -3), btVector3(btScalar(0.1), 1, 1));
	printf("\n");
	return allClosed;
}
}  // namespace

int caliber::demo::linearMathDemo(int argc, char** argv)
{
	caliber::demo::DemoPictures pictures(argc, argv, "LinearMathDemo");
	if (!pictures.ok()) return pictures.exitCode();
	caliber::demo::Scene picture;
	if (pictures.wanted()) gPicture = &picture;

	printf("Caliber LinearMathDemo (btScalar is %s, %s path)\n\n", btIsDoublePrecision() ? "double" : "float",
#ifdef BT_USE_SSE
	       "SSE"
#else
	       "scalar"
#endif
	);

	CProfileManager::Reset();
	const bool integrationOk = demoIntegration();
	const bool hullsOk = demoConvexHulls();
	CProfileManager::Increment_Frame_Counter();

	printf("3. Where the time went (BT_PROFILE + CProfileManager::dumpAll)\n");
	CProfileManager::dumpAll();
	printf("\n");

	if (!integrationOk) printf("FAILED: integrated motion is out of tolerance\n");
	if (!hullsOk) printf("FAILED: a hull is not a closed polyhedron\n");
	if (integrationOk && hullsOk) printf("All LinearMath checks of this demo passed.\n");
	pictures.capture(picture);
	return pictures.finish(integrationOk && hullsOk ? 0 : 1);
}
