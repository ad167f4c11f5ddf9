// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// btCollisionWorld::rayTest against analytic references: spheres, boxes, planes, triangle meshes (plain,
// scaled, height fields), compounds; flags, rays starting inside, zero-length and grazing rays, filtering.

#include <gtest/gtest.h>

#include <limits>
#include <set>

#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btCompoundShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h"
#include "BulletCollision/CollisionShapes/btScaledBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btStaticPlaneShape.h"
#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletCollision/NarrowPhaseCollision/btConvexCast.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"
#include "CollisionWorldTestUtil.h"

using namespace caliber_world_test;

namespace
{
// Convex ray tests stop when the point is within sqrt(MAX_CONVEX_CAST_EPSILON) of the surface (1e-3 in
// float, 1e-6 in double); the fraction is then low by that distance over the speed at which the gap
// closes (ray length times the cosine between ray and normal). Plus rounding of the references.
const double kConvexStopDistance = std::sqrt(double(MAX_CONVEX_CAST_EPSILON));
// Triangle and plane tests are closed-form: a few hundred ulps of the coordinates (up to ~20 units here).
const double kClosedFormTolerance = sizeof(btScalar) == 4 ? 2e-5 : 1e-11;

double convexFractionTolerance(const btVector3& from, const btVector3& to, const btVector3& normal)
{
	const double closing = std::fabs(double((to - from).dot(normal)));
	return 1.5 * kConvexStopDistance / closing + 1e-5;
}

// Records every triangle of a concave shape, in world space (placed by t).
struct TriangleCollector : public btTriangleCallback
{
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		for (int k = 0; k < 3; k++) m_vertices.push_back(m_transform * triangle[k]);
		m_ids.push_back(std::make_pair(partId, triangleIndex));
	}
	btTransform m_transform;
	std::vector<btVector3> m_vertices;
	std::vector<std::pair<int, int>> m_ids;
};

// A bumpy grid of n x n quads (2 triangles each) over [-size, size]^2 in x/z, heights from rng.
btTriangleMesh* bumpyGrid(Random& rng, int n, btScalar size, btScalar bump)
{
	btTriangleMesh* mesh = new btTriangleMesh();
	std::vector<btScalar> heights((n + 1) * (n + 1));
	for (auto& h : heights) h = rng.uniform(-bump, bump);
	auto vertex = [&](int i, int j)
	{ return btVector3(-size + 2 * size * i / n, heights[i * (n + 1) + j], -size + 2 * size * j / n); };
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++)
		{
			// Counter-clockwise seen from +y: front faces point up.
			mesh->addTriangle(vertex(i, j), vertex(i, j + 1), vertex(i + 1, j));
			mesh->addTriangle(vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1));
		}
	return mesh;
}

// Brute force over recorded triangles: the closest hit and its triangle.
Hit closestTriangleHit(const TriangleCollector& tris, const btVector3& from, const btVector3& to, int* which = 0)
{
	Hit best;
	for (size_t t = 0; t < tris.m_ids.size(); t++)
	{
		const Hit h =
		    rayTriangle(from, to, tris.m_vertices[3 * t], tris.m_vertices[3 * t + 1], tris.m_vertices[3 * t + 2]);
		if (h.hit && h.fraction < best.fraction)
		{
			best = h;
			if (which) *which = int(t);
		}
	}
	return best;
}
}  // namespace

