// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// serialize() of every joint Bullet's .bullet format describes (docs/serialization.md). Each joint
// writes the common part (btTypedConstraint::serialize) and then its frames, limits and motors.
#include "BulletDynamics/ConstraintSolver/btConeTwistConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGearConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpringConstraint.h"
#include "BulletDynamics/ConstraintSolver/btHingeConstraint.h"
#include "BulletDynamics/ConstraintSolver/btPoint2PointConstraint.h"
#include "BulletDynamics/ConstraintSolver/btSliderConstraint.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btSerializer.h"

#include <string.h>

int btTypedConstraint::calculateSerializeBufferSize() const { return int(sizeof(btTypedConstraintData2)); }

const char* btTypedConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btTypedConstraintData2* data = static_cast<btTypedConstraintData2*>(dataBuffer);
	// The world's fixed body is never written: a joint to it stores null, as in Bullet's files.
	btRigidBody* fixed = &getFixedBody();
	data->m_rbA = static_cast<btRigidBodyData*>(&m_rbA == fixed ? 0 : serializer->getUniquePointer(&m_rbA));
	data->m_rbB = static_cast<btRigidBodyData*>(&m_rbB == fixed ? 0 : serializer->getUniquePointer(&m_rbB));
	const char* name = serializer->findNameForPointer(this);
	data->m_name = static_cast<char*>(serializer->getUniquePointer(const_cast<char*>(name)));
	if (data->m_name) serializer->serializeName(name);
	data->m_objectType = m_objectType;
	data->m_needsFeedback = m_needsFeedback ? 1 : 0;
	data->m_overrideNumSolverIterations = m_overrideNumSolverIterations;
	data->m_breakingImpulseThreshold = m_breakingImpulseThreshold;
	data->m_isEnabled = m_isEnabled ? 1 : 0;
	data->m_userConstraintId = m_userConstraintId;
	data->m_userConstraintType = m_userConstraintType;
	data->m_appliedImpulse = m_appliedImpulse;
	data->m_dbgDrawSize = m_dbgDrawSize;
	// The world records "no collisions between the bodies" by listing the joint on the bodies.
	data->m_disableCollisionsBetweenLinkedBodies = 0;
	for (int i = 0; i < m_rbA.getNumConstraintRefs(); ++i)
		if (m_rbA.getConstraintRef(i) == this) data->m_disableCollisionsBetweenLinkedBodies = 1;
	for (int i = 0; i < m_rbB.getNumConstraintRefs(); ++i)
		if (m_rbB.getConstraintRef(i) == this) data->m_disableCollisionsBetweenLinkedBodies = 1;
#ifdef BT_USE_DOUBLE_PRECISION
	memset(data->padding, 0, sizeof(data->padding));
#endif
	return btTypedConstraintDataName;
}

int btPoint2PointConstraint::calculateSerializeBufferSize() const { return int(sizeof(btPoint2PointConstraintData2)); }

const char* btPoint2PointConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btPoint2PointConstraintData2* data = static_cast<btPoint2PointConstraintData2*>(dataBuffer);
	btTypedConstraint::serialize(&data->m_typeConstraintData, serializer);
	m_pivotInA.serialize(data->m_pivotInA);
	m_pivotInB.serialize(data->m_pivotInB);
	return btPoint2PointConstraintDataName;
}

int btHingeConstraint::calculateSerializeBufferSize() const { return int(sizeof(btHingeConstraintData)); }

const char* btHingeConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btHingeConstraintData* data = static_cast<btHingeConstraintData*>(dataBuffer);
	btTypedConstraint::serialize(&data->m_typeConstraintData, serializer);
	m_rbAFrame.serialize(data->m_rbAFrame);
	m_rbBFrame.serialize(data->m_rbBFrame);
	data->m_angularOnly = m_angularOnly;
	data->m_enableAngularMotor = m_enableAngularMotor;
	data->m_maxMotorImpulse = m_maxMotorImpulse;
	data->m_motorTargetVelocity = m_motorTargetVelocity;
	data->m_useReferenceFrameA = m_useReferenceFrameA;
	data->m_lowerLimit = m_limit.getLow();
	data->m_upperLimit = m_limit.getHigh();
	data->m_limitSoftness = m_limit.getSoftness();
	data->m_biasFactor = m_limit.getBiasFactor();
	data->m_relaxationFactor = m_limit.getRelaxationFactor();
#ifdef BT_USE_DOUBLE_PRECISION
	memset(data->m_padding1, 0, sizeof(data->m_padding1));
#endif
	return btHingeConstraintDataName;
}

