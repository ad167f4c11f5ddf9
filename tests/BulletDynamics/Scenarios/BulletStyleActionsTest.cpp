// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Code written the way Bullet's users write it (the vehicle and character demos' idioms, a raycaster
// of their own, a controller subclass) compiles unchanged and runs: the actions' API is Bullet's.

#include <gtest/gtest.h>

#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletDynamics/Character/btKinematicCharacterController.h"
#include "btBulletDynamicsCommon.h"

namespace
{
// A user's raycaster, as games write them to filter what wheels stand on.
struct CountingRaycaster : public btVehicleRaycaster
{
	explicit CountingRaycaster(btDynamicsWorld* world) : m_inner(world) {}
	void* castRay(const btVector3& from, const btVector3& to, btVehicleRaycasterResult& result) override
	{
		++m_rays;
		return m_inner.castRay(from, to, result);
	}
	btDefaultVehicleRaycaster m_inner;
	int m_rays = 0;
};

// A user's controller that counts its steps (Bullet's virtuals are the extension points).
class CountingController : public btKinematicCharacterController
{
public:
	CountingController(btPairCachingGhostObject* ghost, btConvexShape* shape, btScalar stepHeight)
	    : btKinematicCharacterController(ghost, shape, stepHeight, btVector3(0, 1, 0))
	{
	}
	void playerStep(btCollisionWorld* world, btScalar dt) override
	{
		++m_steps;
		btKinematicCharacterController::playerStep(world, dt);
	}
	bool onGroundAsBullet() const { return m_wasOnGround; }  // Bullet's protected member
	int m_steps = 0;
};
}  // namespace

TEST(BulletStyleActions, VehicleDemoIdiomsCompileAndDrive)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, -10, 0));
	btBoxShape groundShape(btVector3(100, 1, 100));
	btRigidBody ground(0, 0, &groundShape);
	ground.getWorldTransform().setOrigin(btVector3(0, -1, 0));
	world.addRigidBody(&ground);

	btBoxShape chassisShape(btVector3(1.f, 0.5f, 2.f));
	btVector3 inertia(0, 0, 0);
	chassisShape.calculateLocalInertia(800.f, inertia);
	btDefaultMotionState motion(btTransform(btQuaternion::getIdentity(), btVector3(0, 1.5f, 0)));
	btRigidBody carChassis(800.f, &motion, &chassisShape, inertia);
	world.addRigidBody(&carChassis);

	btRaycastVehicle::btVehicleTuning m_tuning;
	CountingRaycaster raycaster(&world);
	btRaycastVehicle* m_vehicle = new btRaycastVehicle(m_tuning, &carChassis, &raycaster);
	carChassis.setActivationState(DISABLE_DEACTIVATION);
	world.addVehicle(m_vehicle);
	int rightIndex = 0, upIndex = 1, forwardIndex = 2;
	m_vehicle->setCoordinateSystem(rightIndex, upIndex, forwardIndex);
	btVector3 wheelDirectionCS0(0, -1, 0), wheelAxleCS(-1, 0, 0);
	float wheelRadius = 0.5f, suspensionRestLength = 0.6f, connectionHeight = 1.2f - 1.f;
	bool isFrontWheel = true;
	btVector3 connectionPointCS0(1.f, connectionHeight, 1.6f);
	m_vehicle->addWheel(connectionPointCS0, wheelDirectionCS0, wheelAxleCS, suspensionRestLength, wheelRadius, m_tuning,
	                    isFrontWheel);
	connectionPointCS0 = btVector3(-1.f, connectionHeight, 1.6f);
	m_vehicle->addWheel(connectionPointCS0, wheelDirectionCS0, wheelAxleCS, suspensionRestLength, wheelRadius, m_tuning,
	                    isFrontWheel);
	isFrontWheel = false;
	connectionPointCS0 = btVector3(-1.f, connectionHeight, -1.6f);
	m_vehicle->addWheel(connectionPointCS0, wheelDirectionCS0, wheelAxleCS, suspensionRestLength, wheelRadius, m_tuning,
	                    isFrontWheel);
	connectionPointCS0 = btVector3(1.f, connectionHeight, -1.6f);
	m_vehicle->addWheel(connectionPointCS0, wheelDirectionCS0, wheelAxleCS, suspensionRestLength, wheelRadius, m_tuning,
	                    isFrontWheel);
	for (int i = 0; i < m_vehicle->getNumWheels(); i++)
	{
		btWheelInfo& wheel = m_vehicle->getWheelInfo(i);
		wheel.m_suspensionStiffness = 20.f;
		wheel.m_wheelsDampingRelaxation = 2.3f;
		wheel.m_wheelsDampingCompression = 4.4f;
		wheel.m_frictionSlip = 1000;
		wheel.m_rollInfluence = 0.1f;
	}
	for (int frame = 0; frame < 180; ++frame)
	{
		int wheelIndex = 2;
		m_vehicle->applyEngineForce(1000.f, wheelIndex);
		m_vehicle->setBrake(0.f, wheelIndex);
		wheelIndex = 3;
		m_vehicle->applyEngineForce(1000.f, wheelIndex);
		m_vehicle->setBrake(0.f, wheelIndex);
		wheelIndex = 0;
		m_vehicle->setSteeringValue(0.f, wheelIndex);
		wheelIndex = 1;
		m_vehicle->setSteeringValue(0.f, wheelIndex);
		world.stepSimulation(1.f / 60.f);
		btScalar m[16];
		for (int i = 0; i < m_vehicle->getNumWheels(); i++)
		{
			m_vehicle->updateWheelTransform(i, true);
			m_vehicle->getWheelInfo(i).m_worldTransform.getOpenGLMatrix(m);
		}
	}
	// 2000 N on 800 kg for 3 s, less the time the car needed to settle: about 6 m/s.
	EXPECT_GT(m_vehicle->getCurrentSpeedKmHour(), 15.f);
	EXPECT_GT(raycaster.m_rays, 0);
	world.removeVehicle(m_vehicle);
	delete m_vehicle;
	world.removeRigidBody(&carChassis);
	world.removeRigidBody(&ground);
}

