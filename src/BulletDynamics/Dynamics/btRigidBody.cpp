// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/Dynamics/btRigidBody.h"

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "LinearMath/btMotionState.h"
#include "LinearMath/btTransformUtil.h"
#include "LinearMath/btWarningHook.h"

btScalar gDeactivationTime = btScalar(2);
bool gDisableDeactivation = false;

namespace
{
// The angular speed at which a body turns a quarter turn in one step; faster spins are clamped
// (integrateTransform cannot represent more per step, and such speeds are numerical blow-ups).
btScalar maxAngularSpeed(btScalar step) { return SIMD_HALF_PI / step; }

// The skew matrix of v: skew(v) * w == v.cross(w).
btMatrix3x3 skew(const btVector3& v) { return btMatrix3x3(0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0); }
}  // namespace

btRigidBody::btRigidBody(const btRigidBodyConstructionInfo& constructionInfo) { setupRigidBody(constructionInfo); }

btRigidBody::btRigidBody(btScalar mass, btMotionState* motionState, btCollisionShape* collisionShape,
                         const btVector3& localInertia)
{
	btRigidBodyConstructionInfo info(mass, motionState, collisionShape, localInertia);
	setupRigidBody(info);
}

btRigidBody::~btRigidBody()
{
	btAssert(m_constraintRefs.size() == 0 && "btRigidBody destroyed while constraints still refer to it");
}

void btRigidBody::setupRigidBody(const btRigidBodyConstructionInfo& info)
{
	m_internalType = CO_RIGID_BODY;

	// A new body is at rest with nothing pending: no velocity, force, solver delta or split-impulse
	// velocity; mass and inertia are zero until setMassProps below.
	static btVector3 btRigidBody::*const kZeroAtStart[] = {
	    &btRigidBody::m_linearVelocity,
	    &btRigidBody::m_angularVelocity,
	    &btRigidBody::m_gravity,
	    &btRigidBody::m_gravity_acceleration,
	    &btRigidBody::m_totalForce,
	    &btRigidBody::m_totalTorque,
	    &btRigidBody::m_deltaLinearVelocity,
	    &btRigidBody::m_deltaAngularVelocity,
	    &btRigidBody::m_pushVelocity,
	    &btRigidBody::m_turnVelocity,
	    &btRigidBody::m_invMass,
	    &btRigidBody::m_invInertiaLocal,
	    &btRigidBody::m_interpolationLinearVelocity,
	    &btRigidBody::m_interpolationAngularVelocity,
	};
	for (btVector3 btRigidBody::*member : kZeroAtStart) (this->*member).setValue(0, 0, 0);
	m_inverseMass = btScalar(0);
	m_invInertiaTensorWorld.setZero();
	m_linearFactor.setValue(btScalar(1), btScalar(1), btScalar(1));
	m_angularFactor.setValue(btScalar(1), btScalar(1), btScalar(1));

	// Settings the construction info hands over unchanged.
	struct CopiedSetting
	{
		btScalar btRigidBody::*body;
		btScalar btRigidBodyConstructionInfo::*info;
	};
	static const CopiedSetting kCopied[] = {
	    {&btRigidBody::m_linearSleepingThreshold, &btRigidBodyConstructionInfo::m_linearSleepingThreshold},
	    {&btRigidBody::m_angularSleepingThreshold, &btRigidBodyConstructionInfo::m_angularSleepingThreshold},
	    {&btRigidBody::m_additionalDampingFactor, &btRigidBodyConstructionInfo::m_additionalDampingFactor},
	    {&btRigidBody::m_additionalLinearDampingThresholdSqr,
	     &btRigidBodyConstructionInfo::m_additionalLinearDampingThresholdSqr},
	    {&btRigidBody::m_additionalAngularDampingThresholdSqr,
	     &btRigidBodyConstructionInfo::m_additionalAngularDampingThresholdSqr},
	    {&btRigidBody::m_additionalAngularDampingFactor,
	     &btRigidBodyConstructionInfo::m_additionalAngularDampingFactor},
	};
	for (const CopiedSetting& setting : kCopied) this->*setting.body = info.*setting.info;
	m_additionalDamping = info.m_additionalDamping;
	m_optionalMotionState = info.m_motionState;
	m_contactSolverType = 0;
	m_frictionSolverType = 0;
	// The material setters reject negative and non-finite values (the object's defaults stay).
	setFriction(info.m_friction);
	setRollingFriction(info.m_rollingFriction);
	setSpinningFriction(info.m_spinningFriction);
	setRestitution(info.m_restitution);
	m_linearDamping = m_angularDamping = btScalar(0);
	setDamping(info.m_linearDamping, info.m_angularDamping);  // clamped to [0, 1]

	// The motion state, when there is one, knows where the body starts; the info's transform otherwise.
	if (m_optionalMotionState)
		m_optionalMotionState->getWorldTransform(m_worldTransform);
	else
		m_worldTransform = info.m_startWorldTransform;
	m_interpolationWorldTransform = m_worldTransform;

	setCollisionShape(info.m_collisionShape);
	static int nextDebugBodyId = 0;
	m_debugBodyId = nextDebugBodyId++;
	// The implicit body-space gyroscopic term is stable at any spin rate, so it is on by default.
	m_rigidbodyFlags = BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY;
	// Needs the pose and the zero gravity acceleration set above.
	setMassProps(info.m_mass, info.m_localInertia);
	updateInertiaTensor();
	m_updateRevision = 0;
}

