// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_UNIVERSAL_CONSTRAINT_H
#define BT_UNIVERSAL_CONSTRAINT_H

/// btUniversalConstraint: a universal (Cardan, Hooke's) joint. The bodies share the anchor point; axis 1
/// is fixed in body A, axis 2 in body B, and the joint keeps them perpendicular, so body B turns freely
/// about axis 1 and axis 2 but not about the third direction: twist is transmitted, as by a cardan
/// shaft. Built on btGeneric6DofConstraint with frame Z = axis 1, Y = axis 2, X = Y x Z: the Euler angle
/// z is the turn about axis 1 (getAngle1, range (-pi, pi)), y the turn about axis 2 (getAngle2, range
/// (-pi/2, pi/2)), and x, the twist, is locked.

#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"

ATTRIBUTE_ALIGNED16(class)
btUniversalConstraint : public btGeneric6DofConstraint
{
protected:
	/// The anchor and the two axes (unit) in the world, as given at construction or by setAxis.
	btVector3 m_anchor;
	btVector3 m_axis1;
	btVector3 m_axis2;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// anchor, axis1 (fixed in A) and axis2 (fixed in B) in world space; the axes must be perpendicular
	/// (axis 2 is made so, with a warning, when it is not) and not zero or parallel (reported; the joint
	/// is then disabled).
	btUniversalConstraint(btRigidBody & rbA, btRigidBody & rbB, const btVector3& anchor, const btVector3& axis1,
	                      const btVector3& axis2);

	/// The anchor as carried by body A, as last calculated.
	const btVector3& getAnchor() { return m_calculatedTransformA.getOrigin(); }
	/// The anchor as carried by body B, as last calculated.
	const btVector3& getAnchor2() { return m_calculatedTransformB.getOrigin(); }
	/// The axes given at construction (unit length).
	const btVector3& getAxis1() { return m_axis1; }
	const btVector3& getAxis2() { return m_axis2; }
	/// The turn about axis 1, as last calculated.
	btScalar getAngle1() { return getAngle(2); }
	/// The turn about axis 2, as last calculated.
	btScalar getAngle2() { return getAngle(1); }
	/// Upper limits of the turns about axis 1 and axis 2 (radians). Caliber applies ang1max to angle 1 as
	/// the names say; Bullet 2.89 applied its first argument to angle 2.
	void setUpperLimit(btScalar ang1max, btScalar ang2max);
	/// Lower limits of the turns about axis 1 and axis 2 (radians); as setUpperLimit.
	void setLowerLimit(btScalar ang1min, btScalar ang2min);

	/// New world axes (axis1 in A, axis2 in B) at the current anchor.
	void setAxis(const btVector3& axis1, const btVector3& axis2) override;
};

#endif  // BT_UNIVERSAL_CONSTRAINT_H
