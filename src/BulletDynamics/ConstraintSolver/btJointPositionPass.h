// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_POSITION_PASS_H
#define CALIBER_JOINT_POSITION_PASS_H

// What the world's joint position correction needs to know of a joint, kept out of btTypedConstraint so
// that Bullet's class declares only Bullet's members: whether the joint's rows can serve as position
// rows, its anchors, and (inside getInfo2) whether it is being asked for position rows.

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"

namespace caliber
{
/// Whether joint's equality rows report their position error as fps * erp * error, so that the world
/// may correct its position after the step: Caliber's ball, hinge and cone-twist joints and the classes
/// derived from them, recognised by their type tag (as Bullet's own code recognises joint classes).
bool correctsPosition(const btTypedConstraint& joint);
/// For joints that hold one point of A on one point of B: those points in A's and B's centre-of-mass
/// frames, for the cheap anchor-only position correction. Other joints return false and are corrected
/// through their rows.
bool jointAnchors(const btTypedConstraint& joint, btVector3& anchorInA, btVector3& anchorInB);

namespace detail
{
inline bool& jointPositionPassFlag()
{
	static thread_local bool inPass = false;
	return inPass;
}
}  // namespace detail

/// True while the world's joint position correction asks a joint on this thread for its rows (fps = erp
/// = 1, so each equality row's target is its position error): velocity-only terms are then left out.
inline bool inJointPositionPass() { return detail::jointPositionPassFlag(); }

/// Marks the calling thread as in the position pass for the scope's lifetime.
class JointPositionPassScope
{
public:
	JointPositionPassScope() { detail::jointPositionPassFlag() = true; }
	~JointPositionPassScope() { detail::jointPositionPassFlag() = false; }
	JointPositionPassScope(const JointPositionPassScope&) = delete;
	JointPositionPassScope& operator=(const JointPositionPassScope&) = delete;
};
}  // namespace caliber

#endif  // CALIBER_JOINT_POSITION_PASS_H
