// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The kinematic character: each substep it rides what it stands on, steps up, walks (sliding along
// walls and steep slopes, climbing walkable ones), then steps down onto the ground or falls. Every
// move is a convex sweep through the world's broadphase (docs/actions.md, "Character controller").

#include "BulletDynamics/Character/btKinematicCharacterController.h"

#include "BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/NarrowPhaseCollision/btManifoldPoint.h"
#include "BulletCollision/CollisionDispatch/btGhostObject.h"
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btIDebugDraw.h"
#include "LinearMath/btSideTable.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// Gap kept between the character and what it touches, so the next sweep starts outside it.
const btScalar kSkin = btScalar(1e-3);
const int kSlideIterations = 4;
const int kRecoveryIterations = 4;

// Caliber-only state (Bullet's class has no place for it): the body the character stands on.
struct CharacterState
{
	const btCollisionObject* ground = 0;
	bool warnedNotInWorld = false;
	bool blocked = false;       // whether the last walk was stopped by something
	btVector3 blockPoint;       // where (on the obstacle)
	btTransform groundPose = btTransform::getIdentity();  // the ground's pose when the character last stood on it
};

CharacterState& stateOf(const btKinematicCharacterController* character)
{
	return caliber::sideTable<CharacterState>().acquire(character);
}

// The character's own filter group and mask (it only meets what it collides with), or the callback's
// defaults while it is not in the world.
template <class Callback>
void takeFilterOf(const btCollisionObject* self, Callback& callback)
{
	if (!self->getBroadphaseHandle()) return;
	callback.m_collisionFilterGroup = self->getBroadphaseHandle()->m_collisionFilterGroup;
	callback.m_collisionFilterMask = self->getBroadphaseHandle()->m_collisionFilterMask;
}

// Queries never see the character itself or objects without contact response.
bool isObstacle(const btCollisionObject* self, const btBroadphaseProxy* proxy)
{
	const btCollisionObject* object = static_cast<const btCollisionObject*>(proxy->m_clientObject);
	return object != self && !(object && !object->hasContactResponse());
}

// The closest hit of a sweep that the character would collide with: not itself, not objects without
// contact response, by its filter, and not a surface it is moving away from.
struct SweepCallback : public btCollisionWorld::ClosestConvexResultCallback
{
	SweepCallback(const btCollisionObject* self, const btVector3& from, const btVector3& to)
	    : ClosestConvexResultCallback(from, to), m_self(self), m_motion(to - from)
	{
		takeFilterOf(self, *this);
	}
	bool needsCollision(btBroadphaseProxy* proxy) const override
	{
		return isObstacle(m_self, proxy) && ClosestConvexResultCallback::needsCollision(proxy);
	}
	btScalar addSingleResult(btCollisionWorld::LocalConvexResult& result, bool normalInWorldSpace) override
	{
		const btVector3 normal = normalInWorldSpace
		                             ? result.m_hitNormalLocal
		                             : result.m_hitCollisionObject->getWorldTransform().getBasis() * result.m_hitNormalLocal;
		// Surfaces the move leaves or grazes (a floor under a sideways move, whose normal the sweep
		// gives with a little noise) do not stop it.
		if (normal.dot(m_motion) >= -btScalar(1e-3) * m_motion.length()) return m_closestHitFraction;
		return ClosestConvexResultCallback::addSingleResult(result, normalInWorldSpace);
	}
	const btCollisionObject* m_self;
	btVector3 m_motion;
};

struct Hit
{
	bool hit = false;
	btScalar fraction = 1;
	btVector3 normal = btVector3(0, 0, 0);
	btVector3 point = btVector3(0, 0, 0);
	const btCollisionObject* object = 0;
};

