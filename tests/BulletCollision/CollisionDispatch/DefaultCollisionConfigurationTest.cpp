// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include <gtest/gtest.h>

#include "BulletCollision/BroadphaseCollision/btBroadphaseProxy.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btEmptyShape.h"
#include "BulletCollision/CollisionShapes/btSphereShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "LinearMath/btPoolAllocator.h"
#include "TestDispatcher.h"

namespace
{
// Exposes the factories so that the table can be checked without RTTI.
class ProbeConfiguration : public btDefaultCollisionConfiguration
{
public:
	using btDefaultCollisionConfiguration::btDefaultCollisionConfiguration;
	btCollisionAlgorithmCreateFunc* sphereSphere() const { return m_sphereSphereCF; }
	btCollisionAlgorithmCreateFunc* sphereBox() const { return m_sphereBoxCF; }
	btCollisionAlgorithmCreateFunc* boxSphere() const { return m_boxSphereCF; }
	btCollisionAlgorithmCreateFunc* boxBox() const { return m_boxBoxCF; }
	btCollisionAlgorithmCreateFunc* sphereTriangle() const { return m_sphereTriangleCF; }
	btCollisionAlgorithmCreateFunc* triangleSphere() const { return m_triangleSphereCF; }
	btCollisionAlgorithmCreateFunc* convexPlane() const { return m_convexPlaneCF; }
	btCollisionAlgorithmCreateFunc* planeConvex() const { return m_planeConvexCF; }
	btCollisionAlgorithmCreateFunc* convexConvex() const { return m_convexConvexCreateFunc; }
	btCollisionAlgorithmCreateFunc* empty() const { return m_emptyCreateFunc; }
	btCollisionAlgorithmCreateFunc* convexConcave() const { return m_convexConcaveCreateFunc; }
	btCollisionAlgorithmCreateFunc* concaveConvex() const { return m_swappedConvexConcaveCreateFunc; }
	btCollisionAlgorithmCreateFunc* compound() const { return m_compoundCreateFunc; }
	btCollisionAlgorithmCreateFunc* compoundCompound() const { return m_compoundCompoundCreateFunc; }
	btCollisionAlgorithmCreateFunc* swappedCompound() const { return m_swappedCompoundCreateFunc; }
};

btCollisionAlgorithmCreateFunc* orEmpty(btCollisionAlgorithmCreateFunc* factory, const ProbeConfiguration& config)
{
	return factory ? factory : config.empty();
}
}  // namespace

TEST(DefaultCollisionConfiguration, PicksTheSpecialisedAlgorithmForEachPair)
{
	ProbeConfiguration config;
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(SPHERE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE),
	          config.sphereSphere());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(SPHERE_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE), config.sphereBox());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE), config.boxSphere());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE), config.boxBox());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(SPHERE_SHAPE_PROXYTYPE, TRIANGLE_SHAPE_PROXYTYPE),
	          config.sphereTriangle());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(TRIANGLE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE),
	          config.triangleSphere());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE, STATIC_PLANE_PROXYTYPE),
	          config.convexPlane());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(STATIC_PLANE_PROXYTYPE, CAPSULE_SHAPE_PROXYTYPE),
	          config.planeConvex());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(CAPSULE_SHAPE_PROXYTYPE, CONVEX_HULL_SHAPE_PROXYTYPE),
	          config.convexConvex());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(CYLINDER_SHAPE_PROXYTYPE, CONE_SHAPE_PROXYTYPE),
	          config.convexConvex());
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE, TRIANGLE_MESH_SHAPE_PROXYTYPE),
	          orEmpty(config.convexConcave(), config));
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(TERRAIN_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE),
	          orEmpty(config.concaveConvex(), config));
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(COMPOUND_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE),
	          orEmpty(config.compoundCompound(), config));
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(COMPOUND_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE),
	          orEmpty(config.compound(), config));
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(TRIANGLE_MESH_SHAPE_PROXYTYPE, COMPOUND_SHAPE_PROXYTYPE),
	          orEmpty(config.swappedCompound(), config));
	EXPECT_EQ(config.getCollisionAlgorithmCreateFunc(TRIANGLE_MESH_SHAPE_PROXYTYPE, TERRAIN_SHAPE_PROXYTYPE),
	          config.empty());
	// Closest-point queries use the generic convex-convex for boxes.
	EXPECT_EQ(config.getClosestPointsAlgorithmCreateFunc(BOX_SHAPE_PROXYTYPE, BOX_SHAPE_PROXYTYPE),
	          config.convexConvex());
	EXPECT_EQ(config.getClosestPointsAlgorithmCreateFunc(SPHERE_SHAPE_PROXYTYPE, SPHERE_SHAPE_PROXYTYPE),
	          config.sphereSphere());
}

TEST(DefaultCollisionConfiguration, SwappedFactoriesAreMarked)
{
	ProbeConfiguration config;
	EXPECT_FALSE(config.sphereBox()->m_swapped);
	EXPECT_TRUE(config.boxSphere()->m_swapped);
	EXPECT_FALSE(config.sphereTriangle()->m_swapped);
	EXPECT_TRUE(config.triangleSphere()->m_swapped);
	EXPECT_FALSE(config.convexPlane()->m_swapped);
	EXPECT_TRUE(config.planeConvex()->m_swapped);
}