TEST(BulletStyleActions, CharacterDemoIdiomsCompileAndWalk)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btAxisSweep3 sweepBP(btVector3(-100, -100, -100), btVector3(100, 100, 100));
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &sweepBP, &solver, &configuration);
	world.setGravity(btVector3(0, -10, 0));
	btBoxShape groundShape(btVector3(50, 1, 50));
	btRigidBody ground(0, 0, &groundShape);
	ground.getWorldTransform().setOrigin(btVector3(0, -1, 0));
	world.addRigidBody(&ground);

	btTransform startTransform;
	startTransform.setIdentity();
	startTransform.setOrigin(btVector3(0.0, 2.0, 0.0));
	btPairCachingGhostObject* m_ghostObject = new btPairCachingGhostObject();
	m_ghostObject->setWorldTransform(startTransform);
	btGhostPairCallback* ghostPairCallback = new btGhostPairCallback();
	sweepBP.getOverlappingPairCache()->setInternalGhostPairCallback(ghostPairCallback);
	btScalar characterHeight = 1.75, characterWidth = 1.75;
	btConvexShape* capsule = new btCapsuleShape(characterWidth / 4, characterHeight / 2);
	m_ghostObject->setCollisionShape(capsule);
	m_ghostObject->setCollisionFlags(btCollisionObject::CF_CHARACTER_OBJECT);
	btScalar stepHeight = btScalar(0.35);
	CountingController* m_character = new CountingController(m_ghostObject, capsule, stepHeight);
	world.addCollisionObject(m_ghostObject, btBroadphaseProxy::CharacterFilter,
	                         btBroadphaseProxy::StaticFilter | btBroadphaseProxy::DefaultFilter);
	world.addAction(m_character);
	world.getBroadphase()->getOverlappingPairCache()->cleanProxyFromPairs(m_ghostObject->getBroadphaseHandle(),
	                                                                      world.getDispatcher());
	m_character->reset(&world);
	m_character->warp(btVector3(0, 2, 0));

	for (int frame = 0; frame < 120; ++frame)
	{
		btTransform xform = m_ghostObject->getWorldTransform();
		btVector3 forwardDir = xform.getBasis()[2];
		forwardDir.normalize();
		btScalar walkVelocity = btScalar(1.1) * 4.0;
		btScalar walkSpeed = walkVelocity * btScalar(1. / 60.);
		m_character->setWalkDirection(forwardDir * walkSpeed);
		world.stepSimulation(1.f / 60.f);
	}
	EXPECT_EQ(m_character->m_steps, 120);
	EXPECT_TRUE(m_character->onGround());
	EXPECT_TRUE(m_character->onGroundAsBullet());
	EXPECT_NEAR(m_ghostObject->getWorldTransform().getOrigin().z(), btScalar(4.4 * 2), btScalar(0.2));

	world.removeAction(m_character);
	world.removeCollisionObject(m_ghostObject);
	delete m_character;
	delete m_ghostObject;
	delete capsule;
	world.removeRigidBody(&ground);
	sweepBP.getOverlappingPairCache()->setInternalGhostPairCallback(0);
	delete ghostPairCallback;
}