TEST(CollisionWorldRayTest, ClosestHitMatchesBruteForceOverSpheresAndBoxes)
{
	WorldFixture f;
	Random rng(11);
	struct Ref
	{
		bool sphere;
		btTransform t;
		btVector3 he;
		btScalar r;
		const btCollisionObject* object;
	};
	std::vector<Ref> refs;
	for (int i = 0; i < 24; i++)
	{
		Ref ref;
		ref.sphere = (i % 2) == 0;
		ref.t = placed(rng.rotation(), rng.vector(8));
		ref.r = rng.uniform(0.4, 1.5);
		ref.he = btVector3(rng.uniform(0.3, 1.5), rng.uniform(0.3, 1.5), rng.uniform(0.3, 1.5));
		btCollisionShape* shape;
		if (ref.sphere)
			shape = f.own(new btSphereShape(ref.r));
		else
		{
			btBoxShape* box = f.own(new btBoxShape(ref.he));
			box->setMargin(0);  // a sharp box, as the reference
			ref.he = box->getHalfExtentsWithMargin();
			shape = box;
		}
		ref.object = f.add(shape, ref.t);
		refs.push_back(ref);
	}
	for (int useGjk = 0; useGjk < 2; useGjk++)
	{
		int hits = 0, checked = 0;
		for (int k = 0; k < 150; k++)
		{
			const btVector3 from = rng.unitVector() * btScalar(20);
			// Two rays in three aim at an object, so that about half of them hit.
			const btVector3 to =
			    (k % 3) ? refs[rng.integer(0, int(refs.size()) - 1)].t.getOrigin() + rng.vector(1.5) : rng.vector(6);
			Hit best;
			const btCollisionObject* bestObject = 0;
			double second = 2;
			for (const Ref& ref : refs)
			{
				const Hit h =
				    ref.sphere ? raySphere(from, to, ref.t.getOrigin(), ref.r) : rayBox(from, to, ref.t, ref.he);
				if (!h.hit) continue;
				if (h.fraction < best.fraction)
				{
					second = best.fraction;
					best = h;
					bestObject = ref.object;
				}
				else
					second = std::min(second, h.fraction);
			}
			btCollisionWorld::ClosestRayResultCallback cb(from, to);
			if (useGjk) cb.m_flags = btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest;
			f.m_world.rayTest(from, to, cb);
			// Grazing hits (closing speed < 5% of the ray) and near ties are ambiguous within the tolerance.
			if (best.hit && std::fabs(double((to - from).normalized().dot(best.normal))) < 0.05) continue;
			const double tol = !best.hit ? 0
			                   : useGjk  ? convexFractionTolerance(from, to, best.normal)
			                             : kClosedFormTolerance;
			if (best.hit && second - best.fraction < 2 * tol) continue;
			checked++;
			ASSERT_EQ(cb.hasHit(), best.hit) << "ray " << k << " gjk " << useGjk;
			if (!best.hit) continue;
			hits++;
			EXPECT_EQ(cb.m_collisionObject, bestObject) << "ray " << k;
			EXPECT_NEAR(cb.m_closestHitFraction, best.fraction, tol) << "ray " << k << " gjk " << useGjk;
			// Closed form (default): exact. The GJK cast's normal comes from GJK at the stopping distance, within
			// a few degrees on flat faces (measured up to 16 degrees on zero-margin boxes).
			EXPECT_GT(cb.m_hitNormalWorld.dot(best.normal), btScalar(useGjk ? 0.95 : 0.9999)) << "ray " << k;
			EXPECT_NEAR(cb.m_hitNormalWorld.length(), 1, 1e-4);
		}
		EXPECT_GT(hits, 45);
		EXPECT_GT(checked, 120);
	}
}

TEST(CollisionWorldRayTest, AllHitsReportsEveryObjectOnTheRay)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	std::vector<btCollisionObject*> row;
	for (int i = 0; i < 5; i++) row.push_back(f.add(sphere, at(btVector3(btScalar(4 * i), 0, 0))));
	btCollisionObject* off = f.add(sphere, at(btVector3(8, 5, 0)));
	const btVector3 from(-5, 0.5, 0), to(25, 0.5, 0);
	btCollisionWorld::AllHitsRayResultCallback cb(from, to);
	f.m_world.rayTest(from, to, cb);
	ASSERT_EQ(cb.m_collisionObjects.size(), 5);
	EXPECT_TRUE(cb.hasHit());
	std::set<const btCollisionObject*> seen;
	for (int i = 0; i < cb.m_collisionObjects.size(); i++)
	{
		seen.insert(cb.m_collisionObjects[i]);
		EXPECT_NE(cb.m_collisionObjects[i], off);
		const btVector3 c = cb.m_collisionObjects[i]->getWorldTransform().getOrigin();
		const Hit h = raySphere(from, to, c, 1);
		EXPECT_NEAR(cb.m_hitFractions[i], h.fraction, convexFractionTolerance(from, to, h.normal));
		EXPECT_GT(cb.m_hitNormalWorld[i].dot(h.normal), btScalar(0.999));
		const btVector3 expectedPoint = from.lerp(to, cb.m_hitFractions[i]);
		EXPECT_LE((cb.m_hitPointWorld[i] - expectedPoint).length(), btScalar(1e-4));
	}
	EXPECT_EQ(seen.size(), 5u);
}