void btRigidBody::setMassProps(btScalar mass, const btVector3& inertia)
{
	const bool massUsable = btIsFinite(mass) && mass >= btScalar(0);
	btAssert(massUsable && "btRigidBody: mass must be finite and not negative (0 makes a static body)");
	if (!massUsable) mass = btScalar(0);
	if (mass == btScalar(0))
	{
		m_collisionFlags |= CF_STATIC_OBJECT;
		m_inverseMass = btScalar(0);
	}
	else
	{
		m_collisionFlags &= ~CF_STATIC_OBJECT;
		m_inverseMass = btScalar(1) / mass;
	}
	m_gravity = m_gravity_acceleration * mass;

	for (int axis = 0; axis < 3; ++axis)
	{
		const btScalar component = inertia[axis];
		const bool usable = btIsFinite(component) && component >= btScalar(0);
		btAssert(usable && "btRigidBody: inertia must be finite and not negative");
		// 0 (or a rejected value) means infinite inertia: the body does not turn about that axis.
		m_invInertiaLocal[axis] = usable && component != btScalar(0) ? btScalar(1) / component : btScalar(0);
	}
	m_invMass = m_linearFactor * m_inverseMass;
}

namespace
{
// A factor scales the response along an axis: 0 locks it, 1 is free. Negative or non-finite
// factors would invert or poison the response; they are reported and the call ignored.
bool acceptFactor(const btVector3& factor, const char* warning)
{
	const bool valid = caliber::isFinite(factor) && factor.x() >= btScalar(0) && factor.y() >= btScalar(0) &&
	                   factor.z() >= btScalar(0);
	if (!valid) btReportWarning(warning);
	btAssert(valid && "btRigidBody: linear and angular factors must be finite and >= 0");
	return valid;
}
}  // namespace

void btRigidBody::setLinearFactor(const btVector3& linearFactor)
{
	if (!acceptFactor(linearFactor, "Caliber: setLinearFactor: negative or non-finite; ignored\n")) return;
	m_linearFactor = linearFactor;
	m_invMass = m_linearFactor * m_inverseMass;
}

void btRigidBody::setAngularFactor(const btVector3& angFac)
{
	if (!acceptFactor(angFac, "Caliber: setAngularFactor: negative or non-finite; ignored\n")) return;
	m_updateRevision++;
	m_angularFactor = angFac;
}

