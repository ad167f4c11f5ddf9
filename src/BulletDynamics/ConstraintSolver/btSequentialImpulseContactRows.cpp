// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The contact half of the solver's setup: manifold points become normal, friction and rolling rows.
#include "BulletCollision/CollisionShapes/btConvexShape.h"
#include "BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletCollision/NarrowPhaseCollision/ManifoldPrefetch.h"
#include "BulletDynamics/ConstraintSolver/btContactRowSetup.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btSimdBatch.h"
#include "LinearMath/btThreads.h"

#include "LinearMath/btCpuFeatures.h"

#define CALIBER_CONTACT_ROWS_AVX2 CALIBER_AVX2_BUILDS

namespace
{
const btScalar kUnbounded = btScalar(1e10);

// What a row needs to know about one of its bodies.
struct RowBody
{
	const btSolverBody* solverBody;
	const btRigidBody* dynamicBody;  // the rigid body when it is dynamic; 0 for static and kinematic ones

	// Decided once per contact point instead of per use: a point's rows use both bodies many times.
	static RowBody of(const btSolverBody& body)
	{
		const btRigidBody* rigid = body.m_originalBody;
		return {&body, rigid && !rigid->isStaticOrKinematicObject() ? rigid : nullptr};
	}

	// I^-1 F axis, where F is the angular factor; zero for bodies that do not turn.
	btVector3 angularComponent(const btVector3& axis) const
	{
		if (!dynamicBody) return btVector3(0, 0, 0);
		return dynamicBody->getInvInertiaTensorWorld() * (axis * dynamicBody->getAngularFactor());
	}
	// The velocity change the body's accumulated force and torque gave it this step (the world adds them
	// to the velocities before the solve).
	btVector3 forceVelocityChange(btScalar timeStep) const
	{
		if (!dynamicBody) return btVector3(0, 0, 0);
		return dynamicBody->getTotalForce() * solverBody->m_invMass * timeStep;
	}
	btVector3 torqueVelocityChange(btScalar timeStep) const
	{
		if (!dynamicBody) return btVector3(0, 0, 0);
		return dynamicBody->getInvInertiaTensorWorld() * dynamicBody->getTotalTorque() * solverBody->m_angularFactor *
		       timeStep;
	}
	btVector3 angularFactor() const { return solverBody->m_angularFactor; }
	btVector3 invMass() const { return solverBody->m_invMass; }
	btVector3 linearVelocity() const { return solverBody->m_linearVelocity; }
	btVector3 angularVelocity() const { return solverBody->m_angularVelocity; }
};

// Fills the Jacobian half of a row: linear directions n and -n, angular axes r1 x n and -(r2 x n);
// returns J M^-1 J^T.
SIMD_FORCE_INLINE btScalar setupJacobian(btSolverConstraint& row, const RowBody& a, const RowBody& b,
                                         const btVector3& normal, const btVector3& relPos1, const btVector3& relPos2)
{
	row.m_contactNormal1 = normal;
	row.m_contactNormal2 = -normal;
	row.m_relpos1CrossNormal = relPos1.cross(normal);
	row.m_relpos2CrossNormal = -relPos2.cross(normal);
	row.m_angularComponentA = a.angularComponent(row.m_relpos1CrossNormal);
	row.m_angularComponentB = b.angularComponent(row.m_relpos2CrossNormal);
	// (linear A + linear B) + (angular A + angular B), the four dot products side by side.
	const caliber::Dot4 terms = caliber::dot4(normal, normal * a.invMass(), normal, normal * b.invMass(),
	                                          row.m_relpos1CrossNormal, row.m_angularComponentA * a.angularFactor(),
	                                          row.m_relpos2CrossNormal, row.m_angularComponentB * b.angularFactor());
	return terms.sumOfPairs();
}

// The same for a purely angular row about axis (rolling and spinning friction).
btScalar setupAngularJacobian(btSolverConstraint& row, const RowBody& a, const RowBody& b, const btVector3& axis)
{
	row.m_contactNormal1.setZero();
	row.m_contactNormal2.setZero();
	row.m_relpos1CrossNormal = axis;
	row.m_relpos2CrossNormal = -axis;
	row.m_angularComponentA = a.angularComponent(axis);
	row.m_angularComponentB = b.angularComponent(-axis);
	return axis.dot(row.m_angularComponentA * a.angularFactor()) +
	       (-axis).dot(row.m_angularComponentB * b.angularFactor());
}

// J v at the start of the solve. Inlined: a call made the set-up spill and reload its registers around it.
SIMD_FORCE_INLINE btScalar rowVelocity(const btSolverConstraint& row, const RowBody& a, const RowBody& b)
{
	const caliber::Dot4 terms =
	    caliber::dot4(row.m_contactNormal1, a.linearVelocity(), row.m_relpos1CrossNormal, a.angularVelocity(),
	                  row.m_contactNormal2, b.linearVelocity(), row.m_relpos2CrossNormal, b.angularVelocity());
	return terms.sumInOrder();
}

// How a bouncing contact leaves the step. Velocities are those of semi-implicit Euler (x1 = x0 + v1 h):
// the velocity a body moves with over a step is its true velocity at the middle of the step. In those
// terms the exact answer is known for a pair under constant forces: the gap x(t) = gap + u0 t + a t^2/2
// closes at time tc with speed wc and reopens at e wc along the rebound trajectory r(t). When r, taken
// back in time, passes through the starting gap, the pair simply moves along that time-shifted rebound
// from where it is: the right energy, no position correction, at most a step early. A weak rebound
// whose top stays below the starting gap cannot: the pair then follows r itself, with a position
// correction (pushGap = r(0) - gap, negative) that a push moves without leaving velocity.
//   startVelocity   J v before this step's forces (negative when approaching)
//   acceleration    relative normal acceleration of the forces (J a)
//   gap             distance at the start of the step (0 when touching or penetrating)
struct Bounce
{
	btScalar velocity;  // J v to leave the step with
	btScalar pushGap;   // position correction along the normal (<= 0)
};
bool bounceTarget(btScalar startVelocity, btScalar acceleration, btScalar gap, btScalar restitution,
                  btScalar velocityThreshold, btScalar timeStep, Bounce& bounce)
{
	const btScalar halfStepGain = acceleration * timeStep * btScalar(0.5);
	const btScalar velocityNow = startVelocity + halfStepGain;  // true velocity at the start of the step
	const btScalar impactSpeed2 = velocityNow * velocityNow - btScalar(2) * acceleration * gap;
	if (!(velocityNow < btScalar(0)) || !(impactSpeed2 > velocityThreshold * velocityThreshold)) return false;
	const btScalar reboundSpeed2 = restitution * restitution * impactSpeed2 + btScalar(2) * acceleration * gap;
	if (reboundSpeed2 >= btScalar(0))
	{
		bounce.velocity = btSqrt(reboundSpeed2) + halfStepGain;
		bounce.pushGap = btScalar(0);
		return true;
	}
	// Only an attracting force (acceleration < 0) makes the rebound fall short of the gap.
	const btScalar impactSpeed = btSqrt(impactSpeed2);
	const btScalar impactTime = btScalar(2) * gap / (impactSpeed - velocityNow);
	const btScalar reboundSpeed = restitution * impactSpeed;
	bounce.velocity = reboundSpeed + acceleration * (btScalar(0.5) * timeStep - impactTime);
	bounce.pushGap = -reboundSpeed * impactTime + btScalar(0.5) * acceleration * impactTime * impactTime - gap;
	return true;
}

// What every friction-like row (sliding, rolling, spinning) shares once its Jacobian is set: its bodies,
// its coefficient (the bound is the coefficient times the normal impulse, set per sweep), its softness,
// and the target velocity as a right-hand side.
SIMD_FORCE_INLINE void finishFrictionRow(btSolverConstraint& row, const RowBody& a, const RowBody& b,
                                         int solverBodyIdA, int solverBodyIdB, btManifoldPoint& cp, btScalar friction,
                                         int frictionIndex, btScalar denominator, btScalar cfm,
                                         btScalar desiredVelocity)
{
	row.m_jacDiagABInv = denominator + cfm > SIMD_EPSILON ? btScalar(1) / (denominator + cfm) : btScalar(0);
	row.m_cfm = cfm * row.m_jacDiagABInv;
	row.m_solverBodyIdA = solverBodyIdA;
	row.m_solverBodyIdB = solverBodyIdB;
	row.m_originalContactPoint = &cp;
	row.m_friction = friction;
	row.m_frictionIndex = frictionIndex;
	row.m_overrideNumSolverIterations = -1;
	row.m_appliedImpulse = btScalar(0);
	row.m_appliedPushImpulse = btScalar(0);
	row.m_lowerLimit = -kUnbounded;
	row.m_upperLimit = kUnbounded;
	row.m_rhs = (desiredVelocity - rowVelocity(row, a, b)) * row.m_jacDiagABInv;
	row.m_rhsPenetration = btScalar(0);
}

void applyWarmStart(btSolverConstraint& row, btSolverBody& a, btSolverBody& b)
{
	a.applyImpulse(row.m_contactNormal1, row.m_angularComponentA, row.m_appliedImpulse);
	b.applyImpulse(row.m_contactNormal2, row.m_angularComponentB, row.m_appliedImpulse);
}

// How far a body's surface can sweep by turning over a step (0 for a sphere, which turning does not move).
btScalar turningSweep(const btCollisionShape& shape, const btSolverBody& body, btScalar timeStep)
{
	if (shape.getShapeType() == SPHERE_SHAPE_PROXYTYPE) return btScalar(0);
	return body.m_angularVelocity.length() * shape.getAngularMotionDisc() * timeStep;
}

// A speculative point is a plane through the nearest points: the row lets the pair close the gap
// along the normal and no more. At a face that is exact; at an edge or a corner the distance grows
// again as the bodies slide past, and a pair passing close by at speed would be stopped by a contact
// it never makes (a ghost hit). So a convex pair that would close its gap along the normal this step
// while sliding further than the gap, and barely turning, is cast along its motion over the step
// (linear conservative advancement); if it meets nothing, the point gets no rows.
bool slidesPastWithoutTouching(const btCollisionObject& objectA, const btCollisionObject& objectB,
                               const btSolverBody& a, const btSolverBody& b, const btManifoldPoint& cp,
                               btScalar timeStep)
{
	const btCollisionShape* shapeA = objectA.getCollisionShape();
	const btCollisionShape* shapeB = objectB.getCollisionShape();
	if (!shapeA || !shapeB || !shapeA->isConvex() || !shapeB->isConvex()) return false;
	const btScalar gap = cp.getDistance();
	const btVector3& normal = cp.m_normalWorldOnB;
	const btVector3 relative = a.m_linearVelocity - b.m_linearVelocity;
	const btScalar closing = -normal.dot(relative) * timeStep;
	if (!(closing > gap)) return false;  // the row would not act: nothing to decide
	const btVector3 sliding = relative - normal * normal.dot(relative);
	if (!(sliding.length() * timeStep > gap)) return false;  // mostly head on: the plane is right
	// The cast moves the shapes without turning them: only trusted when turning sweeps little.
	if (turningSweep(*shapeA, a, timeStep) + turningSweep(*shapeB, b, timeStep) > btScalar(0.1) * gap) return false;

	btVoronoiSimplexSolver simplex;
	btGjkConvexCast cast(static_cast<const btConvexShape*>(shapeA), static_cast<const btConvexShape*>(shapeB),
	                     &simplex);
	btTransform toA = objectA.getWorldTransform(), toB = objectB.getWorldTransform();
	toA.setOrigin(toA.getOrigin() + a.m_linearVelocity * timeStep);
	toB.setOrigin(toB.getOrigin() + b.m_linearVelocity * timeStep);
	btConvexCast::CastResult result;
	return !cast.calcTimeOfImpact(objectA.getWorldTransform(), toA, objectB.getWorldTransform(), toB, result);
}

// rowBounce for a point with restitution.
bool restitutionRowBounce(const btSolverConstraint& row, const RowBody& a, const RowBody& b, const btManifoldPoint& cp,
                          const btContactSolverInfo& infoGlobal, caliber::SolverBounceRow& bounce)
{
	const btScalar relativeVelocity = rowVelocity(row, a, b);
	const btScalar penetration = cp.getDistance() + infoGlobal.m_linearSlop;
	// The velocity change this step's forces gave the pair (the world adds them before the solve).
	const btScalar forceVelocity = row.m_contactNormal1.dot(a.forceVelocityChange(infoGlobal.m_timeStep)) +
	                               row.m_relpos1CrossNormal.dot(a.torqueVelocityChange(infoGlobal.m_timeStep)) +
	                               row.m_contactNormal2.dot(b.forceVelocityChange(infoGlobal.m_timeStep)) +
	                               row.m_relpos2CrossNormal.dot(b.torqueVelocityChange(infoGlobal.m_timeStep));
	const btScalar invTimeStep = btScalar(1) / infoGlobal.m_timeStep;
	Bounce target;
	if (!bounceTarget(relativeVelocity - forceVelocity, forceVelocity * invTimeStep, btMax(btScalar(0), penetration),
	                  cp.m_combinedRestitution, infoGlobal.m_restitutionVelocityThreshold, infoGlobal.m_timeStep,
	                  target))
		return false;
	bounce.startVelocity = relativeVelocity;
	bounce.targetVelocity = target.velocity;
	bounce.targetPushVelocity = target.pushGap * invTimeStep;
	return true;
}

// Whether a contact row rebounds if it is met this step, and how (its J v at setup, the target J v and
// the push velocity of a weak rebound); bounce.row is left to the caller. Most points have no
// restitution: that test is inlined, the rest is a call.
SIMD_FORCE_INLINE bool rowBounce(const btSolverConstraint& row, const RowBody& a, const RowBody& b,
                                 const btManifoldPoint& cp, const btContactSolverInfo& infoGlobal,
                                 caliber::SolverBounceRow& bounce)
{
	if (!(cp.m_combinedRestitution > btScalar(0))) return false;
	return restitutionRowBounce(row, a, b, cp, infoGlobal, bounce);
}

// One test on the sum rather than caliber::isFinite per vector: cheaper per contact, and a sum that
// overflows (a point near the float range) is refused too.
bool isFinitePoint(const btManifoldPoint& cp)
{
	const btVector3& a = cp.m_positionWorldOnA;
	const btVector3& b = cp.m_positionWorldOnB;
	const btVector3& n = cp.m_normalWorldOnB;
	return btIsFinite(a.x() + a.y() + a.z() + b.x() + b.y() + b.z() + n.x() + n.y() + n.z() + cp.m_distance1);
}

// Scales a friction direction by the object's anisotropic friction when the object has the mode's flag:
// in the object's frame, each local axis's friction is the direction's component along it times that
// axis's factor (Bullet's convention; the row is not renormalised, so a factor also scales the row's
// impulse per unit of sliding speed).
void scaleByAnisotropicFriction(const btCollisionObject* colObj, btVector3& frictionDirection, int frictionMode)
{
	if (!colObj || !colObj->hasAnisotropicFriction(frictionMode)) return;
	const btMatrix3x3& basis = colObj->getWorldTransform().getBasis();
	const btVector3 local = frictionDirection * basis;
	frictionDirection = basis * (local * colObj->getAnisotropicFriction());
}

// Fills a contact's normal row; its warm-start impulse is set but not applied to the bodies.
SIMD_FORCE_INLINE void setupContactRow(const RowBody& a, const RowBody& b, btSolverConstraint& row, int solverBodyIdA,
                                       int solverBodyIdB, btManifoldPoint& cp, const btContactSolverInfo& infoGlobal,
                                       btScalar& relaxation, const btVector3& rel_pos1, const btVector3& rel_pos2)
{
	relaxation = infoGlobal.m_sor;
	const btScalar invTimeStep = btScalar(1) / infoGlobal.m_timeStep;

	const btScalar denominator = setupJacobian(row, a, b, cp.m_normalWorldOnB, rel_pos1, rel_pos2);
	btScalar erp = infoGlobal.m_erp2;
	btScalar cfm = infoGlobal.m_globalCfm;
	if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_CFM) cfm = cp.m_contactCFM;
	if (cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP) erp = cp.m_contactERP;
	// CFM is given per step in Bullet's convention (impulse-space softness scales with 1/h).
	cfm *= invTimeStep;
	row.m_jacDiagABInv = denominator + cfm > SIMD_EPSILON ? btScalar(1) / (denominator + cfm) : btScalar(0);
	row.m_cfm = cfm * row.m_jacDiagABInv;
	row.m_solverBodyIdA = solverBodyIdA;
	row.m_solverBodyIdB = solverBodyIdB;
	row.m_originalContactPoint = &cp;
	row.m_friction = cp.m_combinedFriction;
	row.m_overrideNumSolverIterations = -1;
	row.m_frictionIndex = -1;
	row.m_lowerLimit = btScalar(0);
	row.m_upperLimit = kUnbounded;
	row.m_appliedPushImpulse = btScalar(0);