Hit sweep(btCollisionWorld* world, const btConvexShape* shape, const btCollisionObject* self,
          const btQuaternion& orientation, const btVector3& from, const btVector3& to)
{
	Hit hit;
	if ((to - from).length2() < SIMD_EPSILON * SIMD_EPSILON) return hit;
	SweepCallback callback(self, from, to);
	world->convexSweepTest(shape, btTransform(orientation, from), btTransform(orientation, to), callback);
	if (!callback.hasHit() || !caliber::isFinite(callback.m_hitNormalWorld)) return hit;
	hit.hit = true;
	hit.fraction = callback.m_closestHitFraction;
	hit.normal = callback.m_hitNormalWorld.normalized();
	hit.point = callback.m_hitPointWorld;
	hit.object = callback.m_hitCollisionObject;
	return hit;
}

// Where a sweep from `from` along motion stops: at the hit, backed off by the skin.
btVector3 stopAt(const btVector3& from, const btVector3& motion, const Hit& hit)
{
	if (!hit.hit) return from + motion;
	const btScalar length = motion.length();
	const btScalar travelled = btMax(btScalar(0), hit.fraction * length - kSkin);
	return from + motion * (length > 0 ? travelled / length : btScalar(0));
}

// Distance from the shape's centre down to its lowest point along up.
btScalar feetBelowCentre(const btConvexShape* shape, const btVector3& up)
{
	return shape->localGetSupportingVertex(-up).dot(-up);
}

// Ray from the character's centre straight down: the surface under it, if any, within reach.
struct GroundRay : public btCollisionWorld::ClosestRayResultCallback
{
	GroundRay(const btCollisionObject* self, const btVector3& from, const btVector3& to)
	    : ClosestRayResultCallback(from, to), m_self(self)
	{
		takeFilterOf(self, *this);
	}
	bool needsCollision(btBroadphaseProxy* proxy) const override
	{
		return isObstacle(m_self, proxy) && ClosestRayResultCallback::needsCollision(proxy);
	}
	const btCollisionObject* m_self;
};

struct PenetrationCallback : public btCollisionWorld::ContactResultCallback
{
	explicit PenetrationCallback(const btCollisionObject* self) : m_self(self) {}
	bool needsCollision(btBroadphaseProxy* proxy) const override
	{
		return isObstacle(m_self, proxy) && ContactResultCallback::needsCollision(proxy);
	}
	btScalar addSingleResult(btManifoldPoint& point, const btCollisionObjectWrapper* wrap0, int, int,
	                         const btCollisionObjectWrapper*, int, int) override
	{
		const btScalar depth = -point.getDistance();
		if (depth > m_depth)
		{
			m_depth = depth;
			// The normal points from B to A: out of the other object when the character is A.
			m_push = wrap0->getCollisionObject() == m_self ? point.m_normalWorldOnB : -point.m_normalWorldOnB;
		}
		return 0;
	}
	const btCollisionObject* m_self;
	btScalar m_depth = 0;
	btVector3 m_push = btVector3(0, 0, 0);
};
}  // namespace

