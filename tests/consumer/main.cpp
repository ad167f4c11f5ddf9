// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// A user's program built against an installed Caliber, with the includes a Bullet program has.
// Usage: consumer [float|double]  -- with an argument, exits 2 unless btScalar is that type.

#include "btBulletDynamicsCommon.h"
#include "btBulletSoftBodyCommon.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcherMt.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorldMt.h"
#include "LinearMath/btThreads.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#include <stdio.h>
#include <string.h>

// A sphere dropped on a box for 30 steps, in the plain world or in Bullet 2.89's multithreaded world
// (set up as Bullet's examples do); returns the sphere's final height.
static btScalar dropSphere(bool multithreaded)
{
	btDefaultCollisionConstructionInfo info;
	info.m_defaultMaxPersistentManifoldPoolSize = 1000;
	btDefaultCollisionConfiguration config(info);
	btCollisionDispatcher plainDispatcher(&config);
	btCollisionDispatcherMt dispatcherMt(&config, 40);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver plainSolver;
	btConstraintSolverPoolMt pool(4);
	btSequentialImpulseConstraintSolverMt solverMt;
	btDiscreteDynamicsWorld plainWorld(&plainDispatcher, &broadphase, &plainSolver, &config);
	btDiscreteDynamicsWorldMt worldMt(&dispatcherMt, &broadphase, &pool, &solverMt, &config);
	btDiscreteDynamicsWorld& world = multithreaded ? worldMt : plainWorld;
	btBoxShape groundShape(btVector3(10, 1, 10));
	btSphereShape sphereShape(btScalar(0.5));
	btDefaultMotionState groundMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
	btDefaultMotionState sphereMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, 2, 0)));
	btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, &groundMotion, &groundShape));
	btVector3 inertia(0, 0, 0);
	sphereShape.calculateLocalInertia(1, inertia);
	btRigidBody sphere(btRigidBody::btRigidBodyConstructionInfo(1, &sphereMotion, &sphereShape, inertia));
	world.addRigidBody(&ground);
	world.addRigidBody(&sphere);
	for (int i = 0; i < 30; ++i) world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	const btScalar height = sphere.getWorldTransform().getOrigin().y();
	world.removeRigidBody(&sphere);
	world.removeRigidBody(&ground);
	return height;
}

// A cloth dropped on a static box in the soft-rigid world for 60 steps (the BulletSoftBody layer);
// returns its lowest node's height, which rests on the box's top face at y = 0.
static btScalar dropCloth()
{
	btSoftBodyRigidBodyCollisionConfiguration config;
	btCollisionDispatcher dispatcher(&config);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
	btBoxShape groundShape(btVector3(10, 1, 10));
	btDefaultMotionState groundMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, -1, 0)));
	btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, &groundMotion, &groundShape));
	world.addRigidBody(&ground);
	btSoftBody* cloth = btSoftBodyHelpers::CreatePatch(world.getWorldInfo(), btVector3(-1, 1, -1), btVector3(1, 1, -1),
	                                                   btVector3(-1, 1, 1), btVector3(1, 1, 1), 8, 8, 0, true);
	cloth->setTotalMass(1);
	world.addSoftBody(cloth);
	for (int i = 0; i < 60; ++i) world.stepSimulation(btScalar(1) / 60, 1, btScalar(1) / 60);
	btScalar lowest = cloth->m_nodes[0].m_x.y();
	for (int i = 0; i < cloth->m_nodes.size(); ++i) lowest = btMin(lowest, cloth->m_nodes[i].m_x.y());
	world.removeSoftBody(cloth);
	delete cloth;
	world.removeRigidBody(&ground);
	return lowest;
}

int main(int argc, char** argv)
{
	const char* precision = btIsDoublePrecision() ? "double" : "float";
	printf("Caliber consumer: Bullet API %d, btScalar is %s (%d bytes)\n", btGetVersion(), precision,
	       int(sizeof(btScalar)));
	if (argc > 1 && strcmp(argv[1], precision) != 0)
	{
		printf("error: expected btScalar to be %s\n", argv[1]);
		return 2;
	}

	// A rigid transform, a point through it and back.
	btTransform bodyToWorld;
	bodyToWorld.setIdentity();
	bodyToWorld.setRotation(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI));
	bodyToWorld.setOrigin(btVector3(1, 2, 3));
	const btVector3 local(1, 0, 0);
	const btVector3 world = bodyToWorld * local;
	const btVector3 back = bodyToWorld.inverse() * world;
	printf("(1, 0, 0) in the body is (%.3f, %.3f, %.3f) in the world\n", double(world.x()), double(world.y()),
	       double(world.z()));

	// A library call (aligned allocation) through the container every Bullet program uses.
	btAlignedObjectArray<btVector3> points;
	for (int i = 0; i < 100; ++i) points.push_back(btVector3(btScalar(i), btScalar(2 * i), btScalar(-i)));
	btVector3 sum(0, 0, 0);
	for (int i = 0; i < points.size(); ++i) sum += points[i];
	printf("sum of %d points: (%.0f, %.0f, %.0f)\n", points.size(), double(sum.x()), double(sum.y()), double(sum.z()));

	// The multithreaded world on every scheduler this library has gives the plain world's bits.
	const btScalar plainHeight = dropSphere(false);
	btITaskScheduler* pool = btCreateDefaultTaskScheduler();
	btITaskScheduler* schedulers[] = {btGetSequentialTaskScheduler(), pool, btGetOpenMPTaskScheduler(),
	                                  btGetTBBTaskScheduler()};
	bool sameBits = true;
	for (btITaskScheduler* scheduler : schedulers)
	{
		if (!scheduler) continue;
		btSetTaskScheduler(scheduler);
		scheduler->setNumThreads(2);
		const btScalar height = dropSphere(true);
		printf("multithreaded world, %s scheduler, %d threads: %s\n", scheduler->getName(), scheduler->getNumThreads(),
		       height == plainHeight ? "same bits" : "DIFFERENT");
		sameBits = sameBits && height == plainHeight;
	}
	btSetTaskScheduler(0);
	delete pool;

	const btScalar clothLow = dropCloth();
	printf("cloth dropped on a box rests at y = %.3f\n", double(clothLow));

	const bool ok = sameBits && btFabs(clothLow) < btScalar(1e-3) && (back - local).length() < btScalar(1e-5) &&
	                (world - btVector3(1, 3, 3)).length() < btScalar(1e-5) && sum == btVector3(4950, 9900, -4950);
	printf("%s\n", ok ? "consumer OK" : "consumer FAILED");
	return ok ? 0 : 1;
}