TEST(CollisionWorldRayTest, BvhMeshHitsMatchMollerTrumboreWithTriangleIds)
{
	WorldFixture f;
	Random rng(21);
	std::unique_ptr<btTriangleMesh> mesh(bumpyGrid(rng, 12, 10, 1));
	btBvhTriangleMeshShape* shape = f.own(new btBvhTriangleMeshShape(mesh.get(), true));
	const btTransform t = placed(btQuaternion(btVector3(1, 0, 1).normalized(), btScalar(0.3)), btVector3(1, -2, 3));
	btCollisionObject* object = f.add(shape, t);
	TriangleCollector tris;
	tris.m_transform = t;
	shape->processAllTriangles(&tris, btVector3(-100, -100, -100), btVector3(100, 100, 100));
	ASSERT_EQ(tris.m_ids.size(), 12u * 12u * 2u);

	int hits = 0;
	for (int k = 0; k < 300; k++)
	{
		const btVector3 from = t * btVector3(rng.uniform(-12, 12), rng.uniform(-6, 6), rng.uniform(-12, 12));
		const btVector3 to = t * btVector3(rng.uniform(-12, 12), rng.uniform(-6, 6), rng.uniform(-12, 12));
		int which = -1;
		const Hit best = closestTriangleHit(tris, from, to, &which);
		RecordingRayCallback cb;
		f.m_world.rayTest(from, to, cb);
		// Skip rays whose closest hit is within rounding of a triangle edge (either triangle may be reported).
		if (best.hit)
		{
			const btVector3 p = from.lerp(to, btScalar(best.fraction));
			const btVector3* v = &tris.m_vertices[3 * which];
			bool nearEdge = false;
			for (int e = 0; e < 3; e++)
			{
				const btVector3 a = v[e], b = v[(e + 1) % 3];
				const btVector3 ab = b - a;
				const btScalar s = btMax(btScalar(0), btMin(btScalar(1), (p - a).dot(ab) / ab.length2()));
				nearEdge = nearEdge || (p - (a + ab * s)).length() < btScalar(1e-3);
			}
			if (nearEdge) continue;
		}
		ASSERT_EQ(!cb.m_entries.empty(), best.hit) << "ray " << k;
		if (!best.hit) continue;
		hits++;
		const RecordingRayCallback::Entry& e = cb.m_entries.back();
		EXPECT_EQ(e.object, object);
		EXPECT_NEAR(e.fraction, best.fraction, kClosedFormTolerance) << "ray " << k;
		EXPECT_GT(e.normal.dot(best.normal), btScalar(0.9999)) << "ray " << k;
		EXPECT_EQ(e.part, tris.m_ids[which].first);
		EXPECT_EQ(e.index, tris.m_ids[which].second);
	}
	EXPECT_GT(hits, 100);
}

TEST(CollisionWorldRayTest, BackfaceFlagsOnMeshes)
{
	WorldFixture f;
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(-5, 0, -5), btVector3(-5, 0, 5), btVector3(5, 0, -5));  // front face up
	btBvhTriangleMeshShape* shape = f.own(new btBvhTriangleMeshShape(&mesh, true));
	f.add(shape, at(btVector3(0, 1, 0)));
	const btVector3 above(-1, 5, -1), below(-1, -3, -1);

	btCollisionWorld::ClosestRayResultCallback down(above, below);
	down.m_flags = btTriangleRaycastCallback::kF_FilterBackfaces;
	f.m_world.rayTest(above, below, down);
	ASSERT_TRUE(down.hasHit());
	EXPECT_NEAR(down.m_closestHitFraction, 0.5, kClosedFormTolerance);
	EXPECT_GT(down.m_hitNormalWorld.y(), btScalar(0.9999));

	btCollisionWorld::ClosestRayResultCallback upCulled(below, above);
	upCulled.m_flags = btTriangleRaycastCallback::kF_FilterBackfaces;
	f.m_world.rayTest(below, above, upCulled);
	EXPECT_FALSE(upCulled.hasHit());

	btCollisionWorld::ClosestRayResultCallback up(below, above);
	f.m_world.rayTest(below, above, up);
	ASSERT_TRUE(up.hasHit());
	EXPECT_LT(up.m_hitNormalWorld.y(), btScalar(-0.9999));  // faces the ray origin

	btCollisionWorld::ClosestRayResultCallback upUnflipped(below, above);
	upUnflipped.m_flags = btTriangleRaycastCallback::kF_KeepUnflippedNormal;
	f.m_world.rayTest(below, above, upUnflipped);
	ASSERT_TRUE(upUnflipped.hasHit());
	EXPECT_GT(upUnflipped.m_hitNormalWorld.y(), btScalar(0.9999));
}

