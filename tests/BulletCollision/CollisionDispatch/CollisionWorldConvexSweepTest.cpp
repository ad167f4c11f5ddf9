// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCollisionWorld::convexSweepTest: a sphere swept against spheres, boxes, meshes, height fields, planes and
// compounds, compared with analytic times of impact; filtering, starts in contact, bad input.

#include <gtest/gtest.h>

#include <limits>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "CollisionWorldTestUtil.h"

using namespace caliber_world_test;

namespace
{
// The continuous cast stops when distance + allowed penetration <= 1e-3 (float) / 1e-6 (double): the fraction
// is low by at most that distance over the closing speed (sweep length times the cosine to the normal).
const double kSweepStopDistance = sizeof(btScalar) == 4 ? 1e-3 : 1e-6;

double sweepTolerance(const btVector3& from, const btVector3& to, const btVector3& normal)
{
	const double closing = std::fabs(double((to - from).dot(normal)));
	return 1.5 * kSweepStopDistance / closing + 2e-5;
}

btTransform sweepPose(const btVector3& origin) { return at(origin); }

struct SweepResult
{
	bool hit;
	btScalar fraction;
	btVector3 normal, point;
	const btCollisionObject* object;
	int part, index;
};

struct RecordingConvexCallback : public btCollisionWorld::ConvexResultCallback
{
	btScalar addSingleResult(btCollisionWorld::LocalConvexResult& r, bool normalInWorldSpace) override
	{
		EXPECT_TRUE(normalInWorldSpace);
		m_closestHitFraction = r.m_hitFraction;
		m_last = {true,
		          r.m_hitFraction,
		          r.m_hitNormalLocal,
		          r.m_hitPointLocal,
		          r.m_hitCollisionObject,
		          r.m_localShapeInfo ? r.m_localShapeInfo->m_shapePart : -2,
		          r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -2};
		return r.m_hitFraction;
	}
	SweepResult m_last = {false, 1, btVector3(0, 0, 0), btVector3(0, 0, 0), 0, -2, -2};
};

// A flat n x n grid of triangles over [-size, size]^2 in the y = 0 plane, front faces up.
btTriangleMesh* flatGrid(int n, btScalar size)
{
	btTriangleMesh* mesh = new btTriangleMesh();
	auto vertex = [&](int i, int j) { return btVector3(-size + 2 * size * i / n, 0, -size + 2 * size * j / n); };
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++)
		{
			mesh->addTriangle(vertex(i, j), vertex(i, j + 1), vertex(i + 1, j));
			mesh->addTriangle(vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1));
		}
	return mesh;
}
}  // namespace

