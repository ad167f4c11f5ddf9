// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GENERIC_6DOF_SPRING_CONSTRAINT_H
#define BT_GENERIC_6DOF_SPRING_CONSTRAINT_H

/// btGeneric6DofSpringConstraint: a btGeneric6DofConstraint with a spring and damper on any of its six
/// coordinates (index 0..2 linear, 3..5 the Euler angles x, y, z). A spring on coordinate q applies the
/// generalised force -stiffness (q - equilibrium) - damping q'. It acts on free and limited coordinates
/// (a locked coordinate has nothing to spring), alongside any limit or motor.
/// Units: stiffness N/m or N m/rad, damping N s/m or N m s/rad. Caliber's damping is this physical
/// coefficient, default 0 (undamped); Bullet's was a dimensionless factor whose default 1 meant undamped.

#include "BulletDynamics/ConstraintSolver/btGeneric6DofConstraint.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btGeneric6DofSpringConstraintData2 btGeneric6DofSpringConstraintDoubleData2
#define btGeneric6DofSpringConstraintDataName "btGeneric6DofSpringConstraintDoubleData2"
#else
#define btGeneric6DofSpringConstraintData2 btGeneric6DofSpringConstraintData
#define btGeneric6DofSpringConstraintDataName "btGeneric6DofSpringConstraintData"
#endif

ATTRIBUTE_ALIGNED16(class)
btGeneric6DofSpringConstraint : public btGeneric6DofConstraint
{
protected:
	bool m_springEnabled[6];
	btScalar m_equilibriumPoint[6];
	btScalar m_springStiffness[6];
	btScalar m_springDamping[6];

	/// Sets the defaults: springs off, equilibrium 0, no stiffness or damping.
	void init();
	/// Bullet's way of driving the springs through the 6-DoF joint's motors, for subclasses that write
	/// their rows with btGeneric6DofConstraint::getInfo2: each spring coordinate's motor is enabled, its
	/// target is the rate the spring's impulse of this step gives, and its force bound is that impulse
	/// per step, so the motor row applies the spring row's impulse (exactly where the coordinate does not
	/// lean on the locked ones: the target uses the coordinate's own effective mass). This joint's getInfo2
	/// writes spring rows instead and does not call it. A null info or one without a step (fps <= 0)
	/// asserts and changes nothing.
	void internalUpdateSprings(btConstraintInfo2 * info);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// As btGeneric6DofConstraint's constructors.
	btGeneric6DofSpringConstraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& frameInA,
	                              const btTransform& frameInB, bool useLinearReferenceFrameA);
	btGeneric6DofSpringConstraint(btRigidBody & rbB, const btTransform& frameInB, bool useLinearReferenceFrameB);

	/// Turns the spring of coordinate index (0..5) on or off.
	void enableSpring(int index, bool onOff);
	/// Spring stiffness of coordinate index (N/m or N m/rad, >= 0).
	void setStiffness(int index, btScalar stiffness);
	/// Damping coefficient of coordinate index (N s/m or N m s/rad, >= 0).
	void setDamping(int index, btScalar damping);
	/// Makes the current value of every coordinate its spring's rest position.
	void setEquilibriumPoint();
	/// Makes the current value of coordinate index its spring's rest position.
	void setEquilibriumPoint(int index);
	/// Sets the rest position of coordinate index's spring (radians for angles).
	void setEquilibriumPoint(int index, btScalar val);

	/// The spring settings of coordinate index (0..5); an index out of range is reported and reads false / 0.
	bool isSpringEnabled(int index) const;
	btScalar getStiffness(int index) const;
	btScalar getDamping(int index) const;
	btScalar getEquilibriumPoint(int index) const;

	/// As btGeneric6DofConstraint::setAxis; the springs keep their rest positions.
	void setAxis(const btVector3& axis1, const btVector3& axis2) override;

	void getInfo1(btConstraintInfo1 * info) override;
	void getInfo2(btConstraintInfo2 * info) override;

public:
	/// Bytes of the joint's data struct (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the joint's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btGeneric6DofSpringConstraintData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGeneric6DofSpringConstraintData
{
	btGeneric6DofConstraintData m_6dofData;
	int m_springEnabled[6];
	float m_equilibriumPoint[6];
	float m_springStiffness[6];
	float m_springDamping[6];
};

/// File layout of btGeneric6DofSpringConstraintDoubleData2 in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGeneric6DofSpringConstraintDoubleData2
{
	btGeneric6DofConstraintDoubleData2 m_6dofData;
	int m_springEnabled[6];
	double m_equilibriumPoint[6];
	double m_springStiffness[6];
	double m_springDamping[6];
};

// clang-format on

#endif  // BT_GENERIC_6DOF_SPRING_CONSTRAINT_H
