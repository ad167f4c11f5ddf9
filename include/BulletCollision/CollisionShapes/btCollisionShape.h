// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_SHAPE_H
#define BT_COLLISION_SHAPE_H

#include "LinearMath/btScalar.h"
#include "LinearMath/btVector3.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btMatrix3x3.h"
#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"

class btSerializer;

/// The abstract base of every collision shape: bounds, classification, scaling, margin and inertia.
/// Shapes are defined in their own local frame; a transform places them in the world.
ATTRIBUTE_ALIGNED16(class)
btCollisionShape
{
protected:
	/// One of BroadphaseNativeTypes, set by the concrete shape's constructor.
	int m_shapeType;
	/// Free for the user.
	void* m_userPointer;
	/// Free for the user (-1 by default).
	int m_userIndex;
	/// Free for the user (-1 by default).
	int m_userIndex2;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A shape of type INVALID_SHAPE_PROXYTYPE until the derived constructor sets its type.
	btCollisionShape() : m_shapeType(INVALID_SHAPE_PROXYTYPE), m_userPointer(0), m_userIndex(-1), m_userIndex2(-1) {}
	/// Shapes are deleted through base pointers.
	virtual ~btCollisionShape() {}

	/// The world AABB of the shape (margin included) under transform t. Every shape of Caliber returns a
	/// finite box: a transform with a NaN or infinite entry asserts, and in release builds gives the box
	/// [-BT_LARGE_FLOAT, BT_LARGE_FLOAT]^3, which the collision world reports as an AABB overflow.
	virtual void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const = 0;

	/// A sphere containing the shape: the sphere around its local AABB (identity transform).
	virtual void getBoundingSphere(btVector3 & center, btScalar & radius) const;

	/// The distance from the local origin to the farthest point of the shape's bounding sphere; rotating
	/// the shape by an angle a moves no point further than a times this disc.
	virtual btScalar getAngularMotionDisc() const;

	/// getAngularMotionDisc() * defaultContactThresholdFactor: the distance at which contacts break.
	virtual btScalar getContactBreakingThreshold(btScalar defaultContactThresholdFactor) const;

	/// The AABB swept over timeStep by linear velocity linvel and angular velocity angvel from curTrans:
	/// the AABB at curTrans grown on the side of motion by linvel * timeStep, and on every side by
	/// |angvel| * timeStep * getAngularMotionDisc() (a conservative bound of the rotation). Non-finite
	/// motion asserts; in release builds non-finite (or negative angular) growth terms are ignored.
	void calculateTemporalAabb(const btTransform& curTrans, const btVector3& linvel, const btVector3& angvel,
	                           btScalar timeStep, btVector3& temporalAabbMin, btVector3& temporalAabbMax) const;

	/// True for polyhedral shapes (box, triangle, hulls).
	SIMD_FORCE_INLINE bool isPolyhedral() const { return btBroadphaseProxy::isPolyhedral(getShapeType()); }
	/// True for the 2D convex shapes.
	SIMD_FORCE_INLINE bool isConvex2d() const { return btBroadphaseProxy::isConvex2d(getShapeType()); }
	/// True for convex shapes.
	SIMD_FORCE_INLINE bool isConvex() const { return btBroadphaseProxy::isConvex(getShapeType()); }
	/// True for concave shapes that never move.
	SIMD_FORCE_INLINE bool isNonMoving() const { return btBroadphaseProxy::isNonMoving(getShapeType()); }
	/// True for concave shapes.
	SIMD_FORCE_INLINE bool isConcave() const { return btBroadphaseProxy::isConcave(getShapeType()); }
	/// True for compound shapes.
	SIMD_FORCE_INLINE bool isCompound() const { return btBroadphaseProxy::isCompound(getShapeType()); }
	/// True for soft body shapes.
	SIMD_FORCE_INLINE bool isSoftBody() const { return btBroadphaseProxy::isSoftBody(getShapeType()); }
	/// True for shapes of unbounded extent (the static plane).
	SIMD_FORCE_INLINE bool isInfinite() const { return btBroadphaseProxy::isInfinite(getShapeType()); }

	/// Scales the shape along its local axes.
	virtual void setLocalScaling(const btVector3& scaling) = 0;
	/// The local scaling.
	virtual const btVector3& getLocalScaling() const = 0;
	/// The diagonal of the inertia tensor of a solid of this shape with the given mass.
	virtual void calculateLocalInertia(btScalar mass, btVector3 & inertia) const = 0;
	/// A short name of the shape kind, as Bullet spells it ("Box", "SPHERE", "CapsuleShape", ...).
	virtual const char* getName() const = 0;

	/// The shape type, one of BroadphaseNativeTypes.
	int getShapeType() const { return m_shapeType; }

	/// The direction in which rolling friction acts (all axes by default).
	virtual btVector3 getAnisotropicRollingFrictionDirection() const { return btVector3(1, 1, 1); }

	/// Sets the collision margin.
	virtual void setMargin(btScalar margin) = 0;
	/// The collision margin.
	virtual btScalar getMargin() const = 0;

	/// Sets the user pointer.
	void setUserPointer(void* userPtr) { m_userPointer = userPtr; }
	/// The user pointer.
	void* getUserPointer() const { return m_userPointer; }
	/// Sets the user index.
	void setUserIndex(int index) { m_userIndex = index; }
	/// The user index.
	int getUserIndex() const { return m_userIndex; }
	/// Sets the second user index.
	void setUserIndex2(int index) { m_userIndex2 = index; }
	/// The second user index.
	int getUserIndex2() const { return m_userIndex2; }

public:
	/// Bytes of the data struct serialize() writes (docs/serialization.md).
	virtual int calculateSerializeBufferSize() const;
	/// Writes the shape's data struct into dataBuffer (calculateSerializeBufferSize() bytes) and returns
	/// the struct's name; sub-objects (children, points, meshes) become chunks of their own.
	virtual const char* serialize(void* dataBuffer, btSerializer* serializer) const;
	/// Writes the shape as a chunk of its own (once: a shape already written is skipped).
	virtual void serializeSingleShape(btSerializer * serializer) const;
};

// clang-format off
/// File layout of btCollisionShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCollisionShapeData
{
	char* m_name;
	int m_shapeType;
	char m_padding[4];
};

// clang-format on

#endif  // BT_COLLISION_SHAPE_H
