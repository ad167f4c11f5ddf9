// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_JOINT_ROW_UTIL_H
#define CALIBER_JOINT_ROW_UTIL_H

// Writing one row of btConstraintInfo2 by name instead of by pointer arithmetic. Every joint builds its
// rows from two kinds: a linear row (the relative velocity of two anchor points along a direction) and
// an angular row (the relative angular velocity about an axis).

#include "BulletDynamics/ConstraintSolver/btJointPositionPass.h"
#include "BulletDynamics/ConstraintSolver/btTypedConstraint.h"

namespace caliber
{
// How far an anchor at arm from a body's centre moves in one step of h beyond the straight line
// h (w x arm) that a linear row sees: (R(w h) - 1) arm - h w x arm, the inward pull of turning. A row
// that ignores it lets every turning joint open by this much per step; closing it afterwards by error
// reduction or by moving the bodies costs energy (a hinge pendulum released at 60 degrees then loses
// 0.1 rad of amplitude in 20 s, or 0.35 rad with the position correction alone, against 0.0004 with
// this term).
inline btVector3 turningDrift(const btVector3& arm, const btVector3& angularVelocity, btScalar h)
{
	const btScalar speed = angularVelocity.length();
	const btScalar angle = speed * h;
	if (!(angle > btScalar(1e-7)) || !(angle < SIMD_PI)) return btVector3(0, 0, 0);
	const btVector3 axis = angularVelocity / speed;
	// Rodrigues: R arm = arm cos + (axis x arm) sin + axis (axis . arm)(1 - cos).
	const btScalar c = btCos(angle), s = btSin(angle);
	const btVector3 across = axis.cross(arm);
	const btVector3 turned = arm * c + across * s + axis * (axis.dot(arm) * (btScalar(1) - c));
	return turned - arm - across * angle;
}

// Targets of the three linear rows (x, y, z) that hold anchor A (at armA from A's centre) on anchor B:
// close the gap (B minus A) by the share erp per step, plus both anchors' turning drift over the step
// (left out in the position pass, where there is no step to drift over).
inline btVector3 linearRowTargets(const btTypedConstraint::btConstraintInfo2& info, btScalar erp, const btVector3& gap,
                                  const btVector3& armA, const btVector3& angularVelocityA, const btVector3& armB,
                                  const btVector3& angularVelocityB)
{
	if (inJointPositionPass()) return gap * (erp * info.fps);
	const btScalar h = btScalar(1) / info.fps;
	const btVector3 drift = turningDrift(armB, angularVelocityB, h) - turningDrift(armA, angularVelocityA, h);
	return (gap * erp + drift) * info.fps;
}

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
