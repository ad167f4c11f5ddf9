// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <cstring>

#include "LinearMath/btMatrix3x3.h"
#include "MathTestUtil.h"

using caliber_test::kLooseTolerance;
using caliber_test::kTightTolerance;
using caliber_test::matricesNear;
using caliber_test::Random;
using caliber_test::rotationsNear;
using caliber_test::vectorsNear;

namespace
{
bool sameBits(btScalar a, btScalar b) { return std::memcmp(&a, &b, sizeof(btScalar)) == 0; }

// Entries in [-1, 1] plus 3 I: diagonally dominant, so the condition number stays below ~5 and
// inversion loses only a few bits.
btMatrix3x3 wellConditioned(Random& random)
{
	btMatrix3x3 m;
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j) m[i][j] = random.uniform(-1, 1) + (i == j ? 3 : 0);
	return m;
}

btMatrix3x3 randomSymmetric(Random& random)
{
	btMatrix3x3 m;
	for (int i = 0; i < 3; ++i)
		for (int j = i; j < 3; ++j) m[i][j] = m[j][i] = random.uniform(-2, 2);
	return m;
}
}  // namespace

TEST(Matrix3x3, SetRotationGivesAnOrthonormalMatrixWithDeterminantOne)
{
	Random random(31);
	for (int i = 0; i < 300; ++i)
	{
		const btQuaternion q = random.rotation();
		btMatrix3x3 m;
		m.setRotation(q * random.uniform(btScalar(0.5), 2));  // non-unit input is normalised
		EXPECT_TRUE(matricesNear(m * m.transpose(), btMatrix3x3::getIdentity(), kTightTolerance));
		EXPECT_NEAR(m.determinant(), 1, kTightTolerance);
	}
}

TEST(Matrix3x3, QuaternionRoundTripCoversEveryBranch)
{
	Random random(32);
	for (int i = 0; i < 1000; ++i)
	{
		// Angles up to pi reach the negative-trace branches of the conversion.
		const btQuaternion q(random.unitVector(), random.uniform(0, SIMD_PI));
		btQuaternion back;
		btMatrix3x3(q).getRotation(back);
		EXPECT_TRUE(rotationsNear(back, q, kTightTolerance));
	}
	// Half turns about each axis: trace = -1, one branch per axis.
	for (const btVector3& axis : {btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(0, 0, 1)})
	{
		const btQuaternion q(axis, SIMD_PI);
		btQuaternion back;
		btMatrix3x3(q).getRotation(back);
		EXPECT_TRUE(rotationsNear(back, q, kTightTolerance));
	}
}

TEST(Matrix3x3, InverseTimesMatrixIsIdentity)
{
	Random random(33);
	for (int i = 0; i < 300; ++i)
	{
		const btMatrix3x3 m = wellConditioned(random);
		EXPECT_TRUE(matricesNear(m * m.inverse(), btMatrix3x3::getIdentity(), kTightTolerance));
		EXPECT_TRUE(matricesNear(m.inverse() * m, btMatrix3x3::getIdentity(), kTightTolerance));
		// The adjugate is det * inverse.
		EXPECT_TRUE(matricesNear(m.adjoint(), m.inverse() * m.determinant(), kTightTolerance * 30));
	}
}

TEST(Matrix3x3, SingularInverseAssertsOrGivesZero)
{
	const btMatrix3x3 singular(1, 2, 3, 2, 4, 6, 0, 0, 1);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(singular.inverse(), "assertion failed");
#else
	btMatrix3x3 zero;
	zero.setZero();
	EXPECT_EQ(singular.inverse(), zero);
#endif
	EXPECT_EQ(singular.solve33(btVector3(1, 1, 1)), btVector3(0, 0, 0));
}

