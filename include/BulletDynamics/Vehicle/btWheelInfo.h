// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_WHEEL_INFO_H
#define BT_WHEEL_INFO_H

#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

class btRigidBody;

/// The values a wheel is built from (btRaycastVehicle::addWheel fills one from its arguments and the
/// tuning).
struct btWheelInfoConstructionInfo
{
	/// Where the suspension is attached, in the chassis frame.
	btVector3 m_chassisConnectionCS;
	/// The direction the suspension extends in (down), in the chassis frame.
	btVector3 m_wheelDirectionCS;
	/// The wheel's axle, in the chassis frame.
	btVector3 m_wheelAxleCS;
	/// Suspension length with the spring relaxed.
	btScalar m_suspensionRestLength;
	/// How far, in centimetres, the suspension may compress or extend from its rest length.
	btScalar m_maxSuspensionTravelCm;
	/// Wheel radius.
	btScalar m_wheelRadius;
	/// Spring stiffness per unit chassis mass (force = stiffness * compression * chassis mass).
	btScalar m_suspensionStiffness;
	/// Damping per unit chassis mass while the suspension compresses.
	btScalar m_wheelsDampingCompression;
	/// Damping per unit chassis mass while the suspension extends.
	btScalar m_wheelsDampingRelaxation;
	/// Friction coefficient of the tyre (grip = frictionSlip * suspension force).
	btScalar m_frictionSlip;
	/// Largest force the suspension can push with.
	btScalar m_maxSuspensionForce;
	/// Whether this is a front wheel (information for the user; steering is per wheel).
	bool m_bIsFrontWheel;
};

/// One wheel of a raycast vehicle: its geometry, tuning, controls and what the last update found.
struct btWheelInfo
{
	/// What the wheel's rays found in the last update, in world space.
	struct RaycastInfo
	{
		/// Ground normal at the contact.
		btVector3 m_contactNormalWS;
		/// Contact point on the ground.
		btVector3 m_contactPointWS;
		/// Current suspension length (hard point to wheel centre).
		btScalar m_suspensionLength;
		/// Suspension attachment point.
		btVector3 m_hardPointWS;
		/// Suspension direction (down).
		btVector3 m_wheelDirectionWS;
		/// Axle direction (without steering).
		btVector3 m_wheelAxleWS;
		/// Whether the wheel touches the ground.
		bool m_isInContact;
		/// The btCollisionObject the wheel stands on, or null.
		void* m_groundObject;
	};

	/// Last ray results.
	RaycastInfo m_raycastInfo;
	/// The wheel's world transform (local x: axle; updateWheelTransform writes it).
	btTransform m_worldTransform;
	/// Suspension attachment, chassis frame.
	btVector3 m_chassisConnectionPointCS;
	/// Suspension direction, chassis frame.
	btVector3 m_wheelDirectionCS;
	/// Axle, chassis frame.
	btVector3 m_wheelAxleCS;
	/// Suspension rest length.
	btScalar m_suspensionRestLength1;
	/// Suspension travel either side of the rest length, in centimetres.
	btScalar m_maxSuspensionTravelCm;
	/// The rest length.
	btScalar getSuspensionRestLength() const { return m_suspensionRestLength1; }
	/// Wheel radius.
	btScalar m_wheelsRadius;
	/// Spring stiffness per unit chassis mass.
	btScalar m_suspensionStiffness;
	/// Compression damping per unit chassis mass.
	btScalar m_wheelsDampingCompression;
	/// Extension damping per unit chassis mass.
	btScalar m_wheelsDampingRelaxation;
	/// Tyre friction coefficient.
	btScalar m_frictionSlip;
	/// Steering angle in radians about the suspension axis.
	btScalar m_steering;
	/// Spin angle about the axle in radians.
	btScalar m_rotation;
	/// Spin angle added in the last update.
	btScalar m_deltaRotation;
	/// How much of the side force's roll torque reaches the chassis (0: none, 1: all).
	btScalar m_rollInfluence;
	/// Largest suspension force.
	btScalar m_maxSuspensionForce;
	/// Driving force at the contact (newtons).
	btScalar m_engineForce;
	/// Largest braking impulse per substep (newton seconds), as in Bullet.
	btScalar m_brake;
	/// Whether this is a front wheel.
	bool m_bIsFrontWheel;
	/// Free for the user.
	void* m_clientInfo;

	/// An unset wheel (addWheel builds wheels from construction info).
	btWheelInfo() {}
	/// A wheel at rest length, with no controls applied.
	btWheelInfo(btWheelInfoConstructionInfo& ci);

	/// Recomputes the suspension's relative velocity and the normal factor from raycastInfo and the
	/// chassis' motion (the vehicle calls it after each ray cast).
	void updateWheel(const btRigidBody& chassis, RaycastInfo& raycastInfo);

	/// 1 / (normal . -suspension direction), limited to 10 (steep contacts); 1 off the ground.
	btScalar m_clippedInvContactDotSuspension;
	/// Rate of change of the suspension length along the contact normal (negative: compressing).
	btScalar m_suspensionRelativeVelocity;
	/// Suspension force of the last update (newtons).
	btScalar m_wheelsSuspensionForce;
	/// 1 when the tyre grips, less when it slides (the share of the wanted friction it got).
	btScalar m_skidInfo;
};

#endif  // BT_WHEEL_INFO_H
