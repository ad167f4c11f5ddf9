// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btFixedConstraint.h"

btFixedConstraint::btFixedConstraint(btRigidBody& rbA, btRigidBody& rbB, const btTransform& frameInA,
                                     const btTransform& frameInB)
    : btGeneric6DofSpring2Constraint(rbA, rbB, frameInA, frameInB)
{
	const btVector3 zero(0, 0, 0);
	setLinearLowerLimit(zero);
	setLinearUpperLimit(zero);
	setAngularLowerLimit(zero);
	setAngularUpperLimit(zero);
}

btFixedConstraint::~btFixedConstraint() {}