TEST(CollisionWorldRayTest, ScaledMeshHitsTheScaledTrianglesWithTheirNormals)
{
	WorldFixture f;
	Random rng(31);
	std::unique_ptr<btTriangleMesh> mesh(bumpyGrid(rng, 6, 3, 1));
	btBvhTriangleMeshShape* child = f.own(new btBvhTriangleMeshShape(mesh.get(), true));
	const btVector3 scale(2, 0.5, 3);
	btScaledBvhTriangleMeshShape* shape = f.own(new btScaledBvhTriangleMeshShape(child, scale));
	const btTransform t = placed(btQuaternion(btVector3(0, 1, 0), btScalar(0.7)), btVector3(0, 1, 0));
	f.add(shape, t);
	TriangleCollector tris;
	tris.m_transform = t;
	shape->processAllTriangles(&tris, btVector3(-100, -100, -100), btVector3(100, 100, 100));
	// The reference scales the raw vertices itself.
	TriangleCollector raw;
	raw.m_transform.setIdentity();
	child->processAllTriangles(&raw, btVector3(-100, -100, -100), btVector3(100, 100, 100));
	ASSERT_EQ(raw.m_ids.size(), tris.m_ids.size());
	for (size_t i = 0; i < raw.m_vertices.size(); i++) tris.m_vertices[i] = t * (raw.m_vertices[i] * scale);

	int hits = 0;
	for (int k = 0; k < 200; k++)
	{
		const btVector3 from = t * btVector3(rng.uniform(-6, 6), 4, rng.uniform(-9, 9));
		const btVector3 to = t * btVector3(rng.uniform(-6, 6), -4, rng.uniform(-9, 9));
		const Hit best = closestTriangleHit(tris, from, to);
		btCollisionWorld::ClosestRayResultCallback cb(from, to);
		f.m_world.rayTest(from, to, cb);
		ASSERT_EQ(cb.hasHit(), best.hit) << "ray " << k;
		if (!best.hit) continue;
		hits++;
		EXPECT_NEAR(cb.m_closestHitFraction, best.fraction, kClosedFormTolerance) << "ray " << k;
		EXPECT_GT(cb.m_hitNormalWorld.dot(best.normal), btScalar(0.9999)) << "ray " << k;
	}
	EXPECT_GT(hits, 50);
}

TEST(CollisionWorldRayTest, HeightfieldHitsMatchItsTriangles)
{
	WorldFixture f;
	Random rng(41);
	const int w = 9, l = 7;
	std::vector<float> heights(w * l);
	for (float& h : heights) h = float(rng.uniform(0, 2));
	btHeightfieldTerrainShape* shape =
	    f.own(new btHeightfieldTerrainShape(w, l, heights.data(), btScalar(0), btScalar(2), 1, false));
	const btTransform t = at(btVector3(3, 0, -2));
	f.add(shape, t);
	TriangleCollector tris;
	tris.m_transform = t;
	shape->processAllTriangles(&tris, btVector3(-100, -100, -100), btVector3(100, 100, 100));
	ASSERT_EQ(tris.m_ids.size(), size_t(2 * (w - 1) * (l - 1)));
	int hits = 0;
	for (int k = 0; k < 200; k++)
	{
		const btVector3 from = t * btVector3(rng.uniform(-5, 5), 3, rng.uniform(-4, 4));
		const btVector3 to = t * btVector3(rng.uniform(-5, 5), -3, rng.uniform(-4, 4));
		const Hit best = closestTriangleHit(tris, from, to);
		btCollisionWorld::ClosestRayResultCallback cb(from, to);
		f.m_world.rayTest(from, to, cb);
		ASSERT_EQ(cb.hasHit(), best.hit) << "ray " << k;
		if (!best.hit) continue;
		hits++;
		EXPECT_NEAR(cb.m_closestHitFraction, best.fraction, kClosedFormTolerance) << "ray " << k;
		EXPECT_GT(cb.m_hitNormalWorld.dot(best.normal), btScalar(0.9999)) << "ray " << k;
	}
	EXPECT_GT(hits, 50);
}

