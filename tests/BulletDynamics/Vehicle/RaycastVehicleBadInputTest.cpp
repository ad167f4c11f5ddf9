// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Misuse of the raycast vehicle (docs/bad-input.md): each case asserts in builds with asserts and is
// reported and ignored without them; the world keeps stepping with finite values.

#include <gtest/gtest.h>

#include <limits>

#include "VehicleTestUtil.h"

using caliber_test::CarSpec;
using caliber_test::TestCar;
using caliber_test::TestWorld;
using caliber_test::WarningCounter;

namespace
{
const btScalar kNaN = std::numeric_limits<btScalar>::quiet_NaN();
const btScalar kStep = btScalar(1. / 60.);

bool finiteChassis(const btRigidBody* body)
{
	const btVector3& p = body->getCenterOfMassPosition();
	const btVector3& v = body->getLinearVelocity();
	return btIsFinite(p.x()) && btIsFinite(p.y()) && btIsFinite(p.z()) && btIsFinite(v.x()) && btIsFinite(v.y()) &&
	       btIsFinite(v.z());
}
}  // namespace

TEST(RaycastVehicleBadInput, NonFiniteEngineForceSteeringAndBrakeAreRejected)
{
	WarningCounter warnings;
	TestWorld w;
	w.addGround();
	TestCar car(w);
	w.run(60, kStep);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(car.vehicle()->applyEngineForce(kNaN, 0), "non-finite force");
	EXPECT_DEATH(car.vehicle()->setSteeringValue(kNaN, 0), "non-finite steering");
	EXPECT_DEATH(car.vehicle()->setBrake(btScalar(-1), 0), "negative or non-finite brake");
#else
	car.vehicle()->applyEngineForce(kNaN, 0);
	car.vehicle()->setSteeringValue(kNaN, 0);
	car.vehicle()->setBrake(kNaN, 0);
	car.vehicle()->setBrake(btScalar(-1), 0);
	EXPECT_EQ(warnings.count(), 4);
#endif
	EXPECT_EQ(car.vehicle()->getWheelInfo(0).m_engineForce, 0);
	EXPECT_EQ(car.vehicle()->getSteeringValue(0), 0);
	EXPECT_EQ(car.vehicle()->getWheelInfo(0).m_brake, 0);
	w.run(60, kStep);
	EXPECT_TRUE(finiteChassis(car.chassis()));
}

TEST(RaycastVehicleBadInput, WheelIndexOutOfRangeIsRejected)
{
	WarningCounter warnings;
	TestWorld w;
	w.addGround();
	TestCar car(w);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(car.vehicle()->applyEngineForce(100, 4), "wheel index out of range");
	EXPECT_DEATH(car.vehicle()->getWheelInfo(-1), "wheel index out of range");
	EXPECT_DEATH(car.vehicle()->setBrake(1, 99), "wheel index out of range");
#else
	car.vehicle()->applyEngineForce(100, 4);
	car.vehicle()->setSteeringValue(btScalar(0.1), -1);
	car.vehicle()->setBrake(1, 99);
	// A placeholder wheel that belongs to no vehicle: reading it is harmless, writing to it is lost.
	btWheelInfo& placeholder = car.vehicle()->getWheelInfo(7);
	placeholder.m_engineForce = 1e6;
	EXPECT_EQ(car.vehicle()->getSteeringValue(12), 0);
	EXPECT_EQ(warnings.count(), 5);
#endif
	for (int i = 0; i < 4; ++i) EXPECT_EQ(car.vehicle()->getWheelInfo(i).m_engineForce, 0);
	w.run(60, kStep);
	EXPECT_TRUE(finiteChassis(car.chassis()));
	EXPECT_NEAR(car.chassis()->getLinearVelocity().z(), 0, btScalar(1e-3));
}

TEST(RaycastVehicleBadInput, NullChassisOrRaycasterIsReported)
{
	WarningCounter warnings;
	TestWorld w;
	w.addGround();
	btRaycastVehicle::btVehicleTuning tuning;
	btDefaultVehicleRaycaster raycaster(w.world());
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btRaycastVehicle(tuning, 0, &raycaster), "null chassis");
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(1, btScalar(0.3), 2)), 800, btVector3(0, 1, 0));
	EXPECT_DEATH(btRaycastVehicle(tuning, body, 0), "null raycaster");
