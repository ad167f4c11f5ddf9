// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_HINGE_CONSTRAINT_H
#define BT_HINGE_CONSTRAINT_H

/// btHingeConstraint: a revolute joint (doors, wheels, knees). The Z axes of the two joint frames are
/// kept aligned and their origins together; the rotation about the axis is free, optionally limited
/// and driven by a motor. Guide: docs/constraints.md.

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btHingeConstraintData btHingeConstraintDoubleData2
#define btHingeConstraintDataName "btHingeConstraintDoubleData2"
#else
#define btHingeConstraintData btHingeConstraintFloatData
#define btHingeConstraintDataName "btHingeConstraintFloatData"
#endif

enum btHingeFlags
{
	BT_HINGE_FLAGS_CFM_STOP = 1,
	BT_HINGE_FLAGS_ERP_STOP = 2,
	BT_HINGE_FLAGS_CFM_NORM = 4,
	BT_HINGE_FLAGS_ERP_NORM = 8
};

ATTRIBUTE_ALIGNED16(class)
btHingeConstraint : public btTypedConstraint
{
protected:
	/// Joint frames in the bodies' centre-of-mass frames; the hinge axis is their Z axis.
	btTransform m_rbAFrame;
	btTransform m_rbBFrame;

	btScalar m_motorTargetVelocity = 0;
	btScalar m_maxMotorImpulse = 0;
	btAngularLimit m_limit;
	/// Hinge angle measured when the rows were last built.
	btScalar m_hingeAngle = 0;
	/// +1 measures the angle of A relative to B (Bullet's default), -1 of B relative to A.
	btScalar m_referenceSign;

private:
	/// Whether this step has a limit row (past the limit, or close enough to reach it soon): decided in
	/// getInfo1, read by getInfo2 (Bullet's hinge keeps the same decision in its limit).
	bool m_limitRowNeeded = false;
	/// The time step of the joint's last rows, for judging in getInfo1 whether a limit can be reached soon.
	btScalar m_lastTimeStep = btScalar(1) / btScalar(60);

protected:
	bool m_angularOnly = false;
	bool m_enableAngularMotor = false;
	bool m_useReferenceFrameA;
	bool m_useOffsetForConstraintFrame = false;
	int m_flags = 0;
	btScalar m_normalCFM = 0;
	btScalar m_normalERP = 0;
	btScalar m_stopCFM = 0;
	btScalar m_stopERP = 0;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Pivots and axes in each body's centre-of-mass frame.
	btHingeConstraint(btRigidBody & rbA, btRigidBody & rbB, const btVector3& pivotInA, const btVector3& pivotInB,
	                  const btVector3& axisInA, const btVector3& axisInB, bool useReferenceFrameA = false);
	/// Body A hinged to the world at its pivot and axis.
	btHingeConstraint(btRigidBody & rbA, const btVector3& pivotInA, const btVector3& axisInA,
	                  bool useReferenceFrameA = false);
	/// Joint frames in each body's centre-of-mass frame; the hinge axis is their Z axis.
	btHingeConstraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& rbAFrame, const btTransform& rbBFrame,
	                  bool useReferenceFrameA = false);
	btHingeConstraint(btRigidBody & rbA, const btTransform& rbAFrame, bool useReferenceFrameA = false);

	void getInfo1(btConstraintInfo1 * info) override;
	void getInfo1NonVirtual(btConstraintInfo1 * info);
	void getInfo2(btConstraintInfo2 * info) override;
	void getInfo2NonVirtual(btConstraintInfo2 * info, const btTransform& transA, const btTransform& transB,
	                        const btVector3& angVelA, const btVector3& angVelB);
	void getInfo2Internal(btConstraintInfo2 * info, const btTransform& transA, const btTransform& transB,
	                      const btVector3& angVelA, const btVector3& angVelB);
	void getInfo2InternalUsingFrameOffset(btConstraintInfo2 * info, const btTransform& transA,
	                                      const btTransform& transB, const btVector3& angVelA,
	                                      const btVector3& angVelB);

	/// Nothing to update: the rows are rebuilt every step.
	void updateRHS(btScalar timeStep) { (void)timeStep; }

	const btRigidBody& getRigidBodyA() const { return m_rbA; }
	const btRigidBody& getRigidBodyB() const { return m_rbB; }
	btRigidBody& getRigidBodyA() { return m_rbA; }
	btRigidBody& getRigidBodyB() { return m_rbB; }

	btTransform& getFrameOffsetA() { return m_rbAFrame; }
	btTransform& getFrameOffsetB() { return m_rbBFrame; }
	void setFrames(const btTransform& frameA, const btTransform& frameB);

	/// Only the two angular rows: the pivots are not held together.
	void setAngularOnly(bool angularOnly) { m_angularOnly = angularOnly; }
	bool getAngularOnly() const { return m_angularOnly; }

	/// A motor driving the hinge angle's rate to targetVelocity (rad/s) with at most maxMotorImpulse per step.
	void enableAngularMotor(bool enableMotor, btScalar targetVelocity, btScalar maxMotorImpulse);
	void enableMotor(bool enableMotor) { m_enableAngularMotor = enableMotor; }
	void setMaxMotorImpulse(btScalar maxMotorImpulse) { m_maxMotorImpulse = maxMotorImpulse; }
	void setMotorTargetVelocity(btScalar motorTargetVelocity) { m_motorTargetVelocity = motorTargetVelocity; }
	/// Sets the motor velocity that reaches the relative orientation qAinB (A's frame in B's) in dt.
	void setMotorTarget(const btQuaternion& qAinB, btScalar dt);
	/// Sets the motor velocity that reaches targetAngle (clamped to the limits) in dt.
	void setMotorTarget(btScalar targetAngle, btScalar dt);

	/// Limits the hinge angle to [low, high] (radians; low > high: no limit). biasFactor is the share of
	/// an overshoot corrected per step, relaxationFactor (0..1) the share of a velocity into the limit
	/// that the limit removes (1: stops it dead). softness is stored for compatibility (Caliber's limits
	/// are hard).
	void setLimit(btScalar low, btScalar high, btScalar _softness = 0.9f, btScalar _biasFactor = 0.3f,
	              btScalar _relaxationFactor = 1.0f)
	{
		m_limit.set(low, high, _softness, _biasFactor, _relaxationFactor);
	}
	btScalar getLimitSoftness() const { return m_limit.getSoftness(); }
	btScalar getLimitBiasFactor() const { return m_limit.getBiasFactor(); }
	btScalar getLimitRelaxationFactor() const { return m_limit.getRelaxationFactor(); }

	/// Re-aims the hinge: axisInA in A's frame, keeping the pivot; B's frame follows from the current poses.
	void setAxis(btVector3 & axisInA);

	bool hasLimit() const { return m_limit.getHalfRange() > 0; }
	btScalar getLowerLimit() const { return m_limit.getLow(); }
	btScalar getUpperLimit() const { return m_limit.getHigh(); }

	/// The hinge angle now: the rotation about the axis that takes B's frame to A's (sign flipped with
	/// useReferenceFrameA), in (-pi, pi].
	btScalar getHingeAngle();
	btScalar getHingeAngle(const btTransform& transA, const btTransform& transB);

	/// Measures the angle against the limit (getSolveLimit, getLimitSign).
	void testLimit(const btTransform& transA, const btTransform& transB);

	const btTransform& getAFrame() const { return m_rbAFrame; }
	const btTransform& getBFrame() const { return m_rbBFrame; }
	btTransform& getAFrame() { return m_rbAFrame; }
	btTransform& getBFrame() { return m_rbBFrame; }

	int getSolveLimit() { return m_limit.isLimit() ? 1 : 0; }
	btScalar getLimitSign() { return m_limit.getSign(); }
	bool getEnableAngularMotor() { return m_enableAngularMotor; }
	btScalar getMotorTargetVelocity() { return m_motorTargetVelocity; }
	btScalar getMaxMotorImpulse() { return m_maxMotorImpulse; }

	/// Kept for source compatibility: Caliber's rows always use both frames in full.
	bool getUseFrameOffset() { return m_useOffsetForConstraintFrame; }
	void setUseFrameOffset(bool frameOffsetOnOff) { m_useOffsetForConstraintFrame = frameOffsetOnOff; }
	bool getUseReferenceFrameA() const { return m_useReferenceFrameA; }
	void setUseReferenceFrameA(bool useReferenceFrameA)
	{
		m_useReferenceFrameA = useReferenceFrameA;
		m_referenceSign = useReferenceFrameA ? btScalar(-1) : btScalar(1);
	}

	/// ERP/CFM of the joint rows (axis -1 or 0..5) or of the limit (STOP_ERP/STOP_CFM, axis -1 or 5).
	void setParam(int num, btScalar value, int axis = -1) override;
	btScalar getParam(int num, int axis = -1) const override;
	int getFlags() const { return m_flags; }

