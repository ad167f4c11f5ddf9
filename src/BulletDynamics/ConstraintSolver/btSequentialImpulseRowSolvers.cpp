// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Bullet's row-solver interface of btSequentialImpulseConstraintSolver (btSingleConstraintRowSolver and
// its getters and setters), the conversions a subclass may override (bodies, one joint), and the sweep
// that calls a user's row solvers.
#include "BulletDynamics/ConstraintSolver/btSolverRowSolvers.h"

#include "BulletDynamics/ConstraintSolver/btSolverRowKernels.h"
#include "BulletDynamics/ConstraintSolver/btJointWarmStart.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btWarningHook.h"

namespace caliber
{
// The rows live in the solver's own (mutable) pools: Bullet's interface passes them const and lets the
// kernel accumulate into them.
btScalar rowSolverGeneric(btSolverBody& bodyA, btSolverBody& bodyB, const btSolverConstraint& row)
{
	btSolverConstraint& mutableRow = const_cast<btSolverConstraint&>(row);
	return resolveRow(bodyA, bodyB, mutableRow, row.m_lowerLimit, row.m_upperLimit);
}

btScalar rowSolverLowerLimit(btSolverBody& bodyA, btSolverBody& bodyB, const btSolverConstraint& row)
{
	btSolverConstraint& mutableRow = const_cast<btSolverConstraint&>(row);
	return resolveRow(bodyA, bodyB, mutableRow, row.m_lowerLimit, BT_LARGE_FLOAT);
}

btScalar rowSolverPush(btSolverBody& bodyA, btSolverBody& bodyB, const btSolverConstraint& row)
{
	return resolvePushRow(bodyA, bodyB, const_cast<btSolverConstraint&>(row));
}

btScalar sweepWithRowSolvers(int iteration, const btContactSolverInfo& infoGlobal, const SolverScratch& scratch,
                             btSolverBody* bodies, btConstraintArray& jointRows,
                             const btAlignedObjectArray<btTypedConstraint::btConstraintInfo1>& jointSizes,
                             const btAlignedObjectArray<int>& jointOrder, btConstraintArray& contacts,
                             const btAlignedObjectArray<int>& contactOrder, btConstraintArray& friction,
                             const btAlignedObjectArray<int>& frictionOrder, btConstraintArray& rolling,
                             const btAlignedObjectArray<int>& rollingOrder, btSingleConstraintRowSolver generic,
                             btSingleConstraintRowSolver lowerLimit)
{
	btScalar residual = 0;
	for (int k = 0; k < scratch.joints.size(); ++k)
	{
		const int j = jointOrder[k];
		const int first = scratch.jointFirstRow[j];
		if (iteration >= jointRows[first].m_overrideNumSolverIterations) continue;
		for (int r = first; r < first + jointSizes[j].m_numConstraintRows; ++r)
		{
			btSolverConstraint& row = jointRows[r];
			residual += generic(bodies[row.m_solverBodyIdA], bodies[row.m_solverBodyIdB], row);
		}
	}
	if (iteration >= infoGlobal.m_numIterations) return residual;
	for (int k = 0; k < contacts.size(); ++k)
	{
		btSolverConstraint& row = contacts[contactOrder[k]];
		residual += lowerLimit(bodies[row.m_solverBodyIdA], bodies[row.m_solverBodyIdB], row);
	}
	for (int k = 0; k < friction.size(); ++k)
	{
		btSolverConstraint& row = friction[frictionOrder[k]];
		const btScalar bound = row.m_friction * btMax(btScalar(0), contacts[row.m_frictionIndex].m_appliedImpulse);
		row.m_lowerLimit = -bound;
		row.m_upperLimit = bound;
		residual += generic(bodies[row.m_solverBodyIdA], bodies[row.m_solverBodyIdB], row);
	}
	for (int k = 0; k < rolling.size(); ++k)
	{
		btSolverConstraint& row = rolling[rollingOrder[k]];
		const btScalar bound = row.m_friction * btMax(btScalar(0), contacts[row.m_frictionIndex].m_appliedImpulse);
		row.m_lowerLimit = -bound;
		row.m_upperLimit = bound;
		residual += generic(bodies[row.m_solverBodyIdA], bodies[row.m_solverBodyIdB], row);
	}
	return residual;
}
}  // namespace caliber

void btSequentialImpulseConstraintSolver::setupSolverFunctions(bool useSimd)
{
	(void)useSimd;
	m_resolveSingleConstraintRowGeneric = &caliber::rowSolverGeneric;
	m_resolveSingleConstraintRowLowerLimit = &caliber::rowSolverLowerLimit;
	m_resolveSplitPenetrationImpulse = &caliber::rowSolverPush;
}