TEST(Matrix3x3, DeterminantIsMultiplicative)
{
	Random random(34);
	for (int i = 0; i < 100; ++i)
	{
		const btMatrix3x3 a = wellConditioned(random), b = wellConditioned(random);
		const btScalar expected = a.determinant() * b.determinant();
		EXPECT_NEAR((a * b).determinant(), expected, kTightTolerance * btFabs(expected) * 10);
		EXPECT_NEAR(a.transpose().determinant(), a.determinant(), kTightTolerance * btFabs(expected));
	}
	EXPECT_EQ(btMatrix3x3(2, 0, 0, 0, 3, 0, 0, 0, 4).determinant(), 24);
}

TEST(Matrix3x3, ProductsAgreeWithTheDefinition)
{
	Random random(35);
	for (int i = 0; i < 100; ++i)
	{
		const btMatrix3x3 a = wellConditioned(random), b = wellConditioned(random);
		btMatrix3x3 expected;
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c)
			{
				expected[r][c] = 0;
				for (int k = 0; k < 3; ++k) expected[r][c] += a[r][k] * b[k][c];
			}
		EXPECT_TRUE(matricesNear(a * b, expected, kTightTolerance * 10));
		EXPECT_TRUE(matricesNear(a.transposeTimes(b), a.transpose() * b, kTightTolerance * 10));
		EXPECT_TRUE(matricesNear(a.timesTranspose(b), a * b.transpose(), kTightTolerance * 10));
		btMatrix3x3 c = a;
		c *= b;
		EXPECT_EQ(c, a * b);
		const btVector3 v = random.vector();
		EXPECT_TRUE(vectorsNear(v * a, a.transpose() * v, kTightTolerance * 10));
		EXPECT_EQ(a.tdotx(v), (v * a).x());
		EXPECT_EQ(a.tdoty(v), (v * a).y());
		EXPECT_EQ(a.tdotz(v), (v * a).z());
	}
}

// The SIMD products add in the same order as the scalar formulas, so the bits agree.
TEST(Matrix3x3, ProductsAreBitIdenticalToTheScalarFormulas)
{
	Random random(36);
	for (int i = 0; i < 300; ++i)
	{
		const btMatrix3x3 a = wellConditioned(random), b = wellConditioned(random);
		const btVector3 v = random.vector(10);
		const btVector3 mv = a * v;
		for (int r = 0; r < 3; ++r)
			EXPECT_TRUE(sameBits(mv[r], a[r].x() * v.x() + a[r].y() * v.y() + a[r].z() * v.z()));
		EXPECT_EQ(mv.w(), 0);
		const btMatrix3x3 ab = a * b;
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c)
				EXPECT_TRUE(sameBits(ab[r][c], a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c]));
	}
}

TEST(Matrix3x3, RowsColumnsAndElementAccess)
{
	const btMatrix3x3 m(1, 2, 3, 4, 5, 6, 7, 8, 9);
	EXPECT_EQ(m.getRow(1), btVector3(4, 5, 6));
	EXPECT_EQ(m[2], btVector3(7, 8, 9));
	EXPECT_EQ(m.getColumn(0), btVector3(1, 4, 7));
	EXPECT_EQ(m.transpose(), btMatrix3x3(1, 4, 7, 2, 5, 8, 3, 6, 9));
	EXPECT_EQ(m.scaled(btVector3(1, 10, 100)), btMatrix3x3(1, 20, 300, 4, 50, 600, 7, 80, 900));
	EXPECT_EQ(btMatrix3x3(-1, 2, -3, 4, -5, 6, -7, 8, -9).absolute(), m);
	EXPECT_EQ(m.cofac(0, 0, 1, 1), 1 * 5 - 2 * 4);
	EXPECT_EQ(m + m, m * btScalar(2));
	btMatrix3x3 zero;
	zero.setZero();
	EXPECT_EQ(m - m, zero);
	btMatrix3x3 acc = m;
	acc += m;
	acc -= m;
	EXPECT_EQ(acc, m);
	EXPECT_EQ(btMatrix3x3(btVector3(1, 2, 3), btVector3(4, 5, 6), btVector3(7, 8, 9)), m);
}

