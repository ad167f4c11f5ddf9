// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpringConstraint.h"

#include "BulletDynamics/ConstraintSolver/btGeneric6DofRows.h"
#include "BulletDynamics/ConstraintSolver/btJointRowUtil.h"
#include "LinearMath/btWarningHook.h"

// The spring as one row of fixed impulse per step.
//
// Each step the spring applies the impulse lambda = h F along its coordinate's (projected) row, which
// changes the coordinate's rate by K lambda, K the coordinate's effective inverse mass with the locked
// coordinates held. With F evaluated at the position the step starts from and the damping at the new rate,
//   lambda = -h (k x + d (v + K lambda))  =>  lambda = -h (k x + d v) / (1 + h d K),
// the spring part is semi-implicit Euler, like the rest of the world: it keeps the energy of an undamped
// oscillator (no numerical decay), with the period too short by (omega h)^2 / 24, and the damping part
// is implicit, so no damping coefficient can make it unstable. The explicit spring is stable only for
// omega h < 2 (omega^2 = k K); a stiffer spring takes part of its force at the step's end position,
// x + theta h (v + K lambda), with theta chosen so that theta = 0 up to omega h = sqrt 2 and beyond it
// (omega h)^2 (1 - 2 theta) = 2, inside the stability bound 4: it then loses some energy per step rather
// than blowing up.

btGeneric6DofSpringConstraint::btGeneric6DofSpringConstraint(btRigidBody& rbA, btRigidBody& rbB,
                                                             const btTransform& frameInA, const btTransform& frameInB,
                                                             bool useLinearReferenceFrameA)
    : btGeneric6DofConstraint(rbA, rbB, frameInA, frameInB, useLinearReferenceFrameA)
{
	init();
}

btGeneric6DofSpringConstraint::btGeneric6DofSpringConstraint(btRigidBody& rbB, const btTransform& frameInB,
                                                             bool useLinearReferenceFrameB)
    : btGeneric6DofConstraint(rbB, frameInB, useLinearReferenceFrameB)
{
	init();
}

void btGeneric6DofSpringConstraint::init()
{
	m_objectType = D6_SPRING_CONSTRAINT_TYPE;
	for (int i = 0; i < 6; ++i)
	{
		m_springEnabled[i] = false;
		m_equilibriumPoint[i] = btScalar(0);
		m_springStiffness[i] = btScalar(0);
		m_springDamping[i] = btScalar(0);
	}
}

namespace
{
// Spring coordinates are 0..5 (three linear, three angular); a user's index outside is reported, never used.
bool springIndexInRange(int index)
{
	const bool valid = index >= 0 && index < 6;
	if (!valid) btReportWarning("Caliber: btGeneric6DofSpringConstraint: spring index outside 0..5; ignored\n");
	btAssert(valid && "btGeneric6DofSpringConstraint: spring index must be 0..5");
	return valid;
}
}  // namespace

bool btGeneric6DofSpringConstraint::isSpringEnabled(int index) const
{
	return springIndexInRange(index) && m_springEnabled[index];
}

btScalar btGeneric6DofSpringConstraint::getStiffness(int index) const
{
	return springIndexInRange(index) ? m_springStiffness[index] : btScalar(0);
}

btScalar btGeneric6DofSpringConstraint::getDamping(int index) const
{
	return springIndexInRange(index) ? m_springDamping[index] : btScalar(0);
}

btScalar btGeneric6DofSpringConstraint::getEquilibriumPoint(int index) const
{
	return springIndexInRange(index) ? m_equilibriumPoint[index] : btScalar(0);
}

void btGeneric6DofSpringConstraint::enableSpring(int index, bool onOff)
{
	if (!springIndexInRange(index)) return;
	m_springEnabled[index] = onOff;
}

void btGeneric6DofSpringConstraint::setStiffness(int index, btScalar stiffness)
{
	if (!springIndexInRange(index)) return;
	if (!(stiffness >= btScalar(0)) || !btIsFinite(stiffness))
	{
		btReportWarning("Caliber: btGeneric6DofSpringConstraint::setStiffness: negative or non-finite; ignored\n", 0);
		return;
	}
	m_springStiffness[index] = stiffness;
}

void btGeneric6DofSpringConstraint::setDamping(int index, btScalar damping)
{
	if (!springIndexInRange(index)) return;
	if (!(damping >= btScalar(0)) || !btIsFinite(damping))
	{
		btReportWarning("Caliber: btGeneric6DofSpringConstraint::setDamping: negative or non-finite; ignored\n", 0);
		return;
	}
	m_springDamping[index] = damping;
}

void btGeneric6DofSpringConstraint::setEquilibriumPoint()
{
	calculateTransforms();
	for (int i = 0; i < 6; ++i) m_equilibriumPoint[i] = caliber::sixDofCoordinate(*this, i);
}

void btGeneric6DofSpringConstraint::setEquilibriumPoint(int index)
{
	if (!springIndexInRange(index)) return;
	calculateTransforms();
	m_equilibriumPoint[index] = caliber::sixDofCoordinate(*this, index);
}

void btGeneric6DofSpringConstraint::setEquilibriumPoint(int index, btScalar val)
{
	if (!springIndexInRange(index)) return;
	m_equilibriumPoint[index] = val;
}

void btGeneric6DofSpringConstraint::setAxis(const btVector3& axis1, const btVector3& axis2)
{
	btGeneric6DofConstraint::setAxis(axis1, axis2);
}