public:
	/// Bytes of the joint's data struct (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the joint's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

/// A hinge whose angle keeps counting past +-pi (getAccumulatedHingeAngle), for motors and limits that
/// span more than one turn.
ATTRIBUTE_ALIGNED16(class)
btHingeAccumulatedAngleConstraint : public btHingeConstraint
{
protected:
	btScalar m_accumulatedAngle;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	btHingeAccumulatedAngleConstraint(btRigidBody & rbA, btRigidBody & rbB, const btVector3& pivotInA,
	                                  const btVector3& pivotInB, const btVector3& axisInA, const btVector3& axisInB,
	                                  bool useReferenceFrameA = false)
	    : btHingeConstraint(rbA, rbB, pivotInA, pivotInB, axisInA, axisInB, useReferenceFrameA)
	{
		m_accumulatedAngle = getHingeAngle();
	}
	btHingeAccumulatedAngleConstraint(btRigidBody & rbA, const btVector3& pivotInA, const btVector3& axisInA,
	                                  bool useReferenceFrameA = false)
	    : btHingeConstraint(rbA, pivotInA, axisInA, useReferenceFrameA)
	{
		m_accumulatedAngle = getHingeAngle();
	}
	btHingeAccumulatedAngleConstraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& rbAFrame,
	                                  const btTransform& rbBFrame, bool useReferenceFrameA = false)
	    : btHingeConstraint(rbA, rbB, rbAFrame, rbBFrame, useReferenceFrameA)
	{
		m_accumulatedAngle = getHingeAngle();
	}
	btHingeAccumulatedAngleConstraint(btRigidBody & rbA, const btTransform& rbAFrame, bool useReferenceFrameA = false)
	    : btHingeConstraint(rbA, rbAFrame, useReferenceFrameA)
	{
		m_accumulatedAngle = getHingeAngle();
	}

	/// The hinge angle counted continuously since construction (or the last setAccumulatedHingeAngle).
	btScalar getAccumulatedHingeAngle();
	void setAccumulatedHingeAngle(btScalar accAngle);
	/// Updates the accumulated angle once per step, then as btHingeConstraint.
	void getInfo1(btConstraintInfo1 * info) override;
};

