// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_COLLISION_OBJECT_H
#define BT_COLLISION_OBJECT_H

/// btCollisionObject: a shape placed in the world, with its material, filtering and activation state.

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMotionState.h"
#include "LinearMath/btTransform.h"

#include "BulletCollision/CollisionShapes/btCollisionShape.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btCollisionObjectData btCollisionObjectDoubleData
#define btCollisionObjectDataName "btCollisionObjectDoubleData"
#else
#define btCollisionObjectData btCollisionObjectFloatData
#define btCollisionObjectDataName "btCollisionObjectFloatData"
#endif

/// Activation state: awake.
#define ACTIVE_TAG 1
/// Activation state: asleep with its island.
#define ISLAND_SLEEPING 2
/// Activation state: resting long enough to be put to sleep.
#define WANTS_DEACTIVATION 3
/// Activation state: never sleeps.
#define DISABLE_DEACTIVATION 4
/// Activation state: excluded from the simulation.
#define DISABLE_SIMULATION 5
/// Activation state: the fixed base of a multibody.
#define FIXED_BASE_MULTI_BODY 6

struct btBroadphaseProxy;
class btCollisionShape;

/// An array of collision objects (the world's object list).
typedef btAlignedObjectArray<class btCollisionObject*> btCollisionObjectArray;

