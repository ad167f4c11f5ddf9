// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_KINEMATIC_CHARACTER_CONTROLLER_H
#define BT_KINEMATIC_CHARACTER_CONTROLLER_H

#include "BulletCollision/BroadphaseCollision/btCollisionAlgorithm.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btVector3.h"
#include "btCharacterControllerInterface.h"

class btCollisionShape;
class btConvexShape;
class btRigidBody;
class btCollisionWorld;
class btCollisionDispatcher;
class btPairCachingGhostObject;

/// A character moved by convex sweeps rather than simulated: it walks, slides along walls, climbs
/// steps up to its step height and slopes up to its maximum slope, falls, jumps and rides moving
/// bodies it stands on. Its body is a btPairCachingGhostObject with a convex shape (docs/actions.md).
ATTRIBUTE_ALIGNED16(class)
btKinematicCharacterController : public btCharacterControllerInterface
{
protected:
	btScalar m_halfHeight;
	btPairCachingGhostObject* m_ghostObject;
	btConvexShape* m_convexShape;

	btScalar m_maxPenetrationDepth;
	btScalar m_verticalVelocity;
	btScalar m_verticalOffset;
	btScalar m_fallSpeed;
	btScalar m_jumpSpeed;
	btScalar m_SetjumpSpeed;
	btScalar m_maxJumpHeight;
	btScalar m_maxSlopeRadians;
	btScalar m_maxSlopeCosine;
	btScalar m_gravity;

	btScalar m_turnAngle;
	btScalar m_stepHeight;
	btScalar m_addedMargin;

	btVector3 m_walkDirection;
	btVector3 m_normalizedDirection;
	btVector3 m_AngVel;

	btVector3 m_jumpPosition;

	btVector3 m_currentPosition;
	btScalar m_currentStepOffset;
	btVector3 m_targetPosition;

	btQuaternion m_currentOrientation;
	btQuaternion m_targetOrientation;

	btManifoldArray m_manifoldArray;

	bool m_touchingContact;
	btVector3 m_touchingNormal;

	btScalar m_linearDamping;
	btScalar m_angularDamping;

	bool m_wasOnGround;
	bool m_wasJumping;
	bool m_useGhostObjectSweepTest;
	bool m_useWalkDirection;
	btScalar m_velocityTimeInterval;
	btVector3 m_up;
	btVector3 m_jumpAxis;

	static btVector3* getUpAxisDirections();
	bool m_interpolateUp;
	bool full_drop;
	bool bounce_fix;

	btVector3 computeReflectionDirection(const btVector3& direction, const btVector3& normal);
	btVector3 parallelComponent(const btVector3& direction, const btVector3& normal);
	btVector3 perpindicularComponent(const btVector3& direction, const btVector3& normal);

	bool recoverFromPenetration(btCollisionWorld * collisionWorld);
	void stepUp(btCollisionWorld * collisionWorld);
	void updateTargetPositionBasedOnCollision(const btVector3& hit_normal, btScalar tangentMag = btScalar(0.),
	                                          btScalar normalMag = btScalar(1.));
	void stepForwardAndStrafe(btCollisionWorld * collisionWorld, const btVector3& walkMove);
	void stepDown(btCollisionWorld * collisionWorld, btScalar dt);

	virtual bool needsCollision(const btCollisionObject* body0, const btCollisionObject* body1);

	void setUpVector(const btVector3& up);

	btQuaternion getRotation(btVector3 & v0, btVector3 & v1) const;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// A character on ghostObject (in the world, with a btGhostPairCallback installed) shaped by
	/// convexShape, climbing steps up to stepHeight, standing along up (Bullet's default: +x).
	btKinematicCharacterController(btPairCachingGhostObject * ghostObject, btConvexShape * convexShape,
	                               btScalar stepHeight, const btVector3& up = btVector3(1.0, 0.0, 0.0));
	~btKinematicCharacterController() override;

	/// The world's per-substep call: preStep, then playerStep.
	void updateAction(btCollisionWorld * collisionWorld, btScalar deltaTime) override
	{
		preStep(collisionWorld);
		playerStep(collisionWorld, deltaTime);
	}

	/// Draws the character's up axis and its last contact normal.
	void debugDraw(btIDebugDraw * debugDrawer) override;

	/// Sets the up direction (a zero or non-finite vector is rejected).
	void setUp(const btVector3& up);
	/// The up direction.
	const btVector3& getUp() { return m_up; }

	/// Turning rate about up (radians per second).
	void setAngularVelocity(const btVector3& velocity);
	/// Turning rate.
	const btVector3& getAngularVelocity() const;

	/// Sets the vertical speed (along up) and the walking velocity (the rest).
	void setLinearVelocity(const btVector3& velocity);
	/// Walking velocity plus vertical velocity.
	btVector3 getLinearVelocity() const;

	/// Per-second damping of the vertical velocity (0..1).
	void setLinearDamping(btScalar d) { m_linearDamping = btClamped(d, (btScalar)btScalar(0.0), (btScalar)btScalar(1.0)); }
	/// Linear damping.
	btScalar getLinearDamping() const { return m_linearDamping; }
	/// Per-second damping of the turning rate (0..1).
	void setAngularDamping(btScalar d) { m_angularDamping = btClamped(d, (btScalar)btScalar(0.0), (btScalar)btScalar(1.0)); }
	/// Angular damping.
	btScalar getAngularDamping() const { return m_angularDamping; }

	void setWalkDirection(const btVector3& walkDirection) override;
	void setVelocityForTimeInterval(const btVector3& velocity, btScalar timeInterval) override;
	void reset(btCollisionWorld * collisionWorld) override;
	void warp(const btVector3& origin) override;
	void preStep(btCollisionWorld * collisionWorld) override;
	void playerStep(btCollisionWorld * collisionWorld, btScalar dt) override;

	/// Highest step climbed without jumping.
	void setStepHeight(btScalar h);
	/// Step height.
	btScalar getStepHeight() const { return m_stepHeight; }
	/// Terminal falling speed (default 55).
	void setFallSpeed(btScalar fallSpeed);
	/// Falling speed limit.
	btScalar getFallSpeed() const { return m_fallSpeed; }
	/// Take-off speed of jump() (default 10).
	void setJumpSpeed(btScalar jumpSpeed);
	/// Jump speed.
	btScalar getJumpSpeed() const { return m_jumpSpeed; }
	/// Caps the jump speed so the apex is at most this high (0: no cap).
	void setMaxJumpHeight(btScalar maxJumpHeight);
	bool canJump() const override;
	void jump(const btVector3& v = btVector3(0, 0, 0)) override;
	/// Same as jump(v).
	void applyImpulse(const btVector3& v) { jump(v); }

	/// Sets gravity (a non-zero vector also sets up to its opposite).
	void setGravity(const btVector3& gravity);
	/// Gravity as a vector (magnitude times -up).
	btVector3 getGravity() const;

	/// Steepest walkable slope (radians, default 45 degrees).
	void setMaxSlope(btScalar slopeRadians);
	/// Steepest walkable slope.
	btScalar getMaxSlope() const;

	/// Largest penetration tolerated before preStep pushes the character out.
	void setMaxPenetrationDepth(btScalar d);
	/// Largest tolerated penetration.
	btScalar getMaxPenetrationDepth() const;

	/// The ghost object.
	btPairCachingGhostObject* getGhostObject();
	/// Stored; sweeps always use the world's broadphase (docs/actions.md).
	void setUseGhostSweepTest(bool useGhostObjectSweepTest) { m_useGhostObjectSweepTest = useGhostObjectSweepTest; }

	bool onGround() const override;
	void setUpInterpolate(bool value) override;
};

#endif  // BT_KINEMATIC_CHARACTER_CONTROLLER_H
