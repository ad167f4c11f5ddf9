// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"

#include "BulletDynamics/ConstraintSolver/btJointWarmStart.h"

namespace
{
const btScalar kDefaultDebugDrawSize = btScalar(0.3);
}

// A joint built later at this address must not start from this joint's impulses.
btTypedConstraint::~btTypedConstraint() { caliber::forgetJoint(this); }

btRigidBody& btTypedConstraint::getFixedBody()
{
	// Zero mass and zero inertia: the solver gives it the shared static entry. Never added to a world.
	static btRigidBody fixedBody(btScalar(0), 0, 0, btVector3(0, 0, 0));
	return fixedBody;
}

btTypedConstraint::btTypedConstraint(btTypedConstraintType type, btRigidBody& rbA)
    : btTypedObject(type),
      m_userConstraintType(-1),
      m_userConstraintPtr((void*)-1),
      m_breakingImpulseThreshold(SIMD_INFINITY),
      m_isEnabled(true),
      m_needsFeedback(false),
      m_overrideNumSolverIterations(-1),
      m_rbA(rbA),
      m_rbB(getFixedBody()),
      m_appliedImpulse(btScalar(0)),
      m_dbgDrawSize(kDefaultDebugDrawSize),
      m_jointFeedback(0)
{
}

btTypedConstraint::btTypedConstraint(btTypedConstraintType type, btRigidBody& rbA, btRigidBody& rbB)
    : btTypedObject(type),
      m_userConstraintType(-1),
      m_userConstraintPtr((void*)-1),
      m_breakingImpulseThreshold(SIMD_INFINITY),
      m_isEnabled(true),
      m_needsFeedback(false),
      m_overrideNumSolverIterations(-1),
      m_rbA(rbA),
      m_rbB(rbB),
      m_appliedImpulse(btScalar(0)),
      m_dbgDrawSize(kDefaultDebugDrawSize),
      m_jointFeedback(0)
{
}

btScalar btTypedConstraint::getMotorFactor(btScalar pos, btScalar lowLim, btScalar uppLim, btScalar vel,
                                           btScalar timeFact)
{
	if (lowLim > uppLim) return btScalar(1);   // no limit: full power
	if (lowLim == uppLim) return btScalar(0);  // locked: a motor has nothing to do
	if (vel == btScalar(0) || !(timeFact > btScalar(0))) return btScalar(1);
	// How far the motor would carry pos this step, and how far the limit it heads for is.
	const btScalar stepTravel = vel / timeFact;
	const btScalar room = stepTravel > btScalar(0) ? uppLim - pos : pos - lowLim;
	if (room <= btScalar(0)) return btScalar(0);  // at or past that limit
	const btScalar travel = btFabs(stepTravel);
	return room < travel ? room / travel : btScalar(1);
}

void btAngularLimit::set(btScalar low, btScalar high, btScalar _softness, btScalar _biasFactor,
                         btScalar _relaxationFactor)
{
	m_halfRange = (high - low) * btScalar(0.5);
	m_center = btNormalizeAngle(low + m_halfRange);
	m_softness = _softness;
	m_biasFactor = _biasFactor;
	m_relaxationFactor = _relaxationFactor;
}

void btAngularLimit::test(const btScalar angle)
{
	m_correction = btScalar(0);
	m_sign = btScalar(0);
	m_solveLimit = false;
	if (m_halfRange < btScalar(0)) return;
	const btScalar deviation = btNormalizeAngle(angle - m_center);
	if (deviation < -m_halfRange)
	{
		m_solveLimit = true;
		m_correction = -m_halfRange - deviation;  // positive: the angle must grow
		m_sign = btScalar(1);
	}
	else if (deviation > m_halfRange)
	{
		m_solveLimit = true;
		m_correction = m_halfRange - deviation;  // negative: the angle must shrink
		m_sign = btScalar(-1);
	}
}

btScalar btAngularLimit::getError() const { return m_correction * m_sign; }

void btAngularLimit::fit(btScalar& angle) const
{
	if (m_halfRange <= btScalar(0)) return;
	const btScalar deviation = btNormalizeAngle(angle - m_center);
	if (deviation < -m_halfRange)
		angle = getLow();
	else if (deviation > m_halfRange)
		angle = getHigh();
}

btScalar btAngularLimit::getLow() const { return btNormalizeAngle(m_center - m_halfRange); }

btScalar btAngularLimit::getHigh() const { return btNormalizeAngle(m_center + m_halfRange); }
