// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_TYPED_CONSTRAINT_H
#define BT_TYPED_CONSTRAINT_H

/// btTypedConstraint: the base of every joint, and the row interface that user-written joints use too.
/// A joint describes itself to the solver as rows (getInfo1: how many; getInfo2: each row's Jacobian,
/// target, softness and bounds); the solver treats those rows exactly like contact rows. Guide:
/// docs/constraints.md.

#include "BulletDynamics/ConstraintSolver/btSolverConstraint.h"
#include "BulletDynamics/Dynamics/btRigidBody.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btScalar.h"

#ifdef BT_USE_DOUBLE_PRECISION
#define btTypedConstraintData2 btTypedConstraintDoubleData
#define btTypedConstraintDataName "btTypedConstraintDoubleData"
#else
#define btTypedConstraintData2 btTypedConstraintFloatData
#define btTypedConstraintDataName "btTypedConstraintFloatData"
#endif

class btSerializer;
struct btSolverBody;

enum btTypedConstraintType
{
	POINT2POINT_CONSTRAINT_TYPE = 3,
	HINGE_CONSTRAINT_TYPE,
	CONETWIST_CONSTRAINT_TYPE,
	D6_CONSTRAINT_TYPE,
	SLIDER_CONSTRAINT_TYPE,
	CONTACT_CONSTRAINT_TYPE,
	D6_SPRING_CONSTRAINT_TYPE,
	GEAR_CONSTRAINT_TYPE,
	FIXED_CONSTRAINT_TYPE,
	D6_SPRING_2_CONSTRAINT_TYPE,
	MAX_CONSTRAINT_TYPE
};

/// What setParam/getParam change: the error reduction and softness of the joint's rows (ERP, CFM) or of
/// its limits (STOP_ERP, STOP_CFM).
enum btConstraintParams
{
	BT_CONSTRAINT_ERP = 1,
	BT_CONSTRAINT_STOP_ERP,
	BT_CONSTRAINT_CFM,
	BT_CONSTRAINT_STOP_CFM
};

#if 1
#define btAssertConstrParams(_par) btAssert(_par)
#else
#define btAssertConstrParams(_par)
#endif

/// Forces and torques the joint applied to its bodies in the last step (impulse / time step, world frame).
ATTRIBUTE_ALIGNED16(struct)
btJointFeedback
{
	BT_DECLARE_ALIGNED_ALLOCATOR();
	btVector3 m_appliedForceBodyA;
	btVector3 m_appliedTorqueBodyA;
	btVector3 m_appliedForceBodyB;
	btVector3 m_appliedTorqueBodyB;
};

