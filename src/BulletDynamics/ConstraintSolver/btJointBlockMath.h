// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_BLOCK_MATH_H
#define CALIBER_JOINT_BLOCK_MATH_H

// The small dense algebra of a joint's block of equality rows, shared by the velocity solver and the
// position correction.

#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"

namespace caliber
{
// Inverts the n x n matrix J M^-1 J^T of rows [0, n) by Gauss-Jordan elimination with partial pivoting
// into invK (stride btSolverJointBlock::MAX_ROWS); false when it is singular (redundant rows, or both
// bodies immovable), in which case the rows are solved one by one.
inline bool buildBlockInverse(const btSolverConstraint* rows, int n, const btSolverBody& a, const btSolverBody& b,
                              btScalar* invK)
{
	const int S = btSolverJointBlock::MAX_ROWS;
	btScalar k[S][2 * S];
	btScalar largestDiagonal = 0;
	for (int i = 0; i < n; ++i)
	{
		for (int j = 0; j < n; ++j)
		{
			k[i][j] = rows[i].m_contactNormal1.dot(rows[j].m_contactNormal1 * a.m_invMass) +
			          rows[i].m_relpos1CrossNormal.dot(rows[j].m_angularComponentA * a.m_angularFactor) +
			          rows[i].m_contactNormal2.dot(rows[j].m_contactNormal2 * b.m_invMass) +
			          rows[i].m_relpos2CrossNormal.dot(rows[j].m_angularComponentB * b.m_angularFactor);
			k[i][n + j] = i == j ? btScalar(1) : btScalar(0);
		}
		largestDiagonal = btMax(largestDiagonal, k[i][i]);
	}
	if (!(largestDiagonal > btScalar(0))) return false;
	const btScalar tiny = largestDiagonal * btScalar(1e-5);
	for (int c = 0; c < n; ++c)
	{
		int pivot = c;
		for (int r = c + 1; r < n; ++r)
			if (btFabs(k[r][c]) > btFabs(k[pivot][c])) pivot = r;
		if (!(btFabs(k[pivot][c]) > tiny)) return false;
		if (pivot != c)
			for (int j = 0; j < 2 * n; ++j) btSwap(k[c][j], k[pivot][j]);
		const btScalar inv = btScalar(1) / k[c][c];
		for (int j = 0; j < 2 * n; ++j) k[c][j] *= inv;
		for (int r = 0; r < n; ++r)
		{
			if (r == c || k[r][c] == btScalar(0)) continue;
			const btScalar f = k[r][c];
			for (int j = 0; j < 2 * n; ++j) k[r][j] -= f * k[c][j];
		}
	}
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) invK[i * S + j] = k[i][n + j];
	return true;
}

}  // namespace caliber

#endif  // CALIBER_JOINT_BLOCK_MATH_H
