// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btTriangleInfoMap and btTriangleInfo: Bullet's defaults, flag bits, and use as a hash map.

#include <gtest/gtest.h>

#include "BulletCollision/CollisionShapes/btTriangleInfoMap.h"

TEST(TriangleInfoMapTest, TriangleInfoDefaultsToNoNeighbours)
{
	const btTriangleInfo info;
	EXPECT_EQ(0, info.m_flags);
	EXPECT_EQ(SIMD_2_PI, info.m_edgeV0V1Angle);
	EXPECT_EQ(SIMD_2_PI, info.m_edgeV1V2Angle);
	EXPECT_EQ(SIMD_2_PI, info.m_edgeV2V0Angle);
}

TEST(TriangleInfoMapTest, FlagsAreDistinctBits)
{
	const int flags[6] = {TRI_INFO_V0V1_CONVEX,       TRI_INFO_V1V2_CONVEX,       TRI_INFO_V2V0_CONVEX,
	                      TRI_INFO_V0V1_SWAP_NORMALB, TRI_INFO_V1V2_SWAP_NORMALB, TRI_INFO_V2V0_SWAP_NORMALB};
	int seen = 0;
	for (int flag : flags)
	{
		EXPECT_EQ(0, flag & (flag - 1)) << flag << " is not a single bit";
		EXPECT_EQ(0, seen & flag) << flag << " reused";
		seen |= flag;
	}
	// Bullet's values, which serialized maps and user code rely on.
	EXPECT_EQ(1, TRI_INFO_V0V1_CONVEX);
	EXPECT_EQ(32, TRI_INFO_V2V0_SWAP_NORMALB);
}

TEST(TriangleInfoMapTest, MapHasBulletDefaultTolerances)
{
	const btTriangleInfoMap map;
	EXPECT_EQ(btScalar(0), map.m_convexEpsilon);
	EXPECT_EQ(btScalar(0.0001), map.m_planarEpsilon);
	EXPECT_EQ(btScalar(0.0001) * btScalar(0.0001), map.m_equalVertexThreshold);
	EXPECT_EQ(btScalar(0.1), map.m_edgeDistanceThreshold);
	EXPECT_EQ(SIMD_2_PI, map.m_maxEdgeAngleThreshold);
	EXPECT_EQ(btScalar(0.0001) * btScalar(0.0001), map.m_zeroAreaThreshold);
	EXPECT_EQ(0, map.size());
}

TEST(TriangleInfoMapTest, StoresAndFindsInfoByHashKey)
{
	btTriangleInfoMap map;
	for (int key = 0; key < 100; ++key)
	{
		btTriangleInfo info;
		info.m_flags = key % 7;
		info.m_edgeV0V1Angle = btScalar(key) * btScalar(0.01);
		map.insert(btHashInt(key * 31), info);
	}
	EXPECT_EQ(100, map.size());
	for (int key = 0; key < 100; ++key)
	{
		const btTriangleInfo* info = map.find(btHashInt(key * 31));
		ASSERT_NE(nullptr, info) << key;
		EXPECT_EQ(key % 7, info->m_flags);
		EXPECT_EQ(btScalar(key) * btScalar(0.01), info->m_edgeV0V1Angle);
		EXPECT_EQ(SIMD_2_PI, info->m_edgeV1V2Angle);
	}
	EXPECT_EQ(nullptr, map.find(btHashInt(1)));
}