void btRigidBody::setAngularFactor(btScalar angFac) { setAngularFactor(btVector3(angFac, angFac, angFac)); }

void btRigidBody::setDamping(btScalar lin_damping, btScalar ang_damping)
{
	const bool finite = btIsFinite(lin_damping) && btIsFinite(ang_damping);
	if (!finite) btReportWarning("Caliber: setDamping: non-finite damping; ignored\n");
	btAssert(finite && "btRigidBody::setDamping: non-finite damping");
	if (!finite) return;
	m_linearDamping = btClamped(lin_damping, btScalar(0), btScalar(1));
	m_angularDamping = btClamped(ang_damping, btScalar(0), btScalar(1));
}

namespace
{
// (1 - damping)^timeStep, remembered per thread for the last damping and step asked for: the bodies of a
// scene mostly share their damping, so the power (a library call) runs about once per step and thread
// instead of once per body. Slot 0 serves linear damping, slot 1 angular.
btScalar dampingFactor(int slot, btScalar damping, btScalar timeStep)
{
	struct Remembered
	{
		btScalar damping, timeStep, factor;
	};
	thread_local Remembered remembered[2] = {{btScalar(0), btScalar(0), btScalar(1)},
	                                         {btScalar(0), btScalar(0), btScalar(1)}};
	Remembered& r = remembered[slot];
	if (r.damping != damping || r.timeStep != timeStep)
	{
		r.damping = damping;
		r.timeStep = timeStep;
		r.factor = btPow(btScalar(1) - damping, timeStep);
	}
	return r.factor;
}
}  // namespace

void btRigidBody::applyDamping(btScalar timeStep)
{
	// Exponential decay per second, independent of how a second is cut into steps. Without damping the
	// factor is exactly 1, and the power is skipped.
	if (m_linearDamping != btScalar(0)) m_linearVelocity *= dampingFactor(0, m_linearDamping, timeStep);
	if (m_angularDamping != btScalar(0)) m_angularVelocity *= dampingFactor(1, m_angularDamping, timeStep);
	if (!m_additionalDamping) return;

	// Bodies that are nearly at rest get damped hard, so that they settle and can fall asleep.
	if (m_angularVelocity.length2() < m_additionalAngularDampingThresholdSqr &&
	    m_linearVelocity.length2() < m_additionalLinearDampingThresholdSqr)
	{
		m_angularVelocity *= m_additionalDampingFactor;
		m_linearVelocity *= m_additionalDampingFactor;
	}
	// Slow bodies also lose a small constant amount of speed per step (a rolling-resistance stand-in).
	const btScalar decrement = btScalar(0.005);
	const btScalar speed = m_linearVelocity.length();
	if (speed < m_linearDamping)
		m_linearVelocity = speed > decrement ? m_linearVelocity * ((speed - decrement) / speed) : btVector3(0, 0, 0);
	const btScalar angularSpeed = m_angularVelocity.length();
	if (angularSpeed < m_angularDamping)
	{
		m_angularVelocity = angularSpeed > decrement ? m_angularVelocity * ((angularSpeed - decrement) / angularSpeed)
		                                             : btVector3(0, 0, 0);
	}
}

void btRigidBody::setGravity(const btVector3& acceleration)
{
	btAssert(caliber::isFinite(acceleration) && "btRigidBody::setGravity: non-finite acceleration");
	if (!caliber::isFinite(acceleration)) return;
	if (m_inverseMass != btScalar(0)) m_gravity = acceleration * (btScalar(1) / m_inverseMass);
	m_gravity_acceleration = acceleration;
}

void btRigidBody::applyGravity()
{
	if (isStaticOrKinematicObject()) return;
	applyCentralForce(m_gravity);
}

void btRigidBody::clearGravity()
{
	if (isStaticOrKinematicObject()) return;
	applyCentralForce(-m_gravity);
}

void btRigidBody::applyCentralForce(const btVector3& force)
{
	btAssert(caliber::isFinite(force) && "btRigidBody: non-finite force");
	if (!caliber::isFinite(force)) return;
	m_totalForce += force * m_linearFactor;
}

