// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btQuaternion.h"

namespace
{
// Fake bodies: the manifold stores the pointers and never dereferences them.
int gBodyStorage[2];
const btCollisionObject* fakeBody0() { return reinterpret_cast<const btCollisionObject*>(&gBodyStorage[0]); }
const btCollisionObject* fakeBody1() { return reinterpret_cast<const btCollisionObject*>(&gBodyStorage[1]); }

const btScalar kThreshold = btScalar(0.02);

btManifoldPoint makePoint(const btVector3& localA, btScalar distance)
{
	return btManifoldPoint(localA, localA - btVector3(0, 0, distance), btVector3(0, 0, 1), distance);
}

// Callback recorders.
int gStartedCount = 0;
int gEndedCount = 0;
int gDestroyedCount = 0;
int gProcessedCount = 0;
btPersistentManifold* gLastStarted = 0;
btPersistentManifold* gLastEnded = 0;
std::vector<void*> gDestroyedData;
void* gProcessedBody0 = 0;
void* gProcessedBody1 = 0;

void onStarted(btPersistentManifold* const& manifold)
{
	++gStartedCount;
	gLastStarted = manifold;
}
void onEnded(btPersistentManifold* const& manifold)
{
	++gEndedCount;
	gLastEnded = manifold;
}
bool onDestroyed(void* data)
{
	++gDestroyedCount;
	gDestroyedData.push_back(data);
	return true;
}
bool onProcessed(btManifoldPoint& cp, void* body0, void* body1)
{
	(void)cp;
	++gProcessedCount;
	gProcessedBody0 = body0;
	gProcessedBody1 = body1;
	return true;
}

// Every test leaves the global hooks null and the recorders reset.
class PersistentManifoldTest : public ::testing::Test
{
protected:
	void SetUp() override { reset(); }
	void TearDown() override { reset(); }
	static void reset()
	{
		gContactStartedCallback = 0;
		gContactEndedCallback = 0;
		gContactDestroyedCallback = 0;
		gContactProcessedCallback = 0;
		gStartedCount = gEndedCount = gDestroyedCount = gProcessedCount = 0;
		gLastStarted = gLastEnded = 0;
		gDestroyedData.clear();
		gProcessedBody0 = gProcessedBody1 = 0;
	}
};

// Independent brute force of the documented measure: the largest squared cross product over the three
// ways of pairing four points into two difference vectors.
btScalar bruteAreaMeasure(const btVector3 p[4])
{
	const int pairings[3][4] = {{0, 1, 2, 3}, {0, 2, 1, 3}, {0, 3, 1, 2}};
	btScalar best = 0;
	for (const auto& q : pairings)
	{
		const btVector3 c = (p[q[0]] - p[q[1]]).cross(p[q[2]] - p[q[3]]);
		best = btMax(best, c.dot(c));
	}
	return best;
}
}  // namespace

TEST_F(PersistentManifoldTest, AddsUpToFourPointsAtIncreasingIndices)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	EXPECT_EQ(manifold.getObjectType(), int(BT_PERSISTENT_MANIFOLD_TYPE));
	EXPECT_EQ(BT_PERSISTENT_MANIFOLD_TYPE, 1025);
	EXPECT_EQ(manifold.getBody0(), fakeBody0());
	EXPECT_EQ(manifold.getBody1(), fakeBody1());
	for (int i = 0; i < MANIFOLD_CACHE_SIZE; ++i)
	{
		EXPECT_EQ(manifold.addManifoldPoint(makePoint(btVector3(btScalar(i), 0, 0), btScalar(-0.01))), i);
		EXPECT_EQ(manifold.getNumContacts(), i + 1);
		EXPECT_EQ(manifold.getContactPoint(i).m_localPointA.x(), btScalar(i));
	}
}

TEST_F(PersistentManifoldTest, DefaultConstructorUsesGlobalBreakingThreshold)
{
	btPersistentManifold manifold;
	EXPECT_EQ(manifold.getNumContacts(), 0);
	EXPECT_EQ(manifold.getContactBreakingThreshold(), gContactBreakingThreshold);
	EXPECT_EQ(gContactBreakingThreshold, btScalar(0.02));
}

