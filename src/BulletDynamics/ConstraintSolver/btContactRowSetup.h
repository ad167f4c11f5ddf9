// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_CONTACT_ROW_SETUP_H
#define CALIBER_CONTACT_ROW_SETUP_H

// The contact rows of the solver's setup in three parts, so that the multithreaded solver can fill the
// rows of many points at once and still get the serial solver's bits: deciding which points get rows
// and where (in point order), filling a point's rows (any order, any thread: a row reads only its
// point and the solver bodies' velocities), and applying the warm-start impulses to the bodies (in
// point order: the bodies' velocity changes are sums whose order matters).

#include "BulletCollision/NarrowPhaseCollision/btManifoldPoint.h"
#include "BulletDynamics/ConstraintSolver/btContactSolverInfo.h"
#include "BulletDynamics/ConstraintSolver/btSolverBody.h"
#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "LinearMath/btAlignedObjectArray.h"

class btCollisionObject;
class btPersistentManifold;

namespace caliber
{
/// A manifold point that gets rows, and where they go.
struct ContactPointRows
{
	btManifoldPoint* cp;
	btCollisionObject* object0;
	btCollisionObject* object1;
	int solverBodyIdA;
	int solverBodyIdB;
	int contactRow;        ///< its normal row
	int firstFrictionRow;  ///< frictionRowsPerContact rows from here
	int firstRollingRow;   ///< rollingRowsOf(*cp) rows from here
	btVector3 relPos1;
	btVector3 relPos2;
};

/// The solver's row pools.
struct ContactRowPools
{
	btAlignedObjectArray<btSolverBody>* bodies;
	btConstraintArray* contacts;
	btConstraintArray* friction;
	btConstraintArray* rolling;
};

/// Rolling and spinning rows of a point: 1 for spinning friction, 2 for rolling friction.
inline int rollingRowsOf(const btManifoldPoint& cp)
{
	return (cp.m_combinedSpinningFriction > btScalar(0) ? 1 : 0) + (cp.m_combinedRollingFriction > btScalar(0) ? 2 : 0);
}

/// Whether a manifold between these solver bodies needs rows (false when neither body can move).
bool solverBodiesCanMove(const btAlignedObjectArray<btSolverBody>& bodies, int solverBodyIdA, int solverBodyIdB);
/// Whether manifold's point `index` gets rows this solve (within the processing threshold, finite, and not a
/// speculative point its bodies cannot close, whose old impulses are then cleared); fills point except
/// its row indices. Call in point order (it may write the point).
bool planContactPoint(btPersistentManifold& manifold, int index, btCollisionObject* object0,
                      btCollisionObject* object1, int solverBodyIdA, int solverBodyIdB,
                      const btAlignedObjectArray<btSolverBody>& bodies, const btContactSolverInfo& infoGlobal,
                      ContactPointRows& point);
/// Fills the point's rows at its indices (the pools are already that large); warm-start impulses are set
/// in the rows, not applied. Writes the point's friction directions.
void fillContactPointRows(const ContactRowPools& pools, const ContactPointRows& point,
                          const btContactSolverInfo& infoGlobal);
/// Whether fillContactPointRows (and the serial set-up) run their AVX2 build on this processor: the same
/// operations in the same order (no FMA), so the same bits as the SSE build.
bool contactPointRowsUseAvx2();
/// For tests: fillContactPointRows in the AVX2 build when avx2 and the processor has it, otherwise in the
/// library's baseline build; then the warm starts when warmStarts is 1 (fused with the fill, as the serial
/// set-up does) or 2 (applyContactPointWarmStarts after the fill, as the Mt set-up does).
void fillContactPointRowsIn(const ContactRowPools& pools, const ContactPointRows& point,
                            const btContactSolverInfo& infoGlobal, bool avx2, int warmStarts);
/// Applies the point's warm-start impulses to its bodies: the normal row's, then the friction rows'.
void applyContactPointWarmStarts(const ContactRowPools& pools, const ContactPointRows& point,
                                 const btContactSolverInfo& infoGlobal);
}  // namespace caliber

#endif  // CALIBER_CONTACT_ROW_SETUP_H