btKinematicCharacterController::btKinematicCharacterController(btPairCachingGhostObject* ghostObject,
                                                               btConvexShape* convexShape, btScalar stepHeight,
                                                               const btVector3& up)
    : m_halfHeight(0),
      m_ghostObject(ghostObject),
      m_convexShape(convexShape),
      m_maxPenetrationDepth(btScalar(0.2)),
      m_verticalVelocity(0),
      m_verticalOffset(0),
      m_fallSpeed(btScalar(55.0)),
      m_jumpSpeed(btScalar(10.0)),
      m_SetjumpSpeed(btScalar(10.0)),
      m_maxJumpHeight(0),
      m_maxSlopeRadians(0),
      m_maxSlopeCosine(0),
      m_gravity(btScalar(9.8) * 3),  // Bullet's default: three times Earth's gravity
      m_turnAngle(0),
      m_stepHeight(btIsFinite(stepHeight) ? btMax(btScalar(0), stepHeight) : btScalar(0)),
      m_addedMargin(btScalar(0.02)),
      m_walkDirection(0, 0, 0),
      m_normalizedDirection(0, 0, 0),
      m_AngVel(0, 0, 0),
      m_jumpPosition(0, 0, 0),
      m_currentPosition(0, 0, 0),
      m_currentStepOffset(0),
      m_targetPosition(0, 0, 0),
      m_currentOrientation(btQuaternion::getIdentity()),
      m_targetOrientation(btQuaternion::getIdentity()),
      m_touchingContact(false),
      m_touchingNormal(0, 0, 0),
      m_linearDamping(0),
      m_angularDamping(0),
      m_wasOnGround(false),
      m_wasJumping(false),
      m_useGhostObjectSweepTest(true),
      m_useWalkDirection(true),
      m_velocityTimeInterval(0),
      m_up(0, 1, 0),
      m_jumpAxis(0, 0, 1),
      m_interpolateUp(true),
      full_drop(false),
      bounce_fix(false)
{
	btAssert(ghostObject && convexShape && "btKinematicCharacterController: null ghost object or shape");
	btAssert(btIsFinite(stepHeight) && stepHeight >= 0 && "btKinematicCharacterController: bad step height");
	if (!ghostObject || !convexShape)
		btReportWarning("Caliber: btKinematicCharacterController: null ghost object or shape; it will do nothing\n");
	setUp(up);
	setMaxSlope(btRadians(btScalar(45.0)));
	if (ghostObject)
	{
		m_currentPosition = ghostObject->getWorldTransform().getOrigin();
		m_currentOrientation = ghostObject->getWorldTransform().getRotation();
	}
}

btKinematicCharacterController::~btKinematicCharacterController() { caliber::sideTable<CharacterState>().release(this); }

btPairCachingGhostObject* btKinematicCharacterController::getGhostObject() { return m_ghostObject; }

btVector3* btKinematicCharacterController::getUpAxisDirections()
{
	static btVector3 directions[3] = {btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)};
	return directions;
}

btVector3 btKinematicCharacterController::computeReflectionDirection(const btVector3& direction, const btVector3& normal)
{
	return direction - (btScalar(2.0) * direction.dot(normal)) * normal;
}

btVector3 btKinematicCharacterController::parallelComponent(const btVector3& direction, const btVector3& normal)
{
	return normal * direction.dot(normal);
}

btVector3 btKinematicCharacterController::perpindicularComponent(const btVector3& direction, const btVector3& normal)
{
	return direction - parallelComponent(direction, normal);
}

bool btKinematicCharacterController::needsCollision(const btCollisionObject* body0, const btCollisionObject* body1)
{
	if (!body0 || !body1) return false;
	return body0->hasContactResponse() && body1->hasContactResponse();
}

btQuaternion btKinematicCharacterController::getRotation(btVector3& v0, btVector3& v1) const
{
	if (v0.length2() == 0 || v1.length2() == 0) return btQuaternion::getIdentity();
	return shortestArcQuatNormalize2(v0, v1);
}

void btKinematicCharacterController::setUpVector(const btVector3& up)
{
	if (!caliber::isFinite(up) || up.fuzzyZero()) return;
	m_up = up.normalized();
}

void btKinematicCharacterController::setUp(const btVector3& up)
{
	const bool valid = caliber::isFinite(up) && !up.fuzzyZero();
	btAssert(valid && "btKinematicCharacterController::setUp: zero or non-finite up");
	if (!valid)
	{
		btReportWarning("Caliber: btKinematicCharacterController::setUp: zero or non-finite up ignored\n");
		return;
	}
	setUpVector(up);
}

void btKinematicCharacterController::setAngularVelocity(const btVector3& velocity)
{
	if (caliber::isFinite(velocity)) m_AngVel = velocity;
}

const btVector3& btKinematicCharacterController::getAngularVelocity() const { return m_AngVel; }

void btKinematicCharacterController::setLinearVelocity(const btVector3& velocity)
{
	if (!caliber::isFinite(velocity)) return;
	m_verticalVelocity = velocity.dot(m_up);
	if (m_verticalVelocity > 0) m_wasOnGround = false;
	setVelocityForTimeInterval(velocity - m_up * m_verticalVelocity, BT_LARGE_FLOAT);
}

