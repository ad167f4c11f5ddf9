// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_ACTION_INTERFACE_H
#define BT_ACTION_INTERFACE_H

#include "LinearMath/btScalar.h"

class btCollisionWorld;
class btIDebugDraw;
class btRigidBody;

/// Something the world updates once per internal substep, after the solver and the integration
/// (vehicles and character controllers are actions).
class btActionInterface
{
protected:
	/// A static body for actions that need one to constrain against.
	static btRigidBody& getFixedBody();

public:
	virtual ~btActionInterface() {}

	/// Called once per substep with the substep's length.
	virtual void updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) = 0;

	/// Draws the action (called by debugDrawWorld).
	virtual void debugDraw(btIDebugDraw* debugDrawer) = 0;
};

#endif  // BT_ACTION_INTERFACE_H
