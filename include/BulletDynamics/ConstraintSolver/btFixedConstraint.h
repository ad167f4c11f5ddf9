// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_FIXED_CONSTRAINT_H
#define BT_FIXED_CONSTRAINT_H

/// btFixedConstraint: welds two bodies together. A btGeneric6DofSpring2Constraint with all six
/// coordinates locked, so its six rows are solved together as one exact block.

#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"

ATTRIBUTE_ALIGNED16(class)
btFixedConstraint : public btGeneric6DofSpring2Constraint
{
public:
	/// Keeps frameInA (in A's centre-of-mass frame) and frameInB (in B's) together in the world.
	btFixedConstraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& frameInA, const btTransform& frameInB);

	/// Out of line, as in Bullet.
	virtual ~btFixedConstraint();
};

#endif  // BT_FIXED_CONSTRAINT_H
