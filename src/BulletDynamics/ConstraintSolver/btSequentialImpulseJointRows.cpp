// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The joint half of the solver's setup and write-back: each joint describes its rows through
// getInfo1/getInfo2, written straight into the solver's row array, and the rows are then solved exactly
// like contact rows (btSolverRowKernels.h).
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "BulletDynamics/ConstraintSolver/btJointBlockMath.h"
#include "BulletDynamics/ConstraintSolver/btJointRowSetup.h"
#include "BulletDynamics/ConstraintSolver/btSolverScratch.h"
#include "BulletDynamics/ConstraintSolver/btSolverRowKernels.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btQuickprof.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// I^-1 F axis for a body that turns, zero for static and kinematic ones (nothing pushes them).
btVector3 angularComponent(const btRigidBody& body, const btVector3& axis)
{
	if (body.isStaticOrKinematicObject()) return btVector3(0, 0, 0);
	return body.getInvInertiaTensorWorld() * (axis * body.getAngularFactor());
}

// Rows whose bounds reach this far are equality rows.
const btScalar kUnboundedImpulse = btScalar(1e30) < SIMD_INFINITY ? btScalar(1e30) : SIMD_INFINITY;

// The block inverse column by column, zero outside n x n: the sweeps then form K^-1 e as a sum of whole
// columns, every row of the result in its own SIMD lane, each summed in the order of the row-by-row dot
// product (the same bits, without the strided reads).
void storeColumnMajor(const btScalar* rowMajor, int n, btScalar* columnMajor)
{
	const int S = caliber::SolverJointBlock::MAX_ROWS;
	for (int j = 0; j < S; ++j)
		for (int i = 0; i < S; ++i) columnMajor[j * S + i] = i < n && j < n ? rowMajor[i * S + j] : btScalar(0);
}

// Makes a joint's later row (a limit or a motor) blind to its equality block: the row's Jacobian loses its
// component along the block's rows in the bodies' mass metric, J_r - sum_j c_j J_j with c = K^-1 (J_block
// M^-1 J_r^T), and its target the matching share of theirs. The block holds its rows to their targets, so
// the solution is the same; but solving the row no longer disturbs the block and the block no longer
// undoes the row, so a limit strongly coupled to its joint's pivot (a limb swinging into its cone) settles
// in one sweep instead of opening the pivot while Gauss-Seidel goes back and forth.
void decoupleFromBlock(const btSolverConstraint* blockRows, const caliber::SolverJointBlock& block,
                       const btScalar* blockTargets, btSolverConstraint& row, btScalar& target, const btRigidBody& rbA,
                       const btRigidBody& rbB, const btSolverBody& bodyA, const btSolverBody& bodyB)
{
	const int S = caliber::SolverJointBlock::MAX_ROWS;
	const int n = block.m_size;
	btScalar coupling[S];
	bool coupled = false;
	for (int i = 0; i < n; ++i)
	{
		const btSolverConstraint& b = blockRows[i];
		coupling[i] = b.m_contactNormal1.dot(row.m_contactNormal1 * bodyA.m_invMass) +
		              b.m_relpos1CrossNormal.dot(row.m_angularComponentA * bodyA.m_angularFactor) +
		              b.m_contactNormal2.dot(row.m_contactNormal2 * bodyB.m_invMass) +
		              b.m_relpos2CrossNormal.dot(row.m_angularComponentB * bodyB.m_angularFactor);
		coupled = coupled || coupling[i] != btScalar(0);
	}
	if (!coupled) return;
	const btScalar originalK = row.m_jacDiagABInv > btScalar(0) ? btScalar(1) / row.m_jacDiagABInv : btScalar(0);
	for (int j = 0; j < n; ++j)
	{
		btScalar c = 0;
		for (int i = 0; i < n; ++i) c += block.m_invK[i * S + j] * coupling[i];  // row j of K^-1
		const btSolverConstraint& b = blockRows[j];
		row.m_contactNormal1 -= b.m_contactNormal1 * c;
		row.m_relpos1CrossNormal -= b.m_relpos1CrossNormal * c;
		row.m_contactNormal2 -= b.m_contactNormal2 * c;
		row.m_relpos2CrossNormal -= b.m_relpos2CrossNormal * c;
		target -= blockTargets[j] * c;
	}
	row.m_angularComponentA = angularComponent(rbA, row.m_relpos1CrossNormal);
	row.m_angularComponentB = angularComponent(rbB, row.m_relpos2CrossNormal);
	const btScalar k = row.m_contactNormal1.dot(row.m_contactNormal1 * bodyA.m_invMass) +
	                   row.m_relpos1CrossNormal.dot(row.m_angularComponentA * bodyA.m_angularFactor) +
	                   row.m_contactNormal2.dot(row.m_contactNormal2 * bodyB.m_invMass) +
	                   row.m_relpos2CrossNormal.dot(row.m_angularComponentB * bodyB.m_angularFactor);
	// A row (almost) wholly within the block's span asks for what the block already decides: it is
	// dropped rather than left to fight the block through a near-zero effective mass.
	const bool independent = k > btScalar(1e-4) * originalK && k > SIMD_EPSILON;
	row.m_jacDiagABInv = independent ? btScalar(1) / k : btScalar(0);
	row.m_rhs = independent ? target * row.m_jacDiagABInv : btScalar(0);
}

