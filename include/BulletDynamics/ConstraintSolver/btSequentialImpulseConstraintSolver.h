// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_H
#define BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_H

/// btSequentialImpulseConstraintSolver: projected Gauss-Seidel on velocity rows (sequential impulses),
/// with warm starting, friction, rolling friction, restitution and split impulse. Design notes:
/// docs/rigid-body-dynamics.md.

#include "BulletDynamics/ConstraintSolver/btConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btContactSolverInfo.h"
#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btAlignedObjectArray.h"

class btManifoldPoint;

/// Solves one row (a btSolverConstraint between two pool bodies): applies the impulse change that the
/// row's limits allow and returns the squared velocity change (the row's least-squares residual).
typedef btScalar (*btSingleConstraintRowSolver)(btSolverBody&, btSolverBody&, const btSolverConstraint&);

/// The default solver of btDiscreteDynamicsWorld. Each solveGroup copies the bodies into a contiguous
/// pool of btSolverBody, turns every manifold point within the contact processing threshold into one
/// normal row, two friction rows and optional rolling/spinning rows (contiguous arrays, indices into
/// the body pool), iterates them m_numIterations times, and writes velocities, split-impulse position
/// corrections and the accumulated impulses (for warm starting) back. The arrays keep their capacity
/// between steps, so a scene in steady state does not allocate.
ATTRIBUTE_ALIGNED16(class)
btSequentialImpulseConstraintSolver : public btConstraintSolver
{
protected:
	btAlignedObjectArray<btSolverBody> m_tmpSolverBodyPool;
	btConstraintArray m_tmpSolverContactConstraintPool;
	/// Joint rows, constraint after constraint.
	btConstraintArray m_tmpSolverNonContactConstraintPool;
	btConstraintArray m_tmpSolverContactFrictionConstraintPool;
	btConstraintArray m_tmpSolverContactRollingFrictionConstraintPool;
	btAlignedObjectArray<int> m_orderTmpConstraintPool;
	/// Sweep order of the joints of this solve.
	btAlignedObjectArray<int> m_orderNonContactConstraintPool;
	/// Rows per joint in this solve.
	btAlignedObjectArray<btTypedConstraint::btConstraintInfo1> m_tmpConstraintSizesPool;
	btAlignedObjectArray<int> m_orderFrictionConstraintPool;
	btAlignedObjectArray<int> m_orderRollingFrictionConstraintPool;
	/// Index of the shared entry for static bodies in m_tmpSolverBodyPool (-1 until needed).
	int m_fixedBodyId;
	unsigned long m_btSeed2;
	/// Squared velocity change of the last iteration (the least-squares residual).
	btScalar m_leastSquaresResidual;
	int m_maxOverrideNumSolverIterations;
	/// Bullet's table from a kinematic body's unique id to its solver-pool index, for solvers that run on
	/// several threads at once. Caliber's solver does not need it (each pool entry is found from the
	/// body's companion id, checked against the pool; see getOrInitSolverBody): it stays empty.
	btAlignedObjectArray<int> m_kinematicBodyUniqueIdToSolverBodyTable;

	/// The row solvers the sweeps use: equality rows and friction (generic, between the row's lower and
	/// upper limits), contact rows (lower limit only) and the split-impulse push rows. Set to Caliber's
	/// own kernels by setupSolverFunctions; a subclass or setConstraintRowSolver* may replace them, and the
	/// sweeps then call the replacements for every row (see docs/rigid-body-dynamics.md).
	btSingleConstraintRowSolver m_resolveSingleConstraintRowGeneric;
	btSingleConstraintRowSolver m_resolveSingleConstraintRowLowerLimit;
	btSingleConstraintRowSolver m_resolveSplitPenetrationImpulse;
	/// The solver mode of the last solve (infoGlobal.m_solverMode).
	int m_cachedSolverMode;
	/// Installs Caliber's row kernels (the same vectorised kernel serves both settings of useSimd).
	void setupSolverFunctions(bool useSimd);

	/// The solver-pool index of body, creating its entry on first use (static bodies share one).
	int getOrInitSolverBody(btCollisionObject & body, btScalar timeStep);
	/// Fills solverBody from collisionObject (0 or a non-rigid body gives a fixed entry).
	void initSolverBody(btSolverBody * solverBody, btCollisionObject * collisionObject, btScalar timeStep);

	/// Adds the rows of one manifold (points within its contact processing threshold).
	void convertContact(btPersistentManifold * manifold, const btContactSolverInfo& infoGlobal);
	/// Adds the rows of every manifold (convertContact for each).
	virtual void convertContacts(btPersistentManifold * *manifoldPtr, int numManifolds,
	                             const btContactSolverInfo& infoGlobal);
	/// Fills the normal row of one point, warm started; relaxation receives infoGlobal.m_sor (Bullet's
	/// successive over-relaxation factor, which the rows do not otherwise use).
	void setupContactConstraint(btSolverConstraint & solverConstraint, int solverBodyIdA, int solverBodyIdB,
	                            btManifoldPoint& cp, const btContactSolverInfo& infoGlobal, btScalar& relaxation,
	                            const btVector3& rel_pos1, const btVector3& rel_pos2);
	/// Fills a friction row along normalAxis for the contact row at the index the row's m_frictionIndex
	/// will hold (set by the caller), not warm started. relaxation is accepted for Bullet's signature.
	void setupFrictionConstraint(btSolverConstraint & solverConstraint, const btVector3& normalAxis,
	                             int solverBodyIdA, int solverBodyIdB, btManifoldPoint& cp, const btVector3& rel_pos1,
	                             const btVector3& rel_pos2, btCollisionObject* colObj0, btCollisionObject* colObj1,
	                             btScalar relaxation, const btContactSolverInfo& infoGlobal,
	                             btScalar desiredVelocity = 0., btScalar cfmSlip = 0.);
	/// Fills an angular friction row about normalAxis (rolling or spinning friction, bounded by
	/// combinedTorsionalFriction times the normal impulse).
	void setupTorsionalFrictionConstraint(btSolverConstraint & solverConstraint, const btVector3& normalAxis,
	                                      int solverBodyIdA, int solverBodyIdB, btManifoldPoint& cp,
	                                      btScalar combinedTorsionalFriction, const btVector3& rel_pos1,
	                                      const btVector3& rel_pos2, btCollisionObject* colObj0,
	                                      btCollisionObject* colObj1, btScalar relaxation,
	                                      btScalar desiredVelocity = 0., btScalar cfmSlip = 0.);
	/// Adds a friction row along normalAxis (a unit vector) for the contact row at frictionIndex.
	btSolverConstraint& addFrictionConstraint(const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB,
	                                          int frictionIndex, btManifoldPoint& cp, const btVector3& rel_pos1,
	                                          const btVector3& rel_pos2, btCollisionObject* colObj0,
	                                          btCollisionObject* colObj1, btScalar relaxation,
	                                          const btContactSolverInfo& infoGlobal, btScalar desiredVelocity = 0.,
	                                          btScalar cfmSlip = 0.);
	/// Adds an angular friction row about normalAxis (rolling or spinning friction).
	btSolverConstraint& addTorsionalFrictionConstraint(
	    const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB, int frictionIndex, btManifoldPoint& cp,
	    btScalar torsionalFriction, const btVector3& rel_pos1, const btVector3& rel_pos2, btCollisionObject* colObj0,
	    btCollisionObject* colObj1, btScalar relaxation, const btContactSolverInfo& infoGlobal,
	    btScalar desiredVelocity = 0, btScalar cfmSlip = 0.f);
	/// Scales frictionDirection by the object's anisotropic friction (in the object's frame) when the
	/// object has the frictionMode bit (btCollisionObject::CF_ANISOTROPIC_FRICTION or
	/// CF_ANISOTROPIC_ROLLING_FRICTION) set; otherwise leaves it alone.
	static void applyAnisotropicFriction(btCollisionObject * colObj, btVector3 & frictionDirection, int frictionMode);
	/// Warm starts the friction rows of a contact row (its m_frictionIndex is its first friction row) from
	/// the point's lateral impulses of the last step, or zeroes them without SOLVER_USE_WARMSTARTING.
	void setFrictionConstraintImpulse(btSolverConstraint & solverConstraint, int solverBodyIdA, int solverBodyIdB,
	                                  btManifoldPoint& cp, const btContactSolverInfo& infoGlobal);
	/// Bullet's restitution target: -rel_vel * restitution for an approach faster than velocityThreshold,
	/// else 0. (The solver's own rebounds come from its restitution pass; see docs/rigid-body-dynamics.md.)
	btScalar restitutionCurve(btScalar rel_vel, btScalar restitution, btScalar velocityThreshold);

	/// The row solvers, through the pointers above.
	btScalar resolveSingleConstraintRowGeneric(btSolverBody & bodyA, btSolverBody & bodyB,
	                                           const btSolverConstraint& contactConstraint);
	btScalar resolveSingleConstraintRowGenericSIMD(btSolverBody & bodyA, btSolverBody & bodyB,
	                                               const btSolverConstraint& contactConstraint);
	btScalar resolveSingleConstraintRowLowerLimit(btSolverBody & bodyA, btSolverBody & bodyB,
	                                              const btSolverConstraint& contactConstraint);
	btScalar resolveSingleConstraintRowLowerLimitSIMD(btSolverBody & bodyA, btSolverBody & bodyB,
	                                                  const btSolverConstraint& contactConstraint);
	btScalar resolveSplitPenetrationSIMD(btSolverBody & bodyA, btSolverBody & bodyB,
	                                     const btSolverConstraint& contactConstraint)
	{
		return m_resolveSplitPenetrationImpulse(bodyA, bodyB, contactConstraint);
	}
	btScalar resolveSplitPenetrationImpulseCacheFriendly(btSolverBody & bodyA, btSolverBody & bodyB,
	                                                     const btSolverConstraint& contactConstraint)
	{
		return m_resolveSplitPenetrationImpulse(bodyA, bodyB, contactConstraint);
	}
	btScalar resolveSplitPenetrationImpulse(btSolverBody & bodyA, btSolverBody & bodyB,
	                                        const btSolverConstraint& contactConstraint)
	{
		return m_resolveSplitPenetrationImpulse(bodyA, bodyB, contactConstraint);
	}

	/// Adds the rows of every enabled joint, warm started from the joint's last step.
	virtual void convertJoints(btTypedConstraint * *constraints, int numConstraints,
	                           const btContactSolverInfo& infoGlobal);
	/// Fills the info1.m_numConstraintRows rows of one joint from currentConstraintRow on (its getInfo2,
	/// limits, breaking threshold and feedback rows), warm started from the joint's last step. A joint
	/// whose rows are not finite is disabled, with a warning, and its rows are made inert.
	void convertJoint(btSolverConstraint * currentConstraintRow, btTypedConstraint * constraint,
	                  const btTypedConstraint::btConstraintInfo1& info1, int solverBodyIdA, int solverBodyIdB,
	                  const btContactSolverInfo& infoGlobal);
	/// Puts every body of the island into the solver pool (getOrInitSolverBody for each).
	virtual void convertBodies(btCollisionObject * *bodies, int numBodies, const btContactSolverInfo& infoGlobal);
	/// Stores the joints' row impulses (warm start, applied impulse, feedback) and breaks overloaded ones.
	void writeBackJoints(int iBegin, int iEnd, const btContactSolverInfo& infoGlobal);

	/// Builds the body pool and the rows, and applies the warm-start impulses.
	virtual btScalar solveGroupCacheFriendlySetup(btCollisionObject * *bodies, int numBodies,
	                                              btPersistentManifold** manifoldPtr, int numManifolds,
	                                              btTypedConstraint** constraints, int numConstraints,
	                                              const btContactSolverInfo& infoGlobal, btIDebugDraw* debugDrawer);
	/// One sweep over all rows; returns the squared velocity change of the sweep.
	virtual btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
	                                      btPersistentManifold** manifoldPtr, int numManifolds,
	                                      btTypedConstraint** constraints, int numConstraints,
	                                      const btContactSolverInfo& infoGlobal, btIDebugDraw* debugDrawer);
	/// The velocity sweeps, then the split-impulse (position) sweeps.
	virtual btScalar solveGroupCacheFriendlyIterations(
	    btCollisionObject * *bodies, int numBodies, btPersistentManifold** manifoldPtr, int numManifolds,
	    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& infoGlobal,
	    btIDebugDraw* debugDrawer);
	/// The split-impulse sweeps over the rows that carry a position error.
	virtual void solveGroupCacheFriendlySplitImpulseIterations(
	    btCollisionObject * *bodies, int numBodies, btPersistentManifold** manifoldPtr, int numManifolds,
	    btTypedConstraint** constraints, int numConstraints, const btContactSolverInfo& infoGlobal,
	    btIDebugDraw* debugDrawer);
	/// Writes impulses to the manifold points and velocities and transforms to the bodies.
	virtual btScalar solveGroupCacheFriendlyFinish(btCollisionObject * *bodies, int numBodies,
	                                               const btContactSolverInfo& infoGlobal);
	/// Copies the accumulated impulses of rows [first, first + count) to their manifold points.
	void writeBackContacts(int iBegin, int iEnd, const btContactSolverInfo& infoGlobal);
	/// Copies the solved velocities (and split-impulse moves) of pool entries [iBegin, iEnd) to the bodies.
	void writeBackBodies(int iBegin, int iEnd, const btContactSolverInfo& infoGlobal);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	btSequentialImpulseConstraintSolver();
	virtual ~btSequentialImpulseConstraintSolver();

	/// Solves one island (see btConstraintSolver): its contacts and its joints.
	virtual btScalar solveGroup(btCollisionObject * *bodies, int numBodies, btPersistentManifold** manifold,
	                            int numManifolds, btTypedConstraint** constraints, int numConstraints,
	                            const btContactSolverInfo& info, btIDebugDraw* debugDrawer, btDispatcher* dispatcher)
	    override;

	/// Resets the random seed used by SOLVER_RANDMIZE_ORDER, so that a rerun shuffles the same way.
	void reset() override;

	/// A deterministic pseudo-random number (the shuffle of SOLVER_RANDMIZE_ORDER).
	unsigned long btRand2();
	/// A deterministic pseudo-random integer in [0, n).
	int btRandInt2(int n);

	void setRandSeed(unsigned long seed) { m_btSeed2 = seed; }
	unsigned long getRandSeed() const { return m_btSeed2; }

	btConstraintSolverType getSolverType() const override { return BT_SEQUENTIAL_IMPULSE_SOLVER; }

	btSingleConstraintRowSolver getActiveConstraintRowSolverGeneric() { return m_resolveSingleConstraintRowGeneric; }
	void setConstraintRowSolverGeneric(btSingleConstraintRowSolver rowSolver)
	{
		m_resolveSingleConstraintRowGeneric = rowSolver;
	}
	btSingleConstraintRowSolver getActiveConstraintRowSolverLowerLimit()
	{
		return m_resolveSingleConstraintRowLowerLimit;
	}
	void setConstraintRowSolverLowerLimit(btSingleConstraintRowSolver rowSolver)
	{
		m_resolveSingleConstraintRowLowerLimit = rowSolver;
	}
	/// Caliber's row kernels. There is one vectorised kernel of each kind (SSE2 where the build has
	/// SIMD, scalar otherwise): the scalar, SSE2 and SSE4.1 getters all return it.
	btSingleConstraintRowSolver getScalarConstraintRowSolverGeneric();
	btSingleConstraintRowSolver getSSE2ConstraintRowSolverGeneric();
	btSingleConstraintRowSolver getSSE4_1ConstraintRowSolverGeneric();
	btSingleConstraintRowSolver getScalarConstraintRowSolverLowerLimit();
	btSingleConstraintRowSolver getSSE2ConstraintRowSolverLowerLimit();
	btSingleConstraintRowSolver getSSE4_1ConstraintRowSolverLowerLimit();
};

#endif  // BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_H
