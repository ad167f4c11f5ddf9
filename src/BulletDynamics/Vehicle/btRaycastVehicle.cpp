// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The raycast vehicle: controls, wheel transforms, the wheels' rays and the suspension. Tyre friction
// is in btRaycastVehicleFriction.cpp; the model is described in docs/actions.md.

#include "BulletDynamics/Vehicle/btRaycastVehicle.h"

#include "LinearMath/btIDebugDraw.h"
#include "LinearMath/btMotionState.h"
#include "LinearMath/btWarningHook.h"
#include "btVehicleInternal.h"

namespace
{
// A wheel is sampled by rays at these offsets along its forward direction, in wheel radii, sorted: a
// kerb or a plank under the front of the tyre lifts the wheel as soon as it touches the tyre's circle,
// not only once it reaches the centre ray (Bullet's single ray lets wheels sink into such obstacles).
const btScalar kRayOffsets[] = {btScalar(-0.95), btScalar(-0.75), btScalar(-0.5), btScalar(-0.25), btScalar(0),
                                btScalar(0.25),  btScalar(0.5),   btScalar(0.75), btScalar(0.95)};
const int kRayCount = int(sizeof(kRayOffsets) / sizeof(kRayOffsets[0]));
const int kCentreRay = kRayCount / 2;
// Where two neighbouring rays see different surfaces (an edge between them), the edge is found by this
// many bisections, so a box corner between rays is located to 1/32 of their spacing.
const int kEdgeBisections = 5;
// Two hits lie on one plane when the second is within this distance of the first one's plane.
const btScalar kSamePlaneTolerance = btScalar(1e-3);

// Wheel spin decays by this factor per update while the wheel is in the air (as in Bullet).
const btScalar kAirSpinDecay = btScalar(0.99);

bool wheelIndexValid(const btRaycastVehicle& vehicle, int index, const char* what)
{
	const bool valid = index >= 0 && index < vehicle.getNumWheels();
	btAssert(valid && "btRaycastVehicle: wheel index out of range");
	if (!valid)
	{
		btReportWarning(what);
	}
	return valid;
}

// What getWheelInfo and getWheelTransformWS hand out for a bad index in builds without asserts:
// a wheel that belongs to no vehicle (writes to it are lost). One per thread, reset on each use.
btWheelInfo& placeholderWheel()
{
	thread_local btWheelInfoConstructionInfo info;
	thread_local btWheelInfo wheel;
	info.m_chassisConnectionCS.setValue(0, 0, 0);
	info.m_wheelDirectionCS.setValue(0, -1, 0);
	info.m_wheelAxleCS.setValue(-1, 0, 0);
	info.m_suspensionRestLength = 0;
	info.m_maxSuspensionTravelCm = 0;
	info.m_wheelRadius = 0;
	info.m_suspensionStiffness = 0;
	info.m_wheelsDampingCompression = 0;
	info.m_wheelsDampingRelaxation = 0;
	info.m_frictionSlip = 0;
	info.m_maxSuspensionForce = 0;
	info.m_bIsFrontWheel = false;
	wheel = btWheelInfo(info);
	return wheel;
}

// A wheel whose geometry the rays cannot use never touches the ground.
bool wheelGeometryUsable(const btWheelInfo& wheel)
{
	return btIsFinite(wheel.m_wheelsRadius) && wheel.m_wheelsRadius > 0 &&
	       btIsFinite(wheel.m_suspensionRestLength1) && wheel.m_suspensionRestLength1 >= 0 &&
	       caliber::isFinite(wheel.m_chassisConnectionPointCS) && caliber::isFinite(wheel.m_wheelDirectionCS) &&
	       caliber::isFinite(wheel.m_wheelAxleCS) && !wheel.m_wheelDirectionCS.fuzzyZero() && !wheel.m_wheelAxleCS.fuzzyZero();
}
}  // namespace

btRaycastVehicle::btRaycastVehicle(const btVehicleTuning& tuning, btRigidBody* chassis, btVehicleRaycaster* raycaster)
    : m_userConstraintType(-1),
      m_userConstraintId(-1),
      m_vehicleRaycaster(raycaster),
      m_pitchControl(0),
      m_steeringValue(0),
      m_currentVehicleSpeedKmHour(0),
      m_chassisBody(chassis),
      m_indexRightAxis(0),
      m_indexUpAxis(2),
      m_indexForwardAxis(1)
{
	btAssert(chassis && "btRaycastVehicle: null chassis");
	btAssert(raycaster && "btRaycastVehicle: null raycaster");
	if (!chassis) btReportWarning("Caliber: btRaycastVehicle: null chassis; the vehicle will do nothing\n");
	if (!raycaster) btReportWarning("Caliber: btRaycastVehicle: null raycaster; no wheel will touch the ground\n");
	defaultInit(tuning);
}