void clearRow(btSolverConstraint& row, const caliber::JointRowParameters& parameters, btTypedConstraint* joint)
{
	const btVector3 zero(0, 0, 0);
	row.m_relpos1CrossNormal = zero;
	row.m_contactNormal1 = zero;
	row.m_relpos2CrossNormal = zero;
	row.m_contactNormal2 = zero;
	row.m_angularComponentA = zero;
	row.m_angularComponentB = zero;
	row.m_appliedPushImpulse = 0;
	row.m_appliedImpulse = 0;
	row.m_friction = 0;
	row.m_jacDiagABInv = 0;
	row.m_rhs = 0;
	row.m_cfm = parameters.cfm;
	row.m_lowerLimit = -SIMD_INFINITY;
	row.m_upperLimit = SIMD_INFINITY;
	row.m_rhsPenetration = 0;
	row.m_originalContactPoint = joint;
	row.m_overrideNumSolverIterations = parameters.rowIterations;
	row.m_frictionIndex = -1;
	row.m_solverBodyIdA = parameters.solverBodyIdA;
	row.m_solverBodyIdB = parameters.solverBodyIdB;
}
}  // namespace

namespace
{
// The shared row set-up, inlined into the solver's convertJoint (once per joint per step).
SIMD_FORCE_INLINE void setUpRows(btTypedConstraint& constraint, btSolverConstraint* firstRow, int numRows,
                                 const caliber::JointRowParameters& parameters)
{
	for (int j = 0; j < numRows; ++j) clearRow(firstRow[j], parameters, &constraint);
	btTypedConstraint::btConstraintInfo2 info2;
	info2.fps = parameters.fps;
	info2.erp = parameters.erp;
	info2.m_J1linearAxis = firstRow->m_contactNormal1.m_floats;
	info2.m_J1angularAxis = firstRow->m_relpos1CrossNormal.m_floats;
	info2.m_J2linearAxis = firstRow->m_contactNormal2.m_floats;
	info2.m_J2angularAxis = firstRow->m_relpos2CrossNormal.m_floats;
	info2.rowskip = int(sizeof(btSolverConstraint) / sizeof(btScalar));
	btAssert(info2.rowskip * sizeof(btScalar) == sizeof(btSolverConstraint));
	info2.m_constraintError = &firstRow->m_rhs;
	info2.cfm = &firstRow->m_cfm;
	info2.m_lowerLimit = &firstRow->m_lowerLimit;
	info2.m_upperLimit = &firstRow->m_upperLimit;
	info2.m_numIterations = parameters.numIterations;
	info2.m_damping = parameters.damping;
	constraint.getInfo2(&info2);
}
}  // namespace

