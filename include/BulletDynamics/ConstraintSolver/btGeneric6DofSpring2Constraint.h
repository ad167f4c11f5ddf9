// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_GENERIC_6DOF_CONSTRAINT2_H
#define BT_GENERIC_6DOF_CONSTRAINT2_H

/// btGeneric6DofSpring2Constraint: a joint with six coordinates between a frame fixed in body A and one
/// fixed in body B, each of which can be locked, limited or free, and driven by a motor, a servo or a
/// spring. Coordinates 0..2 are the position of B's frame origin in A's frame (getRelativePivotPosition);
/// coordinates 3..5 are Euler angles of the relative rotation in a chosen order (getAngle).
///
/// Conventions (Bullet's):
/// - Limits: lower == upper locks a coordinate, lower > upper frees it, lower < upper limits it.
/// - Angles: for rotation order RO_ijk the rotation that takes frame B to frame A is
///   R_i(angle_i) R_j(angle_j) R_k(angle_k) (B's basis transposed times A's basis). The first rotation
///   turns about B's axis i, the last about A's axis k; the middle angle stays within [-pi/2, pi/2].
///   So an angle grows when body A turns positively about the axis relative to body B; the *Reversed
///   setters take limits for the opposite sense (B relative to A).
/// - Motors drive the velocity of A relative to B: for an angular coordinate that is the rate of
///   getAngle, for a linear one it is minus the rate of getRelativePivotPosition. Servos move the
///   coordinate itself towards m_servoTarget at up to |m_targetVelocity|. Both push with at most
///   m_maxMotorForce (a force, or a torque for angular coordinates).
/// - Springs pull a coordinate towards m_equilibriumPoint with force -k (x - x0) - c v. They are
///   integrated implicitly (backward Euler), so any stiffness is stable at any time step; the price is
///   a small numerical damping (amplitude factor 1 / sqrt(1 + (omega h)^2) per step when undamped).
/// Rows: locked coordinates give equality rows first (the solver solves them together exactly), then
/// two one-sided rows per limited coordinate, then motors, then springs.

#include "BulletDynamics/ConstraintSolver/btJacobianEntry.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btGeneric6DofSpring2ConstraintData2 btGeneric6DofSpring2ConstraintDoubleData2
#define btGeneric6DofSpring2ConstraintDataName "btGeneric6DofSpring2ConstraintDoubleData2"
#else
#define btGeneric6DofSpring2ConstraintData2 btGeneric6DofSpring2ConstraintData
#define btGeneric6DofSpring2ConstraintDataName "btGeneric6DofSpring2ConstraintData"
#endif

/// The order of the three Euler rotations: RO_ijk rotates first about B's axis i, then about the
/// intermediate axis j, last about A's axis k.
enum RotateOrder
{
	RO_XYZ = 0,
	RO_XZY,
	RO_YXZ,
	RO_YZX,
	RO_ZXY,
	RO_ZYX
};

/// Limit, motor, servo and spring settings of one angular coordinate, and its measured state.
class btRotationalLimitMotor2
{
public:
	/// Limits in radians: upper < lower frees the coordinate, upper == lower locks it.
	btScalar m_loLimit;
	btScalar m_hiLimit;
	/// Fraction of the approach speed a limit gives back (0: none, 1: all).
	btScalar m_bounce;
	/// Error reduction and softness of locked and limit rows (used once set through setParam).
	btScalar m_stopERP;
	btScalar m_stopCFM;
	/// Error reduction of the servo and softness of motor rows (used once set through setParam).
	btScalar m_motorERP;
	btScalar m_motorCFM;
	/// A velocity motor (or, with m_servoMotor, a servo) acts on this coordinate.
	bool m_enableMotor;
	/// Motor target velocity (rad/s); the servo's speed limit.
	btScalar m_targetVelocity;
	/// Largest torque the motor or servo applies.
	btScalar m_maxMotorForce;
	/// The motor is a servo that drives the angle to m_servoTarget.
	bool m_servoMotor;
	btScalar m_servoTarget;
	/// A spring acts on this coordinate.
	bool m_enableSpring;
	/// Spring stiffness (torque per radian) and damping (torque per rad/s).
	btScalar m_springStiffness;
	/// Kept for source compatibility: Caliber's implicit spring never needs its stiffness limited.
	bool m_springStiffnessLimited;
	btScalar m_springDamping;
	/// Kept for source compatibility: Caliber's implicit spring never needs its damping limited.
	bool m_springDampingLimited;
	/// The angle the spring pulls towards.
	btScalar m_equilibriumPoint;