void btRaycastVehicle::defaultInit(const btVehicleTuning& tuning)
{
	(void)tuning;  // tunings are per wheel (addWheel)
	m_currentVehicleSpeedKmHour = 0;
	m_steeringValue = 0;
}

btRaycastVehicle::~btRaycastVehicle() { caliber::forgetVehicleWarnings(this); }

btWheelInfo& btRaycastVehicle::addWheel(const btVector3& connectionPointCS, const btVector3& wheelDirectionCS0,
                                        const btVector3& wheelAxleCS, btScalar suspensionRestLength,
                                        btScalar wheelRadius, const btVehicleTuning& tuning, bool isFrontWheel)
{
	btWheelInfoConstructionInfo ci;
	ci.m_chassisConnectionCS = connectionPointCS;
	ci.m_wheelDirectionCS = wheelDirectionCS0;
	ci.m_wheelAxleCS = wheelAxleCS;
	ci.m_suspensionRestLength = suspensionRestLength;
	ci.m_wheelRadius = wheelRadius;
	ci.m_suspensionStiffness = tuning.m_suspensionStiffness;
	ci.m_wheelsDampingCompression = tuning.m_suspensionCompression;
	ci.m_wheelsDampingRelaxation = tuning.m_suspensionDamping;
	ci.m_frictionSlip = tuning.m_frictionSlip;
	ci.m_bIsFrontWheel = isFrontWheel;
	ci.m_maxSuspensionTravelCm = tuning.m_maxSuspensionTravelCm;
	ci.m_maxSuspensionForce = tuning.m_maxSuspensionForce;

	m_wheelInfo.push_back(btWheelInfo(ci));
	btWheelInfo& wheel = m_wheelInfo[m_wheelInfo.size() - 1];
	const bool usable = wheelGeometryUsable(wheel);
	btAssert(usable && "btRaycastVehicle::addWheel: bad wheel geometry");
	if (!usable)
		btReportWarning(
		    "Caliber: btRaycastVehicle::addWheel: non-finite or non-positive radius, negative rest length or zero "
		    "direction/axle; the wheel is kept but never touches the ground\n");
	if (m_chassisBody)
	{
		updateWheelTransformsWS(wheel, false);
		updateWheelTransform(getNumWheels() - 1, false);
	}
	return wheel;
}

const btTransform& btRaycastVehicle::getWheelTransformWS(int wheelIndex) const
{
	if (!wheelIndexValid(*this, wheelIndex, "Caliber: btRaycastVehicle::getWheelTransformWS: bad wheel index\n"))
		return btTransform::getIdentity();
	return m_wheelInfo[wheelIndex].m_worldTransform;
}

const btWheelInfo& btRaycastVehicle::getWheelInfo(int index) const
{
	if (!wheelIndexValid(*this, index, "Caliber: btRaycastVehicle::getWheelInfo: bad wheel index\n"))
		return placeholderWheel();
	return m_wheelInfo[index];
}

btWheelInfo& btRaycastVehicle::getWheelInfo(int index)
{
	if (!wheelIndexValid(*this, index, "Caliber: btRaycastVehicle::getWheelInfo: bad wheel index\n"))
		return placeholderWheel();
	return m_wheelInfo[index];
}

btScalar btRaycastVehicle::getSteeringValue(int wheel) const
{
	if (!wheelIndexValid(*this, wheel, "Caliber: btRaycastVehicle::getSteeringValue: bad wheel index\n")) return 0;
	return m_wheelInfo[wheel].m_steering;
}

void btRaycastVehicle::setSteeringValue(btScalar steering, int wheel)
{
	if (!wheelIndexValid(*this, wheel, "Caliber: btRaycastVehicle::setSteeringValue: bad wheel index, ignored\n"))
		return;
	btAssert(btIsFinite(steering) && "btRaycastVehicle::setSteeringValue: non-finite steering");
	if (!btIsFinite(steering))
	{
		btReportWarning("Caliber: btRaycastVehicle::setSteeringValue: non-finite steering ignored\n");
		return;
	}
	m_wheelInfo[wheel].m_steering = steering;
	m_steeringValue = steering;
}