void caliber::setUpJointRows(btTypedConstraint& constraint, btSolverConstraint* firstRow, int numRows,
                             const JointRowParameters& parameters)
{
	setUpRows(constraint, firstRow, numRows, parameters);
}

bool caliber::convertJoint(btAlignedObjectArray<btSolverBody>& bodies, btSolverConstraint* firstRow,
                           btTypedConstraint* constraint, const btTypedConstraint::btConstraintInfo1& info1,
                           int solverBodyIdA, int solverBodyIdB, const btContactSolverInfo& infoGlobal,
                           caliber::SolverJointBlock& block, const caliber::JointImpulses& warm)
{
	const int numRows = info1.m_numConstraintRows;
	block.m_size = 0;
	const int iterations = constraint->getOverrideNumSolverIterations() >= 0
	                           ? constraint->getOverrideNumSolverIterations()
	                           : infoGlobal.m_numIterations;
	caliber::JointRowParameters parameters;
	parameters.fps = btScalar(1) / infoGlobal.m_timeStep;
	parameters.erp = infoGlobal.m_erp;
	parameters.cfm = infoGlobal.m_globalCfm;
	parameters.numIterations = infoGlobal.m_numIterations;
	parameters.damping = infoGlobal.m_damping;
	parameters.solverBodyIdA = solverBodyIdA;
	parameters.solverBodyIdB = solverBodyIdB;
	parameters.rowIterations = iterations;
	setUpRows(*constraint, firstRow, numRows, parameters);

	btRigidBody& rbA = constraint->getRigidBodyA();
	btRigidBody& rbB = constraint->getRigidBodyB();
	const btSolverBody& bodyA = bodies[solverBodyIdA];
	const btSolverBody& bodyB = bodies[solverBodyIdB];
	const btScalar threshold = constraint->getBreakingImpulseThreshold();

	const bool warmStart = (infoGlobal.m_solverMode & SOLVER_USE_WARMSTARTING) && warm.size() == numRows;

	// The leading equality rows (no bounds, no softness) can be solved as one block.
	int equalityRows = 0;
	while (equalityRows < numRows && equalityRows < caliber::SolverJointBlock::MAX_ROWS &&
	       firstRow[equalityRows].m_lowerLimit <= -kUnboundedImpulse &&
	       firstRow[equalityRows].m_upperLimit >= kUnboundedImpulse && firstRow[equalityRows].m_cfm == btScalar(0))
		++equalityRows;

	const int kMaxDecoupledRows = 32;
	btScalar targets[kMaxDecoupledRows];
	for (int j = 0; j < numRows; ++j)
	{
		btSolverConstraint& row = firstRow[j];
		// A joint whose frames, pivots or bodies have gone non-finite must not spread NaN to its bodies.
		if (!caliber::isFinite(row.m_contactNormal1) || !caliber::isFinite(row.m_relpos1CrossNormal) ||
		    !caliber::isFinite(row.m_contactNormal2) || !caliber::isFinite(row.m_relpos2CrossNormal) ||
		    !btIsFinite(row.m_rhs) || !btIsFinite(row.m_cfm) || row.m_lowerLimit != row.m_lowerLimit ||
		    row.m_upperLimit != row.m_upperLimit)
			return false;

		// No row may apply more than the breaking impulse: the joint breaks when one reaches it.
		row.m_upperLimit = btMin(row.m_upperLimit, threshold);
		row.m_lowerLimit = btMax(row.m_lowerLimit, -threshold);

		row.m_angularComponentA = angularComponent(rbA, row.m_relpos1CrossNormal);
		row.m_angularComponentB = angularComponent(rbB, row.m_relpos2CrossNormal);
		const btScalar k = row.m_contactNormal1.dot(row.m_contactNormal1 * bodyA.m_invMass) +
		                   row.m_relpos1CrossNormal.dot(row.m_angularComponentA * bodyA.m_angularFactor) +
		                   row.m_contactNormal2.dot(row.m_contactNormal2 * bodyB.m_invMass) +
		                   row.m_relpos2CrossNormal.dot(row.m_angularComponentB * bodyB.m_angularFactor);
		row.m_jacDiagABInv = k > SIMD_EPSILON ? btScalar(1) / k : btScalar(0);

		// The target (m_constraintError, written to m_rhs) minus the velocity the row starts with.
		const btScalar velocity =
		    row.m_contactNormal1.dot(bodyA.m_linearVelocity) + row.m_relpos1CrossNormal.dot(bodyA.m_angularVelocity) +
		    row.m_contactNormal2.dot(bodyB.m_linearVelocity) + row.m_relpos2CrossNormal.dot(bodyB.m_angularVelocity);
		const btScalar target = row.m_rhs - velocity * infoGlobal.m_damping;
		if (j < equalityRows) block.m_target[j] = target;
		if (j < kMaxDecoupledRows) targets[j] = target;
		row.m_rhs = target * row.m_jacDiagABInv;
		row.m_rhsPenetration = 0;
	}
	btScalar inverse[caliber::SolverJointBlock::MAX_ROWS * caliber::SolverJointBlock::MAX_ROWS];
	if (equalityRows >= 2 && caliber::buildBlockInverse(firstRow, equalityRows, bodyA, bodyB, inverse))
	{
		storeColumnMajor(inverse, equalityRows, block.m_invK);
		block.m_size = equalityRows;
		if (numRows <= kMaxDecoupledRows)
			for (int j = equalityRows; j < numRows; ++j)
				decoupleFromBlock(firstRow, block, targets, firstRow[j], targets[j], rbA, rbB, bodyA, bodyB);
	}

	// Soft rows (cfm c > 0) as K (1 + c) with cfm c / (1 + c): the same solution as Bullet's form
	// (J v = target - c K lambda) but Gauss-Seidel on it converges for any c, where Bullet's overshoots
	// once c reaches 1.
	for (int j = 0; j < numRows; ++j)
	{
		btSolverConstraint& row = firstRow[j];
		if (!(row.m_cfm > btScalar(0))) continue;
		const btScalar softening = btScalar(1) + row.m_cfm;
		row.m_jacDiagABInv /= softening;
		row.m_rhs /= softening;
		row.m_cfm /= softening;
	}

	if (warmStart)
	{
		for (int j = 0; j < numRows; ++j)
		{
			btSolverConstraint& row = firstRow[j];
			const btScalar impulse =
			    btMax(row.m_lowerLimit, btMin(row.m_upperLimit, warm[j] * infoGlobal.m_warmstartingFactor));
			row.m_appliedImpulse = impulse;
			bodies[solverBodyIdA].applyImpulse(row.m_contactNormal1, row.m_angularComponentA, impulse);
			bodies[solverBodyIdB].applyImpulse(row.m_contactNormal2, row.m_angularComponentB, impulse);
		}
	}
	return true;
}