	/// Measured by the joint each step: angle minus lower limit, angle minus upper limit, the angle
	/// (moved by whole turns towards the limits), and 0 free / 3 locked / 4 limited.
	btScalar m_currentLimitError;
	btScalar m_currentLimitErrorHi;
	btScalar m_currentPosition;
	int m_currentLimit;

	/// Free, unpowered and springless (Bullet's defaults).
	btRotationalLimitMotor2()
	    : m_loLimit(1),
	      m_hiLimit(-1),
	      m_bounce(0),
	      m_stopERP(btScalar(0.2)),
	      m_stopCFM(0),
	      m_motorERP(btScalar(0.9)),
	      m_motorCFM(0),
	      m_enableMotor(false),
	      m_targetVelocity(0),
	      m_maxMotorForce(btScalar(6)),
	      m_servoMotor(false),
	      m_servoTarget(0),
	      m_enableSpring(false),
	      m_springStiffness(0),
	      m_springStiffnessLimited(false),
	      m_springDamping(0),
	      m_springDampingLimited(false),
	      m_equilibriumPoint(0),
	      m_currentLimitError(0),
	      m_currentLimitErrorHi(0),
	      m_currentPosition(0),
	      m_currentLimit(0)
	{
	}

	/// True unless the coordinate is free (lower > upper).
	bool isLimited() const { return !(m_loLimit > m_hiLimit); }

	/// Sets m_currentLimit and the limit errors for the angle test_value.
	void testLimitValue(btScalar test_value);
};

/// Limit, motor, servo and spring settings of the three linear coordinates, and their measured state.
class btTranslationalLimitMotor2
{
public:
	/// Limits per coordinate: upper < lower frees it, upper == lower locks it (default: all locked).
	btVector3 m_lowerLimit;
	btVector3 m_upperLimit;
	/// Fraction of the approach speed a limit gives back.
	btVector3 m_bounce;
	/// Error reduction and softness of locked and limit rows (used once set through setParam).
	btVector3 m_stopERP;
	btVector3 m_stopCFM;
	/// Error reduction of the servo and softness of motor rows (used once set through setParam).
	btVector3 m_motorERP;
	btVector3 m_motorCFM;
	/// A velocity motor (or a servo) acts on the coordinate.
	bool m_enableMotor[3];
	/// The motor is a servo driving the coordinate to m_servoTarget.
	bool m_servoMotor[3];
	/// A spring acts on the coordinate.
	bool m_enableSpring[3];
	btVector3 m_servoTarget;
	/// Spring stiffness (force per metre) and damping (force per m/s).
	btVector3 m_springStiffness;
	/// Kept for source compatibility: Caliber's implicit spring never needs its stiffness limited.
	bool m_springStiffnessLimited[3];
	btVector3 m_springDamping;
	/// Kept for source compatibility: Caliber's implicit spring never needs its damping limited.
	bool m_springDampingLimited[3];
	/// The positions the springs pull towards.
	btVector3 m_equilibriumPoint;
	/// Motor target velocities (A relative to B; see the class comment); the servos' speed limits.
	btVector3 m_targetVelocity;
	/// Largest force each motor or servo applies.
	btVector3 m_maxMotorForce;

	/// Measured by the joint each step: position minus lower limit, position minus upper limit, the
	/// position, and 0 free / 3 locked / 4 limited.
	btVector3 m_currentLimitError;
	btVector3 m_currentLimitErrorHi;
	btVector3 m_currentLinearDiff;
	int m_currentLimit[3];