TEST(CollisionWorldRayTest, StaticPlaneHitIsExactFromBothSides)
{
	WorldFixture f;
	btStaticPlaneShape* plane = f.own(new btStaticPlaneShape(btVector3(0, 1, 0), 2));
	const btTransform t = placed(btQuaternion(btVector3(1, 0, 0), btScalar(0.4)), btVector3(0, 1, 0));
	f.add(plane, t);
	const btVector3 n = t.getBasis() * btVector3(0, 1, 0);
	const btVector3 onPlane = t * btVector3(0, 2, 0);
	Random rng(5);
	for (int k = 0; k < 50; k++)
	{
		const btVector3 from = onPlane + rng.vector(10);
		const btVector3 to = onPlane + rng.vector(10);
		const double d0 = (from - onPlane).dot(n), d1 = (to - onPlane).dot(n);
		btCollisionWorld::ClosestRayResultCallback cb(from, to);
		cb.m_flags = (k % 2) ? unsigned(btTriangleRaycastCallback::kF_FilterBackfaces) : 0u;
		f.m_world.rayTest(from, to, cb);
		const bool crosses = d0 * d1 < 0 && !((k % 2) && d0 < 0);
		ASSERT_EQ(cb.hasHit(), crosses) << "ray " << k;
		if (!crosses) continue;
		EXPECT_NEAR(cb.m_closestHitFraction, d0 / (d0 - d1), kClosedFormTolerance);
		EXPECT_GT(cb.m_hitNormalWorld.dot(d0 > 0 ? n : -n), btScalar(0.9999));
	}
}

TEST(CollisionWorldRayTest, CompoundReportsTheChildIndex)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btBoxShape* box = f.own(new btBoxShape(btVector3(1, 1, 1)));
	box->setMargin(0);
	for (int useTree = 0; useTree < 2; useTree++)
	{
		btCompoundShape* compound = f.own(new btCompoundShape(useTree == 1));
		compound->addChildShape(at(btVector3(-3, 0, 0)), sphere);
		compound->addChildShape(at(btVector3(0, 0, 0)), box);
		compound->addChildShape(at(btVector3(3, 0, 0)), sphere);
		const btTransform t =
		    placed(btQuaternion(btVector3(0, 0, 1), btScalar(0.2)), btVector3(0, btScalar(10 * useTree), 0));
		btCollisionObject* object = f.add(compound, t);
		for (int child = 0; child < 3; child++)
		{
			const btVector3 target = t * btVector3(btScalar(3 * (child - 1)), 0, 0);
			const btVector3 from = target + btVector3(0.2, 5, 0.1), to = target - btVector3(0, 5, 0);
			RecordingRayCallback cb;
			f.m_world.rayTest(from, to, cb);
			ASSERT_FALSE(cb.m_entries.empty());
			const RecordingRayCallback::Entry& e = cb.m_entries.back();
			EXPECT_EQ(e.object, object);
			EXPECT_EQ(e.part, -1);
			EXPECT_EQ(e.index, child);
			const Hit h = child == 1 ? rayBox(from, to, t, btVector3(1, 1, 1)) : raySphere(from, to, target, 1);
			ASSERT_TRUE(h.hit);
			EXPECT_NEAR(e.fraction, h.fraction, convexFractionTolerance(from, to, h.normal));
		}
	}
}

