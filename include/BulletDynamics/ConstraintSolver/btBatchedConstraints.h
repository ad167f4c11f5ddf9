// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_BATCHED_CONSTRAINTS_H
#define BT_BATCHED_CONSTRAINTS_H

#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

class btIDebugDraw;

/// Bullet 2.89's grouping of solver rows into phases of batches: the batches of one phase share no
/// dynamic body and may be solved at the same time; phases run one after another. This version makes
/// one phase of one batch (always valid); the colouring that makes wide phases is still to come.
class btBatchedConstraints
{
public:
	/// How rows would be grouped (both give the single batch in this version).
	enum BatchingMethod
	{
		BATCHING_METHOD_SPATIAL_GRID_2D,
		BATCHING_METHOD_SPATIAL_GRID_3D,
		BATCHING_METHOD_COUNT
	};
	/// A half-open range of indices.
	struct Range
	{
		int begin;
		int end;

		Range() : begin(0), end(0) {}
		Range(int _begin, int _end) : begin(_begin), end(_end) {}
	};

	btAlignedObjectArray<int> m_constraintIndices;  ///< row indices, batch after batch
	btAlignedObjectArray<Range> m_batches;          ///< ranges of m_constraintIndices
	btAlignedObjectArray<Range> m_phases;           ///< ranges of m_batches
	btAlignedObjectArray<char> m_phaseGrainSize;    ///< batches per task in each phase
	btAlignedObjectArray<int> m_phaseOrder;         ///< the order phases are solved in
	btIDebugDraw* m_debugDrawer;

	static bool s_debugDrawBatches;

	btBatchedConstraints() { m_debugDrawer = 0; }
	/// Groups the rows of constraints over bodies (minBatchSize, maxBatchSize and scratchMemory are hints).
	void setup(btConstraintArray* constraints, const btAlignedObjectArray<btSolverBody>& bodies,
	           BatchingMethod batchingMethod, int minBatchSize, int maxBatchSize,
	           btAlignedObjectArray<char>* scratchMemory);
	/// True when every row is in exactly one batch and no two batches of a phase share a dynamic body.
	bool validate(btConstraintArray* constraints, const btAlignedObjectArray<btSolverBody>& bodies) const;
};

#endif  // BT_BATCHED_CONSTRAINTS_H