TEST(Matrix3x3, OpenGLSubMatrixIsColumnMajorAndRoundTrips)
{
	const btMatrix3x3 m(1, 2, 3, 4, 5, 6, 7, 8, 9);
	btScalar gl[12];
	m.getOpenGLSubMatrix(gl);
	// Column 0 first: m[0][0], m[1][0], m[2][0], padding.
	EXPECT_EQ(gl[0], 1);
	EXPECT_EQ(gl[1], 4);
	EXPECT_EQ(gl[2], 7);
	EXPECT_EQ(gl[3], 0);
	EXPECT_EQ(gl[4], 2);
	EXPECT_EQ(gl[10], 9);
	btMatrix3x3 back;
	back.setFromOpenGLSubMatrix(gl);
	EXPECT_EQ(back, m);
}

TEST(Matrix3x3, EulerZYXIsRzRyRxAndRoundTrips)
{
	Random random(37);
	for (int i = 0; i < 300; ++i)
	{
		const btScalar x = random.uniform(-3, 3), y = random.uniform(-1.5, 1.5), z = random.uniform(-3, 3);
		btMatrix3x3 m;
		m.setEulerZYX(x, y, z);
		const btMatrix3x3 expected = btMatrix3x3(btQuaternion(btVector3(0, 0, 1), z)) *
		                             btMatrix3x3(btQuaternion(btVector3(0, 1, 0), y)) *
		                             btMatrix3x3(btQuaternion(btVector3(1, 0, 0), x));
		EXPECT_TRUE(matricesNear(m, expected, kTightTolerance));
		btScalar yaw, pitch, roll;
		m.getEulerZYX(yaw, pitch, roll);
		EXPECT_NEAR(yaw, z, kLooseTolerance);
		EXPECT_NEAR(pitch, y, kLooseTolerance);
		EXPECT_NEAR(roll, x, kLooseTolerance);
		// The second solution describes the same matrix.
		m.getEulerZYX(yaw, pitch, roll, 2);
		btMatrix3x3 other;
		other.setEulerZYX(roll, pitch, yaw);
		EXPECT_TRUE(matricesNear(other, m, kLooseTolerance));
	}
}

TEST(Matrix3x3, EulerYPRRoundTripsAwayFromGimbalLock)
{
	Random random(38);
	for (int i = 0; i < 300; ++i)
	{
		const btScalar yaw = random.uniform(-3, 3), pitch = random.uniform(-1.5, 1.5), roll = random.uniform(-3, 3);
		btMatrix3x3 m;
		m.setEulerYPR(yaw, pitch, roll);
		btScalar y2, p2, r2;
		m.getEulerYPR(y2, p2, r2);
		EXPECT_NEAR(y2, yaw, kLooseTolerance);
		EXPECT_NEAR(p2, pitch, kLooseTolerance);
		EXPECT_NEAR(r2, roll, kLooseTolerance);
	}
}

TEST(Matrix3x3, EulerAtGimbalLockReproducesTheMatrix)
{
	for (btScalar pitch : {SIMD_HALF_PI, -SIMD_HALF_PI})
	{
		btMatrix3x3 m;
		m.setEulerZYX(btScalar(0.3), pitch, btScalar(1.1));
		m[2].setX(pitch > 0 ? -1 : 1);  // exactly locked, as rounding may leave |m20| just below 1
		btScalar yaw, p2, roll;
		m.getEulerZYX(yaw, p2, roll);
		EXPECT_EQ(yaw, 0);
		EXPECT_EQ(p2, pitch);
		btMatrix3x3 back;
		back.setEulerZYX(roll, p2, yaw);
		EXPECT_TRUE(matricesNear(back, m, kLooseTolerance));
	}
}

