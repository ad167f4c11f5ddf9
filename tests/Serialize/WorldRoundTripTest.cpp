// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// A world written and read into a fresh world: its settings and bodies come back, and stepping the
// copy gives the original's trajectory. Body state is stored in the build's precision, so the copy
// is compared bit for bit; contact caches are not part of .bullet files, so scenes with contacts are
// saved before their first step (docs/serialization.md, "What a file does not hold").
#include <gtest/gtest.h>

#include "BulletWorldImporter/btBulletWorldImporter.h"
#include "Serialize/SerializeTestUtil.h"

using caliber_test::TestWorld;

namespace
{
struct Loaded
{
	TestWorld world;
	btBulletWorldImporter importer{&world.world};
	explicit Loaded(const std::vector<char>& file)
	{
		world.world.setGravity(btVector3(0, 0, 0));  // the file's gravity must replace this
		ok = importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size()));
	}
	~Loaded() { importer.deleteAllData(); }
	bool ok = false;
};

btRigidBody* bodyAt(btDiscreteDynamicsWorld& world, int index)
{
	return btRigidBody::upcast(world.getCollisionObjectArray()[index]);
}

// Compares the dynamic state of every body of two worlds, bit for bit.
void expectSameState(btDiscreteDynamicsWorld& a, btDiscreteDynamicsWorld& b, int step)
{
	ASSERT_EQ(a.getNumCollisionObjects(), b.getNumCollisionObjects());
	for (int i = 0; i < a.getNumCollisionObjects(); ++i)
	{
		btRigidBody* x = bodyAt(a, i);
		btRigidBody* y = bodyAt(b, i);
		ASSERT_TRUE(x && y);
		const btTransform& tx = x->getWorldTransform();
		const btTransform& ty = y->getWorldTransform();
		for (int k = 0; k < 3; ++k)
		{
			ASSERT_EQ(tx.getOrigin()[k], ty.getOrigin()[k]) << "body " << i << " step " << step;
			ASSERT_EQ(x->getLinearVelocity()[k], y->getLinearVelocity()[k]) << "body " << i << " step " << step;
			ASSERT_EQ(x->getAngularVelocity()[k], y->getAngularVelocity()[k]) << "body " << i << " step " << step;
			for (int c = 0; c < 3; ++c)
				ASSERT_EQ(tx.getBasis()[k][c], ty.getBasis()[k][c]) << "body " << i << " step " << step;
		}
		ASSERT_EQ(x->getActivationState(), y->getActivationState()) << "body " << i << " step " << step;
	}
}
}  // namespace

TEST(WorldRoundTrip, SettingsAndGravityComeBack)
{
	TestWorld original;
	original.world.setGravity(btVector3(1, -9, 0.5));
	original.world.getSolverInfo().m_numIterations = 23;
	original.world.getSolverInfo().m_erp2 = btScalar(0.7);
	original.world.getSolverInfo().m_splitImpulse = 0;
	Loaded loaded(original.save());
	ASSERT_TRUE(loaded.ok);
	const btVector3 g = loaded.world.world.getGravity();
	EXPECT_EQ(g.x(), 1);
	EXPECT_EQ(g.y(), -9);
	EXPECT_EQ(g.z(), btScalar(0.5));
	EXPECT_EQ(loaded.world.world.getSolverInfo().m_numIterations, 23);
	EXPECT_EQ(loaded.world.world.getSolverInfo().m_erp2, btScalar(0.7));
	EXPECT_EQ(loaded.world.world.getSolverInfo().m_splitImpulse, 0);
}

TEST(WorldRoundTrip, BodyPropertiesNamesAndFiltersComeBack)
{
	TestWorld original;
	btCollisionShape* box = original.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
	btRigidBody* ground =
	    original.body(original.shape(new btStaticPlaneShape(btVector3(0, 1, 0), 0)), 0, btVector3(0, 0, 0));
	original.world.removeRigidBody(ground);
	original.world.addRigidBody(ground, 2, 1);
	btRigidBody* crate = original.body(box, 3, btVector3(0, 5, 0));
	crate->setFriction(btScalar(0.3));
	crate->setRestitution(btScalar(0.6));
	crate->setRollingFriction(btScalar(0.01));
	crate->setDamping(btScalar(0.1), btScalar(0.2));
	crate->setSleepingThresholds(btScalar(0.5), btScalar(0.6));
	crate->setLinearFactor(btVector3(1, 1, 0));
	crate->setAngularFactor(btVector3(0, 0, 1));
	crate->setCcdMotionThreshold(btScalar(0.05));
	crate->setCcdSweptSphereRadius(btScalar(0.2));
	btRigidBody* sleeper = original.body(box, 1, btVector3(3, 5, 0));
	sleeper->setActivationState(ISLAND_SLEEPING);
	btRigidBody* kinematic = original.body(box, 0, btVector3(-3, 1, 0));
	kinematic->setCollisionFlags(kinematic->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
	btDefaultSerializer s;
	s.registerNameForPointer(crate, "crate");
	s.registerNameForPointer(ground, "ground");
	Loaded loaded(original.save(&s));
	ASSERT_TRUE(loaded.ok);
	ASSERT_EQ(loaded.importer.getNumRigidBodies(), 4);
	btRigidBody* c = loaded.importer.getRigidBodyByName("crate");
	btRigidBody* g = loaded.importer.getRigidBodyByName("ground");
	ASSERT_TRUE(c && g);
	EXPECT_EQ(loaded.importer.getRigidBodyByName("nobody"), nullptr);
	EXPECT_STREQ(loaded.importer.getNameForPointer(c), "crate");
	EXPECT_EQ(c->getFriction(), crate->getFriction());
	EXPECT_EQ(c->getRestitution(), crate->getRestitution());
	EXPECT_EQ(c->getRollingFriction(), crate->getRollingFriction());
	EXPECT_EQ(c->getLinearDamping(), crate->getLinearDamping());
	EXPECT_EQ(c->getAngularDamping(), crate->getAngularDamping());
	EXPECT_EQ(c->getLinearSleepingThreshold(), crate->getLinearSleepingThreshold());
	EXPECT_EQ(c->getCcdMotionThreshold(), crate->getCcdMotionThreshold());
	EXPECT_EQ(c->getCcdSweptSphereRadius(), crate->getCcdSweptSphereRadius());
	EXPECT_EQ(c->getInvMass(), crate->getInvMass());
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_EQ(c->getLinearFactor()[i], crate->getLinearFactor()[i]);
		EXPECT_EQ(c->getAngularFactor()[i], crate->getAngularFactor()[i]);
		EXPECT_EQ(c->getInvInertiaDiagLocal()[i], crate->getInvInertiaDiagLocal()[i]);
	}
	EXPECT_EQ(g->getInvMass(), 0);
	EXPECT_EQ(g->getBroadphaseHandle()->m_collisionFilterGroup, 2);
	EXPECT_EQ(g->getBroadphaseHandle()->m_collisionFilterMask, 1);
	EXPECT_EQ(btRigidBody::upcast(loaded.importer.getRigidBodyByIndex(2))->getActivationState(), ISLAND_SLEEPING);
	EXPECT_TRUE(loaded.importer.getRigidBodyByIndex(3)->isKinematicObject());
	// Both boxes share one shape after loading, as before.
	EXPECT_EQ(c->getCollisionShape(), loaded.importer.getRigidBodyByIndex(2)->getCollisionShape());
}