/// A collision shape with a world transform, material (friction, restitution, ...), collision flags,
/// an activation state and the bookkeeping the broadphase, islands and CCD need.
ATTRIBUTE_ALIGNED16(class)
btCollisionObject
{
protected:
	/// Current world transform.
	btTransform m_worldTransform;
	/// Transform at the end of the step, used for motion-state interpolation and CCD.
	btTransform m_interpolationWorldTransform;
	/// Linear velocity used for interpolation.
	btVector3 m_interpolationLinearVelocity;
	/// Angular velocity used for interpolation.
	btVector3 m_interpolationAngularVelocity;
	/// Per-axis friction scaling in the object's frame.
	btVector3 m_anisotropicFriction;
	/// AnisotropicFrictionFlags bits.
	int m_hasAnisotropicFriction;
	/// Distance below which contacts are handed to the solver.
	btScalar m_contactProcessingThreshold;
	/// The broadphase's handle of this object.
	btBroadphaseProxy* m_broadphaseHandle;
	/// The shape used for collision.
	btCollisionShape* m_collisionShape;
	/// Extra data for derived kinds of object (soft bodies, ...).
	void* m_extensionPointer;
	/// The shape given by the user; m_collisionShape may temporarily point at a child.
	btCollisionShape* m_rootCollisionShape;
	/// CollisionFlags bits.
	int m_collisionFlags;
	/// Simulation island of the object.
	int m_islandTag1;
	/// Index used by the solver.
	int m_companionId;
	/// Index in the world's object array.
	int m_worldArrayIndex;
	/// Activation state (ACTIVE_TAG ... FIXED_BASE_MULTI_BODY); mutable as in Bullet.
	mutable int m_activationState1;
	/// Time spent resting; mutable as in Bullet.
	mutable btScalar m_deactivationTime;
	/// Friction coefficient.
	btScalar m_friction;
	/// Restitution coefficient.
	btScalar m_restitution;
	/// Rolling friction coefficient.
	btScalar m_rollingFriction;
	/// Spinning (torsional) friction coefficient.
	btScalar m_spinningFriction;
	/// Contact damping (with CF_HAS_CONTACT_STIFFNESS_DAMPING).
	btScalar m_contactDamping;
	/// Contact stiffness (with CF_HAS_CONTACT_STIFFNESS_DAMPING).
	btScalar m_contactStiffness;
	/// CollisionObjectTypes value of the concrete class.
	int m_internalType;
	/// User data.
	void* m_userObjectPointer;
	/// Second user index.
	int m_userIndex2;
	/// User index.
	int m_userIndex;
	/// Third user index.
	int m_userIndex3;
	/// Time of impact fraction found by CCD.
	btScalar m_hitFraction;
	/// Radius of the sphere swept for CCD.
	btScalar m_ccdSweptSphereRadius;
	/// Motion per step above which CCD is used (0: never).
	btScalar m_ccdMotionThreshold;
	/// Non-zero when checkCollideWithOverride must be called.
	int m_checkCollideWith;
	/// Objects this one never collides with.
	btAlignedObjectArray<const btCollisionObject*> m_objectsWithoutCollisionCheck;
	/// Incremented whenever the shape changes, so caches can notice.
	int m_updateRevision;
	/// Debug draw colour (with CF_HAS_CUSTOM_DEBUG_RENDERING_COLOR).
	btVector3 m_customDebugColorRGB;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Bits of the collision flags.
	enum CollisionFlags
	{
		CF_DYNAMIC_OBJECT = 0,                      ///< Moved by the simulation.
		CF_STATIC_OBJECT = 1,                       ///< Never moves.
		CF_KINEMATIC_OBJECT = 2,                    ///< Moved by the user.
		CF_NO_CONTACT_RESPONSE = 4,                 ///< Reports contacts but is not pushed (triggers).
		CF_CUSTOM_MATERIAL_CALLBACK = 8,            ///< Calls gContactAddedCallback for its contacts.
		CF_CHARACTER_OBJECT = 16,                   ///< A character controller's object.
		CF_DISABLE_VISUALIZE_OBJECT = 32,           ///< Skipped by debug drawing.
		CF_DISABLE_SPU_COLLISION_PROCESSING = 64,   ///< Kept for source compatibility.
		CF_HAS_CONTACT_STIFFNESS_DAMPING = 128,     ///< Contacts use the stiffness and damping.
		CF_HAS_CUSTOM_DEBUG_RENDERING_COLOR = 256,  ///< Debug drawing uses the custom colour.
		CF_HAS_FRICTION_ANCHOR = 512,               ///< Contacts are friction anchors.
		CF_HAS_COLLISION_SOUND_TRIGGER = 1024       ///< Contacts may trigger sounds (user meaning).
	};

	/// Kinds of collision object (getInternalType).
	enum CollisionObjectTypes
	{
		CO_COLLISION_OBJECT = 1,   ///< A plain btCollisionObject.
		CO_RIGID_BODY = 2,         ///< A btRigidBody.
		CO_GHOST_OBJECT = 4,       ///< A btGhostObject.
		CO_SOFT_BODY = 8,          ///< A btSoftBody.
		CO_HF_FLUID = 16,          ///< A height-field fluid.
		CO_USER_TYPE = 32,         ///< A user-defined kind.
		CO_FEATHERSTONE_LINK = 64  ///< A multibody link.
	};

	/// Bits selecting which frictions the anisotropic scaling applies to.
	enum AnisotropicFrictionFlags
	{
		CF_ANISOTROPIC_FRICTION_DISABLED = 0,  ///< No anisotropic friction.
		CF_ANISOTROPIC_FRICTION = 1,           ///< Sliding friction is anisotropic.
		CF_ANISOTROPIC_ROLLING_FRICTION = 2    ///< Rolling friction is anisotropic.
	};

	/// True when contacts with this object may join simulation islands (dynamic, responding objects).
	SIMD_FORCE_INLINE bool mergesSimulationIslands() const
	{
		return (m_collisionFlags & (CF_STATIC_OBJECT | CF_KINEMATIC_OBJECT | CF_NO_CONTACT_RESPONSE)) == 0;
	}

	/// Per-axis friction scaling.
	const btVector3& getAnisotropicFriction() const { return m_anisotropicFriction; }
	/// Sets the friction scaling; all ones disables it.
	void setAnisotropicFriction(const btVector3& anisotropicFriction, int frictionMode = CF_ANISOTROPIC_FRICTION)
	{
		m_anisotropicFriction = anisotropicFriction;
		const bool isUnity = anisotropicFriction[0] == btScalar(1) && anisotropicFriction[1] == btScalar(1) &&
		                     anisotropicFriction[2] == btScalar(1);
		m_hasAnisotropicFriction = isUnity ? CF_ANISOTROPIC_FRICTION_DISABLED : frictionMode;
	}
	/// True when the given friction kind is anisotropic.
	bool hasAnisotropicFriction(int frictionMode = CF_ANISOTROPIC_FRICTION) const
	{
		return (m_hasAnisotropicFriction & frictionMode) != 0;
	}

	/// Sets the distance below which contacts are handed to the solver.
	void setContactProcessingThreshold(btScalar contactProcessingThreshold)
	{
		m_contactProcessingThreshold = contactProcessingThreshold;
	}
	/// Distance below which contacts are handed to the solver.
	btScalar getContactProcessingThreshold() const { return m_contactProcessingThreshold; }

	/// True for static objects.
	SIMD_FORCE_INLINE bool isStaticObject() const { return (m_collisionFlags & CF_STATIC_OBJECT) != 0; }
	/// True for kinematic objects.
	SIMD_FORCE_INLINE bool isKinematicObject() const { return (m_collisionFlags & CF_KINEMATIC_OBJECT) != 0; }
	/// True for static or kinematic objects.
	SIMD_FORCE_INLINE bool isStaticOrKinematicObject() const
	{
		return (m_collisionFlags & (CF_KINEMATIC_OBJECT | CF_STATIC_OBJECT)) != 0;
	}
	/// False for objects with CF_NO_CONTACT_RESPONSE.
	SIMD_FORCE_INLINE bool hasContactResponse() const { return (m_collisionFlags & CF_NO_CONTACT_RESPONSE) == 0; }

	/// A static object with no shape at the origin, friction 0.5, active.
	btCollisionObject();
	/// Objects are deleted through base pointers.
	virtual ~btCollisionObject();

	/// Sets the shape (and the root shape) and bumps the update revision.
	virtual void setCollisionShape(btCollisionShape * collisionShape)
	{
		m_updateRevision++;
		m_collisionShape = collisionShape;
		m_rootCollisionShape = collisionShape;
	}
	/// The collision shape.
	SIMD_FORCE_INLINE const btCollisionShape* getCollisionShape() const { return m_collisionShape; }
	/// The collision shape.
	SIMD_FORCE_INLINE btCollisionShape* getCollisionShape() { return m_collisionShape; }
	/// The shape given to setCollisionShape.
	const btCollisionShape* getRootCollisionShape() const { return m_rootCollisionShape; }
	/// The shape given to setCollisionShape.
	btCollisionShape* getRootCollisionShape() { return m_rootCollisionShape; }
	/// Swaps the shape the narrowphase sees (a compound child, say) without touching the root shape
	/// or the update revision; the caller puts the root shape back when done.
	void internalSetTemporaryCollisionShape(btCollisionShape * collisionShape) { m_collisionShape = collisionShape; }

	/// Adds (true) or removes (false) co from the objects this one never collides with.
	void setIgnoreCollisionCheck(const btCollisionObject* co, bool ignoreCollisionCheck);
	/// Number of objects this one never collides with.
	int getNumObjectsWithoutCollision() const { return m_objectsWithoutCollisionCheck.size(); }
	/// Object at index of the ignore list.
	const btCollisionObject* getObjectWithoutCollision(int index) { return m_objectsWithoutCollisionCheck[index]; }
	/// False when co is on the ignore list; derived classes may refine.
	virtual bool checkCollideWithOverride(const btCollisionObject* co) const;

	/// Extension data of derived kinds (internal).
	void* internalGetExtensionPointer() const { return m_extensionPointer; }
	/// Sets the extension data (internal).
	void internalSetExtensionPointer(void* pointer) { m_extensionPointer = pointer; }

	/// The activation state.
	SIMD_FORCE_INLINE int getActivationState() const { return m_activationState1; }
	/// Sets the activation state unless it is DISABLE_DEACTIVATION or DISABLE_SIMULATION.
	void setActivationState(int newState) const;
	/// Sets the time spent resting.
	void setDeactivationTime(btScalar time) { m_deactivationTime = time; }
	/// Time spent resting.
	btScalar getDeactivationTime() const { return m_deactivationTime; }
	/// Sets the activation state unconditionally.
	void forceActivationState(int newState) const;
	/// Wakes the object (static and kinematic objects only with forceActivation).
	void activate(bool forceActivation = false) const;
	/// True unless asleep, excluded from simulation or a fixed multibody base.
	SIMD_FORCE_INLINE bool isActive() const
	{
		const int state = getActivationState();
		return state != FIXED_BASE_MULTI_BODY && state != ISLAND_SLEEPING && state != DISABLE_SIMULATION;
	}

	/// Sets the restitution coefficient (finite and >= 0; anything else is reported and ignored).
	void setRestitution(btScalar rest);
	/// Restitution coefficient.
	btScalar getRestitution() const { return m_restitution; }
	/// Sets the friction coefficient (finite and >= 0; anything else is reported and ignored).
	void setFriction(btScalar frict);
	/// Friction coefficient.
	btScalar getFriction() const { return m_friction; }
	/// Sets the rolling friction coefficient (finite and >= 0; anything else is reported and ignored).
	void setRollingFriction(btScalar frict);
	/// Rolling friction coefficient.
	btScalar getRollingFriction() const { return m_rollingFriction; }
	/// Sets the spinning friction coefficient (finite and >= 0; anything else is reported and ignored).
	void setSpinningFriction(btScalar frict);
	/// Spinning friction coefficient.
	btScalar getSpinningFriction() const { return m_spinningFriction; }
	/// Sets contact stiffness and damping and turns on CF_HAS_CONTACT_STIFFNESS_DAMPING; a stiffness below
	/// SIMD_EPSILON is raised to SIMD_EPSILON because the combination divides by it. A non-finite value or
	/// a negative damping is reported and the call ignored.
	void setContactStiffnessAndDamping(btScalar stiffness, btScalar damping);
	/// Contact stiffness.
	btScalar getContactStiffness() const { return m_contactStiffness; }
	/// Contact damping.
	btScalar getContactDamping() const { return m_contactDamping; }

	/// CollisionObjectTypes value of the concrete class.
	int getInternalType() const { return m_internalType; }

	/// Current world transform.
	btTransform& getWorldTransform() { return m_worldTransform; }
	/// Current world transform.
	const btTransform& getWorldTransform() const { return m_worldTransform; }
	/// Sets the world transform. A NaN or infinite entry asserts; in release the old transform is kept.
	void setWorldTransform(const btTransform& worldTrans);

	/// The broadphase handle.
	btBroadphaseProxy* getBroadphaseHandle() { return m_broadphaseHandle; }
	/// The broadphase handle.
	const btBroadphaseProxy* getBroadphaseHandle() const { return m_broadphaseHandle; }
	/// Sets the broadphase handle.
	void setBroadphaseHandle(btBroadphaseProxy * handle) { m_broadphaseHandle = handle; }

	/// Transform used for interpolation and CCD.
	const btTransform& getInterpolationWorldTransform() const { return m_interpolationWorldTransform; }
	/// Transform used for interpolation and CCD.
	btTransform& getInterpolationWorldTransform() { return m_interpolationWorldTransform; }
	/// Sets the interpolation transform.
	void setInterpolationWorldTransform(const btTransform& trans)
	{
		m_updateRevision++;
		m_interpolationWorldTransform = trans;
	}
	/// Sets the interpolation linear velocity.
	void setInterpolationLinearVelocity(const btVector3& linvel)
	{
		m_updateRevision++;
		m_interpolationLinearVelocity = linvel;
	}
	/// Sets the interpolation angular velocity.
	void setInterpolationAngularVelocity(const btVector3& angvel)
	{
		m_updateRevision++;
		m_interpolationAngularVelocity = angvel;
	}
	/// Interpolation linear velocity.
	const btVector3& getInterpolationLinearVelocity() const { return m_interpolationLinearVelocity; }
	/// Interpolation angular velocity.
	const btVector3& getInterpolationAngularVelocity() const { return m_interpolationAngularVelocity; }

	/// Simulation island tag.
	SIMD_FORCE_INLINE int getIslandTag() const { return m_islandTag1; }
	/// Sets the island tag.
	void setIslandTag(int tag) { m_islandTag1 = tag; }
	/// Solver companion id.
	SIMD_FORCE_INLINE int getCompanionId() const { return m_companionId; }
	/// Sets the solver companion id.
	void setCompanionId(int id) { m_companionId = id; }
	/// Index in the world's object array.
	SIMD_FORCE_INLINE int getWorldArrayIndex() const { return m_worldArrayIndex; }
	/// Sets the index in the world's object array (world use only).
	void setWorldArrayIndex(int ix) { m_worldArrayIndex = ix; }

	/// Time of impact fraction found by CCD.
	SIMD_FORCE_INLINE btScalar getHitFraction() const { return m_hitFraction; }
	/// Sets the time of impact fraction.
	void setHitFraction(btScalar hitFraction) { m_hitFraction = hitFraction; }

	/// CollisionFlags bits.
	SIMD_FORCE_INLINE int getCollisionFlags() const { return m_collisionFlags; }
	/// Sets the CollisionFlags bits.
	void setCollisionFlags(int flags) { m_collisionFlags = flags; }

	/// Radius of the sphere swept for CCD.
	btScalar getCcdSweptSphereRadius() const { return m_ccdSweptSphereRadius; }
	/// Sets the radius of the sphere swept for CCD (finite and >= 0; anything else is reported and ignored).
	void setCcdSweptSphereRadius(btScalar radius);
	/// Motion per step above which CCD is used.
	btScalar getCcdMotionThreshold() const { return m_ccdMotionThreshold; }
	/// Square of the CCD motion threshold.
	btScalar getCcdSquareMotionThreshold() const { return m_ccdMotionThreshold * m_ccdMotionThreshold; }
	/// Sets the motion per step above which CCD is used (0 disables CCD; finite and >= 0, anything else is
	/// reported and ignored).
	void setCcdMotionThreshold(btScalar ccdMotionThreshold);

	/// User pointer.
	void* getUserPointer() const { return m_userObjectPointer; }
	/// User index.
	int getUserIndex() const { return m_userIndex; }
	/// Second user index.
	int getUserIndex2() const { return m_userIndex2; }
	/// Third user index.
	int getUserIndex3() const { return m_userIndex3; }
	/// Sets the user pointer.
	void setUserPointer(void* userPointer) { m_userObjectPointer = userPointer; }
	/// Sets the user index.
	void setUserIndex(int index) { m_userIndex = index; }
	/// Sets the second user index.
	void setUserIndex2(int index) { m_userIndex2 = index; }
	/// Sets the third user index.
	void setUserIndex3(int index) { m_userIndex3 = index; }

	/// Counter bumped by changes that invalidate cached data.
	int getUpdateRevisionInternal() const { return m_updateRevision; }

	/// Sets the debug draw colour and turns on CF_HAS_CUSTOM_DEBUG_RENDERING_COLOR.
	void setCustomDebugColor(const btVector3& colorRGB)
	{
		m_customDebugColorRGB = colorRGB;
		m_collisionFlags |= CF_HAS_CUSTOM_DEBUG_RENDERING_COLOR;
	}
	/// Turns off the custom debug colour.
	void removeCustomDebugColor() { m_collisionFlags &= ~CF_HAS_CUSTOM_DEBUG_RENDERING_COLOR; }
	/// Writes the custom debug colour and returns true when one is set.
	bool getCustomDebugColor(btVector3 & colorRGB) const
	{
		const bool hasCustomColor = (m_collisionFlags & CF_HAS_CUSTOM_DEBUG_RENDERING_COLOR) != 0;
		if (hasCustomColor) colorRGB = m_customDebugColorRGB;
		return hasCustomColor;
	}

	/// False when co is on the ignore list (checked only when the list is not empty).
	inline bool checkCollideWith(const btCollisionObject* co) const
	{
		if (m_checkCollideWith) return checkCollideWithOverride(co);
		return true;
	}

public:
	/// Bytes of btCollisionObjectData (float or double as the build).
	virtual int calculateSerializeBufferSize() const;
	/// Writes the object's data struct into dataBuffer and returns the struct's name.
	virtual const char* serialize(void* dataBuffer, class btSerializer* serializer) const;
	/// Writes the object as a chunk of its own (its shape is written separately).
	virtual void serializeSingleObject(class btSerializer * serializer) const;
};