	/// Locked, unpowered and springless (Bullet's defaults).
	btTranslationalLimitMotor2()
	    : m_lowerLimit(0, 0, 0),
	      m_upperLimit(0, 0, 0),
	      m_bounce(0, 0, 0),
	      m_stopERP(btScalar(0.2), btScalar(0.2), btScalar(0.2)),
	      m_stopCFM(0, 0, 0),
	      m_motorERP(btScalar(0.9), btScalar(0.9), btScalar(0.9)),
	      m_motorCFM(0, 0, 0),
	      m_servoTarget(0, 0, 0),
	      m_springStiffness(0, 0, 0),
	      m_springDamping(0, 0, 0),
	      m_equilibriumPoint(0, 0, 0),
	      m_targetVelocity(0, 0, 0),
	      m_maxMotorForce(0, 0, 0),
	      m_currentLimitError(0, 0, 0),
	      m_currentLimitErrorHi(0, 0, 0),
	      m_currentLinearDiff(0, 0, 0)
	{
		for (int i = 0; i < 3; ++i)
		{
			m_enableMotor[i] = false;
			m_servoMotor[i] = false;
			m_enableSpring[i] = false;
			m_springStiffnessLimited[i] = false;
			m_springDampingLimited[i] = false;
			m_currentLimit[i] = 0;
		}
	}

	/// True unless coordinate limitIndex is free (lower > upper).
	bool isLimited(int limitIndex) const { return m_upperLimit[limitIndex] >= m_lowerLimit[limitIndex]; }

	/// Sets m_currentLimit[limitIndex] and its limit errors for the position test_value.
	void testLimitValue(int limitIndex, btScalar test_value);
};

/// Which per-axis parameters were set through setParam (4 bits per axis, axis 0 lowest).
enum bt6DofFlags2
{
	BT_6DOF_FLAGS_CFM_STOP2 = 1,
	BT_6DOF_FLAGS_ERP_STOP2 = 2,
	BT_6DOF_FLAGS_CFM_MOTO2 = 4,
	BT_6DOF_FLAGS_ERP_MOTO2 = 8
};
#define BT_6DOF_FLAGS_AXIS_SHIFT2 4  // bits per axis

