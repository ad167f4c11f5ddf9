// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CHARACTER_CONTROLLER_INTERFACE_H
#define BT_CHARACTER_CONTROLLER_INTERFACE_H

#include "BulletDynamics/Dynamics/btActionInterface.h"
#include "LinearMath/btVector3.h"

class btCollisionWorld;

/// What a character controller offers a game: walking, jumping, teleporting (docs/actions.md).
class btCharacterControllerInterface : public btActionInterface
{
public:
	btCharacterControllerInterface() {}
	~btCharacterControllerInterface() override {}

	/// Displacement to walk per substep (a velocity times the substep).
	virtual void setWalkDirection(const btVector3& walkDirection) = 0;
	/// Walks at velocity (per second) for timeInterval seconds.
	virtual void setVelocityForTimeInterval(const btVector3& velocity, btScalar timeInterval) = 0;
	/// Forgets motion and ground state.
	virtual void reset(btCollisionWorld* collisionWorld) = 0;
	/// Teleports the character.
	virtual void warp(const btVector3& origin) = 0;
	/// Gets the character out of anything that moved into it.
	virtual void preStep(btCollisionWorld* collisionWorld) = 0;
	/// Moves the character by one substep.
	virtual void playerStep(btCollisionWorld* collisionWorld, btScalar dt) = 0;
	/// Whether jump() would jump now.
	virtual bool canJump() const = 0;
	/// Jumps (dir: the jump velocity; zero: the jump speed along up).
	virtual void jump(const btVector3& dir = btVector3(0, 0, 0)) = 0;
	/// Whether the character stands on walkable ground.
	virtual bool onGround() const = 0;
	/// Whether setUp turns the character gradually.
	virtual void setUpInterpolate(bool value) = 0;
};

#endif  // BT_CHARACTER_CONTROLLER_INTERFACE_H