int btConeTwistConstraint::calculateSerializeBufferSize() const { return int(sizeof(btConeTwistConstraintData2)); }

const char* btConeTwistConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btConeTwistConstraintData2* data = static_cast<btConeTwistConstraintData2*>(dataBuffer);
	btTypedConstraint::serialize(&data->m_typeConstraintData, serializer);
	m_rbAFrame.serialize(data->m_rbAFrame);
	m_rbBFrame.serialize(data->m_rbBFrame);
	data->m_swingSpan1 = m_swingSpan1;
	data->m_swingSpan2 = m_swingSpan2;
	data->m_twistSpan = m_twistSpan;
	data->m_limitSoftness = m_limitSoftness;
	data->m_biasFactor = m_biasFactor;
	data->m_relaxationFactor = m_relaxationFactor;
	data->m_damping = m_damping;
#ifndef BT_USE_DOUBLE_PRECISION
	memset(data->m_pad, 0, sizeof(data->m_pad));
#endif
	return btConeTwistConstraintDataName;
}

int btSliderConstraint::calculateSerializeBufferSize() const { return int(sizeof(btSliderConstraintData2)); }

const char* btSliderConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btSliderConstraintData2* data = static_cast<btSliderConstraintData2*>(dataBuffer);
	btTypedConstraint::serialize(&data->m_typeConstraintData, serializer);
	m_frameInA.serialize(data->m_rbAFrame);
	m_frameInB.serialize(data->m_rbBFrame);
	data->m_linearUpperLimit = m_upperLinLimit;
	data->m_linearLowerLimit = m_lowerLinLimit;
	data->m_angularUpperLimit = m_upperAngLimit;
	data->m_angularLowerLimit = m_lowerAngLimit;
	data->m_useLinearReferenceFrameA = m_useLinearReferenceFrameA;
	data->m_useOffsetForConstraintFrame = m_useOffsetForConstraintFrame;
	return btSliderConstraintDataName;
}

int btGeneric6DofConstraint::calculateSerializeBufferSize() const { return int(sizeof(btGeneric6DofConstraintData2)); }

const char* btGeneric6DofConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btGeneric6DofConstraintData2* data = static_cast<btGeneric6DofConstraintData2*>(dataBuffer);
	btTypedConstraint::serialize(&data->m_typeConstraintData, serializer);
	m_frameInA.serialize(data->m_rbAFrame);
	m_frameInB.serialize(data->m_rbBFrame);
	for (int i = 0; i < 3; ++i)
	{
		data->m_angularLowerLimit.m_floats[i] = m_angularLimits[i].m_loLimit;
		data->m_angularUpperLimit.m_floats[i] = m_angularLimits[i].m_hiLimit;
		data->m_linearLowerLimit.m_floats[i] = m_linearLimits.m_lowerLimit[i];
		data->m_linearUpperLimit.m_floats[i] = m_linearLimits.m_upperLimit[i];
	}
	data->m_angularLowerLimit.m_floats[3] = data->m_angularUpperLimit.m_floats[3] = 0;
	data->m_linearLowerLimit.m_floats[3] = data->m_linearUpperLimit.m_floats[3] = 0;
	data->m_useLinearReferenceFrameA = m_useLinearReferenceFrameA ? 1 : 0;
	data->m_useOffsetForConstraintFrame = m_useOffsetForConstraintFrame ? 1 : 0;
	return btGeneric6DofConstraintDataName;
}

int btGeneric6DofSpringConstraint::calculateSerializeBufferSize() const
{
	return int(sizeof(btGeneric6DofSpringConstraintData2));
}

const char* btGeneric6DofSpringConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btGeneric6DofSpringConstraintData2* data = static_cast<btGeneric6DofSpringConstraintData2*>(dataBuffer);
	btGeneric6DofConstraint::serialize(&data->m_6dofData, serializer);
	for (int i = 0; i < 6; ++i)
	{
		data->m_equilibriumPoint[i] = m_equilibriumPoint[i];
		data->m_springDamping[i] = m_springDamping[i];
		data->m_springEnabled[i] = m_springEnabled[i] ? 1 : 0;
		data->m_springStiffness[i] = m_springStiffness[i];
	}
	return btGeneric6DofSpringConstraintDataName;
}

int btGeneric6DofSpring2Constraint::calculateSerializeBufferSize() const
{
	return int(sizeof(btGeneric6DofSpring2ConstraintData2));
}

