// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_VEHICLE_SCENE_H
#define CALIBER_DEMOS_VEHICLE_SCENE_H
// VehicleDemo's scene: a raycast vehicle (800 kg, four wheels of radius 0.4 m, rear-wheel drive) on a
// 128 m height field with a patch of bumps, a ramp up to a 1 m plateau and down again. Used by
// VehicleDemo, which scripts and measures it, and by the demo browser, where the keys drive it.

#include <vector>

#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "DemoWorld.h"
#include "btBulletDynamicsCommon.h"

namespace vehicle_demo
{
const btScalar kGravity = 10;
const btScalar kMass = 800;
const btScalar kStiffness = 20;  // per unit chassis mass, Bullet's convention
const btScalar kFriction = 1;
const btScalar kHalfWheelbase = btScalar(1.3), kHalfTrack = btScalar(0.8), kRestLength = btScalar(0.6);
const btScalar kWheelWidth = btScalar(0.3);

/// Terrain height at (x, z): bumps 4 cm high for z in [-35, -20], a ramp from z = -10 up to 1 m at
/// z = 0, a plateau to z = 8 and a ramp down to z = 18.
btScalar terrain(btScalar x, btScalar z);

/// The world, the terrain and the car (at rest over z = -50, facing +z).
class Scene
{
public:
	Scene();
	~Scene();
	Scene(const Scene&) = delete;
	Scene& operator=(const Scene&) = delete;
	btDiscreteDynamicsWorld& world() { return m_world; }
	btRigidBody& chassis() { return m_chassis; }
	btRaycastVehicle& car() { return m_car; }
	/// A driver's controls: throttle in [-1, 1] (negative: reverse), steering in [-1, 1] (positive:
	/// left), brake on or off.
	void drive(btScalar throttle, btScalar steering, bool brake);

private:
	caliber::demo::DemoWorld m_demoWorld;  // the demos' usual world
	btDiscreteDynamicsWorld& m_world{m_demoWorld.world()};
	std::vector<float> m_heights;
	btHeightfieldTerrainShape m_terrainShape;
	btRigidBody m_ground;
	btBoxShape m_chassisShape;
	btDefaultMotionState m_chassisMotion;
	btRigidBody m_chassis;
	btRaycastVehicle::btVehicleTuning m_tuning;
	btDefaultVehicleRaycaster m_raycaster{&m_world};
	btRaycastVehicle m_car;
};
}  // namespace vehicle_demo

#endif
