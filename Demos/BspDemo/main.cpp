// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// BspDemo: a Quake 3 level as static collision, headless. It loads a BSP file (by default the example room
// that Extras/BspLoader/tools/MakeBspLevel writes at build time: a 16 x 16 m room with four walls, a ramp,
// four pillars and a pool of water), turns each solid brush into a convex hull, builds one static compound
// from them and drops 44 bodies (spheres, boxes and cylinders) from 3 to 9 m, one box over each pillar and
// some over the ramp. Quake levels are z-up, in units of about 1/32 m. Each second it prints how many bodies are
// asleep or slower than 0.1 m/s and the lowest body centre (0.2 m for a cylinder on its side; less only
// for a moment at a landing, at up to 12 m/s). Checks: no body leaves the room or falls through the
// floor (every centre stays above z = 0 and inside the walls), the bodies at rest lie on a surface (no
// centre below 0.19 m after 8 s), at least 3/4 of them are at rest after 8 s, and the pillars' boxes
// stay on top. Then it shows what a damaged file gives: a clear error, no crash.
// Usage: BspDemo [FILE.bsp]. Exit 1 when a check fails or the file does not load.

#include "DemoPictures.h"

#include <stdio.h>

#include <memory>
#include <vector>

#include "BspLoader/BspConverter.h"
#include "BspLoader/BspLoader.h"
#include "BspScene.h"

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "BspDemo";
	commandLine.maxPositional = 1;
	commandLine.positionalUsage = "[level.bsp]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	const char* path = pictures.positional().empty() ? CALIBER_EXAMPLE_BSP : pictures.positional()[0].c_str();
	caliber::BspLevel level;
	if (!caliber::loadBspFile(path, level))
	{
		printf("BspDemo: %s\n", level.error.c_str());
		return 1;
	}
	const btScalar scale = bsp_demo::kScale;
	const caliber::BspConversion conversion = caliber::convertBspBrushes(level, scale);
	for (const std::string& warning : conversion.warnings) printf("  warning: %s\n", warning.c_str());
	printf("level %s: %zu textures, %zu world brushes: %zu solid hulls, %d not solid, %zu skipped\n", path,
	       level.textures.size(), level.brushes.size(), conversion.pieces.size(), conversion.nonSolidBrushes,
	       conversion.warnings.size());
	caliber::BspLevelShape levelShape = caliber::buildBspLevelShape(conversion);
	if (!levelShape.compound)
	{
		printf("BspDemo: the level has no solid brush\n");
		return 1;
	}
	btVector3 levelMin, levelMax;
	btTransform identity;
	identity.setIdentity();
	levelShape.compound->getAabb(identity, levelMin, levelMax);
	printf("level bounds (m): (%.2f %.2f %.2f) to (%.2f %.2f %.2f)\n", levelMin.x(), levelMin.y(), levelMin.z(),
	       levelMax.x(), levelMax.y(), levelMax.z());

	bsp_demo::Scene scene(levelShape.compound.get());  // BspScene.h: the world and the 44 bodies
	btDiscreteDynamicsWorld& world = scene.world();
	const std::vector<std::unique_ptr<btRigidBody>>& bodies = scene.bodies();

	const btScalar wallInside = btScalar(8);  // the walls' inner faces are at +-256 units = +-8 m
	bool escaped = false;
	int atRest = 0;
	btScalar lowestAtEnd = 0;
	for (int second = 1; second <= 8; ++second)
	{
		btScalar lowest = BT_LARGE_FLOAT;
		for (int step = 0; step < 60; ++step)
		{
			world.stepSimulation(btScalar(1) / 60, 0);
			for (const auto& body : bodies)
			{
				const btVector3& at = body->getWorldTransform().getOrigin();
				lowest = btMin(lowest, at.z());
				if (!(at.z() > 0) || btFabs(at.x()) > wallInside || btFabs(at.y()) > wallInside) escaped = true;
			}
		}
		int sleeping = 0;
		atRest = 0;
		for (const auto& body : bodies)
		{
			sleeping += body->getActivationState() == ISLAND_SLEEPING;
			atRest += body->getLinearVelocity().length() < btScalar(0.1);
		}
		lowestAtEnd = lowest;
		printf("t = %d s: %2d asleep, %2d slower than 0.1 m/s, lowest centre z = %.3f m\n", second, sleeping, atRest,
		       lowest);
	}
	int onPillars = 0, raised = 0;
	for (const auto& body : bodies)
	{
		const btScalar z = body->getWorldTransform().getOrigin().z();
		onPillars += z > btScalar(6);                     // pillar tops are at 192 units = 6 m
		raised += z > btScalar(0.35) && z < btScalar(6);  // on the ramp or on another body
	}
	printf("at the end: %d bodies on pillar tops, %d on the ramp or on other bodies, %d on the floor\n", onPillars,
	       raised, int(bodies.size()) - onPillars - raised);
	// The picture: the world as the run ends (z up, so seen from above at a slant).
	pictures.setViewDirection(btVector3(btScalar(0.3), btScalar(0.8), btScalar(-1)));
	pictures.capture(world);

	// A damaged copy of the file: cut in half. The loader names what is wrong instead of crashing.
	std::vector<unsigned char> bytes;
	if (FILE* file = fopen(path, "rb"))
	{
		unsigned char buffer[4096];
		size_t got;
		while ((got = fread(buffer, 1, sizeof(buffer), file)) > 0) bytes.insert(bytes.end(), buffer, buffer + got);
		fclose(file);
	}
	caliber::BspLevel damaged;
	caliber::loadBspFromMemory(bytes.data(), bytes.size() / 2, damaged);
	printf("the same file cut to %zu bytes: %s\n", bytes.size() / 2, damaged.ok() ? "loaded" : damaged.error.c_str());

	const bool restOk = atRest * 4 >= int(bodies.size()) * 3 && lowestAtEnd > btScalar(0.19);
	printf("check: every body stayed in the room above the floor: %s\n", escaped ? "FAILED" : "ok");
	printf("check: at least 3/4 of the bodies at rest after 8 s (%d of %zu), lowest centre %.3f m >= 0.19: %s\n",
	       atRest, bodies.size(), lowestAtEnd, restOk ? "ok" : "FAILED");
	printf("check: the four boxes dropped on the pillars stay on top: %s\n", onPillars == 4 ? "ok" : "FAILED");
	printf("check: the damaged file is refused: %s\n", damaged.ok() ? "FAILED" : "ok");
	return pictures.finish((!escaped && restOk && onPillars == 4 && !damaged.ok()) ? 0 : 1);
}
