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
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
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
// Contact row r and its friction rows in a shock sweep: the lower body held fixed.
void propagateShockRow(const caliber::SolverScratch& scratch, btSolverBody* bodies, btConstraintArray& contacts,
                       btConstraintArray& friction, int frictionRowsPerContact, int r)
{
	btSolverConstraint& row = contacts[r];
	btSolverBody& bodyA = bodies[row.m_solverBodyIdA];
	btSolverBody& bodyB = bodies[row.m_solverBodyIdB];
	const int levelA = scratch.shockBodyLevel[row.m_solverBodyIdA],
	          levelB = scratch.shockBodyLevel[row.m_solverBodyIdB];
	if (levelA == levelB)
	{
		// Side by side: ordinary rows.
		caliber::resolveRow(bodyA, bodyB, row, row.m_lowerLimit, row.m_upperLimit);
		for (int f = 0; f < frictionRowsPerContact; ++f)
			caliber::solveFrictionRow(bodies, contacts, friction, r * frictionRowsPerContact + f);
		return;
	}
	const bool upperIsA = levelA > levelB;
	resolveRowOneSided(bodyA, bodyB, row, upperIsA, row.m_lowerLimit, row.m_upperLimit);
	// Its friction too: the upper body must not slide on what holds it either.
	const btScalar bound = row.m_friction * btMax(btScalar(0), row.m_appliedImpulse);
	for (int f = 0; f < frictionRowsPerContact; ++f)
	{
		btSolverConstraint& frictionRow = friction[r * frictionRowsPerContact + f];
		resolveRowOneSided(bodyA, bodyB, frictionRow, upperIsA, -bound, bound);
	}
}
}  // namespace

void caliber::propagateShock(SolverScratch& scratch, btAlignedObjectArray<btSolverBody>& bodyPool,
                             btConstraintArray& contacts, btConstraintArray& friction,
                             const btContactSolverInfo& infoGlobal)
{
	if (!scratch.shockPropagationNeeded) return;
	BT_PROFILE("propagateShock");
	const int numBodies = bodyPool.size();
	const int numRows = contacts.size();

	// Contact graph in compressed rows: the rows touching each body.
	scratch.shockAdjacencyStart.resize(0);
	scratch.shockAdjacencyStart.resize(numBodies + 1, 0);
	for (int r = 0; r < numRows; ++r)
	{
		const btSolverConstraint& row = contacts[r];
		++scratch.shockAdjacencyStart[row.m_solverBodyIdA + 1];
		++scratch.shockAdjacencyStart[row.m_solverBodyIdB + 1];
	}
	for (int b = 0; b < numBodies; ++b) scratch.shockAdjacencyStart[b + 1] += scratch.shockAdjacencyStart[b];
	scratch.shockAdjacency.resizeNoInitialize(2 * numRows);
	scratch.shockCursor.resizeNoInitialize(numBodies);
	for (int b = 0; b < numBodies; ++b) scratch.shockCursor[b] = scratch.shockAdjacencyStart[b];
	for (int r = 0; r < numRows; ++r)
	{
		const btSolverConstraint& row = contacts[r];
		scratch.shockAdjacency[scratch.shockCursor[row.m_solverBodyIdA]++] = r;
		scratch.shockAdjacency[scratch.shockCursor[row.m_solverBodyIdB]++] = r;
	}

	// Levels by breadth-first search from everything that does not move (level 0); bodies that no chain
	// of contacts connects to the ground keep INT_MAX and are left alone.
	scratch.shockBodyLevel.resizeNoInitialize(numBodies);
	scratch.shockQueue.resizeNoInitialize(numBodies);
	int queueEnd = 0;
	for (int b = 0; b < numBodies; ++b)
	{
		const bool fixed = !isDynamic(bodyPool[b]);
		scratch.shockBodyLevel[b] = fixed ? 0 : INT_MAX;
		if (fixed) scratch.shockQueue[queueEnd++] = b;
	}
	for (int head = 0; head < queueEnd; ++head)
	{
		const int body = scratch.shockQueue[head];
		const int next = scratch.shockBodyLevel[body] + 1;
		for (int k = scratch.shockAdjacencyStart[body]; k < scratch.shockAdjacencyStart[body + 1]; ++k)
		{
			const btSolverConstraint& row = contacts[scratch.shockAdjacency[k]];
			const int other = row.m_solverBodyIdA == body ? row.m_solverBodyIdB : row.m_solverBodyIdA;
			if (scratch.shockBodyLevel[other] != INT_MAX) continue;
			scratch.shockBodyLevel[other] = next;
			scratch.shockQueue[queueEnd++] = other;
		}
	}

	// The rows in the order their upper bodies were reached: ground contacts first, then level by level.
	scratch.shockRowOrder.resize(0);
	for (int head = 0; head < queueEnd; ++head)
	{
		const int body = scratch.shockQueue[head];
		for (int k = scratch.shockAdjacencyStart[body]; k < scratch.shockAdjacencyStart[body + 1]; ++k)
		{
			const int r = scratch.shockAdjacency[k];
			const btSolverConstraint& row = contacts[r];
			const int other = row.m_solverBodyIdA == body ? row.m_solverBodyIdB : row.m_solverBodyIdA;
			// Each row once, from its lower body (ties: from the smaller index).
			const int levelHere = scratch.shockBodyLevel[body], levelOther = scratch.shockBodyLevel[other];
			if (levelOther < levelHere || (levelOther == levelHere && other < body)) continue;
			scratch.shockRowOrder.push_back(r);
		}
	}

	btSolverBody* bodies = &bodyPool[0];
	// Several points hold each upper body (a box on a box has four): one sweep leaves the first point of
	// each manifold with most of the correction and tilts the body, so the bottom-up pass is repeated,
	// as many times as the velocity sweeps. Each body then converges against a fixed base, which takes
	// a few sweeps whatever the mass ratio.
	for (int sweep = 0; sweep < infoGlobal.m_numIterations; ++sweep)
	{
		for (int k = 0; k < scratch.shockRowOrder.size(); ++k)
			propagateShockRow(scratch, bodies, contacts, friction, frictionRowsPerContact(infoGlobal),
			                  scratch.shockRowOrder[k]);
	}
}