void btRaycastVehicle::applyEngineForce(btScalar force, int wheel)
{
	if (!wheelIndexValid(*this, wheel, "Caliber: btRaycastVehicle::applyEngineForce: bad wheel index, ignored\n"))
		return;
	btAssert(btIsFinite(force) && "btRaycastVehicle::applyEngineForce: non-finite force");
	if (!btIsFinite(force))
	{
		btReportWarning("Caliber: btRaycastVehicle::applyEngineForce: non-finite force ignored\n");
		return;
	}
	m_wheelInfo[wheel].m_engineForce = force;
}

void btRaycastVehicle::setBrake(btScalar brake, int wheelIndex)
{
	if (!wheelIndexValid(*this, wheelIndex, "Caliber: btRaycastVehicle::setBrake: bad wheel index, ignored\n"))
		return;
	const bool valid = btIsFinite(brake) && brake >= 0;
	btAssert(valid && "btRaycastVehicle::setBrake: negative or non-finite brake");
	if (!valid)
	{
		btReportWarning("Caliber: btRaycastVehicle::setBrake: negative or non-finite brake ignored\n");
		return;
	}
	m_wheelInfo[wheelIndex].m_brake = brake;
}

void btRaycastVehicle::setCoordinateSystem(int rightIndex, int upIndex, int forwardIndex)
{
	const bool inRange = rightIndex >= 0 && rightIndex < 3 && upIndex >= 0 && upIndex < 3 && forwardIndex >= 0 &&
	                     forwardIndex < 3;
	const bool permutation = inRange && rightIndex != upIndex && upIndex != forwardIndex && rightIndex != forwardIndex;
	btAssert(permutation && "btRaycastVehicle::setCoordinateSystem: not a permutation of 0, 1, 2");
	if (!permutation)
	{
		btReportWarning("Caliber: btRaycastVehicle::setCoordinateSystem: not a permutation of 0, 1, 2; ignored\n");
		return;
	}
	m_indexRightAxis = rightIndex;
	m_indexUpAxis = upIndex;
	m_indexForwardAxis = forwardIndex;
}

const btTransform& btRaycastVehicle::getChassisWorldTransform() const
{
	if (!m_chassisBody) return btTransform::getIdentity();
	return m_chassisBody->getCenterOfMassTransform();
}

btVector3 btRaycastVehicle::getForwardVector() const
{
	return getChassisWorldTransform().getBasis().getColumn(m_indexForwardAxis);
}

void btRaycastVehicle::updateWheelTransformsWS(btWheelInfo& wheel, bool interpolatedTransform)
{
	btTransform chassisTransform = getChassisWorldTransform();
	if (interpolatedTransform && m_chassisBody && m_chassisBody->getMotionState())
		m_chassisBody->getMotionState()->getWorldTransform(chassisTransform);
	btWheelInfo::RaycastInfo& info = wheel.m_raycastInfo;
	info.m_hardPointWS = chassisTransform(wheel.m_chassisConnectionPointCS);
	info.m_wheelDirectionWS = chassisTransform.getBasis() * wheel.m_wheelDirectionCS;
	info.m_wheelAxleWS = chassisTransform.getBasis() * wheel.m_wheelAxleCS;
}

void btRaycastVehicle::updateWheelTransform(int wheelIndex, bool interpolatedTransform)
{
	if (!wheelIndexValid(*this, wheelIndex, "Caliber: btRaycastVehicle::updateWheelTransform: bad wheel index\n"))
		return;
	btWheelInfo& wheel = m_wheelInfo[wheelIndex];
	updateWheelTransformsWS(wheel, interpolatedTransform);
	if (!wheelGeometryUsable(wheel)) return;
	const btWheelInfo::RaycastInfo& info = wheel.m_raycastInfo;
	// The wheel's frame before steering and spin: x along the axle, y forward, z up.
	btVector3 up = -info.m_wheelDirectionWS;
	up.safeNormalize();
	btVector3 forward = up.cross(info.m_wheelAxleWS);
	forward.safeNormalize();
	const btVector3 axle = forward.cross(up);
	const btMatrix3x3 unturned(axle.x(), forward.x(), up.x(), axle.y(), forward.y(), up.y(), axle.z(), forward.z(),
	                           up.z());
	const btMatrix3x3 steer(btQuaternion(up, wheel.m_steering));
	// Rolling forward turns the wheel about -axle (right-hand rule about the axle pointing left).
	const btMatrix3x3 spin(btQuaternion(axle, -wheel.m_rotation));
	wheel.m_worldTransform.setBasis(steer * spin * unturned);
	wheel.m_worldTransform.setOrigin(info.m_hardPointWS + info.m_wheelDirectionWS * info.m_suspensionLength);
}

