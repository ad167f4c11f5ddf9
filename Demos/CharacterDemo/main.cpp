// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// CharacterDemo: a kinematic character (a capsule of radius 0.3 m and height 1.6 m on a ghost object,
// step height 0.35 m, maximum slope 45 degrees, Bullet's 3 g gravity) tries a course, headless, one
// lane each: walks across flat ground, climbs stairs of 0.3 m, walks up a 30 degree slope and fails to
// walk up a 50 degree one, jumps, runs into a wall at 20 m/s, and rides a moving platform. It prints
// where it is after each part.
// Checks: 5 m walked on the flat; the stairs' top reached (1.2 m); the 30 degree slope climbed, the
// 50 degree one not (height gained below the step height); the jump's apex v^2 / (2 g) within 1 cm
// and no ground reported in the air; the wall not passed; the character keeps its place on the
// platform within 1 cm. Exit 1 when a check fails. --frames N stops the course after N steps (the whole
// course is 1340); the checks of the parts it did not finish are skipped. --png shows the end of the
// course: the wall's lane and the platform (docs/demos.md).

#include <math.h>
#include <stdio.h>

#include "CharacterScene.h"
#include "DemoPictures.h"
#include "DemoScript.h"

using namespace character_demo;

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "CharacterDemo";
	commandLine.defaultFrames = 1000000;  // more than the course takes: by default it runs to its end
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	// The course is 60 m wide; the picture shows its last two lanes, the wall and the moving platform.
	pictures.setFocus(btVector3(45, 0, -2), btVector3(63, 3, 6));

	character_demo::Scene scene;
	// --frames: once the budget is spent nothing steps any more, and a part it cut short is not judged.
	caliber::demo::DemoScript script(scene.world(), kStep, pictures.stepBudget());
	btRigidBody* platform = scene.platform();
	btPairCachingGhostObject& ghost = scene.ghost();
	btKinematicCharacterController& character = scene.character();
	auto feet = [&]() { return ghost.getWorldTransform().getOrigin() - btVector3(0, kHalfHeight, 0); };
	auto report = [&](const char* part) {
		const btVector3 f = feet();
		printf("%-10s feet at (%6.2f, %5.2f, %6.2f)  on ground %s\n", part, f.x(), f.y(), f.z(),
		       character.onGround() ? "yes" : "no");
	};
	auto startLane = [&](btScalar x, btScalar y = 0) {
		character.setWalkDirection(btVector3(0, 0, 0));
		character.warp(btVector3(x, y + kHalfHeight + btScalar(0.001), 0));
		script.run(20);
	};
	const btVector3 walk(0, 0, btScalar(0.05));  // 3 m/s

	printf("CharacterDemo: capsule r 0.3 m, height 1.6 m, step height 0.35 m, max slope 45 degrees\n");
	startLane(0);
	character.setWalkDirection(walk);
	script.run(100);
	report("flat");
	script.judge(fabs(feet().z() - 5) < 0.01 && fabs(feet().y()) < 0.01, "walked 5 m on flat ground");

	startLane(10);
	character.setWalkDirection(walk);
	script.run(200);
	report("stairs");
	script.judge(fabs(feet().y() - 1.2) < 0.01, "climbed four 0.3 m steps to 1.2 m");

	startLane(20);
	character.setWalkDirection(walk);
	script.run(200);
	report("slope 30");
	script.judge(feet().y() > 3, "walked up the 30 degree slope");

	startLane(30);
	character.setWalkDirection(walk);
	script.run(200);
	report("slope 50");
	script.judge(feet().y() < 0.35, "did not walk up the 50 degree slope");

	startLane(40);
	const btScalar y0 = feet().y();
	character.jump();
	btScalar apex = y0;
	bool groundInAir = false;
	for (int i = 0; i < 60; ++i)
	{
		script.run(1);
		apex = btMax(apex, feet().y());
		if (feet().y() > y0 + btScalar(0.01) && character.onGround()) groundInAir = true;
	}
	report("jump");
	const btScalar expected = character.getJumpSpeed() * character.getJumpSpeed() / (2 * -character.getGravity().y());
	printf("  apex %.3f m (v^2 / (2 g) = %.3f m)\n", double(apex - y0), double(expected));
	script.judge(fabs(apex - y0 - expected) < 0.01, "jump apex");
	script.judge(!groundInAir && character.onGround(), "no ground reported in the air, ground after landing");

	startLane(50);
	character.setVelocityForTimeInterval(btVector3(0, 0, 20), 1);
	script.run(60);
	report("wall");
	script.judge(feet().z() < 5 - 0.05 - kRadius + 0.01, "the 10 cm wall was not passed at 20 m/s");

	startLane(60, btScalar(1.1));
	const btVector3 offset = feet() - platform->getWorldTransform().getOrigin();
	for (int i = 0; i < 180; ++i)
	{
		btTransform pose = platform->getWorldTransform();
		pose.setOrigin(pose.getOrigin() + btVector3(0, btScalar(0.3), 1) * kStep);
		platform->getMotionState()->setWorldTransform(pose);
		script.run(1);
	}
	report("platform");
	const btVector3 drift = feet() - platform->getWorldTransform().getOrigin() - offset;
	printf("  platform moved to (%.2f, %.2f, %.2f); the character moved with it within %.4f m\n",
	       platform->getWorldTransform().getOrigin().x(), platform->getWorldTransform().getOrigin().y(),
	       platform->getWorldTransform().getOrigin().z(), double(drift.length()));
	script.judge(drift.length() < 0.01, "rode the moving platform");

	pictures.capture(scene.world());
	return pictures.finish(script.verdict("CharacterDemo"));
}