void btRigidBody::applyTorque(const btVector3& torque)
{
	btAssert(caliber::isFinite(torque) && "btRigidBody: non-finite torque");
	if (!caliber::isFinite(torque)) return;
	m_totalTorque += torque * m_angularFactor;
}

void btRigidBody::applyForce(const btVector3& force, const btVector3& rel_pos)
{
	btAssert(caliber::isFinite(force) && caliber::isFinite(rel_pos) && "btRigidBody: non-finite force or point");
	if (!caliber::isFinite(force) || !caliber::isFinite(rel_pos)) return;
	applyCentralForce(force);
	applyTorque(rel_pos.cross(force * m_linearFactor));
}

void btRigidBody::applyCentralImpulse(const btVector3& impulse)
{
	btAssert(caliber::isFinite(impulse) && "btRigidBody: non-finite impulse");
	if (!caliber::isFinite(impulse)) return;
	m_linearVelocity += impulse * m_linearFactor * m_inverseMass;
}

void btRigidBody::applyTorqueImpulse(const btVector3& torque)
{
	btAssert(caliber::isFinite(torque) && "btRigidBody: non-finite torque impulse");
	if (!caliber::isFinite(torque)) return;
	m_angularVelocity += m_invInertiaTensorWorld * torque * m_angularFactor;
}

void btRigidBody::applyImpulse(const btVector3& impulse, const btVector3& rel_pos)
{
	btAssert(caliber::isFinite(impulse) && caliber::isFinite(rel_pos) && "btRigidBody: non-finite impulse or point");
	if (!caliber::isFinite(impulse) || !caliber::isFinite(rel_pos)) return;
	if (m_inverseMass == btScalar(0)) return;
	applyCentralImpulse(impulse);
	applyTorqueImpulse(rel_pos.cross(impulse * m_linearFactor));
}

void btRigidBody::applyPushImpulse(const btVector3& impulse, const btVector3& rel_pos)
{
	if (m_inverseMass == btScalar(0)) return;
	applyCentralPushImpulse(impulse);
	applyTorqueTurnImpulse(rel_pos.cross(impulse * m_linearFactor));
}

void btRigidBody::setLinearVelocity(const btVector3& lin_vel)
{
	btAssert(caliber::isFinite(lin_vel) && "btRigidBody::setLinearVelocity: non-finite velocity");
	if (!caliber::isFinite(lin_vel)) return;
	m_updateRevision++;
	m_linearVelocity = lin_vel;
}

void btRigidBody::setAngularVelocity(const btVector3& ang_vel)
{
	btAssert(caliber::isFinite(ang_vel) && "btRigidBody::setAngularVelocity: non-finite velocity");
	if (!caliber::isFinite(ang_vel)) return;
	m_updateRevision++;
	m_angularVelocity = ang_vel;
}

void btRigidBody::integrateVelocities(btScalar step)
{
	if (isStaticOrKinematicObject()) return;
	m_linearVelocity += m_totalForce * (m_inverseMass * step);
	m_angularVelocity += m_invInertiaTensorWorld * m_totalTorque * step;
	const btScalar limit = maxAngularSpeed(step);
	const btScalar angularSpeed = m_angularVelocity.length();
	if (angularSpeed * step > SIMD_HALF_PI) m_angularVelocity *= limit / angularSpeed;
}

void btRigidBody::predictIntegratedTransform(btScalar step, btTransform& predictedTransform)
{
	btTransformUtil::integrateTransform(m_worldTransform, m_linearVelocity, m_angularVelocity, step,
	                                    predictedTransform);
}

