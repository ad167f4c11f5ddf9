// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Internal to the importer library (not installed): what a file's data struct sets on an object, shared by
// the path that creates objects (btWorldImporter) and the path that writes into the world's existing ones
// (eRESTORE_EXISTING_OBJECTS, RestoreExistingObjects.cpp). Float and double structs share field names.
#ifndef CALIBER_IMPORTER_SETTINGS_H
#define CALIBER_IMPORTER_SETTINGS_H

#include "btBulletDynamicsCommon.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"

namespace caliber
{
namespace importer
{
inline btVector3 vec(const btVector3FloatData& d)
{
	btVector3 v;
	v.deSerializeFloat(d);
	return v;
}
inline btVector3 vec(const btVector3DoubleData& d)
{
	btVector3 v;
	v.deSerializeDouble(d);
	return v;
}
inline btTransform xform(const btTransformFloatData& d)
{
	btTransform t;
	t.deSerializeFloat(d);
	return t;
}
inline btTransform xform(const btTransformDoubleData& d)
{
	btTransform t;
	t.deSerializeDouble(d);
	return t;
}

// Everything of btCollisionObject{Float,Double}Data but the shape, the world transform and the filter.
template <class ObjectData>
void applyCollisionObjectData(btCollisionObject* object, const ObjectData& d)
{
	object->setInterpolationWorldTransform(xform(d.m_interpolationWorldTransform));
	object->setInterpolationLinearVelocity(vec(d.m_interpolationLinearVelocity));
	object->setInterpolationAngularVelocity(vec(d.m_interpolationAngularVelocity));
	object->setAnisotropicFriction(vec(d.m_anisotropicFriction), d.m_hasAnisotropicFriction);
	object->setContactProcessingThreshold(btScalar(d.m_contactProcessingThreshold));
	object->setFriction(btScalar(d.m_friction));
	object->setRollingFriction(btScalar(d.m_rollingFriction));
	object->setRestitution(btScalar(d.m_restitution));
	object->setHitFraction(btScalar(d.m_hitFraction));
	object->setCcdSweptSphereRadius(btScalar(d.m_ccdSweptSphereRadius));
	object->setCcdMotionThreshold(btScalar(d.m_ccdMotionThreshold));
	object->setCollisionFlags(d.m_collisionFlags);
	if (d.m_collisionFlags & btCollisionObject::CF_HAS_CONTACT_STIFFNESS_DAMPING)
		object->setContactStiffnessAndDamping(btScalar(d.m_contactStiffness), btScalar(d.m_contactDamping));
	// Unknown activation states (a damaged file) become active.
	const int state = d.m_activationState1;
	object->forceActivationState(state >= ACTIVE_TAG && state <= DISABLE_SIMULATION ? state : ACTIVE_TAG);
	object->setDeactivationTime(btScalar(d.m_deactivationTime));
}

// A rigid body's own fields (not its mass, which only a new body takes, nor its gravity, which the world
// sets when the body is added and the file's replaces afterwards).
template <class BodyData>
void applyRigidBodyData(btRigidBody* body, const BodyData& d)
{
	// The solver uses the inverse inertia: take it from the file rather than from the shape.
	body->setInvInertiaDiagLocal(vec(d.m_invInertiaLocal));
	body->setDamping(btScalar(d.m_linearDamping), btScalar(d.m_angularDamping));
	body->setSleepingThresholds(btScalar(d.m_linearSleepingThreshold), btScalar(d.m_angularSleepingThreshold));
	body->setLinearFactor(vec(d.m_linearFactor));
	body->setAngularFactor(vec(d.m_angularFactor));
	body->setLinearVelocity(vec(d.m_linearVelocity));
	body->setAngularVelocity(vec(d.m_angularVelocity));
	body->updateInertiaTensor();
}

// ---- joints: the settings each kind takes after it is made with its bodies and frames ------------

template <class Common>
void applyJointCommon(btTypedConstraint& c, const Common& d)
{
	c.setBreakingImpulseThreshold(btScalar(d.m_breakingImpulseThreshold));
	c.setEnabled(d.m_isEnabled != 0);
	c.setOverrideNumSolverIterations(d.m_overrideNumSolverIterations);
	c.setDbgDrawSize(btScalar(d.m_dbgDrawSize));
	c.enableFeedback(d.m_needsFeedback != 0);
	c.setUserConstraintType(d.m_userConstraintType);
	c.setUserConstraintId(d.m_userConstraintId);
}

template <class D>
void configure(btHingeConstraint& hinge, const D& d)
{
	hinge.setAngularOnly(d.m_angularOnly != 0);
	hinge.enableAngularMotor(d.m_enableAngularMotor != 0, btScalar(d.m_motorTargetVelocity),
	                         btScalar(d.m_maxMotorImpulse));
	hinge.setLimit(btScalar(d.m_lowerLimit), btScalar(d.m_upperLimit), btScalar(d.m_limitSoftness),
	               btScalar(d.m_biasFactor), btScalar(d.m_relaxationFactor));
}

template <class D>
void configure(btConeTwistConstraint& cone, const D& d)
{
	cone.setLimit(btScalar(d.m_swingSpan1), btScalar(d.m_swingSpan2), btScalar(d.m_twistSpan),
	              btScalar(d.m_limitSoftness), btScalar(d.m_biasFactor), btScalar(d.m_relaxationFactor));
	cone.setDamping(btScalar(d.m_damping));
}

template <class D>
void configure(btGeneric6DofConstraint& dof, const D& d)
{
	dof.setLinearLowerLimit(vec(d.m_linearLowerLimit));
	dof.setLinearUpperLimit(vec(d.m_linearUpperLimit));
	dof.setAngularLowerLimit(vec(d.m_angularLowerLimit));
	dof.setAngularUpperLimit(vec(d.m_angularUpperLimit));
}

template <class D>
void configureSpring(btGeneric6DofSpringConstraint& dof, const D& d)
{
	configure(static_cast<btGeneric6DofConstraint&>(dof), d.m_6dofData);
	for (int i = 0; i < 6; ++i)
	{
		dof.setStiffness(i, btScalar(d.m_springStiffness[i]));
		dof.setEquilibriumPoint(i, btScalar(d.m_equilibriumPoint[i]));
		dof.setDamping(i, btScalar(d.m_springDamping[i]));
		dof.enableSpring(i, d.m_springEnabled[i] != 0);
	}
}

template <class D>
void configure(btGeneric6DofSpring2Constraint& dof, const D& d)
{
	btTranslationalLimitMotor2* lin = dof.getTranslationalLimitMotor();
	lin->m_lowerLimit = vec(d.m_linearLowerLimit);
	lin->m_upperLimit = vec(d.m_linearUpperLimit);
	lin->m_bounce = vec(d.m_linearBounce);
	lin->m_stopERP = vec(d.m_linearStopERP);
	lin->m_stopCFM = vec(d.m_linearStopCFM);
	lin->m_motorERP = vec(d.m_linearMotorERP);
	lin->m_motorCFM = vec(d.m_linearMotorCFM);
	lin->m_targetVelocity = vec(d.m_linearTargetVelocity);
	lin->m_maxMotorForce = vec(d.m_linearMaxMotorForce);
	lin->m_servoTarget = vec(d.m_linearServoTarget);
	lin->m_springStiffness = vec(d.m_linearSpringStiffness);
	lin->m_springDamping = vec(d.m_linearSpringDamping);
	lin->m_equilibriumPoint = vec(d.m_linearEquilibriumPoint);
	for (int i = 0; i < 3; ++i)
	{
		lin->m_enableMotor[i] = d.m_linearEnableMotor[i] != 0;
		lin->m_servoMotor[i] = d.m_linearServoMotor[i] != 0;
		lin->m_enableSpring[i] = d.m_linearEnableSpring[i] != 0;
		lin->m_springStiffnessLimited[i] = d.m_linearSpringStiffnessLimited[i] != 0;
		lin->m_springDampingLimited[i] = d.m_linearSpringDampingLimited[i] != 0;
		btRotationalLimitMotor2* m = dof.getRotationalLimitMotor(i);
		m->m_loLimit = btScalar(d.m_angularLowerLimit.m_floats[i]);
		m->m_hiLimit = btScalar(d.m_angularUpperLimit.m_floats[i]);
		m->m_bounce = btScalar(d.m_angularBounce.m_floats[i]);
		m->m_stopERP = btScalar(d.m_angularStopERP.m_floats[i]);
		m->m_stopCFM = btScalar(d.m_angularStopCFM.m_floats[i]);
		m->m_motorERP = btScalar(d.m_angularMotorERP.m_floats[i]);
		m->m_motorCFM = btScalar(d.m_angularMotorCFM.m_floats[i]);
		m->m_targetVelocity = btScalar(d.m_angularTargetVelocity.m_floats[i]);
		m->m_maxMotorForce = btScalar(d.m_angularMaxMotorForce.m_floats[i]);
		m->m_servoTarget = btScalar(d.m_angularServoTarget.m_floats[i]);
		m->m_springStiffness = btScalar(d.m_angularSpringStiffness.m_floats[i]);
		m->m_springDamping = btScalar(d.m_angularSpringDamping.m_floats[i]);
		m->m_equilibriumPoint = btScalar(d.m_angularEquilibriumPoint.m_floats[i]);
		m->m_enableMotor = d.m_angularEnableMotor[i] != 0;
		m->m_servoMotor = d.m_angularServoMotor[i] != 0;
		m->m_enableSpring = d.m_angularEnableSpring[i] != 0;
		m->m_springStiffnessLimited = d.m_angularSpringStiffnessLimited[i] != 0;
		m->m_springDampingLimited = d.m_angularSpringDampingLimited[i] != 0;
	}
}

template <class D>
void configure(btSliderConstraint& slider, const D& d)
{
	slider.setLowerLinLimit(btScalar(d.m_linearLowerLimit));
	slider.setUpperLinLimit(btScalar(d.m_linearUpperLimit));
	slider.setLowerAngLimit(btScalar(d.m_angularLowerLimit));
	slider.setUpperAngLimit(btScalar(d.m_angularUpperLimit));
	slider.setUseFrameOffset(d.m_useOffsetForConstraintFrame != 0);
}
}  // namespace importer
}  // namespace caliber

#endif
