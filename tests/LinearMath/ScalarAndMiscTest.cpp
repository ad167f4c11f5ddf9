// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btScalar.h"
#include "LinearMath/btMinMax.h"
#include "LinearMath/btRandom.h"
#include "LinearMath/btDefaultMotionState.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#include <gtest/gtest.h>

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmath>
#include <limits>
#include <vector>

#include "MathTestUtil.h"

using caliber_test::kTightTolerance;
using caliber_test::Random;

// ---- versions and precision --------------------------------------------------------------------

TEST(ScalarVersion, ReportsBullet289)
{
	EXPECT_EQ(BT_BULLET_VERSION, 289);
	EXPECT_EQ(btGetVersion(), 289);
}

TEST(ScalarPrecision, SizeOfScalarFollowsPrecisionMacro)
{
#ifdef BT_USE_DOUBLE_PRECISION
	EXPECT_EQ(sizeof(btScalar), sizeof(double));
	EXPECT_EQ(btIsDoublePrecision(), 1);
	EXPECT_EQ(SIMD_EPSILON, DBL_EPSILON);
	EXPECT_EQ(SIMD_INFINITY, DBL_MAX);
#else
	EXPECT_EQ(sizeof(btScalar), sizeof(float));
	EXPECT_EQ(btIsDoublePrecision(), 0);
	EXPECT_EQ(SIMD_EPSILON, FLT_EPSILON);
	EXPECT_EQ(SIMD_INFINITY, FLT_MAX);
#endif
	EXPECT_EQ(SIMD_EPSILON, std::numeric_limits<btScalar>::epsilon());
}

TEST(ScalarPrecision, PrecisionMarkerReturnsSizeOfScalar)
{
	// The library defines the marker only for its own precision; this links only when the test and the
	// library agree, and the value says which one it is.
	EXPECT_EQ(btCaliberPrecisionMarker(btScalar(0)), int(sizeof(btScalar)));
}

// ---- constants --------------------------------------------------------------------------------

TEST(ScalarConstants, ValuesAreCorrectlyRounded)
{
	const double pi = 3.14159265358979323846;
	// Each constant is the literal (or an exact product of it by a power of two) rounded once: equal to
	// the correctly rounded value, or within one rounding (eps relative) for the derived ratios.
	EXPECT_EQ(SIMD_PI, btScalar(pi));
	EXPECT_EQ(SIMD_2_PI, btScalar(2 * pi));
	EXPECT_EQ(SIMD_HALF_PI, btScalar(pi / 2));
	EXPECT_NEAR(SIMD_RADS_PER_DEG, btScalar(pi / 180), SIMD_EPSILON * btScalar(pi / 180));
	EXPECT_NEAR(SIMD_DEGS_PER_RAD, btScalar(180 / pi), SIMD_EPSILON * btScalar(180 / pi));
	EXPECT_EQ(SIMDSQRT12, btScalar(sqrt(0.5)));
	EXPECT_EQ(BT_ONE, btScalar(1));
	EXPECT_EQ(BT_ZERO, btScalar(0));
	EXPECT_EQ(BT_TWO, btScalar(2));
	EXPECT_EQ(BT_HALF, btScalar(0.5));
	EXPECT_TRUE(std::isinf(BT_INFINITY) && BT_INFINITY > 0);
	EXPECT_TRUE(std::isnan(BT_NAN));
	EXPECT_GT(BT_LARGE_FLOAT, btScalar(1e17));
	EXPECT_LT(BT_LARGE_FLOAT, SIMD_INFINITY);
}

// ---- math wrappers ----------------------------------------------------------------------------

