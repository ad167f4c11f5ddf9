// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONSTRAINT_SOLVER_H
#define BT_CONSTRAINT_SOLVER_H

#include "LinearMath/btScalar.h"

class btPersistentManifold;
class btRigidBody;
class btCollisionObject;
class btTypedConstraint;
struct btContactSolverInfo;
struct btBroadphaseProxy;
class btIDebugDraw;
class btStackAlloc;
class btDispatcher;

/// Which solver a btConstraintSolver is (getSolverType), as numbered in Bullet.
enum btConstraintSolverType
{
	BT_SEQUENTIAL_IMPULSE_SOLVER = 1,
	BT_MLCP_SOLVER = 2,
	BT_NNCG_SOLVER = 4,
	BT_MULTIBODY_SOLVER = 8,
	BT_BLOCK_SOLVER = 16,
};

/// What a dynamics world asks of a constraint solver: each step, prepareSolve, then solveGroup once
/// per island (or once for all islands), then allSolved.
class btConstraintSolver
{
public:
	virtual ~btConstraintSolver() {}

	/// Called once per step before the groups, with the step's totals.
	virtual void prepareSolve(int numBodies, int numManifolds)
	{
		(void)numBodies;
		(void)numManifolds;
	}

	/// Solves the contacts in manifold[0..numManifolds) and the constraints among bodies[0..numBodies),
	/// writing velocities back to the bodies. Returns the solver's final residual (0 when not tracked).
	virtual btScalar solveGroup(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifold,
	                            int numManifolds, btTypedConstraint** constraints, int numConstraints,
	                            const btContactSolverInfo& info, btIDebugDraw* debugDrawer,
	                            btDispatcher* dispatcher) = 0;

	/// Called once per step after the last group.
	virtual void allSolved(const btContactSolverInfo& info, btIDebugDraw* debugDrawer)
	{
		(void)info;
		(void)debugDrawer;
	}

	/// Forgets everything carried between steps (for example a random seed).
	virtual void reset() = 0;

	virtual btConstraintSolverType getSolverType() const = 0;
};

#endif  // BT_CONSTRAINT_SOLVER_H
