// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Raytracer: btCollisionWorld::rayTest as a camera, headless. A sphere, a box, a cylinder and a cone stand on a floor
// made of a small triangle mesh; one ray per pixel of a 128x128 image (--size WxH for another) finds the closest hit,
// and the pixel is shaded by the hit normal (its colour) and a directional light. The image is written as a PNG
// (raytracer.png in the current directory, the path given as the argument or by --png); a path ending in .ppm, or a
// build without libpng, gets a binary PPM instead (raytracer.ppm by default). Every ray is also checked against an
// analytic intersection written here: rays that pass clearly through the sphere or the box must hit it, rays that pass
// clearly beside them must not, and hit points must lie on the surface. The demo exits 1 when a check fails or the file
// cannot be written.

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "btBulletCollisionCommon.h"

#include <stdio.h>
#include <string.h>

#include <string>
#include <vector>

#include "DemoPictures.h"
#include "DemoPrograms.h"
#include "Png.h"
#include "WorldScene.h"

namespace
{
const int kDefaultImageSize = 128;

/// How far a convex ray hit may lie from the exact surface: the world's convex ray test stops within
/// sqrt(MAX_CONVEX_CAST_EPSILON) (1e-3 in float) of the shape; five times that leaves room for rounding. Rays whose
/// analytic answer is this close to a silhouette are not judged.
const btScalar kSurfaceTolerance = btScalar(5e-3);

enum ObjectIndex
{
	kSphere,
	kBox,
	kCylinder,
	kCone,
	kFloor,
	kObjectCount
};
const char* const kObjectNames[kObjectCount] = {"sphere", "box", "cylinder", "cone", "floor mesh"};

/// Where a ray enters an axis-aligned box of the given half extents centred at the origin (slab test in double);
/// returns false when the ray from + t * dir, t in [0, 1], misses it.
bool rayHitsAlignedBox(const btVector3& from, const btVector3& dir, const btVector3& halfExtents)
{
	double tEnter = 0.0, tExit = 1.0;
	for (int axis = 0; axis < 3; ++axis)
	{
		const double o = double(from[axis]), d = double(dir[axis]), h = double(halfExtents[axis]);
		if (d == 0.0)
		{
			if (o < -h || o > h) return false;
			continue;
		}
		double t0 = (-h - o) / d, t1 = (h - o) / d;
		if (t0 > t1)
		{
			const double swap = t0;
			t0 = t1;
			t1 = swap;
		}
		tEnter = t0 > tEnter ? t0 : tEnter;
		tExit = t1 < tExit ? t1 : tExit;
		if (tEnter > tExit) return false;
	}
	return true;
}

/// Distance from a point to the segment from + t * dir, t in [0, 1] (in double).
double distanceToSegment(const btVector3& point, const btVector3& from, const btVector3& dir)
{
	const double px = double(point.x() - from.x()), py = double(point.y() - from.y()),
	             pz = double(point.z() - from.z());
	const double dx = double(dir.x()), dy = double(dir.y()), dz = double(dir.z());
	double t = (px * dx + py * dy + pz * dz) / (dx * dx + dy * dy + dz * dz);
	t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
	const double ex = px - t * dx, ey = py - t * dy, ez = pz - t * dz;
	return btSqrt(btScalar(ex * ex + ey * ey + ez * ez));
}

/// Counts of the checks, printed at the end.
struct CheckStats
{
	int judged = 0;
	int failures = 0;
	/// Prints the first few failures only, so a broken build does not flood the log.
	void fail(int px, int py, const char* what)
	{
		if (failures < 10) printf("  WRONG at pixel (%d, %d): %s\n", px, py, what);
		++failures;
	}
};

/// One byte of colour from a value in [0, 1].
unsigned char toByte(btScalar value)
{
	const btScalar clamped = value < 0 ? btScalar(0) : (value > 1 ? btScalar(1) : value);
	return static_cast<unsigned char>(clamped * btScalar(255) + btScalar(0.5));
}
}  // namespace

