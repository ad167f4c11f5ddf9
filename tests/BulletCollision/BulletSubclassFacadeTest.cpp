// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Classes written for Bullet 2.89 and derived from Caliber's: they compile against Bullet's members and
// behave as with Bullet (docs/architecture.md, "Public classes are a facade").

#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/btDbvt.h"
#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/BroadphaseCollision/btOverlappingPairCache.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btSimulationIslandManager.h"
#include "BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "BulletCollision/NarrowPhaseCollision/btRaycastCallback.h"

namespace
{
// Bullet's sorted cache gives subclasses its pairs as m_overlappingPairArray.
class PairCountingCache : public btSortedOverlappingPairCache
{
public:
	int storedPairs() const { return m_overlappingPairArray.size(); }
};

// Bullet's dispatcher gives subclasses a spare manifold result, m_defaultManifoldResult.
class SpareResultDispatcher : public btCollisionDispatcher
{
public:
	using btCollisionDispatcher::btCollisionDispatcher;
	btManifoldResult& spareResult() { return m_defaultManifoldResult; }
};

// A plain Bullet ray callback: counts the triangles it is given and keeps every hit it is told about.
class TriangleCountingRay : public btTriangleRaycastCallback
{
public:
	TriangleCountingRay(const btVector3& from, const btVector3& to) : btTriangleRaycastCallback(from, to) {}
	void processTriangle(btVector3* triangle, int partId, int triangleIndex) override
	{
		++m_trianglesSeen;
		btTriangleRaycastCallback::processTriangle(triangle, partId, triangleIndex);
	}
	btScalar reportHit(const btVector3&, btScalar hitFraction, int, int) override
	{
		++m_hits;
		return hitFraction;  // keep only closer hits from now on
	}
	int m_trianglesSeen = 0;
	int m_hits = 0;
};

// A stack of n unit squares (two triangles each) at heights 0, 1, ..., n - 1, facing up.
void addStackedSquares(btTriangleMesh& mesh, int n)
{
	for (int level = 0; level < n; ++level)
	{
		const btScalar y = btScalar(level);
		mesh.addTriangle(btVector3(0, y, 0), btVector3(1, y, 0), btVector3(1, y, 1));
		mesh.addTriangle(btVector3(0, y, 0), btVector3(1, y, 1), btVector3(0, y, 1));
	}
}

// Bullet 2.89's data members of btDbvt and of btSimulationIslandManager, in Bullet's order: a member that
// Bullet's classes do not declare would make Caliber's larger (one that fits in padding would not; the
// layout of the rest is what a class written against Bullet's headers assumes).
struct BulletDbvtMembers
{
	btDbvtNode* m_root;
	btDbvtNode* m_free;
	int m_lkhd;
	int m_leaves;
	unsigned m_opath;
	btAlignedObjectArray<btDbvt::sStkNN> m_stkStack;
};

struct BulletDbvtProxyMembers : public btBroadphaseProxy
{
	btDbvtNode* leaf;
	btDbvtProxy* links[2];
	int stage;
};

struct BulletDbvtBroadphaseMembers : public btBroadphaseInterface
{
	btDbvt m_sets[2];
	btDbvtProxy* m_stageRoots[btDbvtBroadphase::STAGECOUNT + 1];
	btOverlappingPairCache* m_paircache;
	btScalar m_prediction;
	int m_stageCurrent;
	int m_fupdates;
	int m_dupdates;
	int m_cupdates;
	int m_newpairs;
	int m_fixedleft;
	unsigned m_updates_call;
	unsigned m_updates_done;
	btScalar m_updates_ratio;
	int m_pid;
	int m_cid;
	int m_gid;
	bool m_releasepaircache;
	bool m_deferedcollide;
	bool m_needcleanup;
	btAlignedObjectArray<btAlignedObjectArray<const btDbvtNode*>> m_rayTestStacks;
};

struct BulletIslandManagerMembers
{
	virtual ~BulletIslandManagerMembers() {}
	btUnionFind m_unionFind;
	btAlignedObjectArray<btPersistentManifold*> m_islandmanifold;
	btAlignedObjectArray<btCollisionObject*> m_islandBodies;
	bool m_splitIslands;
};
}  // namespace

