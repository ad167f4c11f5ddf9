// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The contact cache (include/Caliber/ContactCache.h): a box-box pair whose relative pose moved less than
// the cache distance keeps the contacts of its last detection (refreshed at the new poses); more motion,
// a faster approach, or a contact-added callback gets a full detection.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "BulletCollision/BroadphaseCollision/btDbvtBroadphase.h"
#include "BulletCollision/CollisionDispatch/btCollisionDispatcher.h"
#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h"
#include "BulletCollision/CollisionDispatch/btManifoldResult.h"
#include "BulletCollision/CollisionShapes/btBoxShape.h"
#include "BulletCollision/CollisionShapes/btConvexHullShape.h"
#include "BulletCollision/NarrowPhaseCollision/btPersistentManifold.h"
#include "Caliber/ContactCache.h"
#include "LinearMath/btWarningHook.h"

namespace
{
// Restores the process-wide distance when a test ends.
struct CacheDistanceScope
{
	explicit CacheDistanceScope(btScalar distance) : saved(caliber::getContactCacheDistance())
	{
		caliber::setContactCacheDistance(distance);
	}
	~CacheDistanceScope() { caliber::setContactCacheDistance(saved); }
	btScalar saved;
};

// A cuboid hull of the given half extents, with or without its polyhedral features.
btConvexHullShape* cuboidHull(const btVector3& half, bool polyhedral)
{
	btConvexHullShape* hull = new btConvexHullShape();
	for (int i = 0; i < 8; ++i)
		hull->addPoint(
		    btVector3(i & 1 ? half.x() : -half.x(), i & 2 ? half.y() : -half.y(), i & 4 ? half.z() : -half.z()),
		    i == 7);
	if (polyhedral) hull->initializePolyhedralFeatures();
	return hull;
}

enum class Shapes
{
	Boxes,            // btBoxShape pair: the box-box algorithm
	PolyhedralHulls,  // hulls with polyhedral features: convex-convex with clipping
	PlainHulls        // hulls without: convex-convex with one GJK point per step (never cached)
};

// A 1 m box (body 1) resting 1 cm deep on a static slab (body 0), in a bare collision world.
struct BoxOnSlab
{
	btDefaultCollisionConfiguration config;
	btCollisionDispatcher dispatcher{&config};
	btDbvtBroadphase broadphase;
	btCollisionWorld world{&dispatcher, &broadphase, &config};
	std::unique_ptr<btCollisionShape> slabShape, boxShape;
	btCollisionObject slab, box;

	explicit BoxOnSlab(btScalar depth = btScalar(0.01), Shapes shapes = Shapes::Boxes)
	{
		const btVector3 slabHalf(5, 1, 5), boxHalf(btScalar(0.5), btScalar(0.5), btScalar(0.5));
		if (shapes == Shapes::Boxes)
		{
			slabShape.reset(new btBoxShape(slabHalf));
			boxShape.reset(new btBoxShape(boxHalf));
		}
		else
		{
			slabShape.reset(cuboidHull(slabHalf, shapes == Shapes::PolyhedralHulls));
			boxShape.reset(cuboidHull(boxHalf, shapes == Shapes::PolyhedralHulls));
		}
		slab.setCollisionShape(slabShape.get());
		box.setCollisionShape(boxShape.get());
		world.addCollisionObject(&slab);
		world.addCollisionObject(&box);
		world.getDispatchInfo().m_timeStep = btScalar(1) / btScalar(60);
		world.getDispatchInfo().m_useContinuous = true;
		place(btVector3(0, btScalar(1.5) - depth, 0), btQuaternion::getIdentity());
	}
	// The objects die before the world (members go in reverse order): take them out first.
	~BoxOnSlab()
	{
		world.removeCollisionObject(&box);
		world.removeCollisionObject(&slab);
	}
	void place(const btVector3& origin, const btQuaternion& rotation)
	{
		box.setWorldTransform(btTransform(rotation, origin));
		world.performDiscreteCollisionDetection();
	}
	btPersistentManifold* manifold()
	{
		return dispatcher.getNumManifolds() ? dispatcher.getManifoldByIndexInternal(0) : 0;
	}
	// The first point's local position on the box (fixed while the cache keeps the points).
	btVector3 firstLocalPointOnBox()
	{
		btPersistentManifold* m = manifold();
		const btManifoldPoint& p = m->getContactPoint(0);
		return m->getBody0() == &box ? p.m_localPointA : p.m_localPointB;
	}
	btVector3 firstLocalPointOnSlab()
	{
		btPersistentManifold* m = manifold();
		const btManifoldPoint& p = m->getContactPoint(0);
		return m->getBody0() == &slab ? p.m_localPointA : p.m_localPointB;
	}
};

const btScalar kCacheDistance = btScalar(0.001);
}  // namespace