void btRigidBody::saveKinematicState(btScalar step)
{
	if (step == btScalar(0)) return;
	if (m_optionalMotionState) m_optionalMotionState->getWorldTransform(m_worldTransform);
	// The velocities that carried the body from its last pose to this one, for the solver and the
	// motion-state interpolation.
	btTransformUtil::calculateVelocity(m_interpolationWorldTransform, m_worldTransform, step, m_linearVelocity,
	                                   m_angularVelocity);
	m_interpolationLinearVelocity = m_linearVelocity;
	m_interpolationAngularVelocity = m_angularVelocity;
	m_interpolationWorldTransform = m_worldTransform;
}

void btRigidBody::setCenterOfMassTransform(const btTransform& xform)
{
	// A kinematic body keeps its last pose as the interpolation start, so that saveKinematicState
	// derives the velocity of this move.
	if (isKinematicObject())
		m_interpolationWorldTransform = m_worldTransform;
	else
		m_interpolationWorldTransform = xform;
	m_interpolationLinearVelocity = getLinearVelocity();
	m_interpolationAngularVelocity = getAngularVelocity();
	m_worldTransform = xform;
	updateInertiaTensor();
}

void btRigidBody::proceedToTransform(const btTransform& newTrans) { setCenterOfMassTransform(newTrans); }

void btRigidBody::updateInertiaTensor()
{
	const btMatrix3x3& basis = m_worldTransform.getBasis();
	m_invInertiaTensorWorld = basis.scaled(m_invInertiaLocal) * basis.transpose();
}

btQuaternion btRigidBody::getOrientation() const
{
	btQuaternion orientation;
	m_worldTransform.getBasis().getRotation(orientation);
	return orientation;
}

void btRigidBody::getAabb(btVector3& aabbMin, btVector3& aabbMax) const
{
	if (!m_collisionShape)
	{
		aabbMin = aabbMax = m_worldTransform.getOrigin();
		return;
	}
	m_collisionShape->getAabb(m_worldTransform, aabbMin, aabbMax);
}

btScalar btRigidBody::computeImpulseDenominator(const btVector3& pos, const btVector3& normal) const
{
	const btVector3 arm = pos - getCenterOfMassPosition();
	const btVector3 armCrossNormal = arm.cross(normal);
	const btVector3 angular = (m_invInertiaTensorWorld * armCrossNormal).cross(arm);
	return m_inverseMass + normal.dot(angular);
}

btScalar btRigidBody::computeAngularImpulseDenominator(const btVector3& axis) const
{
	return axis.dot(m_invInertiaTensorWorld * axis);
}

void btRigidBody::updateDeactivation(btScalar timeStep)
{
	const int state = getActivationState();
	if (state == ISLAND_SLEEPING || state == DISABLE_DEACTIVATION) return;
	if (getLinearVelocity().length2() < m_linearSleepingThreshold * m_linearSleepingThreshold &&
	    getAngularVelocity().length2() < m_angularSleepingThreshold * m_angularSleepingThreshold)
	{
		m_deactivationTime += timeStep;
	}
	else
	{
		m_deactivationTime = btScalar(0);
		setActivationState(ACTIVE_TAG);
	}
}

bool btRigidBody::wantsSleeping()
{
	const int state = getActivationState();
	if (state == DISABLE_DEACTIVATION) return false;
	if (gDisableDeactivation || gDeactivationTime == btScalar(0)) return false;
	if (state == ISLAND_SLEEPING || state == WANTS_DEACTIVATION) return true;
	return m_deactivationTime > gDeactivationTime;
}

void btRigidBody::setMotionState(btMotionState* motionState)
{
	m_optionalMotionState = motionState;
	if (m_optionalMotionState) motionState->getWorldTransform(m_worldTransform);
}

void btRigidBody::addConstraintRef(btTypedConstraint* c)
{
	btAssert(c && "btRigidBody::addConstraintRef: null constraint");
	if (!c) return;
	// A constraint is registered once, however often it is added.
	if (m_constraintRefs.findLinearSearch(c) == m_constraintRefs.size()) m_constraintRefs.push_back(c);
	m_checkCollideWith = 1;
}

