// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The world's ray test reads a btTriangleIndexVertexArray's parts straight from their arrays (32- and 16-bit
// indices, btScalar vertices) and every other interface or layout through the locked read. Both must give
// the same hits, bit for bit, and the hits must be the triangles' own (Moller-Trumbore in double), for
// random, grazing, in-plane, zero-length and surface-start rays, and the closest fraction must be the checked
// triangle test's (btTriangleRaycastCallback::processTriangle over performRaycast's triangles), bit for bit;
// bad indices and NaN rays keep their documented behaviour.

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"
#include "CollisionWorldTestUtil.h"

using namespace caliber_world_test;

namespace
{
// Triangle tests are closed-form: a few hundred ulps of the coordinates (up to ~40 units here).
const double kClosedFormTolerance = sizeof(btScalar) == 4 ? 4e-5 : 1e-11;

bool sameBits(btScalar a, btScalar b) { return std::memcmp(&a, &b, sizeof(btScalar)) == 0; }
bool sameBits(const btVector3& a, const btVector3& b)
{
	return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

// A btTriangleIndexVertexArray subclass: the ray test cannot know that its lock does nothing, so it reads
// through the locked path. Counts locks and unlocks.
class CountingArray : public btTriangleIndexVertexArray
{
public:
	void getLockedReadOnlyVertexIndexBase(const unsigned char** vertexbase, int& numverts, PHY_ScalarType& type,
	                                      int& vertexStride, const unsigned char** indexbase, int& indexstride,
	                                      int& numfaces, PHY_ScalarType& indicestype, int subpart) const override
	{
		++m_locks;
		btTriangleIndexVertexArray::getLockedReadOnlyVertexIndexBase(
		    vertexbase, numverts, type, vertexStride, indexbase, indexstride, numfaces, indicestype, subpart);
	}
	void unLockReadOnlyVertexBase(int subpart) const override
	{
		++m_unlocks;
		btTriangleIndexVertexArray::unLockReadOnlyVertexBase(subpart);
	}
	mutable int m_locks = 0;
	mutable int m_unlocks = 0;
};

// A bumpy n x n grid over [-size, size]^2 in x/z with a flat band (height exactly 0) at the middle row of
// quads. Rows of quads below n / 2 are part 0 (32-bit indices), the rest part 1 (16-bit indices), and a third
// part (8-bit indices, a layout the direct read does not take) repeats part 0's first row one unit higher.
struct GridData
{
	GridData(Random& rng, int n, btScalar size, btScalar bump)
	{
		for (int i = 0; i <= n; ++i)
			for (int j = 0; j <= n; ++j)
			{
				const bool flat = j == n / 2 || j == n / 2 + 1;
				vertices.push_back(-size + 2 * size * btScalar(i) / btScalar(n));
				vertices.push_back(flat ? btScalar(0) : rng.uniform(-bump, bump));
				vertices.push_back(-size + 2 * size * btScalar(j) / btScalar(n));
			}
		for (int j = 0; j < n; ++j)
			for (int i = 0; i < n; ++i)
			{
				const int v00 = i * (n + 1) + j, v10 = v00 + (n + 1), v01 = v00 + 1, v11 = v10 + 1;
				const int quad[6] = {v00, v01, v10, v10, v01, v11};
				for (int q : quad)
				{
					if (j < n / 2)
						wide.push_back(q);
					else
						narrow.push_back((unsigned short)q);
				}
			}
		// Part 2: the quads of grid row j = 0, raised by one unit, with 8-bit indices into its own vertices.
		for (int i = 0; i <= n; ++i)
			for (int j = 0; j <= 1; ++j)
			{
				const int v = i * (n + 1) + j;
				raised.push_back(vertices[3 * v]);
				raised.push_back(vertices[3 * v + 1] + 1);
				raised.push_back(vertices[3 * v + 2]);
			}
		for (int i = 0; i < n; ++i)
		{
			const int v00 = 2 * i, v01 = v00 + 1, v10 = v00 + 2, v11 = v00 + 3;
			const int quad[6] = {v00, v01, v10, v10, v01, v11};
			for (int q : quad) bytes.push_back((unsigned char)q);
		}
	}

	void fill(btTriangleIndexVertexArray& array) const
	{
		btIndexedMesh part;
		part.m_numVertices = int(vertices.size() / 3);
		part.m_vertexBase = reinterpret_cast<const unsigned char*>(vertices.data());
		part.m_vertexStride = 3 * int(sizeof(btScalar));
		part.m_numTriangles = int(wide.size() / 3);
		part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(wide.data());
		part.m_triangleIndexStride = 3 * int(sizeof(int));
		array.addIndexedMesh(part, PHY_INTEGER);
		part.m_numTriangles = int(narrow.size() / 3);
		part.m_triangleIndexBase = reinterpret_cast<const unsigned char*>(narrow.data());
		part.m_triangleIndexStride = 3 * int(sizeof(unsigned short));
		array.addIndexedMesh(part, PHY_SHORT);
		part.m_numVertices = int(raised.size() / 3);
		part.m_vertexBase = reinterpret_cast<const unsigned char*>(raised.data());
		part.m_numTriangles = int(bytes.size() / 3);
		part.m_triangleIndexBase = bytes.data();
		part.m_triangleIndexStride = 3;
		array.addIndexedMesh(part, PHY_UCHAR);
	}

	std::vector<btScalar> vertices, raised;
	std::vector<int> wide;
	std::vector<unsigned short> narrow;
	std::vector<unsigned char> bytes;
};

// Every triangle of the mesh in world space (shape at the identity), with its part and index.
struct WorldTriangles : public btTriangleCallback
{
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		for (int k = 0; k < 3; ++k) corners.push_back(triangle[k]);
		ids.push_back(std::make_pair(partId, triangleIndex));
	}
	std::vector<btVector3> corners;
	std::vector<std::pair<int, int>> ids;
};

// The two worlds' answers to one ray: the closest hit, and every hit.
void expectSameHits(btCollisionWorld& direct, btCollisionWorld& locked, const btVector3& from, const btVector3& to)
{
	for (int closest = 0; closest < 2; ++closest)
	{
		RecordingRayCallback a, b;
		a.m_closest = b.m_closest = closest != 0;
		direct.rayTest(from, to, a);
		locked.rayTest(from, to, b);
		ASSERT_EQ(a.m_entries.size(), b.m_entries.size()) << "closest " << closest;
		for (size_t i = 0; i < a.m_entries.size(); ++i)
		{
			EXPECT_TRUE(sameBits(a.m_entries[i].fraction, b.m_entries[i].fraction));
			EXPECT_TRUE(sameBits(a.m_entries[i].normal, b.m_entries[i].normal));
			EXPECT_EQ(a.m_entries[i].part, b.m_entries[i].part);
			EXPECT_EQ(a.m_entries[i].index, b.m_entries[i].index);
		}
	}
}

// Every hit of btTriangleRaycastCallback::processTriangle (the checked triangle test) on the triangles
// btBvhTriangleMeshShape::performRaycast reports; the bound stays 1.
struct AllTriangleHits : public btTriangleRaycastCallback
{
	AllTriangleHits(const btVector3& from, const btVector3& to) : btTriangleRaycastCallback(from, to) {}
	btScalar reportHit(const btVector3&, btScalar hitFraction, int, int) override
	{
		fractions.push_back(hitFraction);
		return m_hitFraction;
	}
	std::vector<btScalar> fractions;
};

// The world's closest fraction is the smallest fraction processTriangle finds, bit for bit (the world's
// walk runs the same triangle test without its input checks).
void expectClosestMatchesProcessTriangle(btCollisionWorld& world, btBvhTriangleMeshShape& shape, const btVector3& from,
                                         const btVector3& to)
{
	AllTriangleHits all(from, to);
	shape.performRaycast(&all, from, to);
	btCollisionWorld::ClosestRayResultCallback out(from, to);
	world.rayTest(from, to, out);
	ASSERT_EQ(out.hasHit(), !all.fractions.empty());
	if (all.fractions.empty()) return;
	btScalar smallest = all.fractions[0];
	for (btScalar f : all.fractions) smallest = btMin(smallest, f);
	EXPECT_TRUE(sameBits(out.m_closestHitFraction, smallest)) << out.m_closestHitFraction << " vs " << smallest;
}

// The closest hit of the world against the brute-force Moller-Trumbore reference over every triangle. A
// segment starting in a triangle's plane is no hit on it (the ray test needs a strict sign change). Rays
// through a shared edge or corner hit several triangles at the same fraction: the normal must be one of theirs.
void expectClosestMatchesTriangles(btCollisionWorld& world, const WorldTriangles& triangles, const btVector3& from,
                                   const btVector3& to)
{
	const double length = double((to - from).length());
	const double tolerance = kClosedFormTolerance / length;
	std::vector<Hit> hits;
	Hit best;
	for (size_t t = 0; t < triangles.ids.size(); ++t)
	{
		const Hit h =
		    rayTriangle(from, to, triangles.corners[3 * t], triangles.corners[3 * t + 1], triangles.corners[3 * t + 2]);
		if (!h.hit || !(h.fraction > 0)) continue;
		hits.push_back(h);
		if (h.fraction < best.fraction) best = h;
	}
	btCollisionWorld::ClosestRayResultCallback out(from, to);
	world.rayTest(from, to, out);
	ASSERT_EQ(out.hasHit(), best.hit) << "ray from " << from.x() << " " << from.y() << " " << from.z();
	if (!best.hit) return;
	EXPECT_NEAR(double(out.m_closestHitFraction), best.fraction, tolerance);
	btScalar bestAlignment = -2;
	for (const Hit& h : hits)
		if (h.fraction <= best.fraction + 2 * tolerance)
			bestAlignment = btMax(bestAlignment, out.m_hitNormalWorld.dot(h.normal));
	EXPECT_GT(bestAlignment, btScalar(0.9999)) << "ray from " << from.x() << " " << from.y() << " " << from.z();
}

struct TwoWorlds
{
	TwoWorlds(const GridData& data, const btVector3& scaling)
	{
		data.fill(directArray);
		data.fill(lockedArray);
		directArray.setScaling(scaling);
		lockedArray.setScaling(scaling);
		directShape.reset(new btBvhTriangleMeshShape(&directArray, true));
		lockedShape.reset(new btBvhTriangleMeshShape(&lockedArray, true));
		direct.add(directShape.get(), at(btVector3(0, 0, 0)));
		locked.add(lockedShape.get(), at(btVector3(0, 0, 0)));
		const btVector3 big(1e3, 1e3, 1e3);
		directShape->processAllTriangles(&triangles, -big, big);
	}
	btTriangleIndexVertexArray directArray;
	CountingArray lockedArray;
	std::unique_ptr<btBvhTriangleMeshShape> directShape, lockedShape;
	WorldFixture direct, locked;
	WorldTriangles triangles;
};
}  // namespace