	const btScalar relativeVelocity = rowVelocity(row, a, b);
	const btScalar penetration = cp.getDistance() + infoGlobal.m_linearSlop;
	// Restitution has a pass of its own after the velocity sweeps (solveRestitution): the sweeps treat a
	// bouncing contact like any other (close the gap, stop), and the pass then gives every contact that
	// was really met this step (it took an impulse) its rebound. Deciding the bounce here instead would
	// bounce contacts that other rows keep apart, or miss impacts that fall between two steps.
	caliber::SolverBounceRow bounce;
	const bool bounces = rowBounce(row, a, b, cp, infoGlobal, bounce);
	btScalar velocityError = -relativeVelocity;
	btScalar positionalError = btScalar(0);
	// Deep penetrations are resolved by the split-impulse pass, which moves the bodies without adding
	// the velocity that Baumgarte stabilisation would leave behind (the "popping" of deep contacts). So
	// is any penetration of a bouncing contact: a Baumgarte velocity would add to the rebound's energy.
	const bool useSplit =
	    infoGlobal.m_splitImpulse && (penetration <= infoGlobal.m_splitImpulsePenetrationThreshold || bounces);
	if (penetration > btScalar(0))
	{
		// Speculative: the bodies may still close the gap this step, but not more.
		velocityError -= penetration * invTimeStep;
	}
	else
	{
		if (!useSplit && !(cp.m_contactPointFlags & BT_CONTACT_FLAG_HAS_CONTACT_ERP)) erp = infoGlobal.m_erp;
		positionalError = -penetration * erp * invTimeStep;
	}
	const btScalar penetrationImpulse = positionalError * row.m_jacDiagABInv;
	const btScalar velocityImpulse = velocityError * row.m_jacDiagABInv;
	if (!useSplit)
	{
		row.m_rhs = penetrationImpulse + velocityImpulse;
		row.m_rhsPenetration = btScalar(0);
	}
	else
	{
		row.m_rhs = velocityImpulse;
		row.m_rhsPenetration = penetrationImpulse;
	}