ATTRIBUTE_ALIGNED16(class)
btGeneric6DofSpring2Constraint : public btTypedConstraint
{
protected:
	btTransform m_frameInA;
	btTransform m_frameInB;

	/// Bullet's per-axis Jacobian entries, declared for subclasses; neither Bullet's rows nor Caliber's
	/// fill them.
	btJacobianEntry m_jacLinear[3];
	btJacobianEntry m_jacAng[3];

	btTranslationalLimitMotor2 m_linearLimits;
	btRotationalLimitMotor2 m_angularLimits[3];

	RotateOrder m_rotateOrder;

	btTransform m_calculatedTransformA;
	btTransform m_calculatedTransformB;
	btVector3 m_calculatedAxisAngleDiff;
	/// Unit world directions along which each angle's rate is measured (see getAxis).
	btVector3 m_calculatedAxis[3];
	btVector3 m_calculatedLinearDiff;
	/// How a correction is shared: m_factA = invMassB / (invMassA + invMassB), m_factB = 1 - m_factA (0.5
	/// each when both are immovable); m_hasStaticBody when either inverse mass is (near) zero. Updated by
	/// calculateTransforms.
	btScalar m_factA;
	btScalar m_factB;
	bool m_hasStaticBody;
	int m_flags;

	btGeneric6DofSpring2Constraint& operator=(btGeneric6DofSpring2Constraint&)
	{
		btAssert(0);
		return *this;
	}

	/// Writes the rows of the three angular coordinates (each as get_limit_motor_info2 does, about the
	/// exact rate direction of its angle) from row row_offset on; returns the row after the last one
	/// written. calculateTransforms must have run for these poses. The coordinates' own stop and motor
	/// ERP and CFM apply where set through setParam, info's ERP and the rows' starting CFM otherwise.
	int setAngularLimits(btConstraintInfo2 * info, int row_offset, const btTransform& transA, const btTransform& transB,
	                     const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
	                     const btVector3& angVelB);
	/// The same for the three linear coordinates (each along A's frame axis, acting at B's pivot), from
	/// row `row` on.
	int setLinearLimits(btConstraintInfo2 * info, int row, const btTransform& transA, const btTransform& transB,
	                    const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
	                    const btVector3& angVelB);

	/// From the calculated transforms: the linear coordinates (m_calculatedLinearDiff, B's pivot in A's
	/// frame) and their limit states.
	void calculateLinearInfo();
	/// From the calculated transforms: the Euler angles (m_calculatedAxisAngleDiff) and the directions
	/// their rates are measured along (m_calculatedAxis, unit length).
	void calculateAngleInfo();
	/// Angle axis_index's position (the same angle a turn away when that is inside or nearer the limits)
	/// and limit state (m_currentLimit: 0 free, 3 locked, 4 limited).
	void testAngularLimitMotor(int axis_index);

	/// Writes the Jacobian of row srow along ax1: rotational, A turns about ax1 and B about -ax1;
	/// otherwise A moves along ax1 and B along -ax1, and with rotAllowed each body also turns about its
	/// centre of mass (transA's and transB's origins) as a push at B's pivot would turn it.
	void calculateJacobi(btRotationalLimitMotor2 * limot, const btTransform& transA, const btTransform& transB,
	                     btConstraintInfo2* info, int srow, btVector3& ax1, int rotational, int rotAllowed);
	/// Writes the rows of one coordinate with limot's settings (its m_currentLimit, m_currentPosition,
	/// limits, bounce, motor, servo and spring; its ERPs and CFMs as they are) from row `row` on: a locked
	/// row, or a row per limit end, then a motor row and a spring row when enabled; returns how many rows
	/// it wrote. The rows measure the coordinate's rate: an angle's along ax1 (rotational), a linear
	/// coordinate's (B's pivot relative to A along ax1) along -ax1. Bounds and targets are those of
	/// getInfo2's rows.
	int get_limit_motor_info2(btRotationalLimitMotor2 * limot, const btTransform& transA, const btTransform& transB,
	                          const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
	                          const btVector3& angVelB, btConstraintInfo2* info, int row, btVector3& ax1,
	                          int rotational, int rotAllowed = false);

private:
	/// The world vectors d_n with d_n . (wA - wB) = d(angle n)/dt exactly (the dual basis of the three
	/// Euler rotation axes); m_calculatedAxis holds them normalised.
	btVector3 m_angularJacobian[3];

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// frameInA and frameInB are the joint frames in the bodies' centre-of-mass frames.
	btGeneric6DofSpring2Constraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& frameInA,
	                               const btTransform& frameInB, RotateOrder rotOrder = RO_XYZ);
	/// Body B held to the world; A's frame is where B's frame is now.
	btGeneric6DofSpring2Constraint(btRigidBody & rbB, const btTransform& frameInB, RotateOrder rotOrder = RO_XYZ);

	/// Nothing to prepare: the rows are rebuilt from the bodies' poses every step.
	void buildJacobian() override {}
	/// Measures the joint and counts its rows (nub: the locked ones).
	void getInfo1(btConstraintInfo1 * info) override;
	/// Writes the rows: locked, then limits, motors and springs.
	void getInfo2(btConstraintInfo2 * info) override;

	/// The settings of angular coordinate index (0..2).
	/// The motor of angle index (0..2); an index out of range is reported and clamped into 0..2.
	btRotationalLimitMotor2* getRotationalLimitMotor(int index);
	/// The settings of the three linear coordinates.
	btTranslationalLimitMotor2* getTranslationalLimitMotor() { return &m_linearLimits; }

	/// Measures the joint for the given body transforms: world frames, positions, angles, axes, limits.
	void calculateTransforms(const btTransform& transA, const btTransform& transB);
	/// calculateTransforms for the bodies' current centre-of-mass transforms.
	void calculateTransforms();

	/// Joint frame of A in the world (after calculateTransforms).
	const btTransform& getCalculatedTransformA() const { return m_calculatedTransformA; }
	/// Joint frame of B in the world (after calculateTransforms).
	const btTransform& getCalculatedTransformB() const { return m_calculatedTransformB; }
	/// Joint frame in A's centre-of-mass frame.
	const btTransform& getFrameOffsetA() const { return m_frameInA; }
	/// Joint frame in B's centre-of-mass frame.
	const btTransform& getFrameOffsetB() const { return m_frameInB; }
	/// Writable joint frames (changes take effect at the next step).
	btTransform& getFrameOffsetA() { return m_frameInA; }
	btTransform& getFrameOffsetB() { return m_frameInB; }

	/// Unit world direction about which angle axis_index (0..2) is measured (after calculateTransforms);
	/// an index out of range is reported and gives zero, as do the two getters below.
	btVector3 getAxis(int axis_index) const;
	/// Euler angle axis_index (0..2) in radians (after calculateTransforms).
	btScalar getAngle(int axis_index) const;
	/// Coordinate axis_index (0..2) of B's frame origin in A's frame (after calculateTransforms).
	btScalar getRelativePivotPosition(int axis_index) const;

	/// Replaces both joint frames (non-finite frames are reported and disable the joint).
	void setFrames(const btTransform& frameA, const btTransform& frameB);

	/// Linear limits per coordinate (metres).
	void setLinearLowerLimit(const btVector3& linearLower) { m_linearLimits.m_lowerLimit = linearLower; }
	void getLinearLowerLimit(btVector3 & linearLower) const { linearLower = m_linearLimits.m_lowerLimit; }
	void setLinearUpperLimit(const btVector3& linearUpper) { m_linearLimits.m_upperLimit = linearUpper; }
	void getLinearUpperLimit(btVector3 & linearUpper) const { linearUpper = m_linearLimits.m_upperLimit; }

	/// Lower angular limits (radians, wrapped into [-pi, pi]).
	void setAngularLowerLimit(const btVector3& angularLower)
	{
		for (int i = 0; i < 3; ++i) m_angularLimits[i].m_loLimit = btNormalizeAngle(angularLower[i]);
	}
	/// Lower limits of the opposite sense (B relative to A): stored as the negated upper limits.
	void setAngularLowerLimitReversed(const btVector3& angularLower)
	{
		for (int i = 0; i < 3; ++i) m_angularLimits[i].m_hiLimit = btNormalizeAngle(-angularLower[i]);
	}
	/// The lower angular limits as stored.
	void getAngularLowerLimit(btVector3 & angularLower) const
	{
		for (int i = 0; i < 3; ++i) angularLower[i] = m_angularLimits[i].m_loLimit;
	}
	/// The lower limits of the opposite sense (the negated upper limits).
	void getAngularLowerLimitReversed(btVector3 & angularLower) const
	{
		for (int i = 0; i < 3; ++i) angularLower[i] = -m_angularLimits[i].m_hiLimit;
	}
	/// Upper angular limits (radians, wrapped into [-pi, pi]).
	void setAngularUpperLimit(const btVector3& angularUpper)
	{
		for (int i = 0; i < 3; ++i) m_angularLimits[i].m_hiLimit = btNormalizeAngle(angularUpper[i]);
	}
	/// Upper limits of the opposite sense (B relative to A): stored as the negated lower limits.
	void setAngularUpperLimitReversed(const btVector3& angularUpper)
	{
		for (int i = 0; i < 3; ++i) m_angularLimits[i].m_loLimit = btNormalizeAngle(-angularUpper[i]);
	}
	/// The upper angular limits as stored.
	void getAngularUpperLimit(btVector3 & angularUpper) const
	{
		for (int i = 0; i < 3; ++i) angularUpper[i] = m_angularLimits[i].m_hiLimit;
	}
	/// The upper limits of the opposite sense (the negated lower limits).
	void getAngularUpperLimitReversed(btVector3 & angularUpper) const
	{
		for (int i = 0; i < 3; ++i) angularUpper[i] = -m_angularLimits[i].m_loLimit;
	}

	/// Limits of coordinate axis (0..2 linear, 3..5 angular, angles wrapped into [-pi, pi]).
	void setLimit(int axis, btScalar lo, btScalar hi);
	/// setLimit for the opposite sense of an angle (B relative to A); linear coordinates as setLimit.
	void setLimitReversed(int axis, btScalar lo, btScalar hi);
	/// True unless coordinate limitIndex (0..5) is free.
	bool isLimited(int limitIndex) const;

	/// The Euler order the angles (and their limits, motors and springs) are measured in.
	void setRotationOrder(RotateOrder order) { m_rotateOrder = order; }
	RotateOrder getRotationOrder() const { return m_rotateOrder; }

	/// Re-aims both frames: z along axis1, y along axis2 (made perpendicular to axis1), both world
	/// directions; as in Bullet the frames' origin moves to the world origin.
	void setAxis(const btVector3& axis1, const btVector3& axis2);

	/// Bounce of coordinate index's limits (0..5).
	void setBounce(int index, btScalar bounce);

	/// Turns the motor of coordinate index (0..5) on or off.
	void enableMotor(int index, bool onOff);
	/// Makes the motor a servo (it must be enabled too).
	void setServo(int index, bool onOff);
	/// Motor target velocity; for a servo, its speed limit.
	void setTargetVelocity(int index, btScalar velocity);
	/// Servo target position (angles wrapped into [-pi, pi)).
	void setServoTarget(int index, btScalar target);
	/// Largest force (or torque) the motor applies.
	void setMaxMotorForce(int index, btScalar force);

	/// Turns the spring of coordinate index (0..5) on or off.
	void enableSpring(int index, bool onOff);
	/// Spring stiffness; limitIfNeeded is kept for source compatibility (the implicit spring needs no
	/// limiting).
	void setStiffness(int index, btScalar stiffness, bool limitIfNeeded = true);
	/// Spring damping; limitIfNeeded is kept for source compatibility.
	void setDamping(int index, btScalar damping, bool limitIfNeeded = true);
	/// The current position of every coordinate becomes its spring's equilibrium.
	void setEquilibriumPoint();
	/// The current position of coordinate index becomes its spring's equilibrium.
	void setEquilibriumPoint(int index);
	/// Sets the equilibrium of coordinate index.
	void setEquilibriumPoint(int index, btScalar val);

	/// BT_CONSTRAINT_STOP_ERP / STOP_CFM set the locked and limit rows of axis 0..5, BT_CONSTRAINT_ERP /
	/// CFM the servo and motor rows. Until set, the world's ERP and CFM are used.
	void setParam(int num, btScalar value, int axis = -1) override;
	/// The value set through setParam (asserts that it was set, as in Bullet).
	btScalar getParam(int num, int axis = -1) const override;

	/// Element index of mat, counting down the columns (index % 3 is the row, index / 3 the column).
	static btScalar btGetMatrixElem(const btMatrix3x3& mat, int index);
	/// Euler angles (in xyz, indexed by axis) of the relative rotation mat = A^T B for each order; false
	/// at gimbal lock (middle angle +-pi/2), where the last angle is set to 0.
	static bool matrixToEulerXYZ(const btMatrix3x3& mat, btVector3& xyz);
	static bool matrixToEulerXZY(const btMatrix3x3& mat, btVector3& xyz);
	static bool matrixToEulerYXZ(const btMatrix3x3& mat, btVector3& xyz);
	static bool matrixToEulerYZX(const btMatrix3x3& mat, btVector3& xyz);
	static bool matrixToEulerZXY(const btMatrix3x3& mat, btVector3& xyz);
	static bool matrixToEulerZYX(const btMatrix3x3& mat, btVector3& xyz);

