// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_TESTS_JOINT_TEST_UTIL_H
#define CALIBER_TESTS_JOINT_TEST_UTIL_H

#include <cmath>
#include <vector>

#include "../Dynamics/DynamicsWorldTestUtil.h"

namespace caliber_test
{
/// The exact period of a pendulum of equivalent length L released from rest at amplitude theta0:
/// T = 2 pi sqrt(L / g) / AGM(1, cos(theta0 / 2)) (the complete elliptic integral through the
/// arithmetic-geometric mean, which converges quadratically).
inline double exactPendulumPeriod(double L, double g, double theta0)
{
	double a = 1.0, b = std::cos(theta0 / 2.0);
	for (int i = 0; i < 8; ++i)
	{
		const double an = 0.5 * (a + b);
		b = std::sqrt(a * b);
		a = an;
	}
	return 2.0 * M_PI * std::sqrt(L / g) / a;
}

/// Times (interpolated between steps) at which x(t) crosses zero going the same way as the first
/// crossing; their spacing is the period.
class CrossingTimer
{
public:
	void sample(double t, double x)
	{
		if (m_started && ((m_last < 0) != (x < 0)))
		{
			const double tc = m_lastT + (t - m_lastT) * (0 - m_last) / (x - m_last);
			const bool rising = x > m_last;
			if (m_crossings.empty()) m_firstRising = rising;
			if (rising == m_firstRising) m_crossings.push_back(tc);
		}
		m_started = true;
		m_last = x;
		m_lastT = t;
	}
	/// Mean period over the recorded crossings (0 if fewer than two).
	double period() const
	{
		if (m_crossings.size() < 2) return 0;
		return (m_crossings.back() - m_crossings.front()) / double(m_crossings.size() - 1);
	}

private:
	bool m_started = false, m_firstRising = false;
	double m_last = 0, m_lastT = 0;
	std::vector<double> m_crossings;
};

/// Distance between the world positions of a pivot given in A's and in B's centre-of-mass frames.
inline btScalar pivotGap(const btRigidBody& a, const btVector3& pivotInA, const btRigidBody& b,
                         const btVector3& pivotInB)
{
	return (a.getCenterOfMassTransform()(pivotInA) - b.getCenterOfMassTransform()(pivotInB)).length();
}
}  // namespace caliber_test

#endif  // CALIBER_TESTS_JOINT_TEST_UTIL_H