TEST_F(PersistentManifoldTest, FifthPointReplacesNearCornerToMaximiseSquareArea)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(makePoint(btVector3(1, 1, 0), btScalar(-0.05)));  // deepest
	manifold.addManifoldPoint(makePoint(btVector3(-1, 1, 0), btScalar(-0.01)));
	manifold.addManifoldPoint(makePoint(btVector3(1, -1, 0), btScalar(-0.01)));
	manifold.addManifoldPoint(makePoint(btVector3(-1, -1, 0), btScalar(-0.01)));
	// (-2,-2) extends the (-1,-1) corner: replacing that corner grows the square; any other choice
	// leaves three nearly collinear points.
	const int index = manifold.addManifoldPoint(makePoint(btVector3(-2, -2, 0), btScalar(-0.01)));
	EXPECT_EQ(index, 3);
	EXPECT_EQ(manifold.getNumContacts(), 4);
	EXPECT_EQ(manifold.getContactPoint(3).m_localPointA, btVector3(-2, -2, 0));
	EXPECT_EQ(manifold.getContactPoint(0).m_localPointA, btVector3(1, 1, 0));
}

TEST_F(PersistentManifoldTest, FifthPointKeepsDeepestAndMaximisesAreaOverCandidates)
{
	std::mt19937 engine(20261122u);
	std::uniform_real_distribution<double> coord(-1.0, 1.0);
	std::uniform_real_distribution<double> depth(-0.05, 0.0);
	for (int trial = 0; trial < 500; ++trial)
	{
		btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
		btManifoldPoint points[5];
		for (auto& p : points)
			p = makePoint(btVector3(btScalar(coord(engine)), btScalar(coord(engine)), btScalar(coord(engine))),
			              btScalar(depth(engine)));
		for (int i = 0; i < 4; ++i) manifold.addManifoldPoint(points[i]);
		const int index = manifold.addManifoldPoint(points[4]);
		ASSERT_GE(index, 0);
		ASSERT_LT(index, 4);

		int deepest = -1;
		btScalar deepestDistance = points[4].m_distance1;
		for (int i = 0; i < 4; ++i)
			if (points[i].m_distance1 < deepestDistance)
			{
				deepestDistance = points[i].m_distance1;
				deepest = i;
			}
		EXPECT_NE(index, deepest) << "trial " << trial << " replaced the deepest point";

		btScalar measures[4];
		btScalar bestMeasure = -1;
		for (int replaced = 0; replaced < 4; ++replaced)
		{
			btVector3 kept[4];
			for (int i = 0; i < 4; ++i) kept[i] = (i == replaced) ? points[4].m_localPointA : points[i].m_localPointA;
			measures[replaced] = bruteAreaMeasure(kept);
			if (replaced != deepest) bestMeasure = btMax(bestMeasure, measures[replaced]);
		}
		// Measures are sums of products of order-1 coordinates; 64 ulps of the largest is far above the
		// rounding of either computation and far below the gaps between distinct candidates.
		const btScalar tolerance = 64 * SIMD_EPSILON * btMax(btScalar(1), bestMeasure);
		EXPECT_GE(measures[index], bestMeasure - tolerance)
		    << "trial " << trial << " measure " << measures[index] << " best " << bestMeasure;
		for (int i = 0; i < 4; ++i)
		{
			const btVector3 expected = (i == index) ? points[4].m_localPointA : points[i].m_localPointA;
			EXPECT_EQ(manifold.getContactPoint(i).m_localPointA, expected);
		}
	}
}

TEST_F(PersistentManifoldTest, GetCacheEntryFindsClosestPointWithinThresholdOnly)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), 0));
	manifold.addManifoldPoint(makePoint(btVector3(1, 0, 0), 0));
	// Within half the threshold of point 1 (and closer to it than to point 0).
	EXPECT_EQ(manifold.getCacheEntry(makePoint(btVector3(1 + kThreshold / 2, 0, 0), 0)), 1);
	EXPECT_EQ(manifold.getCacheEntry(makePoint(btVector3(0, kThreshold / 2, 0), 0)), 0);
	// Twice the threshold away from every point.
	EXPECT_EQ(manifold.getCacheEntry(makePoint(btVector3(0.5, 2 * kThreshold, 0), 0)), -1);
	EXPECT_EQ(manifold.getCacheEntry(makePoint(btVector3(1 + 2 * kThreshold, 0, 0), 0)), -1);
}