// Bullet's semantics for rays that start inside a convex shape (its default btSubsimplexConvexCast reports
// no hit without an advance, and btGjkConvexCast without a depth solver finds no contact): the shape is
// not hit, and the ray goes on to what lies beyond it. Each shape here holds the ray's start; a wall at
// x = 10 (its face at x = 9.5) is the first thing the ray enters, at fraction (9.5 - x0) / (20 - x0).
TEST(CollisionWorldRayTest, RayStartingInsideAConvexShapeDoesNotHitIt)
{
	btSphereShape sphere(2);
	btBoxShape box(btVector3(1, 2, 3));
	box.setMargin(0);
	btCapsuleShape capsule(1, 2);
	btConvexHullShape hull;
	for (int corner = 0; corner < 8; ++corner)
		hull.addPoint(btVector3(corner & 1 ? 1.5 : -1, corner & 2 ? 1 : -1.5, corner & 4 ? 1 : -1), false);
	hull.recalcLocalAabb();
	// The same hull with polyhedral features: the ray test's face-plane test decides the deep start.
	btConvexHullShape hullWithFaces(hull);
	ASSERT_TRUE(hullWithFaces.initializePolyhedralFeatures());
	btCollisionShape* shapes[] = {&sphere, &box, &capsule, &hull, &hullWithFaces};
	const char* names[] = {"sphere", "box", "capsule", "hull", "hull with faces"};
	// Where +x leaves each shape (at y = 0.2, z = 0).
	const btScalar surfaceX[] = {2, 1, 1, btScalar(1.5), btScalar(1.5)};
	const unsigned int flagSets[] = {0u, unsigned(btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest)};
	for (int k = 0; k < 5; ++k)
	{
		WorldFixture f;
		btBoxShape* wallShape = f.own(new btBoxShape(btVector3(0.5, 5, 5)));
		wallShape->setMargin(0);
		const btCollisionObject* wall = f.add(wallShape, at(btVector3(10, 0, 0)));
		const btCollisionObject* holder = f.add(shapes[k], at(btVector3(0, 0, 0)));
		for (unsigned int flags : flagSets)
		{
			SCOPED_TRACE(std::string(names[k]) + (flags ? " gjk cast" : " default"));
			// From near the centre, and from 0.3 inside the surface (the margin's depth is 0.04 for the
			// capsule and hull), along +x out through the shape towards the wall.
			for (btScalar x0 : {btScalar(0.1), surfaceX[k] - btScalar(0.3)})
			{
				const btVector3 from(x0, btScalar(0.2), 0), to(20, btScalar(0.2), 0);
				btCollisionWorld::ClosestRayResultCallback ray(from, to);
				ray.m_flags = flags;
				f.m_world.rayTest(from, to, ray);
				ASSERT_TRUE(ray.hasHit());
				EXPECT_EQ(ray.m_collisionObject, wall);
				// The wall is a box, tested in closed form: exact but for float rounding.
				EXPECT_NEAR(ray.m_closestHitFraction, (9.5 - x0) / (20 - x0), 1e-5);
				btCollisionWorld::AllHitsRayResultCallback all(from, to);
				all.m_flags = flags;
				f.m_world.rayTest(from, to, all);
				for (int i = 0; i < all.m_collisionObjects.size(); ++i) EXPECT_NE(all.m_collisionObjects[i], holder);
			}
			// Zero-length rays inside hit nothing either.
			btCollisionWorld::AllHitsRayResultCallback zero(btVector3(0.1, 0.2, 0), btVector3(0.1, 0.2, 0));
			zero.m_flags = flags;
			f.m_world.rayTest(zero.m_rayFromWorld, zero.m_rayToWorld, zero);
			EXPECT_FALSE(zero.hasHit());
			// The same shape seen from outside is hit where the ray enters it (the wall is behind the start).
			const btVector3 outside(-6, btScalar(0.2), 0);
			btCollisionWorld::ClosestRayResultCallback in(outside, btVector3(0, btScalar(0.2), 0));
			in.m_flags = flags;
			f.m_world.rayTest(in.m_rayFromWorld, in.m_rayToWorld, in);
			ASSERT_TRUE(in.hasHit());
			EXPECT_EQ(in.m_collisionObject, holder);
			EXPECT_LT(in.m_closestHitFraction, btScalar(1));
			EXPECT_LT(in.m_hitNormalWorld.x(), btScalar(-0.9));
		}
	}
}

