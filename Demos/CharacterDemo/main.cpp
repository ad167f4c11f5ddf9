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

#include <limits.h>
#include <math.h>
#include <stdio.h>

#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletDynamics/Character/btKinematicCharacterController.h"
#include "DemoPictures.h"
#include "btBulletDynamicsCommon.h"

namespace
{
const btScalar kStep = btScalar(1. / 60.);
const btScalar kRadius = btScalar(0.3), kCylinder = btScalar(1.0), kHalfHeight = kRadius + kCylinder / 2;
int failures = 0;

void check(bool ok, const char* what)
{
	printf("  check: %s: %s\n", what, ok ? "ok" : "FAILED");
	if (!ok) ++failures;
}

struct Scene
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher{&configuration};
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
	btGhostPairCallback ghostCallback;
	btAlignedObjectArray<btCollisionShape*> shapes;
	btAlignedObjectArray<btRigidBody*> bodies;

	Scene()
	{
		world.setGravity(btVector3(0, -10, 0));
		broadphase.getOverlappingPairCache()->setInternalGhostPairCallback(&ghostCallback);
	}
	~Scene()
	{
		for (int i = 0; i < bodies.size(); ++i)
		{
			world.removeRigidBody(bodies[i]);
			delete bodies[i]->getMotionState();
			delete bodies[i];
		}
		for (int i = 0; i < shapes.size(); ++i) delete shapes[i];
	}
	btRigidBody* box(const btVector3& halfExtents, const btTransform& pose, bool kinematic = false)
	{
		btBoxShape* shape = new btBoxShape(halfExtents);
		shape->setMargin(0);  // sharp edges: step heights are exact
		shapes.push_back(shape);
		btRigidBody* body =
		    new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(0, new btDefaultMotionState(pose), shape));
		if (kinematic)
		{
			body->setCollisionFlags(body->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
			body->setActivationState(DISABLE_DEACTIVATION);
		}
		bodies.push_back(body);
		world.addRigidBody(body);
		return body;
	}
	void run(int steps)
	{
		for (int i = 0; i < steps && !budget.spent(); ++i)
		{
			world.stepSimulation(kStep, 1, kStep);
			budget.count();
		}
	}
	/// --frames' budget of steps: once it is used up nothing steps any more.
	caliber::demo::StepBudget budget{INT_MAX, false};
};

