// Stored points with distinct solver fields and their bit-for-bit comparison, shared by the tests that run two
// builds or two paths of the contact upkeep on the same inputs and require the same points.
#pragma once

#include <cstring>

#include <gtest/gtest.h>

#include "BulletCollision/NarrowPhaseCollision/btManifoldPoint.h"

namespace caliber_test
{
inline bool sameBits(btScalar a, btScalar b) { return std::memcmp(&a, &b, sizeof(btScalar)) == 0; }
inline bool sameBits(const btVector3& a, const btVector3& b)
{
	return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

// Every field of two points, bit for bit (w lanes and padding aside).
inline void expectSamePoint(const btManifoldPoint& a, const btManifoldPoint& b, int trial)
{
	SCOPED_TRACE(trial);
	EXPECT_TRUE(sameBits(a.m_localPointA, b.m_localPointA));
	EXPECT_TRUE(sameBits(a.m_localPointB, b.m_localPointB));
	EXPECT_TRUE(sameBits(a.m_positionWorldOnB, b.m_positionWorldOnB));
	EXPECT_TRUE(sameBits(a.m_positionWorldOnA, b.m_positionWorldOnA));
	EXPECT_TRUE(sameBits(a.m_normalWorldOnB, b.m_normalWorldOnB));
	EXPECT_TRUE(sameBits(a.m_distance1, b.m_distance1));
	EXPECT_TRUE(sameBits(a.m_combinedFriction, b.m_combinedFriction));
	EXPECT_TRUE(sameBits(a.m_combinedRollingFriction, b.m_combinedRollingFriction));
	EXPECT_TRUE(sameBits(a.m_combinedSpinningFriction, b.m_combinedSpinningFriction));
	EXPECT_TRUE(sameBits(a.m_combinedRestitution, b.m_combinedRestitution));
	EXPECT_EQ(a.m_partId0, b.m_partId0);
	EXPECT_EQ(a.m_partId1, b.m_partId1);
	EXPECT_EQ(a.m_index0, b.m_index0);
	EXPECT_EQ(a.m_index1, b.m_index1);
	EXPECT_EQ(a.m_userPersistentData, b.m_userPersistentData);
	EXPECT_EQ(a.m_contactPointFlags, b.m_contactPointFlags);
	EXPECT_TRUE(sameBits(a.m_appliedImpulse, b.m_appliedImpulse));
	EXPECT_TRUE(sameBits(a.m_prevRHS, b.m_prevRHS));
	EXPECT_TRUE(sameBits(a.m_appliedImpulseLateral1, b.m_appliedImpulseLateral1));
	EXPECT_TRUE(sameBits(a.m_appliedImpulseLateral2, b.m_appliedImpulseLateral2));
	EXPECT_TRUE(sameBits(a.m_contactMotion1, b.m_contactMotion1));
	EXPECT_TRUE(sameBits(a.m_contactMotion2, b.m_contactMotion2));
	EXPECT_TRUE(sameBits(a.m_contactCFM, b.m_contactCFM));
	EXPECT_TRUE(sameBits(a.m_combinedContactStiffness1, b.m_combinedContactStiffness1));
	EXPECT_TRUE(sameBits(a.m_contactERP, b.m_contactERP));
	EXPECT_TRUE(sameBits(a.m_combinedContactDamping1, b.m_combinedContactDamping1));
	EXPECT_TRUE(sameBits(a.m_frictionCFM, b.m_frictionCFM));
	EXPECT_EQ(a.m_lifeTime, b.m_lifeTime);
	EXPECT_TRUE(sameBits(a.m_lateralFrictionDir1, b.m_lateralFrictionDir1));
	EXPECT_TRUE(sameBits(a.m_lateralFrictionDir2, b.m_lateralFrictionDir2));
}

// Gives a stored point's solver fields values that no default has, so a comparison notices any field that a
// path drops or overwrites (the point's own address as user data: only compared, never dereferenced).
inline void setDistinctSolverFields(btManifoldPoint& point, int i)
{
	point.m_contactMotion1 = btScalar(0.5);
	point.m_contactMotion2 = btScalar(0.25);
	point.m_contactCFM = btScalar(0.125);
	point.m_contactERP = btScalar(0.75);
	point.m_frictionCFM = btScalar(0.0625);
	point.m_combinedContactStiffness1 = btScalar(9);
	point.m_combinedContactDamping1 = btScalar(8);
	point.m_contactPointFlags = BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED | BT_CONTACT_FLAG_HAS_CONTACT_CFM;
	point.m_lifeTime = 10 + i;
	point.m_userPersistentData = &point;
	point.m_lateralFrictionDir1 = btVector3(1, 0, 0);
	point.m_lateralFrictionDir2 = btVector3(0, 0, 1);
}
} // namespace caliber_test
