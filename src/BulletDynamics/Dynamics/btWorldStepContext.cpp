// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Each world's step context, kept beside the world rather than in it (see btWorldStepContext.h).
#include "BulletDynamics/Dynamics/btWorldStepContext.h"

#include "Caliber/JointPositionCorrection.h"

#include "LinearMath/btScalar.h"
#include "LinearMath/btSideTable.h"
#include "LinearMath/btWarningHook.h"

namespace caliber
{
WorldStepContext& stepContextOf(const btDiscreteDynamicsWorld& world)
{
	return sideTable<WorldStepContext>().acquire(&world);
}

void releaseStepContext(const btDiscreteDynamicsWorld& world) { sideTable<WorldStepContext>().release(&world); }

void setJointPositionIterations(btDiscreteDynamicsWorld& world, int iterations)
{
	// Each sweep visits every joint once per substep: beyond this the step would only get slower (the
	// correction converges in a handful), and a garbage count would stall the simulation.
	const int kMaxIterations = 1024;
	btAssert(iterations >= 0 && iterations <= kMaxIterations && "joint position iterations out of range");
	if (iterations < 0)
	{
		btReportWarning("caliber::setJointPositionIterations: a negative count is ignored");
		return;
	}
	if (iterations > kMaxIterations)
	{
		btReportWarning("caliber::setJointPositionIterations: count clamped to 1024");
		iterations = kMaxIterations;
	}
	stepContextOf(world).jointPositionIterations = iterations;
}

int getJointPositionIterations(const btDiscreteDynamicsWorld& world)
{
	return stepContextOf(world).jointPositionIterations;
}
}  // namespace caliber