TEST(RayMeshRead, DirectAndLockedReadsGiveTheSameHitsAsTheTriangles)
{
	Random rng(20261128);
	const int n = 16;
	const btScalar size = 8;
	const GridData data(rng, n, size, btScalar(0.7));
	for (const btVector3& scaling : {btVector3(1, 1, 1), btVector3(btScalar(1.5), btScalar(0.5), 2)})
	{
		TwoWorlds worlds(data, scaling);
		ASSERT_EQ(worlds.triangles.ids.size(), size_t(2 * n * n + 2 * n));
		const btScalar sx = size * scaling.x(), sz = size * scaling.z();
		std::vector<std::pair<btVector3, btVector3>> rays;
		// Random rays through the surface from above and below, and long slanted ones.
		for (int i = 0; i < 150; ++i)
		{
			const btVector3 p(rng.uniform(-sx, sx), 0, rng.uniform(-sz, sz));
			rays.push_back({p + btVector3(rng.uniform(-1, 1), 4, rng.uniform(-1, 1)),
			                p + btVector3(rng.uniform(-1, 1), -4, rng.uniform(-1, 1))});
			rays.push_back({p + btVector3(0, -4, 0), p + btVector3(rng.uniform(-3, 3), 4, rng.uniform(-3, 3))});
			rays.push_back({btVector3(-sx - 1, rng.uniform(-1, 2), rng.uniform(-sz, sz)),
			                btVector3(sx + 1, rng.uniform(-1, 2), rng.uniform(-sz, sz))});
		}
		// Vertical rays through grid vertices and edge midpoints (shared edges and corners, grazing).
		for (int i = 0; i <= n; i += 3)
			for (int j = 0; j <= n; j += 3)
			{
				const btScalar x = (-size + 2 * size * btScalar(i) / btScalar(n)) * scaling.x();
				const btScalar z = (-size + 2 * size * btScalar(j) / btScalar(n)) * scaling.z();
				const btScalar half = size / btScalar(n) * scaling.x();
				rays.push_back({btVector3(x, 5, z), btVector3(x, -5, z)});
				rays.push_back({btVector3(x + half, 5, z), btVector3(x + half, -5, z)});
			}
		// Rays in the plane of the flat band's faces (y = 0 there): no strict sign change, no hit on them.
		const btScalar bandZ = (-size + 2 * size * btScalar(n / 2 + 0.5) / btScalar(n)) * scaling.z();
		rays.push_back({btVector3(-sx - 1, 0, bandZ), btVector3(sx + 1, 0, bandZ)});
		// Rays starting on the flat band, and zero-length rays on it and above it.
		rays.push_back({btVector3(0, 0, bandZ), btVector3(0, -3, bandZ)});
		rays.push_back({btVector3(0, 0, bandZ), btVector3(0, 0, bandZ)});
		rays.push_back({btVector3(1, 3, bandZ), btVector3(1, 3, bandZ)});
		for (const auto& ray : rays)
		{
			expectSameHits(worlds.direct.m_world, worlds.locked.m_world, ray.first, ray.second);
			expectClosestMatchesTriangles(worlds.direct.m_world, worlds.triangles, ray.first, ray.second);
			expectClosestMatchesProcessTriangle(worlds.direct.m_world, *worlds.directShape, ray.first, ray.second);
		}
		// The in-plane ray (it stays over the flat band, in its faces' plane) and the zero-length rays hit nothing.
		btCollisionWorld::ClosestRayResultCallback inPlane(rays[rays.size() - 4].first, rays[rays.size() - 4].second);
		worlds.direct.m_world.rayTest(inPlane.m_rayFromWorld, inPlane.m_rayToWorld, inPlane);
		EXPECT_FALSE(inPlane.hasHit());
		for (size_t k = rays.size() - 2; k < rays.size(); ++k)
		{
			btCollisionWorld::ClosestRayResultCallback zero(rays[k].first, rays[k].second);
			worlds.direct.m_world.rayTest(rays[k].first, rays[k].second, zero);
			EXPECT_FALSE(zero.hasHit());
		}
		// The locked path locked and unlocked in pairs, and used the lock at all (the direct one does not).
		EXPECT_GT(worlds.lockedArray.m_locks, 0);
		EXPECT_EQ(worlds.lockedArray.m_locks, worlds.lockedArray.m_unlocks);
	}
}