btVector3 btKinematicCharacterController::getLinearVelocity() const
{
	const btVector3 walk = m_useWalkDirection ? btVector3(0, 0, 0) : m_walkDirection;
	return walk + m_up * m_verticalVelocity;
}

void btKinematicCharacterController::setWalkDirection(const btVector3& walkDirection)
{
	btAssert(caliber::isFinite(walkDirection) && "btKinematicCharacterController::setWalkDirection: non-finite direction");
	if (!caliber::isFinite(walkDirection))
	{
		btReportWarning("Caliber: btKinematicCharacterController::setWalkDirection: non-finite direction ignored\n");
		return;
	}
	m_useWalkDirection = true;
	m_walkDirection = walkDirection;
	m_normalizedDirection = walkDirection.fuzzyZero() ? btVector3(0, 0, 0) : walkDirection.normalized();
}

void btKinematicCharacterController::setVelocityForTimeInterval(const btVector3& velocity, btScalar timeInterval)
{
	const bool valid = caliber::isFinite(velocity) && !(timeInterval != timeInterval);
	btAssert(valid && "btKinematicCharacterController::setVelocityForTimeInterval: non-finite velocity or interval");
	if (!valid)
	{
		btReportWarning("Caliber: btKinematicCharacterController::setVelocityForTimeInterval: bad input ignored\n");
		return;
	}
	m_useWalkDirection = false;
	m_walkDirection = velocity;
	m_normalizedDirection = velocity.fuzzyZero() ? btVector3(0, 0, 0) : velocity.normalized();
	m_velocityTimeInterval = btMax(btScalar(0), timeInterval);
}

void btKinematicCharacterController::reset(btCollisionWorld* collisionWorld)
{
	(void)collisionWorld;
	m_verticalVelocity = 0;
	m_verticalOffset = 0;
	m_wasOnGround = false;
	m_wasJumping = false;
	m_walkDirection.setValue(0, 0, 0);
	m_velocityTimeInterval = 0;
	stateOf(this).ground = 0;
}

void btKinematicCharacterController::warp(const btVector3& origin)
{
	btAssert(caliber::isFinite(origin) && "btKinematicCharacterController::warp: non-finite origin");
	if (!caliber::isFinite(origin) || !m_ghostObject)
	{
		btReportWarning("Caliber: btKinematicCharacterController::warp: non-finite origin or no ghost; ignored\n");
		return;
	}
	m_ghostObject->getWorldTransform().setOrigin(origin);
	m_currentPosition = origin;
	m_targetPosition = origin;
	m_verticalVelocity = 0;
	m_wasOnGround = false;
	stateOf(this).ground = 0;
}

void btKinematicCharacterController::setStepHeight(btScalar h)
{
	if (btIsFinite(h) && h >= 0) m_stepHeight = h;
}

void btKinematicCharacterController::setFallSpeed(btScalar fallSpeed)
{
	if (btIsFinite(fallSpeed) && fallSpeed > 0) m_fallSpeed = fallSpeed;
}

void btKinematicCharacterController::setJumpSpeed(btScalar jumpSpeed)
{
	if (!btIsFinite(jumpSpeed) || jumpSpeed < 0) return;
	m_jumpSpeed = jumpSpeed;
	m_SetjumpSpeed = jumpSpeed;
}

void btKinematicCharacterController::setMaxJumpHeight(btScalar maxJumpHeight)
{
	if (btIsFinite(maxJumpHeight) && maxJumpHeight >= 0) m_maxJumpHeight = maxJumpHeight;
}

bool btKinematicCharacterController::canJump() const { return onGround(); }

void btKinematicCharacterController::jump(const btVector3& v)
{
	btScalar speed = v.fuzzyZero() ? m_SetjumpSpeed : v.dot(m_up);
	if (!btIsFinite(speed)) return;
	// The apex of a jump at speed v is v^2 / (2 g): cap the speed to keep it below the maximum height.
	if (m_maxJumpHeight > 0 && m_gravity > 0) speed = btMin(speed, btSqrt(2 * m_gravity * m_maxJumpHeight));
	m_jumpSpeed = speed;
	m_verticalVelocity = speed;
	m_wasJumping = true;
	m_wasOnGround = false;  // airborne from take-off to landing (Bullet reports ground at the apex)
	if (!v.fuzzyZero()) m_jumpAxis = v.normalized();
	if (m_ghostObject) m_jumpPosition = m_ghostObject->getWorldTransform().getOrigin();
}

