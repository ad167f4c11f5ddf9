// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_ROW_UTIL_H
#define CALIBER_JOINT_ROW_UTIL_H

// Writing one row of btConstraintInfo2 by name instead of by pointer arithmetic. Every joint builds its
// rows from two kinds: a linear row (the relative velocity of two anchor points along a direction) and
// an angular row (the relative angular velocity about an axis).

#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"

namespace caliber
{
class JointRow
{
public:
	JointRow(btTypedConstraint::btConstraintInfo2& info, int row) : m_info(info), m_offset(row * info.rowskip) {}

	// vA + wA x armA - vB - wB x armB, along direction.
	void setLinear(const btVector3& direction, const btVector3& armA, const btVector3& armB)
	{
		write(m_info.m_J1linearAxis, direction);
		write(m_info.m_J1angularAxis, armA.cross(direction));
		if (m_info.m_J2linearAxis) write(m_info.m_J2linearAxis, -direction);
		write(m_info.m_J2angularAxis, -armB.cross(direction));
	}
	// wA - wB, about axis.
	void setAngular(const btVector3& axis)
	{
		write(m_info.m_J1angularAxis, axis);
		write(m_info.m_J2angularAxis, -axis);
	}

	btScalar& error() { return m_info.m_constraintError[m_offset]; }
	btScalar& cfm() { return m_info.cfm[m_offset]; }
	btScalar& lower() { return m_info.m_lowerLimit[m_offset]; }
	btScalar& upper() { return m_info.m_upperLimit[m_offset]; }

private:
	void write(btScalar* base, const btVector3& v)
	{
		btScalar* p = base + m_offset;
		p[0] = v.x();
		p[1] = v.y();
		p[2] = v.z();
	}

	btTypedConstraint::btConstraintInfo2& m_info;
	int m_offset;
};
}  // namespace caliber

#endif  // CALIBER_JOINT_ROW_UTIL_H