TEST(ContactCache, ABoxThatMovedLessThanTheDistanceKeepsItsPointsRefreshedAtTheNewPose)
{
	CacheDistanceScope scope(kCacheDistance);
	BoxOnSlab scene;
	ASSERT_TRUE(scene.manifold());
	ASSERT_EQ(scene.manifold()->getNumContacts(), 4);
	const btVector3 onSlab = scene.firstLocalPointOnSlab();
	// 0.3 mm sideways and 0.2 mm up: a detection would move the slab's points with the box.
	scene.place(btVector3(btScalar(0.0003), btScalar(1.4902), 0), btQuaternion::getIdentity());
	ASSERT_EQ(scene.manifold()->getNumContacts(), 4);
	EXPECT_EQ(scene.firstLocalPointOnSlab(), onSlab) << "the cached point was replaced by a new detection";
	// The refresh measured the distances at the new pose: 0.8 mm less deep than the 1 cm of before.
	for (int i = 0; i < 4; ++i)
		EXPECT_NEAR(scene.manifold()->getContactPoint(i).getDistance(), btScalar(-0.0098), btScalar(1e-5));

	// With the cache off, the same motion gives new points.
	caliber::setContactCacheDistance(0);
	scene.place(btVector3(btScalar(0.0006), btScalar(1.4902), 0), btQuaternion::getIdentity());
	EXPECT_NE(scene.firstLocalPointOnSlab(), onSlab);
}

TEST(ContactCache, PolyhedralHullsUseTheCacheAndOtherConvexPairsAreDetectedEveryStep)
{
	CacheDistanceScope scope(kCacheDistance);
	for (Shapes shapes : {Shapes::PolyhedralHulls, Shapes::PlainHulls})
	{
		BoxOnSlab scene(btScalar(0.01), shapes);
		// The convex algorithm makes its manifold in its first detection; the cache starts at the second.
		scene.place(btVector3(0, btScalar(1.49), 0), btQuaternion::getIdentity());
		ASSERT_TRUE(scene.manifold());
		ASSERT_GT(scene.manifold()->getNumContacts(), 0);
		const btVector3 onSlab = scene.firstLocalPointOnSlab();
		scene.place(btVector3(btScalar(0.0003), btScalar(1.49), 0), btQuaternion::getIdentity());
		if (shapes == Shapes::PolyhedralHulls)
		{
			EXPECT_EQ(scene.manifold()->getNumContacts(), 4);
			EXPECT_EQ(scene.firstLocalPointOnSlab(), onSlab) << "polyhedral hulls: the cached point was replaced";
		}
		else
		{
			// One GJK point per step builds the manifold up over several steps: caching would freeze it.
			EXPECT_NE(scene.firstLocalPointOnSlab(), onSlab) << "hulls without polyhedra must be detected";
		}
	}
}