TEST(ScalarMath, AcosAndAsinClampSlightlyOutOfRangeArguments)
{
	// Rounding can push a cosine just past +-1; the clamped functions must not return NaN.
	const btScalar above = btScalar(1) + btScalar(4) * SIMD_EPSILON;
	EXPECT_EQ(btAcos(above), btScalar(0));
	EXPECT_NEAR(btAcos(-above), SIMD_PI, SIMD_EPSILON * 4);  // acos(-1) rounded once
	EXPECT_NEAR(btAsin(above), SIMD_HALF_PI, SIMD_EPSILON * 4);
	EXPECT_NEAR(btAsin(-above), -SIMD_HALF_PI, SIMD_EPSILON * 4);
	EXPECT_EQ(btAcos(btScalar(1e10)), btScalar(0));
	EXPECT_FALSE(std::isnan(btAsin(btScalar(-1e10))));
	// Inside the range they are the plain functions.
	for (int i = -10; i <= 10; ++i)
	{
		const btScalar x = btScalar(i) / 10;
		EXPECT_EQ(btAcos(x), btScalar(acos(x))) << x;
		EXPECT_EQ(btAsin(x), btScalar(asin(x))) << x;
	}
}

TEST(ScalarMath, Atan2FastIsWithinDocumentedError)
{
	// Documented: absolute error below 2e-5 rad, exactly 0 at the origin. The polynomial's own error is
	// about 1e-5; evaluating it in single precision adds a few eps (~1e-6 at most), so the documented bound
	// holds in both precisions. Checked on a grid of 3601 directions at three very different radii.
	const btScalar kDocumentedError = btScalar(2e-5);
	btScalar worst = 0;
	btScalar worstAngle = 0, worstRadius = 0;
	const btScalar radii[] = {btScalar(1e-3), btScalar(1), btScalar(250)};
	for (btScalar radius : radii)
	{
		for (int i = -1800; i <= 1800; ++i)
		{
			const btScalar angle = btScalar(i) * SIMD_PI / btScalar(1800);
			const btScalar y = radius * btSin(angle), x = radius * btCos(angle);
			// The difference as an angle: +pi and -pi are the same direction.
			btScalar error = btFabs(btAtan2Fast(y, x) - btAtan2(y, x));
			error = btMin(error, btScalar(SIMD_2_PI - error));
			if (error > worst)
			{
				worst = error;
				worstAngle = angle;
				worstRadius = radius;
			}
		}
	}
	EXPECT_LE(worst, kDocumentedError) << "worst error " << worst << " rad at angle " << worstAngle << ", radius "
	                                   << worstRadius;
	// The axes and diagonals, including both signs of zero on the negative x axis.
	EXPECT_NEAR(btAtan2Fast(1, 1), SIMD_PI / 4, kDocumentedError);
	EXPECT_NEAR(btAtan2Fast(1, 0), SIMD_HALF_PI, kDocumentedError);
	EXPECT_NEAR(btAtan2Fast(-1, 0), -SIMD_HALF_PI, kDocumentedError);
	EXPECT_NEAR(btAtan2Fast(-1, -1), btScalar(-0.75) * SIMD_PI, kDocumentedError);
	EXPECT_NEAR(btAtan2Fast(0, -1), SIMD_PI, kDocumentedError);
	EXPECT_NEAR(btFabs(btAtan2Fast(-btScalar(0), -1)), SIMD_PI, kDocumentedError);
	EXPECT_NEAR(btAtan2Fast(0, 1), btScalar(0), kDocumentedError);
	EXPECT_EQ(btAtan2Fast(0, 0), btScalar(0)) << "documented: exactly 0 at the origin";
	EXPECT_EQ(btAtan2Fast(-btScalar(0), -btScalar(0)), btScalar(0));
	// Tiny and huge arguments (no overflow or underflow in the ratio).
	EXPECT_NEAR(btAtan2Fast(btScalar(1e-30), btScalar(1e-30)), SIMD_PI / 4, kDocumentedError);
	EXPECT_NEAR(btAtan2Fast(btScalar(1e30), btScalar(-1e30)), btScalar(0.75) * SIMD_PI, kDocumentedError);
}

TEST(ScalarMath, FuzzyZeroIsStrictlyBelowEpsilon)
{
	EXPECT_TRUE(btFuzzyZero(0));
	EXPECT_TRUE(btFuzzyZero(-btScalar(0)));
	EXPECT_TRUE(btFuzzyZero(SIMD_EPSILON * btScalar(0.5)));
	EXPECT_TRUE(btFuzzyZero(-SIMD_EPSILON * btScalar(0.5)));
	EXPECT_FALSE(btFuzzyZero(SIMD_EPSILON));
	EXPECT_FALSE(btFuzzyZero(-SIMD_EPSILON));
	EXPECT_FALSE(btFuzzyZero(1));
}