TEST_F(PersistentManifoldTest, ReplaceContactPointKeepsWarmStartImpulsesAndLifetime)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), btScalar(-0.01)));
	btManifoldPoint& old = manifold.getContactPoint(0);
	old.m_appliedImpulse = 3;
	old.m_prevRHS = 4;
	old.m_appliedImpulseLateral1 = 5;
	old.m_appliedImpulseLateral2 = 6;
	old.m_lifeTime = 7;
	btManifoldPoint fresh = makePoint(btVector3(btScalar(0.001), 0, 0), btScalar(-0.02));
	fresh.m_appliedImpulse = 100;
	manifold.replaceContactPoint(fresh, 0);
	const btManifoldPoint& now = manifold.getContactPoint(0);
	EXPECT_EQ(now.m_localPointA, fresh.m_localPointA);
	EXPECT_EQ(now.getDistance(), btScalar(-0.02));
	EXPECT_EQ(now.getAppliedImpulse(), btScalar(3));
	EXPECT_EQ(now.m_prevRHS, btScalar(4));
	EXPECT_EQ(now.m_appliedImpulseLateral1, btScalar(5));
	EXPECT_EQ(now.m_appliedImpulseLateral2, btScalar(6));
	EXPECT_EQ(now.getLifeTime(), 7);
}

TEST_F(PersistentManifoldTest, ReplaceContactPointKeepsTheFrictionDirectionsOfTheLateralImpulses)
{
	// The lateral impulses are kept for warm starting; they mean something only along the directions
	// they were solved in, so those directions are kept too (unless the new point brings its own).
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), btScalar(-0.01)));
	btManifoldPoint& old = manifold.getContactPoint(0);
	old.m_appliedImpulseLateral1 = 5;
	old.m_lateralFrictionDir1 = btVector3(1, 0, 0);
	old.m_lateralFrictionDir2 = btVector3(0, 1, 0);
	manifold.replaceContactPoint(makePoint(btVector3(btScalar(0.001), 0, 0), btScalar(-0.02)), 0);
	EXPECT_EQ(manifold.getContactPoint(0).m_lateralFrictionDir1, btVector3(1, 0, 0));
	EXPECT_EQ(manifold.getContactPoint(0).m_lateralFrictionDir2, btVector3(0, 1, 0));

	btManifoldPoint userDirections = makePoint(btVector3(btScalar(0.002), 0, 0), btScalar(-0.02));
	userDirections.m_contactPointFlags |= BT_CONTACT_FLAG_LATERAL_FRICTION_INITIALIZED;
	userDirections.m_lateralFrictionDir1 = btVector3(0, 1, 0);
	userDirections.m_lateralFrictionDir2 = btVector3(-1, 0, 0);
	manifold.replaceContactPoint(userDirections, 0);
	EXPECT_EQ(manifold.getContactPoint(0).m_lateralFrictionDir1, btVector3(0, 1, 0));
	EXPECT_EQ(manifold.getContactPoint(0).m_lateralFrictionDir2, btVector3(-1, 0, 0));
}

TEST_F(PersistentManifoldTest, RefreshUpdatesDistancesExactlyForKnownMotion)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(btManifoldPoint(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1), 0));
	manifold.addManifoldPoint(btManifoldPoint(btVector3(1, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1), 0));
	btTransform trA = btTransform::getIdentity();
	const btTransform trB = btTransform::getIdentity();
	// Dyadic offsets make every operation exact in float and double.
	trA.setOrigin(btVector3(0, 0, btScalar(-0.0078125)));
	manifold.refreshContactPoints(trA, trB);
	ASSERT_EQ(manifold.getNumContacts(), 2);
	for (int i = 0; i < 2; ++i)
	{
		EXPECT_EQ(manifold.getContactPoint(i).getDistance(), btScalar(-0.0078125));
		EXPECT_EQ(manifold.getContactPoint(i).getPositionWorldOnA().z(), btScalar(-0.0078125));
		EXPECT_EQ(manifold.getContactPoint(i).getPositionWorldOnB().z(), btScalar(0));
		EXPECT_EQ(manifold.getContactPoint(i).getLifeTime(), 1);
	}
}