	// The warm start: the impulse is set here, applied to the bodies by the caller (see applyWarmStart).
	row.m_appliedImpulse = (infoGlobal.m_solverMode & SOLVER_USE_WARMSTARTING)
	                           ? cp.m_appliedImpulse * infoGlobal.m_warmstartingFactor
	                           : btScalar(0);
}

// Fills a friction row along normalAxis (its m_frictionIndex set by the caller).
SIMD_FORCE_INLINE void setupFrictionRow(const RowBody& a, const RowBody& b, btSolverConstraint& row,
                                        const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB,
                                        btManifoldPoint& cp, const btVector3& rel_pos1, const btVector3& rel_pos2,
                                        btScalar desiredVelocity, btScalar cfmSlip)
{
	const btScalar denominator = setupJacobian(row, a, b, normalAxis, rel_pos1, rel_pos2);
	finishFrictionRow(row, a, b, solverBodyIdA, solverBodyIdB, cp, cp.m_combinedFriction, row.m_frictionIndex,
	                  denominator, cfmSlip + cp.m_frictionCFM, desiredVelocity);
}

// Fills an angular friction row about normalAxis (its m_frictionIndex set by the caller).
void setupTorsionalRow(btAlignedObjectArray<btSolverBody>& bodies, btSolverConstraint& row, const btVector3& normalAxis,
                       int solverBodyIdA, int solverBodyIdB, btManifoldPoint& cp, btScalar combinedTorsionalFriction,
                       btScalar desiredVelocity, btScalar cfmSlip)
{
	const RowBody a = RowBody::of(bodies[solverBodyIdA]);
	const RowBody b = RowBody::of(bodies[solverBodyIdB]);
	const btScalar denominator = setupAngularJacobian(row, a, b, normalAxis);
	finishFrictionRow(row, a, b, solverBodyIdA, solverBodyIdB, cp, combinedTorsionalFriction, row.m_frictionIndex,
	                  denominator, cfmSlip, desiredVelocity);
}
}  // namespace