namespace
{
bool endsWith(const std::string& text, const char* suffix)
{
	const size_t n = strlen(suffix);
	return text.size() >= n && text.compare(text.size() - n, n, suffix) == 0;
}
}  // namespace

int caliber::demo::raytracerDemo(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "Raytracer";
	commandLine.maxPositional = 1;
	commandLine.positionalUsage = "[OUTPUT.png|OUTPUT.ppm]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	const bool png = caliber::demo::pngAvailable();
	const std::string outputPath = !pictures.positional().empty() ? pictures.positional()[0]
	                               : png                          ? "raytracer.png"
	                                                              : "raytracer.ppm";
	const int width = pictures.sizeGiven() ? pictures.width() : kDefaultImageSize;
	const int height = pictures.sizeGiven() ? pictures.height() : kDefaultImageSize;
	const btScalar aspect = btScalar(width) / btScalar(height);

	// The world: default configuration, dispatcher, broadphase.
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btCollisionWorld world(&dispatcher, &broadphase, &configuration);

	// The shapes, all standing on the floor at y = -1.
	btSphereShape sphere(btScalar(1));
	const btVector3 boxHalfExtents(btScalar(0.9), btScalar(0.9), btScalar(0.9));
	btBoxShape box(boxHalfExtents);
	btCylinderShape cylinder(btVector3(btScalar(0.8), btScalar(1), btScalar(0.8)));
	btConeShape cone(btScalar(1), btScalar(2));

	// The floor: a 14 x 6 grid of 2 x 2 quads at y = -1, two triangles each, wound to face up.
	btTriangleMesh floorMesh;
	for (int ix = 0; ix < 7; ++ix)
	{
		for (int iz = 0; iz < 3; ++iz)
		{
			const btScalar x0 = btScalar(-7 + 2 * ix), z0 = btScalar(-3 + 2 * iz);
			const btVector3 a(x0, -1, z0), b(x0 + 2, -1, z0), c(x0 + 2, -1, z0 + 2), d(x0, -1, z0 + 2);
			floorMesh.addTriangle(a, d, c);
			floorMesh.addTriangle(a, c, b);
		}
	}
	btBvhTriangleMeshShape floorShape(&floorMesh, true);

	const btQuaternion boxRotation(btVector3(0, 1, 0), btScalar(0.5));
	btCollisionObject objects[kObjectCount];
	const btTransform placements[kObjectCount] = {
	    btTransform(btQuaternion::getIdentity(), btVector3(btScalar(-4.5), 0, 0)),
	    btTransform(boxRotation, btVector3(btScalar(-1.5), btScalar(-0.1), 0)),
	    btTransform(btQuaternion::getIdentity(), btVector3(btScalar(1.5), 0, 0)),
	    btTransform(btQuaternion::getIdentity(), btVector3(btScalar(4.5), 0, 0)),
	    btTransform::getIdentity(),
	};
	btCollisionShape* const shapes[kObjectCount] = {&sphere, &box, &cylinder, &cone, &floorShape};
	for (int i = 0; i < kObjectCount; ++i)
	{
		objects[i].setCollisionShape(shapes[i]);
		objects[i].setWorldTransform(placements[i]);
		objects[i].setUserIndex(i);
		world.addCollisionObject(&objects[i]);
	}
	world.updateAabbs();

	// A pinhole camera above and in front of the row, looking at its middle, 64 degree field of view.
	const btVector3 eye(0, btScalar(4.5), btScalar(8.5));
	const btVector3 forward = (btVector3(0, btScalar(-0.8), 0) - eye).normalized();
	const btVector3 right = forward.cross(btVector3(0, 1, 0)).normalized();
	const btVector3 up = right.cross(forward);
	const btScalar halfWidth = btTan(btScalar(SIMD_PI * 32.0 / 180.0));
	const btScalar rayLength = btScalar(100);
	const btVector3 light = btVector3(btScalar(-0.4), btScalar(1), btScalar(0.6)).normalized();

	std::vector<unsigned char> image(size_t(width) * size_t(height) * 3u);
	int hitCounts[kObjectCount] = {0, 0, 0, 0, 0};
	int misses = 0;
	CheckStats checks;

	// In the demo browser (a recording): the shapes and every 8th ray of every 8th row, from the eye to
	// its hit (a dot in the pixel's colour) or into the sky, recorded row by row so that the scan plays back.
	const int rayStride = 8;
	caliber::demo::Scene rays;
	for (int py = 0; py < height; ++py)
	{
		for (int px = 0; px < width; ++px)
		{
			const btScalar u = ((btScalar(px) + btScalar(0.5)) / btScalar(width) * 2 - 1) * aspect;
			const btScalar v = 1 - (btScalar(py) + btScalar(0.5)) / btScalar(height) * 2;
			const btVector3 dir = (forward + right * (u * halfWidth) + up * (v * halfWidth)).normalized();
			const btVector3 to = eye + dir * rayLength;
			btCollisionWorld::ClosestRayResultCallback callback(eye, to);
			world.rayTest(eye, to, callback);

			const int hitIndex = callback.hasHit() ? callback.m_collisionObject->getUserIndex() : -1;
			unsigned char* pixel = &image[(size_t(py) * size_t(width) + size_t(px)) * 3u];
			if (hitIndex < 0)
			{
				++misses;
				const btScalar sky = btScalar(0.5) + btScalar(0.5) * dir.y();
				pixel[0] = toByte(btScalar(0.15) * sky);
				pixel[1] = toByte(btScalar(0.2) * sky);
				pixel[2] = toByte(btScalar(0.35) * sky);
			}
			else
			{
				++hitCounts[hitIndex];
				const btVector3& n = callback.m_hitNormalWorld;
				const btScalar diffuse = btMax(btScalar(0), n.dot(light));
				const btScalar shade = btScalar(0.25) + btScalar(0.75) * diffuse;
				pixel[0] = toByte((btScalar(0.5) + btScalar(0.5) * n.x()) * shade);
				pixel[1] = toByte((btScalar(0.5) + btScalar(0.5) * n.y()) * shade);
				pixel[2] = toByte((btScalar(0.5) + btScalar(0.5) * n.z()) * shade);
				if (btFabs(n.length() - 1) > btScalar(1e-3) || n.dot(dir) > 0)
				{
					checks.fail(px, py, "hit normal not unit length or not facing the ray");
				}
			}
			if (pictures.recording() && px % rayStride == rayStride / 2 && py % rayStride == rayStride / 2)
			{
				const btVector3 colour(pixel[0] / btScalar(255), pixel[1] / btScalar(255), pixel[2] / btScalar(255));
				const btVector3 end = hitIndex < 0 ? eye + dir * btScalar(9) : callback.m_hitPointWorld;
				rays.addLine(eye, end, hitIndex < 0 ? btVector3(0.55f, 0.6f, 0.75f) : btVector3(0.9f, 0.75f, 0.2f));
				if (hitIndex >= 0) rays.addPoint(end, colour);
			}

			// Analytic checks. The sphere: rays passing clearly inside must hit it, clearly outside must not.
			const btVector3 segment = to - eye;
			const btScalar sphereDistance = btScalar(distanceToSegment(placements[kSphere].getOrigin(), eye, segment));
			if (sphereDistance < sphere.getRadius() - kSurfaceTolerance)
			{
				++checks.judged;
				if (hitIndex != kSphere) checks.fail(px, py, "ray through the sphere missed it");
			}
			else if (sphereDistance > sphere.getRadius() + kSurfaceTolerance)
			{
				++checks.judged;
				if (hitIndex == kSphere) checks.fail(px, py, "ray beside the sphere hit it");
			}
			if (hitIndex == kSphere)
			{
				const btVector3 offset = callback.m_hitPointWorld - placements[kSphere].getOrigin();
				if (btFabs(offset.length() - sphere.getRadius()) > kSurfaceTolerance ||
				    offset.normalized().dot(callback.m_hitNormalWorld) < btScalar(0.99))
				{
					checks.fail(px, py, "sphere hit point or normal off the surface");
				}
			}
			// The box, in its own frame: its edges are rounded by the collision margin, so it lies between the core box
			// (half extents minus margin) and the full box.
			const btTransform toBoxLocal = placements[kBox].inverse();
			const btVector3 localFrom = toBoxLocal * eye;
			const btVector3 localDir = toBoxLocal.getBasis() * segment;
			const btVector3 margin(box.getMargin(), box.getMargin(), box.getMargin());
			const btVector3 tolerance(kSurfaceTolerance, kSurfaceTolerance, kSurfaceTolerance);
			if (rayHitsAlignedBox(localFrom, localDir, boxHalfExtents - margin - tolerance))
			{
				++checks.judged;
				if (hitIndex != kBox) checks.fail(px, py, "ray through the box missed it");
			}
			else if (!rayHitsAlignedBox(localFrom, localDir, boxHalfExtents + tolerance))
			{
				++checks.judged;
				if (hitIndex == kBox) checks.fail(px, py, "ray beside the box hit it");
			}
			// The floor is the plane y = -1 facing up.
			if (hitIndex == kFloor && (btFabs(callback.m_hitPointWorld.y() + 1) > btScalar(1e-3) ||
			                           callback.m_hitNormalWorld.dot(btVector3(0, 1, 0)) < btScalar(0.999)))
			{
				checks.fail(px, py, "floor hit off the plane y = -1 or normal not up");
			}
		}
		if (pictures.recording() && (py % rayStride == rayStride / 2 || py == height - 1))
		{
			caliber::demo::Scene shot;
			caliber::demo::WorldStyle style;
			style.debugMode = 0;
			caliber::demo::addWorld(shot, world, style);
			for (const caliber::demo::SceneLine& line : rays.lines()) shot.addLine(line.from, line.to, line.color);
			for (const caliber::demo::ScenePoint& point : rays.points()) shot.addPoint(point.position, point.color);
			shot.focusOn(btVector3(-7, -1, -3), btVector3(7, 2, 3));
			shot.focusOn(eye, eye);
			pictures.setViewDirection(btVector3(btScalar(-0.6), btScalar(-0.5), -1));
			pictures.capture(shot);
		}
	}

	for (int i = 0; i < kObjectCount; ++i)
	{
		printf("%-11s %5d pixels\n", kObjectNames[i], hitCounts[i]);
		if (hitCounts[i] == 0)
		{
			printf("  WRONG: the %s is in view but no ray hit it\n", kObjectNames[i]);
			++checks.failures;
		}
	}
	printf("%-11s %5d pixels (of %d rays)\n", "no hit", misses, width * height);
	printf("%d rays judged against the analytic sphere and box, %d failures\n", checks.judged, checks.failures);

	bool written = true;
	if (pictures.wanted())
	{
		// --png PATH: the ray-traced image is the demo's picture.
		caliber::demo::Image picture;
		picture.width = width;
		picture.height = height;
		picture.rgb = image;
		pictures.capture(picture);
	}
	else if (png && !endsWith(outputPath, ".ppm"))
	{
		caliber::demo::Image picture;
		picture.width = width;
		picture.height = height;
		picture.rgb = image;
		std::string error;
		written = caliber::demo::writePng(outputPath, picture, error);
		if (written)
			printf("Wrote %s\n", outputPath.c_str());
		else
			printf("FAILED: %s\n", error.c_str());
	}
	else
	{
		FILE* file = fopen(outputPath.c_str(), "wb");
		written = file != nullptr;
		if (written)
		{
			fprintf(file, "P6\n%d %d\n255\n", width, height);
			written = fwrite(image.data(), 1, image.size(), file) == image.size();
			written = fclose(file) == 0 && written;
		}
		printf(written ? "Wrote %s\n" : "FAILED to write %s\n", outputPath.c_str());
	}

	for (int i = 0; i < kObjectCount; ++i)
	{
		world.removeCollisionObject(&objects[i]);
	}
	return pictures.finish((written && checks.failures == 0) ? 0 : 1);
}