TEST_F(PersistentManifoldTest, RefreshRemovesPointsSeparatedBeyondThresholdAlongNormal)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(btManifoldPoint(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1), 0));
	btTransform trA = btTransform::getIdentity();
	trA.setOrigin(btVector3(0, 0, kThreshold / 2));
	manifold.refreshContactPoints(trA, btTransform::getIdentity());
	EXPECT_EQ(manifold.getNumContacts(), 1);
	trA.setOrigin(btVector3(0, 0, 2 * kThreshold));
	manifold.refreshContactPoints(trA, btTransform::getIdentity());
	EXPECT_EQ(manifold.getNumContacts(), 0);
}

TEST_F(PersistentManifoldTest, RefreshRemovesPointsThatSlidSidewaysBeyondThreshold)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(btManifoldPoint(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1), 0));
	manifold.addManifoldPoint(btManifoldPoint(btVector3(1, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1), 0));
	btTransform trA = btTransform::getIdentity();
	trA.setOrigin(btVector3(kThreshold / 2, 0, 0));
	manifold.refreshContactPoints(trA, btTransform::getIdentity());
	EXPECT_EQ(manifold.getNumContacts(), 2);
	trA.setOrigin(btVector3(0, 2 * kThreshold, 0));
	manifold.refreshContactPoints(trA, btTransform::getIdentity());
	EXPECT_EQ(manifold.getNumContacts(), 0);
}

TEST_F(PersistentManifoldTest, RemoveContactPointMovesLastPointIntoHole)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	for (int i = 0; i < 4; ++i) manifold.addManifoldPoint(makePoint(btVector3(btScalar(i), 0, 0), 0));
	manifold.removeContactPoint(1);
	ASSERT_EQ(manifold.getNumContacts(), 3);
	EXPECT_EQ(manifold.getContactPoint(0).m_localPointA.x(), btScalar(0));
	EXPECT_EQ(manifold.getContactPoint(1).m_localPointA.x(), btScalar(3));
	EXPECT_EQ(manifold.getContactPoint(2).m_localPointA.x(), btScalar(2));
	manifold.removeContactPoint(2);
	EXPECT_EQ(manifold.getNumContacts(), 2);
}

TEST_F(PersistentManifoldTest, StartedAndEndedCallbacksFireOnFirstAndLastPoint)
{
	gContactStartedCallback = onStarted;
	gContactEndedCallback = onEnded;
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), 0));
	manifold.addManifoldPoint(makePoint(btVector3(1, 0, 0), 0));
	EXPECT_EQ(gStartedCount, 1);
	EXPECT_EQ(gLastStarted, &manifold);
	manifold.removeContactPoint(0);
	EXPECT_EQ(gEndedCount, 0);
	manifold.removeContactPoint(0);
	EXPECT_EQ(gEndedCount, 1);
	EXPECT_EQ(gLastEnded, &manifold);
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), 0));
	EXPECT_EQ(gStartedCount, 2);
	manifold.clearManifold();
	EXPECT_EQ(gEndedCount, 2);
	manifold.clearManifold();  // already empty: no second end
	EXPECT_EQ(gEndedCount, 2);
}

