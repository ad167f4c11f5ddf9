// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_RIGIDBODY_H
#define BT_RIGIDBODY_H

#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btTransform.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btRigidBodyData btRigidBodyDoubleData
#define btRigidBodyDataName "btRigidBodyDoubleData"
#else
#define btRigidBodyData btRigidBodyFloatData
#define btRigidBodyDataName "btRigidBodyFloatData"
#endif

class btCollisionShape;
class btMotionState;
class btTypedConstraint;

/// Seconds a body must stay below its sleeping thresholds before its island may sleep (Bullet: 2).
extern btScalar gDeactivationTime;
/// When true no body ever sleeps.
extern bool gDisableDeactivation;

/// btRigidBody::setFlags bits.
enum btRigidBodyFlags
{
	/// The world's gravity is not given to this body (addRigidBody, setGravity on the world).
	BT_DISABLE_WORLD_GRAVITY = 1,
	/// Gyroscopic torque applied explicitly (can gain energy; clamped by m_maxGyroscopicForce).
	BT_ENABLE_GYROSCOPIC_FORCE_EXPLICIT = 2,
	/// Gyroscopic term integrated implicitly in world space.
	BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_WORLD = 4,
	/// Gyroscopic term integrated implicitly in body space (stable; Bullet's default).
	BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY = 8,
	BT_ENABLE_GYROPSCOPIC_FORCE = BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY,
};

