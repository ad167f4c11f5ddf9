// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_VEHICLE_INTERNAL_H
#define CALIBER_VEHICLE_INTERNAL_H

// What the raycast vehicle's files share and Bullet's classes have no place for.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

class btCollisionObject;
class btRaycastVehicle;
class btRigidBody;

namespace caliber
{
/// The chassis whose wheel rays are being cast on this thread (null outside btRaycastVehicle::rayCast).
/// btDefaultVehicleRaycaster reads it to skip the chassis and to use its collision filter; the
/// raycaster interface (Bullet's) has no way to pass it.
const btCollisionObject* currentVehicleChassis();

/// Sets currentVehicleChassis() for its lifetime.
class VehicleChassisScope
{
public:
	explicit VehicleChassisScope(const btCollisionObject* chassis);
	~VehicleChassisScope();
	VehicleChassisScope(const VehicleChassisScope&) = delete;
	VehicleChassisScope& operator=(const VehicleChassisScope&) = delete;

private:
	const btCollisionObject* m_previous;
};

/// Reports message once per vehicle and kind (kind: a bit); later reports of the same kind are dropped.
void warnVehicleOnce(const btRaycastVehicle* vehicle, unsigned kind, const char* message);
/// Where each braked wheel holds on to its ground: the contact point when the brake took hold, in the
/// ground object's frame, so the brake rows can pull a parked car back to where it stopped (drift from
/// forces the rows cannot anticipate: joints on the chassis, a load).
struct VehicleAnchors
{
	btAlignedObjectArray<btVector3> pointInGround;
	btAlignedObjectArray<const btCollisionObject*> ground;  // null: the wheel holds no anchor
};

/// The vehicle's anchors (made empty on first use).
VehicleAnchors& vehicleAnchors(const btRaycastVehicle* vehicle);

/// Forgets the vehicle's Caliber-only state: reported warnings, anchors (its destructor calls it).
void forgetVehicleWarnings(const btRaycastVehicle* vehicle);

/// Velocity of body at world point, or zero for a null body.
btVector3 velocityAtPoint(const btRigidBody* body, const btVector3& worldPoint);

/// Kinds for warnVehicleOnce.
enum VehicleWarning : unsigned
{
	kVehicleNoChassis = 1u,
	kVehicleNoRaycaster = 2u,
	kVehicleChassisNotInWorld = 4u,
	kVehicleChassisNotDynamic = 8u,
	kVehicleBadStep = 16u,
};
}  // namespace caliber

#endif  // CALIBER_VEHICLE_INTERNAL_H
