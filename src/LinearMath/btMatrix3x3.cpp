// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btMatrix3x3.h"

void btMatrix3x3::getRotation(btQuaternion& q) const
{
	const btScalar m00 = m_el[0].x(), m01 = m_el[0].y(), m02 = m_el[0].z();
	const btScalar m10 = m_el[1].x(), m11 = m_el[1].y(), m12 = m_el[1].z();
	const btScalar m20 = m_el[2].x(), m21 = m_el[2].y(), m22 = m_el[2].z();
	const btScalar trace = m00 + m11 + m22;
	// Each branch recovers the largest of |w|, |x|, |y|, |z| from the diagonal first, then divides
	// the off-diagonal sums and differences by it: no division by a small number.
	if (trace > btScalar(0.0))
	{
		const btScalar s = btSqrt(trace + btScalar(1.0)) * btScalar(2.0);  // 4 w
		q.setValue((m21 - m12) / s, (m02 - m20) / s, (m10 - m01) / s, btScalar(0.25) * s);
	}
	else if (m00 > m11 && m00 > m22)
	{
		const btScalar s = btSqrt(btScalar(1.0) + m00 - m11 - m22) * btScalar(2.0);  // 4 x
		q.setValue(btScalar(0.25) * s, (m01 + m10) / s, (m02 + m20) / s, (m21 - m12) / s);
	}
	else if (m11 > m22)
	{
		const btScalar s = btSqrt(btScalar(1.0) + m11 - m00 - m22) * btScalar(2.0);  // 4 y
		q.setValue((m01 + m10) / s, btScalar(0.25) * s, (m12 + m21) / s, (m02 - m20) / s);
	}
	else
	{
		const btScalar s = btSqrt(btScalar(1.0) + m22 - m00 - m11) * btScalar(2.0);  // 4 z
		q.setValue((m02 + m20) / s, (m12 + m21) / s, btScalar(0.25) * s, (m10 - m01) / s);
	}
}

void btMatrix3x3::getEulerYPR(btScalar& yaw, btScalar& pitch, btScalar& roll) const
{
	unsigned int firstSolution = 1;
	getEulerZYX(yaw, pitch, roll, firstSolution);
}

void btMatrix3x3::getEulerZYX(btScalar& yaw, btScalar& pitch, btScalar& roll, unsigned int solution_number) const
{
	// For R = Rz(yaw) Ry(pitch) Rx(roll): R[2][0] = -sin(pitch), R[2][1] / R[2][2] = tan(roll) and
	// R[1][0] / R[0][0] = tan(yaw), each scaled by cos(pitch).
	const btScalar r20 = m_el[2].x();
	if (btFabs(r20) >= btScalar(1.0))
	{
		// Gimbal lock: only yaw - roll (or yaw + roll) is defined; report it all as roll with yaw = 0.
		yaw = btScalar(0.0);
		if (r20 < btScalar(0.0))
		{
			pitch = SIMD_HALF_PI;
			roll = btAtan2(m_el[0].y(), m_el[0].z());
		}
		else
		{
			pitch = -SIMD_HALF_PI;
			roll = btAtan2(-m_el[0].y(), -m_el[0].z());
		}
		return;
	}
	pitch = -btAsin(r20);
	if (solution_number != 1) pitch = SIMD_PI - pitch;
	const btScalar c = btCos(pitch);  // positive for solution 1, negative for solution 2
	roll = btAtan2(m_el[2].y() / c, m_el[2].z() / c);
	yaw = btAtan2(m_el[1].x() / c, m_el[0].x() / c);
}

void btMatrix3x3::diagonalize(btMatrix3x3& rot, btScalar threshold, int maxSteps)
{
	rot.setIdentity();
	for (int step = 0; step < maxSteps; ++step)
	{
		// Pick the largest off-diagonal element (p, q), p < q.
		int p = 0, q = 1;
		btScalar largest = btFabs(m_el[0][1]);
		if (btFabs(m_el[0][2]) > largest)
		{
			p = 0;
			q = 2;
			largest = btFabs(m_el[0][2]);
		}
		if (btFabs(m_el[1][2]) > largest)
		{
			p = 1;
			q = 2;
			largest = btFabs(m_el[1][2]);
		}
		const btScalar diagonalScale = btMax(btMax(btFabs(m_el[0][0]), btFabs(m_el[1][1])), btFabs(m_el[2][2]));
		const btScalar tolerance = diagonalScale > btScalar(0) ? threshold * diagonalScale : threshold;
		if (!(largest > tolerance)) return;  // also stops on NaN input instead of spinning

		// Jacobi rotation in the (p, q) plane that zeroes element (p, q): t = tan(angle) is the
		// smaller root of t^2 + 2 theta t - 1 = 0.
		const btScalar apq = m_el[p][q];
		const btScalar theta = (m_el[q][q] - m_el[p][p]) / (btScalar(2.0) * apq);
		const btScalar theta2 = theta * theta;
		btScalar t;
		if (btIsFinite(theta2))
			t = (theta >= btScalar(0) ? btScalar(1) : btScalar(-1)) / (btFabs(theta) + btSqrt(btScalar(1.0) + theta2));
		else
			t = btScalar(0.5) / theta;  // theta^2 overflows: the leading term of t's series in 1/theta
		const btScalar c = btScalar(1.0) / btSqrt(btScalar(1.0) + t * t);
		const btScalar s = c * t;

		m_el[p][p] -= t * apq;
		m_el[q][q] += t * apq;
		m_el[p][q] = m_el[q][p] = btScalar(0);
		const int r = 3 - p - q;
		const btScalar arp = m_el[r][p], arq = m_el[r][q];
		m_el[r][p] = m_el[p][r] = c * arp - s * arq;
		m_el[r][q] = m_el[q][r] = s * arp + c * arq;
		for (int i = 0; i < 3; ++i)
		{
			const btScalar vip = rot[i][p], viq = rot[i][q];
			rot[i][p] = c * vip - s * viq;
			rot[i][q] = s * vip + c * viq;
		}
	}
}

void btMatrix3x3::extractRotation(btQuaternion& q, btScalar tolerance, int maxIter)
{
	// Mueller, Bender, Chentanez, Macklin, "A Robust Method to Extract the Rotational Part of
	// Deformations" (2016): rotate q by the torque-like vector omega until it vanishes.
	const btMatrix3x3& a = *this;
	for (int iter = 0; iter < maxIter; ++iter)
	{
		const btMatrix3x3 r(q);
		const btVector3 torque = r.getColumn(0).cross(a.getColumn(0)) + r.getColumn(1).cross(a.getColumn(1)) +
		                         r.getColumn(2).cross(a.getColumn(2));
		const btScalar alignment = r.getColumn(0).dot(a.getColumn(0)) + r.getColumn(1).dot(a.getColumn(1)) +
		                           r.getColumn(2).dot(a.getColumn(2));
		const btVector3 omega = torque * (btScalar(1.0) / (btFabs(alignment) + tolerance));
		const btScalar w = omega.norm();
		if (!(w >= tolerance)) break;  // converged (or NaN input: keep q)
		q = btQuaternion(omega / w, w) * q;
		q.normalize();
	}
}
