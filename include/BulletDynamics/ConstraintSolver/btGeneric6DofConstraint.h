// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GENERIC_6DOF_CONSTRAINT_H
#define BT_GENERIC_6DOF_CONSTRAINT_H

/// btGeneric6DofConstraint: a joint that locks, limits, frees or drives each of the six coordinates of
/// frame B (fixed in body B) relative to frame A (fixed in body A).
///  - Linear coordinates 0..2: the position of B's frame origin relative to A's, along the axes of the
///    linear reference frame (frame A's by default, frame B's with useLinearReferenceFrameA false).
///  - Angular coordinates 3..5: the Euler angles (x, y, z) of frame B relative to frame A, with
///    A^-1 B = Rz(z) Ry(y) Rx(x) (rotations about A's fixed X, then Y, then Z axes; the same matrix as
///    btMatrix3x3::setEulerZYX(x, y, z)). x and z lie in (-pi, pi], y in [-pi/2, pi/2]; the joint is
///    singular at y = +-pi/2, so keep y's range inside (-pi/2, pi/2).
/// Per coordinate: lower == upper locks it there, lower > upper frees it, lower < upper limits it to
/// [lower, upper]. Defaults (as in Bullet): linear coordinates locked at 0, angular coordinates free.
/// Rows: locked coordinates first (solved together as one block), then limits, then motors.

#include "BulletDynamics/ConstraintSolver/btJacobianEntry.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btGeneric6DofConstraintData2 btGeneric6DofConstraintDoubleData2
#define btGeneric6DofConstraintDataName "btGeneric6DofConstraintDoubleData2"
#else
#define btGeneric6DofConstraintData2 btGeneric6DofConstraintData
#define btGeneric6DofConstraintDataName "btGeneric6DofConstraintData"
#endif

class btRigidBody;

/// The limit and motor of one angular coordinate of a btGeneric6DofConstraint.
class btRotationalLimitMotor
{
public:
	/// Lower and upper angle (radians); equal locks, lower > upper frees the angle.
	btScalar m_loLimit;
	btScalar m_hiLimit;
	/// The rate of the angle (rad/s) the motor drives towards.
	btScalar m_targetVelocity;
	/// The largest torque (N m, along the coordinate) the motor applies.
	btScalar m_maxMotorForce;
	/// Kept for source compatibility: Bullet's obsolete iterative path used it; the row solver does not.
	btScalar m_maxLimitForce;
	/// Kept for source compatibility (obsolete iterative path).
	btScalar m_damping;
	/// Kept for source compatibility (obsolete iterative path).
	btScalar m_limitSoftness;
	/// Softness of the motor row, used when set through setParam(BT_CONSTRAINT_CFM).
	btScalar m_normalCFM;
	/// Error reduction of the lock and limit rows, used when set through setParam(BT_CONSTRAINT_STOP_ERP).
	btScalar m_stopERP;
	/// Softness of the lock and limit rows, used when set through setParam(BT_CONSTRAINT_STOP_CFM).
	btScalar m_stopCFM;
	/// Restitution at the limits: the fraction of the approach rate that is reversed.
	btScalar m_bounce;
	/// Whether the motor drives the angle.
	bool m_enableMotor;

	/// How far the angle is past the limit it crossed (signed; 0 inside), set by testLimitValue.
	btScalar m_currentLimitError;
	/// The angle last given to testLimitValue.
	btScalar m_currentPosition;
	/// 0: inside the limits or free, 1: below the lower limit, 2: above the upper limit.
	int m_currentLimit;
	/// Kept for source compatibility (obsolete iterative path).
	btScalar m_accumulatedImpulse;

	btRotationalLimitMotor();

	/// True when the angle is locked or limited (lower <= upper).
	bool isLimited() const { return m_loLimit <= m_hiLimit; }
	/// True when the motor is on or the angle is past a limit.
	bool needApplyTorques() const { return m_currentLimit != 0 || m_enableMotor; }
	/// Measures test_value (radians) against the limits, whole turns allowed: sets m_currentPosition,
	/// m_currentLimit and m_currentLimitError; returns m_currentLimit.
	int testLimitValue(btScalar test_value);
};