TEST_F(PersistentManifoldTest, DestroyedCallbackReceivesUserDataOfRemovedPoints)
{
	gContactDestroyedCallback = onDestroyed;
	int dataA = 0, dataB = 0, dataC = 0;
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), 0));
	manifold.addManifoldPoint(makePoint(btVector3(1, 0, 0), 0));
	manifold.addManifoldPoint(makePoint(btVector3(2, 0, 0), 0));
	manifold.getContactPoint(0).m_userPersistentData = &dataA;
	manifold.getContactPoint(1).m_userPersistentData = &dataB;
	manifold.getContactPoint(2).m_userPersistentData = &dataC;
	manifold.removeContactPoint(0);
	ASSERT_EQ(gDestroyedCount, 1);
	EXPECT_EQ(gDestroyedData[0], &dataA);
	// The moved point keeps its own data.
	EXPECT_EQ(manifold.getContactPoint(0).m_userPersistentData, &dataC);
	manifold.clearManifold();
	ASSERT_EQ(gDestroyedCount, 3);
	EXPECT_EQ(gDestroyedData[1], &dataC);
	EXPECT_EQ(gDestroyedData[2], &dataB);
	EXPECT_EQ(manifold.getNumContacts(), 0);

	// clearUserCache on a point without data does nothing.
	btManifoldPoint empty;
	manifold.clearUserCache(empty);
	EXPECT_EQ(gDestroyedCount, 3);
}

TEST_F(PersistentManifoldTest, ProcessedCallbackFiresForEachSurvivorWithBothBodies)
{
	gContactProcessedCallback = onProcessed;
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(btManifoldPoint(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1), 0));
	manifold.addManifoldPoint(btManifoldPoint(btVector3(1, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1), 0));
	// The second point separates by 1 (a known far motion) and is dropped before the callback.
	manifold.getContactPoint(1).m_localPointB = btVector3(1, 0, -1);
	manifold.refreshContactPoints(btTransform::getIdentity(), btTransform::getIdentity());
	EXPECT_EQ(manifold.getNumContacts(), 1);
	EXPECT_EQ(gProcessedCount, 1);
	EXPECT_EQ(gProcessedBody0, (void*)fakeBody0());
	EXPECT_EQ(gProcessedBody1, (void*)fakeBody1());
}

TEST_F(PersistentManifoldTest, ClearManifoldRemovesAllPoints)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	for (int i = 0; i < 3; ++i) manifold.addManifoldPoint(makePoint(btVector3(btScalar(i), 0, 0), 0));
	manifold.clearManifold();
	EXPECT_EQ(manifold.getNumContacts(), 0);
	EXPECT_EQ(manifold.addManifoldPoint(makePoint(btVector3(5, 0, 0), 0)), 0);
}

TEST_F(PersistentManifoldTest, ValidContactDistanceComparesWithBreakingThreshold)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	EXPECT_TRUE(manifold.validContactDistance(makePoint(btVector3(0, 0, 0), kThreshold)));
	EXPECT_FALSE(manifold.validContactDistance(makePoint(btVector3(0, 0, 0), 2 * kThreshold)));
	manifold.setContactProcessingThreshold(btScalar(0.5));
	EXPECT_EQ(manifold.getContactProcessingThreshold(), btScalar(0.5));
	manifold.setContactBreakingThreshold(btScalar(0.25));
	EXPECT_EQ(manifold.getContactBreakingThreshold(), btScalar(0.25));
}

TEST_F(PersistentManifoldTest, ZeroThresholdNeverMatchesCacheAndDropsSeparatedPoints)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, 0, 0);
	manifold.addManifoldPoint(btManifoldPoint(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1), 0));
	EXPECT_EQ(manifold.getCacheEntry(makePoint(btVector3(0, 0, 0), 0)), -1);
	manifold.refreshContactPoints(btTransform::getIdentity(), btTransform::getIdentity());
	EXPECT_EQ(manifold.getNumContacts(), 1);  // touching exactly is still valid
	btTransform trA = btTransform::getIdentity();
	trA.setOrigin(btVector3(0, 0, btScalar(0.0078125)));
	manifold.refreshContactPoints(trA, btTransform::getIdentity());
	EXPECT_EQ(manifold.getNumContacts(), 0);
}