void btSequentialImpulseConstraintSolver::setupContactConstraint(btSolverConstraint& row, int solverBodyIdA,
                                                                 int solverBodyIdB, btManifoldPoint& cp,
                                                                 const btContactSolverInfo& infoGlobal,
                                                                 btScalar& relaxation, const btVector3& rel_pos1,
                                                                 const btVector3& rel_pos2)
{
	setupContactRow(RowBody::of(m_tmpSolverBodyPool[solverBodyIdA]), RowBody::of(m_tmpSolverBodyPool[solverBodyIdB]),
	                row, solverBodyIdA, solverBodyIdB, cp, infoGlobal, relaxation, rel_pos1, rel_pos2);
	applyWarmStart(row, m_tmpSolverBodyPool[solverBodyIdA], m_tmpSolverBodyPool[solverBodyIdB]);
}

void btSequentialImpulseConstraintSolver::setupFrictionConstraint(
    btSolverConstraint& row, const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB, btManifoldPoint& cp,
    const btVector3& rel_pos1, const btVector3& rel_pos2, btCollisionObject* colObj0, btCollisionObject* colObj1,
    btScalar relaxation, const btContactSolverInfo& infoGlobal, btScalar desiredVelocity, btScalar cfmSlip)
{
	(void)colObj0;
	(void)colObj1;
	(void)relaxation;
	(void)infoGlobal;
	setupFrictionRow(RowBody::of(m_tmpSolverBodyPool[solverBodyIdA]), RowBody::of(m_tmpSolverBodyPool[solverBodyIdB]),
	                 row, normalAxis, solverBodyIdA, solverBodyIdB, cp, rel_pos1, rel_pos2, desiredVelocity, cfmSlip);
}

void btSequentialImpulseConstraintSolver::setupTorsionalFrictionConstraint(
    btSolverConstraint& row, const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB, btManifoldPoint& cp,
    btScalar combinedTorsionalFriction, const btVector3& rel_pos1, const btVector3& rel_pos2,
    btCollisionObject* colObj0, btCollisionObject* colObj1, btScalar relaxation, btScalar desiredVelocity,
    btScalar cfmSlip)
{
	(void)rel_pos1;
	(void)rel_pos2;
	(void)colObj0;
	(void)colObj1;
	(void)relaxation;
	setupTorsionalRow(m_tmpSolverBodyPool, row, normalAxis, solverBodyIdA, solverBodyIdB, cp, combinedTorsionalFriction,
	                  desiredVelocity, cfmSlip);
}

btSolverConstraint& btSequentialImpulseConstraintSolver::addFrictionConstraint(
    const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB, int frictionIndex, btManifoldPoint& cp,
    const btVector3& rel_pos1, const btVector3& rel_pos2, btCollisionObject* colObj0, btCollisionObject* colObj1,
    btScalar relaxation, const btContactSolverInfo& infoGlobal, btScalar desiredVelocity, btScalar cfmSlip)
{
	btSolverConstraint& row = m_tmpSolverContactFrictionConstraintPool.expandNonInitializing();
	row.m_frictionIndex = frictionIndex;
	setupFrictionConstraint(row, normalAxis, solverBodyIdA, solverBodyIdB, cp, rel_pos1, rel_pos2, colObj0, colObj1,
	                        relaxation, infoGlobal, desiredVelocity, cfmSlip);
	return row;
}

btSolverConstraint& btSequentialImpulseConstraintSolver::addTorsionalFrictionConstraint(
    const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB, int frictionIndex, btManifoldPoint& cp,
    btScalar torsionalFriction, const btVector3& rel_pos1, const btVector3& rel_pos2, btCollisionObject* colObj0,
    btCollisionObject* colObj1, btScalar relaxation, const btContactSolverInfo& infoGlobal, btScalar desiredVelocity,
    btScalar cfmSlip)
{
	(void)infoGlobal;
	btSolverConstraint& row = m_tmpSolverContactRollingFrictionConstraintPool.expandNonInitializing();
	row.m_frictionIndex = frictionIndex;
	setupTorsionalFrictionConstraint(row, normalAxis, solverBodyIdA, solverBodyIdB, cp, torsionalFriction, rel_pos1,
	                                 rel_pos2, colObj0, colObj1, relaxation, desiredVelocity, cfmSlip);
	return row;
}

