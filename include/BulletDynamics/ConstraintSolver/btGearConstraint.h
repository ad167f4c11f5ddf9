// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GEAR_CONSTRAINT_H
#define BT_GEAR_CONSTRAINT_H

/// btGearConstraint: couples two bodies' turning about one axis each, as meshing gears do. One row:
///     wA . axisA + ratio * wB . axisB = 0
/// with axisA and axisB the given axes carried into the world by each body's rotation (used as given: unit
/// axes make ratio the plain speed ratio |wA| / |wB|).
///
/// Sign convention: Bullet documents only that the joint couples the angular velocities about the given
/// axes with the given ratio; the relation above is the one its row imposes, and Caliber keeps it. So with
/// parallel axes and ratio > 0 the bodies turn in opposite senses, like two external spur gears (ratio =
/// teeth of B / teeth of A); ratio < 0 makes them turn the same way, like a belt or an internal gear.
///
/// Only the speeds are coupled, not the angles (also as in Bullet): nothing pulls the bodies back into
/// phase, so the relative angle may drift by the solver's residual.

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btVector3.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btGearConstraintData btGearConstraintDoubleData
#define btGearConstraintDataName "btGearConstraintDoubleData"
#else
#define btGearConstraintData btGearConstraintFloatData
#define btGearConstraintDataName "btGearConstraintFloatData"
#endif

ATTRIBUTE_ALIGNED16(class)
btGearConstraint : public btTypedConstraint
{
protected:
	btVector3 m_axisInA;
	btVector3 m_axisInB;
	/// Kept for source compatibility (Bullet declares it and never reads it).
	bool m_useFrameA;
	btScalar m_ratio;
	btScalar m_cfm;
	bool m_hasCfm;

	/// Checks the axes and the ratio; reports and disables the joint when one is unusable (assertOnFailure:
	/// the caller has just handed it in, a programming error).
	bool checkInput(bool assertOnFailure);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// axisInA and axisInB are in the bodies' centre-of-mass frames; ratio as in the relation above.
	btGearConstraint(btRigidBody & rbA, btRigidBody & rbB, const btVector3& axisInA, const btVector3& axisInB,
	                 btScalar ratio = 1.f);
	virtual ~btGearConstraint() {}

	void getInfo1(btConstraintInfo1 * info) override;
	void getInfo2(btConstraintInfo2 * info) override;

	/// The axes (bodies' frames) and the ratio; a zero-length or non-finite axis or a non-finite ratio is
	/// reported and disables the joint.
	void setAxisA(const btVector3& axisA);
	void setAxisB(const btVector3& axisB);
	void setRatio(btScalar ratio);
	const btVector3& getAxisA() const { return m_axisInA; }
	const btVector3& getAxisB() const { return m_axisInB; }
	btScalar getRatio() const { return m_ratio; }

	/// BT_CONSTRAINT_CFM (or STOP_CFM), axis -1 or 0: the softness of the coupling. There is no position
	/// error to reduce, so ERP is not a parameter of this joint (asserts, as in Bullet, and is ignored).
	void setParam(int num, btScalar value, int axis = -1) override;
	btScalar getParam(int num, int axis = -1) const override;

public:
	/// Bytes of the joint's data struct (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the joint's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btGearConstraintFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGearConstraintFloatData
{
	btTypedConstraintFloatData m_typeConstraintData;
	btVector3FloatData m_axisInA;
	btVector3FloatData m_axisInB;
	float m_ratio;
	char m_padding[4];
};

/// File layout of btGearConstraintDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGearConstraintDoubleData
{
	btTypedConstraintDoubleData m_typeConstraintData;
	btVector3DoubleData m_axisInA;
	btVector3DoubleData m_axisInB;
	double m_ratio;
};

// clang-format on

#endif  // BT_GEAR_CONSTRAINT_H