TEST_F(PersistentManifoldTest, NegativeOrNanThresholdAssertsOrBecomesZero)
{
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(btPersistentManifold(fakeBody0(), fakeBody1(), 0, btScalar(-1), 0), "assertion failed");
	btPersistentManifold manifold;
	EXPECT_DEATH(manifold.setContactBreakingThreshold(std::numeric_limits<btScalar>::quiet_NaN()), "assertion failed");
	EXPECT_DEATH(manifold.setContactProcessingThreshold(std::numeric_limits<btScalar>::quiet_NaN()),
	             "assertion failed");
#else
	btPersistentManifold negative(fakeBody0(), fakeBody1(), 0, btScalar(-1), 0);
	EXPECT_EQ(negative.getContactBreakingThreshold(), btScalar(0));
	btPersistentManifold manifold;
	manifold.setContactBreakingThreshold(std::numeric_limits<btScalar>::quiet_NaN());
	EXPECT_EQ(manifold.getContactBreakingThreshold(), btScalar(0));
	manifold.setContactProcessingThreshold(std::numeric_limits<btScalar>::quiet_NaN());
	EXPECT_EQ(manifold.getContactProcessingThreshold(), btScalar(0));
#endif
}

TEST_F(PersistentManifoldTest, OutOfRangeIndexAssertsOrIsHarmless)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(manifold.getContactPoint(1), "assertion failed");
	EXPECT_DEATH(manifold.removeContactPoint(-1), "assertion failed");
	EXPECT_DEATH(manifold.replaceContactPoint(makePoint(btVector3(0, 0, 0), 0), 4), "assertion failed");
	EXPECT_DEATH(manifold.setNumContacts(5), "assertion failed");
#else
	// getContactPoint clamps into the cache array; remove/replace do nothing; setNumContacts clamps.
	EXPECT_EQ(&manifold.getContactPoint(-3), &manifold.getContactPoint(0));
	const btManifoldPoint& clampedHigh = manifold.getContactPoint(99);
	(void)clampedHigh;
	manifold.removeContactPoint(-1);
	manifold.removeContactPoint(7);
	manifold.replaceContactPoint(makePoint(btVector3(9, 9, 9), 0), 4);
	EXPECT_EQ(manifold.getNumContacts(), 1);
	EXPECT_EQ(manifold.getContactPoint(0).m_localPointA, btVector3(0, 0, 0));
	manifold.setNumContacts(5);
	EXPECT_EQ(manifold.getNumContacts(), MANIFOLD_CACHE_SIZE);
	manifold.setNumContacts(-2);
	EXPECT_EQ(manifold.getNumContacts(), 0);
#endif
}

TEST_F(PersistentManifoldTest, NanPointIsRejectedAndNothingIsStored)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	manifold.addManifoldPoint(makePoint(btVector3(0, 0, 0), 0));
	btManifoldPoint bad = makePoint(btVector3(nan, 0, 0), 0);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(manifold.addManifoldPoint(bad), "assertion failed");
	EXPECT_DEATH(manifold.replaceContactPoint(bad, 0), "assertion failed");
#else
	EXPECT_EQ(manifold.addManifoldPoint(bad), -1);
	manifold.replaceContactPoint(bad, 0);
	EXPECT_EQ(manifold.getNumContacts(), 1);
	EXPECT_EQ(manifold.getContactPoint(0).m_localPointA, btVector3(0, 0, 0));
#endif
}

TEST_F(PersistentManifoldTest, NanTransformLeavesManifoldUnchanged)
{
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, kThreshold, 0);
	manifold.addManifoldPoint(
	    btManifoldPoint(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 1), btScalar(-0.01)));
	btTransform bad = btTransform::getIdentity();
	bad.setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(manifold.refreshContactPoints(bad, btTransform::getIdentity()), "assertion failed");
#else
	manifold.refreshContactPoints(bad, btTransform::getIdentity());
	ASSERT_EQ(manifold.getNumContacts(), 1);
	EXPECT_EQ(manifold.getContactPoint(0).getDistance(), btScalar(-0.01));
	EXPECT_EQ(manifold.getContactPoint(0).getLifeTime(), 0);
#endif
}