/// The base class of all joints between two rigid bodies (or one body and the world: getFixedBody()).
ATTRIBUTE_ALIGNED16(class)
btTypedConstraint : public btTypedObject
{
	int m_userConstraintType;

	union
	{
		int m_userConstraintId;
		void* m_userConstraintPtr;
	};

	btScalar m_breakingImpulseThreshold;
	bool m_isEnabled;
	bool m_needsFeedback;
	int m_overrideNumSolverIterations;

	btTypedConstraint& operator=(btTypedConstraint& other)
	{
		btAssert(0);
		(void)other;
		return *this;
	}

protected:
	btRigidBody& m_rbA;
	btRigidBody& m_rbB;
	/// The largest row impulse of the last step (see getAppliedImpulse).
	btScalar m_appliedImpulse;
	btScalar m_dbgDrawSize;
	btJointFeedback* m_jointFeedback;

	/// How strongly a motor may still push at position pos between lowLim and uppLim: 1 well inside,
	/// falling to 0 at the limit it is driving towards (so a motor does not fight its own limit).
	btScalar getMotorFactor(btScalar pos, btScalar lowLim, btScalar uppLim, btScalar vel, btScalar timeFact);

public:
	BT_DECLARE_ALIGNED_ALLOCATOR();

	/// Also drops the row impulses solvers keep to warm start the joint.
	virtual ~btTypedConstraint();
	/// A joint between rbA and the world (the fixed body).
	btTypedConstraint(btTypedConstraintType type, btRigidBody & rbA);
	btTypedConstraint(btTypedConstraintType type, btRigidBody & rbA, btRigidBody & rbB);

	/// The static body of zero mass that stands for the world in one-body joints.
	static btRigidBody& getFixedBody();

	/// How many rows the joint adds this step; nub is the number of rows without bounds.
	struct btConstraintInfo1
	{
		int m_numConstraintRows, nub;
	};

	/// Where getInfo2 writes its rows. Each pointer points at the first row's field; the next row's is
	/// rowskip scalars further on. Row i asks for J1linearAxis . vA + J1angularAxis . wA +
	/// J2linearAxis . vB + J2angularAxis . wB = m_constraintError[i] (a velocity: fps * erp * position
	/// error plus any motor target), with impulse kept in [m_lowerLimit[i], m_upperLimit[i]] and
	/// softness cfm[i].
	struct btConstraintInfo2
	{
		btScalar fps, erp;
		btScalar *m_J1linearAxis, *m_J1angularAxis;
		btScalar *m_J2linearAxis, *m_J2angularAxis;
		int rowskip;
		btScalar* m_constraintError;
		btScalar* cfm;
		btScalar *m_lowerLimit, *m_upperLimit;
		int m_numIterations;
		btScalar m_damping;
	};

	int getOverrideNumSolverIterations() const { return m_overrideNumSolverIterations; }
	/// Solve this joint with more (or fewer) iterations than the world's; -1 uses the world's.
	void setOverrideNumSolverIterations(int overrideNumIterations)
	{
		m_overrideNumSolverIterations = overrideNumIterations;
	}

	/// Legacy hooks of the old solver interface; rows come from getInfo1/getInfo2.
	virtual void buildJacobian() {}
	virtual void setupSolverConstraint(btConstraintArray & ca, int solverBodyA, int solverBodyB, btScalar timeStep)
	{
		(void)ca;
		(void)solverBodyA;
		(void)solverBodyB;
		(void)timeStep;
	}
	virtual void solveConstraintObsolete(btSolverBody & bodyA, btSolverBody & bodyB, btScalar timeStep)
	{
		(void)bodyA;
		(void)bodyB;
		(void)timeStep;
	}

	virtual void getInfo1(btConstraintInfo1 * info) = 0;
	virtual void getInfo2(btConstraintInfo2 * info) = 0;

	void internalSetAppliedImpulse(btScalar appliedImpulse) { m_appliedImpulse = appliedImpulse; }
	btScalar internalGetAppliedImpulse() { return m_appliedImpulse; }

	btScalar getBreakingImpulseThreshold() const { return m_breakingImpulseThreshold; }
	/// The joint breaks (is disabled) in the step in which one of its rows needs an impulse of at least
	/// threshold; no row ever applies more. Default: unbreakable (SIMD_INFINITY).
	void setBreakingImpulseThreshold(btScalar threshold) { m_breakingImpulseThreshold = threshold; }

	bool isEnabled() const { return m_isEnabled; }
	void setEnabled(bool enabled) { m_isEnabled = enabled; }

	const btRigidBody& getRigidBodyA() const { return m_rbA; }
	const btRigidBody& getRigidBodyB() const { return m_rbB; }
	btRigidBody& getRigidBodyA() { return m_rbA; }
	btRigidBody& getRigidBodyB() { return m_rbB; }

	int getUserConstraintType() const { return m_userConstraintType; }
	void setUserConstraintType(int userConstraintType) { m_userConstraintType = userConstraintType; }
	void setUserConstraintId(int uid) { m_userConstraintId = uid; }
	int getUserConstraintId() const { return m_userConstraintId; }
	void setUserConstraintPtr(void* ptr) { m_userConstraintPtr = ptr; }
	void* getUserConstraintPtr() { return m_userConstraintPtr; }
	int getUid() const { return m_userConstraintId; }

	bool needsFeedback() const { return m_needsFeedback; }
	/// With feedback on, the joint feedback (if set) receives the forces and torques of every step.
	void enableFeedback(bool needsFeedback) { m_needsFeedback = needsFeedback; }
	void setJointFeedback(btJointFeedback * jointFeedback) { m_jointFeedback = jointFeedback; }
	const btJointFeedback* getJointFeedback() const { return m_jointFeedback; }
	btJointFeedback* getJointFeedback() { return m_jointFeedback; }

	/// The impulse of the joint's most loaded row in the last step (impulse = force * time step). Only
	/// meaningful with feedback enabled, as in Bullet; Caliber fills it always.
	btScalar getAppliedImpulse() const
	{
		btAssert(m_needsFeedback);
		return m_appliedImpulse;
	}

	btTypedConstraintType getConstraintType() const { return btTypedConstraintType(m_objectType); }

	void setDbgDrawSize(btScalar dbgDrawSize) { m_dbgDrawSize = dbgDrawSize; }
	btScalar getDbgDrawSize() { return m_dbgDrawSize; }

	/// Sets ERP or CFM (btConstraintParams) of one axis (0..5: linear x, y, z, angular x, y, z; -1: the
	/// joint's default axes). Joints document which axes they accept.
	virtual void setParam(int num, btScalar value, int axis = -1) = 0;
	virtual btScalar getParam(int num, int axis = -1) const = 0;

	/// Bytes of the joint's data struct (btTypedConstraintData2: float or double as the build).
	virtual int calculateSerializeBufferSize() const;
	/// Writes the joint's common data (bodies, name, type, feedback, threshold, enabled) into dataBuffer
	/// and returns the struct's name; each joint type extends it with its own frames and limits.
	virtual const char* serialize(void* dataBuffer, btSerializer* serializer) const;
};

