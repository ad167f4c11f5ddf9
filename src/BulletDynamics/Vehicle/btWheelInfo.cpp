// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Vehicle/btWheelInfo.h"

#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "btVehicleInternal.h"

btWheelInfo::btWheelInfo(btWheelInfoConstructionInfo& ci)
    : m_worldTransform(btTransform::getIdentity()),
      m_chassisConnectionPointCS(ci.m_chassisConnectionCS),
      m_wheelDirectionCS(ci.m_wheelDirectionCS),
      m_wheelAxleCS(ci.m_wheelAxleCS),
      m_suspensionRestLength1(ci.m_suspensionRestLength),
      m_maxSuspensionTravelCm(ci.m_maxSuspensionTravelCm),
      m_wheelsRadius(ci.m_wheelRadius),
      m_suspensionStiffness(ci.m_suspensionStiffness),
      m_wheelsDampingCompression(ci.m_wheelsDampingCompression),
      m_wheelsDampingRelaxation(ci.m_wheelsDampingRelaxation),
      m_frictionSlip(ci.m_frictionSlip),
      m_steering(0),
      m_rotation(0),
      m_deltaRotation(0),
      m_rollInfluence(btScalar(0.1)),  // Bullet's default: a tenth of the side force's roll torque
      m_maxSuspensionForce(ci.m_maxSuspensionForce),
      m_engineForce(0),
      m_brake(0),
      m_bIsFrontWheel(ci.m_bIsFrontWheel),
      m_clientInfo(0),
      m_clippedInvContactDotSuspension(1),
      m_suspensionRelativeVelocity(0),
      m_wheelsSuspensionForce(0),
      m_skidInfo(1)
{
	const btVector3 zero(0, 0, 0);
	m_raycastInfo.m_contactNormalWS = zero;
	m_raycastInfo.m_contactPointWS = zero;
	m_raycastInfo.m_suspensionLength = ci.m_suspensionRestLength;
	m_raycastInfo.m_hardPointWS = zero;
	m_raycastInfo.m_wheelDirectionWS = zero;
	m_raycastInfo.m_wheelAxleWS = zero;
	m_raycastInfo.m_isInContact = false;
	m_raycastInfo.m_groundObject = 0;
}

void btWheelInfo::updateWheel(const btRigidBody& chassis, RaycastInfo& raycastInfo)
{
	if (!raycastInfo.m_isInContact)
	{
		m_suspensionRelativeVelocity = 0;
		m_clippedInvContactDotSuspension = 1;
		return;
	}
	// How fast the suspension shortens: the chassis' approach to the ground along the normal, relative
	// to the ground's own motion (a platform or a moving body), turned into suspension length rate.
	const btVector3& normal = raycastInfo.m_contactNormalWS;
	const btScalar normalDotUp = -normal.dot(raycastInfo.m_wheelDirectionWS);
	const btRigidBody* ground =
	    btRigidBody::upcast(static_cast<const btCollisionObject*>(raycastInfo.m_groundObject));
	const btVector3 relative = caliber::velocityAtPoint(&chassis, raycastInfo.m_contactPointWS) -
	                           caliber::velocityAtPoint(ground, raycastInfo.m_contactPointWS);
	// Near-vertical walls would blow the factor up; 10 keeps a grazing contact's spring finite.
	const btScalar kMinNormalDotUp = btScalar(0.1);
	if (normalDotUp <= kMinNormalDotUp)
	{
		m_suspensionRelativeVelocity = 0;
		m_clippedInvContactDotSuspension = btScalar(1) / kMinNormalDotUp;
		return;
	}
	const btScalar inverse = btScalar(1) / normalDotUp;
	m_clippedInvContactDotSuspension = inverse;
	m_suspensionRelativeVelocity = normal.dot(relative) * inverse;
}