TEST(CollisionWorldConvexSweep, SphereAgainstSpheresMatchesAnalyticTimeOfImpact)
{
	WorldFixture f;
	Random rng(101);
	std::vector<std::pair<btVector3, btScalar>> spheres;
	for (int i = 0; i < 16; i++)
	{
		const btScalar r = rng.uniform(0.5, 1.5);
		const btVector3 c = rng.vector(8);
		f.add(f.own(new btSphereShape(r)), at(c));
		spheres.push_back(std::make_pair(c, r));
	}
	const btScalar castRadius = btScalar(0.4);
	btSphereShape cast(castRadius);
	int hits = 0;
	for (int k = 0; k < 100; k++)
	{
		const btVector3 from = rng.unitVector() * btScalar(20);
		const btVector3 to = spheres[rng.integer(0, 15)].first + rng.vector(1.5);
		Hit best;
		btVector3 bestCenter(0, 0, 0);
		btScalar bestRadius = 0;
		double second = 2;
		bool ambiguous = false;
		for (const auto& s : spheres)
		{
			// Segments that pass (or end) within the stopping distance of touching may or may not hit.
			const btVector3 d = to - from;
			const btScalar u = btMax(btScalar(0), btMin(btScalar(1), (s.first - from).dot(d) / d.length2()));
			const double closest = (from + d * u - s.first).length() - (s.second + castRadius);
			ambiguous = ambiguous || std::fabs(closest) < 4 * kSweepStopDistance;
			const Hit h = raySphere(from, to, s.first, s.second + castRadius);
			if (!h.hit) continue;
			if (h.fraction < best.fraction)
			{
				second = best.fraction;
				best = h;
				bestCenter = s.first;
				bestRadius = s.second;
			}
			else
				second = std::min(second, h.fraction);
		}
		btCollisionWorld::ClosestConvexResultCallback cb(from, to);
		f.m_world.convexSweepTest(&cast, sweepPose(from), sweepPose(to), cb);
		if (ambiguous) continue;
		if (best.hit && std::fabs(double((to - from).normalized().dot(best.normal))) < 0.05) continue;  // grazing
		const double tol = best.hit ? sweepTolerance(from, to, best.normal) : 0;
		if (best.hit && second - best.fraction < 2 * tol) continue;  // near tie
		ASSERT_EQ(cb.hasHit(), best.hit) << "sweep " << k;
		if (!best.hit) continue;
		hits++;
		EXPECT_NEAR(cb.m_closestHitFraction, best.fraction, tol) << "sweep " << k;
		EXPECT_GT(cb.m_hitNormalWorld.dot(best.normal), btScalar(0.999)) << "sweep " << k;
		// The point lies on the object's surface, where the normal leaves it.
		EXPECT_LE((cb.m_hitPointWorld - (bestCenter + best.normal * bestRadius)).length(), btScalar(0.01)) << k;
		EXPECT_EQ(cb.m_hitCollisionObject->getWorldTransform().getOrigin(), bestCenter);
	}
	EXPECT_GT(hits, 40);
}

TEST(CollisionWorldConvexSweep, SphereOntoRotatedBoxFacesMatchesGapOverTravel)
{
	WorldFixture f;
	Random rng(202);
	const btScalar castRadius = btScalar(0.3);
	btSphereShape cast(castRadius);
	for (int k = 0; k < 30; k++)
	{
		const btVector3 he(rng.uniform(0.8, 2), rng.uniform(0.8, 2), rng.uniform(0.8, 2));
		btBoxShape* box = f.own(new btBoxShape(he));
		const btTransform t = placed(rng.rotation(), rng.vector(3) + btVector3(btScalar(40 * k), 0, 0));
		f.add(box, t);
		const int axis = k % 3;
		const btScalar sign = (k / 3) % 2 ? btScalar(1) : btScalar(-1);
		btVector3 nLocal(0, 0, 0);
		nLocal[axis] = sign;
		// A start over the face's interior (away from its rounded edges), gap above it.
		btVector3 onFace(rng.uniform(-0.5, 0.5) * he.x(), rng.uniform(-0.5, 0.5) * he.y(),
		                 rng.uniform(-0.5, 0.5) * he.z());
		onFace[axis] = sign * he[axis];
		const btScalar gap = rng.uniform(0.5, 3), travel = gap + rng.uniform(0.5, 2);
		const btVector3 n = t.getBasis() * nLocal;
		const btVector3 from = t * onFace + n * (castRadius + gap);
		const btVector3 to = from - n * travel;
		btCollisionWorld::ClosestConvexResultCallback cb(from, to);
		f.m_world.convexSweepTest(&cast, sweepPose(from), sweepPose(to), cb);
		ASSERT_TRUE(cb.hasHit()) << "sweep " << k;
		EXPECT_NEAR(cb.m_closestHitFraction, gap / travel, sweepTolerance(from, to, n)) << "sweep " << k;
		EXPECT_GT(cb.m_hitNormalWorld.dot(n), btScalar(0.999)) << "sweep " << k;
		EXPECT_LE((cb.m_hitPointWorld - t * onFace).length(), btScalar(0.01)) << "sweep " << k;
	}
}