void btKinematicCharacterController::setGravity(const btVector3& gravity)
{
	if (!caliber::isFinite(gravity)) return;
	if (gravity.length2() > 0) setUpVector(-gravity);
	m_gravity = gravity.length();
}

btVector3 btKinematicCharacterController::getGravity() const { return -m_gravity * m_up; }

void btKinematicCharacterController::setMaxSlope(btScalar slopeRadians)
{
	if (!btIsFinite(slopeRadians)) return;
	m_maxSlopeRadians = btClamped(slopeRadians, btScalar(0), SIMD_HALF_PI);
	m_maxSlopeCosine = btCos(m_maxSlopeRadians);
}

btScalar btKinematicCharacterController::getMaxSlope() const { return m_maxSlopeRadians; }

void btKinematicCharacterController::setMaxPenetrationDepth(btScalar d)
{
	if (btIsFinite(d) && d >= 0) m_maxPenetrationDepth = d;
}

btScalar btKinematicCharacterController::getMaxPenetrationDepth() const { return m_maxPenetrationDepth; }

bool btKinematicCharacterController::onGround() const { return m_wasOnGround; }

void btKinematicCharacterController::setUpInterpolate(bool value) { m_interpolateUp = value; }

bool btKinematicCharacterController::recoverFromPenetration(btCollisionWorld* collisionWorld)
{
	// Pushed out along the deepest contact's normal, beyond the tolerated depth only: touching
	// contacts (the floor it stands on) are left alone.
	bool moved = false;
	for (int i = 0; i < kRecoveryIterations; ++i)
	{
		m_ghostObject->getWorldTransform().setOrigin(m_currentPosition);
		PenetrationCallback callback(m_ghostObject);
		if (m_ghostObject->getBroadphaseHandle())
		{
			callback.m_collisionFilterGroup = m_ghostObject->getBroadphaseHandle()->m_collisionFilterGroup;
			callback.m_collisionFilterMask = m_ghostObject->getBroadphaseHandle()->m_collisionFilterMask;
		}
		collisionWorld->contactTest(m_ghostObject, callback);
		if (callback.m_depth <= m_maxPenetrationDepth || callback.m_push.fuzzyZero()) break;
		m_currentPosition += callback.m_push.normalized() * (callback.m_depth - m_maxPenetrationDepth + kSkin);
		moved = true;
	}
	m_ghostObject->getWorldTransform().setOrigin(m_currentPosition);
	return moved;
}

namespace
{
// A ghost that left the world (removeCollisionObject while the controller is still an action) is not
// moved: the controller waits, reporting it once, until the ghost is added again.
bool ghostInWorld(const btKinematicCharacterController* character, const btCollisionObject* ghost)
{
	if (ghost->getBroadphaseHandle()) return true;
	CharacterState& state = stateOf(character);
	if (!state.warnedNotInWorld)
	{
		state.warnedNotInWorld = true;
		btReportWarning(
		    "Caliber: btKinematicCharacterController: its ghost object is not in a world; the character waits\n");
	}
	return false;
}
}  // namespace

void btKinematicCharacterController::preStep(btCollisionWorld* collisionWorld)
{
	if (!m_ghostObject || !m_convexShape || !collisionWorld || !ghostInWorld(this, m_ghostObject)) return;
	m_currentPosition = m_ghostObject->getWorldTransform().getOrigin();
	m_currentOrientation = m_ghostObject->getWorldTransform().getRotation();
	m_touchingContact = recoverFromPenetration(collisionWorld);
	m_targetPosition = m_currentPosition;
}

