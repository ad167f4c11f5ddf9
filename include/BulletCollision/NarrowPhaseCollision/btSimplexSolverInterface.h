// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SIMPLEX_SOLVER_INTERFACE_H
#define BT_SIMPLEX_SOLVER_INTERFACE_H

/// btSimplexSolverInterface: the simplex solver type GJK uses (the Voronoi solver, not a virtual interface).

#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"

/// The simplex solver used by GJK. A macro rather than a typedef, as in Bullet, so that user code that
/// forward-declares `class btSimplexSolverInterface;` keeps compiling.
#define btSimplexSolverInterface btVoronoiSimplexSolver

#endif  // BT_SIMPLEX_SOLVER_INTERFACE_H
