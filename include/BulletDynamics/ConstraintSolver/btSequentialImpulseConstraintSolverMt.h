// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_MT_H
#define BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_MT_H

#include "BulletDynamics/ConstraintSolver/btBatchedConstraints.h"
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolver.h"
#include "LinearMath/btThreads.h"

/// Bullet 2.89's multithreaded sequential-impulse solver. A solve with at least
/// s_minimumContactManifoldsForBatching manifolds colours its contacts: manifolds that share no dynamic
/// body get the same colour, the colours are solved one after another, and the manifolds of one colour
/// in batches on the task scheduler's threads. The result does not depend on the thread count or the
/// scheduler, bit for bit; it differs from btSequentialImpulseConstraintSolver's (another Gauss-Seidel
/// order). Its contact rows are set up on the threads too, with the serial setup's bits. Smaller solves
/// are btSequentialImpulseConstraintSolver's (docs/threading.md).
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

protected:
	/// The contact rows of the solve grouped by colour (phases) into batches, when m_useBatching.
	btBatchedConstraints m_batchedContactConstraints;
	/// Whether this solve colours its contacts.
	bool m_useBatching;

	/// Large solves: the points' rows filled on the scheduler's threads (the serial solver's bits).
	void convertContacts(btPersistentManifold * *manifoldPtr, int numManifolds,
	                     const btContactSolverInfo& infoGlobal) override;
	btScalar solveGroupCacheFriendlySetup(btCollisionObject * *bodies, int numBodies, btPersistentManifold** manifoldPtr,
	                                      int numManifolds, btTypedConstraint** constraints, int numConstraints,
	                                      const btContactSolverInfo& infoGlobal, btIDebugDraw* debugDrawer) override;
	/// Large solves: contacts and bodies written back on the scheduler's threads.
	btScalar solveGroupCacheFriendlyFinish(btCollisionObject * *bodies, int numBodies,
	                                       const btContactSolverInfo& infoGlobal) override;
	btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
	                              btPersistentManifold** manifoldPtr, int numManifolds, btTypedConstraint** constraints,
	                              int numConstraints, const btContactSolverInfo& infoGlobal,
	                              btIDebugDraw* debugDrawer) override;
};

#endif  // BT_SEQUENTIAL_IMPULSE_CONSTRAINT_SOLVER_MT_H
