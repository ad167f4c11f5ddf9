// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// HelloWorld: the Bullet manual's first program, unchanged in substance. A static ground box and a
// dynamic sphere of radius 1 dropped from y = 10; the program steps the world 150 times at 60 Hz and
// prints the sphere's height from its motion state each step. It then checks the physics it printed:
// the sphere came to rest on the ground at its radius (y = 1 within a centimetre), and while it was
// falling freely its height followed the integrator's exact answer y_n = 10 - g h^2 n (n + 1) / 2
// (y lags one substep behind through the motion state's interpolation). Exit 1 when either fails.

#include <stdio.h>

#include "btBulletDynamicsCommon.h"

int main()
{
	btDefaultCollisionConfiguration* collisionConfiguration = new btDefaultCollisionConfiguration();
	btCollisionDispatcher* dispatcher = new btCollisionDispatcher(collisionConfiguration);
	btBroadphaseInterface* overlappingPairCache = new btDbvtBroadphase();
	btSequentialImpulseConstraintSolver* solver = new btSequentialImpulseConstraintSolver;
	btDiscreteDynamicsWorld* dynamicsWorld =
	    new btDiscreteDynamicsWorld(dispatcher, overlappingPairCache, solver, collisionConfiguration);
	dynamicsWorld->setGravity(btVector3(0, -10, 0));

	btAlignedObjectArray<btCollisionShape*> collisionShapes;

	// The ground: a box 100 x 100 x 100 whose top face is y = 0.
	{
		btCollisionShape* groundShape = new btBoxShape(btVector3(btScalar(50.), btScalar(50.), btScalar(50.)));
		collisionShapes.push_back(groundShape);
		btTransform groundTransform;
		groundTransform.setIdentity();
		groundTransform.setOrigin(btVector3(0, -50, 0));
		btScalar mass(0.);
		btVector3 localInertia(0, 0, 0);
		btDefaultMotionState* myMotionState = new btDefaultMotionState(groundTransform);
		btRigidBody::btRigidBodyConstructionInfo rbInfo(mass, myMotionState, groundShape, localInertia);
		btRigidBody* body = new btRigidBody(rbInfo);
		dynamicsWorld->addRigidBody(body);
	}

	// The ball.
	{
		btCollisionShape* colShape = new btSphereShape(btScalar(1.));
		collisionShapes.push_back(colShape);
		btTransform startTransform;
		startTransform.setIdentity();
		btScalar mass(1.f);
		btVector3 localInertia(0, 0, 0);
		colShape->calculateLocalInertia(mass, localInertia);
		startTransform.setOrigin(btVector3(2, 10, 0));
		btDefaultMotionState* myMotionState = new btDefaultMotionState(startTransform);
		btRigidBody::btRigidBodyConstructionInfo rbInfo(mass, myMotionState, colShape, localInertia);
		btRigidBody* body = new btRigidBody(rbInfo);
		dynamicsWorld->addRigidBody(body);
	}

	const btScalar h = btScalar(1.) / btScalar(60.);
	btRigidBody* ball = btRigidBody::upcast(dynamicsWorld->getCollisionObjectArray()[1]);
	btScalar worstFreeFallError = 0;
	for (int i = 0; i < 150; i++)
	{
		dynamicsWorld->stepSimulation(h, 10);

		for (int j = dynamicsWorld->getNumCollisionObjects() - 1; j >= 0; j--)
		{
			btCollisionObject* obj = dynamicsWorld->getCollisionObjectArray()[j];
			btRigidBody* body = btRigidBody::upcast(obj);
			btTransform trans;
			if (body && body->getMotionState())
				body->getMotionState()->getWorldTransform(trans);
			else
				trans = obj->getWorldTransform();
			printf("world pos object %d = %f,%f,%f\n", j, float(trans.getOrigin().getX()),
			       float(trans.getOrigin().getY()), float(trans.getOrigin().getZ()));
		}

		// Free fall lasts until the ball reaches the ground (its bottom at y = 0 after about 1.4 s).
		const int n = i + 1;
		const btScalar simulated = 10 - 10 * h * h * n * (n + 1) / 2;
		if (simulated > btScalar(1.2))
		{
			const btScalar error = btFabs(ball->getCenterOfMassPosition().getY() - simulated);
			if (error > worstFreeFallError) worstFreeFallError = error;
		}
	}

	const btScalar restingY = ball->getCenterOfMassPosition().getY();
	const bool freeFallOk = worstFreeFallError < btScalar(1e-3);
	const bool restOk = btFabs(restingY - 1) < btScalar(0.01);
	printf("free fall: worst deviation from y_n = 10 - g h^2 n(n+1)/2 is %g (limit 1e-3): %s\n",
	       double(worstFreeFallError), freeFallOk ? "ok" : "FAILED");
	printf("resting height %f (radius 1, limit 0.01): %s\n", double(restingY), restOk ? "ok" : "FAILED");

	// Clean up in the reverse order of creation, as the manual does.
	for (int i = dynamicsWorld->getNumCollisionObjects() - 1; i >= 0; i--)
	{
		btCollisionObject* obj = dynamicsWorld->getCollisionObjectArray()[i];
		btRigidBody* body = btRigidBody::upcast(obj);
		if (body && body->getMotionState()) delete body->getMotionState();
		dynamicsWorld->removeCollisionObject(obj);
		delete obj;
	}
	for (int j = 0; j < collisionShapes.size(); j++)
	{
		btCollisionShape* shape = collisionShapes[j];
		collisionShapes[j] = 0;
		delete shape;
	}
	delete dynamicsWorld;
	delete solver;
	delete overlappingPairCache;
	delete dispatcher;
	delete collisionConfiguration;
	collisionShapes.clear();
	return freeFallOk && restOk ? 0 : 1;
}
