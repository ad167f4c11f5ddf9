// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_CORRECTION_H
#define CALIBER_JOINT_CORRECTION_H

// What the joint position correction's two files share (btDiscreteDynamicsWorldJointCorrection.cpp:
// the stage and its Gauss-Seidel correction of one joint; btJointCorrectionIslands.cpp: the same stage
// island by island on the task scheduler's threads).

#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btAlignedObjectArray.h"

class btDiscreteDynamicsWorld;

namespace caliber
{
struct WorldStepContext;

namespace joint_correction
{
// Articulations with at least this many anchor joints get the exact tree solve; Gauss-Seidel sweeps
// converge well enough on shorter ones (a ragdoll's 10 joints), at a fraction of the cost.
const int kTreeMinJoints = 12;
// Marks a body whose corrected pose has been written back (in its companion id, -1 otherwise).
const int kCorrectedMark = -2;
// Anchor gaps below this are left alone (0.1 mm: far below what any test or user can see).
const btScalar kNegligibleGap = btScalar(1e-4);
// The fewest joints worth a parallel loop.
const int kMinJointsForParallelCorrection = 64;

/// Whether the correction may move body (awake, neither static nor kinematic).
inline bool movable(const btRigidBody& body) { return !body.isStaticOrKinematicObject() && body.isActive(); }

/// Writes a corrected body's pose back once (interpolation starts from it, inertia follows it), marked
/// through its companion id (free outside the solver; the caller resets it to -1 afterwards). Bodies
/// that may not move are skipped.
inline void writeBackPose(btRigidBody& body)
{
	if (!movable(body) || body.getCompanionId() == kCorrectedMark) return;
	body.setCompanionId(kCorrectedMark);
	body.setInterpolationWorldTransform(body.getWorldTransform());
	body.updateInertiaTensor();
}

/// The island whose bodies joint's correction moves; -2 when it moves no body; -1 when that cannot be
/// told (a moving body outside the islands, or two moving bodies in different islands: a body that does
/// not merge islands).
inline int islandOfJoint(const btTypedConstraint& joint, int numObjects)
{
	const btRigidBody& a = joint.getRigidBodyA();
	const btRigidBody& b = joint.getRigidBodyB();
	const bool moveA = movable(a), moveB = movable(b);
	if (!moveA && !moveB) return -2;
	const int tag = moveA ? a.getIslandTag() : b.getIslandTag();
	if (tag < 0 || tag >= numObjects) return -1;
	if (moveA && moveB && b.getIslandTag() != tag) return -1;
	return tag;
}

/// One Gauss-Seidel correction of a joint the trees left out; lists its two bodies in correctedBodies
/// when it moved them.
bool correctLeftOverJoint(btTypedConstraint* constraint, int numIterations, btConstraintArray& rowScratch,
                          btAlignedObjectArray<btRigidBody*>& correctedBodies);

/// The joints the correction works on (enabled, correcting position) into joints, in their order. When
/// correctByIsland will run on the threads (enough constraints, more than one thread), the constraints
/// are judged on the threads, which also tell each selected joint's island (islandOfJoint) into
/// context.jointCorrectionIslandOf, and context.jointCorrectionIslandsKnown is set.
void selectJoints(const btDiscreteDynamicsWorld& world, const btAlignedObjectArray<btTypedConstraint*>& constraints,
                  btAlignedObjectArray<btTypedConstraint*>& joints, WorldStepContext& context);

/// The whole correction of joints (enabled, correcting position) island by island on the task
/// scheduler's threads, with the bits of the serial pass. False, having done nothing, when it does not
/// apply (one thread, few joints, a joint whose island cannot be told).
bool correctByIsland(btDiscreteDynamicsWorld& world, const btAlignedObjectArray<btTypedConstraint*>& joints,
                     WorldStepContext& context);
}  // namespace joint_correction
}  // namespace caliber

#endif  // CALIBER_JOINT_CORRECTION_H
