// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// BasicDemo: a 5 x 5 x 5 block of boxes (half extent 1, mass 1, 0.2 gaps between them) dropped onto a
// static ground, headless. Each simulated second the demo prints the lowest and highest box, the
// fastest speed and how many boxes sleep. The block lands, settles into five layers and falls asleep.
// Checks: no box ever sinks into the ground (centre below 0.95, the ground's surface plus its half
// extent minus 5 cm of allowed penetration), the block keeps its five layers (top layer within 10 cm
// of y = 9), and every box sleeps by the end. Exit 1 when a check fails. With --frames shorter than the
// default 480 (8 s) only the first check is made. --png and --png-sequence: docs/demos.md.

#include <stdio.h>

#include "DemoPictures.h"
#include "btBulletDynamicsCommon.h"

int main(int argc, char** argv)
{
	caliber::demo::DemoCommandLine commandLine;
	commandLine.name = "BasicDemo";
	commandLine.defaultFrames = 480;
	commandLine.sequences = true;
	caliber::demo::DemoPictures pictures(argc, argv, commandLine);
	if (!pictures.ok()) return pictures.exitCode();

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, -10, 0));

	btBoxShape groundShape(btVector3(50, 50, 50));
	btTransform groundPose(btQuaternion::getIdentity(), btVector3(0, -50, 0));
	btDefaultMotionState groundMotion(groundPose);
	btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, &groundMotion, &groundShape));
	world.addRigidBody(&ground);

	const int size = 5;
	btBoxShape boxShape(btVector3(1, 1, 1));
	btVector3 inertia;
	boxShape.calculateLocalInertia(1, inertia);
	btAlignedObjectArray<btDefaultMotionState*> motions;
	btAlignedObjectArray<btRigidBody*> boxes;
	for (int k = 0; k < size; ++k)
		for (int i = 0; i < size; ++i)
			for (int j = 0; j < size; ++j)
			{
				const btVector3 origin(btScalar(2.2) * (i - 2), btScalar(1.5) + btScalar(2.2) * k,
				                       btScalar(2.2) * (j - 2));
				btDefaultMotionState* motion =
				    new btDefaultMotionState(btTransform(btQuaternion::getIdentity(), origin));
				btRigidBody* box =
				    new btRigidBody(btRigidBody::btRigidBodyConstructionInfo(1, motion, &boxShape, inertia));
				world.addRigidBody(box);
				motions.push_back(motion);
				boxes.push_back(box);
			}

	bool sank = false;
	btScalar lowest = BT_LARGE_FLOAT, highest = -BT_LARGE_FLOAT;
	int sleeping = 0;
	for (int frame = 1; frame <= pictures.frames(); ++frame)
	{
		world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		for (int b = 0; b < boxes.size(); ++b)
			if (boxes[b]->getCenterOfMassPosition().getY() < btScalar(0.95)) sank = true;
		pictures.frame(world, frame);
		if (frame % 60 != 0 && frame != pictures.frames()) continue;
		lowest = BT_LARGE_FLOAT;
		highest = -BT_LARGE_FLOAT;
		btScalar fastest = 0;
		sleeping = 0;
		for (int b = 0; b < boxes.size(); ++b)
		{
			const btScalar y = boxes[b]->getCenterOfMassPosition().getY();
			lowest = btMin(lowest, y);
			highest = btMax(highest, y);
			fastest = btMax(fastest, boxes[b]->getLinearVelocity().length());
			if (boxes[b]->getActivationState() == ISLAND_SLEEPING) ++sleeping;
		}
		if (frame % 60 == 0)
			printf("t=%d s: lowest box y=%.3f, highest y=%.3f, fastest %.3f m/s, sleeping %d/%d\n", frame / 60,
			       double(lowest), double(highest), double(fastest), sleeping, boxes.size());
		else
			printf("t=%.3f s: lowest box y=%.3f, highest y=%.3f, fastest %.3f m/s, sleeping %d/%d\n", frame / 60.0,
			       double(lowest), double(highest), double(fastest), sleeping, boxes.size());
	}
	bool ok = !sank;
	if (pictures.shortened())
		printf("never sank into the ground: %s; layers and sleep not checked (--frames %d is shorter than 480)\n",
		       sank ? "FAILED" : "ok", pictures.frames());
	else
	{
		const bool layersOk = btFabs(highest - 9) < btScalar(0.1);
		const bool allAsleep = sleeping == boxes.size();
		printf("never sank into the ground: %s; five layers (top at %.3f, expected 9): %s; all asleep: %s\n",
		       sank ? "FAILED" : "ok", double(highest), layersOk ? "ok" : "FAILED", allAsleep ? "ok" : "FAILED");
		ok = ok && layersOk && allAsleep;
	}
	for (int b = 0; b < boxes.size(); ++b)
	{
		world.removeRigidBody(boxes[b]);
		delete boxes[b];
		delete motions[b];
	}
	world.removeRigidBody(&ground);
	return pictures.finish(ok ? 0 : 1);
}
