// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SLIDER_CONSTRAINT_H
#define BT_SLIDER_CONSTRAINT_H

/// btSliderConstraint: a prismatic joint that also lets the bodies turn about the slide direction. The X
/// axes of a frame fixed in A and a frame fixed in B are kept on one line; B's frame may slide along it
/// and turn about it. Both motions can be limited (lower > upper: free, lower == upper: locked) and driven
/// by a motor of bounded force or torque.
///
/// Positions: getLinearPos is the distance along the reference frame's X axis from the reference
/// frame's origin to the other frame's origin (the reference frame is A's when useLinearReferenceFrameA,
/// else B's, so the sign flips with it, as in Bullet). getAngularPos is the angle of B's frame about the
/// axis, measured from A's Y axis towards A's Z axis.
///
/// Motors follow Bullet's sign conventions: the linear motor drives getLinearPos at the target velocity;
/// the angular motor drives A's angular velocity minus B's, about the axis, to the target (so a positive
/// target makes getAngularPos decrease).

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btSliderConstraintData2 btSliderConstraintDoubleData
#define btSliderConstraintDataName "btSliderConstraintDoubleData"
#else
#define btSliderConstraintData2 btSliderConstraintData
#define btSliderConstraintDataName "btSliderConstraintData"
#endif

class btRigidBody;

#define SLIDER_CONSTRAINT_DEF_SOFTNESS (btScalar(1.0))
#define SLIDER_CONSTRAINT_DEF_DAMPING (btScalar(1.0))
#define SLIDER_CONSTRAINT_DEF_RESTITUTION (btScalar(0.7))
#define SLIDER_CONSTRAINT_DEF_CFM (btScalar(0.f))

/// Which ERP and CFM values were set through setParam (getFlags). DIR: the motor rows, ORT: the rows
/// perpendicular to the axis, LIM: the limit rows; LIN / ANG: linear / angular.
enum btSliderFlags
{
	BT_SLIDER_FLAGS_CFM_DIRLIN = (1 << 0),
	BT_SLIDER_FLAGS_ERP_DIRLIN = (1 << 1),
	BT_SLIDER_FLAGS_CFM_DIRANG = (1 << 2),
	BT_SLIDER_FLAGS_ERP_DIRANG = (1 << 3),
	BT_SLIDER_FLAGS_CFM_ORTLIN = (1 << 4),
	BT_SLIDER_FLAGS_ERP_ORTLIN = (1 << 5),
	BT_SLIDER_FLAGS_CFM_ORTANG = (1 << 6),
	BT_SLIDER_FLAGS_ERP_ORTANG = (1 << 7),
	BT_SLIDER_FLAGS_CFM_LIMLIN = (1 << 8),
	BT_SLIDER_FLAGS_ERP_LIMLIN = (1 << 9),
	BT_SLIDER_FLAGS_CFM_LIMANG = (1 << 10),
	BT_SLIDER_FLAGS_ERP_LIMANG = (1 << 11)
};