TEST(ContactCache, AMaterialChangeReachesTheCachedPointsAtOnce)
{
	CacheDistanceScope scope(kCacheDistance);
	for (Shapes shapes : {Shapes::Boxes, Shapes::PolyhedralHulls})
	{
		BoxOnSlab scene(btScalar(0.01), shapes);
		scene.place(btVector3(0, btScalar(1.49), 0), btQuaternion::getIdentity());
		const btVector3 onSlab = scene.firstLocalPointOnSlab();
		// Ice under a resting box: a box held by friction on a slope must start to slide at once, not once it
		// has moved (it would never move). So must a bounce, rolling friction and soft contacts.
		scene.slab.setFriction(0);
		scene.box.setRestitution(btScalar(0.5));
		scene.slab.setRestitution(btScalar(0.5));
		scene.box.setRollingFriction(btScalar(0.2));
		scene.slab.setRollingFriction(btScalar(0.5));
		scene.box.setContactStiffnessAndDamping(1000, 10);
		scene.place(btVector3(0, btScalar(1.49), 0), btQuaternion::getIdentity());
		ASSERT_EQ(scene.firstLocalPointOnSlab(), onSlab) << "the pair must still be cached for this test";
		const btPersistentManifold* m = scene.manifold();
		for (int i = 0; i < m->getNumContacts(); ++i)
		{
			const btManifoldPoint& p = m->getContactPoint(i);
			EXPECT_EQ(p.m_combinedFriction, btScalar(0));
			EXPECT_EQ(p.m_combinedRestitution, btScalar(0.25));
			// Bullet's rule r0 f1 + r1 f0, with the slab's friction now 0 and the box's the default 0.5.
			EXPECT_EQ(p.m_combinedRollingFriction, btScalar(0.5) * btScalar(0.5));
			EXPECT_TRUE(p.m_contactPointFlags & BT_CONTACT_FLAG_CONTACT_STIFFNESS_DAMPING);
			// In series with the slab's default (a huge stiffness): the box's own.
			EXPECT_NEAR(p.m_combinedContactStiffness1, btScalar(1000), btScalar(0.01));
		}
	}
}

TEST(ContactCache, AClearedManifoldIsFilledAgainAtTheNextDetection)
{
	CacheDistanceScope scope(kCacheDistance);
	BoxOnSlab scene;
	ASSERT_EQ(scene.manifold()->getNumContacts(), 4);
	// A program that empties a manifold (as after a teleport) must not leave the resting box without
	// contacts until it has sunk a millimetre.
	scene.manifold()->clearManifold();
	scene.place(btVector3(0, btScalar(1.49), 0), btQuaternion::getIdentity());
	EXPECT_EQ(scene.manifold()->getNumContacts(), 4);
}

TEST(ContactCache, AResizedShapeIsDetectedAgain)
{
	CacheDistanceScope scope(kCacheDistance);
	BoxOnSlab scene;
	const btVector3 onBox = scene.firstLocalPointOnBox();
	// The box grows by 10% without moving: its corners are elsewhere, and so are the contacts.
	scene.boxShape->setLocalScaling(btVector3(btScalar(1.1), btScalar(1.1), btScalar(1.1)));
	scene.place(btVector3(0, btScalar(1.49), 0), btQuaternion::getIdentity());
	EXPECT_NE(scene.firstLocalPointOnBox(), onBox);
	EXPECT_NEAR(btFabs(scene.firstLocalPointOnBox().x()), btScalar(0.55), btScalar(0.01));
}

TEST(ContactCache, MotionBeyondTheDistanceIsDetectedAgainCountedFromTheLastDetection)
{
	CacheDistanceScope scope(kCacheDistance);
	BoxOnSlab scene;
	const btVector3 onSlab = scene.firstLocalPointOnSlab();
	// 0.6 mm twice: each step alone is within the distance, together they are not.
	scene.place(btVector3(btScalar(0.0006), btScalar(1.49), 0), btQuaternion::getIdentity());
	EXPECT_EQ(scene.firstLocalPointOnSlab(), onSlab);
	scene.place(btVector3(btScalar(0.0012), btScalar(1.49), 0), btQuaternion::getIdentity());
	EXPECT_NE(scene.firstLocalPointOnSlab(), onSlab);
}

