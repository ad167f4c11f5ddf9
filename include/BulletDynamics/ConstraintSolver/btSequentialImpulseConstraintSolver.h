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

	/// The solver-pool index of body, creating its entry on first use (static bodies share one).
	int getOrInitSolverBody(btCollisionObject & body, btScalar timeStep);
	/// Fills solverBody from collisionObject (0 or a non-rigid body gives a fixed entry).
	void initSolverBody(btSolverBody * solverBody, btCollisionObject * collisionObject, btScalar timeStep);

	/// Adds the rows of one manifold (points within its contact processing threshold).
	void convertContact(btPersistentManifold * manifold, const btContactSolverInfo& infoGlobal);
	/// Fills the normal row of one point; returns the relative normal velocity at the start of the step.
	void setupContactConstraint(btSolverConstraint & solverConstraint, int solverBodyIdA, int solverBodyIdB,
	                            btManifoldPoint& cp, const btContactSolverInfo& infoGlobal, const btVector3& rel_pos1,
	                            const btVector3& rel_pos2);
	/// Adds a friction row along normalAxis (a unit vector) for the contact row at frictionIndex.
	btSolverConstraint& addFrictionConstraint(
	    const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB, int frictionIndex, btManifoldPoint& cp,
	    const btVector3& rel_pos1, const btVector3& rel_pos2, btCollisionObject* colObj0, btCollisionObject* colObj1,
	    btScalar desiredVelocity = 0., btScalar cfmSlip = 0.);
	/// Adds an angular friction row about normalAxis (rolling or spinning friction).
	btSolverConstraint& addTorsionalFrictionConstraint(
	    const btVector3& normalAxis, int solverBodyIdA, int solverBodyIdB, int frictionIndex, btManifoldPoint& cp,
	    btScalar torsionalFriction, const btVector3& rel_pos1, const btVector3& rel_pos2, btCollisionObject* colObj0,
	    btCollisionObject* colObj1, btScalar desiredVelocity = 0, btScalar cfmSlip = 0.f);

	/// Adds the rows of every enabled joint, warm started from the joint's last step.
	void convertJoints(btTypedConstraint * *constraints, int numConstraints, const btContactSolverInfo& infoGlobal);
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
};

#endif  // BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_H