TEST(ScalarMath, EqualMeansWithinEpsilonOfZero)
{
	// Bullet's meaning: btEqual(a, eps) is |a| <= eps (the closed interval).
	const btScalar eps = btScalar(0.125);
	EXPECT_TRUE(btEqual(0, eps));
	EXPECT_TRUE(btEqual(eps, eps));
	EXPECT_TRUE(btEqual(-eps, eps));
	EXPECT_TRUE(btEqual(btScalar(0.1), eps));
	EXPECT_FALSE(btEqual(btScalar(0.13), eps));
	EXPECT_FALSE(btEqual(btScalar(-0.13), eps));
	EXPECT_FALSE(btEqual(btScalar(1), btScalar(0)));
	EXPECT_TRUE(btEqual(btScalar(0), btScalar(0)));
}

TEST(ScalarMath, GreaterEqualMeansAboveEpsilon)
{
	// Bullet's meaning: btGreaterEqual(a, eps) is a > eps.
	const btScalar eps = btScalar(0.125);
	EXPECT_TRUE(btGreaterEqual(btScalar(0.25), eps));
	EXPECT_FALSE(btGreaterEqual(eps, eps));
	EXPECT_FALSE(btGreaterEqual(0, eps));
	EXPECT_FALSE(btGreaterEqual(btScalar(-1), eps));
	EXPECT_TRUE(btGreaterEqual(btScalar(-0.1), btScalar(-0.125)));
}

TEST(ScalarMath, FselSelectsOnSignOfCondition)
{
	EXPECT_EQ(btFsel(btScalar(2), 1, -1), btScalar(1));
	EXPECT_EQ(btFsel(btScalar(0), 1, -1), btScalar(1)) << "0 counts as non-negative";
	EXPECT_EQ(btFsel(-btScalar(0), 1, -1), btScalar(1)) << "-0 counts as non-negative";
	EXPECT_EQ(btFsel(-SIMD_EPSILON, 1, -1), btScalar(-1));
	EXPECT_EQ(btFsel(-SIMD_INFINITY, 1, -1), btScalar(-1));
}

TEST(ScalarMath, RadiansAndDegreesRoundTrip)
{
	EXPECT_NEAR(btRadians(180), SIMD_PI, SIMD_PI * SIMD_EPSILON * 2);
	EXPECT_NEAR(btDegrees(SIMD_HALF_PI), btScalar(90), btScalar(90) * SIMD_EPSILON * 2);
	EXPECT_EQ(btRadians(0), btScalar(0));
	Random rng(901);
	for (int i = 0; i < 1000; ++i)
	{
		const btScalar degrees = rng.uniform(-720, 720);
		// Two products by constants, each rounded (plus the constants' own rounding): 4 eps relative.
		EXPECT_NEAR(btDegrees(btRadians(degrees)), degrees, btFabs(degrees) * SIMD_EPSILON * 4) << degrees;
		const btScalar radians = rng.uniform(-10, 10);
		EXPECT_NEAR(btRadians(btDegrees(radians)), radians, btFabs(radians) * SIMD_EPSILON * 4) << radians;
		EXPECT_NEAR(btRadians(degrees), btScalar(double(degrees) * 3.14159265358979323846 / 180),
		            btFabs(btRadians(degrees)) * SIMD_EPSILON * 2)
		    << degrees;
	}
}

