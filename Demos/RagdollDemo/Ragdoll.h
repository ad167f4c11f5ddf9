// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_RAGDOLL_H
#define CALIBER_DEMOS_RAGDOLL_H

// The classic Bullet ragdoll: 11 capsules (pelvis, spine, head, legs, arms) joined by 5 hinges (pelvis-spine,
// knees, elbows) and 5 cone-twist joints (neck, hips, shoulders), with the sizes, frames and limits of
// the benchmark's ragdolls136 scene (docs/rigid-body-dynamics.md, "Speed"). Used by RagdollDemo and
// BenchmarkDemo.

#include "btBulletDynamicsCommon.h"

namespace ragdoll
{
/// What building a ragdoll needs from its owner: keeping shapes and joints alive and adding bodies.
class Owner
{
public:
	virtual ~Owner() {}
	virtual btCollisionShape* keepShape(btCollisionShape* shape) = 0;
	/// A dynamic body of the given mass at pose, added to the world.
	virtual btRigidBody* addBody(btCollisionShape* shape, btScalar mass, const btTransform& pose) = 0;
	/// A joint added to the world with collisions between its bodies disabled.
	virtual void addJoint(btTypedConstraint* joint) = 0;
};

/// One ragdoll: its bodies, joints and the joint frames (for measuring pivot errors).
struct Ragdoll
{
	enum
	{
		NUM_BODIES = 11,
		NUM_JOINTS = 10
	};
	btRigidBody* bodies[NUM_BODIES];
	btTypedConstraint* joints[NUM_JOINTS];
	btTransform frameInA[NUM_JOINTS];
	btTransform frameInB[NUM_JOINTS];

	/// Distance between the two ends of joint j's pivot in the world (0 for a perfect joint).
	btScalar pivotError(int j) const;
};

/// Builds a ragdoll standing at offset, scaled by scale (1: 1.8 m tall), with the benchmark's damping
/// (0.05 linear, 0.85 angular) and sleeping settings.
void build(Owner& owner, const btVector3& offset, btScalar scale, Ragdoll& out);
}  // namespace ragdoll

#endif  // CALIBER_DEMOS_RAGDOLL_H