btSingleConstraintRowSolver btSequentialImpulseConstraintSolver::getScalarConstraintRowSolverGeneric()
{
	return &caliber::rowSolverGeneric;
}
btSingleConstraintRowSolver btSequentialImpulseConstraintSolver::getSSE2ConstraintRowSolverGeneric()
{
	return &caliber::rowSolverGeneric;
}
btSingleConstraintRowSolver btSequentialImpulseConstraintSolver::getSSE4_1ConstraintRowSolverGeneric()
{
	return &caliber::rowSolverGeneric;
}
btSingleConstraintRowSolver btSequentialImpulseConstraintSolver::getScalarConstraintRowSolverLowerLimit()
{
	return &caliber::rowSolverLowerLimit;
}
btSingleConstraintRowSolver btSequentialImpulseConstraintSolver::getSSE2ConstraintRowSolverLowerLimit()
{
	return &caliber::rowSolverLowerLimit;
}
btSingleConstraintRowSolver btSequentialImpulseConstraintSolver::getSSE4_1ConstraintRowSolverLowerLimit()
{
	return &caliber::rowSolverLowerLimit;
}

btScalar btSequentialImpulseConstraintSolver::resolveSingleConstraintRowGeneric(btSolverBody& bodyA,
                                                                               btSolverBody& bodyB,
                                                                               const btSolverConstraint& row)
{
	return m_resolveSingleConstraintRowGeneric(bodyA, bodyB, row);
}
btScalar btSequentialImpulseConstraintSolver::resolveSingleConstraintRowGenericSIMD(btSolverBody& bodyA,
                                                                                   btSolverBody& bodyB,
                                                                                   const btSolverConstraint& row)
{
	return m_resolveSingleConstraintRowGeneric(bodyA, bodyB, row);
}
btScalar btSequentialImpulseConstraintSolver::resolveSingleConstraintRowLowerLimit(btSolverBody& bodyA,
                                                                                  btSolverBody& bodyB,
                                                                                  const btSolverConstraint& row)
{
	return m_resolveSingleConstraintRowLowerLimit(bodyA, bodyB, row);
}
btScalar btSequentialImpulseConstraintSolver::resolveSingleConstraintRowLowerLimitSIMD(btSolverBody& bodyA,
                                                                                      btSolverBody& bodyB,
                                                                                      const btSolverConstraint& row)
{
	return m_resolveSingleConstraintRowLowerLimit(bodyA, bodyB, row);
}

void btSequentialImpulseConstraintSolver::convertBodies(btCollisionObject** bodies, int numBodies,
                                                        const btContactSolverInfo& infoGlobal)
{
	for (int i = 0; i < numBodies; ++i)
	{
		// An island holds dynamic bodies; the static and kinematic ones they touch come in through the
		// manifolds. Reset the hint so a stale id from another island is never trusted.
		bodies[i]->setCompanionId(-1);
	}
	for (int i = 0; i < numBodies; ++i) getOrInitSolverBody(*bodies[i], infoGlobal.m_timeStep);
}

void btSequentialImpulseConstraintSolver::convertJoint(btSolverConstraint* currentConstraintRow,
                                                       btTypedConstraint* constraint,
                                                       const btTypedConstraint::btConstraintInfo1& info1,
                                                       int solverBodyIdA, int solverBodyIdB,
                                                       const btContactSolverInfo& infoGlobal)
{
	if (!currentConstraintRow || !constraint || info1.m_numConstraintRows <= 0) return;
	// Called on its own (by a subclass), a joint starts cold and is solved row by row: the warm-start
	// store and the joint blocks belong to convertJoints's bookkeeping.
	caliber::SolverJointBlock block;
	block.m_firstRow = 0;
	block.m_size = 0;
	const caliber::JointImpulses cold;
	if (!caliber::convertJoint(m_tmpSolverBodyPool, currentConstraintRow, constraint, info1, solverBodyIdA,
	                           solverBodyIdB, infoGlobal, block, cold))
	{
		constraint->setEnabled(false);
		btReportWarning(
		    "Caliber: a constraint produced non-finite rows (NaN or infinite frames, pivots or body state); "
		    "it has been disabled\n",
		    0);
		for (int r = 0; r < info1.m_numConstraintRows; ++r)
		{
			// Inert rows: no impulse can be applied (zero effective mass and limits).
			btSolverConstraint& row = currentConstraintRow[r];
			row.m_jacDiagABInv = 0;
			row.m_rhs = row.m_cfm = row.m_appliedImpulse = row.m_appliedPushImpulse = 0;
			row.m_lowerLimit = row.m_upperLimit = 0;
		}
	}
}