public:
	/// Bytes of the joint's data struct (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the joint's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btGeneric6DofSpring2ConstraintData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGeneric6DofSpring2ConstraintData
{
	btTypedConstraintData m_typeConstraintData;
	btTransformFloatData m_rbAFrame;
	btTransformFloatData m_rbBFrame;
	btVector3FloatData m_linearUpperLimit;
	btVector3FloatData m_linearLowerLimit;
	btVector3FloatData m_linearBounce;
	btVector3FloatData m_linearStopERP;
	btVector3FloatData m_linearStopCFM;
	btVector3FloatData m_linearMotorERP;
	btVector3FloatData m_linearMotorCFM;
	btVector3FloatData m_linearTargetVelocity;
	btVector3FloatData m_linearMaxMotorForce;
	btVector3FloatData m_linearServoTarget;
	btVector3FloatData m_linearSpringStiffness;
	btVector3FloatData m_linearSpringDamping;
	btVector3FloatData m_linearEquilibriumPoint;
	char m_linearEnableMotor[4];
	char m_linearServoMotor[4];
	char m_linearEnableSpring[4];
	char m_linearSpringStiffnessLimited[4];
	char m_linearSpringDampingLimited[4];
	char m_padding1[4];
	btVector3FloatData m_angularUpperLimit;
	btVector3FloatData m_angularLowerLimit;
	btVector3FloatData m_angularBounce;
	btVector3FloatData m_angularStopERP;
	btVector3FloatData m_angularStopCFM;
	btVector3FloatData m_angularMotorERP;
	btVector3FloatData m_angularMotorCFM;
	btVector3FloatData m_angularTargetVelocity;
	btVector3FloatData m_angularMaxMotorForce;
	btVector3FloatData m_angularServoTarget;
	btVector3FloatData m_angularSpringStiffness;
	btVector3FloatData m_angularSpringDamping;
	btVector3FloatData m_angularEquilibriumPoint;
	char m_angularEnableMotor[4];
	char m_angularServoMotor[4];
	char m_angularEnableSpring[4];
	char m_angularSpringStiffnessLimited[4];
	char m_angularSpringDampingLimited[4];
	int m_rotateOrder;
};

