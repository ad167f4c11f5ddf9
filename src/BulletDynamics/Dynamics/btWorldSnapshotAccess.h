// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WORLD_SNAPSHOT_ACCESS_H
#define CALIBER_WORLD_SNAPSHOT_ACCESS_H

// Reaching the step state that Bullet's classes keep in protected or private members, for the world
// snapshot (caliber::saveWorldState / restoreWorldState) only. Bullet's classes have no accessors for
// everything a bit-exact restore must write back (a body's accumulated force, a manifold's point
// count, the convex-convex algorithm's GJK warm start, ...), and a facade class may not grow one.
//
// The technique: a pointer to a member named in the argument list of an explicit template
// instantiation is exempt from access checking ([temp.explicit]), so an instantiation stores it in a
// static that our accessor reads. Nothing is added to the classes; each accessor names exactly one
// member, and a renamed or removed member fails to compile here, not silently.

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/CollisionDispatch/btCollisionObject.h"
#include "BulletCollision/CollisionDispatch/btCompoundCompoundCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btConvexConcaveCollisionAlgorithm.h"
#include "BulletCollision/CollisionDispatch/btConvexConvexAlgorithm.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletDynamics/Character/btKinematicCharacterController.h"
#include "BulletDynamics/ConstraintSolver/btConeTwistConstraint.h"
#include "BulletDynamics/ConstraintSolver/btHingeConstraint.h"
#include "BulletDynamics/Dynamics/btDiscreteDynamicsWorld.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "BulletDynamics/Vehicle/btRaycastVehicle.h"

namespace caliber
{
namespace snapshot_access
{
template <class Tag>
struct MemberPointer
{
	static typename Tag::Type pointer;
};
template <class Tag>
typename Tag::Type MemberPointer<Tag>::pointer = nullptr;

template <class Tag, typename Tag::Type Member>
struct BindMember
{
	BindMember() { MemberPointer<Tag>::pointer = Member; }
	static BindMember instance;
};
template <class Tag, typename Tag::Type Member>
BindMember<Tag, Member> BindMember<Tag, Member>::instance;
}  // namespace snapshot_access
}  // namespace caliber

