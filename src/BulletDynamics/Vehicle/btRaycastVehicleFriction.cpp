// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Tyre friction, driving and braking of the raycast vehicle (docs/actions.md, "Tyre model").
//
// Each wheel on the ground has two rows at its contact: forward (rolling direction) and side (along
// the axle in the ground plane). The side row stops sideways sliding; the forward row carries the
// engine's impulse and, when braking, stops the rolling up to the brake's impulse. Both impulses of a
// wheel share one friction circle of radius frictionSlip * suspension force * step. All wheels are
// solved together by a few Gauss-Seidel sweeps, so the wheels of one axle do not each try to stop the
// whole car (Bullet's per-wheel impulses overshoot and make a braked car jitter at standstill), and
// the circle is applied whatever the side impulse is (Bullet skips the clamp when it is 0 or -0 and
// then lets the engine push with no limit).
//
// The rows aim at the velocity the chassis will have when the next substep moves it: the forces
// already accumulated for the step (gravity, the user's forces) are added before the velocity is
// measured. Actions run after the bodies moved, so a row that aimed at zero now would let gravity
// creep a parked car down a slope by g sin(slope) h^2 every substep.
//
// What the rows cannot anticipate (the impulses of joints on the chassis, a load on a fork) is
// corrected at the position level: a braked wheel that holds (neither sliding nor at its brake's
// limit) keeps an anchor on the ground where it took hold, and its rows pull the contact back to it.

#include "BulletDynamics/Vehicle/btRaycastVehicle.h"
#include "btVehicleInternal.h"

namespace
{
const int kFrictionSweeps = 10;
// Share of a held wheel's drift from its anchor removed per substep.
const btScalar kAnchorCorrection = btScalar(0.2);

struct RowBodies
{
	btRigidBody* chassis;
	btRigidBody* ground;  // null when the ground cannot move
};

// Impulse needed per unit of velocity change along direction, measured at measurePoint and applied
// at applyPoint (they differ for the side row, whose roll torque is scaled by roll influence).
btScalar rowInverseMass(const RowBodies& bodies, const btVector3& direction, const btVector3& measureArm,
                        const btVector3& applyArm, const btVector3& groundArm)
{
	btScalar k = bodies.chassis->getInvMass() +
	             measureArm.cross(direction).dot(bodies.chassis->getInvInertiaTensorWorld() * applyArm.cross(direction));
	if (bodies.ground)
		k += bodies.ground->getInvMass() +
		     groundArm.cross(direction).dot(bodies.ground->getInvInertiaTensorWorld() * groundArm.cross(direction));
	// A roll influence near zero with a tall contact arm could make the cross term negative; never let
	// the row's mass become infinite or change sign.
	return btMax(k, bodies.chassis->getInvMass() * btScalar(0.1));
}
}  // namespace

