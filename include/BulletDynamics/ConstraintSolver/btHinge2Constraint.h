// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_HINGE2_CONSTRAINT_H
#define BT_HINGE2_CONSTRAINT_H

/// btHinge2Constraint: a wheel suspension in the manner of ODE's hinge-2 joint. Body A (the chassis)
/// carries axis1, the suspension and steering axis; body B (the wheel) turns freely about axis2, its
/// axle, which stays perpendicular to axis1. B slides along axis1 on a spring (travel limited to
/// [-1, 1] by default) and steers about axis1 within limits (+-pi/4 by default); everything else is
/// locked. Built on btGeneric6DofSpring2Constraint with frame z along axis1 and x along axis2, so the
/// suspension is linear coordinate 2, the steering angle is angle 2 and the wheel's spin angle 0.

#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "LinearMath/btVector3.h"

ATTRIBUTE_ALIGNED16(class)
btHinge2Constraint : public btGeneric6DofSpring2Constraint
{
protected:
	btVector3 m_anchor;
	btVector3 m_axis1;
	btVector3 m_axis2;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// anchor, axis1 and axis2 are in world coordinates; axis2 must be perpendicular to axis1 (its part
	/// along axis1 is removed, with a warning when that part is not negligible).
	btHinge2Constraint(btRigidBody & rbA, btRigidBody & rbB, const btVector3& anchor, const btVector3& axis1,
	                   const btVector3& axis2);

	/// The joint point on the chassis, in the world (after calculateTransforms, i.e. after a step).
	const btVector3& getAnchor() const { return m_calculatedTransformA.getOrigin(); }
	/// The joint point on the wheel, in the world (after calculateTransforms).
	const btVector3& getAnchor2() const { return m_calculatedTransformB.getOrigin(); }
	/// The suspension and steering axis given at construction (unit length).
	const btVector3& getAxis1() const { return m_axis1; }
	/// The axle given at construction (unit length, perpendicular to axis1).
	const btVector3& getAxis2() const { return m_axis2; }
	/// Steering angle (about axis1), radians.
	btScalar getAngle1() const { return getAngle(2); }
	/// Spin angle of the wheel (about axis2), radians.
	btScalar getAngle2() const { return getAngle(0); }
	/// Upper steering limit; also frees the spin and locks the third rotation, as in Bullet.
	void setUpperLimit(btScalar ang1max) { setAngularUpperLimit(btVector3(-1, 0, ang1max)); }
	/// Lower steering limit; also frees the spin and locks the third rotation, as in Bullet.
	void setLowerLimit(btScalar ang1min) { setAngularLowerLimit(btVector3(1, 0, ang1min)); }
};

#endif  // BT_HINGE2_CONSTRAINT_H
