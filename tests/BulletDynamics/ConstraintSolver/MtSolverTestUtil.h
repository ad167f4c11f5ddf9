// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_MT_SOLVER_TEST_UTIL_H
#define CALIBER_TESTS_MT_SOLVER_TEST_UTIL_H

#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"

namespace caliber_test
{
/// Sets btSequentialImpulseConstraintSolverMt's colouring threshold (a public static knob, shared by every
/// test in the process) for one scope and puts the old value back, also when an ASSERT leaves early.
/// A threshold of 1 colours every solve: the test scenes have far fewer than the default 250 manifolds.
class ScopedManifoldBatchingThreshold
{
public:
	explicit ScopedManifoldBatchingThreshold(int threshold = 1)
	{
		btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = threshold;
	}
	~ScopedManifoldBatchingThreshold()
	{
		btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = m_saved;
	}
	ScopedManifoldBatchingThreshold(const ScopedManifoldBatchingThreshold&) = delete;
	ScopedManifoldBatchingThreshold& operator=(const ScopedManifoldBatchingThreshold&) = delete;

private:
	int m_saved = btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching;
};
}  // namespace caliber_test

#endif