void btSequentialImpulseConstraintSolver::applyAnisotropicFriction(btCollisionObject* colObj,
                                                                   btVector3& frictionDirection, int frictionMode)
{
	scaleByAnisotropicFriction(colObj, frictionDirection, frictionMode);
}

void btSequentialImpulseConstraintSolver::setFrictionConstraintImpulse(btSolverConstraint& contactRow,
                                                                       int solverBodyIdA, int solverBodyIdB,
                                                                       btManifoldPoint& cp,
                                                                       const btContactSolverInfo& infoGlobal)
{
	const int first = contactRow.m_frictionIndex;
	if (first < 0) return;
	const int rows = btMin(caliber::frictionRowsPerContact(infoGlobal),
	                       m_tmpSolverContactFrictionConstraintPool.size() - first);
	btSolverBody& bodyA = m_tmpSolverBodyPool[solverBodyIdA];
	btSolverBody& bodyB = m_tmpSolverBodyPool[solverBodyIdB];
	for (int f = 0; f < rows; ++f)
	{
		btSolverConstraint& friction = m_tmpSolverContactFrictionConstraintPool[first + f];
		if (infoGlobal.m_solverMode & SOLVER_USE_WARMSTARTING)
		{
			const btScalar previous = f == 0 ? cp.m_appliedImpulseLateral1 : cp.m_appliedImpulseLateral2;
			friction.m_appliedImpulse = previous * infoGlobal.m_warmstartingFactor;
			applyWarmStart(friction, bodyA, bodyB);
		}
		else
		{
			friction.m_appliedImpulse = btScalar(0);
		}
	}
}

btScalar btSequentialImpulseConstraintSolver::restitutionCurve(btScalar rel_vel, btScalar restitution,
                                                               btScalar velocityThreshold)
{
	// rel_vel < 0 is an approach; slower than the threshold, nothing bounces.
	if (btFabs(rel_vel) < velocityThreshold) return btScalar(0);
	return -rel_vel * restitution;
}

void btSequentialImpulseConstraintSolver::convertContacts(btPersistentManifold** manifoldPtr, int numManifolds,
                                                          const btContactSolverInfo& infoGlobal)
{
	caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	for (int i = 0; i < numManifolds; ++i)
	{
		// Manifolds are scattered over the heap: the header line (with the point count) four ahead, then
		// the lines of the points held two ahead.
		if (i + 4 < numManifolds) caliber::prefetchManifoldHeader(manifoldPtr[i + 4]);
		if (i + 2 < numManifolds) caliber::prefetchManifoldPoints(manifoldPtr[i + 2]);
		const int firstRow = m_tmpSolverContactConstraintPool.size();
		convertContact(manifoldPtr[i], infoGlobal);
		if (m_tmpSolverContactConstraintPool.size() > firstRow) scratch.manifoldFirstRow.push_back(firstRow);
	}
}

bool caliber::solverBodiesCanMove(const btAlignedObjectArray<btSolverBody>& bodies, int solverBodyIdA,
                                  int solverBodyIdB)
{
	// Two bodies that nothing can move (static or kinematic against each other) need no rows.
	const btSolverBody& a = bodies[solverBodyIdA];
	const btSolverBody& b = bodies[solverBodyIdB];
	const bool aMoves = a.m_originalBody && !a.m_originalBody->isStaticOrKinematicObject();
	const bool bMoves = b.m_originalBody && !b.m_originalBody->isStaticOrKinematicObject();
	return aMoves || bMoves;
}

bool caliber::planContactPoint(btPersistentManifold& manifold, int index, btCollisionObject* colObj0,
                               btCollisionObject* colObj1, int solverBodyIdA, int solverBodyIdB,
                               const btAlignedObjectArray<btSolverBody>& bodies, const btContactSolverInfo& infoGlobal,
                               ContactPointRows& point)
{
	btManifoldPoint& cp = manifold.getContactPoint(index);
	if (cp.getDistance() > manifold.getContactProcessingThreshold()) return false;
	btAssert(isFinitePoint(cp));
	if (!isFinitePoint(cp)) return false;

	// Both bodies are pushed at the same point, halfway between the two witness points. With Bullet's
	// choice (each body at its own witness point) a friction impulse on a penetrating contact has
	// lever arms that differ by the depth, which creates angular momentum out of nothing.
	const btVector3 contactPoint = (cp.getPositionWorldOnA() + cp.getPositionWorldOnB()) * btScalar(0.5);
	point.relPos1 = contactPoint - colObj0->getWorldTransform().getOrigin();
	point.relPos2 = contactPoint - colObj1->getWorldTransform().getOrigin();

	if (cp.getDistance() > btScalar(0))
	{
		// A speculative point (apart, kept because the pair might close the gap this step) that its
		// bodies could not close even if each moved along the normal at twice its present normal speed
		// needs no rows: they would carry no impulse. Each body's own normal speed counts, not the
		// pair's relative approach: two boxes falling together do not approach, but the ground may
		// stop the lower one during the solve. Neighbours side by side (normal across the fall) and
		// fast approaches (what speculative contacts are for) are told apart. The point's old
		// impulses are cleared: a gap that wide means it carries none.
		const btSolverBody& a = bodies[solverBodyIdA];
		const btSolverBody& b = bodies[solverBodyIdB];
		const btVector3& n = cp.m_normalWorldOnB;
		const btScalar approach = btFabs(n.dot(a.m_linearVelocity + a.m_angularVelocity.cross(point.relPos1))) +
		                          btFabs(n.dot(b.m_linearVelocity + b.m_angularVelocity.cross(point.relPos2)));
		if (cp.getDistance() > btScalar(2) * approach * infoGlobal.m_timeStep ||
		    slidesPastWithoutTouching(*colObj0, *colObj1, a, b, cp, infoGlobal.m_timeStep))
		{
			cp.m_appliedImpulse = cp.m_appliedImpulseLateral1 = cp.m_appliedImpulseLateral2 = btScalar(0);
			return false;
		}
	}
	point.cp = &cp;
	point.object0 = colObj0;
	point.object1 = colObj1;
	point.solverBodyIdA = solverBodyIdA;
	point.solverBodyIdB = solverBodyIdB;
	return true;
}

