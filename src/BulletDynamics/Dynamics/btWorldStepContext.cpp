// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Each world's step context, kept beside the world rather than in it (see btWorldStepContext.h).
#include "BulletDynamics/Dynamics/btWorldStepContext.h"

#include "Caliber/JointPositionCorrection.h"

#include "LinearMath/btSideTable.h"

namespace caliber
{
WorldStepContext& stepContextOf(const btDiscreteDynamicsWorld& world)
{
	return sideTable<WorldStepContext>().acquire(&world);
}

void releaseStepContext(const btDiscreteDynamicsWorld& world) { sideTable<WorldStepContext>().release(&world); }

void setJointPositionIterations(btDiscreteDynamicsWorld& world, int iterations)
{
	stepContextOf(world).jointPositionIterations = iterations;
}

int getJointPositionIterations(const btDiscreteDynamicsWorld& world)
{
	return stepContextOf(world).jointPositionIterations;
}
}  // namespace caliber
