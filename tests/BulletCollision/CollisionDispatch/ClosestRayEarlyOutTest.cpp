// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The early-outs of closest-hit ray tests: btDbvtBroadphase::rayTest's nearest-first walk (reads the
// callback's shrinking m_lambda_max at every box), the nearest-first walk of a BVH mesh's tree, and the
// box and plane rejects in front of the convex cast. Each must leave the answer of the exhaustive test
// unchanged, bit for bit: these tests compare against brute force over every proxy, every triangle, or
// the cast run directly.

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <set>
#include <vector>

#include "BulletCollision/BroadphaseCollision/QuantizedBvhCast.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionShapes/btOptimizedBvh.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/CollisionShapes/btConvexPointCloudShape.h"
#include "BulletCollision/CollisionShapes/btConvexTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btMultiSphereShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletCollision/NarrowPhaseCollision/btConvexCastHelpers.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"
#include "BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h"
#include "CollisionWorldTestUtil.h"

using namespace caliber_world_test;

namespace
{
// A world over the default configuration and a btDbvtBroadphase (the broadphase whose ray walk is tested).
struct DbvtWorld
{
	DbvtWorld() : dispatcher(&config), world(&dispatcher, &broadphase, &config) {}
	~DbvtWorld()
	{
		for (int i = world.getNumCollisionObjects() - 1; i >= 0; i--)
			world.removeCollisionObject(world.getCollisionObjectArray()[i]);
	}
	btCollisionObject* add(btCollisionShape* shape, const btTransform& transform, bool isStatic)
	{
		objects.emplace_back(new btCollisionObject());
		btCollisionObject* object = objects.back().get();
		object->setCollisionShape(shape);
		object->setWorldTransform(transform);
		if (isStatic)
			world.addCollisionObject(object, btBroadphaseProxy::StaticFilter,
			                         btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
		else
			world.addCollisionObject(object);
		return object;
	}
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher;
	btDbvtBroadphase broadphase;
	btCollisionWorld world;
	std::vector<std::unique_ptr<btCollisionObject>> objects;
};

// Records the proxies the broadphase hands over; with closestBox it shrinks m_lambda_max to the entry of
// each proxy's box, so the walk may prune everything beyond the nearest box found so far.
struct ProxyRecorder : btBroadphaseRayCallback
{
	ProxyRecorder(const btVector3& from, const btVector3& to, bool closestBox) : m_from(from), m_closestBox(closestBox)
	{
		const btVector3 d = to - from;
		for (int a = 0; a < 3; a++)
		{
			m_rayDirectionInverse[a] = d[a] == btScalar(0) ? btScalar(BT_LARGE_FLOAT) : btScalar(1) / d[a];
			m_signs[a] = m_rayDirectionInverse[a] < btScalar(0);
		}
		m_lambda_max = 1;
	}
	bool process(const btBroadphaseProxy* proxy) override
	{
		m_seen.insert(proxy);
		if (m_closestBox)
		{
			const btVector3 bounds[2] = {proxy->m_aabbMin, proxy->m_aabbMax};
			btScalar enter;
			if (btRayAabb2(m_from, m_rayDirectionInverse, m_signs, bounds, enter, 0, m_lambda_max)) m_lambda_max = enter;
		}
		return true;
	}
	btVector3 m_from;
	bool m_closestBox;
	std::set<const btBroadphaseProxy*> m_seen;
};

// Every triangle of a mesh as the triangle ray test sees it, for brute force.
struct Triangle
{
	btVector3 v[3];
	int part;
	int index;
};

// Runs the library's own triangle ray test over every triangle in index order and keeps the closest hit, as
// a closest-hit query without any tree would.
struct BruteForceTriangles : btTriangleRaycastCallback
{
	BruteForceTriangles(const btVector3& from, const btVector3& to, unsigned flags)
	    : btTriangleRaycastCallback(from, to, flags)
	{
	}
	btScalar reportHit(const btVector3& normal, btScalar fraction, int partId, int triangleIndex) override
	{
		m_normal = normal;
		m_part = partId;
		m_index = triangleIndex;
		return fraction;
	}
	// The hit fraction of one triangle alone (2 when it is not hit).
	static btScalar fractionOf(const Triangle& t, const btVector3& from, const btVector3& to, unsigned flags)
	{
		BruteForceTriangles one(from, to, flags);
		btVector3 v[3] = {t.v[0], t.v[1], t.v[2]};
		one.processTriangle(v, t.part, t.index);
		return one.m_part >= 0 ? one.m_hitFraction : btScalar(2);
	}
	btVector3 m_normal;
	int m_part = -1;
	int m_index = -1;
};

// A bumpy grid of n x n quads (two triangles each) over [-size, size]^2 in x/z; with flatQuads some quads
// are flat and share exact integer coordinates, so that rays can run exactly through shared edges.
btTriangleMesh* grid(Random& rng, int n, btScalar size, btScalar bump, std::vector<Triangle>& triangles)
{
	btTriangleMesh* mesh = new btTriangleMesh();
	std::vector<btScalar> heights((n + 1) * (n + 1));
	for (size_t i = 0; i < heights.size(); i++) heights[i] = (i % 3 == 0) ? btScalar(0) : rng.uniform(-bump, bump);
	auto vertex = [&](int i, int j) {
		return btVector3(-size + 2 * size * btScalar(i) / btScalar(n), heights[i * (n + 1) + j],
		                 -size + 2 * size * btScalar(j) / btScalar(n));
	};
	for (int i = 0; i < n; i++)
		for (int j = 0; j < n; j++)
		{
			const btVector3 quad[2][3] = {{vertex(i, j), vertex(i, j + 1), vertex(i + 1, j)},
			                              {vertex(i + 1, j), vertex(i, j + 1), vertex(i + 1, j + 1)}};
			for (int k = 0; k < 2; k++)
			{
				Triangle t = {{quad[k][0], quad[k][1], quad[k][2]}, 0, int(triangles.size())};
				triangles.push_back(t);
				mesh->addTriangle(quad[k][0], quad[k][1], quad[k][2]);
			}
		}
	return mesh;
}

// Checks one ray through the world against brute force over the triangles (the mesh placed at identity,
// so that the world's local ray is the ray itself): the same hit or miss, the same fraction bit for bit, a
// reported triangle that itself hits at that fraction (on exact ties either triangle is right), and that
// triangle's normal (within the rounding of one more normalisation).
void expectClosestTriangle(btCollisionWorld& world, const std::vector<Triangle>& triangles, const btVector3& from,
                           const btVector3& to, unsigned flags, const char* what, int ray)
{
	BruteForceTriangles brute(from, to, flags);
	for (const Triangle& t : triangles)
	{
		btVector3 v[3] = {t.v[0], t.v[1], t.v[2]};
		brute.processTriangle(v, t.part, t.index);
	}
	RecordingRayCallback cb;
	cb.m_flags = flags;
	world.rayTest(from, to, cb);
	const bool bruteHit = brute.m_part >= 0;
	ASSERT_EQ(!cb.m_entries.empty(), bruteHit) << what << " ray " << ray;
	if (!bruteHit) return;
	const RecordingRayCallback::Entry& e = cb.m_entries.back();
	EXPECT_EQ(e.fraction, brute.m_hitFraction) << what << " ray " << ray;
	ASSERT_GE(e.index, 0);
	ASSERT_LT(e.index, int(triangles.size()));
	EXPECT_EQ(BruteForceTriangles::fractionOf(triangles[e.index], from, to, flags), brute.m_hitFraction)
	    << what << " ray " << ray << " reported triangle " << e.index << " brute " << brute.m_index;
	// The world normalises the triangle's unit normal once more (and turns it by the identity), which may
	// move its last bits: the same direction within a few ulps.
	if (e.index == brute.m_index)
	{
		EXPECT_GT(e.normal.dot(brute.m_normal), btScalar(1) - btScalar(8) * SIMD_EPSILON) << what << " ray " << ray;
	}
}
}  // namespace

TEST(ClosestRayEarlyOut, DbvtBroadphaseRayReportsExactlyTheProxiesItsBoxTestAdmits)
{
	btDbvtBroadphase broadphase;
	Random rng(5);
	std::vector<btBroadphaseProxy*> proxies;
	for (int i = 0; i < 300; i++)
	{
		const btVector3 c = rng.vector(40);
		const btVector3 h(rng.uniform(0.1, 3), rng.uniform(0.1, 3), rng.uniform(0.1, 3));
		const bool isStatic = i % 4 == 0;
		proxies.push_back(broadphase.createProxy(
		    c - h, c + h, 0, 0, isStatic ? short(btBroadphaseProxy::StaticFilter) : short(btBroadphaseProxy::DefaultFilter),
		    short(btBroadphaseProxy::AllFilter), 0));
	}
	// Move some, so that leaf boxes are fatter than the proxies' own boxes.
	for (int i = 1; i < 300; i += 3)
	{
		const btVector3 d = rng.vector(0.5);
		broadphase.setAabb(proxies[i], proxies[i]->m_aabbMin + d, proxies[i]->m_aabbMax + d, 0);
	}
	for (int k = 0; k < 200; k++)
	{
		const btVector3 from = rng.vector(50);
		btVector3 to = rng.vector(50);
		if (k % 10 == 0) to.setX(from.x());  // a zero direction component
		const btVector3 sweep = (k % 5 == 0) ? btVector3(0.5, 0.25, 1) : btVector3(0, 0, 0);
		ProxyRecorder all(from, to, false);
		broadphase.rayTest(from, to, all, -sweep, sweep);
		std::set<const btBroadphaseProxy*> expected;
		btScalar nearest = 2;
		for (btBroadphaseProxy* p : proxies)
		{
			const btVector3 bounds[2] = {p->m_aabbMin - sweep, p->m_aabbMax + sweep};
			btScalar enter;
			if (btRayAabb2(from, all.m_rayDirectionInverse, all.m_signs, bounds, enter, 0, 1))
			{
				expected.insert(p);
				nearest = btMin(nearest, enter);
			}
		}
		EXPECT_EQ(all.m_seen, expected) << "ray " << k;
		if (sweep.length2() > 0) continue;
		// With the bound shrinking to the nearest box found so far, the walk still finds the nearest box.
		ProxyRecorder closest(from, to, true);
		broadphase.rayTest(from, to, closest);
		EXPECT_EQ(closest.m_lambda_max, expected.empty() ? btScalar(1) : nearest) << "ray " << k;
		EXPECT_LE(closest.m_seen.size(), expected.size());
	}
	for (btBroadphaseProxy* p : proxies) broadphase.destroyProxy(p, 0);
}

TEST(ClosestRayEarlyOut, BvhMeshClosestHitEqualsBruteForceOverEveryTriangle)
{
	for (int quantized = 0; quantized < 2; quantized++)
	{
		Random rng(17 + quantized);
		std::vector<Triangle> triangles;
		std::unique_ptr<btTriangleMesh> mesh(grid(rng, 24, 20, 2, triangles));
		btBvhTriangleMeshShape shape(mesh.get(), quantized != 0);
		DbvtWorld w;
		w.add(&shape, btTransform::getIdentity(), true);
		const unsigned flagSets[3] = {0, btTriangleRaycastCallback::kF_FilterBackfaces,
		                              btTriangleRaycastCallback::kF_KeepUnflippedNormal};
		for (int k = 0; k < 400; k++)
		{
			btVector3 from = rng.vector(25), to = rng.vector(25);
			if (k % 4 == 0) to = from + (to - from) * btScalar(40);  // long rays, as a world's rays often are
			if (k % 7 == 0) to.setZ(from.z());                       // zero direction components
			if (k % 11 == 0) to.setX(from.x());
			expectClosestTriangle(w.world, triangles, from, to, flagSets[k % 3], quantized ? "quantized" : "plain", k);
		}
	}
}

TEST(ClosestRayEarlyOut, RaysThroughSharedEdgesAndAlongGridLinesHitAsBruteForce)
{
	// A flat grid at y = 0 with integer corners: vertical rays through grid points hit shared edges and
	// vertices exactly, and rays in the plane x = const run along the grid lines that bound the tree's boxes.
	Random rng(3);
	std::vector<Triangle> triangles;
	std::unique_ptr<btTriangleMesh> mesh(grid(rng, 16, 16, 0, triangles));
	btBvhTriangleMeshShape shape(mesh.get(), true);
	DbvtWorld w;
	w.add(&shape, btTransform::getIdentity(), true);
	int ray = 0;
	for (int i = -8; i <= 8; i++)
		for (int j = -8; j <= 8; j++)
		{
			const btVector3 p(btScalar(2 * i), 0, btScalar(2 * j));
			expectClosestTriangle(w.world, triangles, p + btVector3(0, 5, 0), p - btVector3(0, 5, 0), 0, "vertical",
			                      ray++);
			expectClosestTriangle(w.world, triangles, p + btVector3(0, 5, 0), p + btVector3(3, -5, 0), 0,
			                      "along a grid line", ray++);
			expectClosestTriangle(w.world, triangles, p + btVector3(-1, 5, 1), p + btVector3(1, -5, -1), 0,
			                      "through a diagonal", ray++);
		}
}

TEST(ClosestRayEarlyOut, ConvexRejectsNeverChangeTheCastsAnswer)
{
	// Shapes whose ray test now starts with two rejects (the grown local box, then a plane through the ray
	// that keeps the shape beyond the casts' reach); rays aimed at points on and just off their surfaces
	// (grazing within the casts' stopping distance), through them, and from inside them. The reference is
	// the cast the world's ray test runs, called directly with the same inputs.
	btConvexHullShape hull;
	for (int ring = 0; ring < 3; ring++)
		for (int k = 0; k < 8; k++)
		{
			const btScalar angle = btScalar(k) * SIMD_PI / 4;
			const btScalar radius = ring == 1 ? btScalar(1.8) : btScalar(1.1);
			hull.addPoint(btVector3(radius * btCos(angle), btScalar(ring - 1) * 2, radius * btSin(angle)));
		}
	btCapsuleShape capsule(0.5, 2);
	btCylinderShape cylinder(btVector3(1, 1.5, 0.7));
	const btVector3 centres[2] = {btVector3(0, 0, 0), btVector3(0.5, 1, 0)};
	const btScalar radii[2] = {1, 0.6};
	btMultiSphereShape multiSphere(centres, radii, 2);
	btConvexShape* shapes[4] = {&hull, &capsule, &cylinder, &multiSphere};
	Random rng(29);
	for (int s = 0; s < 4; s++)
	{
		WorldFixture f;
		const btTransform placement = placed(rng.rotation(), rng.vector(5));
		f.add(shapes[s], placement);
		int hits = 0;
		for (int k = 0; k < 300; k++)
		{
			// A point near the surface: the support point along a random direction, moved off by up to 0.02; every
			// other ray along a local axis, where the shape touches its box, moved off by up to 3 times the casts'
			// stopping distance (the band the reject's growth is there for).
			btVector3 dirLocal = rng.unitVector();
			btScalar offset = rng.uniform(-0.02, 0.02);
			if (k % 2 == 0)
			{
				dirLocal = btVector3(0, 0, 0);
				dirLocal[rng.integer(0, 2)] = rng.integer(0, 1) ? btScalar(1) : btScalar(-1);
				offset = rng.uniform(-3e-3, 3e-3);
			}
			const btVector3 surface = placement * (shapes[s]->localGetSupportingVertex(dirLocal) + dirLocal * offset);
			btVector3 from = placement * (rng.unitVector() * btScalar(8));
			if (k % 10 == 0) from = placement.getOrigin() + rng.vector(0.3);  // from inside
			btVector3 to = from + (surface - from) * rng.uniform(0.5, 3);
			if (k % 4 != 1)  // a grazing ray: through the surface point, across the outward direction
				to = surface + (surface - from).cross(placement.getBasis() * dirLocal) * btScalar(2);
			const unsigned flags = (k % 5 < 2) ? btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest : 0u;
			btTransform fromT = btTransform::getIdentity(), toT = btTransform::getIdentity();
			fromT.setOrigin(from);
			toT.setOrigin(to);
			btSphereShape point(0);
			point.setMargin(0);
			btVoronoiSimplexSolver simplex;
			btConvexCast::CastResult result;
			const bool castHit =
			    flags ? caliber::gjkCast(&point, shapes[s], &simplex, fromT, toT, placement, placement, result,
			                             caliber::StartInContact::kMiss)
			          : caliber::subsimplexCast(&point, shapes[s], &simplex, fromT, toT, placement, placement, result,
			                                    caliber::StartInContact::kMiss);
			// Every third ray starts with a bound just beyond the cast's hit (as when a closer object was found
			// first): within the casts' stopping distance the hit lies before the shape's box, so a box grown
			// too little would drop it.
			btScalar bound = 1;
			if (castHit && k % 3 == 2)
				bound = btMin(btScalar(1), result.m_fraction + rng.uniform(0.01, 2) * btScalar(1e-3) / (to - from).length());
			btCollisionWorld::ClosestRayResultCallback cb(from, to);
			cb.m_flags = flags;
			cb.m_closestHitFraction = bound;
			f.m_world.rayTest(from, to, cb);
			const bool expectHit =
			    castHit && result.m_normal.length2() > btScalar(1e-4) && result.m_fraction < bound;
			ASSERT_EQ(cb.hasHit(), expectHit) << "shape " << s << " ray " << k;
			if (!expectHit) continue;
			hits++;
			EXPECT_EQ(cb.m_closestHitFraction, result.m_fraction) << "shape " << s << " ray " << k;
			EXPECT_EQ(cb.m_hitNormalWorld, result.m_normal.normalized()) << "shape " << s << " ray " << k;
		}
		EXPECT_GT(hits, 30) << "shape " << s;
	}
}

TEST(ClosestRayEarlyOut, StartsInsideTheCoreNeverChangeTheCastsAnswer)
{
	// Shapes without polyhedral features whose ray test now skips the cast when GJK's containment search finds
	// a tetrahedron of core points around the start (a barrel-like hull as in BenchmarkDemo's raycast scene,
	// the same points as a point cloud and as a convex triangle mesh, and a cylinder), placed near the origin
	// and at huge coordinates. Rays start inside the shapes, just inside and just outside their surfaces
	// (within and beyond the margin, heading in or out or along it), at the centre, and some have zero
	// length or run parallel to the barrel's flat ends or to the cylinder's side. The reference is the cast
	// the world's ray test runs, called directly: the same hit or miss, fraction and normal, bit for bit.
	btAlignedObjectArray<btVector3> points;
	for (int ring = 0; ring < 3; ring++)
		for (int k = 0; k < 8; k++)
		{
			const btScalar angle = btScalar(k) * SIMD_PI / 4;
			const btScalar radius = ring == 1 ? btScalar(1.8) : btScalar(1.1);
			points.push_back(btVector3(radius * btCos(angle), btScalar(ring - 1) * 2, radius * btSin(angle)));
		}
	btConvexHullShape hull;
	for (int i = 0; i < points.size(); i++) hull.addPoint(points[i]);
	btConvexPointCloudShape cloud(&points[0], points.size(), btVector3(1, 1, 1));
	btTriangleMesh mesh;
	for (int i = 0; i + 2 < points.size(); i++) mesh.addTriangle(points[i], points[i + 1], points[i + 2]);
	btConvexTriangleMeshShape convexMesh(&mesh);
	btCylinderShape cylinder(btVector3(1.2, 1.5, 1.2));
	btConvexShape* shapes[4] = {&hull, &cloud, &convexMesh, &cylinder};
	const btScalar origins[3] = {0, 3e3, 2e5};
	Random rng(41);
	for (int s = 0; s < 4; s++)
		for (btScalar far : origins)
		{
			WorldFixture f;
			const btTransform placement = placed(rng.rotation(), rng.vector(3) + btVector3(far, -far, far));
			f.add(shapes[s], placement);
			btTransform identity;
			identity.setIdentity();
			btVector3 boxMin, boxMax;
			shapes[s]->getAabb(identity, boxMin, boxMax);
			int hits = 0, startsInside = 0;
			for (int k = 0; k < 400; k++)
			{
				// The start in the shape's frame: anywhere in its box (inside the shape or in the box's corners
				// beside it), or near the surface along a random direction, or at the centre.
				btVector3 startLocal(rng.uniform(boxMin.x(), boxMax.x()), rng.uniform(boxMin.y(), boxMax.y()),
				                     rng.uniform(boxMin.z(), boxMax.z()));
				const btVector3 out = rng.unitVector();
				if (k % 3 == 1)
					startLocal = shapes[s]->localGetSupportingVertex(out) + out * rng.uniform(-0.1, 0.02);
				else if (k % 3 == 2)
					startLocal = shapes[s]->localGetSupportingVertexWithoutMargin(out) + out * rng.uniform(-0.05, 0.05);
				if (k % 4 == 1)  // just outside the surface: heading in, these hit at about 0
					startLocal = shapes[s]->localGetSupportingVertex(out) + out * rng.uniform(0.001, 0.05);
				if (k % 50 == 0) startLocal.setZero();
				btVector3 directionLocal = rng.unitVector() * rng.uniform(0.5, 6);
				if (k % 2 == 1) directionLocal = -out * rng.uniform(0.5, 4);  // heading in
				if (k % 7 == 3) directionLocal = btVector3(rng.uniform(-3, 3), 0, rng.uniform(-3, 3));  // along y's faces
				if (k % 7 == 5) directionLocal = btVector3(0, rng.uniform(-4, 4), 0);  // along the cylinder's side
				if (k % 11 == 4) directionLocal.setZero();  // zero length
				const btVector3 from = placement * startLocal;
				const btVector3 to = placement * (startLocal + directionLocal);
				const unsigned flags = (k % 4 == 3) ? btTriangleRaycastCallback::kF_UseGjkConvexCastRaytest : 0u;
				btTransform fromT = btTransform::getIdentity(), toT = btTransform::getIdentity();
				fromT.setOrigin(from);
				toT.setOrigin(to);
				btSphereShape point(0);
				point.setMargin(0);
				btVoronoiSimplexSolver simplex;
				btConvexCast::CastResult result;
				const bool castHit =
				    flags ? caliber::gjkCast(&point, shapes[s], &simplex, fromT, toT, placement, placement, result,
				                             caliber::StartInContact::kMiss)
				          : caliber::subsimplexCast(&point, shapes[s], &simplex, fromT, toT, placement, placement,
				                                    result, caliber::StartInContact::kMiss);
				btCollisionWorld::ClosestRayResultCallback cb(from, to);
				cb.m_flags = flags;
				f.m_world.rayTest(from, to, cb);
				const bool expectHit = castHit && result.m_normal.length2() > btScalar(1e-4) && result.m_fraction < 1;
				ASSERT_EQ(cb.hasHit(), expectHit) << "shape " << s << " at " << far << " ray " << k;
				// A start inside the shape's core by more than a margin (GJK's distance of the start point to
				// the core, made without the early-out): the case the early-out is for.
				btVector3 normal, onB;
				btScalar distance;
				btVoronoiSimplexSolver distanceSimplex;
				btSphereShape deepPoint(0);
				deepPoint.setMargin(shapes[s]->getMargin());
				if (!caliber::castClosestPoints(&deepPoint, shapes[s], fromT, placement, &distanceSimplex, nullptr,
				                                btVector3(0, 0, 0), normal, onB, distance))
					startsInside++;
				if (!expectHit) continue;
				hits++;
				EXPECT_EQ(cb.m_closestHitFraction, result.m_fraction) << "shape " << s << " ray " << k;
				EXPECT_EQ(cb.m_hitNormalWorld, result.m_normal.normalized()) << "shape " << s << " ray " << k;
			}
			EXPECT_GT(hits, 60) << "shape " << s << " at " << far;
			EXPECT_GT(startsInside, 80) << "shape " << s << " at " << far;
		}
}

namespace
{
// The node callback of the tree walk tests: runs the library's triangle ray test on each reported triangle.
// closest: the walk's bound is the triangle test's own fraction, lowered by each closer hit (as the world's
// closest-hit query does); else the bound stays 1 and every triangle hit is recorded.
struct WalkTriangles : btNodeOverlapCallback
{
	WalkTriangles(const std::vector<Triangle>& triangles, const btVector3& from, const btVector3& to, bool closest)
	    : m_triangles(triangles), m_test(from, to, 0), m_closest(closest)
	{
	}
	void processNode(int part, int index) override
	{
		EXPECT_EQ(part, 0);
		ASSERT_GE(index, 0);
		ASSERT_LT(index, int(m_triangles.size()));
		m_reported.push_back(index);
		const Triangle& t = m_triangles[index];
		btVector3 v[3] = {t.v[0], t.v[1], t.v[2]};
		if (!m_closest) m_test.m_hitFraction = 1;  // each triangle on its own
		const int before = m_test.m_index;
		m_test.m_index = -1;
		m_test.processTriangle(v, part, index);
		if (m_test.m_index >= 0)
			m_hits.insert(index);
		else
			m_test.m_index = before;
	}
	const btScalar* bound() const { return m_closest ? &m_test.m_hitFraction : &m_one; }