namespace
{
// fillContactPointRows and applyContactPointWarmStarts, inlined into the serial set-up's loop over points.
SIMD_FORCE_INLINE void fillPointRows(const caliber::ContactRowPools& pools, const caliber::ContactPointRows& point,
                                     const btContactSolverInfo& infoGlobal)
{
	btAlignedObjectArray<btSolverBody>& bodies = *pools.bodies;
	btManifoldPoint& cp = *point.cp;
	btCollisionObject* colObj0 = point.object0;
	btCollisionObject* colObj1 = point.object1;
	const int solverBodyIdA = point.solverBodyIdA, solverBodyIdB = point.solverBodyIdB;
	const btVector3& rel_pos1 = point.relPos1;
	const btVector3& rel_pos2 = point.relPos2;
	const int frictionRowsPerContact = caliber::frictionRowsPerContact(infoGlobal);

	// The friction impulse of the last step as a vector, to warm start the new directions with its
	// projection (the directions follow the sliding velocity and turn from step to step).
	const btVector3 previousFrictionImpulse = cp.m_lateralFrictionDir1 * cp.m_appliedImpulseLateral1 +
	                                          cp.m_lateralFrictionDir2 * cp.m_appliedImpulseLateral2;

	const int frictionIndex = point.contactRow;
	btSolverConstraint& contactRow = (*pools.contacts)[frictionIndex];
	const btSolverBody& a = bodies[solverBodyIdA];
	const btSolverBody& b = bodies[solverBodyIdB];
	const RowBody rowA = RowBody::of(a), rowB = RowBody::of(b);
	btScalar relaxation;
	setupContactRow(rowA, rowB, contactRow, solverBodyIdA, solverBodyIdB, cp, infoGlobal, relaxation, rel_pos1,
	                rel_pos2);
	const btVector3& normal = cp.m_normalWorldOnB;

	// Rolling and spinning friction: angular rows about the normal and about two axes across it.
	int rollingRow = point.firstRollingRow;
	const auto addTorsional = [&](const btVector3& axis, btScalar friction)
	{
		btSolverConstraint& row = (*pools.rolling)[rollingRow++];
		row.m_frictionIndex = frictionIndex;
		setupTorsionalRow(bodies, row, axis, solverBodyIdA, solverBodyIdB, cp, friction, btScalar(0), btScalar(0));
	};
	if (cp.m_combinedSpinningFriction > btScalar(0)) addTorsional(normal, cp.m_combinedSpinningFriction);
	if (cp.m_combinedRollingFriction > btScalar(0))
	{
		// Zeroed first: btPlaneSpace1 sets x, y and z only, and the rows' w lanes should not be stack garbage.
		btVector3 axis0(0, 0, 0), axis1(0, 0, 0);
		btPlaneSpace1(normal, axis0, axis1);
		const btVector3 relativeSpin = a.m_angularVelocity - b.m_angularVelocity;
		btVector3 rolling = relativeSpin - normal * normal.dot(relativeSpin);
		if (rolling.length2() > SIMD_EPSILON)
		{
			axis0 = rolling.normalized();
			axis1 = normal.cross(axis0);
		}
		for (btVector3* axis : {&axis0, &axis1})
		{
			scaleByAnisotropicFriction(colObj0, *axis, btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
			scaleByAnisotropicFriction(colObj1, *axis, btCollisionObject::CF_ANISOTROPIC_ROLLING_FRICTION);
		}
		addTorsional(axis0, cp.m_combinedRollingFriction);
		addTorsional(axis1, cp.m_combinedRollingFriction);
	}

	// Sliding friction. The first direction follows the tangential relative velocity when there is
	// one, so that a sliding contact needs a single row and its friction opposes the sliding exactly;
	// the second, across it, is added with SOLVER_USE_2_FRICTION_DIRECTIONS.
	const bool keepUserDirections = (infoGlobal.m_solverMode & SOLVER_ENABLE_FRICTION_DIRECTION_CACHING) &&
	                                (cp.m_contactPointFlags & BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED);
	if (!keepUserDirections)
	{
		const btVector3 velocity = (a.m_linearVelocity + a.m_angularVelocity.cross(rel_pos1)) -
		                           (b.m_linearVelocity + b.m_angularVelocity.cross(rel_pos2));
		const btVector3 tangential = velocity - normal * normal.dot(velocity);
		const btScalar tangentialSpeed2 = tangential.length2();
		// Below about 0.35 mm/s (the float epsilon, as a squared speed, in either precision) the velocity
		// is the solver's noise, and following it would point each point's row anywhere: with double's
		// epsilon, 100 kg taking up its load on 1 kg got rows along noise and walked 8 mm sideways.
		const btScalar noiseSpeed2 = btScalar(1.1920928955078125e-07);
		if (!(infoGlobal.m_solverMode & SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION) &&
		    tangentialSpeed2 > noiseSpeed2)
		{
			cp.m_lateralFrictionDir1 = tangential / btSqrt(tangentialSpeed2);
			cp.m_lateralFrictionDir2 = cp.m_lateralFrictionDir1.cross(normal).normalized();
		}
		else
		{
			btPlaneSpace1(normal, cp.m_lateralFrictionDir1, cp.m_lateralFrictionDir2);
		}
		if ((infoGlobal.m_solverMode & SOLVER_ENABLE_FRICTION_DIRECTION_CACHING) &&
		    (infoGlobal.m_solverMode & SOLVER_DISABLE_VELOCITY_DEPENDENT_FRICTION_DIRECTION))
			cp.m_contactPointFlags |= BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
	}
	// Bullet's link from a contact row to its first friction row.
	contactRow.m_frictionIndex = point.firstFrictionRow;
	btVector3 direction1 = cp.m_lateralFrictionDir1, direction2 = cp.m_lateralFrictionDir2;
	if (colObj0->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION) ||
	    colObj1->hasAnisotropicFriction(btCollisionObject::CF_ANISOTROPIC_FRICTION))
	{
		for (btVector3* direction : {&direction1, &direction2})
		{
			scaleByAnisotropicFriction(colObj0, *direction, btCollisionObject::CF_ANISOTROPIC_FRICTION);
			scaleByAnisotropicFriction(colObj1, *direction, btCollisionObject::CF_ANISOTROPIC_FRICTION);
		}
	}
	for (int f = 0; f < frictionRowsPerContact; ++f)
	{
		btSolverConstraint& row = (*pools.friction)[point.firstFrictionRow + f];
		row.m_frictionIndex = frictionIndex;
		setupFrictionRow(rowA, rowB, row, f == 0 ? direction1 : direction2, solverBodyIdA, solverBodyIdB, cp, rel_pos1,
		                 rel_pos2, f == 0 ? cp.m_contactMotion1 : cp.m_contactMotion2, btScalar(0));
		if (infoGlobal.m_solverMode & SOLVER_USE_WARMSTARTING)
		{
			const btVector3& direction = f == 0 ? cp.m_lateralFrictionDir1 : cp.m_lateralFrictionDir2;
			row.m_appliedImpulse = previousFrictionImpulse.dot(direction) * infoGlobal.m_warmstartingFactor;
		}
	}
}

SIMD_FORCE_INLINE void applyPointWarmStarts(const caliber::ContactRowPools& pools,
                                            const caliber::ContactPointRows& point,
                                            const btContactSolverInfo& infoGlobal)
{
	if (!(infoGlobal.m_solverMode & SOLVER_USE_WARMSTARTING)) return;
	btSolverBody& bodyA = (*pools.bodies)[point.solverBodyIdA];
	btSolverBody& bodyB = (*pools.bodies)[point.solverBodyIdB];
	applyWarmStart((*pools.contacts)[point.contactRow], bodyA, bodyB);
	const int frictionRowsPerContact = caliber::frictionRowsPerContact(infoGlobal);
	for (int f = 0; f < frictionRowsPerContact; ++f)
		applyWarmStart((*pools.friction)[point.firstFrictionRow + f], bodyA, bodyB);
}

// The same two functions compiled a second time for AVX2 (VEX encoding), chosen at run time. The set-up
// is SSE arithmetic with a register copy before most operations in the two-operand SSE encoding (about 60
// of a point's 615 instructions in stack1000), which the three-operand encoding does without. Only AVX2 is
// enabled, not FMA: every operation rounds as in the SSE build, in the same order, so the rows have the
// same bits (ContactPointRowFill tests compare the two on varied points).
#if CALIBER_CONTACT_ROWS_AVX2
__attribute__((target("avx2"))) void fillPointRowsAvx2(const caliber::ContactRowPools& pools,
                                                        const caliber::ContactPointRows& point,
                                                        const btContactSolverInfo& infoGlobal)
{
	fillPointRows(pools, point, infoGlobal);
}

__attribute__((target("avx2"))) void fillPointRowsAndWarmStartsAvx2(const caliber::ContactRowPools& pools,
                                                                     const caliber::ContactPointRows& point,
                                                                     const btContactSolverInfo& infoGlobal)
{
	fillPointRows(pools, point, infoGlobal);
	applyPointWarmStarts(pools, point, infoGlobal);
}
#endif

// The baseline build as a call of its own, so that fillContactPointRows is a test and a jump to either build
// (with the baseline inlined into it, the choice paid for the baseline's register saves and stack frame).
__attribute__((noinline)) void fillPointRowsBaseline(const caliber::ContactRowPools& pools,
                                                     const caliber::ContactPointRows& point,
                                                     const btContactSolverInfo& infoGlobal)
{
	fillPointRows(pools, point, infoGlobal);
}

// Whether this processor runs the AVX2 set-up, decided when the library is loaded (a plain load per point;
// a function-local static's guard made the choice cost a stack frame). Before that, during other static
// initialisation, the flag is still false and the baseline runs: the same bits either way.
#if CALIBER_CONTACT_ROWS_AVX2
const bool g_avx2Rows = caliber::detectAvx2();
#endif

bool avx2RowsAvailable()
{
#if CALIBER_CONTACT_ROWS_AVX2
	return g_avx2Rows;
#else
	return false;
#endif
}
}  // namespace