TEST(ScalarMath, NormalizeAngleWrapsIntoMinusPiToPi)
{
	EXPECT_EQ(btNormalizeAngle(0), btScalar(0));
	EXPECT_EQ(btNormalizeAngle(SIMD_PI), SIMD_PI);
	EXPECT_EQ(btNormalizeAngle(-SIMD_PI), -SIMD_PI);
	EXPECT_NEAR(btNormalizeAngle(btScalar(1.5) * SIMD_PI), -SIMD_HALF_PI, kTightTolerance);
	EXPECT_NEAR(btNormalizeAngle(btScalar(-1.5) * SIMD_PI), SIMD_HALF_PI, kTightTolerance);
	EXPECT_NEAR(btNormalizeAngle(SIMD_2_PI), btScalar(0), kTightTolerance);
	Random rng(902);
	for (int i = 0; i < 2000; ++i)
	{
		const btScalar angle = rng.uniform(-100, 100);
		const btScalar wrapped = btNormalizeAngle(angle);
		EXPECT_GE(wrapped, -SIMD_PI) << angle;
		EXPECT_LE(wrapped, SIMD_PI) << angle;
		// The same direction: fmod is exact, but SIMD_2_PI is 2 pi rounded (relative eps / 2), and that
		// error is taken |angle| / 2 pi + 1 times; (|angle| + 4 pi) eps bounds it, plus sin/cos rounding.
		const btScalar tolerance = (btFabs(angle) + btScalar(4) * SIMD_PI) * SIMD_EPSILON + kTightTolerance;
		EXPECT_NEAR(btSin(wrapped), btScalar(sin(double(angle))), tolerance) << angle;
		EXPECT_NEAR(btCos(wrapped), btScalar(cos(double(angle))), tolerance) << angle;
	}
}

// ---- small helpers ----------------------------------------------------------------------------

TEST(ScalarHelpers, SwapExchangesValues)
{
	int a = 1, b = 2;
	btSwap(a, b);
	EXPECT_EQ(a, 2);
	EXPECT_EQ(b, 1);
	btVector3 u(1, 2, 3), v(4, 5, 6);
	btSwap(u, v);
	EXPECT_EQ(u, btVector3(4, 5, 6));
	EXPECT_EQ(v, btVector3(1, 2, 3));
}

TEST(ScalarHelpers, SelectPicksByCondition)
{
	EXPECT_EQ(btSelect(0u, 5u, 7u), 7u);
	EXPECT_EQ(btSelect(1u, 5u, 7u), 5u);
	EXPECT_EQ(btSelect(0x80000000u, 5u, 7u), 5u) << "any non-zero condition";
	EXPECT_EQ(btSelect(0u, 0xffffffffu, 0u), 0u);
	EXPECT_EQ(btSelect(3u, -5, 9), -5);
	EXPECT_EQ(btSelect(0u, -5, 9), 9);
	EXPECT_EQ(btSelect(2u, 1.5f, -2.5f), 1.5f);
	EXPECT_EQ(btSelect(0u, 1.5f, -2.5f), -2.5f);
}

TEST(ScalarHelpers, IsNegativeAndIsFinite)
{
	EXPECT_EQ(btIsNegative(btScalar(-1)), 1);
	EXPECT_EQ(btIsNegative(-SIMD_EPSILON), 1);
	EXPECT_EQ(btIsNegative(btScalar(0)), 0);
	EXPECT_EQ(btIsNegative(-btScalar(0)), 0) << "-0 is not below 0";
	EXPECT_EQ(btIsNegative(btScalar(2)), 0);

	EXPECT_TRUE(btIsFinite(0));
	EXPECT_TRUE(btIsFinite(-1e10));
	EXPECT_TRUE(btIsFinite(SIMD_INFINITY)) << "SIMD_INFINITY is the largest finite value";
	EXPECT_TRUE(btIsFinite(std::numeric_limits<btScalar>::denorm_min()));
	EXPECT_FALSE(btIsFinite(BT_INFINITY));
	EXPECT_FALSE(btIsFinite(-BT_INFINITY));
	EXPECT_FALSE(btIsFinite(BT_NAN));
}

TEST(ScalarHelpers, SwapEndianReversesBytes)
{
	EXPECT_EQ(btSwapEndian(0x12345678u), 0x78563412u);
	EXPECT_EQ(btSwapEndian(static_cast<unsigned short>(0x1234)), static_cast<unsigned short>(0x3412));
	EXPECT_EQ(btSwapEndian(int(-2)), 0xfeffffffu);
	EXPECT_EQ(btSwapEndian(static_cast<short>(-2)), static_cast<unsigned short>(0xfeff));
	Random rng(903);
	for (int i = 0; i < 100; ++i)
	{
		const unsigned value = unsigned(rng.integer(0, 0x7fffffff)) * 2u + unsigned(rng.integer(0, 1));
		EXPECT_EQ(btSwapEndian(btSwapEndian(value)), value);
		unsigned char bytes[4], swappedBytes[4];
		const unsigned swapped = btSwapEndian(value);
		memcpy(bytes, &value, 4);
		memcpy(swappedBytes, &swapped, 4);
		for (int b = 0; b < 4; ++b) EXPECT_EQ(swappedBytes[b], bytes[3 - b]);
	}
	const uint16_t probe = 1;
	unsigned char lowAddressByte;
	memcpy(&lowAddressByte, &probe, 1);
	EXPECT_EQ(btMachineIsLittleEndian(), lowAddressByte == 1);
}