// clang-format off
/// File layout of btHingeConstraintDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btHingeConstraintDoubleData
{
	btTypedConstraintData m_typeConstraintData;
	btTransformDoubleData m_rbAFrame;
	btTransformDoubleData m_rbBFrame;
	int m_useReferenceFrameA;
	int m_angularOnly;
	int m_enableAngularMotor;
	float m_motorTargetVelocity;
	float m_maxMotorImpulse;
	float m_lowerLimit;
	float m_upperLimit;
	float m_limitSoftness;
	float m_biasFactor;
	float m_relaxationFactor;
};

/// File layout of btHingeConstraintFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btHingeConstraintFloatData
{
	btTypedConstraintData m_typeConstraintData;
	btTransformFloatData m_rbAFrame;
	btTransformFloatData m_rbBFrame;
	int m_useReferenceFrameA;
	int m_angularOnly;
	int m_enableAngularMotor;
	float m_motorTargetVelocity;
	float m_maxMotorImpulse;
	float m_lowerLimit;
	float m_upperLimit;
	float m_limitSoftness;
	float m_biasFactor;
	float m_relaxationFactor;
};

/// File layout of btHingeConstraintDoubleData2 in .bullet files (Bullet's struct and field names; tools/makedna reads it).
/// m_padding1 sits before the doubles, not after them as in Bullet's declaration, where the compiler
/// adds hidden padding that the DNA does not describe; readers match fields by name, so files agree.
struct btHingeConstraintDoubleData2
{
	btTypedConstraintDoubleData m_typeConstraintData;
	btTransformDoubleData m_rbAFrame;
	btTransformDoubleData m_rbBFrame;
	int m_useReferenceFrameA;
	int m_angularOnly;
	int m_enableAngularMotor;
	char m_padding1[4];
	double m_motorTargetVelocity;
	double m_maxMotorImpulse;
	double m_lowerLimit;
	double m_upperLimit;
	double m_limitSoftness;
	double m_biasFactor;
	double m_relaxationFactor;
};

// clang-format on

#endif  // BT_HINGE_CONSTRAINT_H
