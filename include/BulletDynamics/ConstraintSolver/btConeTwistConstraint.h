// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_CONE_TWIST_CONSTRAINT_H
#define BT_CONE_TWIST_CONSTRAINT_H

/// btConeTwistConstraint: a ball joint with a cone limit (shoulders, hips, necks). The frames' origins
/// are held together; the twist axis is the frames' X axis. B's X axis may swing away from A's inside
/// an elliptic cone (swingSpan1 about Z, swingSpan2 about Y) and twist about it within +-twistSpan.
/// A motor can drive the relative orientation to a target. Guide: docs/constraints.md.

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btConeTwistConstraintData2 btConeTwistConstraintDoubleData
#define btConeTwistConstraintDataName "btConeTwistConstraintDoubleData"
#else
#define btConeTwistConstraintData2 btConeTwistConstraintData
#define btConeTwistConstraintDataName "btConeTwistConstraintData"
#endif

enum btConeTwistFlags
{
	BT_CONETWIST_FLAGS_LIN_CFM = 1,
	BT_CONETWIST_FLAGS_LIN_ERP = 2,
	BT_CONETWIST_FLAGS_ANG_CFM = 4
};

ATTRIBUTE_ALIGNED16(class)
btConeTwistConstraint : public btTypedConstraint
{
	btTransform m_rbAFrame;
	btTransform m_rbBFrame;

	btScalar m_limitSoftness;
	btScalar m_biasFactor;
	btScalar m_relaxationFactor;
	btScalar m_damping;
	bool m_dampingSet;
	btScalar m_swingSpan1;
	btScalar m_swingSpan2;
	btScalar m_twistSpan;
	btScalar m_fixThresh;

	// Measured by calcAngleInfo2: the swing (angle and world axis) and twist (angle and world axis).
	btScalar m_swingAngle;
	btVector3 m_swingAxis;
	btScalar m_swingLimit;
	btScalar m_twistAngle;
	btVector3 m_twistAxis;
	bool m_solveTwistLimit;
	bool m_solveSwingLimit;
	btScalar m_twistLimitSign;

	/// Whether this step has a swing (twist) limit row: past the limit or close enough to reach it soon.
	bool m_swingRowNeeded;
	bool m_twistRowNeeded;
	/// The solver's last time step, for judging in getInfo1 whether a limit can be reached soon.
	btScalar m_lastTimeStep;

	bool m_angularOnly;
	bool m_bMotorEnabled;
	bool m_bNormalizedMotorStrength;
	btQuaternion m_qTarget;
	btScalar m_maxMotorImpulse;

	int m_flags;
	btScalar m_linCFM;
	btScalar m_linERP;
	btScalar m_angCFM;

	void init();
	/// Number of rows this step (after calcAngleInfo2).
	int rowCount() const;
	/// Whether a swing (twist) limit row is needed: a limit is set and the rotation is not locked.
	bool swingLimited() const;
	bool twistLimited() const;

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Frames in each body's centre-of-mass frame; the twist axis is their X axis.
	btConeTwistConstraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& rbAFrame,
	                      const btTransform& rbBFrame);
	/// Body A joined to the world at its frame's current pose.
	btConeTwistConstraint(btRigidBody & rbA, const btTransform& rbAFrame);

	void buildJacobian() override {}
	void getInfo1(btConstraintInfo1 * info) override;
	void getInfo1NonVirtual(btConstraintInfo1 * info);
	void getInfo2(btConstraintInfo2 * info) override;
	void getInfo2NonVirtual(btConstraintInfo2 * info, const btTransform& transA, const btTransform& transB,
	                        const btMatrix3x3& invInertiaWorldA, const btMatrix3x3& invInertiaWorldB);

	/// Nothing to update: the rows are rebuilt every step.
	void updateRHS(btScalar timeStep) { (void)timeStep; }

	const btRigidBody& getRigidBodyA() const { return m_rbA; }
	const btRigidBody& getRigidBodyB() const { return m_rbB; }

	void setAngularOnly(bool angularOnly) { m_angularOnly = angularOnly; }
	bool getAngularOnly() const { return m_angularOnly; }

	/// One span by axis index: 3 twist, 4 swing about Y (swingSpan2), 5 swing about Z (swingSpan1).
	void setLimit(int limitIndex, btScalar limitValue);
	btScalar getLimit(int limitIndex) const;

	/// The cone (swing spans, radians) and the twist range (+-twistSpan). A span under getFixThresh()
	/// locks that rotation. biasFactor is the share of an overshoot corrected per step,
	/// relaxationFactor (0..1) the share of a velocity into the limit that the limit stops; softness is
	/// stored for compatibility (Caliber's limits are hard).
	void setLimit(btScalar _swingSpan1, btScalar _swingSpan2, btScalar _twistSpan, btScalar _softness = 1.f,
	              btScalar _biasFactor = 0.3f, btScalar _relaxationFactor = 1.0f);

	const btTransform& getAFrame() const { return m_rbAFrame; }
	const btTransform& getBFrame() const { return m_rbBFrame; }
	btTransform getFrameOffsetA() const { return m_rbAFrame; }
	btTransform getFrameOffsetB() const { return m_rbBFrame; }
	void setFrames(const btTransform& frameA, const btTransform& frameB);

	int getSolveTwistLimit() { return m_solveTwistLimit ? 1 : 0; }
	int getSolveSwingLimit() { return m_solveSwingLimit ? 1 : 0; }
	btScalar getTwistLimitSign() { return m_twistLimitSign; }

	/// Measures swing and twist from the bodies' current poses.
	void calcAngleInfo();
	void calcAngleInfo2(const btTransform& transA, const btTransform& transB, const btMatrix3x3& invInertiaWorldA,
	                    const btMatrix3x3& invInertiaWorldB);

	btScalar getSwingSpan1() const { return m_swingSpan1; }
	btScalar getSwingSpan2() const { return m_swingSpan2; }
	btScalar getTwistSpan() const { return m_twistSpan; }
	btScalar getLimitSoftness() const { return m_limitSoftness; }
	btScalar getBiasFactor() const { return m_biasFactor; }
	btScalar getRelaxationFactor() const { return m_relaxationFactor; }
	/// The twist angle measured in the last step (radians).
	btScalar getTwistAngle() const { return m_twistAngle; }
	/// The swing angle measured in the last step (radians).
	btScalar getSwingAngle() const { return m_swingAngle; }
	bool isPastSwingLimit() { return m_solveSwingLimit; }

	/// Damping of the relative rotation: with damping d the joint removes the share d of the bodies'
	/// relative angular velocity per step (rows bounded like the motor). Off until set.
	void setDamping(btScalar damping)
	{
		m_damping = damping;
		m_dampingSet = true;
	}
	btScalar getDamping() const { return m_damping; }

	/// The motor drives the relative orientation to the target (setMotorTarget), with at most
	/// getMaxMotorImpulse per step.
	void enableMotor(bool b) { m_bMotorEnabled = b; }
	bool isMotorEnabled() const { return m_bMotorEnabled; }
	btScalar getMaxMotorImpulse() const { return m_maxMotorImpulse; }
	bool isMaxMotorImpulseNormalized() const { return m_bNormalizedMotorStrength; }
	void setMaxMotorImpulse(btScalar maxMotorImpulse)
	{
		m_maxMotorImpulse = maxMotorImpulse;
		m_bNormalizedMotorStrength = false;
	}
	/// maxMotorImpulse given per unit of the bodies' rotational inertia (an angular velocity change).
	void setMaxMotorImpulseNormalized(btScalar maxMotorImpulse)
	{
		m_maxMotorImpulse = maxMotorImpulse;
		m_bNormalizedMotorStrength = true;
	}

	btScalar getFixThresh() { return m_fixThresh; }
	void setFixThresh(btScalar fixThresh) { m_fixThresh = fixThresh; }

	/// Target orientation of body A relative to body B (A's centre-of-mass frame seen in B's).
	void setMotorTarget(const btQuaternion& q);
	const btQuaternion& getMotorTarget() const { return m_qTarget; }
	/// Target orientation of frame A relative to frame B; clamped into the cone and twist range.
	void setMotorTargetInConstraintSpace(const btQuaternion& q);

	/// A point at distance len from the pivot on the cone's rim, at angle fAngleInRadians around the twist
	/// axis, in A's joint frame (for drawing the cone).
	btVector3 GetPointForAngle(btScalar fAngleInRadians, btScalar len) const;

	/// Linear rows: ERP/CFM (axis -1 or 0..2); angular rows: CFM (axis 3..5).
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
/// File layout of btConeTwistConstraintDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btConeTwistConstraintDoubleData
{
	btTypedConstraintDoubleData m_typeConstraintData;
	btTransformDoubleData m_rbAFrame;
	btTransformDoubleData m_rbBFrame;
	double m_swingSpan1;
	double m_swingSpan2;
	double m_twistSpan;
	double m_limitSoftness;
	double m_biasFactor;
	double m_relaxationFactor;
	double m_damping;
};

/// File layout of btConeTwistConstraintData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btConeTwistConstraintData
{
	btTypedConstraintData m_typeConstraintData;
	btTransformFloatData m_rbAFrame;
	btTransformFloatData m_rbBFrame;
	float m_swingSpan1;
	float m_swingSpan2;
	float m_twistSpan;
	float m_limitSoftness;
	float m_biasFactor;
	float m_relaxationFactor;
	float m_damping;
	char m_pad[4];
};

// clang-format on

#endif  // BT_CONE_TWIST_CONSTRAINT_H
