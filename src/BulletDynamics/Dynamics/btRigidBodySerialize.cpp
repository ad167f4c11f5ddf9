// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Writing rigid bodies and dynamics worlds into .bullet files (docs/serialization.md).
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"

#include <string>

int btRigidBody::calculateSerializeBufferSize() const { return int(sizeof(btRigidBodyData)); }

const char* btRigidBody::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btRigidBodyData* bodyData = static_cast<btRigidBodyData*>(dataBuffer);
	btCollisionObject::serialize(&bodyData->m_collisionObjectData, serializer);
	m_invInertiaTensorWorld.serialize(bodyData->m_invInertiaTensorWorld);
	m_linearVelocity.serialize(bodyData->m_linearVelocity);
	m_angularVelocity.serialize(bodyData->m_angularVelocity);
	bodyData->m_inverseMass = m_inverseMass;
	m_angularFactor.serialize(bodyData->m_angularFactor);
	m_linearFactor.serialize(bodyData->m_linearFactor);
	m_gravity.serialize(bodyData->m_gravity);
	m_gravity_acceleration.serialize(bodyData->m_gravity_acceleration);
	m_invInertiaLocal.serialize(bodyData->m_invInertiaLocal);
	m_totalForce.serialize(bodyData->m_totalForce);
	m_totalTorque.serialize(bodyData->m_totalTorque);
	bodyData->m_linearDamping = m_linearDamping;
	bodyData->m_angularDamping = m_angularDamping;
	bodyData->m_additionalDamping = m_additionalDamping ? 1 : 0;
	bodyData->m_additionalDampingFactor = m_additionalDampingFactor;
	bodyData->m_additionalLinearDampingThresholdSqr = m_additionalLinearDampingThresholdSqr;
	bodyData->m_additionalAngularDampingThresholdSqr = m_additionalAngularDampingThresholdSqr;
	bodyData->m_additionalAngularDampingFactor = m_additionalAngularDampingFactor;
	bodyData->m_linearSleepingThreshold = m_linearSleepingThreshold;
	bodyData->m_angularSleepingThreshold = m_angularSleepingThreshold;
#ifdef BT_USE_DOUBLE_PRECISION
	for (int i = 0; i < 4; ++i) bodyData->m_padding[i] = 0;
#endif
	return btRigidBodyDataName;
}

void btRigidBody::serializeSingleObject(btSerializer* serializer) const
{
	btChunk* chunk = serializer->allocate(size_t(calculateSerializeBufferSize()), 1);
	if (!chunk) return;
	const char* structType = serialize(chunk->m_oldPtr, serializer);
	serializer->finalizeChunk(chunk, structType, BT_RIGIDBODY_CODE, const_cast<btRigidBody*>(this));
}

namespace
{
// A null serializer is a programming error: asserted, and in release builds reported and ignored.
bool haveSerializer(const btSerializer* serializer, const char* function)
{
	if (serializer) return true;
	btAssert(!"serializing without a serializer");
	btReportWarning((std::string("Caliber: ") + function + ": no serializer given; nothing was written\n").c_str());
	return false;
}
}  // namespace

void btDiscreteDynamicsWorld::serializeRigidBodies(btSerializer* serializer)
{
	if (!haveSerializer(serializer, "btDiscreteDynamicsWorld::serializeRigidBodies")) return;
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		const btCollisionObject* object = m_collisionObjects[i];
		if (object->getInternalType() & btCollisionObject::CO_RIGID_BODY) object->serializeSingleObject(serializer);
	}
	for (int i = 0; i < m_constraints.size(); ++i)
	{
		const btTypedConstraint* constraint = m_constraints[i];
		btChunk* chunk = serializer->allocate(size_t(constraint->calculateSerializeBufferSize()), 1);
		if (!chunk) continue;
		const char* structType = constraint->serialize(chunk->m_oldPtr, serializer);
		serializer->finalizeChunk(chunk, structType, BT_CONSTRAINT_CODE, const_cast<btTypedConstraint*>(constraint));
	}
}

namespace
{
template <class WorldData>
void fillWorldInfo(WorldData& data, const btContactSolverInfo& info, const btVector3& gravity)
{
	gravity.serialize(data.m_gravity);
	auto& s = data.m_solverInfo;
	s.m_tau = info.m_tau;
	s.m_damping = info.m_damping;
	s.m_friction = info.m_friction;
	s.m_timeStep = info.m_timeStep;
	s.m_restitution = info.m_restitution;
	s.m_maxErrorReduction = info.m_maxErrorReduction;
	s.m_sor = info.m_sor;
	s.m_erp = info.m_erp;
	s.m_erp2 = info.m_erp2;
	s.m_globalCfm = info.m_globalCfm;
	s.m_splitImpulsePenetrationThreshold = info.m_splitImpulsePenetrationThreshold;
	s.m_splitImpulseTurnErp = info.m_splitImpulseTurnErp;
	s.m_linearSlop = info.m_linearSlop;
	s.m_warmstartingFactor = info.m_warmstartingFactor;
	s.m_maxGyroscopicForce = info.m_maxGyroscopicForce;
	s.m_singleAxisRollingFrictionThreshold = info.m_singleAxisRollingFrictionThreshold;
	s.m_numIterations = info.m_numIterations;
	s.m_solverMode = info.m_solverMode;
	s.m_restingContactRestitutionThreshold = info.m_restingContactRestitutionThreshold;
	s.m_minimumSolverBatchSize = info.m_minimumSolverBatchSize;
	s.m_splitImpulse = info.m_splitImpulse;
	for (int i = 0; i < 4; ++i) s.m_padding[i] = 0;
}
}  // namespace

void btDiscreteDynamicsWorld::serializeDynamicsWorldInfo(btSerializer* serializer)
{
	if (!haveSerializer(serializer, "btDiscreteDynamicsWorld::serializeDynamicsWorldInfo")) return;
#ifdef BT_USE_DOUBLE_PRECISION
	typedef btDynamicsWorldDoubleData WorldData;
	const char* structType = "btDynamicsWorldDoubleData";
#else
	typedef btDynamicsWorldFloatData WorldData;
	const char* structType = "btDynamicsWorldFloatData";
#endif
	btChunk* chunk = serializer->allocate(sizeof(WorldData), 1);
	if (!chunk) return;
	WorldData* worldInfo = static_cast<WorldData*>(chunk->m_oldPtr);
	fillWorldInfo(*worldInfo, getSolverInfo(), getGravity());
	serializer->finalizeChunk(chunk, structType, BT_DYNAMICSWORLD_CODE, worldInfo);
}

void btDiscreteDynamicsWorld::serialize(btSerializer* serializer)
{
	if (!haveSerializer(serializer, "btDiscreteDynamicsWorld::serialize")) return;
	serializer->startSerialization();
	serializeDynamicsWorldInfo(serializer);
	serializeCollisionObjects(serializer);
	serializeRigidBodies(serializer);
	serializeContactManifolds(serializer);
	serializer->finishSerialization();
}