btTransform at(btScalar x, btScalar y, btScalar z) { return btTransform(btQuaternion::getIdentity(), btVector3(x, y, z)); }
btTransform tilted(btScalar degrees, btScalar x, btScalar footZ, btScalar halfLength, btScalar halfThickness)
{
	// A plank rising towards +z from its foot at (x, 0, footZ).
	const btScalar a = btRadians(degrees);
	return btTransform(btQuaternion(btVector3(1, 0, 0), -a),
	                   btVector3(x, halfLength * btSin(a) - halfThickness / btCos(a), footZ + halfLength * btCos(a)));
}
}  // namespace

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "CharacterDemo";
	commandLine.defaultFrames = 1000000;  // more than the course takes: by default it runs to its end
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();
	// The course is 60 m wide; the picture shows its last two lanes, the wall and the moving platform.
	pictures.setFocus(btVector3(45, 0, -2), btVector3(63, 3, 6));

	Scene scene;
	scene.budget = pictures.stepBudget();
	scene.box(btVector3(100, 1, 100), at(0, -1, 0));  // the ground, top at y = 0
	// Stairs in lane x = 10: four steps of 0.3 m, 1 m deep, from z = 2.
	for (int i = 0; i < 4; ++i)
	{
		const btScalar top = btScalar(0.3) * (i + 1);
		scene.box(btVector3(1, top / 2, btScalar(0.5)), at(10, top / 2, btScalar(2.5) + i));
	}
	scene.box(btVector3(1, btScalar(0.6), 3), at(10, btScalar(0.6), btScalar(8.5)));  // landing at 1.2 m
	scene.box(btVector3(1, btScalar(0.5), 10), tilted(30, 20, 2, 10, btScalar(0.5)));
	scene.box(btVector3(1, btScalar(0.5), 10), tilted(50, 30, 2, 10, btScalar(0.5)));
	scene.box(btVector3(2, 2, btScalar(0.05)), at(50, 2, 5));  // a 10 cm wall
	btRigidBody* platform = scene.box(btVector3(2, btScalar(0.1), 2), at(60, btScalar(1), 0), true);

	btCapsuleShape capsule(kRadius, kCylinder);
	btPairCachingGhostObject ghost;
	ghost.setCollisionShape(&capsule);
	ghost.setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
	ghost.setWorldTransform(at(0, kHalfHeight, 0));
	scene.world.addCollisionObject(&ghost, btBroadphaseProxy::CharacterFilter,
	                               btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter |
	                                   btBroadphaseProxy::KinematicFilter);
	btKinematicCharacterController character(&ghost, &capsule, btScalar(0.35), btVector3(0, 1, 0));
	scene.world.addAction(&character);

	// A part that --frames cut short is not judged.
	auto judge = [&](bool ok, const char* what) {
		if (scene.budget.reached(what)) check(ok, what);
	};
	auto feet = [&]() { return ghost.getWorldTransform().getOrigin() - btVector3(0, kHalfHeight, 0); };
	auto report = [&](const char* part) {
		const btVector3 f = feet();
		printf("%-10s feet at (%6.2f, %5.2f, %6.2f)  on ground %s\n", part, f.x(), f.y(), f.z(),
		       character.onGround() ? "yes" : "no");
	};
	auto startLane = [&](btScalar x, btScalar y = 0) {
		character.setWalkDirection(btVector3(0, 0, 0));
		character.warp(btVector3(x, y + kHalfHeight + btScalar(0.001), 0));
		scene.run(20);
	};
	const btVector3 walk(0, 0, btScalar(0.05));  // 3 m/s

	printf("CharacterDemo: capsule r 0.3 m, height 1.6 m, step height 0.35 m, max slope 45 degrees\n");
	startLane(0);
	character.setWalkDirection(walk);
	scene.run(100);
	report("flat");
	judge(fabs(feet().z() - 5) < 0.01 && fabs(feet().y()) < 0.01, "walked 5 m on flat ground");

	startLane(10);
	character.setWalkDirection(walk);
	scene.run(200);
	report("stairs");
	judge(fabs(feet().y() - 1.2) < 0.01, "climbed four 0.3 m steps to 1.2 m");

	startLane(20);
	character.setWalkDirection(walk);
	scene.run(200);
	report("slope 30");
	judge(feet().y() > 3, "walked up the 30 degree slope");

	startLane(30);
	character.setWalkDirection(walk);
	scene.run(200);
	report("slope 50");
	judge(feet().y() < 0.35, "did not walk up the 50 degree slope");

	startLane(40);
	const btScalar y0 = feet().y();
	character.jump();
	btScalar apex = y0;
	bool groundInAir = false;
	for (int i = 0; i < 60; ++i)
	{
		scene.run(1);
		apex = btMax(apex, feet().y());
		if (feet().y() > y0 + btScalar(0.01) && character.onGround()) groundInAir = true;
	}
	report("jump");
	const btScalar expected = character.getJumpSpeed() * character.getJumpSpeed() / (2 * -character.getGravity().y());
	printf("  apex %.3f m (v^2 / (2 g) = %.3f m)\n", double(apex - y0), double(expected));
	judge(fabs(apex - y0 - expected) < 0.01, "jump apex");
	judge(!groundInAir && character.onGround(), "no ground reported in the air, ground after landing");

	startLane(50);
	character.setVelocityForTimeInterval(btVector3(0, 0, 20), 1);
	scene.run(60);
	report("wall");
	judge(feet().z() < 5 - 0.05 - kRadius + 0.01, "the 10 cm wall was not passed at 20 m/s");

	startLane(60, btScalar(1.1));
	const btVector3 offset = feet() - platform->getWorldTransform().getOrigin();
	for (int i = 0; i < 180; ++i)
	{
		btTransform pose = platform->getWorldTransform();
		pose.setOrigin(pose.getOrigin() + btVector3(0, btScalar(0.3), 1) * kStep);
		platform->getMotionState()->setWorldTransform(pose);
		scene.run(1);
	}
	report("platform");
	const btVector3 drift = feet() - platform->getWorldTransform().getOrigin() - offset;
	printf("  platform moved to (%.2f, %.2f, %.2f); the character moved with it within %.4f m\n",
	       platform->getWorldTransform().getOrigin().x(), platform->getWorldTransform().getOrigin().y(),
	       platform->getWorldTransform().getOrigin().z(), double(drift.length()));
	judge(drift.length() < 0.01, "rode the moving platform");

	pictures.capture(scene.world);
	scene.world.removeAction(&character);
	scene.world.removeCollisionObject(&ghost);
	printf("CharacterDemo: %s\n", failures ? "FAILED" : "all checks passed");
	return pictures.finish(failures ? 1 : 0);
}
