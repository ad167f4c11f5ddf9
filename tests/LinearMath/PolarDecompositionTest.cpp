// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btPolarDecomposition.h"

#include <gtest/gtest.h>

#include <math.h>

#include "MathTestUtil.h"

using caliber_test::kLooseTolerance;
using caliber_test::kTightTolerance;
using caliber_test::matricesNear;
using caliber_test::Random;

namespace
{
// Q diag(d) Q^T: a symmetric matrix with eigenvalues d.
btMatrix3x3 symmetricWithEigenvalues(const btQuaternion& q, const btVector3& d)
{
	const btMatrix3x3 rotation(q);
	return rotation.scaled(d).timesTranspose(rotation);
}

bool allFinite(const btMatrix3x3& m)
{
	for (int i = 0; i < 3; ++i)
		for (int j = 0; j < 3; ++j)
			if (!btIsFinite(m[i][j])) return false;
	return true;
}

// Smallest eigenvalue of a symmetric matrix (Jacobi iteration on a copy).
btScalar smallestEigenvalue(const btMatrix3x3& symmetric)
{
	btMatrix3x3 diagonal = symmetric;
	btMatrix3x3 rotation;
	rotation.setIdentity();
	diagonal.diagonalize(rotation, SIMD_EPSILON, 64);
	return btMin(diagonal[0][0], btMin(diagonal[1][1], diagonal[2][2]));
}

// u orthogonal (u^T u = I), h exactly symmetric and positive semi-definite, u h = a. The tolerance is
// relative to the size of a.
void expectPolarFactors(const btMatrix3x3& a, const btMatrix3x3& u, const btMatrix3x3& h, btScalar tolerance)
{
	btScalar size = 0;
	for (int i = 0; i < 3; ++i) size = btMax(size, a[i].length());
	ASSERT_TRUE(allFinite(u));
	ASSERT_TRUE(allFinite(h));
	EXPECT_TRUE(matricesNear(u.transposeTimes(u), btMatrix3x3::getIdentity(), tolerance)) << "u is not orthogonal";
	EXPECT_TRUE(matricesNear(u * h, a, tolerance * btMax(size, btScalar(1)))) << "u h differs from a";
	EXPECT_TRUE(h == h.transpose()) << "h is not symmetric";
	EXPECT_GE(smallestEigenvalue(h), -tolerance * size) << "h is not positive semi-definite";
}
}  // namespace

// A = R S with R a rotation and S symmetric positive definite has the unique polar factors U = R,
// H = S. Eigenvalues of S lie in [0.1, 10], so the condition number is at most 100; the factors'
// sensitivity to rounding is about condition * SIMD_EPSILON, well inside kLooseTolerance.
TEST(PolarDecomposition, RandomRotationTimesStretchGivesRotationAndStretch)
{
	Random random(20260311);
	const btPolarDecomposition polar;
	for (int trial = 0; trial < 300; ++trial)
	{
		const btQuaternion q = random.rotation();
		const btMatrix3x3 r(q);
		const btVector3 d(random.uniform(0.1, 10), random.uniform(0.1, 10), random.uniform(0.1, 10));
		const btMatrix3x3 s = symmetricWithEigenvalues(random.rotation(), d);
		const btMatrix3x3 a = r * s;
		btMatrix3x3 u, h;
		const unsigned int iterations = polar.decompose(a, u, h);
		SCOPED_TRACE(trial);
		EXPECT_GE(iterations, 1u);
		EXPECT_LE(iterations, polar.maxIterations());
		expectPolarFactors(a, u, h, kLooseTolerance);
		EXPECT_NEAR(u.determinant(), 1, kLooseTolerance);
		EXPECT_TRUE(matricesNear(u, r, kLooseTolerance));
		EXPECT_TRUE(matricesNear(h, s, kLooseTolerance * 10));  // elements of s are up to 10
	}
}

// det(A) < 0: U is orthogonal with det -1 (a rotation times a reflection), H still positive definite.
TEST(PolarDecomposition, NegativeDeterminantGivesReflection)
{
	Random random(77);
	for (int trial = 0; trial < 100; ++trial)
	{
		const btMatrix3x3 reflection(1, 0, 0, 0, 1, 0, 0, 0, -1);
		const btMatrix3x3 r = btMatrix3x3(random.rotation()) * reflection;
		const btVector3 d(random.uniform(0.5, 2), random.uniform(0.5, 2), random.uniform(0.5, 2));
		const btMatrix3x3 a = r * symmetricWithEigenvalues(random.rotation(), d);
		btMatrix3x3 u, h;
		polarDecompose(a, u, h);
		SCOPED_TRACE(trial);
		expectPolarFactors(a, u, h, kLooseTolerance);
		EXPECT_NEAR(u.determinant(), -1, kLooseTolerance);
		EXPECT_TRUE(matricesNear(u, r, kLooseTolerance));
	}
}