void btRaycastVehicle::updateFriction(btScalar timeStep)
{
	const int wheelCount = getNumWheels();
	if (wheelCount == 0 || !m_chassisBody || m_chassisBody->getInvMass() <= 0) return;
	caliber::VehicleAnchors& anchors = caliber::vehicleAnchors(this);
	anchors.pointInGround.resize(wheelCount, btVector3(0, 0, 0));
	anchors.ground.resize(wheelCount, 0);
	m_forwardWS.resize(wheelCount);
	m_axle.resize(wheelCount);
	m_forwardImpulse.resize(wheelCount);
	m_sideImpulse.resize(wheelCount);

	btRigidBody* chassis = m_chassisBody;
	const btVector3 chassisUp = getChassisWorldTransform().getBasis().getColumn(m_indexUpAxis);
	bool anyContact = false;
	for (int i = 0; i < wheelCount; ++i)
	{
		btWheelInfo& wheel = m_wheelInfo[i];
		m_forwardImpulse[i] = 0;
		m_sideImpulse[i] = 0;
		wheel.m_skidInfo = 1;
		m_forwardWS[i].setValue(0, 0, 0);
		m_axle[i].setValue(0, 0, 0);
		if (!wheel.m_raycastInfo.m_isInContact || wheel.m_brake <= 0 ||
		    anchors.ground[i] != wheel.m_raycastInfo.m_groundObject)
			anchors.ground[i] = 0;
		if (!wheel.m_raycastInfo.m_isInContact) continue;
		const btVector3& normal = wheel.m_raycastInfo.m_contactNormalWS;
		btVector3 down = wheel.m_raycastInfo.m_wheelDirectionWS;
		down.safeNormalize();
		const btVector3 axle = wheel.m_raycastInfo.m_wheelAxleWS.rotate(-down, wheel.m_steering);
		btVector3 forward = normal.cross(axle);
		if (forward.fuzzyZero()) continue;  // axle along the normal: the wheel lies on its side
		forward.normalize();
		btVector3 side = forward.cross(normal);
		side.normalize();
		m_forwardWS[i] = forward;
		m_axle[i] = side;
		anyContact = true;
	}
	if (!anyContact) return;

	// Velocity change the next substep's accumulated forces will give, so the rows aim past it.
	const btVector3 chassisPending = chassis->getTotalForce() * (chassis->getInvMass() * timeStep);
	const btVector3 chassisPendingSpin = chassis->getInvInertiaTensorWorld() * chassis->getTotalTorque() * timeStep;
	const btVector3 centre = chassis->getCenterOfMassPosition();

	for (int sweep = 0; sweep < kFrictionSweeps; ++sweep)
	{
		for (int i = 0; i < wheelCount; ++i)
		{
			btWheelInfo& wheel = m_wheelInfo[i];
			if (m_forwardWS[i].fuzzyZero()) continue;
			const btVector3& point = wheel.m_raycastInfo.m_contactPointWS;
			RowBodies bodies;
			bodies.chassis = chassis;
			bodies.ground = btRigidBody::upcast(static_cast<btCollisionObject*>(wheel.m_raycastInfo.m_groundObject));
			if (bodies.ground && bodies.ground->getInvMass() <= 0) bodies.ground = 0;
			const btRigidBody* groundForVelocity =
			    btRigidBody::upcast(static_cast<const btCollisionObject*>(wheel.m_raycastInfo.m_groundObject));

			const btVector3 arm = point - centre;
			const btVector3 sideArm = arm - chassisUp * (chassisUp.dot(arm) * (btScalar(1) - wheel.m_rollInfluence));
			const btVector3 groundArm = bodies.ground ? point - bodies.ground->getCenterOfMassPosition() : btVector3(0, 0, 0);
			const btVector3 relative = chassis->getLinearVelocity() + chassisPending +
			                           (chassis->getAngularVelocity() + chassisPendingSpin).cross(arm) -
			                           caliber::velocityAtPoint(groundForVelocity, point);

			const btVector3& forward = m_forwardWS[i];
			const btVector3& side = m_axle[i];
			btVector3 pullBack(0, 0, 0);  // velocity that takes a held wheel back to its anchor
			if (anchors.ground[i])
				pullBack = (anchors.ground[i]->getWorldTransform()(anchors.pointInGround[i]) - point) *
				           (kAnchorCorrection / timeStep);
			const btScalar sideWanted = m_sideImpulse[i] - (relative - pullBack).dot(side) /
			                                                   rowInverseMass(bodies, side, arm, sideArm, groundArm);
			const btScalar drive = wheel.m_engineForce * timeStep;
			btScalar forwardWanted = drive;
			if (wheel.m_brake > 0)
			{
				const btScalar braking = m_forwardImpulse[i] - drive - (relative - pullBack).dot(forward) /
				                                                           rowInverseMass(bodies, forward, arm, arm, groundArm);
				forwardWanted = drive + btMax(-wheel.m_brake, btMin(braking, wheel.m_brake));
			}
			// The friction circle, applied to both rows whatever their signs.
			const btScalar limit = btMax(btScalar(0), wheel.m_frictionSlip * wheel.m_wheelsSuspensionForce * timeStep);
			const btScalar wanted = btSqrt(forwardWanted * forwardWanted + sideWanted * sideWanted);
			btScalar scale = 1;
			if (wanted > limit) scale = wanted > 0 ? limit / wanted : btScalar(0);
			wheel.m_skidInfo = scale;
			const btScalar forwardImpulse = forwardWanted * scale;
			const btScalar sideImpulse = sideWanted * scale;

			const btVector3 forwardDelta = forward * (forwardImpulse - m_forwardImpulse[i]);
			const btVector3 sideDelta = side * (sideImpulse - m_sideImpulse[i]);
			m_forwardImpulse[i] = forwardImpulse;
			m_sideImpulse[i] = sideImpulse;
			chassis->applyImpulse(forwardDelta, arm);
			chassis->applyImpulse(sideDelta, sideArm);
			if (bodies.ground)
			{
				bodies.ground->activate();
				bodies.ground->applyImpulse(-(forwardDelta + sideDelta), groundArm);
			}
		}
	}

	// A braked wheel that holds takes an anchor where it stands; one that slides or is at its brake's
	// limit lets go.
	for (int i = 0; i < wheelCount; ++i)
	{
		const btWheelInfo& wheel = m_wheelInfo[i];
		const btScalar braking = btFabs(m_forwardImpulse[i] - wheel.m_engineForce * timeStep);
		const bool holds = wheel.m_raycastInfo.m_isInContact && wheel.m_brake > 0 && wheel.m_skidInfo >= 1 &&
		                   braking < wheel.m_brake * btScalar(0.999) && !m_forwardWS[i].fuzzyZero();
		if (!holds)
		{
			anchors.ground[i] = 0;
			continue;
		}
		if (anchors.ground[i]) continue;
		const btCollisionObject* ground = static_cast<const btCollisionObject*>(wheel.m_raycastInfo.m_groundObject);
		anchors.ground[i] = ground;
		anchors.pointInGround[i] = ground->getWorldTransform().invXform(wheel.m_raycastInfo.m_contactPointWS);
	}
}
