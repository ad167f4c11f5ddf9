// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_OBJECT_WRAPPER_H
#define BT_COLLISION_OBJECT_WRAPPER_H

/// btCollisionObjectWrapper: a collision object seen through one of its (child) shapes and transforms.

#include "LinearMath/btScalar.h"
#include "LinearMath/btTransform.h"

class btCollisionShape;
class btCollisionObject;

/// What a collision algorithm sees of one side of a pair: the shape to collide (the object's shape or a
/// child of it), its world transform, the owning object and the part/index of the child. Wrappers live on
/// the stack for the duration of one query and refer to (never own) their data.
struct btCollisionObjectWrapper
{
private:
	btCollisionObjectWrapper(const btCollisionObjectWrapper&) = delete;
	btCollisionObjectWrapper& operator=(const btCollisionObjectWrapper&) = delete;

public:
	/// The wrapper of the enclosing shape (compound parent), or null.
	const btCollisionObjectWrapper* m_parent;
	/// The shape to collide.
	const btCollisionShape* m_shape;
	/// The object the shape belongs to.
	const btCollisionObject* m_collisionObject;
	/// World transform of m_shape (referenced, not copied).
	const btTransform& m_worldTransform;
	/// Optional transform applied before the world transform (null when unused).
	const btTransform* m_preTransform;
	/// Part id of the shape (mesh part or -1).
	int m_partId;
	/// Index of the shape (triangle or compound child, or -1).
	int m_index;

	/// A wrapper of shape on collisionObject placed by worldTransform.
	btCollisionObjectWrapper(const btCollisionObjectWrapper* parent, const btCollisionShape* shape,
	                         const btCollisionObject* collisionObject, const btTransform& worldTransform, int partId,
	                         int index)
	    : m_parent(parent),
	      m_shape(shape),
	      m_collisionObject(collisionObject),
	      m_worldTransform(worldTransform),
	      m_preTransform(0),
	      m_partId(partId),
	      m_index(index)
	{
	}

	/// A wrapper that also records the transform applied before worldTransform (referenced, not copied).
	btCollisionObjectWrapper(const btCollisionObjectWrapper* parent, const btCollisionShape* shape,
	                         const btCollisionObject* collisionObject, const btTransform& worldTransform,
	                         const btTransform& preTransform, int partId, int index)
	    : m_parent(parent),
	      m_shape(shape),
	      m_collisionObject(collisionObject),
	      m_worldTransform(worldTransform),
	      m_preTransform(&preTransform),
	      m_partId(partId),
	      m_index(index)
	{
	}

	/// World transform of the shape.
	SIMD_FORCE_INLINE const btTransform& getWorldTransform() const { return m_worldTransform; }
	/// The owning object.
	SIMD_FORCE_INLINE const btCollisionObject* getCollisionObject() const { return m_collisionObject; }
	/// The shape to collide.
	SIMD_FORCE_INLINE const btCollisionShape* getCollisionShape() const { return m_shape; }
};

#endif  // BT_COLLISION_OBJECT_WRAPPER_H