#else
	{
		btRaycastVehicle noChassis(tuning, 0, &raycaster);
		noChassis.addWheel(btVector3(0, 0, 0), btVector3(0, -1, 0), btVector3(-1, 0, 0), 1, 1, tuning, true);
		w.world()->addAction(&noChassis);
		w.run(10, kStep);
		w.world()->removeAction(&noChassis);
		EXPECT_EQ(noChassis.getNumWheels(), 1);
	}
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(1, btScalar(0.3), 2)), 800, btVector3(0, 1, 0));
	btRaycastVehicle noRaycaster(tuning, body, 0);
	noRaycaster.setCoordinateSystem(0, 1, 2);
	noRaycaster.addWheel(btVector3(0, 0, 0), btVector3(0, -1, 0), btVector3(-1, 0, 0), 1, btScalar(0.5), tuning, true);
	w.world()->addAction(&noRaycaster);
	w.run(60, kStep);
	w.world()->removeAction(&noRaycaster);
	EXPECT_FALSE(noRaycaster.getWheelInfo(0).m_raycastInfo.m_isInContact);
	EXPECT_TRUE(finiteChassis(body));
	// Two reports from the constructors, one from each vehicle's first update.
	EXPECT_EQ(warnings.count(), 4);
#endif
}

TEST(RaycastVehicleBadInput, VehicleWithoutWheelsLeavesTheChassisToGravity)
{
	// Not an error: a vehicle with no wheels adds nothing, so its chassis falls freely (y = y0 - g t^2/2
	// for the world's symplectic Euler: y0 - g h^2 n (n + 1) / 2).
	WarningCounter warnings;
	TestWorld w;
	btRaycastVehicle::btVehicleTuning tuning;
	btDefaultVehicleRaycaster raycaster(w.world());
	btRigidBody* body = w.addBody(w.shape<btBoxShape>(btVector3(1, btScalar(0.3), 2)), 800, btVector3(0, 10, 0));
	btRaycastVehicle vehicle(tuning, body, &raycaster);
	w.world()->addAction(&vehicle);
	w.run(30, kStep);
	w.world()->removeAction(&vehicle);
	EXPECT_NEAR(body->getCenterOfMassPosition().y(), 10 - 10 * kStep * kStep * 30 * 31 / 2, btScalar(1e-4));
	EXPECT_EQ(vehicle.getCurrentSpeedKmHour(), btScalar(3.6) * body->getLinearVelocity().length() *
	                                               (body->getLinearVelocity().dot(vehicle.getForwardVector()) < 0 ? -1 : 1));
	EXPECT_EQ(warnings.count(), 0);
}

TEST(RaycastVehicleBadInput, ChassisRemovedWhileTheVehicleIsStillAnActionIsReportedAndWaits)
{
	WarningCounter warnings;
	TestWorld w;
	w.addGround();
	TestCar car(w);
	w.run(60, kStep);
	const btVector3 parked = car.chassis()->getCenterOfMassPosition();
	w.world()->removeRigidBody(car.chassis());
	car.engine(1000);
	w.run(60, kStep);
	EXPECT_EQ(warnings.count(), 1) << "reported once, not every substep";
	EXPECT_EQ(car.chassis()->getCenterOfMassPosition(), parked) << "the vehicle does not drive a removed chassis";
	// Added back, it drives again.
	w.world()->addRigidBody(car.chassis());
	w.run(60, kStep);
	EXPECT_GT(car.forwardSpeed(), btScalar(0.5));
	EXPECT_TRUE(finiteChassis(car.chassis()));
}

TEST(RaycastVehicleBadInput, DefaultRaycasterHonoursTheChassisCollisionFilter)
{
	// A slab 20 cm high under the car in collision group 64. While the chassis' mask leaves out group 64
	// the chassis would pass through the slab, so its wheels do too (Bullet's raycaster stands on it).
	TestWorld w;
	w.addGround();
	btRigidBody* slab = new btRigidBody(0, 0, w.shape<btBoxShape>(btVector3(5, btScalar(0.1), 5)));
	slab->getWorldTransform().setOrigin(btVector3(0, btScalar(0.1), 0));
	w.world()->addRigidBody(slab, 64, btBroadphaseProxy::AllFilter);
	TestCar car(w);
	car.chassis()->getBroadphaseHandle()->m_collisionFilterMask &= ~64;
	w.run(300, kStep);
	const btScalar filteredHeight = car.chassis()->getCenterOfMassPosition().y();
	car.chassis()->getBroadphaseHandle()->m_collisionFilterMask |= 64;
	w.run(300, kStep);
	const btScalar standingHeight = car.chassis()->getCenterOfMassPosition().y();
	EXPECT_NEAR(standingHeight - filteredHeight, btScalar(0.2), btScalar(1e-3));
	w.world()->removeRigidBody(slab);
	delete slab;
}