const char* btGeneric6DofSpring2Constraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btGeneric6DofSpring2ConstraintData2* data = static_cast<btGeneric6DofSpring2ConstraintData2*>(dataBuffer);
	btTypedConstraint::serialize(&data->m_typeConstraintData, serializer);
	m_frameInA.serialize(data->m_rbAFrame);
	m_frameInB.serialize(data->m_rbBFrame);
	const btTranslationalLimitMotor2& lin = m_linearLimits;
	lin.m_upperLimit.serialize(data->m_linearUpperLimit);
	lin.m_lowerLimit.serialize(data->m_linearLowerLimit);
	lin.m_bounce.serialize(data->m_linearBounce);
	lin.m_stopERP.serialize(data->m_linearStopERP);
	lin.m_stopCFM.serialize(data->m_linearStopCFM);
	lin.m_motorERP.serialize(data->m_linearMotorERP);
	lin.m_motorCFM.serialize(data->m_linearMotorCFM);
	lin.m_targetVelocity.serialize(data->m_linearTargetVelocity);
	lin.m_maxMotorForce.serialize(data->m_linearMaxMotorForce);
	lin.m_servoTarget.serialize(data->m_linearServoTarget);
	lin.m_springStiffness.serialize(data->m_linearSpringStiffness);
	lin.m_springDamping.serialize(data->m_linearSpringDamping);
	lin.m_equilibriumPoint.serialize(data->m_linearEquilibriumPoint);
	memset(data->m_padding1, 0, sizeof(data->m_padding1));
	for (int i = 0; i < 4; ++i)
	{
		const bool axis = i < 3;
		data->m_linearEnableMotor[i] = char(axis && lin.m_enableMotor[i]);
		data->m_linearServoMotor[i] = char(axis && lin.m_servoMotor[i]);
		data->m_linearEnableSpring[i] = char(axis && lin.m_enableSpring[i]);
		data->m_linearSpringStiffnessLimited[i] = char(axis && lin.m_springStiffnessLimited[i]);
		data->m_linearSpringDampingLimited[i] = char(axis && lin.m_springDampingLimited[i]);
	}
	// The angular vectors hold one value per axis; the fourth lane is zero.
	for (int i = 0; i < 4; ++i)
	{
		const bool axis = i < 3;
		const btRotationalLimitMotor2* m = axis ? &m_angularLimits[i] : 0;
		data->m_angularUpperLimit.m_floats[i] = axis ? m->m_hiLimit : 0;
		data->m_angularLowerLimit.m_floats[i] = axis ? m->m_loLimit : 0;
		data->m_angularBounce.m_floats[i] = axis ? m->m_bounce : 0;
		data->m_angularStopERP.m_floats[i] = axis ? m->m_stopERP : 0;
		data->m_angularStopCFM.m_floats[i] = axis ? m->m_stopCFM : 0;
		data->m_angularMotorERP.m_floats[i] = axis ? m->m_motorERP : 0;
		data->m_angularMotorCFM.m_floats[i] = axis ? m->m_motorCFM : 0;
		data->m_angularTargetVelocity.m_floats[i] = axis ? m->m_targetVelocity : 0;
		data->m_angularMaxMotorForce.m_floats[i] = axis ? m->m_maxMotorForce : 0;
		data->m_angularServoTarget.m_floats[i] = axis ? m->m_servoTarget : 0;
		data->m_angularSpringStiffness.m_floats[i] = axis ? m->m_springStiffness : 0;
		data->m_angularSpringDamping.m_floats[i] = axis ? m->m_springDamping : 0;
		data->m_angularEquilibriumPoint.m_floats[i] = axis ? m->m_equilibriumPoint : 0;
		data->m_angularEnableMotor[i] = char(axis && m->m_enableMotor);
		data->m_angularServoMotor[i] = char(axis && m->m_servoMotor);
		data->m_angularEnableSpring[i] = char(axis && m->m_enableSpring);
		data->m_angularSpringStiffnessLimited[i] = char(axis && m->m_springStiffnessLimited);
		data->m_angularSpringDampingLimited[i] = char(axis && m->m_springDampingLimited);
	}
	data->m_rotateOrder = int(m_rotateOrder);
	return btGeneric6DofSpring2ConstraintDataName;
}

int btGearConstraint::calculateSerializeBufferSize() const { return int(sizeof(btGearConstraintData)); }

const char* btGearConstraint::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btGearConstraintData* data = static_cast<btGearConstraintData*>(dataBuffer);
	btTypedConstraint::serialize(&data->m_typeConstraintData, serializer);
	m_axisInA.serialize(data->m_axisInA);
	m_axisInB.serialize(data->m_axisInB);
	data->m_ratio = m_ratio;
#ifndef BT_USE_DOUBLE_PRECISION
	memset(data->m_padding, 0, sizeof(data->m_padding));
#endif
	return btGearConstraintDataName;
}