/// The limits and motors of the three linear coordinates of a btGeneric6DofConstraint.
ATTRIBUTE_ALIGNED16(class)
btTranslationalLimitMotor
{
public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Lower and upper position per axis; equal locks, lower > upper frees the axis.
	btVector3 m_lowerLimit;
	btVector3 m_upperLimit;
	/// Kept for source compatibility (obsolete iterative path).
	btVector3 m_accumulatedImpulse;
	/// Kept for source compatibility (obsolete iterative path).
	btScalar m_limitSoftness;
	/// Kept for source compatibility (obsolete iterative path).
	btScalar m_damping;
	/// Kept for source compatibility: linear limits do not bounce (as in Bullet's row path).
	btScalar m_restitution;
	/// Softness of the motor rows, used when set through setParam(BT_CONSTRAINT_CFM).
	btVector3 m_normalCFM;
	/// Error reduction of the lock and limit rows, used when set through setParam(BT_CONSTRAINT_STOP_ERP).
	btVector3 m_stopERP;
	/// Softness of the lock and limit rows, used when set through setParam(BT_CONSTRAINT_STOP_CFM).
	btVector3 m_stopCFM;
	/// Whether each axis's motor is on.
	bool m_enableMotor[3];
	/// The rate of each coordinate (m/s) the motors drive towards.
	btVector3 m_targetVelocity;
	/// The largest force (N, along the coordinate) each motor applies.
	btVector3 m_maxMotorForce;
	/// How far each coordinate is past the limit it crossed (signed; 0 inside), set by testLimitValue.
	btVector3 m_currentLimitError;
	/// The coordinates last measured (see btGeneric6DofConstraint::getRelativePivotPosition).
	btVector3 m_currentLinearDiff;
	/// Per axis: 0 inside the limits or free, 1 below the lower limit, 2 above the upper limit.
	int m_currentLimit[3];

	btTranslationalLimitMotor();

	/// True when the axis is locked or limited (lower <= upper).
	bool isLimited(int limitIndex) const { return m_upperLimit[limitIndex] >= m_lowerLimit[limitIndex]; }
	/// True when the axis's motor is on or the coordinate is past a limit.
	bool needApplyForce(int limitIndex) const { return m_currentLimit[limitIndex] != 0 || m_enableMotor[limitIndex]; }
	/// Measures test_value against axis limitIndex's limits: sets m_currentLimit and m_currentLimitError of
	/// that axis; returns its m_currentLimit.
	int testLimitValue(int limitIndex, btScalar test_value);
};

/// Which per-axis parameters were set through setParam; each axis has BT_6DOF_FLAGS_AXIS_SHIFT bits.
enum bt6DofFlags
{
	BT_6DOF_FLAGS_CFM_NORM = 1,
	BT_6DOF_FLAGS_CFM_STOP = 2,
	BT_6DOF_FLAGS_ERP_STOP = 4
};
#define BT_6DOF_FLAGS_AXIS_SHIFT 3  // bits per axis

