// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_JACOBIAN_ENTRY_H
#define BT_JACOBIAN_ENTRY_H

/// btJacobianEntry: one row of a constraint Jacobian between two rigid bodies, with its effective-mass
/// denominator, in the form Bullet 2 exposes (Bullet's older joints and vehicles kept these per row).
/// The angular parts live in each body's principal inertia frame (world2A / world2B turn world vectors
/// into it), where the inverse inertia is the diagonal vector inertiaInv; angular velocities given to
/// getRelativeVelocity must be in those frames too. Caliber's own solver does not use it.

#include "LinearMath/btMatrix3x3.h"
#include "LinearMath/btVector3.h"

class btJacobianEntry;
namespace caliber
{
/// Fills the inverse-inertia products and the diagonal from the Jacobian's parts.
inline void finishJacobianEntry(btJacobianEntry& entry, const btVector3& inertiaInvA, btScalar massInvA,
                                const btVector3& inertiaInvB, btScalar massInvB);
}  // namespace caliber

ATTRIBUTE_ALIGNED16(class)
btJacobianEntry
{
public:
	btJacobianEntry() : m_Adiag(0) {}

	/// A linear constraint along the unit jointAxis between points rel_pos1 and rel_pos2 (from each body's
	/// centre of mass, in world space) of two bodies.
	btJacobianEntry(const btMatrix3x3& world2A, const btMatrix3x3& world2B, const btVector3& rel_pos1,
	                const btVector3& rel_pos2, const btVector3& jointAxis, const btVector3& inertiaInvA,
	                const btScalar massInvA, const btVector3& inertiaInvB, const btScalar massInvB)
	    : m_linearJointAxis(jointAxis)
	{
		m_aJ = world2A * rel_pos1.cross(m_linearJointAxis);
		m_bJ = world2B * rel_pos2.cross(-m_linearJointAxis);
		caliber::finishJacobianEntry(*this, inertiaInvA, massInvA, inertiaInvB, massInvB);
	}

	/// An angular constraint about the world jointAxis between two bodies.
	btJacobianEntry(const btVector3& jointAxis, const btMatrix3x3& world2A, const btMatrix3x3& world2B,
	                const btVector3& inertiaInvA, const btVector3& inertiaInvB)
	    : m_linearJointAxis(btScalar(0), btScalar(0), btScalar(0))
	{
		m_aJ = world2A * jointAxis;
		m_bJ = world2B * -jointAxis;
		caliber::finishJacobianEntry(*this, inertiaInvA, btScalar(0), inertiaInvB, btScalar(0));
	}

	/// An angular constraint whose axis is given in each body's inertia frame already.
	btJacobianEntry(const btVector3& axisInA, const btVector3& axisInB, const btVector3& inertiaInvA,
	                const btVector3& inertiaInvB)
	    : m_linearJointAxis(btScalar(0), btScalar(0), btScalar(0)), m_aJ(axisInA), m_bJ(-axisInB)
	{
		caliber::finishJacobianEntry(*this, inertiaInvA, btScalar(0), inertiaInvB, btScalar(0));
	}

	/// A linear constraint on one body (against the static world): rel_pos2 is not used.
	btJacobianEntry(const btMatrix3x3& world2A, const btVector3& rel_pos1, const btVector3& rel_pos2,
	                const btVector3& jointAxis, const btVector3& inertiaInvA, const btScalar massInvA)
	    : m_linearJointAxis(jointAxis)
	{
		(void)rel_pos2;
		m_aJ = world2A * rel_pos1.cross(jointAxis);
		m_bJ = btVector3(btScalar(0), btScalar(0), btScalar(0));
		caliber::finishJacobianEntry(*this, inertiaInvA, massInvA, btVector3(btScalar(0), btScalar(0), btScalar(0)),
		                             btScalar(0));
	}

	/// J M^-1 J^T: the inverse of the row's effective mass.
	btScalar getDiagonal() const { return m_Adiag; }

	/// J M^-1 jacB^T for two rows on the same single body (A): how an impulse of one changes the other.
	btScalar getNonDiagonal(const btJacobianEntry& jacB, const btScalar massInvA) const
	{
		return massInvA * m_linearJointAxis.dot(jacB.m_linearJointAxis) + m_0MinvJt.dot(jacB.m_aJ);
	}

	/// J M^-1 jacB^T for two rows on the same pair of bodies.
	btScalar getNonDiagonal(const btJacobianEntry& jacB, const btScalar massInvA, const btScalar massInvB) const
	{
		// Both bodies' linear parts are +-axis, so their products have the same sign.
		const btScalar linear = (massInvA + massInvB) * m_linearJointAxis.dot(jacB.m_linearJointAxis);
		return linear + m_0MinvJt.dot(jacB.m_aJ) + m_1MinvJt.dot(jacB.m_bJ);
	}

	/// J v: the velocity of A relative to B along the row (angular velocities in the inertia frames).
	btScalar getRelativeVelocity(const btVector3& linvelA, const btVector3& angvelA, const btVector3& linvelB,
	                             const btVector3& angvelB)
	{
		return m_linearJointAxis.dot(linvelA - linvelB) + angvelA.dot(m_aJ) + angvelB.dot(m_bJ);
	}

	btVector3 m_linearJointAxis;
	btVector3 m_aJ;
	btVector3 m_bJ;
	btVector3 m_0MinvJt;
	btVector3 m_1MinvJt;
	btScalar m_Adiag;
};

inline void caliber::finishJacobianEntry(btJacobianEntry& entry, const btVector3& inertiaInvA, btScalar massInvA,
                                         const btVector3& inertiaInvB, btScalar massInvB)
{
	entry.m_0MinvJt = inertiaInvA * entry.m_aJ;
	entry.m_1MinvJt = inertiaInvB * entry.m_bJ;
	entry.m_Adiag = massInvA + entry.m_0MinvJt.dot(entry.m_aJ) + massInvB + entry.m_1MinvJt.dot(entry.m_bJ);
	// A row that nothing can move (both bodies static, or a zero axis) has no effective mass.
	btAssert(entry.m_Adiag > btScalar(0));
}

#endif  // BT_JACOBIAN_ENTRY_H