/// A rigid body: mass and inertia, velocities, accumulated forces, damping and sleeping thresholds, on
/// top of a btCollisionObject whose world transform is the centre-of-mass frame. Mass 0 makes a static
/// body (CF_STATIC_OBJECT); CF_KINEMATIC_OBJECT with mass 0 makes a kinematic one, driven by its
/// motion state. Bad input (negative or non-finite mass or inertia, non-finite forces, impulses or
/// velocities) asserts; release builds treat a bad mass as 0 (static), a bad inertia component as
/// infinite (no rotation about that axis), and ignore the bad force, impulse or velocity.
ATTRIBUTE_ALIGNED16(class)
btRigidBody : public btCollisionObject
{
	btMatrix3x3 m_invInertiaTensorWorld;
	btVector3 m_linearVelocity;
	btVector3 m_angularVelocity;
	btScalar m_inverseMass;
	btVector3 m_linearFactor;

	/// Gravity force (mass * acceleration) and the acceleration it came from.
	btVector3 m_gravity;
	btVector3 m_gravity_acceleration;
	btVector3 m_invInertiaLocal;
	btVector3 m_totalForce;
	btVector3 m_totalTorque;

	btScalar m_linearDamping;
	btScalar m_angularDamping;

	bool m_additionalDamping;
	btScalar m_additionalDampingFactor;
	btScalar m_additionalLinearDampingThresholdSqr;
	btScalar m_additionalAngularDampingThresholdSqr;
	btScalar m_additionalAngularDampingFactor;

	btScalar m_linearSleepingThreshold;
	btScalar m_angularSleepingThreshold;

	btMotionState* m_optionalMotionState;
	btAlignedObjectArray<btTypedConstraint*> m_constraintRefs;

	int m_rigidbodyFlags;
	int m_debugBodyId;

protected:
	btVector3 m_deltaLinearVelocity;
	btVector3 m_deltaAngularVelocity;
	btVector3 m_angularFactor;
	/// Inverse mass per axis (inverse mass times the linear factor).
	btVector3 m_invMass;
	/// Split-impulse velocities: move the body out of penetration without changing its velocity.
	btVector3 m_pushVelocity;
	btVector3 m_turnVelocity;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Everything needed to make a body; mass 0 makes it static. The defaults are Bullet's.
	struct btRigidBodyConstructionInfo
	{
		btScalar m_mass;
		/// When set, the body's start transform is read from it (m_startWorldTransform is ignored).
		btMotionState* m_motionState;
		btTransform m_startWorldTransform;
		btCollisionShape* m_collisionShape;
		btVector3 m_localInertia;
		btScalar m_linearDamping;
		btScalar m_angularDamping;
		btScalar m_friction;
		btScalar m_rollingFriction;
		btScalar m_spinningFriction;
		btScalar m_restitution;
		btScalar m_linearSleepingThreshold;
		btScalar m_angularSleepingThreshold;
		bool m_additionalDamping;
		btScalar m_additionalDampingFactor;
		btScalar m_additionalLinearDampingThresholdSqr;
		btScalar m_additionalAngularDampingThresholdSqr;
		btScalar m_additionalAngularDampingFactor;

		btRigidBodyConstructionInfo(btScalar mass, btMotionState* motionState, btCollisionShape* collisionShape,
		                            const btVector3& localInertia = btVector3(0, 0, 0))
		    : m_mass(mass),
		      m_motionState(motionState),
		      m_collisionShape(collisionShape),
		      m_localInertia(localInertia),
		      m_linearDamping(btScalar(0)),
		      m_angularDamping(btScalar(0)),
		      m_friction(btScalar(0.5)),
		      m_rollingFriction(btScalar(0)),
		      m_spinningFriction(btScalar(0)),
		      m_restitution(btScalar(0)),
		      m_linearSleepingThreshold(btScalar(0.8)),
		      m_angularSleepingThreshold(btScalar(1)),
		      m_additionalDamping(false),
		      m_additionalDampingFactor(btScalar(0.005)),
		      m_additionalLinearDampingThresholdSqr(btScalar(0.01)),
		      m_additionalAngularDampingThresholdSqr(btScalar(0.01)),
		      m_additionalAngularDampingFactor(btScalar(0.01))
		{
			m_startWorldTransform.setIdentity();
		}
	};

	btRigidBody(const btRigidBodyConstructionInfo& constructionInfo);
	btRigidBody(btScalar mass, btMotionState * motionState, btCollisionShape * collisionShape,
	            const btVector3& localInertia = btVector3(0, 0, 0));

	/// A body still referenced by constraints asserts (remove the constraints first).
	virtual ~btRigidBody();

	/// Moves the body to newTrans (the end of a step): interpolation frame, transform and inertia.
	void proceedToTransform(const btTransform& newTrans);

	/// The body, or 0 when colObj is not a rigid body.
	static const btRigidBody* upcast(const btCollisionObject* colObj)
	{
		return colObj && (colObj->getInternalType() & CO_RIGID_BODY) ? static_cast<const btRigidBody*>(colObj) : 0;
	}
	static btRigidBody* upcast(btCollisionObject * colObj)
	{
		return colObj && (colObj->getInternalType() & CO_RIGID_BODY) ? static_cast<btRigidBody*>(colObj) : 0;
	}

	/// Where the body would be after step seconds at its current velocities.
	void predictIntegratedTransform(btScalar step, btTransform & predictedTransform);

	/// Kinematic bodies: reads the motion state and derives the velocities of the move since the last call.
	void saveKinematicState(btScalar step);

	/// Adds the gravity force to the accumulated force (dynamic bodies only).
	void applyGravity();
	/// Takes the gravity force back out of the accumulated force.
	void clearGravity();

	/// Gravity acceleration of this body.
	void setGravity(const btVector3& acceleration);
	const btVector3& getGravity() const { return m_gravity_acceleration; }

	/// Damping fractions per second, clamped to [0, 1] (a non-finite value is reported and the call ignored).
	void setDamping(btScalar lin_damping, btScalar ang_damping);
	btScalar getLinearDamping() const { return m_linearDamping; }
	btScalar getAngularDamping() const { return m_angularDamping; }
	btScalar getLinearSleepingThreshold() const { return m_linearSleepingThreshold; }
	btScalar getAngularSleepingThreshold() const { return m_angularSleepingThreshold; }

	/// Scales the velocities by (1 - damping)^timeStep, plus the additional damping when enabled.
	void applyDamping(btScalar timeStep);

	SIMD_FORCE_INLINE const btCollisionShape* getCollisionShape() const { return m_collisionShape; }
	SIMD_FORCE_INLINE btCollisionShape* getCollisionShape() { return m_collisionShape; }

	/// Mass 0 makes the body static; inertia is the diagonal of the local inertia tensor.
	void setMassProps(btScalar mass, const btVector3& inertia);

	const btVector3& getLinearFactor() const { return m_linearFactor; }
	/// Per-axis scale of linear motion (0 locks an axis; negative or non-finite: reported, ignored).
	void setLinearFactor(const btVector3& linearFactor);

	btScalar getInvMass() const { return m_inverseMass; }
	btScalar getMass() const { return m_inverseMass == btScalar(0) ? btScalar(0) : btScalar(1) / m_inverseMass; }
	const btMatrix3x3& getInvInertiaTensorWorld() const { return m_invInertiaTensorWorld; }

	/// Adds the accumulated force and torque, times step, to the velocities (dynamic bodies only); the
	/// angular speed is then limited to a quarter turn per step.
	void integrateVelocities(btScalar step);

	/// Teleports the body (and its interpolation frame, unless kinematic).
	void setCenterOfMassTransform(const btTransform& xform);

	void applyCentralForce(const btVector3& force);
	const btVector3& getTotalForce() const { return m_totalForce; }
	const btVector3& getTotalTorque() const { return m_totalTorque; }

	const btVector3& getInvInertiaDiagLocal() const { return m_invInertiaLocal; }
	void setInvInertiaDiagLocal(const btVector3& diagInvInertia) { m_invInertiaLocal = diagInvInertia; }

	void setSleepingThresholds(btScalar linear, btScalar angular)
	{
		m_linearSleepingThreshold = linear;
		m_angularSleepingThreshold = angular;
	}

	void applyTorque(const btVector3& torque);
	/// A force at rel_pos (from the centre of mass, world axes).
	void applyForce(const btVector3& force, const btVector3& rel_pos);
	void applyCentralImpulse(const btVector3& impulse);
	void applyTorqueImpulse(const btVector3& torque);
	/// An impulse at rel_pos (from the centre of mass, world axes).
	void applyImpulse(const btVector3& impulse, const btVector3& rel_pos);

	/// Split-impulse counterparts: change the push and turn velocities only.
	void applyPushImpulse(const btVector3& impulse, const btVector3& rel_pos);
	btVector3 getPushVelocity() const { return m_pushVelocity; }
	btVector3 getTurnVelocity() const { return m_turnVelocity; }
	void setPushVelocity(const btVector3& v) { m_pushVelocity = v; }
	void setTurnVelocity(const btVector3& v) { m_turnVelocity = v; }
	void applyCentralPushImpulse(const btVector3& impulse)
	{
		m_pushVelocity += impulse * m_linearFactor * m_inverseMass;
	}
	void applyTorqueTurnImpulse(const btVector3& torque)
	{
		m_turnVelocity += m_invInertiaTensorWorld * torque * m_angularFactor;
	}

	/// Zeroes the accumulated force and torque.
	void clearForces()
	{
		m_totalForce.setValue(btScalar(0), btScalar(0), btScalar(0));
		m_totalTorque.setValue(btScalar(0), btScalar(0), btScalar(0));
	}

	/// Recomputes the world inverse inertia from the orientation: R diag(invInertiaLocal) R^T.
	void updateInertiaTensor();

	const btVector3& getCenterOfMassPosition() const { return m_worldTransform.getOrigin(); }
	btQuaternion getOrientation() const;
	const btTransform& getCenterOfMassTransform() const { return m_worldTransform; }
	const btVector3& getLinearVelocity() const { return m_linearVelocity; }
	const btVector3& getAngularVelocity() const { return m_angularVelocity; }

	void setLinearVelocity(const btVector3& lin_vel);
	void setAngularVelocity(const btVector3& ang_vel);

	/// Velocity of the point at rel_pos from the centre of mass.
	btVector3 getVelocityInLocalPoint(const btVector3& rel_pos) const
	{
		return m_linearVelocity + m_angularVelocity.cross(rel_pos);
	}
	btVector3 getPushVelocityInLocalPoint(const btVector3& rel_pos) const
	{
		return m_pushVelocity + m_turnVelocity.cross(rel_pos);
	}

	void translate(const btVector3& v) { m_worldTransform.getOrigin() += v; }

	/// The shape's AABB at the body's transform.
	void getAabb(btVector3 & aabbMin, btVector3 & aabbMax) const;

	/// 1 / effective mass of an impulse along normal at world point pos.
	btScalar computeImpulseDenominator(const btVector3& pos, const btVector3& normal) const;
	/// 1 / effective inertia of an angular impulse about axis.
	btScalar computeAngularImpulseDenominator(const btVector3& axis) const;

	/// Accumulates the time spent below the sleeping thresholds (resets it when above).
	void updateDeactivation(btScalar timeStep);
	/// True when the body has been still long enough to sleep (never with DISABLE_DEACTIVATION).
	bool wantsSleeping();

	const btBroadphaseProxy* getBroadphaseProxy() const { return m_broadphaseHandle; }
	btBroadphaseProxy* getBroadphaseProxy() { return m_broadphaseHandle; }
	void setNewBroadphaseProxy(btBroadphaseProxy * broadphaseProxy) { m_broadphaseHandle = broadphaseProxy; }

	btMotionState* getMotionState() { return m_optionalMotionState; }
	const btMotionState* getMotionState() const { return m_optionalMotionState; }
	/// Also reads the body's transform from the new motion state.
	void setMotionState(btMotionState * motionState);

	/// Solver selection hints (unused by Caliber's solver; kept for source compatibility).
	int m_contactSolverType;
	int m_frictionSolverType;

	/// Per-axis scale of rotation (0 locks an axis; negative or non-finite: reported, ignored).
	void setAngularFactor(const btVector3& angFac);
	void setAngularFactor(btScalar angFac);
	const btVector3& getAngularFactor() const { return m_angularFactor; }

	/// True once the body has a broadphase proxy (it is in a world).
	bool isInWorld() const { return getBroadphaseProxy() != 0; }

	/// Constraint bookkeeping: each constraint registers itself with both of its bodies.
	void addConstraintRef(btTypedConstraint * c);
	void removeConstraintRef(btTypedConstraint * c);
	btTypedConstraint* getConstraintRef(int index) { return m_constraintRefs[index]; }
	int getNumConstraintRefs() const { return m_constraintRefs.size(); }
	/// False for a body linked to this one by an enabled joint that disables collisions between them.
	bool checkCollideWithOverride(const btCollisionObject* co) const override;

	void setFlags(int flags) { m_rigidbodyFlags = flags; }
	int getFlags() const { return m_rigidbodyFlags; }

	/// Change of angular velocity over dt from the gyroscopic term, integrated implicitly in world space.
	btVector3 computeGyroscopicImpulseImplicit_World(btScalar dt) const;
	/// Change of angular velocity over step from the gyroscopic term, integrated implicitly in body space.
	btVector3 computeGyroscopicImpulseImplicit_Body(btScalar step) const;
	/// The gyroscopic torque omega x (I omega), its length clamped to maxGyroscopicForce.
	btVector3 computeGyroscopicForceExplicit(btScalar maxGyroscopicForce) const;
	/// Diagonal of the local inertia tensor (0 where the inverse is 0).
	btVector3 getLocalInertia() const;

	/// Solver scratch (used between a solver's setup and write-back).
	btVector3& internalGetDeltaLinearVelocity() { return m_deltaLinearVelocity; }
	btVector3& internalGetDeltaAngularVelocity() { return m_deltaAngularVelocity; }
	const btVector3& internalGetInvMass() const { return m_invMass; }
	btVector3& internalGetPushVelocity() { return m_pushVelocity; }
	btVector3& internalGetTurnVelocity() { return m_turnVelocity; }

private:
	void setupRigidBody(const btRigidBodyConstructionInfo& constructionInfo);

public:
	/// Bytes of btRigidBodyData (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the body's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, class btSerializer* serializer) const override;
	/// Writes the body as a chunk of its own (its shape is written separately).
	void serializeSingleObject(class btSerializer * serializer) const override;
};