TEST(CollisionWorldConvexSweep, SphereOntoMeshesAndHeightfieldLandsAtRadiusAbove)
{
	WorldFixture f;
	std::unique_ptr<btTriangleMesh> grid(flatGrid(8, 5));
	btBvhTriangleMeshShape* bvh = f.own(new btBvhTriangleMeshShape(grid.get(), true));
	btScaledBvhTriangleMeshShape* scaled = f.own(new btScaledBvhTriangleMeshShape(bvh, btVector3(2, 1, 0.5)));
	std::vector<float> heights(6 * 6, 1.0f);
	btHeightfieldTerrainShape* terrain =
	    f.own(new btHeightfieldTerrainShape(6, 6, heights.data(), btScalar(0), btScalar(2), 1, false));
	// Flat surfaces, tilted in the world: the time of impact is (height - radius) / descent along the normal.
	const btQuaternion tilt(btVector3(1, 0, 1).normalized(), btScalar(0.3));
	struct Case
	{
		btCollisionShape* shape;
		btVector3 surfaceLocal;  // a point of the flat surface, shape frame
	};
	// The heightfield's frame is centred on its height range [0, 2]: height 1 lies at local y = 0.
	const Case cases[] = {
	    {bvh, btVector3(0.3, 0, 0.2)}, {scaled, btVector3(0.3, 0, 0.2)}, {terrain, btVector3(0.3, 0, 0.2)}};
	const btScalar castRadius = btScalar(0.5);
	btSphereShape cast(castRadius);
	int which = 0;
	for (const Case& c : cases)
	{
		const btTransform t = placed(tilt, btVector3(btScalar(30 * which), 0, 0));
		btCollisionObject* object = f.add(c.shape, t);
		const btVector3 n = t.getBasis() * btVector3(0, 1, 0);
		const btVector3 from = t * c.surfaceLocal + n * btScalar(3), to = t * c.surfaceLocal - n * btScalar(1);
		RecordingConvexCallback cb;
		f.m_world.convexSweepTest(&cast, sweepPose(from), sweepPose(to), cb);
		ASSERT_TRUE(cb.m_last.hit) << "case " << which;
		EXPECT_EQ(cb.m_last.object, object);
		EXPECT_NEAR(cb.m_last.fraction, (3 - castRadius) / 4, sweepTolerance(from, to, n)) << "case " << which;
		EXPECT_GT(cb.m_last.normal.dot(n), btScalar(0.999)) << "case " << which;
		EXPECT_LE((cb.m_last.point - t * c.surfaceLocal).length(), btScalar(0.01)) << "case " << which;
		EXPECT_GE(cb.m_last.index, 0) << "case " << which;  // the triangle is named
		which++;
	}
}

TEST(CollisionWorldConvexSweep, BoxOntoStaticPlane)
{
	WorldFixture f;
	btStaticPlaneShape* plane = f.own(new btStaticPlaneShape(btVector3(0, 1, 0), 1));
	f.add(plane, at(btVector3(0, 0, 0)));
	btBoxShape cast(btVector3(0.5, 0.5, 0.5));
	const btVector3 from(2, 5, 1), to(2, -3, 1);
	btCollisionWorld::ClosestConvexResultCallback cb(from, to);
	f.m_world.convexSweepTest(&cast, sweepPose(from), sweepPose(to), cb);
	ASSERT_TRUE(cb.hasHit());
	// The box's bottom face (y - 0.5) reaches the plane y = 1 after 3.5 of 8 units.
	EXPECT_NEAR(cb.m_closestHitFraction, 3.5 / 8, sweepTolerance(from, to, btVector3(0, 1, 0)));
	EXPECT_GT(cb.m_hitNormalWorld.y(), btScalar(0.999));
}