ATTRIBUTE_ALIGNED16(class)
btGeneric6DofConstraint : public btTypedConstraint
{
protected:
	/// The joint frames in each body's centre-of-mass frame.
	btTransform m_frameInA;
	btTransform m_frameInB;
	/// Bullet's per-axis Jacobians of the old iterative path, filled by buildLinearJacobian and
	/// buildAngularJacobian for subclasses that call them (Caliber's rows do not use them).
	btJacobianEntry m_jacLinear[3];
	btJacobianEntry m_jacAng[3];
	btTranslationalLimitMotor m_linearLimits;
	btRotationalLimitMotor m_angularLimits[3];
	/// The step of the last getInfo2 (1 / info->fps).
	btScalar m_timeStep;

	/// The joint frames in the world, as last calculated.
	btTransform m_calculatedTransformA;
	btTransform m_calculatedTransformB;
	/// The Euler angles of frame B relative to frame A.
	btVector3 m_calculatedAxisAngleDiff;
	/// The world directions along which the relative angular velocity measures each angle's rate.
	btVector3 m_calculatedAxis[3];
	/// The linear coordinates.
	btVector3 m_calculatedLinearDiff;
	/// The world point at which the linear rows act when the frame offset is off (see calcAnchorPos).
	/// How the frame-offset method shares a correction: body A's share m_factA = invMassB / (invMassA +
	/// invMassB), m_factB = 1 - m_factA (0.5 each when both are immovable); m_hasStaticBody when either
	/// body's inverse mass is (near) zero. Updated by calculateTransforms.
	btScalar m_factA;
	btScalar m_factB;
	bool m_hasStaticBody;
	btVector3 m_AnchorPos;
	bool m_useLinearReferenceFrameA;
	bool m_useOffsetForConstraintFrame;
	int m_flags;

	/// Fills the linear coordinates and row directions from the calculated transforms.
	void calculateLinearInfo();
	/// Fills the Euler angles and angular row directions from the calculated transforms.
	void calculateAngleInfo();

	/// Writes a limit or motor row for each angular axis that needs one (testAngularLimitMotor decides),
	/// from row row_offset on; returns the row after the last one written. calculateTransforms must have
	/// run for this step.
	int setAngularLimits(btConstraintInfo2 * info, int row_offset, const btTransform& transA,
	                     const btTransform& transB, const btVector3& linVelA, const btVector3& linVelB,
	                     const btVector3& angVelA, const btVector3& angVelB);
	/// The same for the linear axes (the linear limit motor's per-axis settings), from row `row` on.
	int setLinearLimits(btConstraintInfo2 * info, int row, const btTransform& transA, const btTransform& transB,
	                    const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
	                    const btVector3& angVelB);
	/// Fills jacLinear for a linear row along normalWorld between the world points pivotAInW (on A) and
	/// pivotBInW (on B).
	void buildLinearJacobian(btJacobianEntry & jacLinear, const btVector3& normalWorld, const btVector3& pivotAInW,
	                         const btVector3& pivotBInW);
	/// Fills jacAngular for an angular row about the world axis jointAxisW.
	void buildAngularJacobian(btJacobianEntry & jacAngular, const btVector3& jointAxisW);

private:
	// The row directions of the last calculation (the rows in src/ read them). Linear coordinate i's
	// rate is measured along m_linearRowAxis[i] at m_linearRowPoint; angular coordinate i's rate is
	// (angular velocity of B - that of A) . m_angularRowAxis[i] (not unit length away from y = 0).
	btVector3 m_linearRowAxis[3];
	btVector3 m_angularRowAxis[3];
	btVector3 m_linearRowPoint;
	/// The bodies' centres of mass of the last calculation (the rows' lever arms start there).
	btVector3 m_centerOfMassA;
	btVector3 m_centerOfMassB;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Kept for source compatibility; Caliber always solves the joint as rows.
	bool m_useSolveConstraintObsolete;

	/// frameInA and frameInB are in the bodies' centre-of-mass frames. useLinearReferenceFrameA: the linear
	/// coordinates are measured along frame A's axes (else frame B's).
	btGeneric6DofConstraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& frameInA,
	                        const btTransform& frameInB, bool useLinearReferenceFrameA);
	/// Body B jointed to the world: frame A is fixed in the world where frame B is now. The flag is kept
	/// as getUseLinearReferenceFrameA (true: the linear axes are the world-fixed frame's).
	btGeneric6DofConstraint(btRigidBody & rbB, const btTransform& frameInB, bool useLinearReferenceFrameB);

	/// Recalculates the world frames, coordinates and axes for body transforms transA and transB.
	void calculateTransforms(const btTransform& transA, const btTransform& transB);
	/// The same for the bodies' current centre-of-mass transforms.
	void calculateTransforms();

	/// Frame A in the world, as last calculated.
	const btTransform& getCalculatedTransformA() const { return m_calculatedTransformA; }
	/// Frame B in the world, as last calculated.
	const btTransform& getCalculatedTransformB() const { return m_calculatedTransformB; }
	/// Frame A in body A's centre-of-mass frame.
	const btTransform& getFrameOffsetA() const { return m_frameInA; }
	/// Frame B in body B's centre-of-mass frame.
	const btTransform& getFrameOffsetB() const { return m_frameInB; }
	/// The frames, writable: a change takes effect at the next calculateTransforms or step.
	btTransform& getFrameOffsetA() { return m_frameInA; }
	btTransform& getFrameOffsetB() { return m_frameInB; }

	/// Nothing to do: the rows are rebuilt every step.
	void buildJacobian() override {}
	/// One row per locked or limited coordinate and one per motor (internal, for the solver).
	void getInfo1(btConstraintInfo1 * info) override;
	void getInfo1NonVirtual(btConstraintInfo1 * info);
	/// The rows for the bodies' current state (internal, for the solver).
	void getInfo2(btConstraintInfo2 * info) override;
	/// Writes the rows for the given body transforms and velocities.
	void getInfo2NonVirtual(btConstraintInfo2 * info, const btTransform& transA, const btTransform& transB,
	                        const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
	                        const btVector3& angVelB);
	/// Nothing to update: the rows are rebuilt every step.
	void updateRHS(btScalar timeStep) { (void)timeStep; }

	/// The world axis (unit) along which the relative angular velocity measures the rate of angle
	/// axis_index (0..2), as last calculated.
	btVector3 getAxis(int axis_index) const;
	/// The Euler angle axis_index (0..2) of frame B relative to frame A, as last calculated.
	btScalar getAngle(int axis_index) const;
	/// The linear coordinate axis_index (0..2), as last calculated.
	btScalar getRelativePivotPosition(int axis_index) const;
	/// Sets both frames (in the bodies' centre-of-mass frames) and recalculates.
	void setFrames(const btTransform& frameA, const btTransform& frameB);

	/// Measures angle axis_index against its limit; true when the angle needs a limit or motor row.
	bool testAngularLimitMotor(int axis_index);

	/// Writes one row at `row` of info for a limit motor along the world axis ax1 (rotational: an angular
	/// row; otherwise a linear row at the frames' anchor, without angular part unless rotAllowed), when
	/// the motor is at a limit (limot->m_currentLimit, from testLimitValue) or enabled; returns the number
	/// of rows written (0 or 1). The row's J v is ax1 . (wA - wB) (or the anchor's relative velocity along
	/// ax1), the opposite of the coordinate's rate: a limit row drives limot->m_currentLimitError to zero
	/// at m_stopERP with a one-sided impulse (both sides when the limits are equal), with m_stopCFM; a motor
	/// row drives the coordinate's rate to m_targetVelocity within m_maxMotorForce, with m_normalCFM.
	int get_limit_motor_info2(btRotationalLimitMotor * limot, const btTransform& transA, const btTransform& transB,
	                          const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
	                          const btVector3& angVelB, btConstraintInfo2* info, int row, btVector3& ax1,
	                          int rotational, int rotAllowed = false);

	/// Linear limits per axis of the linear reference frame.
	void setLinearLowerLimit(const btVector3& linearLower) { m_linearLimits.m_lowerLimit = linearLower; }
	void getLinearLowerLimit(btVector3 & linearLower) const { linearLower = m_linearLimits.m_lowerLimit; }
	void setLinearUpperLimit(const btVector3& linearUpper) { m_linearLimits.m_upperLimit = linearUpper; }
	void getLinearUpperLimit(btVector3 & linearUpper) const { linearUpper = m_linearLimits.m_upperLimit; }
	/// Angular limits (radians), each moved into (-pi, pi] as in Bullet.
	void setAngularLowerLimit(const btVector3& angularLower);
	void getAngularLowerLimit(btVector3 & angularLower) const;
	void setAngularUpperLimit(const btVector3& angularUpper);
	void getAngularUpperLimit(btVector3 & angularUpper) const;

	/// The limit and motor of angle index (0..2).
	/// The motor of angle index (0..2); an index out of range is reported and clamped into 0..2.
	btRotationalLimitMotor* getRotationalLimitMotor(int index);
	/// The limits and motors of the linear coordinates.
	btTranslationalLimitMotor* getTranslationalLimitMotor() { return &m_linearLimits; }

	/// Limits coordinate axis (0..2 linear, 3..5 angular, angles moved into (-pi, pi]) to [lo, hi].
	void setLimit(int axis, btScalar lo, btScalar hi);
	/// True when coordinate limitIndex (0..5) is locked or limited.
	bool isLimited(int limitIndex) const;

	/// Sets m_AnchorPos: between the two frame origins, nearer the one of the body that moves more
	/// easily (inverse-mass weighted). Used by the linear rows when the frame offset is off.
	virtual void calcAnchorPos(void);

	/// Frame offset on (default): the linear rows measure the exact rate of the linear coordinates. Off:
	/// they act at one shared anchor point (calcAnchorPos), an approximation kept for compatibility.
	bool getUseFrameOffset() const { return m_useOffsetForConstraintFrame; }
	void setUseFrameOffset(bool frameOffsetOnOff) { m_useOffsetForConstraintFrame = frameOffsetOnOff; }

	/// True: the linear coordinates are measured along frame A's axes; false: along frame B's.
	bool getUseLinearReferenceFrameA() const { return m_useLinearReferenceFrameA; }
	void setUseLinearReferenceFrameA(bool linearReferenceFrameA) { m_useLinearReferenceFrameA = linearReferenceFrameA; }

	/// BT_CONSTRAINT_STOP_ERP (also BT_CONSTRAINT_ERP), BT_CONSTRAINT_STOP_CFM (lock and limit rows) and
	/// BT_CONSTRAINT_CFM (motor rows) of coordinate axis 0..5. Unset values fall back to the world's.
	void setParam(int num, btScalar value, int axis = -1) override;
	btScalar getParam(int num, int axis = -1) const override;

	/// Re-orients both frames, keeping their origins: Z along axis1, Y along axis2, X = Y x Z (world axes).
	virtual void setAxis(const btVector3& axis1, const btVector3& axis2);

	/// The bt6DofFlags of all axes (BT_6DOF_FLAGS_AXIS_SHIFT bits per axis).
	virtual int getFlags() const { return m_flags; }

public:
	/// Bytes of the joint's data struct (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the joint's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btGeneric6DofConstraintData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGeneric6DofConstraintData
{
	btTypedConstraintData m_typeConstraintData;
	btTransformFloatData m_rbAFrame;
	btTransformFloatData m_rbBFrame;
	btVector3FloatData m_linearUpperLimit;
	btVector3FloatData m_linearLowerLimit;
	btVector3FloatData m_angularUpperLimit;
	btVector3FloatData m_angularLowerLimit;
	int m_useLinearReferenceFrameA;
	int m_useOffsetForConstraintFrame;
};

/// File layout of btGeneric6DofConstraintDoubleData2 in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGeneric6DofConstraintDoubleData2
{
	btTypedConstraintDoubleData m_typeConstraintData;
	btTransformDoubleData m_rbAFrame;
	btTransformDoubleData m_rbBFrame;
	btVector3DoubleData m_linearUpperLimit;
	btVector3DoubleData m_linearLowerLimit;
	btVector3DoubleData m_angularUpperLimit;
	btVector3DoubleData m_angularLowerLimit;
	int m_useLinearReferenceFrameA;
	int m_useOffsetForConstraintFrame;
};

// clang-format on

#endif  // BT_GENERIC_6DOF_CONSTRAINT_H