// The members, as X(accessor, class, member type, member).
#define CALIBER_SNAPSHOT_MEMBERS(X)                                                                             \
	/* the time accumulator and fixed step of stepSimulation; actions and predictive manifolds (checked) */     \
	X(localTime, btDiscreteDynamicsWorld, btScalar, m_localTime)                                                \
	X(fixedTimeStep, btDiscreteDynamicsWorld, btScalar, m_fixedTimeStep)                                        \
	X(worldActions, btDiscreteDynamicsWorld, btAlignedObjectArray<btActionInterface*>, m_actions)               \
	X(predictiveManifolds, btDiscreteDynamicsWorld, btAlignedObjectArray<btPersistentManifold*>,                \
	  m_predictiveManifolds)                                                                                    \
	/* a collision object's step state */                                                                       \
	X(worldTransform, btCollisionObject, btTransform, m_worldTransform)                                         \
	X(interpolationTransform, btCollisionObject, btTransform, m_interpolationWorldTransform)                    \
	X(interpolationLinearVelocity, btCollisionObject, btVector3, m_interpolationLinearVelocity)                 \
	X(interpolationAngularVelocity, btCollisionObject, btVector3, m_interpolationAngularVelocity)               \
	X(collisionFlags, btCollisionObject, int, m_collisionFlags)                                                 \
	X(islandTag, btCollisionObject, int, m_islandTag1)                                                          \
	X(companionId, btCollisionObject, int, m_companionId)                                                       \
	X(activationState, btCollisionObject, int, m_activationState1)                                              \
	X(deactivationTime, btCollisionObject, btScalar, m_deactivationTime)                                        \
	X(hitFraction, btCollisionObject, btScalar, m_hitFraction)                                                  \
	X(updateRevision, btCollisionObject, int, m_updateRevision)                                                 \
	/* a rigid body's step state */                                                                             \
	X(invInertiaTensorWorld, btRigidBody, btMatrix3x3, m_invInertiaTensorWorld)                                 \
	X(linearVelocity, btRigidBody, btVector3, m_linearVelocity)                                                 \
	X(angularVelocity, btRigidBody, btVector3, m_angularVelocity)                                               \
	X(bodyGravity, btRigidBody, btVector3, m_gravity)                                                           \
	X(bodyGravityAcceleration, btRigidBody, btVector3, m_gravity_acceleration)                                  \
	X(totalForce, btRigidBody, btVector3, m_totalForce)                                                         \
	X(totalTorque, btRigidBody, btVector3, m_totalTorque)                                                       \
	X(deltaLinearVelocity, btRigidBody, btVector3, m_deltaLinearVelocity)                                       \
	X(deltaAngularVelocity, btRigidBody, btVector3, m_deltaAngularVelocity)                                     \
	X(pushVelocity, btRigidBody, btVector3, m_pushVelocity)                                                     \
	X(turnVelocity, btRigidBody, btVector3, m_turnVelocity)                                                     \
	/* a contact manifold's points */                                                                           \
	X(manifoldPoints, btPersistentManifold, ManifoldPointCache, m_pointCache)                                   \
	X(manifoldPointCount, btPersistentManifold, int, m_cachedPoints)                                            \
	X(manifoldBreakingThreshold, btPersistentManifold, btScalar, m_contactBreakingThreshold)                    \
	X(manifoldProcessingThreshold, btPersistentManifold, btScalar, m_contactProcessingThreshold)                \
	/* the collision algorithms' state that carries from step to step (GJK warm start, lazy manifolds) */       \
	X(convexManifold, btConvexConvexAlgorithm, btPersistentManifold*, m_manifoldPtr)                            \
	X(convexOwnsManifold, btConvexConvexAlgorithm, bool, m_ownManifold)                                         \
	X(convexLastAxis, btConvexConvexAlgorithm, btVector3, m_lastSeparatingAxis)                                 \
	X(convexHaveLastAxis, btConvexConvexAlgorithm, bool, m_haveLastSeparatingAxis)                              \
	X(concaveCallback, btConvexConcaveCollisionAlgorithm, btConvexTriangleCallback, m_btConvexTriangleCallback) \
	X(triangleAlgorithm, btConvexTriangleCallback, btCollisionAlgorithm*, m_triangleAlgorithm)                  \
	/* compound algorithms: a child algorithm per child, or per pair of children with the frame counter */     \
	X(compoundChildren, btCompoundCollisionAlgorithm, CompoundChildAlgorithms, m_childCollisionAlgorithms)      \
	X(compoundSwapped, btCompoundCollisionAlgorithm, bool, m_isSwapped)                                         \
	X(compoundSharedManifold, btCompoundCollisionAlgorithm, btPersistentManifold*, m_sharedManifold)            \
	X(compoundPairs, btCompoundCompoundCollisionAlgorithm, CompoundChildPairs, m_childPairAlgorithms)           \
	X(compoundFrame, btCompoundCompoundCollisionAlgorithm, int, m_frame)                                        \
	/* joints: the time step of the last rows (read by the next getInfo1), the accumulated hinge angle */       \
	X(jointAppliedImpulse, btTypedConstraint, btScalar, m_appliedImpulse)                                       \
	X(jointEnabled, btTypedConstraint, bool, m_isEnabled)                                                       \
	X(hingeLastTimeStep, btHingeConstraint, btScalar, m_lastTimeStep)                                           \
	X(hingeAccumulatedAngle, btHingeAccumulatedAngleConstraint, btScalar, m_accumulatedAngle)                   \
	X(coneLastTimeStep, btConeTwistConstraint, btScalar, m_lastTimeStep)                                        \
	/* the raycast vehicle: speed and the tyre friction's directions and impulses of the last substep */       \
	X(vehicleSpeed, btRaycastVehicle, btScalar, m_currentVehicleSpeedKmHour)                                    \
	X(vehicleForwardWS, btRaycastVehicle, btAlignedObjectArray<btVector3>, m_forwardWS)                         \
	X(vehicleAxle, btRaycastVehicle, btAlignedObjectArray<btVector3>, m_axle)                                   \
	X(vehicleForwardImpulse, btRaycastVehicle, btAlignedObjectArray<btScalar>, m_forwardImpulse)                \
	X(vehicleSideImpulse, btRaycastVehicle, btAlignedObjectArray<btScalar>, m_sideImpulse)                      \
	/* the kinematic character controller: its motion state between steps (settings are the user's) */          \
	X(characterGhost, btKinematicCharacterController, btPairCachingGhostObject*, m_ghostObject)                 \
	X(characterVerticalVelocity, btKinematicCharacterController, btScalar, m_verticalVelocity)                  \
	X(characterVerticalOffset, btKinematicCharacterController, btScalar, m_verticalOffset)                      \
	X(characterJumpSpeed, btKinematicCharacterController, btScalar, m_jumpSpeed)                                \
	X(characterWalkDirection, btKinematicCharacterController, btVector3, m_walkDirection)                       \
	X(characterNormalizedDirection, btKinematicCharacterController, btVector3, m_normalizedDirection)           \
	X(characterAngularVelocity, btKinematicCharacterController, btVector3, m_AngVel)                            \
	X(characterJumpPosition, btKinematicCharacterController, btVector3, m_jumpPosition)                         \
	X(characterCurrentPosition, btKinematicCharacterController, btVector3, m_currentPosition)                   \
	X(characterCurrentStepOffset, btKinematicCharacterController, btScalar, m_currentStepOffset)                \
	X(characterTargetPosition, btKinematicCharacterController, btVector3, m_targetPosition)                     \
	X(characterCurrentOrientation, btKinematicCharacterController, btQuaternion, m_currentOrientation)          \
	X(characterTargetOrientation, btKinematicCharacterController, btQuaternion, m_targetOrientation)            \
	X(characterTouchingContact, btKinematicCharacterController, bool, m_touchingContact)                        \
	X(characterTouchingNormal, btKinematicCharacterController, btVector3, m_touchingNormal)                     \
	X(characterWasOnGround, btKinematicCharacterController, bool, m_wasOnGround)                                \
	X(characterWasJumping, btKinematicCharacterController, bool, m_wasJumping)                                  \
	X(characterUseWalkDirection, btKinematicCharacterController, bool, m_useWalkDirection)                      \
	X(characterVelocityTimeInterval, btKinematicCharacterController, btScalar, m_velocityTimeInterval)          \
	X(characterJumpAxis, btKinematicCharacterController, btVector3, m_jumpAxis)

