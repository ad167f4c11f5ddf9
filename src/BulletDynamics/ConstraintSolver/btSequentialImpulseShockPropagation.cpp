// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Shock propagation: the last velocity sweep of an island that holds a heavy body on a light one.
//
// Gauss-Seidel passes a heavy body's weight down through a light one slowly: a row between them has
// the light body's effective mass, so each sweep corrects the heavy body's velocity by about the mass
// ratio's inverse (100 to 1: a hundredth per sweep), and the heavy body sinks and bobs. Shock
// propagation (Guendelman, Bridson and Fedkiw 2003) ends the solve with one sweep from the ground up,
// each contact treating its lower body as fixed: the upper body alone takes the correction, so it
// leaves the step resting on what is below it, whatever the ratio. The impulse stays in the row and
// warm-starts the next step, where the regular sweeps pass it on to the bodies below.
#include <limits.h>

#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btSolverRowKernels.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btQuickprof.h"

namespace
{
bool isDynamic(const btSolverBody& body)
{
	return body.m_originalBody && !body.m_originalBody->isStaticOrKinematicObject();
}

// J M^-1 J^T of one side of a row: the row's effective mass when the other side is held fixed.
btScalar oneSidedDenominator(const btSolverBody& body, const btVector3& linear, const btVector3& angularAxis,
                             const btVector3& angularComponent)
{
	return linear.dot(linear * body.m_invMass) + angularAxis.dot(angularComponent * body.m_angularFactor);
}

// Drives a row to its target moving only its upper body, the accumulated impulse clamped to [lower, upper].
void resolveRowOneSided(btSolverBody& bodyA, btSolverBody& bodyB, btSolverConstraint& row, bool upperIsA,
                        btScalar lower, btScalar upper)
{
	if (!(row.m_jacDiagABInv > btScalar(0))) return;
	// The velocity error the row still has; its right-hand side holds the target as an impulse.
	const btScalar velocityError = row.m_rhs / row.m_jacDiagABInv - caliber::rowDeltaVelocity(bodyA, bodyB, row);
	const btScalar denominator =
	    upperIsA ? oneSidedDenominator(bodyA, row.m_contactNormal1, row.m_relpos1CrossNormal, row.m_angularComponentA)
	             : oneSidedDenominator(bodyB, row.m_contactNormal2, row.m_relpos2CrossNormal, row.m_angularComponentB);
	if (!(denominator > SIMD_EPSILON)) return;
	const btScalar impulse = btMax(lower, btMin(upper, row.m_appliedImpulse + velocityError / denominator));
	const btScalar deltaImpulse = impulse - row.m_appliedImpulse;
	row.m_appliedImpulse = impulse;
	if (upperIsA)
		bodyA.applyImpulse(row.m_contactNormal1, row.m_angularComponentA, deltaImpulse);
	else
		bodyB.applyImpulse(row.m_contactNormal2, row.m_angularComponentB, deltaImpulse);
}
}  // namespace