void caliber::fillContactPointRows(const ContactRowPools& pools, const ContactPointRows& point,
                                   const btContactSolverInfo& infoGlobal)
{
#if CALIBER_CONTACT_ROWS_AVX2
	if (avx2RowsAvailable())
	{
		fillPointRowsAvx2(pools, point, infoGlobal);
		return;
	}
#endif
	fillPointRowsBaseline(pools, point, infoGlobal);
}

bool caliber::contactPointRowsUseAvx2() { return avx2RowsAvailable(); }

void caliber::fillContactPointRowsIn(const ContactRowPools& pools, const ContactPointRows& point,
                                     const btContactSolverInfo& infoGlobal, bool avx2, int warmStarts)
{
#if CALIBER_CONTACT_ROWS_AVX2
	if (avx2 && avx2RowsAvailable())
	{
		if (warmStarts == 1)
		{
			fillPointRowsAndWarmStartsAvx2(pools, point, infoGlobal);
			return;
		}
		fillPointRowsAvx2(pools, point, infoGlobal);
		if (warmStarts == 2) applyPointWarmStarts(pools, point, infoGlobal);
		return;
	}
#else
	(void)avx2;
#endif
	fillPointRows(pools, point, infoGlobal);
	if (warmStarts != 0) applyPointWarmStarts(pools, point, infoGlobal);
}

void caliber::applyContactPointWarmStarts(const ContactRowPools& pools, const ContactPointRows& point,
                                          const btContactSolverInfo& infoGlobal)
{
	// Not built for AVX2: loads, products and sums without register copies, the same count either way.
	applyPointWarmStarts(pools, point, infoGlobal);
}