void btRigidBody::removeConstraintRef(btTypedConstraint* c)
{
	m_constraintRefs.remove(c);
	m_checkCollideWith = m_constraintRefs.size() > 0 || getNumObjectsWithoutCollision() > 0;
}

bool btRigidBody::checkCollideWithOverride(const btCollisionObject* co) const
{
	if (!btCollisionObject::checkCollideWithOverride(co)) return false;
	const btRigidBody* other = btRigidBody::upcast(co);
	if (!other) return true;
	// Bodies linked by an enabled joint added with disableCollisionsBetweenLinkedBodies do not collide; a
	// broken (disabled) joint lets them collide again.
	for (int i = 0; i < m_constraintRefs.size(); ++i)
	{
		const btTypedConstraint* c = m_constraintRefs[i];
		if (c->isEnabled() && (&c->getRigidBodyA() == other || &c->getRigidBodyB() == other)) return false;
	}
	return true;
}

btVector3 btRigidBody::getLocalInertia() const
{
	const btVector3& inv = m_invInertiaLocal;
	return btVector3(inv.x() != btScalar(0) ? btScalar(1) / inv.x() : btScalar(0),
	                 inv.y() != btScalar(0) ? btScalar(1) / inv.y() : btScalar(0),
	                 inv.z() != btScalar(0) ? btScalar(1) / inv.z() : btScalar(0));
}

btVector3 btRigidBody::computeGyroscopicForceExplicit(btScalar maxGyroscopicForce) const
{
	const btVector3 inertiaLocal = getLocalInertia();
	const btMatrix3x3& basis = m_worldTransform.getBasis();
	const btMatrix3x3 inertiaWorld = basis.scaled(inertiaLocal) * basis.transpose();
	btVector3 torque = m_angularVelocity.cross(inertiaWorld * m_angularVelocity);
	const btScalar length2 = torque.length2();
	if (length2 > maxGyroscopicForce * maxGyroscopicForce) torque *= maxGyroscopicForce / btSqrt(length2);
	return torque;
}

btVector3 btRigidBody::computeGyroscopicImpulseImplicit_Body(btScalar step) const
{
	// Torque-free Euler equation in body axes, I dw/dt + w x (I w) = 0, one implicit Euler step solved
	// by one Newton iteration from w1: f(w) = I (w - w1) + h w x (I w), J = I + h (skew(w) I - skew(I w)).
	const btVector3 inertia = getLocalInertia();
	const btMatrix3x3& basis = m_worldTransform.getBasis();
	const btVector3 w1 = basis.transpose() * m_angularVelocity;
	const btMatrix3x3 inertiaMatrix(inertia.x(), 0, 0, 0, inertia.y(), 0, 0, 0, inertia.z());
	const btVector3 iw = inertiaMatrix * w1;
	const btVector3 f = w1.cross(iw) * step;
	const btMatrix3x3 jacobian = inertiaMatrix + (skew(w1) * inertiaMatrix - skew(iw)) * step;
	if (btFabs(jacobian.determinant()) < SIMD_EPSILON) return btVector3(0, 0, 0);
	const btVector3 w2 = w1 - jacobian.inverse() * f;
	return basis * (w2 - w1);
}

btVector3 btRigidBody::computeGyroscopicImpulseImplicit_World(btScalar step) const
{
	// The same implicit step with the world-space inertia tensor.
	const btVector3 inertia = getLocalInertia();
	const btMatrix3x3& basis = m_worldTransform.getBasis();
	const btMatrix3x3 inertiaWorld = basis.scaled(inertia) * basis.transpose();
	const btVector3 w1 = m_angularVelocity;
	const btVector3 iw = inertiaWorld * w1;
	const btVector3 f = w1.cross(iw) * step;
	const btMatrix3x3 jacobian = inertiaWorld + (skew(w1) * inertiaWorld - skew(iw)) * step;
	if (btFabs(jacobian.determinant()) < SIMD_EPSILON) return btVector3(0, 0, 0);
	return -(jacobian.inverse() * f);
}