void btKinematicCharacterController::stepUp(btCollisionWorld* collisionWorld)
{
	// Raise the feet to exactly the step height above the ground they stand on (they hover by the
	// skin), so a step one millimetre higher is a wall.
	const btScalar raise = btMax(btScalar(0), m_stepHeight - kSkin);
	const btVector3 motion = m_up * raise;
	const Hit hit = sweep(collisionWorld, m_convexShape, m_ghostObject, m_currentOrientation, m_currentPosition,
	                      m_currentPosition + motion);
	const btVector3 reached = stopAt(m_currentPosition, motion, hit);
	m_currentStepOffset = (reached - m_currentPosition).dot(m_up);
	m_currentPosition = reached;
}

void btKinematicCharacterController::updateTargetPositionBasedOnCollision(const btVector3& hitNormal,
                                                                         btScalar tangentMag, btScalar normalMag)
{
	// What is left of the move slides along the surface: its part into the surface is removed.
	btVector3 remaining = m_targetPosition - m_currentPosition;
	const btScalar into = remaining.dot(hitNormal);
	if (into < 0) remaining -= hitNormal * (into * normalMag);
	(void)tangentMag;
	m_targetPosition = m_currentPosition + remaining;
}

void btKinematicCharacterController::stepForwardAndStrafe(btCollisionWorld* collisionWorld, const btVector3& walkMove)
{
	CharacterState& state = stateOf(this);
	state.blocked = false;
	m_targetPosition = m_currentPosition + walkMove;
	for (int i = 0; i < kSlideIterations; ++i)
	{
		const btVector3 motion = m_targetPosition - m_currentPosition;
		if (motion.length2() < kSkin * kSkin * btScalar(0.01)) break;
		const Hit hit = sweep(collisionWorld, m_convexShape, m_ghostObject, m_currentOrientation, m_currentPosition,
		                      m_targetPosition);
		if (!hit.hit)
		{
			m_currentPosition = m_targetPosition;
			break;
		}
		m_currentPosition = stopAt(m_currentPosition, motion, hit);
		if (!state.blocked)
		{
			state.blocked = true;
			state.blockPoint = hit.point;
		}
		m_touchingContact = true;
		m_touchingNormal = hit.normal;
		const btVector3 left = motion * (btScalar(1) - hit.fraction);
		m_targetPosition = m_currentPosition + left;
		// After stepping up, every hit is a wall: a step's edge just above the raised feet has a near
		// vertical normal and must not be climbed; walkable slopes are climbed by the step down.
		if (m_currentStepOffset <= 0 && hit.normal.dot(m_up) >= m_maxSlopeCosine)
		{
			// A walkable slope: slide along it, which climbs it.
			updateTargetPositionBasedOnCollision(hit.normal);
		}
		else
		{
			// A wall or a slope too steep to walk: only its horizontal push counts, so the character
			// slides along it and never climbs it.
			btVector3 wall = hit.normal - m_up * hit.normal.dot(m_up);
			if (wall.fuzzyZero()) break;
			wall.normalize();
			updateTargetPositionBasedOnCollision(wall);
			btVector3 rest = m_targetPosition - m_currentPosition;
			rest -= m_up * rest.dot(m_up);
			m_targetPosition = m_currentPosition + rest;
		}
	}
}