void btSequentialImpulseConstraintSolver::convertJoints(btTypedConstraint** constraints, int numConstraints,
                                                        const btContactSolverInfo& infoGlobal)
{
	BT_PROFILE("convertJoints");
	caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	m_tmpSolverNonContactConstraintPool.resize(0);
	m_tmpConstraintSizesPool.resize(0);
	scratch.joints.resize(0);
	scratch.jointFirstRow.resize(0);
	scratch.jointBlocks.resize(0);
	scratch.jointWarmStart.resize(0);
	scratch.idleJoints.resize(0);
	if (numConstraints <= 0 || !constraints) return;

	int totalRows = 0;
	for (int i = 0; i < numConstraints; ++i)
	{
		btTypedConstraint* constraint = constraints[i];
		if (!constraint || !constraint->isEnabled()) continue;
		constraint->buildJacobian();
		btTypedConstraint::btConstraintInfo1 info1;
		info1.m_numConstraintRows = 0;
		info1.nub = 0;
		constraint->getInfo1(&info1);
		if (info1.m_numConstraintRows <= 0)
		{
			scratch.idleJoints.push_back(constraint);
			constraint->internalSetAppliedImpulse(0);
			continue;
		}
		scratch.joints.push_back(constraint);
		m_tmpConstraintSizesPool.push_back(info1);
		scratch.jointFirstRow.push_back(totalRows);
		totalRows += info1.m_numConstraintRows;
		if (constraint->getOverrideNumSolverIterations() > m_maxOverrideNumSolverIterations)
			m_maxOverrideNumSolverIterations = constraint->getOverrideNumSolverIterations();
	}
	m_tmpSolverNonContactConstraintPool.resizeNoInitialize(totalRows);
	scratch.jointBlocks.resizeNoInitialize(scratch.joints.size());

	// Each joint's warm-start entry, once per solve (a joint without rows this step starts cold later).
	scratch.jointWarmStart.resizeNoInitialize(scratch.joints.size());
	{
		caliber::JointWarmStartStore& store = scratch.jointWarmStarts();
		std::lock_guard<std::mutex> lock(store.mutex());
		for (int i = 0; i < scratch.idleJoints.size(); ++i) store.forget(scratch.idleJoints[i]);
		if (scratch.joints.size()) store.resolve(&scratch.joints[0], scratch.joints.size(), &scratch.jointWarmStart[0]);
	}

	int kept = 0;
	for (int i = 0; i < scratch.joints.size(); ++i)
	{
		btTypedConstraint* constraint = scratch.joints[i];
		if (constraint->needsFeedback() && constraint->getJointFeedback())
		{
			btJointFeedback* feedback = constraint->getJointFeedback();
			feedback->m_appliedForceBodyA.setZero();
			feedback->m_appliedTorqueBodyA.setZero();
			feedback->m_appliedForceBodyB.setZero();
			feedback->m_appliedTorqueBodyB.setZero();
		}
		const int idA = getOrInitSolverBody(constraint->getRigidBodyA(), infoGlobal.m_timeStep);
		const int idB = getOrInitSolverBody(constraint->getRigidBodyB(), infoGlobal.m_timeStep);
		// Rows of dropped joints are squeezed out, so the row array stays dense.
		const int firstRow =
		    kept == i
		        ? scratch.jointFirstRow[i]
		        : (kept ? scratch.jointFirstRow[kept - 1] + m_tmpConstraintSizesPool[kept - 1].m_numConstraintRows : 0);
		if (!caliber::convertJoint(m_tmpSolverBodyPool, &m_tmpSolverNonContactConstraintPool[firstRow], constraint,
		                           m_tmpConstraintSizesPool[i], idA, idB, infoGlobal, scratch.jointBlocks[kept],
		                           *scratch.jointWarmStart[i]))
		{
			constraint->setEnabled(false);
			scratch.jointWarmStart[i]->resize(0);
			btReportWarning(
			    "Caliber: a constraint produced non-finite rows (NaN or infinite frames, pivots or body state); "
			    "it has been disabled\n",
			    0);
			continue;
		}
		scratch.joints[kept] = constraint;
		m_tmpConstraintSizesPool[kept] = m_tmpConstraintSizesPool[i];
		scratch.jointFirstRow[kept] = firstRow;
		scratch.jointBlocks[kept].m_firstRow = firstRow;
		scratch.jointWarmStart[kept] = scratch.jointWarmStart[i];
		++kept;
	}
	scratch.joints.resize(kept);
	m_tmpConstraintSizesPool.resize(kept);
	scratch.jointFirstRow.resize(kept);
	scratch.jointBlocks.resize(kept);
	scratch.jointWarmStart.resize(kept);
	const int usedRows =
	    kept ? scratch.jointFirstRow[kept - 1] + m_tmpConstraintSizesPool[kept - 1].m_numConstraintRows : 0;
	m_tmpSolverNonContactConstraintPool.resize(usedRows);
}

