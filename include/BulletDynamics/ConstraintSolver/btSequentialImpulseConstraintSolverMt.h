// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_MT_H
#define BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_MT_H

#include "BulletDynamics/ConstraintSolver/btBatchedConstraints.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "LinearMath/btThreads.h"

/// Bullet 2.89's multithreaded sequential-impulse solver. Its tuning knobs are accepted; in this
/// version it solves exactly as btSequentialImpulseConstraintSolver (docs/threading.md).
ATTRIBUTE_ALIGNED16(class)
btSequentialImpulseConstraintSolverMt : public btSequentialImpulseConstraintSolver
{
public:
	/// Rows of a joint, by solver row and solver bodies.
	struct JointParams
	{
		int m_solverConstraint;
		int m_solverBodyA;
		int m_solverBodyB;
	};

	/// Whether solver loops may run parallel loops inside the islands' parallel loop.
	static bool s_allowNestedParallelForLoops;
	/// Islands with fewer manifolds than this are not batched.
	static int s_minimumContactManifoldsForBatching;
	/// Smallest batch of rows.
	static int s_minBatchSize;
	/// Largest batch of rows.
	static int s_maxBatchSize;
	/// How contact rows are batched.
	static btBatchedConstraints::BatchingMethod s_contactBatchingMethod;
	/// How joint rows are batched.
	static btBatchedConstraints::BatchingMethod s_jointBatchingMethod;

	BT_DECLARE_ALIGNED_ALLOCATOR();

	btSequentialImpulseConstraintSolverMt();
	virtual ~btSequentialImpulseConstraintSolverMt();
};

#endif  // BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_MT_H