TEST(DefaultCollisionConfiguration, PoolsFitEveryAlgorithmAndFollowConstructionInfo)
{
	btDefaultCollisionConstructionInfo info;
	info.m_defaultMaxPersistentManifoldPoolSize = 8;
	info.m_defaultMaxCollisionAlgorithmPoolSize = 16;
	info.m_customCollisionAlgorithmMaxElementSize = 4000;
	btDefaultCollisionConfiguration config(info);
	EXPECT_EQ(config.getPersistentManifoldPool()->getMaxCount(), 8);
	EXPECT_GE(config.getPersistentManifoldPool()->getElementSize(), int(sizeof(btPersistentManifold)));
	EXPECT_EQ(config.getCollisionAlgorithmPool()->getMaxCount(), 16);
	EXPECT_GE(config.getCollisionAlgorithmPool()->getElementSize(), 4000);

	// Borrowed pools are used and not freed by the configuration (the pools outlive it here).
	btPoolAllocator manifolds(int(sizeof(btPersistentManifold)), 2);
	btPoolAllocator algorithms(4096, 2);
	btDefaultCollisionConstructionInfo borrowed;
	borrowed.m_persistentManifoldPool = &manifolds;
	borrowed.m_collisionAlgorithmPool = &algorithms;
	{
		btDefaultCollisionConfiguration user(borrowed);
		EXPECT_EQ(user.getPersistentManifoldPool(), &manifolds);
		EXPECT_EQ(user.getCollisionAlgorithmPool(), &algorithms);
	}
	EXPECT_EQ(manifolds.getFreeCount(), 2);
}

TEST(DefaultCollisionConfiguration, AlgorithmsComeFromThePoolAndReleaseTheirManifolds)
{
	btDefaultCollisionConfiguration config;
	caliber_dispatch_test::TestDispatcher dispatcher(&config);
	btSphereShape sphere(1);
	btBoxShape box(btVector3(1, 1, 1));
	const int freeAlgorithms = config.getCollisionAlgorithmPool()->getFreeCount();
	const int freeManifolds = config.getPersistentManifoldPool()->getFreeCount();
	{
		caliber_dispatch_test::PairFixture pair(dispatcher, &sphere, btTransform::getIdentity(), &box,
		                                        btTransform::getIdentity());
		EXPECT_EQ(config.getCollisionAlgorithmPool()->getFreeCount(), freeAlgorithms - 1);
		EXPECT_EQ(config.getPersistentManifoldPool()->getFreeCount(), freeManifolds - 1);
		btManifoldArray manifolds;
		pair.m_algorithm->getAllContactManifolds(manifolds);
		EXPECT_EQ(manifolds.size(), 1);
		// Steady state: processing again allocates nothing.
		pair.process();
		pair.process();
		EXPECT_EQ(config.getPersistentManifoldPool()->getFreeCount(), freeManifolds - 1);
	}
	EXPECT_EQ(config.getCollisionAlgorithmPool()->getFreeCount(), freeAlgorithms);
	EXPECT_EQ(config.getPersistentManifoldPool()->getFreeCount(), freeManifolds);
	EXPECT_EQ(dispatcher.getNumManifolds(), 0);
}

TEST(DefaultCollisionConfiguration, EmptyShapeAndIgnoredPairsProduceNoContacts)
{
	btDefaultCollisionConfiguration config;
	caliber_dispatch_test::TestDispatcher dispatcher(&config);
	btSphereShape sphere(1);
	btEmptyShape empty;
	caliber_dispatch_test::PairFixture withEmpty(dispatcher, &sphere, btTransform::getIdentity(), &empty,
	                                             btTransform::getIdentity());
	btPersistentManifold* manifold = withEmpty.process();
	EXPECT_TRUE(manifold == 0 || manifold->getNumContacts() == 0);

	// A pair on an ignore list gets no manifold from the single-point algorithms.
	btCollisionObject a, b;
	a.setCollisionShape(&sphere);
	b.setCollisionShape(&sphere);
	a.setIgnoreCollisionCheck(&b, true);
	btCollisionObjectWrapper wa(0, &sphere, &a, a.getWorldTransform(), -1, -1);
	btCollisionObjectWrapper wb(0, &sphere, &b, b.getWorldTransform(), -1, -1);
	const int manifoldsBefore = dispatcher.getNumManifolds();
	btCollisionAlgorithm* algorithm = dispatcher.findAlgorithm(&wa, &wb, 0, BT_CONTACT_POINT_ALGORITHMS);
	btManifoldResult result(&wa, &wb);
	btDispatcherInfo info;
	algorithm->processCollision(&wa, &wb, info, &result);
	EXPECT_EQ(result.getPersistentManifold(), nullptr);
	EXPECT_EQ(dispatcher.getNumManifolds(), manifoldsBefore);
	dispatcher.destroyAlgorithm(algorithm);
}