TEST(ScalarMinMax, MinMaxClampTemplates)
{
	EXPECT_EQ(btMin(3, 5), 3);
	EXPECT_EQ(btMin(5, 3), 3);
	EXPECT_EQ(btMax(3, 5), 5);
	EXPECT_EQ(btMax(btScalar(-1.5), btScalar(-2.5)), btScalar(-1.5));
	// They return a reference to one of the arguments, not a copy.
	const btScalar a = 1, b = 2;
	EXPECT_EQ(&btMin(a, b), &a);
	EXPECT_EQ(&btMax(a, b), &b);

	EXPECT_EQ(btClamped(5, 0, 3), 3);
	EXPECT_EQ(btClamped(-1, 0, 3), 0);
	EXPECT_EQ(btClamped(2, 0, 3), 2);
	EXPECT_EQ(btClamped(btScalar(0.5), btScalar(0), btScalar(1)), btScalar(0.5));

	int value = 7;
	btClamp(value, 0, 3);
	EXPECT_EQ(value, 3);
	value = -7;
	btClamp(value, 0, 3);
	EXPECT_EQ(value, 0);
	value = 2;
	btClamp(value, 0, 3);
	EXPECT_EQ(value, 2);
	btScalar boundary = 3;
	btClamp(boundary, btScalar(0), btScalar(3));
	EXPECT_EQ(boundary, btScalar(3));

	int m = 4;
	btSetMin(m, 6);
	EXPECT_EQ(m, 4);
	btSetMin(m, 2);
	EXPECT_EQ(m, 2);
	btSetMax(m, 1);
	EXPECT_EQ(m, 2);
	btSetMax(m, 9);
	EXPECT_EQ(m, 9);
}

// ---- btAssert ---------------------------------------------------------------------------------

// External linkage (a named namespace): in builds without asserts these are referenced only inside
// sizeof, and an internal function would be reported as unneeded.
namespace caliber_scalar_test
{
int g_assertArgumentEvaluations = 0;
bool countedFalse()
{
	++g_assertArgumentEvaluations;
	return false;
}
bool countedTrue()
{
	++g_assertArgumentEvaluations;
	return true;
}
}  // namespace caliber_scalar_test

using caliber_scalar_test::countedFalse;
using caliber_scalar_test::countedTrue;
using caliber_scalar_test::g_assertArgumentEvaluations;

#if CALIBER_ASSERTS_ENABLED
TEST(ScalarAssertDeathTest, AssertAbortsWithConditionAndPlace)
{
	EXPECT_DEATH(btAssert(1 + 1 == 3), "assertion failed: 1 \\+ 1 == 3 \\(.*ScalarAndMiscTest\\.cpp:[0-9]+\\)");
	EXPECT_DEATH(btFullAssert(countedFalse()), "assertion failed: countedFalse\\(\\)");
}

TEST(ScalarAssert, PassingAssertEvaluatesItsArgumentOnce)
{
	g_assertArgumentEvaluations = 0;
	btAssert(countedTrue());
	EXPECT_EQ(g_assertArgumentEvaluations, 1);
}
#else
TEST(ScalarAssert, DisabledAssertNeitherAbortsNorEvaluates)
{
	g_assertArgumentEvaluations = 0;
	btAssert(countedFalse());
	btFullAssert(countedFalse());
	btAssert(countedTrue());
	EXPECT_EQ(g_assertArgumentEvaluations, 0);
}
#endif

// ---- GEN_rand ---------------------------------------------------------------------------------

