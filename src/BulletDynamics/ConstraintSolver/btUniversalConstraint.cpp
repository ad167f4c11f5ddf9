// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btUniversalConstraint.h"

#include "LinearMath/btWarningHook.h"

namespace
{
// How far the turns may go: just short of the ends of the Euler angles' ranges, where y = +-pi/2 is
// singular and z = +-pi wraps.
const btScalar kRangeMargin = btScalar(0.01);
// |cos| between the unit axes above which they are reported as not perpendicular (0.06 degrees).
const btScalar kPerpendicularTolerance = btScalar(1e-3);

// Places both joint frames at the world point anchor, z along axis1 and y along axis2 (made unit, and
// perpendicular to axis1 with a warning when it is not), and stores anchor and the unit axes in the
// joint's members given; when the axes cannot make a frame, reports it and disables the joint instead.
void placeFrames(btUniversalConstraint& joint, btVector3& anchorOut, btVector3& axis1Out, btVector3& axis2Out,
                 const btVector3& anchor, const btVector3& axis1, const btVector3& axis2)
{
	const btScalar length1 = axis1.length(), length2 = axis2.length();
	const bool usable = caliber::isFinite(axis1) && caliber::isFinite(axis2) && length1 > SIMD_EPSILON &&
	                    length2 > SIMD_EPSILON &&
	                    (axis1 / length1).cross(axis2 / length2).length() > kPerpendicularTolerance;
	btAssert(usable && "btUniversalConstraint: the axes must be finite, non-zero and not parallel");
	if (!usable)
	{
		btReportWarning("Caliber: btUniversalConstraint: zero, parallel or non-finite axes; the joint is disabled\n",
		                0);
		joint.setEnabled(false);
		return;
	}
	const btVector3 zAxis = axis1 / length1;
	btVector3 yAxis = axis2 / length2;
	if (btFabs(zAxis.dot(yAxis)) > kPerpendicularTolerance)
	{
		btReportWarning(
		    "Caliber: btUniversalConstraint: the axes are not perpendicular; axis 2 is made perpendicular to axis 1\n",
		    0);
		yAxis = (yAxis - zAxis * zAxis.dot(yAxis)).normalized();
	}
	const btVector3 xAxis = yAxis.cross(zAxis);
	const btTransform frameInWorld(
	    btMatrix3x3(xAxis.x(), yAxis.x(), zAxis.x(), xAxis.y(), yAxis.y(), zAxis.y(), xAxis.z(), yAxis.z(), zAxis.z()),
	    anchor);
	anchorOut = anchor;
	axis1Out = zAxis;
	axis2Out = yAxis;
	joint.setFrames(joint.getRigidBodyA().getCenterOfMassTransform().inverse() * frameInWorld,
	                joint.getRigidBodyB().getCenterOfMassTransform().inverse() * frameInWorld);
}
}  // namespace

btUniversalConstraint::btUniversalConstraint(btRigidBody& rbA, btRigidBody& rbB, const btVector3& anchor,
                                             const btVector3& axis1, const btVector3& axis2)
    : btGeneric6DofConstraint(rbA, rbB, btTransform::getIdentity(), btTransform::getIdentity(), true),
      m_anchor(anchor),
      m_axis1(axis1),
      m_axis2(axis2)
{
	setLinearLowerLimit(btVector3(0, 0, 0));
	setLinearUpperLimit(btVector3(0, 0, 0));
	setAngularLowerLimit(btVector3(0, -SIMD_HALF_PI + kRangeMargin, -SIMD_PI + kRangeMargin));
	setAngularUpperLimit(btVector3(0, SIMD_HALF_PI - kRangeMargin, SIMD_PI - kRangeMargin));
	placeFrames(*this, m_anchor, m_axis1, m_axis2, anchor, axis1, axis2);
}

void btUniversalConstraint::setUpperLimit(btScalar ang1max, btScalar ang2max)
{
	setAngularUpperLimit(btVector3(0, ang2max, ang1max));
}

void btUniversalConstraint::setLowerLimit(btScalar ang1min, btScalar ang2min)
{
	setAngularLowerLimit(btVector3(0, ang2min, ang1min));
}

void btUniversalConstraint::setAxis(const btVector3& axis1, const btVector3& axis2)
{
	calculateTransforms();
	placeFrames(*this, m_anchor, m_axis1, m_axis2, m_calculatedTransformA.getOrigin(), axis1, axis2);
}
