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
	btScalar k =
	    bodies.chassis->getInvMass() +
	    measureArm.cross(direction).dot(bodies.chassis->getInvInertiaTensorWorld() * applyArm.cross(direction));
	if (bodies.ground)
		k += bodies.ground->getInvMass() +
		     groundArm.cross(direction).dot(bodies.ground->getInvInertiaTensorWorld() * groundArm.cross(direction));
	// A roll influence near zero with a tall contact arm could make the cross term negative; never let
	// the row's mass become infinite or change sign.
	return btMax(k, bodies.chassis->getInvMass() * btScalar(0.1));
}

// The vehicle's friction arrays (Bullet's private members) and anchors, for the steps below.
struct FrictionState
{
	btAlignedObjectArray<btWheelInfo>& wheels;
	btAlignedObjectArray<btVector3>& forward;  // m_forwardWS: rolling direction, zero when off the ground
	btAlignedObjectArray<btVector3>& side;     // m_axle: along the axle in the ground plane
	btAlignedObjectArray<btScalar>& forwardImpulse;
	btAlignedObjectArray<btScalar>& sideImpulse;
	caliber::VehicleAnchors& anchors;
};

// Clears last step's impulses and finds each grounded wheel's forward and side directions; drops the
// anchors of wheels that no longer brake on the same ground. False when no wheel can grip.
bool findWheelDirections(FrictionState& f)
{
	bool anyContact = false;
	for (int i = 0; i < f.wheels.size(); ++i)
	{
		btWheelInfo& wheel = f.wheels[i];
		f.forwardImpulse[i] = 0;
		f.sideImpulse[i] = 0;
		wheel.m_skidInfo = 1;
		f.forward[i].setValue(0, 0, 0);
		f.side[i].setValue(0, 0, 0);
		if (!wheel.m_raycastInfo.m_isInContact || wheel.m_brake <= 0 ||
		    f.anchors.ground[i] != wheel.m_raycastInfo.m_groundObject)
			f.anchors.ground[i] = 0;
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
		f.forward[i] = forward;
		f.side[i] = side;
		anyContact = true;
	}
	return anyContact;
}

// The chassis state every wheel's rows are measured against in one step.
struct ChassisMotion
{
	btRigidBody* chassis;
	btVector3 up;
	btVector3 centre;
	btVector3 pending;      // velocity change the next substep's accumulated force will give
	btVector3 pendingSpin;  // likewise for the torque
	btScalar timeStep;
};

// One Gauss-Seidel update of wheel i's forward and side rows: the impulses each row wants (engine,
// brake up to its limit, no side slip, pulled back to a held anchor), scaled together into the friction
// circle, and the change since the last sweep applied to the chassis and a movable ground.
void solveWheelFriction(FrictionState& f, int i, const ChassisMotion& c)
{
	btWheelInfo& wheel = f.wheels[i];
	const btScalar timeStep = c.timeStep;
	const btVector3& point = wheel.m_raycastInfo.m_contactPointWS;
	RowBodies bodies;
	bodies.chassis = c.chassis;
	bodies.ground = btRigidBody::upcast(static_cast<btCollisionObject*>(wheel.m_raycastInfo.m_groundObject));
	if (bodies.ground && bodies.ground->getInvMass() <= 0) bodies.ground = 0;
	const btRigidBody* groundForVelocity =
	    btRigidBody::upcast(static_cast<const btCollisionObject*>(wheel.m_raycastInfo.m_groundObject));

	const btVector3 arm = point - c.centre;
	const btVector3 sideArm = arm - c.up * (c.up.dot(arm) * (btScalar(1) - wheel.m_rollInfluence));
	const btVector3 groundArm = bodies.ground ? point - bodies.ground->getCenterOfMassPosition() : btVector3(0, 0, 0);
	const btVector3 relative = c.chassis->getLinearVelocity() + c.pending +
	                           (c.chassis->getAngularVelocity() + c.pendingSpin).cross(arm) -
	                           caliber::velocityAtPoint(groundForVelocity, point);

	const btVector3& forward = f.forward[i];
	const btVector3& side = f.side[i];
	btVector3 pullBack(0, 0, 0);  // velocity that takes a held wheel back to its anchor
	if (f.anchors.ground[i])
		pullBack = (f.anchors.ground[i]->getWorldTransform()(f.anchors.pointInGround[i]) - point) *
		           (kAnchorCorrection / timeStep);
	const btScalar sideWanted =
	    f.sideImpulse[i] - (relative - pullBack).dot(side) / rowInverseMass(bodies, side, arm, sideArm, groundArm);
	const btScalar drive = wheel.m_engineForce * timeStep;
	btScalar forwardWanted = drive;
	if (wheel.m_brake > 0)
	{
		const btScalar braking =
		    f.forwardImpulse[i] - drive -
		    (relative - pullBack).dot(forward) / rowInverseMass(bodies, forward, arm, arm, groundArm);
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

	const btVector3 forwardDelta = forward * (forwardImpulse - f.forwardImpulse[i]);
	const btVector3 sideDelta = side * (sideImpulse - f.sideImpulse[i]);
	f.forwardImpulse[i] = forwardImpulse;
	f.sideImpulse[i] = sideImpulse;
	c.chassis->applyImpulse(forwardDelta, arm);
	c.chassis->applyImpulse(sideDelta, sideArm);
	if (bodies.ground)
	{
		bodies.ground->activate();
		bodies.ground->applyImpulse(-(forwardDelta + sideDelta), groundArm);
	}
}

// A braked wheel that holds takes an anchor where it stands; one that slides or is at its brake's
// limit lets go.
void updateBrakeAnchors(FrictionState& f, btScalar timeStep)
{
	for (int i = 0; i < f.wheels.size(); ++i)
	{
		const btWheelInfo& wheel = f.wheels[i];
		const btScalar braking = btFabs(f.forwardImpulse[i] - wheel.m_engineForce * timeStep);
		const bool holds = wheel.m_raycastInfo.m_isInContact && wheel.m_brake > 0 && wheel.m_skidInfo >= 1 &&
		                   braking < wheel.m_brake * btScalar(0.999) && !f.forward[i].fuzzyZero();
		if (!holds)
		{
			f.anchors.ground[i] = 0;
			continue;
		}
		if (f.anchors.ground[i]) continue;
		const btCollisionObject* ground = static_cast<const btCollisionObject*>(wheel.m_raycastInfo.m_groundObject);
		f.anchors.ground[i] = ground;
		f.anchors.pointInGround[i] = ground->getWorldTransform().invXform(wheel.m_raycastInfo.m_contactPointWS);
	}
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
	FrictionState f = {m_wheelInfo, m_forwardWS, m_axle, m_forwardImpulse, m_sideImpulse, anchors};
	if (!findWheelDirections(f)) return;

	btRigidBody* chassis = m_chassisBody;
	ChassisMotion motion;
	motion.chassis = chassis;
	motion.up = getChassisWorldTransform().getBasis().getColumn(m_indexUpAxis);
	motion.centre = chassis->getCenterOfMassPosition();
	motion.pending = chassis->getTotalForce() * (chassis->getInvMass() * timeStep);
	motion.pendingSpin = chassis->getInvInertiaTensorWorld() * chassis->getTotalTorque() * timeStep;
	motion.timeStep = timeStep;
	for (int sweep = 0; sweep < kFrictionSweeps; ++sweep)
		for (int i = 0; i < wheelCount; ++i)
			if (!m_forwardWS[i].fuzzyZero()) solveWheelFriction(f, i, motion);
	updateBrakeAnchors(f, timeStep);
}