TEST(RayMeshRead, AnIndexOutOfRangeAssertsOrSkipsItsTriangle)
{
	Random rng(7);
	const int n = 8;
	GridData data(rng, n, 4, btScalar(0.3));
	btTriangleIndexVertexArray array;
	data.fill(array);
	btBvhTriangleMeshShape shape(&array, true);
	WorldFixture f;
	f.add(&shape, at(btVector3(0, 0, 0)));
	// The first triangle of grid row 1 (part 0, 32-bit indices, read directly; no raised copy above it) gets
	// an index past the vertices after the tree was built: a ray through its centre then meets the bad index.
	const int triangle = 2 * n;
	btVector3 corners[3];
	for (int k = 0; k < 3; ++k)
	{
		const int v = data.wide[3 * triangle + k];
		corners[k] = btVector3(data.vertices[3 * v], data.vertices[3 * v + 1], data.vertices[3 * v + 2]);
	}
	const btVector3 centre = (corners[0] + corners[1] + corners[2]) / btScalar(3);
	const btVector3 from = centre + btVector3(0, 5, 0), to = centre - btVector3(0, 5, 0);
	{
		btCollisionWorld::ClosestRayResultCallback intact(from, to);
		f.m_world.rayTest(from, to, intact);
		ASSERT_TRUE(intact.hasHit());
		EXPECT_EQ(intact.m_collisionObject, f.m_objects[0].get());
	}
	data.wide[3 * triangle + 1] = int(data.vertices.size());
	btCollisionWorld::ClosestRayResultCallback out(from, to);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.rayTest(from, to, out), "mesh index out of range");
#else
	f.m_world.rayTest(from, to, out);
	// The bad triangle is skipped; the ray passes through its centre, away from the other triangles' edges,
	// so nothing else is hit either.
	EXPECT_FALSE(out.hasHit());
#endif
}

TEST(RayMeshRead, NonFiniteRaysAgainstAMeshAssertOrHitNothing)
{
	Random rng(11);
	const GridData data(rng, 8, 4, btScalar(0.3));
	btTriangleIndexVertexArray array;
	data.fill(array);
	btBvhTriangleMeshShape shape(&array, true);
	WorldFixture f;
	f.add(&shape, at(btVector3(0, 0, 0)));
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btVector3 from(0, 5, 0), nanTo(0, nan, 0);
	btCollisionWorld::ClosestRayResultCallback out(from, nanTo);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(f.m_world.rayTest(from, nanTo, out), "assertion failed");
#else
	f.m_world.rayTest(from, nanTo, out);
	EXPECT_FALSE(out.hasHit());
#endif
}