/// File layout of btGeneric6DofSpring2ConstraintDoubleData2 in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btGeneric6DofSpring2ConstraintDoubleData2
{
	btTypedConstraintDoubleData m_typeConstraintData;
	btTransformDoubleData m_rbAFrame;
	btTransformDoubleData m_rbBFrame;
	btVector3DoubleData m_linearUpperLimit;
	btVector3DoubleData m_linearLowerLimit;
	btVector3DoubleData m_linearBounce;
	btVector3DoubleData m_linearStopERP;
	btVector3DoubleData m_linearStopCFM;
	btVector3DoubleData m_linearMotorERP;
	btVector3DoubleData m_linearMotorCFM;
	btVector3DoubleData m_linearTargetVelocity;
	btVector3DoubleData m_linearMaxMotorForce;
	btVector3DoubleData m_linearServoTarget;
	btVector3DoubleData m_linearSpringStiffness;
	btVector3DoubleData m_linearSpringDamping;
	btVector3DoubleData m_linearEquilibriumPoint;
	char m_linearEnableMotor[4];
	char m_linearServoMotor[4];
	char m_linearEnableSpring[4];
	char m_linearSpringStiffnessLimited[4];
	char m_linearSpringDampingLimited[4];
	char m_padding1[4];
	btVector3DoubleData m_angularUpperLimit;
	btVector3DoubleData m_angularLowerLimit;
	btVector3DoubleData m_angularBounce;
	btVector3DoubleData m_angularStopERP;
	btVector3DoubleData m_angularStopCFM;
	btVector3DoubleData m_angularMotorERP;
	btVector3DoubleData m_angularMotorCFM;
	btVector3DoubleData m_angularTargetVelocity;
	btVector3DoubleData m_angularMaxMotorForce;
	btVector3DoubleData m_angularServoTarget;
	btVector3DoubleData m_angularSpringStiffness;
	btVector3DoubleData m_angularSpringDamping;
	btVector3DoubleData m_angularEquilibriumPoint;
	char m_angularEnableMotor[4];
	char m_angularServoMotor[4];
	char m_angularEnableSpring[4];
	char m_angularSpringStiffnessLimited[4];
	char m_angularSpringDampingLimited[4];
	int m_rotateOrder;
};

// clang-format on

#endif  // BT_GENERIC_6DOF_CONSTRAINT2_H