TEST(RandomGenerator, SameSeedGivesSameSequence)
{
	std::vector<unsigned> first;
	GEN_srand(42);
	for (int i = 0; i < 1000; ++i) first.push_back(GEN_rand());
	GEN_srand(7);  // disturb the state in between
	(void)GEN_rand();
	GEN_srand(42);
	for (int i = 0; i < 1000; ++i) ASSERT_EQ(GEN_rand(), first[size_t(i)]) << "position " << i;
}

TEST(RandomGenerator, DifferentSeedsGiveDifferentSequences)
{
	const int kSeeds = 64, kLength = 1000;
	std::vector<std::vector<unsigned>> sequences(kSeeds);
	for (int seed = 0; seed < kSeeds; ++seed)
	{
		GEN_srand(unsigned(seed));
		for (int i = 0; i < kLength; ++i) sequences[size_t(seed)].push_back(GEN_rand());
	}
	for (int a = 0; a < kSeeds; ++a)
		for (int b = a + 1; b < kSeeds; ++b)
		{
			// Two independent uniform 31-bit streams agree at a position with probability 2^-31: over 1000
			// positions, even one coincidence is unlikely (5e-7); allow 2.
			int equal = 0;
			for (int i = 0; i < kLength; ++i)
				equal += sequences[size_t(a)][size_t(i)] == sequences[size_t(b)][size_t(i)];
			EXPECT_LE(equal, 2) << "seeds " << a << " and " << b;
		}
	// Seeds far apart in value, too.
	GEN_srand(0xffffffffu);
	const unsigned fromLargestSeed = GEN_rand();
	GEN_srand(0);
	EXPECT_NE(GEN_rand(), fromLargestSeed);
}

TEST(RandomGenerator, ValuesAreWithinRangeAndCoverIt)
{
	GEN_srand(2024);
	unsigned lowest = GEN_RAND_MAX, highest = 0;
	for (int i = 0; i < 100000; ++i)
	{
		const unsigned value = GEN_rand();
		ASSERT_LE(value, GEN_RAND_MAX) << "sample " << i;
		lowest = btMin(lowest, value);
		highest = btMax(highest, value);
	}
	// With 100000 uniform samples, missing the top or bottom 0.1% has probability 0.999^100000 = e^-100.
	EXPECT_GT(highest, GEN_RAND_MAX - GEN_RAND_MAX / 1000u);
	EXPECT_LT(lowest, GEN_RAND_MAX / 1000u);
}

TEST(RandomGenerator, MeanAndVarianceMatchUniformWithinFiveSigma)
{
	// Samples scaled to [0, 1]. For the uniform distribution the mean is 1/2 and the variance 1/12. Over
	// N samples the sample mean has standard deviation sqrt(1/12 / N), and the sample variance (the mean of
	// (u - 1/2)^2) has standard deviation sqrt((E[(u - 1/2)^4] - (1/12)^2) / N) = sqrt((1/80 - 1/144) / N).
	// A correct generator is outside 5 sigma with probability below 1e-6 per statistic.
	const int kSamples = 100000;
	GEN_srand(12345);
	double sum = 0, sumSquaredDeviation = 0;
	int odd = 0;
	for (int i = 0; i < kSamples; ++i)
	{
		const unsigned value = GEN_rand();
		const double u = double(value) / double(GEN_RAND_MAX);
		sum += u;
		sumSquaredDeviation += (u - 0.5) * (u - 0.5);
		odd += int(value & 1u);
	}
	const double n = kSamples;
	const double mean = sum / n;
	const double variance = sumSquaredDeviation / n;
	const double meanSigma = sqrt(1.0 / 12.0 / n);
	const double varianceSigma = sqrt((1.0 / 80.0 - 1.0 / 144.0) / n);
	EXPECT_NEAR(mean, 0.5, 5 * meanSigma);
	EXPECT_NEAR(variance, 1.0 / 12.0, 5 * varianceSigma);
	// The lowest bit is balanced too (a plain LCG's low bits alternate): binomial, sigma = sqrt(n / 4).
	EXPECT_NEAR(double(odd), n / 2, 5 * sqrt(n / 4));
}