void btSequentialImpulseConstraintSolver::convertContact(btPersistentManifold* manifold,
                                                         const btContactSolverInfo& infoGlobal)
{
	btCollisionObject* colObj0 = const_cast<btCollisionObject*>(manifold->getBody0());
	btCollisionObject* colObj1 = const_cast<btCollisionObject*>(manifold->getBody1());
	if (!colObj0 || !colObj1) return;
	const int solverBodyIdA = getOrInitSolverBody(*colObj0, infoGlobal.m_timeStep);
	const int solverBodyIdB = getOrInitSolverBody(*colObj1, infoGlobal.m_timeStep);
	if (!caliber::solverBodiesCanMove(m_tmpSolverBodyPool, solverBodyIdA, solverBodyIdB)) return;
	const int frictionRowsPerContact = caliber::frictionRowsPerContact(infoGlobal);
	const caliber::ContactRowPools pools = {&m_tmpSolverBodyPool, &m_tmpSolverContactConstraintPool,
	                                        &m_tmpSolverContactFrictionConstraintPool,
	                                        &m_tmpSolverContactRollingFrictionConstraintPool};
	caliber::ContactPointRows point;
	for (int j = 0; j < manifold->getNumContacts(); ++j)
	{
		if (!caliber::planContactPoint(*manifold, j, colObj0, colObj1, solverBodyIdA, solverBodyIdB,
		                               m_tmpSolverBodyPool, infoGlobal, point))
			continue;
		point.contactRow = m_tmpSolverContactConstraintPool.size();
		point.firstFrictionRow = m_tmpSolverContactFrictionConstraintPool.size();
		point.firstRollingRow = m_tmpSolverContactRollingFrictionConstraintPool.size();
		// One row at a time: expandNonInitializing grows the pools geometrically (resizeNoInitialize would
		// reallocate them to the exact size for every point).
		m_tmpSolverContactConstraintPool.expandNonInitializing();
		for (int f = 0; f < frictionRowsPerContact; ++f)
			m_tmpSolverContactFrictionConstraintPool.expandNonInitializing();
		for (int r = caliber::rollingRowsOf(*point.cp); r > 0; --r)
			m_tmpSolverContactRollingFrictionConstraintPool.expandNonInitializing();
#if CALIBER_CONTACT_ROWS_AVX2
		if (avx2RowsAvailable())
		{
			fillPointRowsAndWarmStartsAvx2(pools, point, infoGlobal);
			continue;
		}
#endif
		fillPointRows(pools, point, infoGlobal);
		applyPointWarmStarts(pools, point, infoGlobal);
	}
}

namespace
{
// A heavy body on a light one needs the shock-propagation sweeps (see propagateShock).
const btScalar kShockMassRatio = 4;

// Contact rows per task of findBouncesAndMassRatios, and the fewest worth a loop on the threads.
const int kRowsPerBounceTask = 256;
const int kMinRowsForParallelBounces = 1024;

// The bounces of rows [begin, end) in order, and whether one of them holds bodies of very different masses.
bool findBounces(int begin, int end, const btAlignedObjectArray<btSolverBody>& bodies,
                 const btConstraintArray& contacts, const btContactSolverInfo& infoGlobal,
                 btAlignedObjectArray<caliber::SolverBounceRow>& bounces)
{
	bool massRatio = false;
	// A manifold's rows share their two bodies: their mass ratio is judged once, at the first of them.
	int lastA = -1, lastB = -1;
	for (int r = begin; r < end; ++r)
	{
		const btSolverConstraint& row = contacts[r];
		const btSolverBody& bodyA = bodies[row.m_solverBodyIdA];
		const btSolverBody& bodyB = bodies[row.m_solverBodyIdB];
		const btManifoldPoint& cp = *static_cast<const btManifoldPoint*>(row.m_originalContactPoint);
		caliber::SolverBounceRow bounce;
		// The bodies' kinds are looked up only for a point with restitution (most have none).
		if (cp.m_combinedRestitution > btScalar(0) &&
		    restitutionRowBounce(row, RowBody::of(bodyA), RowBody::of(bodyB), cp, infoGlobal, bounce))
		{
			bounce.row = r;
			bounces.push_back(bounce);
		}
		if (massRatio || (row.m_solverBodyIdA == lastA && row.m_solverBodyIdB == lastB)) continue;
		lastA = row.m_solverBodyIdA;
		lastB = row.m_solverBodyIdB;
		const btRigidBody* rigidA = bodyA.m_originalBody;
		const btRigidBody* rigidB = bodyB.m_originalBody;
		if (rigidA && rigidB && !rigidA->isStaticOrKinematicObject() &&
		    !rigidB->isStaticOrKinematicObject() && rigidA->getInvMass() > btScalar(0) &&
		    rigidB->getInvMass() > btScalar(0))
		{
			const btScalar ratio = rigidA->getInvMass() / rigidB->getInvMass();
			if (ratio > kShockMassRatio || ratio * kShockMassRatio < btScalar(1)) massRatio = true;
		}
	}
	return massRatio;
}

struct FindBounces : public btIParallelForBody
{
	caliber::SolverScratch* scratch;
	const btAlignedObjectArray<btSolverBody>* bodies;
	const btConstraintArray* contacts;
	const btContactSolverInfo* info;

	// Each index is a chunk of kRowsPerBounceTask rows with its own list, so that any split of the loop
	// (a user's scheduler may ignore the grain) fills every list once.
	void forLoop(int iBegin, int iEnd) const override
	{
		const int numRows = contacts->size();
		for (int c = iBegin; c < iEnd; ++c)
		{
			caliber::SolverScratch::BounceChunk& chunk = scratch->bounceChunks[c];
			chunk.bounces.resize(0);
			chunk.massRatio = findBounces(c * kRowsPerBounceTask, btMin(numRows, (c + 1) * kRowsPerBounceTask),
			                              *bodies, *contacts, *info, chunk.bounces);
		}
	}
};
}  // namespace

void caliber::findBouncesAndMassRatios(SolverScratch& scratch, btAlignedObjectArray<btSolverBody>& bodies,
                                       const btConstraintArray& contacts, const btContactSolverInfo& infoGlobal)
{
	// Each row is judged on its own; on the threads, chunks of rows list their bounces, which are then
	// appended in chunk order: the same list as one pass in row order.
	btITaskScheduler* scheduler = btGetTaskScheduler();
	const int numRows = contacts.size();
	if (numRows < kMinRowsForParallelBounces || !scheduler || scheduler->getNumThreads() < 2)
	{
		if (findBounces(0, numRows, bodies, contacts, infoGlobal, scratch.bounceRows))
			scratch.shockPropagationNeeded = true;
		return;
	}
	const int chunks = (numRows + kRowsPerBounceTask - 1) / kRowsPerBounceTask;
	if (scratch.bounceChunks.size() < chunks) scratch.bounceChunks.resize(chunks);
	FindBounces find;
	find.scratch = &scratch;
	find.bodies = &bodies;
	find.contacts = &contacts;
	find.info = &infoGlobal;
	btParallelFor(0, chunks, 1, find);
	for (int c = 0; c < chunks; ++c)
	{
		const SolverScratch::BounceChunk& chunk = scratch.bounceChunks[c];
		for (int k = 0; k < chunk.bounces.size(); ++k) scratch.bounceRows.push_back(chunk.bounces[k]);
		if (chunk.massRatio) scratch.shockPropagationNeeded = true;
	}
}