void btRaycastVehicle::resetSuspension()
{
	for (int i = 0; i < getNumWheels(); ++i)
	{
		btWheelInfo& wheel = m_wheelInfo[i];
		wheel.m_raycastInfo.m_suspensionLength = wheel.getSuspensionRestLength();
		wheel.m_suspensionRelativeVelocity = 0;
		wheel.m_raycastInfo.m_contactNormalWS = -wheel.m_raycastInfo.m_wheelDirectionWS;
		wheel.m_raycastInfo.m_isInContact = false;
		wheel.m_raycastInfo.m_groundObject = 0;
		wheel.m_clippedInvContactDotSuspension = 1;
		wheel.m_wheelsSuspensionForce = 0;
	}
}

btScalar btRaycastVehicle::rayCast(btWheelInfo& wheel)
{
	btWheelInfo::RaycastInfo& info = wheel.m_raycastInfo;
	info.m_isInContact = false;
	info.m_groundObject = 0;
	info.m_suspensionLength = wheel.getSuspensionRestLength();
	if (!m_vehicleRaycaster || !m_chassisBody || !wheelGeometryUsable(wheel))
	{
		wheel.m_suspensionRelativeVelocity = 0;
		wheel.m_clippedInvContactDotSuspension = 1;
		return btScalar(-1);
	}
	updateWheelTransformsWS(wheel, false);

	btVector3 down = info.m_wheelDirectionWS;
	down.safeNormalize();
	// Rays fan out along the steered wheel's forward direction, in the wheel's plane.
	const btVector3 axle = info.m_wheelAxleWS.rotate(-down, wheel.m_steering);
	btVector3 forward = (-down).cross(axle);
	forward.safeNormalize();

	const btScalar radius = wheel.m_wheelsRadius;
	const btScalar restLength = wheel.getSuspensionRestLength();
	caliber::VehicleChassisScope scope(m_chassisBody);
	btScalar bestLength = BT_LARGE_FLOAT;
	btScalar bestDepth = btScalar(-1);

	struct Sample
	{
		btScalar offset;
		btScalar depth;  // along the ray from the hard point's level
		btVector3 normal;
		bool hit;
	};
	// Casts one ray at offset (metres along forward); a hit proposes the suspension length at which
	// the tyre's circle touches the hit point, and the shortest proposal wins.
	auto cast = [&](btScalar offset) {
		Sample sample;
		sample.offset = offset;
		sample.hit = false;
		sample.depth = 0;
		// Depth of the tyre's circle below the centre at this offset.
		const btScalar rim = btSqrt(btMax(btScalar(0), radius * radius - offset * offset));
		const btScalar rayLength = restLength + rim;
		const btVector3 from = info.m_hardPointWS + forward * offset;
		btVehicleRaycaster::btVehicleRaycasterResult hit;
		void* object = m_vehicleRaycaster->castRay(from, from + down * rayLength, hit);
		if (!object || !(hit.m_distFraction >= 0) || !caliber::isFinite(hit.m_hitNormalInWorld)) return sample;
		sample.hit = true;
		sample.depth = hit.m_distFraction * rayLength;
		sample.normal = hit.m_hitNormalInWorld;
		const btScalar length = sample.depth - rim;
		// The first ray cast (the centre) wins ties, so a flat road gives the same contact every update.
		if (length < bestLength - btScalar(1e-5) * radius)
		{
			bestLength = length;
			bestDepth = sample.depth;
			info.m_isInContact = true;
			info.m_groundObject = object;
			info.m_contactPointWS = hit.m_hitPointInWorld;
			info.m_contactNormalWS = hit.m_hitNormalInWorld;
		}
		return sample;
	};
	// Whether something other than one plane lies between two samples (an edge, a step, a gap).
	auto edgeBetween = [&](const Sample& a, const Sample& b) {
		if (a.hit != b.hit) return true;
		if (!a.hit) return false;
		const btScalar along = a.normal.dot(down);
		if (btFabs(along) < btScalar(1e-3)) return true;
		const btScalar predicted = a.depth - (b.offset - a.offset) * a.normal.dot(forward) / along;
		return btFabs(b.depth - predicted) > kSamePlaneTolerance;
	};

	Sample samples[kRayCount];
	samples[kCentreRay] = cast(0);
	for (int k = 0; k < kRayCount; ++k)
		if (k != kCentreRay) samples[k] = cast(kRayOffsets[k] * radius);
	for (int k = 0; k + 1 < kRayCount; ++k)
	{
		Sample low = samples[k], high = samples[k + 1];
		if (!edgeBetween(low, high)) continue;
		// The edge matters only if the higher of the two surfaces, reaching in to the point of the
		// interval nearest the centre, would lift the wheel above what the rays already found.
		const btScalar higher = (low.hit && high.hit) ? btMin(low.depth, high.depth) : (low.hit ? low.depth : high.depth);
		const btScalar nearest =
		    (low.offset <= 0 && high.offset >= 0) ? btScalar(0) : btMin(btFabs(low.offset), btFabs(high.offset));
		if (higher - btSqrt(btMax(btScalar(0), radius * radius - nearest * nearest)) >= bestLength) continue;
		for (int i = 0; i < kEdgeBisections; ++i)
		{
			const Sample middle = cast((low.offset + high.offset) / 2);
			if (edgeBetween(low, middle))
				high = middle;
			else
				low = middle;
		}
	}
	if (!info.m_isInContact)
	{
		info.m_contactNormalWS = -down;
		info.m_contactPointWS = info.m_hardPointWS + down * (restLength + radius);
		wheel.m_suspensionRelativeVelocity = 0;
		wheel.m_clippedInvContactDotSuspension = 1;
		return btScalar(-1);
	}
	const btScalar travel = wheel.m_maxSuspensionTravelCm * btScalar(0.01);
	info.m_suspensionLength = btMax(bestLength, restLength - travel);
	wheel.updateWheel(*m_chassisBody, info);
	return bestDepth;
}

