// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btHinge2Constraint.h"

#include "LinearMath/btWarningHook.h"

namespace
{
// An axle leaning by more than this (as the cosine of its angle to axis1) is reported before it is
// straightened: float round-off in user code stays far below it.
const btScalar kPerpendicularTolerance = btScalar(1e-3);
}  // namespace

btHinge2Constraint::btHinge2Constraint(btRigidBody& rbA, btRigidBody& rbB, const btVector3& anchor,
                                       const btVector3& axis1, const btVector3& axis2)
    : btGeneric6DofSpring2Constraint(rbA, rbB, btTransform::getIdentity(), btTransform::getIdentity(), RO_XYZ),
      m_anchor(anchor),
      m_axis1(axis1),
      m_axis2(axis2)
{
	// Frame: z along axis1, x along axis2, y = z x x. With rotation order XYZ the first rotation turns
	// about B's x (the axle: the wheel's spin, free), the last about A's z (steering, limited) and the
	// middle one, which would tilt the axle out of the plane perpendicular to axis1, is locked.
	const bool finite = caliber::isFinite(anchor) && caliber::isFinite(axis1) && caliber::isFinite(axis2);
	const btScalar length1 = finite ? axis1.length() : btScalar(0);
	const btVector3 zAxis = length1 > SIMD_EPSILON ? axis1 / length1 : btVector3(0, 0, 0);
	const btScalar alongAxis1 = finite ? zAxis.dot(axis2) : btScalar(0);
	const btVector3 across = finite ? axis2 - zAxis * alongAxis1 : btVector3(0, 0, 0);
	const btScalar length2 = across.length();
	const btScalar axis2Length = finite ? axis2.length() : btScalar(0);
	if (!(length1 > SIMD_EPSILON) || !(length2 > SIMD_EPSILON * btMax(btScalar(1), axis2Length)))
	{
		btReportWarning(
		    "Caliber: btHinge2Constraint: zero, non-finite or parallel anchor or axes; the joint is disabled\n", 0);
		setEnabled(false);
	}
	else
	{
		if (btFabs(alongAxis1) > kPerpendicularTolerance * axis2Length)
			btReportWarning(
			    "Caliber: btHinge2Constraint: axis2 is not perpendicular to axis1; its part along axis1 "
			    "is ignored\n",
			    0);
		const btVector3 xAxis = across / length2;
		const btVector3 yAxis = zAxis.cross(xAxis);
		m_axis1 = zAxis;
		m_axis2 = xAxis;
		btTransform frameInWorld;
		frameInWorld.getBasis().setValue(xAxis.x(), yAxis.x(), zAxis.x(), xAxis.y(), yAxis.y(), zAxis.y(), xAxis.z(),
		                                 yAxis.z(), zAxis.z());
		frameInWorld.setOrigin(anchor);
		setFrames(rbA.getCenterOfMassTransform().inverse() * frameInWorld,
		          rbB.getCenterOfMassTransform().inverse() * frameInWorld);
	}

	// Bullet's defaults: suspension travel +-1 along axis1 on a spring, free spin, steering +-pi/4.
	setLinearLowerLimit(btVector3(0, 0, -1));
	setLinearUpperLimit(btVector3(0, 0, 1));
	setAngularLowerLimit(btVector3(1, 0, -SIMD_HALF_PI * btScalar(0.5)));
	setAngularUpperLimit(btVector3(-1, 0, SIMD_HALF_PI * btScalar(0.5)));
	enableSpring(2, true);
	setStiffness(2, SIMD_PI * SIMD_PI * btScalar(4));
	setDamping(2, btScalar(0.01));
	setEquilibriumPoint();
}