// ---- btDefaultMotionState ---------------------------------------------------------------------

namespace
{
// Rigid transforms of coordinates up to ~10 composed once or twice: a few eps of 10.
const btScalar kTransformTolerance = kTightTolerance * 10;

::testing::AssertionResult transformsNear(const btTransform& a, const btTransform& b, btScalar tolerance)
{
	::testing::AssertionResult basis = caliber_test::matricesNear(a.getBasis(), b.getBasis(), tolerance);
	if (!basis) return basis << " (basis)";
	::testing::AssertionResult origin = caliber_test::vectorsNear(a.getOrigin(), b.getOrigin(), tolerance);
	if (!origin) return origin << " (origin)";
	return ::testing::AssertionSuccess();
}
}  // namespace

TEST(MotionStateDefault, DefaultsAreIdentityWithNullUserPointer)
{
	btDefaultMotionState state;
	EXPECT_EQ(state.m_userPointer, nullptr);
	EXPECT_TRUE(state.m_graphicsWorldTrans == btTransform::getIdentity());
	EXPECT_TRUE(state.m_startWorldTrans == btTransform::getIdentity());
	EXPECT_TRUE(state.m_centerOfMassOffset == btTransform::getIdentity());
	btTransform world;
	state.getWorldTransform(world);
	EXPECT_TRUE(transformsNear(world, btTransform::getIdentity(), 0));
}

TEST(MotionStateDefault, WorldTransformIsGraphicsTimesInverseOffset)
{
	Random rng(1001);
	for (int i = 0; i < 200; ++i)
	{
		const btTransform start(rng.rotation(), rng.vector(10));
		const btTransform offset(rng.rotation(), rng.vector(2));
		btDefaultMotionState state(start, offset);
		EXPECT_EQ(state.m_userPointer, nullptr);
		btTransform centreOfMass;
		state.getWorldTransform(centreOfMass);
		// The documented relation graphics = centreOfMass * offset, checked by composing forwards.
		EXPECT_TRUE(transformsNear(centreOfMass * offset, start, kTransformTolerance)) << "case " << i;
		// And the stated formula, evaluated independently.
		EXPECT_TRUE(transformsNear(centreOfMass, start * offset.inverse(), kTransformTolerance)) << "case " << i;
	}
}

TEST(MotionStateDefault, SetThenGetRoundTripsWithOffsetAndKeepsStart)
{
	Random rng(1002);
	for (int i = 0; i < 200; ++i)
	{
		const btTransform start(rng.rotation(), rng.vector(10));
		const btTransform offset(rng.rotation(), rng.vector(2));
		btDefaultMotionState state(start, offset);
		int user = 0;
		state.m_userPointer = &user;
		const btTransform centreOfMass(rng.rotation(), rng.vector(10));
		state.setWorldTransform(centreOfMass);
		EXPECT_TRUE(transformsNear(state.m_graphicsWorldTrans, centreOfMass * offset, kTransformTolerance))
		    << "case " << i;
		btTransform back;
		state.getWorldTransform(back);
		EXPECT_TRUE(transformsNear(back, centreOfMass, kTransformTolerance)) << "case " << i;
		EXPECT_TRUE(state.m_startWorldTrans == start) << "the start transform is kept, case " << i;
		EXPECT_TRUE(state.m_centerOfMassOffset == offset) << "case " << i;
		EXPECT_EQ(state.m_userPointer, &user);
	}
}

TEST(MotionStateDefault, UsableThroughBaseInterface)
{
	const btTransform start(btQuaternion(btVector3(0, 1, 0), btScalar(0.5)), btVector3(1, 2, 3));
	btMotionState* state = new btDefaultMotionState(start);
	btTransform world;
	state->getWorldTransform(world);
	EXPECT_TRUE(transformsNear(world, start, kTransformTolerance));
	state->setWorldTransform(btTransform::getIdentity());
	state->getWorldTransform(world);
	EXPECT_TRUE(transformsNear(world, btTransform::getIdentity(), kTransformTolerance));
	delete state;  // virtual destructor, class operator delete
}

// ---- heap alignment ---------------------------------------------------------------------------

