// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// ColladaDemo: the COLLADA physics viewer, headless. It loads a COLLADA 1.4 physics document (by default
// playground.dae next to this file, written by hand: a ground plane, a stack of three boxes, a ball rolling
// towards the stack, a capsule, a cylinder, a convex pyramid, and a plank hinged to a post by a
// rigid_constraint), simulates it for 4 s at the document's time step and gravity, printing each body's
// height every second, then exports the world, imports the export and exports that again. Checks: every
// body comes to rest above the ground, the stack's top box stays on the stack, the plank has swung down
// with its end still on the hinge, and the two exports are the same text (the round trip is exact). It also shows what
// a damaged document gives. Usage: ColladaDemo [FILE.dae]. Exit 1 when a check fails.

#include "DemoPictures.h"

#include <stdio.h>

#include <string>

#include "ColladaScene.h"
#include "DemoWorld.h"
#include "Serialize/ColladaConverter/ColladaPhysics.h"

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "ColladaDemo";
	commandLine.maxPositional = 1;
	commandLine.positionalUsage = "[scene.dae]";
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	const char* path = pictures.positional().empty() ? CALIBER_COLLADA_DEMO_SCENE : pictures.positional()[0].c_str();
	collada_demo::Scene loaded;  // ColladaScene.h: the document's bodies in a world
	caliber::ColladaPhysicsScene& scene = loaded.document();
	btDiscreteDynamicsWorld& world = loaded.world();
	if (!loaded.load(path))
	{
		printf("ColladaDemo: %s: %s\n", path, scene.error.c_str());
		return 1;
	}
	printf("loaded %s: %zu rigid bodies, gravity (%.2f %.2f %.2f), time step %.4f s\n", path, scene.bodies.size(),
	       scene.gravity.x(), scene.gravity.y(), scene.gravity.z(), scene.timeStep);
	const int stepsPerSecond = int(btScalar(1) / scene.timeStep + btScalar(0.5));
	btScalar lowest = BT_LARGE_FLOAT;
	for (int second = 1; second <= 4; ++second)
	{
		for (int step = 0; step < stepsPerSecond; ++step)
		{
			world.stepSimulation(scene.timeStep, 0);
			for (std::size_t i = 0; i < scene.bodies.size(); ++i)
				if (scene.bodies[i]->getInvMass() > 0)
					lowest = btMin(lowest, scene.bodies[i]->getCenterOfMassPosition().y());
		}
		printf("t = %d s:", second);
		for (std::size_t i = 0; i < scene.bodies.size(); ++i)
			if (scene.bodies[i]->getInvMass() > 0)
				printf(" %s %.2f", scene.bodyNames[i].c_str(), scene.bodies[i]->getCenterOfMassPosition().y());
		printf("\n");
	}
	pictures.capture(world);  // the picture: the scene as the run ends
	int resting = 0, dynamic = 0;
	for (const auto& body : scene.bodies)
	{
		if (body->getInvMass() == 0) continue;
		++dynamic;
		resting += body->getLinearVelocity().length() < btScalar(0.1);
	}
	// The stack is the 2nd to 4th bodies; the top box, 1 m cubes on the ground, rests near y = 2.5.
	const btScalar top = scene.bodies.size() > 3 ? scene.bodies[3]->getCenterOfMassPosition().y() : 0;

	// The plank (last body) hinges at the post's top (4, 0.5, 2) by its end 0.6 m from its centre.
	const btRigidBody& plank = *scene.bodies.back();
	const btVector3 plankEnd = plank.getCenterOfMassTransform() * btVector3(btScalar(-0.6), 0, 0);
	const btScalar hingeGap = (plankEnd - btVector3(4, btScalar(0.5), 2)).length();
	const bool hingeOk = scene.constraints.size() == 1 && hingeGap < btScalar(0.01) &&
	                     plank.getCenterOfMassPosition().y() < btScalar(0.45);
	printf("the plank's end is %.4f m from the hinge, its centre %.3f m up\n", hingeGap,
	       plank.getCenterOfMassPosition().y());

	std::string first, second, error;
	bool roundTrip = caliber::exportColladaPhysics(world, scene.timeStep, first, error);
	caliber::ColladaPhysicsScene copy;
	roundTrip = roundTrip && caliber::importColladaPhysics(first.data(), first.size(), copy);
	caliber::demo::DemoWorld copyPhysics;  // a world of its own for the imported export
	copy.addTo(copyPhysics.world());
	roundTrip =
	    roundTrip && caliber::exportColladaPhysics(copyPhysics.world(), copy.timeStep, second, error) && first == second;
	printf("export: %zu bytes; imported again and exported: %s\n", first.size(),
	       roundTrip ? "the same text" : (error.empty() ? copy.error.c_str() : error.c_str()));

	caliber::ColladaPhysicsScene damaged;
	const std::string cut = first.substr(0, first.size() / 2);
	caliber::importColladaPhysics(cut.data(), cut.size(), damaged);
	printf("the export cut in half: %s\n", damaged.ok() ? "loaded" : damaged.error.c_str());

	copy.removeFrom(copyPhysics.world());  // bodies leave their worlds before either is destroyed

	const bool restOk = resting == dynamic && lowest > 0;
	const bool stackOk = top > btScalar(2.4) && top < btScalar(2.6);
	printf("check: every body at rest above the ground (%d of %d at rest, lowest centre %.3f m): %s\n", resting,
	       dynamic, lowest, restOk ? "ok" : "FAILED");
	printf("check: the stack stands (top box at %.3f m): %s\n", top, stackOk ? "ok" : "FAILED");
	printf("check: the plank swung down on its hinge: %s\n", hingeOk ? "ok" : "FAILED");
	printf("check: export, import, export gives the same document: %s\n", roundTrip ? "ok" : "FAILED");
	printf("check: the damaged document is refused: %s\n", damaged.ok() ? "FAILED" : "ok");
	return pictures.finish((restOk && stackOk && hingeOk && roundTrip && !damaged.ok()) ? 0 : 1);
}