// The closed forms' boundary: a ray that starts on a sphere's or box's surface and heads in hits at 0
// with the outward normal there; heading out it does not hit.
TEST(CollisionWorldRayTest, RayStartingOnTheSurfaceHitsAtZeroOnlyWhenHeadingIn)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(2));
	btBoxShape* box = f.own(new btBoxShape(btVector3(1, 2, 3)));
	box->setMargin(0);
	f.add(sphere, at(btVector3(0, 0, 0)));
	f.add(box, at(btVector3(20, 0, 0)));

	btCollisionWorld::ClosestRayResultCallback inSphere(btVector3(0, 2, 0), btVector3(0, -5, 0));
	f.m_world.rayTest(inSphere.m_rayFromWorld, inSphere.m_rayToWorld, inSphere);
	ASSERT_TRUE(inSphere.hasHit());
	EXPECT_EQ(inSphere.m_closestHitFraction, btScalar(0));
	EXPECT_GT(inSphere.m_hitNormalWorld.y(), btScalar(0.9999));
	btCollisionWorld::ClosestRayResultCallback outSphere(btVector3(0, 2, 0), btVector3(0, 5, 0));
	f.m_world.rayTest(outSphere.m_rayFromWorld, outSphere.m_rayToWorld, outSphere);
	EXPECT_FALSE(outSphere.hasHit());

	btCollisionWorld::ClosestRayResultCallback inBox(btVector3(19, 0.5, 0), btVector3(25, 0.5, 0));
	f.m_world.rayTest(inBox.m_rayFromWorld, inBox.m_rayToWorld, inBox);
	ASSERT_TRUE(inBox.hasHit());
	EXPECT_EQ(inBox.m_closestHitFraction, btScalar(0));
	EXPECT_GT(inBox.m_hitNormalWorld.dot(btVector3(-1, 0, 0)), btScalar(0.9999));
	btCollisionWorld::ClosestRayResultCallback outBox(btVector3(19, 0.5, 0), btVector3(15, 0.5, 0));
	f.m_world.rayTest(outBox.m_rayFromWorld, outBox.m_rayToWorld, outBox);
	EXPECT_FALSE(outBox.hasHit());
}

TEST(CollisionWorldRayTest, MeshesAreSurfacesAndZeroLengthRaysMissThem)
{
	WorldFixture f;
	btTriangleMesh mesh;
	// A closed tetrahedron: a ray from inside hits the far face, not fraction 0.
	const btVector3 a(0, 0, 0), b(4, 0, 0), c(0, 4, 0), d(0, 0, 4);
	mesh.addTriangle(a, c, b);
	mesh.addTriangle(a, b, d);
	mesh.addTriangle(a, d, c);
	mesh.addTriangle(b, c, d);
	btBvhTriangleMeshShape* shape = f.own(new btBvhTriangleMeshShape(&mesh, true));
	f.add(shape, at(btVector3(0, 0, 0)));
	const btVector3 inside(0.5, 0.5, 0.5);
	btCollisionWorld::ClosestRayResultCallback out(inside, btVector3(0.5, 0.5, -1.5));
	f.m_world.rayTest(out.m_rayFromWorld, out.m_rayToWorld, out);
	ASSERT_TRUE(out.hasHit());
	EXPECT_NEAR(out.m_closestHitFraction, 0.25, kClosedFormTolerance);
	EXPECT_GT(out.m_hitNormalWorld.z(), btScalar(0.9999));  // faces the ray origin (inside)
	btCollisionWorld::ClosestRayResultCallback zero(inside, inside);
	f.m_world.rayTest(inside, inside, zero);
	EXPECT_FALSE(zero.hasHit());
}

