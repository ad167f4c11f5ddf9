// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SOLVER_BODY_H
#define BT_SOLVER_BODY_H

#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

class btRigidBody;

/// The solver's copy of one body: its velocities at the start of the solve, the velocity changes the
/// solver has applied so far (delta), the split-impulse push and turn velocities, and what the solver
/// needs of the mass (inverse mass per axis, already scaled by the linear factor; the world inverse
/// inertia lives in the rows, premultiplied). Static bodies share one entry with zero inverse mass.
ATTRIBUTE_ALIGNED16(struct)
btSolverBody
{
	BT_DECLARE_ALIGNED_ALLOCATOR();

	// The four fields the row kernel reads and writes come first: one 64-byte cache line.
	btVector3 m_deltaLinearVelocity;
	btVector3 m_deltaAngularVelocity;
	btVector3 m_angularFactor;
	btVector3 m_invMass;
	btVector3 m_linearFactor;
	btTransform m_worldTransform;
	btVector3 m_pushVelocity;
	btVector3 m_turnVelocity;
	btVector3 m_linearVelocity;
	btVector3 m_angularVelocity;
	/// Velocity changes from external forces over the step (Caliber's world applies forces before the
	/// solve, so these stay zero there; kept for solvers fed by other callers).
	btVector3 m_externalForceImpulse;
	btVector3 m_externalTorqueImpulse;
	/// The body this entry stands for (0 for the shared static entry).
	btRigidBody* m_originalBody;

	/// Velocity of the point at rel_pos from the centre of mass, delta included.
	btVector3 getVelocityInLocalPointNoDelta(const btVector3& rel_pos) const
	{
		return m_linearVelocity + m_externalForceImpulse + (m_angularVelocity + m_externalTorqueImpulse).cross(rel_pos);
	}
	/// Velocity of the point at rel_pos including the solver's changes so far.
	btVector3 getVelocityInLocalPointObsolete(const btVector3& rel_pos) const
	{
		return m_linearVelocity + m_deltaLinearVelocity + (m_angularVelocity + m_deltaAngularVelocity).cross(rel_pos);
	}
	btVector3 getAngularVelocity() const { return m_angularVelocity + m_deltaAngularVelocity; }

	const btVector3& getDeltaLinearVelocity() const { return m_deltaLinearVelocity; }
	const btVector3& getDeltaAngularVelocity() const { return m_deltaAngularVelocity; }
	const btVector3& getPushVelocity() const { return m_pushVelocity; }
	const btVector3& getTurnVelocity() const { return m_turnVelocity; }
	const btTransform& getWorldTransform() const { return m_worldTransform; }

	/// Adds impulseMagnitude along a row: linearComponent is the row's direction (the inverse mass is
	/// applied here), angularComponent the row's I^-1 (r x n), already premultiplied.
	SIMD_FORCE_INLINE void applyImpulse(const btVector3& linearComponent, const btVector3& angularComponent,
	                                    btScalar impulseMagnitude)
	{
		m_deltaLinearVelocity += linearComponent * m_invMass * impulseMagnitude;
		m_deltaAngularVelocity += angularComponent * (impulseMagnitude * m_angularFactor);
	}
	/// The same for the split-impulse velocities.
	SIMD_FORCE_INLINE void internalApplyPushImpulse(const btVector3& linearComponent, const btVector3& angularComponent,
	                                                btScalar impulseMagnitude)
	{
		m_pushVelocity += linearComponent * m_invMass * impulseMagnitude;
		m_turnVelocity += angularComponent * (impulseMagnitude * m_angularFactor);
	}
};

#endif  // BT_SOLVER_BODY_H
