// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_POINT2POINT_CONSTRAINT_H
#define BT_POINT2POINT_CONSTRAINT_H

/// btPoint2PointConstraint: a ball-and-socket joint. A pivot fixed in body A and one fixed in body B
/// are kept at the same point in the world; rotation is free. Three rows, one per world axis.

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btVector3.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btPoint2PointConstraintData2 btPoint2PointConstraintDoubleData2
#define btPoint2PointConstraintDataName "btPoint2PointConstraintDoubleData2"
#else
#define btPoint2PointConstraintData2 btPoint2PointConstraintFloatData
#define btPoint2PointConstraintDataName "btPoint2PointConstraintFloatData"
#endif

/// Per-joint settings of a point-to-point joint. m_impulseClamp > 0 bounds each row's impulse per step
/// (a "rubber" joint that gives way under load). m_tau and m_damping are kept for source compatibility:
/// as in Bullet's row solver, the error reduction comes from ERP (setParam or the world's erp).
struct btConstraintSetting
{
	btConstraintSetting() : m_tau(btScalar(0.3)), m_damping(btScalar(1.)), m_impulseClamp(btScalar(0.)) {}
	btScalar m_tau;
	btScalar m_damping;
	btScalar m_impulseClamp;
};

enum btPoint2PointFlags
{
	BT_P2P_FLAGS_ERP = 1,
	BT_P2P_FLAGS_CFM = 2
};

ATTRIBUTE_ALIGNED16(class)
btPoint2PointConstraint : public btTypedConstraint
{
	btVector3 m_pivotInA;
	btVector3 m_pivotInB;
	int m_flags;
	btScalar m_erp;
	btScalar m_cfm;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Kept for source compatibility; Caliber always solves the joint as rows.
	bool m_useSolveConstraintObsolete;
	btConstraintSetting m_setting;

	/// pivotInA and pivotInB are in the bodies' centre-of-mass frames.
	btPoint2PointConstraint(btRigidBody & rbA, btRigidBody & rbB, const btVector3& pivotInA, const btVector3& pivotInB);
	/// Body A hangs from the world at its pivot's current world position.
	btPoint2PointConstraint(btRigidBody & rbA, const btVector3& pivotInA);

	void buildJacobian() override {}
	void getInfo1(btConstraintInfo1 * info) override;
	void getInfo1NonVirtual(btConstraintInfo1 * info);
	void getInfo2(btConstraintInfo2 * info) override;
	void getInfo2NonVirtual(btConstraintInfo2 * info, const btTransform& body0_trans, const btTransform& body1_trans);

	/// Nothing to update: the rows are rebuilt every step.
	void updateRHS(btScalar timeStep) { (void)timeStep; }

	void setPivotA(const btVector3& pivotA) { m_pivotInA = pivotA; }
	void setPivotB(const btVector3& pivotB) { m_pivotInB = pivotB; }
	const btVector3& getPivotInA() const { return m_pivotInA; }
	const btVector3& getPivotInB() const { return m_pivotInB; }

	/// BT_CONSTRAINT_ERP / BT_CONSTRAINT_CFM (also accepted as STOP_ERP / STOP_CFM) for axis -1 or 0..2.
	void setParam(int num, btScalar value, int axis = -1) override;
	btScalar getParam(int num, int axis = -1) const override;
	int getFlags() const { return m_flags; }

public:
	/// Bytes of the joint's data struct (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the joint's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btPoint2PointConstraintFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btPoint2PointConstraintFloatData
{
	btTypedConstraintData m_typeConstraintData;
	btVector3FloatData m_pivotInA;
	btVector3FloatData m_pivotInB;
};

/// File layout of btPoint2PointConstraintDoubleData2 in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btPoint2PointConstraintDoubleData2
{
	btTypedConstraintDoubleData m_typeConstraintData;
	btVector3DoubleData m_pivotInA;
	btVector3DoubleData m_pivotInB;
};

/// Older double layout of the point-to-point joint (read, not written).
struct btPoint2PointConstraintDoubleData
{
	btTypedConstraintData m_typeConstraintData;
	btVector3DoubleData m_pivotInA;
	btVector3DoubleData m_pivotInB;
};

// clang-format on

#endif  // BT_POINT2POINT_CONSTRAINT_H
