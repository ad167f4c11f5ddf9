// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btBoxBoxDetector::getClosestPoints runs an AVX2 build on processors that have it (btBoxBoxDetectorBuilds.h):
// the same operations in the same order, so it must report the baseline build's points bit for bit. These
// tests detect many box pairs both ways, degenerate ones included, and compare every reported value.

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "BulletCollision/CollisionDispatch/btBoxBoxDetectorBuilds.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/NarrowPhaseCollision/NarrowPhaseTestUtil.h"

using caliber_narrowphase_test::Random;

namespace
{
struct Reported
{
	btVector3 normal;
	btVector3 point;
	btScalar depth;
};

struct Recorder : public btDiscreteCollisionDetectorInterface::Result
{
	std::vector<Reported> points;
	void setShapeIdentifiersA(int, int) override {}
	void setShapeIdentifiersB(int, int) override {}
	void addContactPoint(const btVector3& normal, const btVector3& point, btScalar depth) override
	{
		points.push_back({normal, point, depth});
	}
};

// x, y and z of both vectors and the depth, bit for bit (the w lanes are no result).
bool sameBits(const Reported& a, const Reported& b)
{
	for (int k = 0; k < 3; ++k)
	{
		if (std::memcmp(&a.normal[k], &b.normal[k], sizeof(btScalar)) != 0) return false;
		if (std::memcmp(&a.point[k], &b.point[k], sizeof(btScalar)) != 0) return false;
	}
	return std::memcmp(&a.depth, &b.depth, sizeof(btScalar)) == 0;
}

// Detects the pair with both builds and expects the same points in the same order; returns how many.
int expectSameBothWays(const btBoxShape& a, const btTransform& ta, const btBoxShape& b, const btTransform& tb,
                       btScalar maxDistanceSquared, bool swap)
{
	btDiscreteCollisionDetectorInterface::ClosestPointInput input;
	input.m_transformA = ta;
	input.m_transformB = tb;
	input.m_maximumDistanceSquared = maxDistanceSquared;
	Recorder baseline, wide;
	caliber::boxBoxClosestPointsIn(&a, &b, input, baseline, swap, false);
	caliber::boxBoxClosestPointsIn(&a, &b, input, wide, swap, true);
	EXPECT_EQ(baseline.points.size(), wide.points.size());
	const size_t n = std::min(baseline.points.size(), wide.points.size());
	for (size_t i = 0; i < n; ++i) EXPECT_TRUE(sameBits(baseline.points[i], wide.points[i])) << "point " << i;
	return int(baseline.points.size());
}
}  // namespace

TEST(BoxBoxDetectorBuilds, Avx2BuildReportsTheBaselinePointsOnRandomPairs)
{
	if (!caliber::boxBoxUsesAvx2()) GTEST_SKIP() << "no AVX2 build of box-box detection on this processor or build";
	Random random(20261128u);
	int reported = 0, pairsWithPoints = 0;
	for (int i = 0; i < 3000; ++i)
	{
		SCOPED_TRACE(testing::Message() << "pair " << i);
		const btBoxShape a(btVector3(random.uniform(btScalar(0.05), 3), random.uniform(btScalar(0.05), 3),
		                             random.uniform(btScalar(0.05), 3)));
		const btBoxShape b(btVector3(random.uniform(btScalar(0.05), 3), random.uniform(btScalar(0.05), 3),
		                             random.uniform(btScalar(0.05), 3)));
		const btTransform ta = random.transform(2);
		btTransform tb = random.transform(2);
		// Some pairs resting face on face, axis-aligned, as in a stack.
		if (i % 4 == 0)
		{
			tb.setBasis(ta.getBasis());
			tb.setOrigin(ta.getOrigin() + ta.getBasis().getColumn(1) * (a.getHalfExtentsWithMargin().y() +
			                                                           b.getHalfExtentsWithMargin().y() -
			                                                           random.uniform(0, btScalar(0.01))));
		}
		const btScalar reach = i % 3 == 0 ? btScalar(0.02) : btScalar(0.5);
		const int n = expectSameBothWays(a, ta, b, tb, reach * reach, i % 2 == 1);
		reported += n;
		pairsWithPoints += n > 0 ? 1 : 0;
	}
	// The comparison covered many contacts, not only separated pairs.
	EXPECT_GT(pairsWithPoints, 1000);
	EXPECT_GT(reported, 3000);
}

TEST(BoxBoxDetectorBuilds, Avx2BuildReportsTheBaselinePointsOnDegeneratePairs)
{
	if (!caliber::boxBoxUsesAvx2()) GTEST_SKIP() << "no AVX2 build of box-box detection on this processor or build";
	const btBoxShape unit(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
	const btBoxShape flat(btVector3(2, btScalar(1e-4), 2));
	const btBoxShape thin(btVector3(btScalar(1e-6), 1, btScalar(1e-6)));
	const btTransform identity = btTransform::getIdentity();
	const btTransform same = identity;
	const btTransform stacked(btQuaternion::getIdentity(), btVector3(0, 1, 0));
	const btTransform edgeOnEdge(btQuaternion(btVector3(0, 0, 1), SIMD_HALF_PI * btScalar(0.5)) *
	                                 btQuaternion(btVector3(1, 0, 0), SIMD_HALF_PI * btScalar(0.5)),
	                             btVector3(0, btScalar(1.2), 0));
	const btTransform almostParallel(btQuaternion(btVector3(0, 1, 0), btScalar(1e-4)), btVector3(btScalar(0.3), 1, 0));
	const btTransform cornerDown(btQuaternion(btVector3(1, 0, 1).normalized(), btScalar(0.9553166)), btVector3(0, btScalar(1.3), 0));
	const btTransform farAway(btQuaternion::getIdentity(), btVector3(100, 0, 0));
	const btTransform* poses[] = {&same, &stacked, &edgeOnEdge, &almostParallel, &cornerDown, &farAway};
	const btBoxShape* shapes[] = {&unit, &flat, &thin};
	const btScalar reaches2[] = {0, btScalar(0.02) * btScalar(0.02), -1, BT_LARGE_FLOAT};
	for (const btBoxShape* a : shapes)
		for (const btBoxShape* b : shapes)
			for (const btTransform* pose : poses)
				for (btScalar reach2 : reaches2)
					for (bool swap : {false, true})
					{
						SCOPED_TRACE(testing::Message() << "shapes " << a << " " << b << " pose " << pose
						                                << " reach2 " << reach2 << " swap " << swap);
						expectSameBothWays(*a, identity, *b, *pose, reach2, swap);
					}
}
