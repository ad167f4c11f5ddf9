// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// Writing collision objects and collision worlds into .bullet files (docs/serialization.md).
#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/BroadphaseCollision/btDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btSerializer.h"
#include "LinearMath/btWarningHook.h"

int btCollisionObject::calculateSerializeBufferSize() const { return int(sizeof(btCollisionObjectData)); }

const char* btCollisionObject::serialize(void* dataBuffer, btSerializer* serializer) const
{
	btCollisionObjectData* objectData = static_cast<btCollisionObjectData*>(dataBuffer);
	m_worldTransform.serialize(objectData->m_worldTransform);
	m_interpolationWorldTransform.serialize(objectData->m_interpolationWorldTransform);
	m_interpolationLinearVelocity.serialize(objectData->m_interpolationLinearVelocity);
	m_interpolationAngularVelocity.serialize(objectData->m_interpolationAngularVelocity);
	m_anisotropicFriction.serialize(objectData->m_anisotropicFriction);
	objectData->m_hasAnisotropicFriction = m_hasAnisotropicFriction;
	objectData->m_contactProcessingThreshold = m_contactProcessingThreshold;
	// Run-time links have no meaning in a file.
	objectData->m_broadphaseHandle = 0;
	objectData->m_rootCollisionShape = 0;
	objectData->m_collisionShape = serializer->getUniquePointer(m_collisionShape);
	objectData->m_collisionFlags = m_collisionFlags;
	objectData->m_islandTag1 = m_islandTag1;
	objectData->m_companionId = m_companionId;
	objectData->m_activationState1 = m_activationState1;
	objectData->m_deactivationTime = m_deactivationTime;
	objectData->m_friction = m_friction;
	objectData->m_rollingFriction = m_rollingFriction;
	objectData->m_contactDamping = m_contactDamping;
	objectData->m_contactStiffness = m_contactStiffness;
	objectData->m_restitution = m_restitution;
	objectData->m_internalType = m_internalType;
	const char* name = serializer->findNameForPointer(this);
	objectData->m_name = static_cast<char*>(serializer->getUniquePointer(const_cast<char*>(name)));
	if (objectData->m_name) serializer->serializeName(name);
	objectData->m_hitFraction = m_hitFraction;
	objectData->m_ccdSweptSphereRadius = m_ccdSweptSphereRadius;
	objectData->m_ccdMotionThreshold = m_ccdMotionThreshold;
	objectData->m_checkCollideWith = m_checkCollideWith;
	if (m_broadphaseHandle)
	{
		objectData->m_collisionFilterGroup = m_broadphaseHandle->m_collisionFilterGroup;
		objectData->m_collisionFilterMask = m_broadphaseHandle->m_collisionFilterMask;
		objectData->m_uniqueId = m_broadphaseHandle->m_uniqueId;
	}
	else
	{
		// Not in a world: no filter recorded (a reader then uses its defaults).
		objectData->m_collisionFilterGroup = 0;
		objectData->m_collisionFilterMask = 0;
		objectData->m_uniqueId = -1;
	}
	return btCollisionObjectDataName;
}

void btCollisionObject::serializeSingleObject(btSerializer* serializer) const
{
	btChunk* chunk = serializer->allocate(size_t(calculateSerializeBufferSize()), 1);
	if (!chunk) return;
	const char* structType = serialize(chunk->m_oldPtr, serializer);
	serializer->finalizeChunk(chunk, structType, BT_COLLISIONOBJECT_CODE, const_cast<btCollisionObject*>(this));
}

void btCollisionWorld::serializeCollisionObjects(btSerializer* serializer)
{
	// Shapes first (each once, however many objects share it), then the plain collision objects;
	// rigid bodies and other kinds are written by the worlds that own them.
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		const btCollisionShape* shape = m_collisionObjects[i]->getCollisionShape();
		if (shape) shape->serializeSingleShape(serializer);
	}
	for (int i = 0; i < m_collisionObjects.size(); ++i)
	{
		const btCollisionObject* object = m_collisionObjects[i];
		if (object->getInternalType() == btCollisionObject::CO_COLLISION_OBJECT)
			object->serializeSingleObject(serializer);
	}
}

void btCollisionWorld::serializeContactManifolds(btSerializer* serializer)
{
	if (!(serializer->getSerializationFlags() & BT_SERIALIZE_CONTACT_MANIFOLDS) || !getDispatcher()) return;
	// In the dispatcher's order; the objects are referred to by their ids in the file.
	btDispatcher* dispatcher = getDispatcher();
	for (int i = 0; i < dispatcher->getNumManifolds(); ++i)
	{
		const btPersistentManifold* manifold = dispatcher->getInternalManifoldPointer()[i];
		btChunk* chunk = serializer->allocate(size_t(manifold->calculateSerializeBufferSize()), 1);
		if (!chunk) return;
		const char* structType = manifold->serialize(manifold, chunk->m_oldPtr, serializer);
		serializer->finalizeChunk(chunk, structType, BT_CONTACTMANIFOLD_CODE, const_cast<btPersistentManifold*>(manifold));
	}
}

void btCollisionWorld::serialize(btSerializer* serializer)
{
	if (!serializer)
	{
		// A programming error: asserted, and in release builds reported and ignored.
		btAssert(!"btCollisionWorld::serialize without a serializer");
		btReportWarning("Caliber: btCollisionWorld::serialize: no serializer given; nothing was written\n",
		                getDebugDrawer());
		return;
	}
	serializer->startSerialization();
	serializeCollisionObjects(serializer);
	serializeContactManifolds(serializer);
	serializer->finishSerialization();
}
