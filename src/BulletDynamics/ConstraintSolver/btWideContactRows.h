// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WIDE_CONTACT_ROWS_H
#define CALIBER_WIDE_CONTACT_ROWS_H

// The wide solver: the contact rows of a coloured batch solved several manifolds at a time, one
// manifold per SIMD lane. The manifolds of a batch share no moving body, so the lanes never touch the
// same body (the fixed entry they may share takes impulses of zero), and each lane performs exactly the
// operations the scalar row kernel (btSolverRowKernels.h) performs, in the same order: the bodies end
// with the same bits as when the rows are solved one by one.
//
// Layout: a group holds up to kWideLanes manifolds of one batch, with the constants of their bodies.
// Its k-th block of normal rows holds the k-th point (in the solve's rotated order) of each manifold,
// structure of arrays; a lane whose manifold has fewer points is padding (all zero, row index -1) and
// changes nothing. Friction rows follow the same blocks, frictionRowsPerContact blocks per normal block.
// A group's bodies are loaded once per pass, kept in registers while its blocks are solved, and stored
// back.

#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// Manifolds solved side by side: one SSE register of floats.
const int kWideLanes = 4;

/// kWideLanes rows, one per lane, structure of arrays (components x, y, z, then the lanes).
ATTRIBUTE_ALIGNED16(struct)
WideRowBlock
{
	btScalar normal1[3][kWideLanes];
	btScalar relpos1CrossNormal[3][kWideLanes];
	btScalar normal2[3][kWideLanes];
	btScalar relpos2CrossNormal[3][kWideLanes];
	btScalar angularA[3][kWideLanes];
	btScalar angularB[3][kWideLanes];
	btScalar rhs[kWideLanes];
	btScalar cfm[kWideLanes];
	btScalar jacDiagABInv[kWideLanes];
	btScalar lower[kWideLanes];     // normal rows
	btScalar upper[kWideLanes];     // normal rows
	btScalar friction[kWideLanes];  // friction rows
	btScalar applied[kWideLanes];
	int row[kWideLanes];  // the row in its pool, -1 for padding
};

/// Up to kWideLanes manifolds of one batch and the constants of their bodies.
ATTRIBUTE_ALIGNED16(struct)
WideGroup
{
	btScalar invMassA[3][kWideLanes];
	btScalar angularFactorA[3][kWideLanes];
	btScalar invMassB[3][kWideLanes];
	btScalar angularFactorB[3][kWideLanes];
	int bodyA[kWideLanes];
	int bodyB[kWideLanes];
	int firstBlock;  // its first normal block
	int numBlocks;   // the most points of its manifolds
};

/// The wide rows of a solve, batch by batch.
struct WideContactRows
{
	btAlignedObjectArray<WideGroup> groups;
	btAlignedObjectArray<WideRowBlock> normalBlocks;
	btAlignedObjectArray<WideRowBlock> frictionBlocks;  // frictionRowsPerContact per normal block
	btAlignedObjectArray<int> batchFirstGroup;          // per batch, and one past the last
	int frictionRowsPerContact;

	/// Sizes the arrays for the batches' manifolds: batchManifoldBegin[b] .. batchManifoldBegin[b + 1]
	/// index manifolds, whose rows are manifoldFirstRow[m] .. manifoldFirstRow[m + 1].
	void plan(const btAlignedObjectArray<int>& orderedManifolds, const btAlignedObjectArray<int>& batchManifoldBegin,
	          const btAlignedObjectArray<int>& manifoldFirstRow, int frictionRows);

	/// Fills the groups and blocks of batches [batchBegin, batchEnd) (any order, any thread): points
	/// rotated by solveCount as in the scalar sweep, padding lanes on the batch's padding body.
	void fill(int batchBegin, int batchEnd, const btAlignedObjectArray<int>& orderedManifolds,
	          const btAlignedObjectArray<int>& batchManifoldBegin, const btAlignedObjectArray<int>& manifoldFirstRow,
	          const btAlignedObjectArray<int>& batchPaddingBody, unsigned int solveCount, const btSolverBody* bodies,
	          const btConstraintArray& contacts, const btConstraintArray& friction);

	/// One sweep of batch's normal rows; their impulses are also stored in their rows. Returns the sum of
	/// the squared impulse changes.
	btScalar sweepNormal(int batch, bool reverse, btSolverBody* bodies, btConstraintArray& contacts);
	/// One sweep of batch's friction rows, bounded by the normal impulses of the blocks.
	btScalar sweepFriction(int batch, bool reverse, btSolverBody* bodies, btConstraintArray& friction);
};

/// False turns the wide sweep off (the coloured batches are then solved row by row, with the same bits);
/// for tests and measurements. On by default.
void setWideContactRowsEnabled(bool enabled);
bool wideContactRowsEnabled();

}  // namespace caliber

#endif  // CALIBER_WIDE_CONTACT_ROWS_H