namespace
{
// Every field of two points, compared bit for bit (w lanes and padding aside).
void expectSamePoint(const btManifoldPoint& a, const btManifoldPoint& b)
{
	const auto same = [](btScalar x, btScalar y) { return std::memcmp(&x, &y, sizeof(btScalar)) == 0; };
	const auto sameVector = [&](const btVector3& x, const btVector3& y)
	{ return same(x.x(), y.x()) && same(x.y(), y.y()) && same(x.z(), y.z()); };
	EXPECT_TRUE(sameVector(a.m_localPointA, b.m_localPointA));
	EXPECT_TRUE(sameVector(a.m_localPointB, b.m_localPointB));
	EXPECT_TRUE(sameVector(a.m_positionWorldOnA, b.m_positionWorldOnA));
	EXPECT_TRUE(sameVector(a.m_positionWorldOnB, b.m_positionWorldOnB));
	EXPECT_TRUE(sameVector(a.m_normalWorldOnB, b.m_normalWorldOnB));
	EXPECT_TRUE(same(a.m_distance1, b.m_distance1));
	EXPECT_EQ(a.m_lifeTime, b.m_lifeTime);
	EXPECT_TRUE(same(a.m_appliedImpulse, b.m_appliedImpulse));
	EXPECT_EQ(a.m_userPersistentData, b.m_userPersistentData);
}

// A manifold of four points with varied local points, normals and distances, some of which a refresh
// under the given poses keeps and some it drops (along the normal or sideways).
btPersistentManifold variedManifold(std::mt19937& random, btScalar threshold)
{
	std::uniform_real_distribution<float> unit(-1, 1);
	btPersistentManifold manifold(fakeBody0(), fakeBody1(), 0, threshold, 0);
	for (int i = 0; i < 4; ++i)
	{
		const btVector3 normal = btVector3(unit(random), unit(random), unit(random) + btScalar(2)).normalized();
		const btVector3 localA(unit(random), unit(random), unit(random));
		// Within half a threshold of the point A on even points, two on odd ones: some kept, some too far along
		// or across the normal.
		const btScalar spread = (i % 2 == 0 ? btScalar(0.5) : btScalar(2)) * threshold;
		const btVector3 localB = localA + btVector3(unit(random), unit(random), unit(random)) * spread;
		btManifoldPoint point(localA, localB, normal, btScalar(0));
		point.m_appliedImpulse = btScalar(i + 1);
		point.m_lifeTime = i;
		manifold.addManifoldPoint(point);
	}
	return manifold;
}
}  // namespace

// Without callbacks the refresh decides every point in its first pass (the point at an index, walked
// backwards, is still that pass's point); with a processed callback each point is judged again in its
// turn. Both must drop the same points and leave the same manifold.
TEST_F(PersistentManifoldTest, RefreshDropsTheSamePointsWithAndWithoutAProcessedCallback)
{
	std::mt19937 random(20261128);
	std::uniform_real_distribution<float> unit(-1, 1);
	int dropped = 0, kept = 0;
	for (int trial = 0; trial < 2000; ++trial)
	{
		const btScalar threshold = trial % 10 == 0 ? btScalar(0) : btScalar(0.02);
		btPersistentManifold plain = variedManifold(random, threshold);
		btPersistentManifold reported = plain;
		const btTransform trA(btQuaternion(btVector3(unit(random), unit(random), 1), btScalar(0.005) * unit(random)),
		                      btVector3(unit(random), unit(random), unit(random)) * btScalar(0.005));
		const btTransform trB(btQuaternion(btVector3(1, unit(random), unit(random)), btScalar(0.005) * unit(random)),
		                      btVector3(unit(random), unit(random), unit(random)) * btScalar(0.005));
		gContactProcessedCallback = 0;
		plain.refreshContactPoints(trA, trB);
		gContactProcessedCallback = onProcessed;
		gProcessedCount = 0;
		reported.refreshContactPoints(trA, trB);
		gContactProcessedCallback = 0;
		ASSERT_EQ(plain.getNumContacts(), reported.getNumContacts()) << "trial " << trial;
		EXPECT_EQ(gProcessedCount, reported.getNumContacts());
		for (int i = 0; i < plain.getNumContacts(); ++i) expectSamePoint(plain.getContactPoint(i), reported.getContactPoint(i));
		dropped += 4 - plain.getNumContacts();
		kept += plain.getNumContacts();
	}
	// The trials exercise both verdicts (not a test that cannot fail).
	EXPECT_GT(dropped, 1000);
	EXPECT_GT(kept, 1000);
}