// Declares caliber::snapshot_access::accessor(Class&) -> MemberType& (bound in btWorldSnapshot.cpp).
#define CALIBER_SNAPSHOT_DECLARE(Accessor, Class, MemberType, member) \
	struct Accessor##Tag                                              \
	{                                                                 \
		typedef MemberType Class::*Type;                              \
	};                                                                \
	inline MemberType& Accessor(Class& object) { return object.*MemberPointer<Accessor##Tag>::pointer; }

// The one explicit instantiation per member: used once in the program, in btWorldSnapshot.cpp.
#define CALIBER_SNAPSHOT_BIND(Accessor, Class, MemberType, member) \
	template struct BindMember<Accessor##Tag, &Class::member>;

typedef btManifoldPoint ManifoldPointCache[MANIFOLD_CACHE_SIZE];
typedef btAlignedObjectArray<btCollisionAlgorithm*> CompoundChildAlgorithms;
typedef btHashMap<btCompoundCompoundCollisionAlgorithm::ChildPairKey, btCompoundCompoundCollisionAlgorithm::ChildPairAlgorithm>
    CompoundChildPairs;

namespace caliber
{
namespace snapshot_access
{
CALIBER_SNAPSHOT_MEMBERS(CALIBER_SNAPSHOT_DECLARE)
}  // namespace snapshot_access
}  // namespace caliber

#endif  // CALIBER_WORLD_SNAPSHOT_ACCESS_H