ATTRIBUTE_ALIGNED16(class)
btSliderConstraint : public btTypedConstraint
{
protected:
	/// Kept for source compatibility; Caliber always solves the joint as rows.
	bool m_useSolveConstraintObsolete;
	bool m_useOffsetForConstraintFrame;
	btTransform m_frameInA;
	btTransform m_frameInB;
	bool m_useLinearReferenceFrameA;

	btScalar m_lowerLinLimit;
	btScalar m_upperLinLimit;
	btScalar m_lowerAngLimit;
	btScalar m_upperAngLimit;

	// Per kind of row (Dir: motors, Lim: limits, Ortho: the rows across the axis): softness scales the
	// world's ERP (or is the ERP itself once setParam set it), damping below 1 makes a limit bounce.
	btScalar m_softnessDirLin, m_restitutionDirLin, m_dampingDirLin, m_cfmDirLin;
	btScalar m_softnessDirAng, m_restitutionDirAng, m_dampingDirAng, m_cfmDirAng;
	btScalar m_softnessLimLin, m_restitutionLimLin, m_dampingLimLin, m_cfmLimLin;
	btScalar m_softnessLimAng, m_restitutionLimAng, m_dampingLimAng, m_cfmLimAng;
	btScalar m_softnessOrthoLin, m_restitutionOrthoLin, m_dampingOrthoLin, m_cfmOrthoLin;
	btScalar m_softnessOrthoAng, m_restitutionOrthoAng, m_dampingOrthoAng, m_cfmOrthoAng;

	bool m_solveLinLim;
	bool m_solveAngLim;
	int m_flags;

	btTransform m_calculatedTransformA;
	btTransform m_calculatedTransformB;
	/// The slide direction in the world (the reference frame's X axis, unit length).
	btVector3 m_sliderAxis;
	btVector3 m_realPivotAInW;
	btVector3 m_realPivotBInW;

	btScalar m_linPos;
	btScalar m_angPos;
	btScalar m_linDepth;
	btScalar m_angDepth;

	bool m_poweredLinMotor;
	btScalar m_targetLinMotorVelocity;
	btScalar m_maxLinMotorForce;

	bool m_poweredAngMotor;
	btScalar m_targetAngMotorVelocity;
	btScalar m_maxAngMotorForce;

	void initParams();

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// frameInA and frameInB are in the bodies' centre-of-mass frames; their X axes are the slide axis.
	btSliderConstraint(btRigidBody & rbA, btRigidBody & rbB, const btTransform& frameInA, const btTransform& frameInB,
	                   bool useLinearReferenceFrameA);
	/// Body B slides along the world line where frameInB lies now (A is the world: getFixedBody()).
	btSliderConstraint(btRigidBody & rbB, const btTransform& frameInB, bool useLinearReferenceFrameA);

	void getInfo1(btConstraintInfo1 * info) override;
	/// Same as getInfo1 (Bullet's version reports a fixed count; Caliber's is always the real one).
	void getInfo1NonVirtual(btConstraintInfo1 * info);
	void getInfo2(btConstraintInfo2 * info) override;
	/// The rows for the given body transforms and linear velocities (the masses and inertias are read from
	/// the bodies; the inverse-mass parameters are kept for source compatibility).
	void getInfo2NonVirtual(btConstraintInfo2 * info, const btTransform& transA, const btTransform& transB,
	                        const btVector3& linVelA, const btVector3& linVelB, btScalar rbAinvMass,
	                        btScalar rbBinvMass);

	const btRigidBody& getRigidBodyA() const { return m_rbA; }
	const btRigidBody& getRigidBodyB() const { return m_rbB; }
	/// The frames in the world as of the last calculateTransforms (every step, in getInfo1).
	const btTransform& getCalculatedTransformA() const { return m_calculatedTransformA; }
	const btTransform& getCalculatedTransformB() const { return m_calculatedTransformB; }
	/// The frames in the bodies' centre-of-mass frames (editable; checked again every step).
	const btTransform& getFrameOffsetA() const { return m_frameInA; }
	const btTransform& getFrameOffsetB() const { return m_frameInB; }
	btTransform& getFrameOffsetA() { return m_frameInA; }
	btTransform& getFrameOffsetB() { return m_frameInB; }

	/// Linear limits along the axis (lower > upper: free, lower == upper: locked).
	btScalar getLowerLinLimit() const { return m_lowerLinLimit; }
	void setLowerLinLimit(btScalar lowerLimit) { m_lowerLinLimit = lowerLimit; }
	btScalar getUpperLinLimit() const { return m_upperLinLimit; }
	void setUpperLinLimit(btScalar upperLimit) { m_upperLinLimit = upperLimit; }
	/// Angular limits about the axis in radians, stored in [-pi, pi] (lower > upper: free, equal: locked).
	btScalar getLowerAngLimit() const { return m_lowerAngLimit; }
	void setLowerAngLimit(btScalar lowerLimit) { m_lowerAngLimit = btNormalizeAngle(lowerLimit); }
	btScalar getUpperAngLimit() const { return m_upperAngLimit; }
	void setUpperAngLimit(btScalar upperLimit) { m_upperAngLimit = btNormalizeAngle(upperLimit); }
	/// Whether A's frame (else B's) gives the slide axis and the origin getLinearPos is measured from.
	bool getUseLinearReferenceFrameA() const { return m_useLinearReferenceFrameA; }

	/// Softness (ERP scale), restitution and damping of the motor rows (Dir), limit rows (Lim) and the rows
	/// across the axis (Ortho). Used: the softnesses (the row's ERP is softness * world ERP) and the limit
	/// dampings (a limit bounces back 1 - damping of the speed it is hit with: 1, the default, does not
	/// bounce). The others are kept for source compatibility, as Bullet's row solver ignores them too.
	btScalar getSoftnessDirLin() const { return m_softnessDirLin; }
	btScalar getRestitutionDirLin() const { return m_restitutionDirLin; }
	btScalar getDampingDirLin() const { return m_dampingDirLin; }
	btScalar getSoftnessDirAng() const { return m_softnessDirAng; }
	btScalar getRestitutionDirAng() const { return m_restitutionDirAng; }
	btScalar getDampingDirAng() const { return m_dampingDirAng; }
	btScalar getSoftnessLimLin() const { return m_softnessLimLin; }
	btScalar getRestitutionLimLin() const { return m_restitutionLimLin; }
	btScalar getDampingLimLin() const { return m_dampingLimLin; }
	btScalar getSoftnessLimAng() const { return m_softnessLimAng; }
	btScalar getRestitutionLimAng() const { return m_restitutionLimAng; }
	btScalar getDampingLimAng() const { return m_dampingLimAng; }
	btScalar getSoftnessOrthoLin() const { return m_softnessOrthoLin; }
	btScalar getRestitutionOrthoLin() const { return m_restitutionOrthoLin; }
	btScalar getDampingOrthoLin() const { return m_dampingOrthoLin; }
	btScalar getSoftnessOrthoAng() const { return m_softnessOrthoAng; }
	btScalar getRestitutionOrthoAng() const { return m_restitutionOrthoAng; }
	btScalar getDampingOrthoAng() const { return m_dampingOrthoAng; }
	void setSoftnessDirLin(btScalar softnessDirLin) { m_softnessDirLin = softnessDirLin; }
	void setRestitutionDirLin(btScalar restitutionDirLin) { m_restitutionDirLin = restitutionDirLin; }
	void setDampingDirLin(btScalar dampingDirLin) { m_dampingDirLin = dampingDirLin; }
	void setSoftnessDirAng(btScalar softnessDirAng) { m_softnessDirAng = softnessDirAng; }
	void setRestitutionDirAng(btScalar restitutionDirAng) { m_restitutionDirAng = restitutionDirAng; }
	void setDampingDirAng(btScalar dampingDirAng) { m_dampingDirAng = dampingDirAng; }
	void setSoftnessLimLin(btScalar softnessLimLin) { m_softnessLimLin = softnessLimLin; }
	void setRestitutionLimLin(btScalar restitutionLimLin) { m_restitutionLimLin = restitutionLimLin; }
	void setDampingLimLin(btScalar dampingLimLin) { m_dampingLimLin = dampingLimLin; }
	void setSoftnessLimAng(btScalar softnessLimAng) { m_softnessLimAng = softnessLimAng; }
	void setRestitutionLimAng(btScalar restitutionLimAng) { m_restitutionLimAng = restitutionLimAng; }
	void setDampingLimAng(btScalar dampingLimAng) { m_dampingLimAng = dampingLimAng; }
	void setSoftnessOrthoLin(btScalar softnessOrthoLin) { m_softnessOrthoLin = softnessOrthoLin; }
	void setRestitutionOrthoLin(btScalar restitutionOrthoLin) { m_restitutionOrthoLin = restitutionOrthoLin; }
	void setDampingOrthoLin(btScalar dampingOrthoLin) { m_dampingOrthoLin = dampingOrthoLin; }
	void setSoftnessOrthoAng(btScalar softnessOrthoAng) { m_softnessOrthoAng = softnessOrthoAng; }
	void setRestitutionOrthoAng(btScalar restitutionOrthoAng) { m_restitutionOrthoAng = restitutionOrthoAng; }
	void setDampingOrthoAng(btScalar dampingOrthoAng) { m_dampingOrthoAng = dampingOrthoAng; }

	/// The linear motor: drives getLinearPos at the target velocity (m/s) with at most maxLinMotorForce
	/// (N; the row's impulse bound is force * time step). It fades out as it nears the limit it heads for.
	void setPoweredLinMotor(bool onOff) { m_poweredLinMotor = onOff; }
	bool getPoweredLinMotor() const { return m_poweredLinMotor; }
	void setTargetLinMotorVelocity(btScalar targetLinMotorVelocity)
	{
		m_targetLinMotorVelocity = targetLinMotorVelocity;
	}
	btScalar getTargetLinMotorVelocity() const { return m_targetLinMotorVelocity; }
	void setMaxLinMotorForce(btScalar maxLinMotorForce) { m_maxLinMotorForce = maxLinMotorForce; }
	btScalar getMaxLinMotorForce() const { return m_maxLinMotorForce; }
	/// The angular motor: drives (A's minus B's) angular velocity about the axis to the target (rad/s)
	/// with at most maxAngMotorForce (a torque, N m; the row's bound is torque * time step).
	void setPoweredAngMotor(bool onOff) { m_poweredAngMotor = onOff; }
	bool getPoweredAngMotor() const { return m_poweredAngMotor; }
	void setTargetAngMotorVelocity(btScalar targetAngMotorVelocity)
	{
		m_targetAngMotorVelocity = targetAngMotorVelocity;
	}
	btScalar getTargetAngMotorVelocity() const { return m_targetAngMotorVelocity; }
	void setMaxAngMotorForce(btScalar maxAngMotorForce) { m_maxAngMotorForce = maxAngMotorForce; }
	btScalar getMaxAngMotorForce() const { return m_maxAngMotorForce; }

	/// The slide position and the angle about the axis measured at the start of the last step (or by the
	/// last calculateTransforms / testAngLimits call).
	btScalar getLinearPos() const { return m_linPos; }
	btScalar getAngularPos() const { return m_angPos; }

	/// Whether the position lies outside the linear limits, and by how much (position - limit; 0 inside).
	bool getSolveLinLimit() const { return m_solveLinLim; }
	btScalar getLinDepth() const { return m_linDepth; }
	/// Whether the angle lies outside the angular limits, and by how much (angle - limit; 0 inside).
	bool getSolveAngLimit() const { return m_solveAngLim; }
	btScalar getAngDepth() const { return m_angDepth; }
	/// Measures the frames, the axis and both positions for the given body transforms.
	void calculateTransforms(const btTransform& transA, const btTransform& transB);
	/// Compares the measured positions with the limits (getSolveLinLimit, getLinDepth, and the angular ones).
	void testLinLimits();
	void testAngLimits();
	/// A's frame origin moved to the middle of the linear range, in A's centre-of-mass frame.
	btVector3 getAncorInA();
	/// B's frame origin in B's centre-of-mass frame.
	btVector3 getAncorInB();

	/// Bullet's choice between two row layouts; kept for source compatibility. Caliber's rows put both
	/// bodies' linear impulses at the same point, which is what the frame-offset layout is for.
	bool getUseFrameOffset() const { return m_useOffsetForConstraintFrame; }
	void setUseFrameOffset(bool frameOffsetOnOff) { m_useOffsetForConstraintFrame = frameOffsetOnOff; }

	/// Replaces both frames (checked: a non-finite or degenerate frame disables the joint).
	void setFrames(const btTransform& frameA, const btTransform& frameB);

	/// num: BT_CONSTRAINT_STOP_ERP / STOP_CFM / ERP / CFM; axis 0 (or -1): the slide, 1-2: across it
	/// (linear), 3: the turn about it, 4-5: the turns across it. STOP values are the limits' (axes 0 and 3)
	/// or the cross rows' (1-2, 4-5); ERP / CFM on axes 0 and 3 are the motors', elsewhere the cross rows'.
	void setParam(int num, btScalar value, int axis = -1) override;
	btScalar getParam(int num, int axis = -1) const override;
	/// Which values setParam set (btSliderFlags).
	int getFlags() const { return m_flags; }

public:
	/// Bytes of the joint's data struct (float or double as the build).
	int calculateSerializeBufferSize() const override;
	/// Writes the joint's data struct into dataBuffer and returns the struct's name.
	const char* serialize(void* dataBuffer, btSerializer* serializer) const override;
};

// clang-format off
/// File layout of btSliderConstraintData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btSliderConstraintData
{
	btTypedConstraintData m_typeConstraintData;
	btTransformFloatData m_rbAFrame;
	btTransformFloatData m_rbBFrame;
	float m_linearUpperLimit;
	float m_linearLowerLimit;
	float m_angularUpperLimit;
	float m_angularLowerLimit;
	int m_useLinearReferenceFrameA;
	int m_useOffsetForConstraintFrame;
};

/// File layout of btSliderConstraintDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btSliderConstraintDoubleData
{
	btTypedConstraintDoubleData m_typeConstraintData;
	btTransformDoubleData m_rbAFrame;
	btTransformDoubleData m_rbBFrame;
	double m_linearUpperLimit;
	double m_linearLowerLimit;
	double m_angularUpperLimit;
	double m_angularLowerLimit;
	int m_useLinearReferenceFrameA;
	int m_useOffsetForConstraintFrame;
};

// clang-format on

#endif  // BT_SLIDER_CONSTRAINT_H
