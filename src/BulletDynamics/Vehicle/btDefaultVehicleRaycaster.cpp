// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletDynamics/Dynamics/btDynamicsWorld.h"
#include "BulletDynamics/Vehicle/btRaycastVehicle.h"
#include "LinearMath/btWarningHook.h"
#include "btVehicleInternal.h"

namespace
{
// The closest hit that the chassis would collide with: its own shape and objects without contact
// response (triggers, ghosts) are skipped, and the chassis' filter group and mask apply as they do
// to its contacts (Bullet's raycaster ignores them, so wheels stood on objects the chassis passes).
struct WheelRayCallback : public btCollisionWorld::ClosestRayResultCallback
{
	WheelRayCallback(const btVector3& from, const btVector3& to, const btCollisionObject* chassis)
	    : ClosestRayResultCallback(from, to), m_chassis(chassis)
	{
		if (chassis && chassis->getBroadphaseHandle())
		{
			m_collisionFilterGroup = chassis->getBroadphaseHandle()->m_collisionFilterGroup;
			m_collisionFilterMask = chassis->getBroadphaseHandle()->m_collisionFilterMask;
		}
	}

	bool needsCollision(btBroadphaseProxy* proxy) const override
	{
		const btCollisionObject* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
		if (object == m_chassis) return false;
		if (object && !object->hasContactResponse()) return false;
		return ClosestRayResultCallback::needsCollision(proxy);
	}

	const btCollisionObject* m_chassis;
};
}  // namespace

void* btDefaultVehicleRaycaster::castRay(const btVector3& from, const btVector3& to,
                                         btVehicleRaycasterResult& result)
{
	btAssert(m_dynamicsWorld && "btDefaultVehicleRaycaster: null world");
	if (!m_dynamicsWorld)
	{
		btReportWarning("Caliber: btDefaultVehicleRaycaster: null world, no hit\n");
		return 0;
	}
	WheelRayCallback callback(from, to, caliber::currentVehicleChassis());
	m_dynamicsWorld->rayTest(from, to, callback);
	if (!callback.hasHit()) return 0;
	result.m_hitPointInWorld = callback.m_hitPointWorld;
	result.m_hitNormalInWorld = callback.m_hitNormalWorld;
	result.m_hitNormalInWorld.safeNormalize();
	result.m_distFraction = callback.m_closestHitFraction;
	return const_cast<btCollisionObject*>(callback.m_collisionObject);
}
