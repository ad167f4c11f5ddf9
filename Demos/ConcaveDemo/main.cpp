// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// ConcaveDemo: rigid bodies on concave static terrain, headless. The same rolling landscape
// y = h(x, z) = 0.6 sin(0.35 x) cos(0.3 z) is built twice, as a btBvhTriangleMeshShape (a 40 x 40 grid of
// quads, two triangles each) and as a btHeightfieldTerrainShape (41 x 41 float samples). On each, 48
// bodies (spheres, boxes and capsules, every shape at least 0.3 thick) are dropped from a few metres
// and left for 6 seconds. Each second the demo prints the lowest clearance (body centre above the
// terrain beneath it), the number of sleeping bodies and of bodies slower than 0.1 m/s. Checks: no
// body ever falls through (its centre stays at least 0.2 above h(x, z): every shape is thicker than
// that, and the flat triangles differ from h by under 1 cm), and at least half of them are at rest
// (slower than 0.1 m/s) by the end; spheres on a slope may keep rolling, and one rolling body keeps
// its whole pile's island awake. Exit 1 when a check fails. --frames N runs N steps on each terrain
// (default 360; shorter runs skip the at-rest check); --png shows the height field's last frame;
// --png-sequence covers both terrains (docs/demos.md).

#include <math.h>
#include <stdio.h>

#include "ConcaveScene.h"
#include "DemoPictures.h"

namespace
{
using concave_demo::terrainHeight;

// Runs the bodies of scene on its terrain; returns true when the checks pass.
bool dropBodiesOn(const char* name, concave_demo::Scene& scene, caliber::demo::DemoPictures& pictures)
{
	btDiscreteDynamicsWorld& world = scene.world();
	const std::vector<btRigidBody*>& bodies = scene.bodies();
	btScalar lowestClearance = BT_LARGE_FLOAT;
	int sleeping = 0;
	int slow = 0;
	for (int frame = 1; frame <= pictures.frames(); ++frame)
	{
		world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		for (size_t b = 0; b < bodies.size(); ++b)
		{
			const btVector3& p = bodies[b]->getCenterOfMassPosition();
			lowestClearance = btMin(lowestClearance, p.getY() - terrainHeight(p.getX(), p.getZ()));
		}
		pictures.frame(world, frame);
		if (frame % 60 != 0 && frame != pictures.frames()) continue;
		sleeping = 0;
		slow = 0;
		for (size_t b = 0; b < bodies.size(); ++b)
		{
			if (bodies[b]->getActivationState() == ISLAND_SLEEPING) ++sleeping;
			if (bodies[b]->getLinearVelocity().length() < btScalar(0.1)) ++slow;
		}
		if (frame % 60 == 0)
			printf("%s, t=%d s: lowest clearance %.3f, sleeping %d/%d, slower than 0.1 m/s %d\n", name, frame / 60,
			       double(lowestClearance), sleeping, int(bodies.size()), slow);
		else
			printf("%s, t=%.3f s: lowest clearance %.3f, sleeping %d/%d, slower than 0.1 m/s %d\n", name, frame / 60.0,
			       double(lowestClearance), sleeping, int(bodies.size()), slow);
	}
	const bool noneFellThrough = lowestClearance > btScalar(0.2);
	if (pictures.shortened())
	{
		printf(
		    "%s: nothing fell through (lowest clearance %.3f > 0.2): %s; at rest not checked (--frames %d is "
		    "shorter than 360)\n",
		    name, double(lowestClearance), noneFellThrough ? "ok" : "FAILED", pictures.frames());
		return noneFellThrough;
	}
	const bool mostAtRest = 2 * slow >= int(bodies.size());
	printf("%s: nothing fell through (lowest clearance %.3f > 0.2): %s; at rest (< 0.1 m/s) %d of %d: %s\n", name,
	       double(lowestClearance), noneFellThrough ? "ok" : "FAILED", slow, int(bodies.size()),
	       mostAtRest ? "ok" : "FAILED");
	return noneFellThrough && mostAtRest;
}
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "ConcaveDemo";
	commandLine.defaultFrames = 360;
	commandLine.sequences = true;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	bool ok = true;
	concave_demo::Scene scene;
	scene.build(concave_demo::kTriangleMesh);
	ok = dropBodiesOn("triangle mesh", scene, pictures) && ok;
	scene.build(concave_demo::kHeightField);
	ok = dropBodiesOn("height field", scene, pictures) && ok;
	return pictures.finish(ok ? 0 : 1);
}