TEST(CollisionWorldRayTest, RaysGrazingABoxEdgeHitOnlyWhenTheyTouchIt)
{
	WorldFixture f;
	btBoxShape* box = f.own(new btBoxShape(btVector3(1, 1, 1)));
	box->setMargin(0);
	f.add(box, at(btVector3(0, 0, 0)));
	// Rays parallel to the top face, passing the edge at y = 1, z = 1 just outside / just inside.
	const btScalar offset = btScalar(sizeof(btScalar) == 4 ? 5e-3 : 1e-5);
	btCollisionWorld::ClosestRayResultCallback outside(btVector3(-5, 1 + offset, 1 + offset),
	                                                   btVector3(5, 1 + offset, 1 + offset));
	f.m_world.rayTest(outside.m_rayFromWorld, outside.m_rayToWorld, outside);
	EXPECT_FALSE(outside.hasHit());
	btCollisionWorld::ClosestRayResultCallback inside(btVector3(-5, 1 - offset, 1 - offset),
	                                                  btVector3(5, 1 - offset, 1 - offset));
	f.m_world.rayTest(inside.m_rayFromWorld, inside.m_rayToWorld, inside);
	ASSERT_TRUE(inside.hasHit());
	EXPECT_NEAR(inside.m_closestHitFraction, 0.4,
	            convexFractionTolerance(inside.m_rayFromWorld, inside.m_rayToWorld, btVector3(-1, 0, 0)));
	EXPECT_GT(inside.m_hitNormalWorld.x(), btScalar(-1.0001));
	EXPECT_LT(inside.m_hitNormalWorld.x(), btScalar(-0.99));

	// Through the shared diagonal of a two-triangle quad: exactly the hit fraction, from either triangle.
	btTriangleMesh quad;
	quad.addTriangle(btVector3(-1, 0, -1), btVector3(-1, 0, 1), btVector3(1, 0, -1));
	quad.addTriangle(btVector3(1, 0, -1), btVector3(-1, 0, 1), btVector3(1, 0, 1));
	btBvhTriangleMeshShape* quadShape = f.own(new btBvhTriangleMeshShape(&quad, true));
	f.add(quadShape, at(btVector3(10, 0, 0)));
	btCollisionWorld::ClosestRayResultCallback diagonal(btVector3(10.25, 1, -0.25), btVector3(10.25, -1, -0.25));
	f.m_world.rayTest(diagonal.m_rayFromWorld, diagonal.m_rayToWorld, diagonal);
	ASSERT_TRUE(diagonal.hasHit());
	EXPECT_NEAR(diagonal.m_closestHitFraction, 0.5, kClosedFormTolerance);
}

TEST(CollisionWorldRayTest, GroupAndMaskFilterBothWays)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	btCollisionObject* near = f.add(sphere, at(btVector3(0, 0, 0)), 2, btBroadphaseProxy::AllFilter);
	btCollisionObject* middle = f.add(sphere, at(btVector3(4, 0, 0)), 4, 1);  // accepts only group 1 rays
	btCollisionObject* far = f.add(sphere, at(btVector3(8, 0, 0)), 8, btBroadphaseProxy::AllFilter);
	const btVector3 from(-5, 0, 0), to(15, 0, 0);

	btCollisionWorld::AllHitsRayResultCallback all(from, to);
	f.m_world.rayTest(from, to, all);
	EXPECT_EQ(all.m_collisionObjects.size(), 3);

	btCollisionWorld::AllHitsRayResultCallback skipNear(from, to);
	skipNear.m_collisionFilterMask = 4 | 8;
	f.m_world.rayTest(from, to, skipNear);
	std::set<const btCollisionObject*> got(&skipNear.m_collisionObjects[0],
	                                       &skipNear.m_collisionObjects[0] + skipNear.m_collisionObjects.size());
	EXPECT_EQ(got, (std::set<const btCollisionObject*>{middle, far}));

	btCollisionWorld::AllHitsRayResultCallback group2(from, to);
	group2.m_collisionFilterGroup = 2;  // middle's mask (1) rejects it
	f.m_world.rayTest(from, to, group2);
	std::set<const btCollisionObject*> got2(&group2.m_collisionObjects[0],
	                                        &group2.m_collisionObjects[0] + group2.m_collisionObjects.size());
	EXPECT_EQ(got2, (std::set<const btCollisionObject*>{near, far}));
}

TEST(CollisionWorldRayTest, NonFiniteRayAssertsOrHitsNothing)
{
	WorldFixture f;
	btSphereShape* sphere = f.own(new btSphereShape(1));
	f.add(sphere, at(btVector3(0, 0, 0)));
	const btVector3 nanPoint(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0);
	btCollisionWorld::ClosestRayResultCallback cb(nanPoint, btVector3(0, 0, 0));
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.rayTest(nanPoint, btVector3(0, 0, 0), cb), "assertion failed");
#else
	f.m_world.rayTest(nanPoint, btVector3(0, 0, 0), cb);
	EXPECT_FALSE(cb.hasHit());
	EXPECT_EQ(f.m_broadphase.m_raysTested, 0);
#endif
}