TEST(BulletSubclassFacade, DbvtAndIslandManagerDeclareBulletsDataMembersOnly)
{
	EXPECT_EQ(sizeof(btDbvt), sizeof(BulletDbvtMembers));
	EXPECT_EQ(sizeof(btSimulationIslandManager), sizeof(BulletIslandManagerMembers));
	EXPECT_EQ(sizeof(btDbvtProxy), sizeof(BulletDbvtProxyMembers));
	EXPECT_EQ(sizeof(btDbvtBroadphase), sizeof(BulletDbvtBroadphaseMembers));
	// Bullet's public fields, reached by name as Bullet's users do.
	btDbvt tree;
	EXPECT_EQ(tree.m_root, nullptr);
	EXPECT_EQ(tree.m_free, nullptr);
	EXPECT_EQ(tree.m_leaves, 0);
	EXPECT_EQ(tree.m_stkStack.size(), 0);
}

TEST(BulletSubclassFacade, SortedPairCacheSubclassSeesItsPairsAsOverlappingPairArray)
{
	PairCountingCache cache;
	btBroadphaseProxy a(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, 1, -1);
	btBroadphaseProxy b(btVector3(0, 0, 0), btVector3(1, 1, 1), 0, 1, -1);
	a.m_uniqueId = 1;
	b.m_uniqueId = 2;
	ASSERT_NE(cache.addOverlappingPair(&a, &b), nullptr);
	EXPECT_EQ(cache.storedPairs(), 1);
	cache.removeOverlappingPair(&a, &b, 0);
	EXPECT_EQ(cache.storedPairs(), 0);
}

TEST(BulletSubclassFacade, PerformRaycastGivesEveryTriangleOnTheRayToABulletCallback)
{
	// Bullet's performRaycast hands the callback every triangle whose tree box the ray crosses, also those
	// beyond a hit already found; Caliber's world ray test prunes those internally, never through the callback.
	const int levels = 8;
	btTriangleMesh mesh;
	addStackedSquares(mesh, levels);
	btBvhTriangleMeshShape shape(&mesh, true);
	// Downwards and upwards, so that whichever order the tree is walked in, one ray finds its closest hit
	// early and still sees every level.
	const btVector3 above(0.25, btScalar(levels) + 1, 0.75), below(0.25, -1, 0.75);
	for (int upwards = 0; upwards < 2; ++upwards)
	{
		const btVector3 from = upwards ? below : above, to = upwards ? above : below;
		TriangleCountingRay ray(from, to);
		shape.performRaycast(&ray, from, to);
		EXPECT_GE(ray.m_trianglesSeen, levels) << "upwards " << upwards << ": triangles seen " << ray.m_trianglesSeen;
		EXPECT_GE(ray.m_hits, 1);
		// The top square is 2 units below the start of the downward ray, the bottom one 1 unit above the
		// start of the upward one; the ray is levels + 2 long.
		EXPECT_NEAR(ray.m_hitFraction, btScalar(upwards ? 1 : 2) / btScalar(levels + 2), 1e-5) << "upwards " << upwards;
	}
}

TEST(BulletSubclassFacade, DispatcherSubclassReachesItsSpareManifoldResult)
{
	btDefaultCollisionConfiguration configuration;
	SpareResultDispatcher dispatcher(&configuration);
	// Default-built: no manifold, no bodies; the dispatcher never writes through it.
	EXPECT_EQ(dispatcher.spareResult().getPersistentManifold(), nullptr);
	EXPECT_EQ(dispatcher.spareResult().getBody0Wrap(), nullptr);
}