namespace
{
// The spring settings of one joint, as its protected arrays hold them.
struct SpringSettings
{
	const bool* enabled;
	const btScalar* equilibrium;
	const btScalar* stiffness;
	const btScalar* damping;
};

// True when coordinate index gets a spring row this step.
bool hasSpringRow(const btGeneric6DofConstraint& joint, const SpringSettings& springs, int index)
{
	return springs.enabled[index] && !caliber::sixDofIsLocked(joint, index) &&
	       (springs.stiffness[index] > btScalar(0) || springs.damping[index] > btScalar(0));
}

// The impulse coordinate index's spring applies this step (the rule at the top of this file), with
// the coordinate's rate before it and its effective inverse mass.
struct SpringImpulse
{
	btScalar impulse;
	btScalar rate;
	btScalar inverseMass;
};

SpringImpulse springImpulse(const btGeneric6DofConstraint& joint, const SpringSettings& springs, int i, btScalar h,
                            const btVector3& linVelA, const btVector3& linVelB, const btVector3& angVelA,
                            const btVector3& angVelB)
{
	const btScalar k = springs.stiffness[i], d = springs.damping[i];
	btScalar stretch = caliber::sixDofCoordinate(joint, i) - springs.equilibrium[i];
	if (i >= 3) stretch = btNormalizeAngle(stretch);
	SpringImpulse out;
	out.rate = caliber::sixDofCoordinateVelocity(joint, i, linVelA, linVelB, angVelA, angVelB);
	out.inverseMass = caliber::sixDofCoordinateInverseMass(joint, i);
	const btScalar omegaH2 = h * h * k * out.inverseMass;
	const btScalar theta = omegaH2 <= btScalar(2) ? btScalar(0) : btScalar(0.5) * (1 - btScalar(2) / omegaH2);
	const btScalar implicitRate = theta * h * k + d;  // force per unit of the step's new rate
	out.impulse = -h * (k * stretch + implicitRate * out.rate) / (1 + h * implicitRate * out.inverseMass);
	return out;
}

// Writes the spring rows from row on; returns how many.
int writeSpringRows(const btGeneric6DofConstraint& joint, const SpringSettings& springs,
                    btTypedConstraint::btConstraintInfo2* info, int row, const btVector3& linVelA,
                    const btVector3& linVelB, const btVector3& angVelA, const btVector3& angVelB)
{
	const btScalar h = btScalar(1) / info->fps;
	const int first = row;
	for (int i = 0; i < 6; ++i)
	{
		if (!hasSpringRow(joint, springs, i)) continue;
		const btScalar impulse = springImpulse(joint, springs, i, h, linVelA, linVelB, angVelA, angVelB).impulse;
		caliber::writeSixDofCoordinateRow(joint, info, row, i, btScalar(0));
		caliber::JointRow jointRow(*info, row);
		jointRow.lower() = impulse;
		jointRow.upper() = impulse;
		++row;
	}
	return row - first;
}
}  // namespace

void btGeneric6DofSpringConstraint::getInfo1(btConstraintInfo1* info)
{
	getInfo1NonVirtual(info);
	const SpringSettings springs = {m_springEnabled, m_equilibriumPoint, m_springStiffness, m_springDamping};
	for (int i = 0; i < 6; ++i) info->m_numConstraintRows += hasSpringRow(*this, springs, i) ? 1 : 0;
}

void btGeneric6DofSpringConstraint::getInfo2(btConstraintInfo2* info)
{
	const btVector3 linVelA = m_rbA.getLinearVelocity(), linVelB = m_rbB.getLinearVelocity();
	const btVector3 angVelA = m_rbA.getAngularVelocity(), angVelB = m_rbB.getAngularVelocity();
	calculateTransforms(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
	const int row = caliber::writeSixDofLimitMotorRows(*this, info, linVelA, linVelB, angVelA, angVelB);
	const SpringSettings springs = {m_springEnabled, m_equilibriumPoint, m_springStiffness, m_springDamping};
	writeSpringRows(*this, springs, info, row, linVelA, linVelB, angVelA, angVelB);
}

void btGeneric6DofSpringConstraint::internalUpdateSprings(btConstraintInfo2* info)
{
	btAssert(info && info->fps > btScalar(0) && "btGeneric6DofSpringConstraint::internalUpdateSprings: no step");
	if (!info || !(info->fps > btScalar(0)) || !btIsFinite(info->fps)) return;
	const btVector3 linVelA = m_rbA.getLinearVelocity(), linVelB = m_rbB.getLinearVelocity();
	const btVector3 angVelA = m_rbA.getAngularVelocity(), angVelB = m_rbB.getAngularVelocity();
	calculateTransforms(m_rbA.getCenterOfMassTransform(), m_rbB.getCenterOfMassTransform());
	// Called before this joint's rows exist: the coordinates' own effective masses, no locked ones held.
	caliber::forgetSixDofLockedBlock();
	const SpringSettings springs = {m_springEnabled, m_equilibriumPoint, m_springStiffness, m_springDamping};
	const btScalar h = btScalar(1) / info->fps;
	for (int i = 0; i < 6; ++i)
	{
		if (!hasSpringRow(*this, springs, i)) continue;
		// A motor that reaches the rate the spring's impulse gives, with exactly that impulse as its
		// bound, is the spring row written as a motor row.
		const SpringImpulse s = springImpulse(*this, springs, i, h, linVelA, linVelB, angVelA, angVelB);
		const btScalar targetRate = s.rate + s.inverseMass * s.impulse;
		const btScalar maxForce = btFabs(s.impulse) * info->fps;
		if (i < 3)
		{
			m_linearLimits.m_enableMotor[i] = true;
			m_linearLimits.m_targetVelocity[i] = targetRate;
			m_linearLimits.m_maxMotorForce[i] = maxForce;
		}
		else
		{
			m_angularLimits[i - 3].m_enableMotor = true;
			m_angularLimits[i - 3].m_targetVelocity = targetRate;
			m_angularLimits[i - 3].m_maxMotorForce = maxForce;
		}
	}
}
