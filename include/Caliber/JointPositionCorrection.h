// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_POSITION_CORRECTION_H
#define CALIBER_JOINT_POSITION_CORRECTION_H

/// Caliber-only settings of btDiscreteDynamicsWorld's joint position correction, the stage after
/// integrateTransforms that moves jointed bodies so that their joints hold at the new poses (see
/// docs/constraints.md). Bullet has no such stage, so its setting is not in Bullet's classes.

class btDiscreteDynamicsWorld;

namespace caliber
{
/// Sets the sweeps of world's joint position correction after each substep (default 3; 0 turns it off).
/// A negative count asserts and is ignored in release builds, with a warning; more than 1024 asserts
/// and is clamped to 1024, with a warning.
void setJointPositionIterations(btDiscreteDynamicsWorld& world, int iterations);
/// The sweeps of world's joint position correction after each substep.
int getJointPositionIterations(const btDiscreteDynamicsWorld& world);
}  // namespace caliber

#endif  // CALIBER_JOINT_POSITION_CORRECTION_H