void btKinematicCharacterController::stepDown(btCollisionWorld* collisionWorld, btScalar dt)
{
	(void)dt;
	// Down by the step-up, by the fall of this substep, and (only if ground is found there) by a
	// further step height, so the character follows stairs and slopes down without floating off.
	const btScalar fall = btMax(btScalar(0), -m_verticalOffset);
	const btScalar plain = m_currentStepOffset + fall;
	const btScalar snap = (m_wasOnGround && m_verticalVelocity <= 0) ? m_stepHeight : btScalar(0);
	const btVector3 motion = -m_up * (plain + snap);
	const Hit hit = sweep(collisionWorld, m_convexShape, m_ghostObject, m_currentOrientation, m_currentPosition,
	                      m_currentPosition + motion);
	const btScalar total = plain + snap;
	CharacterState& state = stateOf(this);
	if (hit.hit)
	{
		const btVector3 landed = stopAt(m_currentPosition, motion, hit);
		bool walkable = hit.normal.dot(m_up) >= m_maxSlopeCosine;
		if (!walkable)
		{
			// Standing on an edge (a stair's nose) counts as ground when the surface right under the
			// centre is walkable and within a step.
			btVector3 aabbMin, aabbMax;
			m_convexShape->getAabb(btTransform::getIdentity(), aabbMin, aabbMax);
			const btScalar reach = btMax(aabbMax.dot(m_up), -aabbMin.dot(m_up)) + m_stepHeight + kSkin;
			GroundRay ray(m_ghostObject, landed, landed - m_up * reach);
			collisionWorld->rayTest(landed, landed - m_up * reach, ray);
			walkable = ray.hasHit() && ray.m_hitNormalWorld.normalized().dot(m_up) >= m_maxSlopeCosine;
		}
		if (walkable)
		{
			m_currentPosition = landed;
			m_wasOnGround = true;
			m_wasJumping = false;
			m_verticalVelocity = 0;
			state.ground = hit.object;
			state.groundPose = hit.object->getWorldTransform();
			return;
		}
		if (hit.fraction * total <= plain + kSkin)
		{
			// Too steep to stand on: slide down along it with what is left of the fall.
			m_currentPosition = landed;
			btVector3 slide = motion * (btScalar(1) - hit.fraction) * (plain / btMax(total, SIMD_EPSILON));
			slide -= hit.normal * slide.dot(hit.normal);
			const Hit slideHit = sweep(collisionWorld, m_convexShape, m_ghostObject, m_currentOrientation,
			                           m_currentPosition, m_currentPosition + slide);
			m_currentPosition = stopAt(m_currentPosition, slide, slideHit);
			m_wasOnGround = false;
			state.ground = 0;
			return;
		}
	}
	// Nothing to stand on within reach: fall by this substep's fall only.
	m_currentPosition += -m_up * plain;
	m_wasOnGround = false;
	state.ground = 0;
}

namespace
{
// Whether the obstacle the walk was stopped at is a step no higher than stepHeight: the top of the
// obstacle just beyond the blocking point, found by a ray down from above, measured from the ground
// under the feet (which hover by the skin). A face taller than the probe has no top within reach.
bool climbableStep(btCollisionWorld* world, const btCollisionObject* self, const btVector3& up, btScalar stepHeight,
                   const btVector3& groundPoint, const btVector3& walk, const btVector3& blockPoint)
{
	btVector3 across = walk - up * walk.dot(up);
	if (across.fuzzyZero()) return false;
	across.normalize();
	const btVector3 column = blockPoint + across * btScalar(0.01);
	const btScalar base = groundPoint.dot(up);
	const btVector3 foot = column + up * (base - column.dot(up));
	const btVector3 top = foot + up * (2 * stepHeight + btScalar(0.05));
	GroundRay ray(self, top, foot);
	world->rayTest(top, foot, ray);
	if (!ray.hasHit() || ray.m_closestHitFraction <= 0) return false;
	return ray.m_hitPointWorld.dot(up) - base <= stepHeight;
}
}  // namespace

