// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_WIDE_CONTACT_ROWS_H
#define CALIBER_WIDE_CONTACT_ROWS_H

// The wide solver: the contact rows of a coloured batch solved several manifolds at a time, one
// manifold per SIMD lane (four with SSE2, eight with AVX2). The manifolds of a batch share no moving
// body, so the lanes never touch the same body (the fixed entry they may share takes impulses of zero),
// and each lane performs exactly the operations the scalar row kernel (btSolverRowKernels.h) performs,
// in the same order: the bodies end with the same bits as when the rows are solved one by one.
//
// Layout: a group holds up to W (the lane count) manifolds of one batch, with the constants of their
// bodies. Its k-th block of normal rows holds the k-th point (in the solve's rotated order) of each manifold,
// structure of arrays; a lane whose manifold has fewer points is padding (all zero, row index -1) and
// changes nothing. Friction rows follow the same blocks, frictionRowsPerContact blocks per normal block.
// A group's bodies are loaded once per pass, kept in registers while its blocks are solved, and stored
// back.

#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "LinearMath/btAlignedObjectArray.h"

namespace caliber
{
/// Manifolds solved side by side in the row blocks of a layout: four (one SSE register of floats) or
/// eight (one AVX register).
template <int W>
ATTRIBUTE_ALIGNED16(struct)
WideRowBlockT
{
	btScalar normal1[3][W];
	btScalar relpos1CrossNormal[3][W];
	btScalar relpos2CrossNormal[3][W];
	btScalar angularA[3][W];
	btScalar angularB[3][W];
	btScalar rhs[W];
	btScalar cfm[W];
	btScalar jacDiagABInv[W];
	btScalar lower[W];     // normal rows
	btScalar upper[W];     // normal rows
	btScalar friction[W];  // friction rows
	btScalar applied[W];
	int row[W];  // the row in its pool, -1 for padding
};

/// Up to W manifolds of one batch and the constants of their bodies.
template <int W>
ATTRIBUTE_ALIGNED16(struct)
WideGroupT
{
	btScalar invMassA[3][W];
	btScalar angularFactorA[3][W];
	btScalar invMassB[3][W];
	btScalar angularFactorB[3][W];
	int bodyA[W];
	int bodyB[W];
	int firstBlock;  // its first normal block
	int numBlocks;   // the most points of its manifolds
};

/// The groups and blocks of one lane count.
template <int W>
struct WideLayout
{
	btAlignedObjectArray<WideGroupT<W> > groups;
	btAlignedObjectArray<WideRowBlockT<W> > normalBlocks;
	btAlignedObjectArray<WideRowBlockT<W> > frictionBlocks;  // frictionRowsPerContact per normal block
};

/// The wide rows of a solve, batch by batch.
struct WideContactRows
{
	int lanes = 4;  // of this solve's layout
	WideLayout<4> four;
	WideLayout<8> eight;
	btAlignedObjectArray<int> batchFirstGroup;  // per batch, and one past the last
	btAlignedObjectArray<int> batchFirstBlock;  // per batch, and one past the last: its groups' first block
	int frictionRowsPerContact = 1;

	/// Chooses the lanes (wideContactLanes) and sizes the arrays for the batches' manifolds:
	/// batchManifoldBegin[b] .. batchManifoldBegin[b + 1] index orderedManifolds, whose rows are
	/// manifoldFirstRow[m] .. manifoldFirstRow[m + 1]. Counts the groups' blocks on the task scheduler's
	/// threads (batch by batch: the same plan at any thread count).
	void plan(const btAlignedObjectArray<int>& orderedManifolds, const btAlignedObjectArray<int>& batchManifoldBegin,
	          const btAlignedObjectArray<int>& manifoldFirstRow, int frictionRows);

	/// Fills the groups (their first blocks too) and blocks of batches [batchBegin, batchEnd) (any order,
	/// any thread): points rotated by solveCount as in the scalar sweep, padding lanes on the batch's
	/// padding body. False when a row's second linear direction is not its first one negated (the blocks
	/// keep only the first; every row Caliber's set-up makes has it, a subclass's convertContacts may
	/// not): the solve must then be swept row by row.
	bool fill(int batchBegin, int batchEnd, const btAlignedObjectArray<int>& orderedManifolds,
	          const btAlignedObjectArray<int>& batchManifoldBegin, const btAlignedObjectArray<int>& manifoldFirstRow,
	          const btAlignedObjectArray<int>& batchPaddingBody, unsigned int solveCount, const btSolverBody* bodies,
	          const btConstraintArray& contacts, const btConstraintArray& friction);

	/// One sweep of batch's normal rows; with contacts, their impulses are also stored in their rows (the
	/// rolling rows read them during the sweeps). Returns the sum of the squared impulse changes.
	btScalar sweepNormal(int batch, bool reverse, btSolverBody* bodies, btConstraintArray* contacts);
	/// One sweep of batch's friction rows, bounded by the normal impulses of the blocks; with friction,
	/// their impulses are also stored in their rows.
	btScalar sweepFriction(int batch, bool reverse, btSolverBody* bodies, btConstraintArray* friction);
	/// Every impulse of batches [batchBegin, batchEnd) into its row (after the last sweep: the passes after
	/// the sweeps and the write-back read the rows).
	void storeImpulses(int batchBegin, int batchEnd, btConstraintArray& contacts, btConstraintArray& friction);
};

/// False turns the wide sweep off (the coloured batches are then solved row by row, with the same bits);
/// for tests and measurements. On by default.
void setWideContactRowsEnabled(bool enabled);
bool wideContactRowsEnabled();

/// The lanes of the wide sweep: 8 where the processor has AVX2 (single precision SSE builds compiled by
/// GCC or Clang), else 4. setWideContactLanes(4) or (8) asks for a count (8 falls back to 4 where it is
/// not available), 0 (or any other count) goes back to the automatic choice; for tests and measurements. Read when a solve
/// is set up.
void setWideContactLanes(int lanes);
int wideContactLanes();
/// Whether eight lanes are available on this processor and in this build.
bool wideContactEightLanesAvailable();
}  // namespace caliber

#endif  // CALIBER_WIDE_CONTACT_ROWS_H