// The identity is its own polar factor; the first scaled step lands on it up to rounding.
TEST(PolarDecomposition, IdentityGivesIdentityFactors)
{
	btMatrix3x3 u, h;
	const unsigned int iterations = polarDecompose(btMatrix3x3::getIdentity(), u, h);
	EXPECT_LE(iterations, 3u);
	EXPECT_TRUE(matricesNear(u, btMatrix3x3::getIdentity(), kTightTolerance));
	EXPECT_TRUE(matricesNear(h, btMatrix3x3::getIdentity(), kTightTolerance));
}

// A scaled rotation k R has U = R and H = k I, for any k the scalar type can hold: the input is
// normalised before iterating.
TEST(PolarDecomposition, ScaledRotationIsScaleIndependent)
{
	Random random(5);
	const btMatrix3x3 r(random.rotation());
	const btScalar scales[] = {btScalar(1e-30), btScalar(1e-6), btScalar(1), btScalar(1e6), btScalar(1e30)};
	for (btScalar k : scales)
	{
		btMatrix3x3 u, h;
		polarDecompose(r * k, u, h);
		SCOPED_TRACE(k);
		EXPECT_TRUE(matricesNear(u, r, kLooseTolerance));
		EXPECT_TRUE(matricesNear(h * (1 / k), btMatrix3x3::getIdentity(), kLooseTolerance));
	}
}

// Rank 2 and rank 1 input: U is still a rotation (det +1), H symmetric positive semi-definite and
// U H = A. The eigenvector fallback is accurate to a few hundred SIMD_EPSILON for these well
// separated singular values.
TEST(PolarDecomposition, SingularInputGivesRotationWithoutNaN)
{
	Random random(31);
	for (int trial = 0; trial < 100; ++trial)
	{
		const btMatrix3x3 left(random.rotation());
		const btMatrix3x3 right(random.rotation());
		const btVector3 singularValues = (trial % 2 == 0) ? btVector3(3, 1, 0) : btVector3(2, 0, 0);
		const btMatrix3x3 a = left.scaled(singularValues).timesTranspose(right);
		btMatrix3x3 u, h;
		const unsigned int iterations = polarDecompose(a, u, h);
		SCOPED_TRACE(trial);
		EXPECT_EQ(iterations, 0u);  // the fallback, not Newton
		expectPolarFactors(a, u, h, kLooseTolerance);
		EXPECT_NEAR(u.determinant(), 1, kLooseTolerance);
	}
}

// The zero matrix and non-finite input: U = identity, H = zero, no NaN.
TEST(PolarDecomposition, ZeroAndNonFiniteInputGiveIdentityAndZero)
{
	btMatrix3x3 zero;
	zero.setZero();
	btMatrix3x3 withNaN = btMatrix3x3::getIdentity();
	withNaN[1][2] = btScalar(NAN);
	btMatrix3x3 withInfinity = btMatrix3x3::getIdentity();
	withInfinity[0][0] = SIMD_INFINITY * 2;
	const btMatrix3x3 inputs[] = {zero, withNaN, withInfinity};
	for (const btMatrix3x3& a : inputs)
	{
		btMatrix3x3 u, h;
		EXPECT_EQ(polarDecompose(a, u, h), 0u);
		EXPECT_TRUE(u == btMatrix3x3::getIdentity());
		EXPECT_TRUE(h == zero);
	}
}

// Nearly singular input (smallest singular value 1e-3 of the largest) still takes the Newton path in
// both precisions and gives accurate factors.
TEST(PolarDecomposition, NearlySingularInputConverges)
{
	Random random(8);
	const btMatrix3x3 left(random.rotation());
	const btMatrix3x3 right(random.rotation());
	const btMatrix3x3 a = left.scaled(btVector3(1, btScalar(0.5), btScalar(1e-3))).timesTranspose(right);
	btMatrix3x3 u, h;
	const unsigned int iterations = polarDecompose(a, u, h);
	EXPECT_GE(iterations, 1u);
	EXPECT_LT(iterations, btPolarDecomposition::DEFAULT_MAX_ITERATIONS);
	expectPolarFactors(a, u, h, kLooseTolerance);
	EXPECT_TRUE(matricesNear(u, left.timesTranspose(right), kLooseTolerance));
}

// The step limit is honoured and reported; a single step still gives finite output.
TEST(PolarDecomposition, MaxIterationsIsHonoured)
{
	const btPolarDecomposition oneStep(btPolarDecomposition::DEFAULT_TOLERANCE, 1);
	EXPECT_EQ(oneStep.maxIterations(), 1u);
	EXPECT_EQ(btPolarDecomposition().maxIterations(), btPolarDecomposition::DEFAULT_MAX_ITERATIONS);
	const btMatrix3x3 a(2, 1, 0, 0, 3, 1, 1, 0, 4);
	btMatrix3x3 u, h;
	EXPECT_EQ(oneStep.decompose(a, u, h), 1u);
	EXPECT_TRUE(allFinite(u));
	EXPECT_TRUE(allFinite(h));
}
