// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_BLOCK_MATH_H
#define CALIBER_JOINT_BLOCK_MATH_H

// The small dense algebra of a joint's block of equality rows, shared by the velocity solver and the
// position correction.

#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "BulletDynamics/ConstraintSolver/btSolverJointBlock.h"

namespace caliber
{
// Inverts the n x n matrix a (n <= 6, rows stride apart) into inverse (same stride) by Gauss-Jordan
// elimination with partial pivoting; false when a pivot falls to tiny or below (singular for the
// caller's scale). Used by every small dense solve of the joints.
inline bool invertDense(const btScalar* a, int n, int stride, btScalar tiny, btScalar* inverse)
{
	btScalar m[6][12];
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j)
		{
			m[i][j] = a[i * stride + j];
			m[i][n + j] = i == j ? btScalar(1) : btScalar(0);
		}
	for (int c = 0; c < n; ++c)
	{
		int pivot = c;
		for (int r = c + 1; r < n; ++r)
			if (btFabs(m[r][c]) > btFabs(m[pivot][c])) pivot = r;
		if (!(btFabs(m[pivot][c]) > tiny)) return false;
		if (pivot != c)
			for (int j = 0; j < 2 * n; ++j) btSwap(m[c][j], m[pivot][j]);
		const btScalar inv = btScalar(1) / m[c][c];
		for (int j = 0; j < 2 * n; ++j) m[c][j] *= inv;
		for (int r = 0; r < n; ++r)
		{
			if (r == c || m[r][c] == btScalar(0)) continue;
			const btScalar f = m[r][c];
			for (int j = 0; j < 2 * n; ++j) m[r][j] -= f * m[c][j];
		}
	}
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) inverse[i * stride + j] = m[i][n + j];
	return true;
}

// Inverts the n x n matrix J M^-1 J^T of rows [0, n) by Gauss-Jordan elimination with partial pivoting
// into invK (stride caliber::SolverJointBlock::MAX_ROWS); false when it is singular (redundant rows, or both
// bodies immovable), in which case the rows are solved one by one.
inline bool buildBlockInverse(const btSolverConstraint* rows, int n, const btSolverBody& a, const btSolverBody& b,
                              btScalar* invK)
{
	const int S = caliber::SolverJointBlock::MAX_ROWS;
	btScalar k[S][2 * S];
	btScalar largestDiagonal = 0;
	// K is symmetric: each pair once. Rows carry I^-1 J in m_angularComponent, so K_ij = J_i . M^-1 J_j.
	for (int i = 0; i < n; ++i)
	{
		const btVector3 linearA = rows[i].m_contactNormal1 * a.m_invMass;
		const btVector3 linearB = rows[i].m_contactNormal2 * b.m_invMass;
		const btVector3 angularA = rows[i].m_angularComponentA * a.m_angularFactor;
		const btVector3 angularB = rows[i].m_angularComponentB * b.m_angularFactor;
		for (int j = i; j < n; ++j)
		{
			const btVector3 lanes = rows[j].m_contactNormal1 * linearA + rows[j].m_relpos1CrossNormal * angularA +
			                        rows[j].m_contactNormal2 * linearB + rows[j].m_relpos2CrossNormal * angularB;
			k[i][j] = k[j][i] = lanes.x() + lanes.y() + lanes.z();
		}
		for (int j = 0; j < n; ++j) k[i][n + j] = i == j ? btScalar(1) : btScalar(0);
		largestDiagonal = btMax(largestDiagonal, k[i][i]);
	}
	if (!(largestDiagonal > btScalar(0))) return false;
	const btScalar tiny = largestDiagonal * btScalar(1e-5);
	if (n >= 3)
	{
		// The leading 3 x 3 (a ball joint's block, or the pivot rows of a hinge) in closed form, the rest
		// through its Schur complement: cheaper than eliminating the whole block.
		const btMatrix3x3 leading(k[0][0], k[0][1], k[0][2], k[1][0], k[1][1], k[1][2], k[2][0], k[2][1], k[2][2]);
		const btScalar det = leading.determinant();
		if (btFabs(det) > tiny * tiny * tiny)
		{
			const btMatrix3x3 aInverse = leading.adjoint() * (btScalar(1) / det);
			const int m = n - 3;
			if (m == 0)
			{
				for (int i = 0; i < 3; ++i)
					for (int j = 0; j < 3; ++j) invK[i * S + j] = aInverse[i][j];
				return true;
			}
			// A^-1 B (3 x m), then S = C - B^T A^-1 B (m x m), inverted by elimination.
			btScalar aInvB[3][3], schur[3][2 * 3];
			for (int i = 0; i < 3; ++i)
				for (int j = 0; j < m; ++j)
					aInvB[i][j] =
					    aInverse[i][0] * k[0][3 + j] + aInverse[i][1] * k[1][3 + j] + aInverse[i][2] * k[2][3 + j];
			for (int i = 0; i < m; ++i)
				for (int j = 0; j < m; ++j)
				{
					schur[i][j] = k[3 + i][3 + j] -
					              (k[0][3 + i] * aInvB[0][j] + k[1][3 + i] * aInvB[1][j] + k[2][3 + i] * aInvB[2][j]);
					schur[i][m + j] = i == j ? btScalar(1) : btScalar(0);
				}
			bool regular = true;
			for (int c = 0; c < m && regular; ++c)
			{
				int pivot = c;
				for (int r = c + 1; r < m; ++r)
					if (btFabs(schur[r][c]) > btFabs(schur[pivot][c])) pivot = r;
				regular = btFabs(schur[pivot][c]) > tiny;
				if (!regular) break;
				if (pivot != c)
					for (int j = 0; j < 2 * m; ++j) btSwap(schur[c][j], schur[pivot][j]);
				const btScalar inv = btScalar(1) / schur[c][c];
				for (int j = 0; j < 2 * m; ++j) schur[c][j] *= inv;
				for (int r = 0; r < m; ++r)
				{
					if (r == c) continue;
					const btScalar f = schur[r][c];
					for (int j = 0; j < 2 * m; ++j) schur[r][j] -= f * schur[c][j];
				}
			}
			if (regular)
			{
				// [[A^-1 + A^-1 B S^-1 B^T A^-1, -A^-1 B S^-1], [-S^-1 B^T A^-1, S^-1]].
				btScalar cross[3][3];  // A^-1 B S^-1 (3 x m)
				for (int i = 0; i < 3; ++i)
					for (int j = 0; j < m; ++j)
					{
						btScalar sum = 0;
						for (int l = 0; l < m; ++l) sum += aInvB[i][l] * schur[l][m + j];
						cross[i][j] = sum;
					}
				for (int i = 0; i < 3; ++i)
				{
					for (int j = 0; j < 3; ++j)
					{
						btScalar sum = aInverse[i][j];
						for (int l = 0; l < m; ++l) sum += cross[i][l] * aInvB[j][l];
						invK[i * S + j] = sum;
					}
					for (int j = 0; j < m; ++j)
					{
						invK[i * S + 3 + j] = -cross[i][j];
						invK[(3 + j) * S + i] = -cross[i][j];
					}
				}
				for (int i = 0; i < m; ++i)
					for (int j = 0; j < m; ++j) invK[(3 + i) * S + 3 + j] = schur[i][m + j];
				return true;
			}
		}
	}
	btScalar dense[S * S];
	for (int i = 0; i < n; ++i)
		for (int j = 0; j < n; ++j) dense[i * S + j] = k[i][j];
	return invertDense(dense, n, S, tiny, invK);
}

}  // namespace caliber

#endif  // CALIBER_JOINT_BLOCK_MATH_H
