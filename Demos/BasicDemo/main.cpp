// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// BasicDemo: a 5 x 5 x 5 block of boxes (half extent 1, mass 1, 0.2 gaps between them) dropped onto a
// static ground, headless. Each simulated second the demo prints the lowest and highest box, the
// fastest speed and how many boxes sleep. The block lands, settles into five layers and falls asleep.
// Checks: no box ever sinks into the ground (centre below 0.95, the ground's surface plus its half
// extent minus 5 cm of allowed penetration), the block keeps its five layers (top layer within 10 cm
// of y = 9), and every box sleeps by the end. Exit 1 when a check fails.

#include <stdio.h>

#include "btBulletDynamicsCommon.h"

int main()
{
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
	const int seconds = 8;
	for (int second = 1; second <= seconds; ++second)
	{
		for (int step = 0; step < 60; ++step)
		{
			world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
			for (int b = 0; b < boxes.size(); ++b)
				if (boxes[b]->getCenterOfMassPosition().getY() < btScalar(0.95)) sank = true;
		}
		btScalar lowest = BT_LARGE_FLOAT, highest = -BT_LARGE_FLOAT, fastest = 0;
		int sleeping = 0;
		for (int b = 0; b < boxes.size(); ++b)
		{
			const btScalar y = boxes[b]->getCenterOfMassPosition().getY();
			lowest = btMin(lowest, y);
			highest = btMax(highest, y);
			fastest = btMax(fastest, boxes[b]->getLinearVelocity().length());
			if (boxes[b]->getActivationState() == ISLAND_SLEEPING) ++sleeping;
		}
		printf("t=%d s: lowest box y=%.3f, highest y=%.3f, fastest %.3f m/s, sleeping %d/%d\n", second, double(lowest),
		       double(highest), double(fastest), sleeping, boxes.size());
		if (second == seconds)
		{
			const bool layersOk = btFabs(highest - 9) < btScalar(0.1);
			const bool allAsleep = sleeping == boxes.size();
			printf("never sank into the ground: %s; five layers (top at %.3f, expected 9): %s; all asleep: %s\n",
			       sank ? "FAILED" : "ok", double(highest), layersOk ? "ok" : "FAILED", allAsleep ? "ok" : "FAILED");
			for (int b = 0; b < boxes.size(); ++b)
			{
				world.removeRigidBody(boxes[b]);
				delete boxes[b];
				delete motions[b];
			}
			world.removeRigidBody(&ground);
			return !sank && layersOk && allAsleep ? 0 : 1;
		}
	}
	return 1;
}
