// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_VEHICLE_TEST_UTIL_H
#define CALIBER_TESTS_VEHICLE_TEST_UTIL_H

// A four-wheeled car on the test world's ground (y up, z forward), with the numbers the tests'
// analytic values are computed from.

#include <memory>

#include "BulletDynamics/Vehicle/btRaycastVehicle.h"
#include "../Dynamics/DynamicsWorldTestUtil.h"

namespace caliber_test
{
struct CarSpec
{
	btScalar mass = 800;
	btScalar stiffness = 20;  // per unit chassis mass (Bullet's convention)
	btScalar frictionSlip = btScalar(0.8);
	btScalar radius = btScalar(0.4);
	btScalar restLength = btScalar(0.6);
	btScalar halfWheelbase = btScalar(1.3);
	btScalar halfTrack = btScalar(0.8);
	btScalar hardPointY = btScalar(-0.1);  // below the chassis centre, inside the box
	btScalar startHeight = btScalar(1.0);  // chassis centre above the ground
};

class TestCar
{
public:
	TestCar(TestWorld& world, const CarSpec& spec = CarSpec(),
	        const btTransform& start = btTransform(btQuaternion::getIdentity(), btVector3(0, 1, 0)))
	    : m_spec(spec)
	{
		btTransform pose = start;
		m_chassis = world.addBody(world.shape<btBoxShape>(btVector3(btScalar(0.9), btScalar(0.3), btScalar(2.0))),
		                          spec.mass, pose);
		m_chassis->setActivationState(DISABLE_DEACTIVATION);
		m_raycaster.reset(new btDefaultVehicleRaycaster(world.world()));
		btRaycastVehicle::btVehicleTuning tuning;
		tuning.m_suspensionStiffness = spec.stiffness;
		// Close to critical damping of the car's bounce (2 sqrt(n k) per unit mass, shared by n wheels).
		tuning.m_suspensionCompression = btScalar(2) * btSqrt(btScalar(4) * spec.stiffness) / btScalar(4);
		tuning.m_suspensionDamping = tuning.m_suspensionCompression;
		tuning.m_frictionSlip = spec.frictionSlip;
		m_vehicle.reset(new btRaycastVehicle(tuning, m_chassis, m_raycaster.get()));
		m_vehicle->setCoordinateSystem(0, 1, 2);
		const btVector3 down(0, -1, 0);
		const btVector3 axle(-1, 0, 0);
		for (int i = 0; i < 4; ++i)
		{
			const btScalar x = (i & 1) ? -spec.halfTrack : spec.halfTrack;
			const btScalar z = (i < 2) ? spec.halfWheelbase : -spec.halfWheelbase;
			m_vehicle->addWheel(btVector3(x, spec.hardPointY, z), down, axle, spec.restLength, spec.radius, tuning,
			                    i < 2);
		}
		world.world()->addAction(m_vehicle.get());
		m_world = world.world();
	}

	~TestCar()
	{
		if (m_vehicle) m_world->removeAction(m_vehicle.get());
	}

	btRaycastVehicle* vehicle() { return m_vehicle.get(); }
	btRigidBody* chassis() { return m_chassis; }
	const CarSpec& spec() const { return m_spec; }

	void engine(btScalar forcePerWheel)
	{
		for (int i = 0; i < 4; ++i) m_vehicle->applyEngineForce(forcePerWheel, i);
	}
	void brake(btScalar impulsePerWheel)
	{
		for (int i = 0; i < 4; ++i) m_vehicle->setBrake(impulsePerWheel, i);
	}
	void steer(btScalar angle)
	{
		m_vehicle->setSteeringValue(angle, 0);
		m_vehicle->setSteeringValue(angle, 1);
	}
	/// Speed along the chassis' forward axis (m/s).
	btScalar forwardSpeed() const
	{
		return m_chassis->getLinearVelocity().dot(m_chassis->getWorldTransform().getBasis().getColumn(2));
	}
	/// Centre of the rear axle, in world space.
	btVector3 rearAxleCentre() const
	{
		return m_chassis->getWorldTransform()(btVector3(0, m_spec.hardPointY, -m_spec.halfWheelbase));
	}

private:
	CarSpec m_spec;
	btDiscreteDynamicsWorld* m_world = 0;
	btRigidBody* m_chassis = 0;
	std::unique_ptr<btDefaultVehicleRaycaster> m_raycaster;
	std::unique_ptr<btRaycastVehicle> m_vehicle;
};
}  // namespace caliber_test

#endif  // CALIBER_TESTS_VEHICLE_TEST_UTIL_H