	const std::vector<Triangle>& m_triangles;
	BruteForceTriangles m_test;
	bool m_closest;
	const btScalar m_one = 1;
	std::vector<int> m_reported;
	std::set<int> m_hits;
};

// Every triangle the triangle ray test hits on its own (brute force over the whole mesh).
std::set<int> bruteForceHits(const std::vector<Triangle>& triangles, const btVector3& from, const btVector3& to)
{
	std::set<int> hits;
	for (const Triangle& t : triangles)
		if (BruteForceTriangles::fractionOf(t, from, to, 0) < btScalar(2)) hits.insert(t.index);
	return hits;
}

// The tree's nearest-first walk (the closest-hit ray's walk) against brute force over every triangle: with the
// bound fixed at 1 it reaches every triangle the ray hits, and each at most once; with the bound lowered by
// each hit it finds the closest fraction bit for bit, on a triangle that itself hits there (on an exact tie
// of two triangles either is right), and it never reports more triangles than with the fixed bound.
void expectWalkEqualsBruteForce(const btQuantizedBvh& bvh, const std::vector<Triangle>& triangles,
                                const btVector3& from, const btVector3& to, const char* what, int ray)
{
	const btVector3 zero(0, 0, 0);
	WalkTriangles all(triangles, from, to, false);
	caliber::reportBoxCastOverlappingNodesNearestFirst(bvh, &all, from, to, zero, zero, all.bound());
	const std::set<int> expected = bruteForceHits(triangles, from, to);
	EXPECT_EQ(all.m_hits, expected) << what << " ray " << ray;
	EXPECT_EQ(std::set<int>(all.m_reported.begin(), all.m_reported.end()).size(), all.m_reported.size())
	    << what << " ray " << ray << ": a triangle reported twice";

	WalkTriangles closest(triangles, from, to, true);
	caliber::reportBoxCastOverlappingNodesNearestFirst(bvh, &closest, from, to, zero, zero, closest.bound());
	BruteForceTriangles brute(from, to, 0);
	for (const Triangle& t : triangles)
	{
		btVector3 v[3] = {t.v[0], t.v[1], t.v[2]};
		brute.processTriangle(v, t.part, t.index);
	}
	ASSERT_EQ(closest.m_test.m_index >= 0, brute.m_index >= 0) << what << " ray " << ray;
	EXPECT_LE(closest.m_reported.size(), all.m_reported.size()) << what << " ray " << ray;
	if (brute.m_index < 0) return;
	EXPECT_EQ(closest.m_test.m_hitFraction, brute.m_hitFraction) << what << " ray " << ray;
	EXPECT_EQ(BruteForceTriangles::fractionOf(triangles[closest.m_test.m_index], from, to, 0), brute.m_hitFraction)
	    << what << " ray " << ray;
}
}  // namespace

TEST(ClosestRayEarlyOut, TreeWalkReportsTheClosestAndAllHitsOfBruteForce)
{
	for (int quantized = 0; quantized < 2; quantized++)
	{
		const char* what = quantized ? "quantized" : "plain";
		// A bumpy grid with random rays, then a flat grid (y = 0, corners on even integers) for the exact cases.
		Random rng(41 + quantized);
		std::vector<Triangle> bumpy;
		std::unique_ptr<btTriangleMesh> bumpyMesh(grid(rng, 20, 20, 2, bumpy));
		btBvhTriangleMeshShape bumpyShape(bumpyMesh.get(), quantized != 0);
		const btQuantizedBvh& bumpyBvh = *bumpyShape.getOptimizedBvh();
		int ray = 0;
		for (int k = 0; k < 150; k++)
		{
			btVector3 from = rng.vector(25), to = rng.vector(25);
			if (k % 3 == 0) to = from + (to - from) * btScalar(30);  // long rays
			expectWalkEqualsBruteForce(bumpyBvh, bumpy, from, to, what, ray++);
		}
		// Starting inside the tree's boxes (between the bumps) and ending there or far away.
		for (int k = 0; k < 60; k++)
		{
			const btVector3 from(rng.uniform(-19, 19), rng.uniform(-2, 2), rng.uniform(-19, 19));
			const btVector3 to = k % 2 ? from + rng.vector(3) : from + rng.vector(60);
			expectWalkEqualsBruteForce(bumpyBvh, bumpy, from, to, what, ray++);
		}

		std::vector<Triangle> flat;
		std::unique_ptr<btTriangleMesh> flatMesh(grid(rng, 16, 16, 0, flat));
		btBvhTriangleMeshShape flatShape(flatMesh.get(), quantized != 0);
		const btQuantizedBvh& flatBvh = *flatShape.getOptimizedBvh();
		for (int i = -8; i <= 8; i++)
			for (int j = -8; j <= 8; j += 2)
			{
				const btVector3 p(btScalar(2 * i), 0, btScalar(2 * j));
				const btVector3 up(0, 5, 0);
				// Along the y axis through a vertex, down and up (the up ray hits back faces).
				expectWalkEqualsBruteForce(flatBvh, flat, p + up, p - up, what, ray++);
				expectWalkEqualsBruteForce(flatBvh, flat, p - up, p + up, what, ray++);
				// Through the middle of an edge (shared by two triangles) and of a diagonal.
				expectWalkEqualsBruteForce(flatBvh, flat, p + btVector3(1, 5, 0), p + btVector3(1, -5, 0), what,
				                           ray++);
				expectWalkEqualsBruteForce(flatBvh, flat, p + btVector3(1, 5, 1), p + btVector3(1, -5, 1), what,
				                           ray++);
				// Along the x and z axes, in the plane of the faces and just above it (parallel to them).
				expectWalkEqualsBruteForce(flatBvh, flat, p + btVector3(-40, 0, 0), p + btVector3(40, 0, 0), what,
				                           ray++);
				expectWalkEqualsBruteForce(flatBvh, flat, p + btVector3(0, btScalar(0.01), -40),
				                           p + btVector3(0, btScalar(0.01), 40), what, ray++);
				// Of zero length: on a face and above it (nothing to hit).
				expectWalkEqualsBruteForce(flatBvh, flat, p + btVector3(1, 0, 1), p + btVector3(1, 0, 1), what,
				                           ray++);
				expectWalkEqualsBruteForce(flatBvh, flat, p + up, p + up, what, ray++);
			}
	}
}

TEST(ClosestRayEarlyOut, TreeWalkOfAnInvertedCastBoxShrinksTheBoxes)
{
	// A cast box with its minimum above its maximum shrinks every node box by the inversion: one inverted by
	// more than the leaves' size reaches no leaf, one inverted by far less than a triangle reaches a subset of
	// what the ray alone reaches (the walk's general slab test; the ray's own test needs a box that is not
	// inverted).
	for (int quantized = 0; quantized < 2; quantized++)
	{
		Random rng(7 + quantized);
		std::vector<Triangle> triangles;
		std::unique_ptr<btTriangleMesh> mesh(grid(rng, 12, 12, 1, triangles));
		btBvhTriangleMeshShape shape(mesh.get(), quantized != 0);
		const btQuantizedBvh& bvh = *shape.getOptimizedBvh();
		const btVector3 zero(0, 0, 0);
		for (int k = 0; k < 60; k++)
		{
			const btVector3 from(rng.uniform(-10, 10), 5, rng.uniform(-10, 10));
			const btVector3 to(rng.uniform(-10, 10), -5, rng.uniform(-10, 10));
			WalkTriangles ray(triangles, from, to, false);
			caliber::reportBoxCastOverlappingNodesNearestFirst(bvh, &ray, from, to, zero, zero, ray.bound());
			EXPECT_FALSE(ray.m_reported.empty()) << "ray " << k;
			const btVector3 big(3, 3, 3), small(btScalar(0.001), btScalar(0.001), btScalar(0.001));
			WalkTriangles inverted(triangles, from, to, false);
			caliber::reportBoxCastOverlappingNodesNearestFirst(bvh, &inverted, from, to, big, -big, inverted.bound());
			EXPECT_TRUE(inverted.m_reported.empty()) << "ray " << k;
			WalkTriangles slightly(triangles, from, to, false);
			caliber::reportBoxCastOverlappingNodesNearestFirst(bvh, &slightly, from, to, small, -small,
			                                                   slightly.bound());
			const std::set<int> rayReported(ray.m_reported.begin(), ray.m_reported.end());
			for (int index : slightly.m_reported) EXPECT_EQ(rayReported.count(index), 1u) << "ray " << k;
			EXPECT_FALSE(slightly.m_reported.empty()) << "ray " << k;
		}
	}
}

TEST(ClosestRayEarlyOut, TreeWalkOfANonFiniteRayAssertsOrReportsNothing)
{
	Random rng(9);
	std::vector<Triangle> triangles;
	std::unique_ptr<btTriangleMesh> mesh(grid(rng, 8, 8, 1, triangles));
	btBvhTriangleMeshShape shape(mesh.get(), true);
	const btVector3 zero(0, 0, 0);
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btVector3 from(0, 5, nan), to(0, -5, 0);
	WalkTriangles walk(triangles, btVector3(0, 5, 0), to, true);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(caliber::reportBoxCastOverlappingNodesNearestFirst(*shape.getOptimizedBvh(), &walk, from, to, zero,
	                                                                zero, walk.bound()),
	             "assertion failed");
#else
	caliber::reportBoxCastOverlappingNodesNearestFirst(*shape.getOptimizedBvh(), &walk, from, to, zero, zero,
	                                                   walk.bound());
	EXPECT_TRUE(walk.m_reported.empty());
#endif
}

TEST(ClosestRayEarlyOut, DbvtBroadphaseRayWithAZeroSweptBoxOfEitherSignReportsAsBruteForce)
{
	// The walk skips growing the tree's boxes when the swept box is a point; with boxes and ray starts on the
	// planes x, y, z = 0 (some written -0) and rays along the axes, the proxies handed over must still be
	// exactly those btRayAabb2 admits, for a swept box of +0, of -0 and for a real one.
	btDbvtBroadphase broadphase;
	std::vector<btBroadphaseProxy*> proxies;
	const btScalar negativeZero = -btScalar(0);
	for (int i = -3; i <= 3; i++)
		for (int j = -3; j <= 3; j++)
		{
			const btScalar x = btScalar(2 * i), z = btScalar(2 * j);
			// Boxes touching the planes through the origin from either side, with a -0 face where they touch.
			const btVector3 lo(i == 0 ? negativeZero : x, i % 2 == 0 ? negativeZero : btScalar(-1), z);
			const btVector3 hi(x + 1, btScalar(1), j == 0 ? negativeZero : z + 1);
			proxies.push_back(broadphase.createProxy(lo, hi, 0, 0, short(btBroadphaseProxy::DefaultFilter),
			                                         short(btBroadphaseProxy::AllFilter), 0));
		}
	const btVector3 sweeps[3] = {btVector3(0, 0, 0), btVector3(negativeZero, negativeZero, negativeZero),
	                             btVector3(btScalar(0.25), 0, btScalar(0.5))};
	int ray = 0, nonEmpty = 0;
	for (int a = 0; a < 3; a++)
		for (int s = -1; s <= 1; s += 2)
			for (int k = -3; k <= 3; k++)
			{
				btVector3 from(0, 0, 0);
				from[(a + 1) % 3] = btScalar(k);
				if (k == 0) from[(a + 2) % 3] = negativeZero;
				btVector3 to = from;
				to[a] = btScalar(20 * s);
				for (const btVector3& sweep : sweeps)
				{
					ProxyRecorder all(from, to, false);
					broadphase.rayTest(from, to, all, -sweep, sweep);
					std::set<const btBroadphaseProxy*> expected;
					for (btBroadphaseProxy* p : proxies)
					{
						const btVector3 bounds[2] = {p->m_aabbMin - sweep, p->m_aabbMax - (-sweep)};
						btScalar enter;
						if (btRayAabb2(from, all.m_rayDirectionInverse, all.m_signs, bounds, enter, 0, 1))
							expected.insert(p);
					}
					EXPECT_EQ(all.m_seen, expected) << "ray " << ray;
					if (!expected.empty()) nonEmpty++;
					ray++;
				}
			}
	EXPECT_GT(nonEmpty, ray / 2);  // most rays cross boxes: the comparisons are not all of empty sets
	for (btBroadphaseProxy* p : proxies) broadphase.destroyProxy(p, 0);
}
