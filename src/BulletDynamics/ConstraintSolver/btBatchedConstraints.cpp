// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btBatchedConstraints' first step: every row in one batch of one phase, which is valid for any rows.
// validate checks the property a real colouring must keep, so it already guards the later one.
#include "BulletDynamics/ConstraintSolver/btBatchedConstraints.h"

bool btBatchedConstraints::s_debugDrawBatches = false;

void btBatchedConstraints::setup(btConstraintArray* constraints, const btAlignedObjectArray<btSolverBody>& bodies,
                                 BatchingMethod batchingMethod, int minBatchSize, int maxBatchSize,
                                 btAlignedObjectArray<char>* scratchMemory)
{
	(void)bodies;
	(void)batchingMethod;
	(void)minBatchSize;
	(void)maxBatchSize;
	(void)scratchMemory;
	const int numRows = constraints ? constraints->size() : 0;
	m_constraintIndices.resize(numRows);
	for (int i = 0; i < numRows; ++i) m_constraintIndices[i] = i;
	m_batches.resize(0);
	m_phases.resize(0);
	m_phaseGrainSize.resize(0);
	m_phaseOrder.resize(0);
	if (numRows == 0) return;
	m_batches.push_back(Range(0, numRows));
	m_phases.push_back(Range(0, 1));
	m_phaseGrainSize.push_back(1);
	m_phaseOrder.push_back(0);
}

bool btBatchedConstraints::validate(btConstraintArray* constraints, const btAlignedObjectArray<btSolverBody>& bodies) const
{
	const int numRows = constraints ? constraints->size() : 0;
	if (m_constraintIndices.size() != numRows) return false;
	// Every row exactly once.
	btAlignedObjectArray<int> seen;
	seen.resize(numRows, 0);
	for (int i = 0; i < m_constraintIndices.size(); ++i)
	{
		const int row = m_constraintIndices[i];
		if (row < 0 || row >= numRows || seen[row]++) return false;
	}
	// Within a phase, a dynamic body belongs to at most one batch (-1: none yet).
	btAlignedObjectArray<int> batchOfBody;
	for (int p = 0; p < m_phases.size(); ++p)
	{
		batchOfBody.resize(0);
		batchOfBody.resize(bodies.size(), -1);
		const Range& phase = m_phases[p];
		if (phase.begin < 0 || phase.end > m_batches.size() || phase.begin > phase.end) return false;
		for (int b = phase.begin; b < phase.end; ++b)
		{
			const Range& batch = m_batches[b];
			if (batch.begin < 0 || batch.end > m_constraintIndices.size() || batch.begin > batch.end) return false;
			for (int i = batch.begin; i < batch.end; ++i)
			{
				const btSolverConstraint& row = (*constraints)[m_constraintIndices[i]];
				const int ends[2] = {row.m_solverBodyIdA, row.m_solverBodyIdB};
				for (int e = 0; e < 2; ++e)
				{
					const int body = ends[e];
					if (body < 0 || body >= bodies.size()) return false;
					if (bodies[body].m_invMass.fuzzyZero()) continue;  // static or kinematic: shared freely
					if (batchOfBody[body] >= 0 && batchOfBody[body] != b) return false;
					batchOfBody[body] = b;
				}
			}
		}
	}
	return true;
}
