// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "btVehicleInternal.h"

#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btSideTable.h"
#include "LinearMath/btWarningHook.h"

namespace caliber
{
namespace
{
thread_local const btCollisionObject* t_currentChassis = 0;

struct VehicleWarnings
{
	unsigned reported = 0;
};
}  // namespace

const btCollisionObject* currentVehicleChassis() { return t_currentChassis; }

VehicleChassisScope::VehicleChassisScope(const btCollisionObject* chassis) : m_previous(t_currentChassis)
{
	t_currentChassis = chassis;
}

VehicleChassisScope::~VehicleChassisScope() { t_currentChassis = m_previous; }

void warnVehicleOnce(const btRaycastVehicle* vehicle, unsigned kind, const char* message)
{
	// Rare path (bad input), so the locked side table costs nothing in a healthy step.
	VehicleWarnings& state = sideTable<VehicleWarnings>().acquire(vehicle);
	if (state.reported & kind) return;
	state.reported |= kind;
	btReportWarning(message);
}

VehicleAnchors& vehicleAnchors(const btRaycastVehicle* vehicle) { return sideTable<VehicleAnchors>().acquire(vehicle); }

void forgetVehicleWarnings(const btRaycastVehicle* vehicle)
{
	sideTable<VehicleWarnings>().release(vehicle);
	sideTable<VehicleAnchors>().release(vehicle);
}

btVector3 velocityAtPoint(const btRigidBody* body, const btVector3& worldPoint)
{
	if (!body) return btVector3(0, 0, 0);
	return body->getVelocityInLocalPoint(worldPoint - body->getCenterOfMassPosition());
}
}  // namespace caliber