TEST(ContactCache, TurningCountsByHowFarTheBoxCornersMove)
{
	CacheDistanceScope scope(kCacheDistance);
	BoxOnSlab scene;
	const btVector3 onSlab = scene.firstLocalPointOnSlab();
	// The box's corners are sqrt(3)/2 m from its centre. The cache bounds a point's motion by the extent
	// (0.866 m) times the change of the rotation's columns (sqrt(2) * 2 sin(angle/2) for a turn about y):
	// 0.5 mm for 0.00041 rad, 1.2 mm for 0.001 rad.
	const btVector3 origin(0, btScalar(1.49), 0);
	scene.place(origin, btQuaternion(btVector3(0, 1, 0), btScalar(0.00041)));
	EXPECT_EQ(scene.firstLocalPointOnSlab(), onSlab);
	scene.place(origin, btQuaternion(btVector3(0, 1, 0), btScalar(0.001)));
	EXPECT_NE(scene.firstLocalPointOnSlab(), onSlab);
}

TEST(ContactCache, AFastApproachIsDetectedBeforeTheBodiesMove)
{
	CacheDistanceScope scope(kCacheDistance);
	// 3 cm apart: farther than the contact breaking threshold (2 cm), so a pair at rest has no point.
	BoxOnSlab scene(btScalar(-0.03));
	ASSERT_TRUE(scene.manifold());
	EXPECT_EQ(scene.manifold()->getNumContacts(), 0);
	// Falling at 10 m/s the box closes 17 cm this step: the speculative points must be found although
	// the pose has not changed at all.
	scene.box.setInterpolationLinearVelocity(btVector3(0, -10, 0));
	scene.place(btVector3(0, btScalar(1.53), 0), btQuaternion::getIdentity());
	ASSERT_EQ(scene.manifold()->getNumContacts(), 4);
	EXPECT_NEAR(scene.manifold()->getContactPoint(0).getDistance(), btScalar(0.03), btScalar(1e-5));
}

namespace
{
int g_addedCalls = 0;
bool countAdded(btManifoldPoint&, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*, int, int)
{
	++g_addedCalls;
	return false;
}
}  // namespace

TEST(ContactCache, AContactAddedCallbackSeesEveryPointOfEveryDetection)
{
	CacheDistanceScope scope(kCacheDistance);
	ContactAddedCallback saved = gContactAddedCallback;
	gContactAddedCallback = countAdded;
	g_addedCalls = 0;
	{
		BoxOnSlab scene;
		scene.box.setCollisionFlags(scene.box.getCollisionFlags() | btCollisionObject::CF_CUSTOM_MATERIAL_CALLBACK);
		const int first = g_addedCalls;
		for (int step = 0; step < 3; ++step) scene.place(btVector3(0, btScalar(1.49), 0), btQuaternion::getIdentity());
		// The box does not move, yet each detection reports its 4 points to the callback.
		EXPECT_EQ(g_addedCalls - first, 12);
	}
	gContactAddedCallback = saved;
}

TEST(ContactCache, NonsenseDistancesAreRefused)
{
	CacheDistanceScope scope(btScalar(0.002));
	int warnings = 0;
	btSetWarningHook([](const char*, void* count) { ++*static_cast<int*>(count); }, &warnings);
#if CALIBER_ASSERTS_ENABLED
	EXPECT_DEATH(caliber::setContactCacheDistance(-1), "finite");
#else
	caliber::setContactCacheDistance(-1);
	caliber::setContactCacheDistance(std::numeric_limits<btScalar>::quiet_NaN());
	caliber::setContactCacheDistance(std::numeric_limits<btScalar>::infinity());
	EXPECT_EQ(warnings, 3);
#endif
	btSetWarningHook(0, 0);
	EXPECT_EQ(caliber::getContactCacheDistance(), btScalar(0.002));
	caliber::setContactCacheDistance(0);
	EXPECT_EQ(caliber::getContactCacheDistance(), btScalar(0));
}
