// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The multithreaded solver's first step: Bullet's class and knobs over the serial solver.
#include "BulletDynamics/ConstraintSolver/btSequentialImpulseConstraintSolverMt.h"

bool btSequentialImpulseConstraintSolverMt::s_allowNestedParallelForLoops = false;
int btSequentialImpulseConstraintSolverMt::s_minimumContactManifoldsForBatching = 250;
int btSequentialImpulseConstraintSolverMt::s_minBatchSize = 50;
int btSequentialImpulseConstraintSolverMt::s_maxBatchSize = 100;
btBatchedConstraints::BatchingMethod btSequentialImpulseConstraintSolverMt::s_contactBatchingMethod =
    btBatchedConstraints::BATCHING_METHOD_SPATIAL_GRID_2D;
btBatchedConstraints::BatchingMethod btSequentialImpulseConstraintSolverMt::s_jointBatchingMethod =
    btBatchedConstraints::BATCHING_METHOD_SPATIAL_GRID_2D;

btSequentialImpulseConstraintSolverMt::btSequentialImpulseConstraintSolverMt() {}

btSequentialImpulseConstraintSolverMt::~btSequentialImpulseConstraintSolverMt() {}
