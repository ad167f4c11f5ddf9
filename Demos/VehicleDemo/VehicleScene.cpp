// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "VehicleScene.h"

#include <math.h>

namespace vehicle_demo
{
namespace
{
const int kSamples = 129;  // height field samples per side, 1 m apart

// The height field's samples, centred on the origin.
std::vector<float> sampleTerrain()
{
	std::vector<float> heights(kSamples * kSamples);
	for (int j = 0; j < kSamples; ++j)
		for (int i = 0; i < kSamples; ++i)
			heights[size_t(j * kSamples + i)] =
			    float(terrain(btScalar(i - kSamples / 2), btScalar(j - kSamples / 2)));
	return heights;
}

btVector3 chassisInertia(const btBoxShape& shape)
{
	btVector3 inertia;
	shape.calculateLocalInertia(kMass, inertia);
	return inertia;
}

btRaycastVehicle::btVehicleTuning carTuning()
{
	btRaycastVehicle::btVehicleTuning tuning;
	tuning.m_suspensionStiffness = kStiffness;
	tuning.m_suspensionCompression = btScalar(2.2);  // near critical damping of the car's bounce
	tuning.m_suspensionDamping = btScalar(2.2);
	tuning.m_frictionSlip = kFriction;
	return tuning;
}
}  // namespace

btScalar terrain(btScalar x, btScalar z)
{
	(void)x;
	if (z > -35 && z < -20) return btScalar(0.04) * btScalar(0.5 - 0.5 * cos(2 * M_PI * (z + 35) / 3));
	if (z >= -10 && z < 0) return (z + 10) / 10;
	if (z >= 0 && z < 8) return 1;
	if (z >= 8 && z < 18) return 1 - (z - 8) / 10;
	return 0;
}

// The members are built in the order the demo always built them (the world's state depends on it).
Scene::Scene()
    : m_heights(sampleTerrain()),
      m_terrainShape(kSamples, kSamples, m_heights.data(), btScalar(0), btScalar(1), 1, false),
      m_ground(btRigidBody::btRigidBodyConstructionInfo(0, 0, &m_terrainShape)),
      m_chassisShape(btVector3(btScalar(0.9), btScalar(0.3), btScalar(2.0))),
      m_chassisMotion(btTransform(btQuaternion::getIdentity(), btVector3(0, 1, -50))),
      m_chassis(btRigidBody::btRigidBodyConstructionInfo(kMass, &m_chassisMotion, &m_chassisShape,
                                                         chassisInertia(m_chassisShape))),
      m_tuning(carTuning()),
      m_car(m_tuning, &m_chassis, &m_raycaster)
{
	m_world.setGravity(btVector3(0, -kGravity, 0));
	m_ground.getWorldTransform().setOrigin(btVector3(0, btScalar(0.5), 0));
	m_world.addRigidBody(&m_ground);
	m_chassis.setActivationState(DISABLE_DEACTIVATION);
	m_world.addRigidBody(&m_chassis);
	m_car.setCoordinateSystem(0, 1, 2);  // x right, y up, z forward
	for (int i = 0; i < 4; ++i)
		m_car.addWheel(
		    btVector3((i & 1) ? -kHalfTrack : kHalfTrack, btScalar(-0.1), i < 2 ? kHalfWheelbase : -kHalfWheelbase),
		    btVector3(0, -1, 0), btVector3(-1, 0, 0), kRestLength, btScalar(0.4), m_tuning, i < 2);
	m_world.addAction(&m_car);
}

Scene::~Scene()
{
	m_world.removeAction(&m_car);
	m_world.removeRigidBody(&m_chassis);
	m_world.removeRigidBody(&m_ground);
}

void Scene::drive(btScalar throttle, btScalar steering, bool brake)
{
	const btScalar force = 1500 * btMax(btScalar(-1), btMin(btScalar(1), throttle));
	m_car.applyEngineForce(force, 2);
	m_car.applyEngineForce(force, 3);
	const btScalar angle = btScalar(0.4) * btMax(btScalar(-1), btMin(btScalar(1), steering));
	m_car.setSteeringValue(angle, 0);
	m_car.setSteeringValue(angle, 1);
	for (int i = 0; i < 4; ++i) m_car.setBrake(brake ? 200 : 0, i);
}
}  // namespace vehicle_demo