void btRaycastVehicle::updateSuspension(btScalar deltaTime)
{
	(void)deltaTime;
	if (!m_chassisBody || m_chassisBody->getInvMass() <= 0) return;
	const btScalar chassisMass = btScalar(1) / m_chassisBody->getInvMass();
	for (int i = 0; i < getNumWheels(); ++i)
	{
		btWheelInfo& wheel = m_wheelInfo[i];
		if (!wheel.m_raycastInfo.m_isInContact)
		{
			wheel.m_wheelsSuspensionForce = 0;
			continue;
		}
		// Bullet's convention, kept so that tunings carry over: stiffness and damping are per unit
		// chassis mass, so the force is (k x - c v) m.
		const btScalar compression = wheel.getSuspensionRestLength() - wheel.m_raycastInfo.m_suspensionLength;
		btScalar forcePerMass = wheel.m_suspensionStiffness * compression * wheel.m_clippedInvContactDotSuspension;
		const btScalar rate = wheel.m_suspensionRelativeVelocity;
		const btScalar damping = rate < 0 ? wheel.m_wheelsDampingCompression : wheel.m_wheelsDampingRelaxation;
		forcePerMass -= damping * rate;
		btScalar force = forcePerMass * chassisMass;
		// A suspension only pushes; it never pulls the chassis down to the ground.
		force = btMax(btScalar(0), btMin(force, btMax(btScalar(0), wheel.m_maxSuspensionForce)));
		wheel.m_wheelsSuspensionForce = btIsFinite(force) ? force : btScalar(0);
	}
}