/// angleInRadians moved by whole turns into [angleLowerLimitInRadians, angleUpperLimitInRadians] when it
/// fits there, else to the turn closest to the nearer limit.
SIMD_FORCE_INLINE btScalar btAdjustAngleToLimits(btScalar angleInRadians, btScalar angleLowerLimitInRadians,
                                                 btScalar angleUpperLimitInRadians)
{
	const btScalar low = angleLowerLimitInRadians, high = angleUpperLimitInRadians;
	if (low >= high) return angleInRadians;
	// How far an angle lies outside [low, high]; of the angle and its neighbours one turn away, the one
	// nearest the range wins (the angle itself on a tie).
	struct Outside
	{
		static btScalar by(btScalar a, btScalar lo, btScalar hi) { return a < lo ? lo - a : (a > hi ? a - hi : 0); }
	};
	btScalar best = angleInRadians;
	const btScalar candidates[2] = {angleInRadians - SIMD_2_PI, angleInRadians + SIMD_2_PI};
	for (int i = 0; i < 2; ++i)
		if (Outside::by(candidates[i], low, high) < Outside::by(best, low, high)) best = candidates[i];
	return best;
}

/// A one-dimensional angular limit: a range around a centre, with softness, bias and relaxation (how
/// hard the limit corrects and how much of the bounce it lets through). Used by btHingeConstraint.
class btAngularLimit
{
	btScalar m_center, m_halfRange, m_softness, m_biasFactor, m_relaxationFactor, m_correction, m_sign;
	bool m_solveLimit;

public:
	btAngularLimit()
	    : m_center(0),
	      m_halfRange(-1),
	      m_softness(btScalar(0.9)),
	      m_biasFactor(btScalar(0.3)),
	      m_relaxationFactor(btScalar(1)),
	      m_correction(0),
	      m_sign(0),
	      m_solveLimit(false)
	{
	}

	/// Limits to [low, high] (radians); low > high frees the angle.
	void set(btScalar low, btScalar high, btScalar _softness = 0.9f, btScalar _biasFactor = 0.3f,
	         btScalar _relaxationFactor = 1.0f);

	/// Measures angle against the limit: sets getCorrection (how far past it) and getSign (+1 past
	/// the high end, -1 past the low end, 0 inside).
	void test(const btScalar angle);

	btScalar getSoftness() const { return m_softness; }
	btScalar getBiasFactor() const { return m_biasFactor; }
	btScalar getRelaxationFactor() const { return m_relaxationFactor; }
	btScalar getCorrection() const { return m_correction; }
	btScalar getSign() const { return m_sign; }
	btScalar getHalfRange() const { return m_halfRange; }
	/// The middle of the range (radians).
	btScalar getCenter() const { return m_center; }
	bool isLimit() const { return m_solveLimit; }

	/// Moves angle into the limit range (clamps to the nearer end).
	void fit(btScalar& angle) const;
	/// How far angle is past the limit (0 inside).
	btScalar getError() const;
	btScalar getLow() const;
	btScalar getHigh() const;
};

// clang-format off
/// File layout of btTypedConstraintFloatData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btTypedConstraintFloatData
{
	btRigidBodyFloatData* m_rbA;
	btRigidBodyFloatData* m_rbB;
	char* m_name;
	int m_objectType;
	int m_userConstraintType;
	int m_userConstraintId;
	int m_needsFeedback;
	float m_appliedImpulse;
	float m_dbgDrawSize;
	int m_disableCollisionsBetweenLinkedBodies;
	int m_overrideNumSolverIterations;
	float m_breakingImpulseThreshold;
	int m_isEnabled;
};

/// File layout of btTypedConstraintData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btTypedConstraintData
{
	btRigidBodyData* m_rbA;
	btRigidBodyData* m_rbB;
	char* m_name;
	int m_objectType;
	int m_userConstraintType;
	int m_userConstraintId;
	int m_needsFeedback;
	float m_appliedImpulse;
	float m_dbgDrawSize;
	int m_disableCollisionsBetweenLinkedBodies;
	int m_overrideNumSolverIterations;
	float m_breakingImpulseThreshold;
	int m_isEnabled;
};

/// File layout of btTypedConstraintDoubleData in .bullet files (Bullet's struct and field names; tools/makedna reads it).
struct btTypedConstraintDoubleData
{
	btRigidBodyDoubleData* m_rbA;
	btRigidBodyDoubleData* m_rbB;
	char* m_name;
	int m_objectType;
	int m_userConstraintType;
	int m_userConstraintId;
	int m_needsFeedback;
	double m_appliedImpulse;
	double m_dbgDrawSize;
	int m_disableCollisionsBetweenLinkedBodies;
	int m_overrideNumSolverIterations;
	double m_breakingImpulseThreshold;
	int m_isEnabled;
	char padding[4];
};

// clang-format on

#endif  // BT_TYPED_CONSTRAINT_H