void btKinematicCharacterController::playerStep(btCollisionWorld* collisionWorld, btScalar dt)
{
	if (!m_ghostObject || !m_convexShape || !collisionWorld || !(dt > 0) || !btIsFinite(dt)) return;
	if (!ghostInWorld(this, m_ghostObject)) return;

	// Turning about up.
	const btScalar turnRate = m_AngVel.dot(m_up);
	if (turnRate != 0)
	{
		m_currentOrientation = btQuaternion(m_up, turnRate * dt) * m_currentOrientation;
		m_currentOrientation.normalize();
		m_AngVel *= btPow(btScalar(1) - m_angularDamping, dt);
	}

	// Ride what it stands on: the ground's motion since the last substep carried to the feet (however
	// the ground was moved: simulated, kinematic, or set by the user), swept so it cannot carry the
	// character into a wall.
	CharacterState& state = stateOf(this);
	if (m_wasOnGround && state.ground)
	{
		const btTransform& now = state.ground->getWorldTransform();
		const btVector3 carry = (now * state.groundPose.inverse())(m_currentPosition) - m_currentPosition;
		if (!carry.fuzzyZero() && caliber::isFinite(carry))
		{
			// The ground may have moved into the feet (a lift going up): the upward part needs no sweep.
			const btVector3 up = m_up * btMax(btScalar(0), carry.dot(m_up));
			m_currentPosition += up;
			const btVector3 rest = carry - up;
			const Hit hit = sweep(collisionWorld, m_convexShape, m_ghostObject, m_currentOrientation,
			                      m_currentPosition, m_currentPosition + rest);
			m_currentPosition = stopAt(m_currentPosition, rest, hit);
		}
	}

	// Vertical motion: constant gravity integrated exactly over the substep, limited by the fall speed.
	const btScalar before = m_verticalVelocity;
	btScalar after = before - m_gravity * dt;
	if (after < -m_fallSpeed) after = -m_fallSpeed;
	m_verticalOffset = (before + after) * btScalar(0.5) * dt;
	m_verticalVelocity = after * btPow(btScalar(1) - m_linearDamping, dt);

	// Walking displacement, along the ground plane only.
	btVector3 walk = m_walkDirection;
	if (!m_useWalkDirection)
	{
		const btScalar time = btMin(dt, m_velocityTimeInterval);
		m_velocityTimeInterval = btMax(btScalar(0), m_velocityTimeInterval - dt);
		walk = m_walkDirection * time;
	}
	walk -= m_up * walk.dot(m_up);

	m_currentStepOffset = 0;
	m_touchingContact = false;
	if (m_verticalOffset > 0)
	{
		const btVector3 rise = m_up * m_verticalOffset;
		const Hit hit = sweep(collisionWorld, m_convexShape, m_ghostObject, m_currentOrientation, m_currentPosition,
		                      m_currentPosition + rise);
		m_currentPosition = stopAt(m_currentPosition, rise, hit);
		if (hit.hit && m_verticalVelocity > 0) m_verticalVelocity = 0;  // head against a ceiling
		m_wasOnGround = false;
	}
	const btVector3 start = m_currentPosition;
	auto progress = [&]() {
		btVector3 moved = m_currentPosition - start;
		moved -= m_up * moved.dot(m_up);
		return moved.length();
	};
	stepForwardAndStrafe(collisionWorld, walk);
	const btScalar walkedProgress = progress();
	if (m_wasOnGround && before <= 0 && state.blocked && walkedProgress < walk.length() * btScalar(0.999) &&
	    climbableStep(collisionWorld, m_ghostObject, m_up, m_stepHeight,
	                  start - m_up * (feetBelowCentre(m_convexShape, m_up) + kSkin), walk, state.blockPoint))
	{
		// Walk again with the feet raised by the step height, and keep that if it went further.
		const btVector3 walked = m_currentPosition;
		m_currentPosition = start;
		stepUp(collisionWorld);
		stepForwardAndStrafe(collisionWorld, walk);
		if (progress() <= walkedProgress + kSkin)
		{
			m_currentPosition = walked;
			m_currentStepOffset = 0;
		}
	}
	stepDown(collisionWorld, dt);

	m_ghostObject->setWorldTransform(btTransform(m_currentOrientation, m_currentPosition));
	m_targetPosition = m_currentPosition;
}

void btKinematicCharacterController::debugDraw(btIDebugDraw* debugDrawer)
{
	if (!debugDrawer || !m_ghostObject) return;
	const btVector3 origin = m_ghostObject->getWorldTransform().getOrigin();
	debugDrawer->drawLine(origin, origin + m_up, btVector3(0, 1, 0));
	if (m_touchingContact) debugDrawer->drawLine(origin, origin + m_touchingNormal, btVector3(1, 0, 0));
}
