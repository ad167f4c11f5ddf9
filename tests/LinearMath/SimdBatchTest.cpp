// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The batched vector operations of src/LinearMath/btSimdBatch.h and the finiteness tests of btVector3.h
// and btTransform.h: the solver and the manifold rely on them giving the one-at-a-time forms' bits.
#include "LinearMath/btSimdBatch.h"
#include "LinearMath/btQuaternion.h"
#include "LinearMath/btTransform.h"
#include "LinearMath/btVector3.h"

#include <gtest/gtest.h>

#include <string.h>

#include <limits>

#include "MathTestUtil.h"

using caliber_test::Random;

namespace
{
bool sameBits(btScalar a, btScalar b) { return memcmp(&a, &b, sizeof(btScalar)) == 0; }

// Components spread over many magnitudes, so that rounding differs between summation orders.
btVector3 spreadVector(Random& random)
{
	btVector3 v;
	for (int k = 0; k < 3; ++k) v[k] = random.uniform(-1, 1) * btPow(btScalar(10), random.uniform(-3, 3));
	return v;
}
}  // namespace

TEST(SimdBatch, Dot4SumsHaveTheBitsOfSeparateDotProducts)
{
	Random random(17);
	for (int trial = 0; trial < 2000; ++trial)
	{
		btVector3 a[4], b[4];
		for (int k = 0; k < 4; ++k)
		{
			a[k] = spreadVector(random);
			b[k] = spreadVector(random);
		}
		const caliber::Dot4 terms = caliber::dot4(a[0], b[0], a[1], b[1], a[2], b[2], a[3], b[3]);
		const btScalar pairs = (a[0].dot(b[0]) + a[1].dot(b[1])) + (a[2].dot(b[2]) + a[3].dot(b[3]));
		const btScalar inOrder = a[0].dot(b[0]) + a[1].dot(b[1]) + a[2].dot(b[2]) + a[3].dot(b[3]);
		ASSERT_TRUE(sameBits(terms.sumOfPairs(), pairs))
		    << "trial " << trial << ": " << terms.sumOfPairs() << " vs " << pairs;
		ASSERT_TRUE(sameBits(terms.sumInOrder(), inOrder))
		    << "trial " << trial << ": " << terms.sumInOrder() << " vs " << inOrder;
	}
}

TEST(SimdBatch, ColumnTransformHasTheBitsOfTransform)
{
	Random random(29);
	for (int trial = 0; trial < 500; ++trial)
	{
		const btQuaternion rotation(random.unitVector(), random.uniform(-3, 3));
		const btTransform pose(rotation, spreadVector(random));
		const caliber::ColumnTransform columns(pose);
		for (int point = 0; point < 4; ++point)
		{
			const btVector3 p = spreadVector(random);
			const btVector3 expected = pose(p);
			const btVector3 actual = columns(p);
			for (int k = 0; k < 4; ++k)
				ASSERT_TRUE(sameBits(actual.m_floats[k], expected.m_floats[k]))
				    << "trial " << trial << " component " << k << ": " << actual.m_floats[k] << " vs "
				    << expected.m_floats[k];
		}
	}
}

TEST(SimdBatch, IsFiniteRejectsNanAndInfinityInEveryComponent)
{
	const btScalar bad[] = {std::numeric_limits<btScalar>::quiet_NaN(), std::numeric_limits<btScalar>::infinity(),
	                        -std::numeric_limits<btScalar>::infinity()};
	const btScalar huge = std::numeric_limits<btScalar>::max();
	EXPECT_TRUE(caliber::isFinite(btVector3(huge, -huge, huge)));
	EXPECT_TRUE(caliber::isFinite(btTransform(btMatrix3x3(huge, huge, huge, huge, huge, huge, huge, huge, huge),
	                                          btVector3(-huge, -huge, -huge))));
	for (btScalar value : bad)
	{
		for (int k = 0; k < 3; ++k)
		{
			btVector3 v(1, 2, 3);
			v[k] = value;
			EXPECT_FALSE(caliber::isFinite(v)) << "component " << k << " = " << value;
			btTransform origin = btTransform::getIdentity();
			origin.setOrigin(v);
			EXPECT_FALSE(caliber::isFinite(origin)) << "origin component " << k << " = " << value;
			for (int row = 0; row < 3; ++row)
			{
				btTransform basis = btTransform::getIdentity();
				basis.getBasis()[row][k] = value;
				EXPECT_FALSE(caliber::isFinite(basis)) << "basis[" << row << "][" << k << "] = " << value;
			}
		}
		// The padding lane is not part of the vector.
		btVector3 padded(1, 2, 3);
		padded.setW(value);
		EXPECT_TRUE(caliber::isFinite(padded)) << "w = " << value;
	}
}