TEST(WorldRoundTrip, FlyingBodiesSavedMidFlightContinueBitForBit)
{
	TestWorld original;
	btCollisionShape* box = original.shape(new btBoxShape(btVector3(0.25, 0.5, 1)));
	box->setMargin(btScalar(0.0625));
	btCollisionShape* capsule = original.shape(new btCapsuleShape(0.25, 0.75));
	btRigidBody* a = original.body(box, 2, btVector3(0, 10, 0));
	a->setLinearVelocity(btVector3(3, 5, -1));
	a->setAngularVelocity(btVector3(1, 7, 2));  // tumbling: the gyroscopic terms matter
	btRigidBody* b = original.body(capsule, 1, btVector3(5, 10, 0));
	b->setAngularVelocity(btVector3(0, 0, 4));
	b->setDamping(btScalar(0.2), btScalar(0.3));
	for (int i = 0; i < 20; ++i) original.world.stepSimulation(btScalar(1) / 60, 0);
	Loaded loaded(original.save());
	ASSERT_TRUE(loaded.ok);
	expectSameState(original.world, loaded.world.world, 0);
	for (int i = 1; i <= 120; ++i)
	{
		original.world.stepSimulation(btScalar(1) / 60, 0);
		loaded.world.world.stepSimulation(btScalar(1) / 60, 0);
		expectSameState(original.world, loaded.world.world, i);
	}
}

TEST(WorldRoundTrip, StackAndJointsSavedBeforeTheFirstStepEvolveBitForBit)
{
	// Shape sizes are exact in float (the format stores shapes in float): double builds too must
	// get back the very same shapes for the contacts to be the same.
	TestWorld original;
	original.body(original.shape(new btStaticPlaneShape(btVector3(0, 1, 0), 0)), 0, btVector3(0, 0, 0));
	btCollisionShape* box = original.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
	box->setMargin(btScalar(0.0625));
	for (int i = 0; i < 4; ++i) original.body(box, 1, btVector3(btScalar(0.05 * i), btScalar(0.5 + 1.0 * i), 0));
	btCollisionShape* link = original.shape(new btSphereShape(0.25));
	btRigidBody* prev = original.body(link, 1, btVector3(4, 5, 0));
	original.joint(new btPoint2PointConstraint(*prev, btVector3(0, 0.5, 0)));
	for (int i = 1; i < 4; ++i)
	{
		btRigidBody* next = original.body(link, 1, btVector3(btScalar(4 + 0.5 * i), 5, 0));
		original.joint(new btPoint2PointConstraint(*prev, *next, btVector3(0.25, 0, 0), btVector3(-0.25, 0, 0)));
		prev = next;
	}
	btRigidBody* door = original.body(box, 2, btVector3(-4, 2, 0));
	btHingeConstraint* hinge = original.joint(new btHingeConstraint(*door, btVector3(0, 0, 0.5), btVector3(0, 1, 0)));
	hinge->enableAngularMotor(true, 2, 1);
	Loaded loaded(original.save());
	ASSERT_TRUE(loaded.ok);
	ASSERT_EQ(loaded.world.world.getNumConstraints(), original.world.getNumConstraints());
	for (int i = 1; i <= 180; ++i)
	{
		original.world.stepSimulation(btScalar(1) / 60, 0);
		loaded.world.world.stepSimulation(btScalar(1) / 60, 0);
		expectSameState(original.world, loaded.world.world, i);
	}
	// The scene did something: the stack settled on the ground, the chain swung.
	EXPECT_LT(bodyAt(original.world, 1)->getWorldTransform().getOrigin().y(), btScalar(0.6));
}