TEST(Matrix3x3, DiagonalizeReconstructsTheMatrix)
{
	Random random(39);
	for (int i = 0; i < 300; ++i)
	{
		const btMatrix3x3 original = randomSymmetric(random);
		btMatrix3x3 d = original, rot;
		d.diagonalize(rot, SIMD_EPSILON, 100);
		EXPECT_TRUE(matricesNear(rot * rot.transpose(), btMatrix3x3::getIdentity(), kTightTolerance * 4));
		EXPECT_TRUE(matricesNear(rot * d * rot.transpose(), original, kTightTolerance * 8));
		// Off-diagonals are below threshold * largest diagonal element (6 is the largest possible).
		for (int r = 0; r < 3; ++r)
			for (int c = 0; c < 3; ++c)
				if (r != c)
				{
					EXPECT_LE(btFabs(d[r][c]), SIMD_EPSILON * 6);
				}
	}
	// A diagonal matrix needs no rotation; a zero matrix stops at once.
	btMatrix3x3 diag(1, 0, 0, 0, 2, 0, 0, 0, 3), rot;
	diag.diagonalize(rot, SIMD_EPSILON, 10);
	EXPECT_EQ(rot, btMatrix3x3::getIdentity());
	btMatrix3x3 zero;
	zero.setZero();
	zero.diagonalize(rot, SIMD_EPSILON, 10);
	EXPECT_EQ(rot, btMatrix3x3::getIdentity());
}

TEST(Matrix3x3, DiagonalizeTerminatesOnNaN)
{
	btMatrix3x3 m(1, BT_NAN, 0, BT_NAN, 1, 0, 0, 0, 1), rot;
	m.diagonalize(rot, SIMD_EPSILON, 1000000);  // must return at once, not spin through every step
	EXPECT_EQ(rot, btMatrix3x3::getIdentity());
}

TEST(Matrix3x3, Solve33SolvesTheSystem)
{
	Random random(40);
	for (int i = 0; i < 200; ++i)
	{
		const btMatrix3x3 m = wellConditioned(random);
		const btVector3 x = random.vector(5);
		EXPECT_TRUE(vectorsNear(m.solve33(m * x), x, kTightTolerance * 20));
	}
}

TEST(Matrix3x3, ExtractRotationRecoversTheRotationOfAStretchedMatrix)
{
	Random random(41);
	for (int i = 0; i < 100; ++i)
	{
		const btQuaternion rotation = random.rotation();
		// A = R S with S symmetric positive definite: the polar decomposition's rotation is R.
		btMatrix3x3 s;
		const btMatrix3x3 basis(random.rotation());
		const btMatrix3x3 diag(random.uniform(0.5, 2), 0, 0, 0, random.uniform(0.5, 2), 0, 0, 0,
		                       random.uniform(0.5, 2));
		s = basis * diag * basis.transpose();
		btMatrix3x3 a = btMatrix3x3(rotation) * s;
		btQuaternion q = btQuaternion::getIdentity();
		a.extractRotation(q, btScalar(1e-6), 200);
		EXPECT_TRUE(rotationsNear(q, rotation, btScalar(1e-3)));
	}
}

TEST(Matrix3x3, IdentityAndZero)
{
	btMatrix3x3 m;
	m.setIdentity();
	EXPECT_EQ(m, btMatrix3x3::getIdentity());
	const btVector3 v(1, 2, 3);
	EXPECT_EQ(m * v, v);
	m.setZero();
	EXPECT_EQ(m * v, btVector3(0, 0, 0));
}

TEST(Matrix3x3, SerializationRoundTrips)
{
	const btMatrix3x3 m(1, 2, 3, 4, 5, 6, 7, 8, 9);
	btMatrix3x3Data native;
	m.serialize(native);
	btMatrix3x3 back;
	back.deSerialize(native);
	EXPECT_EQ(back, m);
	btMatrix3x3FloatData f;
	m.serializeFloat(f);
	back.setZero();
	back.deSerializeFloat(f);
	EXPECT_EQ(back, m);
}