TEST(CollisionWorldConvexSweep, CompoundReportsTheChildIndex)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	for (int useTree = 0; useTree < 2; useTree++)
	{
		btCompoundShape* compound = f.own(new btCompoundShape(useTree == 1));
		for (int i = 0; i < 3; i++) compound->addChildShape(at(btVector3(btScalar(4 * (i - 1)), 0, 0)), sphere);
		const btTransform t = at(btVector3(0, btScalar(20 * useTree), 0));
		btCollisionObject* object = f.add(compound, t);
		btSphereShape cast(btScalar(0.5));
		for (int child = 0; child < 3; child++)
		{
			const btVector3 target = t * btVector3(btScalar(4 * (child - 1)), 0, 0);
			const btVector3 from = target + btVector3(0, 5, 0), to = target - btVector3(0, 5, 0);
			RecordingConvexCallback cb;
			f.m_world.convexSweepTest(&cast, sweepPose(from), sweepPose(to), cb);
			ASSERT_TRUE(cb.m_last.hit);
			EXPECT_EQ(cb.m_last.object, object);
			EXPECT_EQ(cb.m_last.part, -1);
			EXPECT_EQ(cb.m_last.index, child);
			EXPECT_NEAR(cb.m_last.fraction, 3.5 / 10, sweepTolerance(from, to, btVector3(0, 1, 0)));
		}
	}
}

TEST(CollisionWorldConvexSweep, GroupMaskAndStartInContact)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	f.add(sphere, at(btVector3(0, 0, 0)), 2, btBroadphaseProxy::AllFilter);
	btCollisionObject* far = f.add(sphere, at(btVector3(0, -6, 0)), 4, btBroadphaseProxy::AllFilter);
	btSphereShape cast(btScalar(0.5));
	const btVector3 from(0, 5, 0), to(0, -10, 0);
	btCollisionWorld::ClosestConvexResultCallback skipNear(from, to);
	skipNear.m_collisionFilterMask = 4;
	f.m_world.convexSweepTest(&cast, sweepPose(from), sweepPose(to), skipNear);
	ASSERT_TRUE(skipNear.hasHit());
	EXPECT_EQ(skipNear.m_hitCollisionObject, far);
	EXPECT_NEAR(skipNear.m_closestHitFraction, 9.5 / 15, sweepTolerance(from, to, btVector3(0, 1, 0)));

	// Starting overlapping: a hit at fraction 0 (the casts' documented behaviour).
	btCollisionWorld::ClosestConvexResultCallback inside(btVector3(0, 1, 0), btVector3(0, 3, 0));
	f.m_world.convexSweepTest(&cast, sweepPose(btVector3(0, 1, 0)), sweepPose(btVector3(0, 3, 0)), inside);
	ASSERT_TRUE(inside.m_hitCollisionObject != 0);
	EXPECT_EQ(inside.m_closestHitFraction, btScalar(0));
}

TEST(CollisionWorldConvexSweep, NonFiniteSweepAssertsOrHitsNothing)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	f.add(sphere, at(btVector3(0, 0, 0)));
	btSphereShape cast(btScalar(0.5));
	const btVector3 nanPoint(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0);
	btCollisionWorld::ClosestConvexResultCallback cb(nanPoint, btVector3(0, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.convexSweepTest(&cast, sweepPose(nanPoint), sweepPose(btVector3(0, 0, 0)), cb),
	             "assertion failed");
	EXPECT_DEATH(f.m_world.convexSweepTest(0, sweepPose(btVector3(0, 5, 0)), sweepPose(btVector3(0, 0, 0)), cb),
	             "assertion failed");
#else
	f.m_world.convexSweepTest(&cast, sweepPose(nanPoint), sweepPose(btVector3(0, 0, 0)), cb);
	EXPECT_FALSE(cb.hasHit());
	f.m_world.convexSweepTest(0, sweepPose(btVector3(0, 5, 0)), sweepPose(btVector3(0, 0, 0)), cb);
	EXPECT_FALSE(cb.hasHit());
#endif
}