btScalar caliber::solveJoint(const SolverScratch& scratch, btSolverBody* solverBodies, btConstraintArray& jointRows,
                             const btAlignedObjectArray<btTypedConstraint::btConstraintInfo1>& sizes, int jointIndex)
{
	const int first = scratch.jointFirstRow[jointIndex];
	const int end = first + sizes[jointIndex].m_numConstraintRows;
	btSolverConstraint* rows = &jointRows[0];
	btSolverBody& bodyA = solverBodies[rows[first].m_solverBodyIdA];
	btSolverBody& bodyB = solverBodies[rows[first].m_solverBodyIdB];
	btScalar residual = 0;
	int r = first;
	const caliber::SolverJointBlock& block = scratch.jointBlocks[jointIndex];
	if (block.m_size)
	{
		const int S = caliber::SolverJointBlock::MAX_ROWS;
		const int n = block.m_size;
		btScalar error[S];
		for (int i = 0; i < n; ++i)
			error[i] = block.m_target[i] - caliber::rowDeltaVelocity(bodyA, bodyB, rows[first + i]);
		// K^-1 error, a column at a time over all S rows (the columns are zero below n).
		btScalar deltas[S] = {};
		for (int j = 0; j < n; ++j)
		{
			const btScalar* column = &block.m_invK[j * S];
			for (int i = 0; i < S; ++i) deltas[i] += column[i] * error[j];
		}
		for (int i = 0; i < n; ++i)
		{
			btScalar delta = deltas[i];
			btSolverConstraint& row = rows[first + i];
			const btScalar clamped = btMax(row.m_lowerLimit, btMin(row.m_upperLimit, row.m_appliedImpulse + delta));
			delta = clamped - row.m_appliedImpulse;
			row.m_appliedImpulse = clamped;
			bodyA.applyImpulse(row.m_contactNormal1, row.m_angularComponentA, delta);
			bodyB.applyImpulse(row.m_contactNormal2, row.m_angularComponentB, delta);
			residual += delta * delta;
		}
		r += n;
	}
	for (; r < end; ++r)
		residual += caliber::resolveRow(bodyA, bodyB, rows[r], rows[r].m_lowerLimit, rows[r].m_upperLimit);
	return residual;
}

