// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COMPOUND_SHAPE_H
#define BT_COMPOUND_SHAPE_H

#include "BulletCollision/CollisionShapes/btCollisionShape.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

struct btDbvt;
struct btDbvtNode;

/// One child of a compound shape: a shape (not owned) placed by a transform in the compound's frame.
ATTRIBUTE_ALIGNED16(struct)
btCompoundShapeChild
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// The child's placement in the compound's local frame.
	btTransform m_transform;
	/// The child's shape (owned by the caller).
	btCollisionShape* m_childShape;
	/// m_childShape->getShapeType(), cached.
	int m_childShapeType;
	/// The child's margin when it was added.
	btScalar m_childMargin;
	/// The child's leaf in the compound's AABB tree (its dataAsInt is the child's index), 0 without a tree.
	btDbvtNode* m_node;
};

/// True when both children have the same transform, shape, type and margin.
SIMD_FORCE_INLINE bool operator==(const btCompoundShapeChild& c1, const btCompoundShapeChild& c2)
{
	return c1.m_transform == c2.m_transform && c1.m_childShape == c2.m_childShape &&
	       c1.m_childShapeType == c2.m_childShapeType && c1.m_childMargin == c2.m_childMargin;
}

/// A shape made of other shapes, each placed by a local transform. The children's AABBs in the compound's
/// frame live in a dynamic AABB tree (btDbvt) whose leaves carry the child index, so collision against a
/// compound of many children visits only the children near the other object.
/// Bad input: a null child shape asserts and is ignored; a child transform with a NaN or infinite entry
/// asserts and the child is not added (release builds); an index out of range asserts and the call does
/// nothing. An empty compound has the local AABB [0, 0]^3 (a point at its origin, grown by the margin),
/// zero inertia, and an identity principal transform.
ATTRIBUTE_ALIGNED16(class)
btCompoundShape : public btCollisionShape
{
protected:
	/// The children, in insertion order (removal moves the last child into the hole).
	btAlignedObjectArray<btCompoundShapeChild> m_children;
	/// The local AABB of all children (each with its own margin, without the compound's margin).
	btVector3 m_localAabbMin;
	/// Upper corner of the local AABB.
	btVector3 m_localAabbMax;
	/// The children's AABB tree, or 0 when disabled.
	btDbvt* m_dynamicAabbTree;
	/// Increased whenever a child is added or removed (collision algorithms rebuild their caches then).
	int m_updateRevision;
	/// The compound's own margin (0 by default), added around the children's AABB.
	btScalar m_collisionMargin;
	/// The scaling applied so far (child origins and child shapes are scaled by it).
	btVector3 m_localScaling;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// An empty compound, with an AABB tree of its children unless enableDynamicAabbTree is false.
	explicit btCompoundShape(bool enableDynamicAabbTree = true, const int initialChildCapacity = 0);
	/// Frees the tree (not the child shapes).
	virtual ~btCompoundShape();

	/// Adds shape (not owned) at localTransform.
	void addChildShape(const btTransform& localTransform, btCollisionShape* shape);
	/// Removes every child whose shape is shape.
	virtual void removeChildShape(btCollisionShape * shape);
	/// Removes one child; the last child takes its index.
	void removeChildShapeByIndex(int childShapeindex);
	/// The number of children.
	int getNumChildShapes() const { return m_children.size(); }
	/// The shape of child index (0 when out of range, after an assert).
	btCollisionShape* getChildShape(int index);
	/// The shape of child index (0 when out of range, after an assert).
	const btCollisionShape* getChildShape(int index) const;
	/// The transform of child index (an out-of-range index asserts and gives an identity transform).
	btTransform& getChildTransform(int index);
	/// The transform of child index (an out-of-range index asserts and gives an identity transform).
	const btTransform& getChildTransform(int index) const;
	/// Moves child childIndex, updates its leaf in the tree and, unless told not to, the local AABB.
	void updateChildTransform(int childIndex, const btTransform& newChildTransform,
	                          bool shouldRecalculateLocalAabb = true);
	/// The children array (0 when empty).
	btCompoundShapeChild* getChildList() { return m_children.size() ? &m_children[0] : 0; }

	/// The world AABB: the local AABB grown by the margin, transformed by t (exact for the box).
	void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
	/// Recomputes the local AABB as the union of the children's AABBs.
	virtual void recalculateLocalAabb();
	/// Scales the children's origins and the children's own scaling by scaling / (the previous scaling).
	/// Components that are zero or not finite assert and the call is ignored (release builds).
	void setLocalScaling(const btVector3& scaling) override;
	/// The scaling.
	const btVector3& getLocalScaling() const override { return m_localScaling; }
	/// Bullet's approximation, kept for compatibility: the inertia of a solid box of the local AABB's size
	/// (margin included). Use calculatePrincipalAxisTransform for the exact tensor of the children.
	void calculateLocalInertia(btScalar mass, btVector3 & inertia) const override;
	/// Sets the compound's margin (grows the AABB; the children keep theirs).
	void setMargin(btScalar margin) override { m_collisionMargin = margin; }
	/// The compound's margin.
	btScalar getMargin() const override { return m_collisionMargin; }
	/// "Compound".
	const char* getName() const override { return "Compound"; }

	/// The AABB tree of the children (0 when disabled).
	const btDbvt* getDynamicAabbTree() const { return m_dynamicAabbTree; }
	/// The AABB tree of the children (0 when disabled).
	btDbvt* getDynamicAabbTree() { return m_dynamicAabbTree; }
	/// Creates the AABB tree of the children when there is none.
	void createAabbTreeFromChildren();

	/// The centre of mass and principal axes of the children with the given masses (one per child), and
	/// the principal moments: principal maps the principal frame to the compound frame (its origin is the
	/// centre of mass). Each child's inertia comes from its own calculateLocalInertia, rotated into the
	/// compound frame and moved to the centre of mass by the parallel axis theorem; the sum is diagonalised.
	/// Negative or non-finite masses, a null masses pointer or a zero total mass assert and give the identity
	/// and zero inertia (an empty compound gives them without asserting).
	void calculatePrincipalAxisTransform(const btScalar* masses, btTransform& principal, btVector3& inertia) const;

	/// The revision, increased by every addition or removal of a child.
	int getUpdateRevision() const { return m_updateRevision; }

	/// Bytes of the data struct serialize() writes.
	int calculateSerializeBufferSize() const override;
	/// Writes the shape's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btCompoundShapeChildData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCompoundShapeChildData
{
	btTransformFloatData m_transform;
	btCollisionShapeData* m_childShape;
	int m_childShapeType;
	float m_childMargin;
};

/// File layout of btCompoundShapeData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCompoundShapeData
{
	btCollisionShapeData m_collisionShapeData;
	btCompoundShapeChildData* m_childShapePtr;
	int m_numChildShapes;
	float m_collisionMargin;
};

// clang-format on

#endif  // BT_COMPOUND_SHAPE_H