namespace
{
bool isAligned16(const void* ptr) { return reinterpret_cast<uintptr_t>(ptr) % 16 == 0; }

int g_alignedAllocCalls = 0;
int g_alignedFreeCalls = 0;
int g_lastAlignment = 0;
void* countingAlignedAlloc(size_t size, int alignment)
{
	++g_alignedAllocCalls;
	g_lastAlignment = alignment;
	const size_t rounded = (size + size_t(alignment) - 1) / size_t(alignment) * size_t(alignment);
	return aligned_alloc(size_t(alignment), rounded == 0 ? size_t(alignment) : rounded);
}
void countingAlignedFree(void* ptr)
{
	++g_alignedFreeCalls;
	free(ptr);
}
struct RestoreDefaultAlignedAllocator
{
	~RestoreDefaultAlignedAllocator() { btAlignedAllocSetCustomAligned(nullptr, nullptr); }
};
}  // namespace

TEST(MiscAlignedNew, HeapObjectsAre16ByteAligned)
{
	for (int i = 0; i < 64; ++i)
	{
		btVector3* v = new btVector3(1, 2, 3);
		btTransform* t = new btTransform(btTransform::getIdentity());
		btDefaultMotionState* m = new btDefaultMotionState();
		btVector3* array = new btVector3[size_t(i % 7 + 1)];
		EXPECT_TRUE(isAligned16(v)) << v;
		EXPECT_TRUE(isAligned16(t)) << t;
		EXPECT_TRUE(isAligned16(m)) << m;
		EXPECT_TRUE(isAligned16(&m->m_graphicsWorldTrans)) << m;
		EXPECT_TRUE(isAligned16(array)) << array;
		delete[] array;
		delete m;
		delete t;
		delete v;
	}
}

TEST(MiscAlignedNew, AlignedClassesAllocateThroughBtAlignedAlloc)
{
	// BT_DECLARE_ALIGNED_ALLOCATOR routes new/delete through btAlignedAlloc/btAlignedFree with 16-byte
	// alignment, so a user allocator installed with btAlignedAllocSetCustomAligned sees them.
	RestoreDefaultAlignedAllocator restore;
	g_alignedAllocCalls = g_alignedFreeCalls = g_lastAlignment = 0;
	btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree);
	btVector3* v = new btVector3(1, 2, 3);
	EXPECT_EQ(g_alignedAllocCalls, 1);
	EXPECT_EQ(g_lastAlignment, 16);
	delete v;
	EXPECT_EQ(g_alignedFreeCalls, 1);
	btDefaultMotionState* m = new btDefaultMotionState();
	EXPECT_EQ(g_alignedAllocCalls, 2);
	EXPECT_EQ(g_lastAlignment, 16);
	delete m;
	EXPECT_EQ(g_alignedFreeCalls, 2);
	btVector3* array = new btVector3[5];
	EXPECT_EQ(g_alignedAllocCalls, 3);
	delete[] array;
	EXPECT_EQ(g_alignedFreeCalls, 3);
	// Placement new uses the given storage and allocates nothing.
	alignas(16) unsigned char storage[sizeof(btVector3)];
	btVector3* placed = new (storage) btVector3(4, 5, 6);
	EXPECT_EQ(static_cast<void*>(placed), static_cast<void*>(storage));
	EXPECT_EQ(g_alignedAllocCalls, 3);
}

// An allocation function must return a distinct non-null pointer on success even for size 0
// ([basic.stc.dynamic.allocation]); code that treats null as "out of memory" relies on it for empty arrays.
TEST(MiscAlignedNew, ZeroLengthArrayNewGivesDistinctNonNullPointers)
{
	// The results go through volatile pointers: compilers may assume a new-expression is never null and
	// fold the comparisons away otherwise.
	volatile size_t count = 0;
	btVector3* volatile first = new btVector3[count];
	btVector3* volatile second = new btVector3[count];
	EXPECT_NE(static_cast<void*>(first), nullptr);
	EXPECT_NE(static_cast<void*>(first), static_cast<void*>(second));
	EXPECT_TRUE(isAligned16(first)) << static_cast<void*>(first);
	delete[] second;
	delete[] first;
}