void btSequentialImpulseConstraintSolver::writeBackJoints(int iBegin, int iEnd, const btContactSolverInfo& infoGlobal)
{
	const btScalar invTimeStep = btScalar(1) / infoGlobal.m_timeStep;
	const caliber::SolverScratch& scratch = caliber::solverScratchOf(*this);
	for (int i = iBegin; i < iEnd; ++i)
	{
		btTypedConstraint* constraint = scratch.joints[i];
		const int first = scratch.jointFirstRow[i];
		const int numRows = m_tmpConstraintSizesPool[i].m_numConstraintRows;
		caliber::JointImpulses& warm = *scratch.jointWarmStart[i];
		warm.resizeNoInitialize(numRows);
		btJointFeedback* feedback = constraint->needsFeedback() ? constraint->getJointFeedback() : 0;
		const btRigidBody& rbA = constraint->getRigidBodyA();
		const btRigidBody& rbB = constraint->getRigidBodyB();
		btScalar largest = 0;
		bool broken = false;
		for (int j = 0; j < numRows; ++j)
		{
			const btSolverConstraint& row = m_tmpSolverNonContactConstraintPool[first + j];
			const btScalar impulse = row.m_appliedImpulse;
			warm[j] = impulse;
			if (btFabs(impulse) > btFabs(largest)) largest = impulse;
			if (btFabs(impulse) >= constraint->getBreakingImpulseThreshold()) broken = true;
			if (feedback)
			{
				feedback->m_appliedForceBodyA += row.m_contactNormal1 * rbA.getLinearFactor() * (impulse * invTimeStep);
				feedback->m_appliedTorqueBodyA +=
				    row.m_relpos1CrossNormal * rbA.getAngularFactor() * (impulse * invTimeStep);
				feedback->m_appliedForceBodyB += row.m_contactNormal2 * rbB.getLinearFactor() * (impulse * invTimeStep);
				feedback->m_appliedTorqueBodyB +=
				    row.m_relpos2CrossNormal * rbB.getAngularFactor() * (impulse * invTimeStep);
			}
		}
		constraint->internalSetAppliedImpulse(largest);
		if (broken)
		{
			constraint->setEnabled(false);
			warm.resize(0);
		}
	}
}