void btRaycastVehicle::updateVehicle(btScalar step)
{
	if (!m_chassisBody)
	{
		caliber::warnVehicleOnce(this, caliber::kVehicleNoChassis,
		                         "Caliber: btRaycastVehicle: null chassis; the vehicle does nothing\n");
		return;
	}
	if (!(step > 0) || !btIsFinite(step))
	{
		caliber::warnVehicleOnce(this, caliber::kVehicleBadStep,
		                         "Caliber: btRaycastVehicle::updateVehicle: non-positive or non-finite step ignored\n");
		return;
	}
	for (int i = 0; i < getNumWheels(); ++i) updateWheelTransform(i, false);
	const btVector3 velocity = m_chassisBody->getLinearVelocity();
	m_currentVehicleSpeedKmHour = btScalar(3.6) * velocity.length();
	if (getForwardVector().dot(velocity) < 0) m_currentVehicleSpeedKmHour = -m_currentVehicleSpeedKmHour;

	// A chassis that left the world (removeRigidBody while the vehicle is still an action) or that
	// cannot move has nothing to be driven; the vehicle waits until it is back.
	if (!m_chassisBody->getBroadphaseHandle())
	{
		caliber::warnVehicleOnce(
		    this, caliber::kVehicleChassisNotInWorld,
		    "Caliber: btRaycastVehicle: the chassis is not in a world (removed while the vehicle is an action); "
		    "the vehicle does nothing until it is added again\n");
		return;
	}
	if (m_chassisBody->getInvMass() <= 0)
	{
		caliber::warnVehicleOnce(this, caliber::kVehicleChassisNotDynamic,
		                         "Caliber: btRaycastVehicle: static or kinematic chassis; the vehicle does nothing\n");
		return;
	}
	if (!m_vehicleRaycaster)
		caliber::warnVehicleOnce(this, caliber::kVehicleNoRaycaster,
		                         "Caliber: btRaycastVehicle: null raycaster; no wheel touches the ground\n");

	bool driving = false;
	for (int i = 0; i < getNumWheels(); ++i) driving = driving || m_wheelInfo[i].m_engineForce != 0;
	if (!m_chassisBody->isActive())
	{
		// A sleeping chassis rests on its springs as it fell asleep; only the throttle wakes it.
		if (!driving) return;
		m_chassisBody->activate();
	}

	for (int i = 0; i < getNumWheels(); ++i) rayCast(m_wheelInfo[i]);
	updateSuspension(step);

	const btVector3 centre = m_chassisBody->getCenterOfMassPosition();
	for (int i = 0; i < getNumWheels(); ++i)
	{
		const btWheelInfo& wheel = m_wheelInfo[i];
		if (!wheel.m_raycastInfo.m_isInContact || wheel.m_wheelsSuspensionForce <= 0) continue;
		const btVector3 impulse = wheel.m_raycastInfo.m_contactNormalWS * (wheel.m_wheelsSuspensionForce * step);
		const btVector3& point = wheel.m_raycastInfo.m_contactPointWS;
		m_chassisBody->applyImpulse(impulse, point - centre);
		// The ground takes the reaction when it is a body that can move.
		btRigidBody* ground =
		    btRigidBody::upcast(static_cast<btCollisionObject*>(wheel.m_raycastInfo.m_groundObject));
		if (ground && ground->getInvMass() > 0)
		{
			ground->activate();
			ground->applyImpulse(-impulse, point - ground->getCenterOfMassPosition());
		}
	}

	updateFriction(step);

	for (int i = 0; i < getNumWheels(); ++i)
	{
		btWheelInfo& wheel = m_wheelInfo[i];
		if (!wheel.m_raycastInfo.m_isInContact)
		{
			wheel.m_rotation += wheel.m_deltaRotation;
			wheel.m_deltaRotation *= kAirSpinDecay;
			continue;
		}
		// The tyre rolls on the ground: spin = contact speed along the wheel / radius, relative to the
		// ground and as it will be when the next substep moves the chassis (m_forwardWS is the
		// wheel's rolling direction, set by updateFriction). A braked wheel that slides is locked.
		const bool locked = wheel.m_brake > 0 && wheel.m_skidInfo < 1;
		btScalar delta = 0;
		if (!locked && i < m_forwardWS.size())
		{
			const btVector3& point = wheel.m_raycastInfo.m_contactPointWS;
			const btRigidBody* ground =
			    btRigidBody::upcast(static_cast<const btCollisionObject*>(wheel.m_raycastInfo.m_groundObject));
			const btVector3 relative = caliber::velocityAtPoint(m_chassisBody, point) +
			                           m_chassisBody->getTotalForce() * (m_chassisBody->getInvMass() * step) -
			                           caliber::velocityAtPoint(ground, point);
			delta = relative.dot(m_forwardWS[i]) * step / wheel.m_wheelsRadius;
		}
		wheel.m_deltaRotation = delta;
		wheel.m_rotation += delta;
	}
	for (int i = 0; i < getNumWheels(); ++i) updateWheelTransform(i, false);
}

void btRaycastVehicle::debugDraw(btIDebugDraw* debugDrawer)
{
	if (!debugDrawer) return;
	for (int i = 0; i < getNumWheels(); ++i)
	{
		const btWheelInfo& wheel = m_wheelInfo[i];
		const btVector3 colour = wheel.m_raycastInfo.m_isInContact ? btVector3(0, 0, 1) : btVector3(1, 0, 1);
		const btVector3 centre = wheel.m_worldTransform.getOrigin();
		const btVector3 axle = wheel.m_worldTransform.getBasis().getColumn(0);
		debugDrawer->drawLine(centre, centre + axle, colour);
		debugDrawer->drawLine(centre, wheel.m_raycastInfo.m_contactPointWS, colour);
	}
}