// clang-format off
/// File layout of btCollisionObjectDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCollisionObjectDoubleData
{
	void* m_broadphaseHandle;
	void* m_collisionShape;
	btCollisionShapeData* m_rootCollisionShape;
	char* m_name;
	btTransformDoubleData m_worldTransform;
	btTransformDoubleData m_interpolationWorldTransform;
	btVector3DoubleData m_interpolationLinearVelocity;
	btVector3DoubleData m_interpolationAngularVelocity;
	btVector3DoubleData m_anisotropicFriction;
	double m_contactProcessingThreshold;
	double m_deactivationTime;
	double m_friction;
	double m_rollingFriction;
	double m_contactDamping;
	double m_contactStiffness;
	double m_restitution;
	double m_hitFraction;
	double m_ccdSweptSphereRadius;
	double m_ccdMotionThreshold;
	int m_hasAnisotropicFriction;
	int m_collisionFlags;
	int m_islandTag1;
	int m_companionId;
	int m_activationState1;
	int m_internalType;
	int m_checkCollideWith;
	int m_collisionFilterGroup;
	int m_collisionFilterMask;
	int m_uniqueId;
};

/// File layout of btCollisionObjectFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btCollisionObjectFloatData
{
	void* m_broadphaseHandle;
	void* m_collisionShape;
	btCollisionShapeData* m_rootCollisionShape;
	char* m_name;
	btTransformFloatData m_worldTransform;
	btTransformFloatData m_interpolationWorldTransform;
	btVector3FloatData m_interpolationLinearVelocity;
	btVector3FloatData m_interpolationAngularVelocity;
	btVector3FloatData m_anisotropicFriction;
	float m_contactProcessingThreshold;
	float m_deactivationTime;
	float m_friction;
	float m_rollingFriction;
	float m_contactDamping;
	float m_contactStiffness;
	float m_restitution;
	float m_hitFraction;
	float m_ccdSweptSphereRadius;
	float m_ccdMotionThreshold;
	int m_hasAnisotropicFriction;
	int m_collisionFlags;
	int m_islandTag1;
	int m_companionId;
	int m_activationState1;
	int m_internalType;
	int m_checkCollideWith;
	int m_collisionFilterGroup;
	int m_collisionFilterMask;
	int m_uniqueId;
};

// clang-format on

#endif  // BT_COLLISION_OBJECT_H