void btSequentialImpulseConstraintSolver::propagateShock(const btContactSolverInfo& infoGlobal)
{
	if (!m_shockPropagationNeeded) return;
	BT_PROFILE("propagateShock");
	const int numBodies = m_tmpSolverBodyPool.size();
	const int numRows = m_tmpSolverContactConstraintPool.size();

	// Contact graph in compressed rows: the rows touching each body.
	m_shockAdjacencyStart.resize(0);
	m_shockAdjacencyStart.resize(numBodies + 1, 0);
	for (int r = 0; r < numRows; ++r)
	{
		const btSolverConstraint& row = m_tmpSolverContactConstraintPool[r];
		++m_shockAdjacencyStart[row.m_solverBodyIdA + 1];
		++m_shockAdjacencyStart[row.m_solverBodyIdB + 1];
	}
	for (int b = 0; b < numBodies; ++b) m_shockAdjacencyStart[b + 1] += m_shockAdjacencyStart[b];
	m_shockAdjacency.resizeNoInitialize(2 * numRows);
	m_shockCursor.resizeNoInitialize(numBodies);
	for (int b = 0; b < numBodies; ++b) m_shockCursor[b] = m_shockAdjacencyStart[b];
	for (int r = 0; r < numRows; ++r)
	{
		const btSolverConstraint& row = m_tmpSolverContactConstraintPool[r];
		m_shockAdjacency[m_shockCursor[row.m_solverBodyIdA]++] = r;
		m_shockAdjacency[m_shockCursor[row.m_solverBodyIdB]++] = r;
	}

	// Levels by breadth-first search from everything that does not move (level 0); bodies that no chain
	// of contacts connects to the ground keep INT_MAX and are left alone.
	m_shockBodyLevel.resizeNoInitialize(numBodies);
	m_shockQueue.resizeNoInitialize(numBodies);
	int queueEnd = 0;
	for (int b = 0; b < numBodies; ++b)
	{
		const bool fixed = !isDynamic(m_tmpSolverBodyPool[b]);
		m_shockBodyLevel[b] = fixed ? 0 : INT_MAX;
		if (fixed) m_shockQueue[queueEnd++] = b;
	}
	for (int head = 0; head < queueEnd; ++head)
	{
		const int body = m_shockQueue[head];
		const int next = m_shockBodyLevel[body] + 1;
		for (int k = m_shockAdjacencyStart[body]; k < m_shockAdjacencyStart[body + 1]; ++k)
		{
			const btSolverConstraint& row = m_tmpSolverContactConstraintPool[m_shockAdjacency[k]];
			const int other = row.m_solverBodyIdA == body ? row.m_solverBodyIdB : row.m_solverBodyIdA;
			if (m_shockBodyLevel[other] != INT_MAX) continue;
			m_shockBodyLevel[other] = next;
			m_shockQueue[queueEnd++] = other;
		}
	}

	// The rows in the order their upper bodies were reached: ground contacts first, then level by level.
	m_shockRowOrder.resize(0);
	for (int head = 0; head < queueEnd; ++head)
	{
		const int body = m_shockQueue[head];
		for (int k = m_shockAdjacencyStart[body]; k < m_shockAdjacencyStart[body + 1]; ++k)
		{
			const int r = m_shockAdjacency[k];
			const btSolverConstraint& row = m_tmpSolverContactConstraintPool[r];
			const int other = row.m_solverBodyIdA == body ? row.m_solverBodyIdB : row.m_solverBodyIdA;
			// Each row once, from its lower body (ties: from the smaller index).
			const int levelHere = m_shockBodyLevel[body], levelOther = m_shockBodyLevel[other];
			if (levelOther < levelHere || (levelOther == levelHere && other < body)) continue;
			m_shockRowOrder.push_back(r);
		}
	}

	btSolverBody* bodies = &m_tmpSolverBodyPool[0];
	// Several points hold each upper body (a box on a box has four): one sweep leaves the first point of
	// each manifold with most of the correction and tilts the body, so the bottom-up pass is repeated,
	// as many times as the velocity sweeps. Each body then converges against a fixed base, which takes
	// a few sweeps whatever the mass ratio.
	for (int sweep = 0; sweep < infoGlobal.m_numIterations; ++sweep)
	{
		for (int k = 0; k < m_shockRowOrder.size(); ++k) propagateShockRow(bodies, m_shockRowOrder[k]);
	}
}

void btSequentialImpulseConstraintSolver::propagateShockRow(btSolverBody* bodies, int r)
{
	btSolverConstraint& row = m_tmpSolverContactConstraintPool[r];
	btSolverBody& bodyA = bodies[row.m_solverBodyIdA];
	btSolverBody& bodyB = bodies[row.m_solverBodyIdB];
	const int levelA = m_shockBodyLevel[row.m_solverBodyIdA], levelB = m_shockBodyLevel[row.m_solverBodyIdB];
	if (levelA == levelB)
	{
		// Side by side: ordinary rows.
		caliber::resolveRow(bodyA, bodyB, row, row.m_lowerLimit, row.m_upperLimit);
		for (int f = 0; f < m_frictionRowsPerContact; ++f) solveFrictionRow(bodies, r * m_frictionRowsPerContact + f);
		return;
	}
	const bool upperIsA = levelA > levelB;
	resolveRowOneSided(bodyA, bodyB, row, upperIsA, row.m_lowerLimit, row.m_upperLimit);
	// Its friction too: the upper body must not slide on what holds it either.
	const btScalar bound = row.m_friction * btMax(btScalar(0), row.m_appliedImpulse);
	for (int f = 0; f < m_frictionRowsPerContact; ++f)
	{
		btSolverConstraint& friction = m_tmpSolverContactFrictionConstraintPool[r * m_frictionRowsPerContact + f];
		resolveRowOneSided(bodyA, bodyB, friction, upperIsA, -bound, bound);
	}
}
