// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_MOTIONSTATE_H
#define BT_MOTIONSTATE_H

/// btMotionState: how the simulation and the user's graphics exchange an object's transform.

#include "LinearMath/btTransform.h"

/// Interface through which a rigid body reads its start (and kinematic) transform and reports the
/// simulated one, once per step and only for bodies that moved.
class btMotionState
{
public:
	virtual ~btMotionState() {}
	/// Gives the body's centre-of-mass world transform to the simulation.
	virtual void getWorldTransform(btTransform& worldTrans) const = 0;
	/// Receives the (interpolated) centre-of-mass world transform from the simulation.
	virtual void setWorldTransform(const btTransform& worldTrans) = 0;
};

#endif  // BT_MOTIONSTATE_H