// clang-format off
/// File layout of btRigidBodyFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btRigidBodyFloatData
{
	btCollisionObjectFloatData m_collisionObjectData;
	btMatrix3x3FloatData m_invInertiaTensorWorld;
	btVector3FloatData m_linearVelocity;
	btVector3FloatData m_angularVelocity;
	btVector3FloatData m_angularFactor;
	btVector3FloatData m_linearFactor;
	btVector3FloatData m_gravity;
	btVector3FloatData m_gravity_acceleration;
	btVector3FloatData m_invInertiaLocal;
	btVector3FloatData m_totalForce;
	btVector3FloatData m_totalTorque;
	float m_inverseMass;
	float m_linearDamping;
	float m_angularDamping;
	float m_additionalDampingFactor;
	float m_additionalLinearDampingThresholdSqr;
	float m_additionalAngularDampingThresholdSqr;
	float m_additionalAngularDampingFactor;
	float m_linearSleepingThreshold;
	float m_angularSleepingThreshold;
	int m_additionalDamping;
};

/// File layout of btRigidBodyDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btRigidBodyDoubleData
{
	btCollisionObjectDoubleData m_collisionObjectData;
	btMatrix3x3DoubleData m_invInertiaTensorWorld;
	btVector3DoubleData m_linearVelocity;
	btVector3DoubleData m_angularVelocity;
	btVector3DoubleData m_angularFactor;
	btVector3DoubleData m_linearFactor;
	btVector3DoubleData m_gravity;
	btVector3DoubleData m_gravity_acceleration;
	btVector3DoubleData m_invInertiaLocal;
	btVector3DoubleData m_totalForce;
	btVector3DoubleData m_totalTorque;
	double m_inverseMass;
	double m_linearDamping;
	double m_angularDamping;
	double m_additionalDampingFactor;
	double m_additionalLinearDampingThresholdSqr;
	double m_additionalAngularDampingThresholdSqr;
	double m_additionalAngularDampingFactor;
	double m_linearSleepingThreshold;
	double m_angularSleepingThreshold;
	int m_additionalDamping;
	char m_padding[4];
};

// clang-format on

#endif  // BT_RIGIDBODY_H
