// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// btWorldImporter's flag eRESTORE_EXISTING_OBJECTS: a file loaded with it creates nothing and writes its
// state into the world's own objects (docs/serialization.md, "Restoring into existing objects"). The main
// check: a world saved, changed and restored saves again to the very same bytes, so every field the file
// holds went back into the same objects. Misuse (names or ids that match nothing, other kinds, duplicates,
// fewer objects, no world) gives warnings and leaves the unmatched objects alone.
#include <gtest/gtest.h>

#include "BulletDynamics/ConstraintSolver/btGeneric6DofSpring2Constraint.h"
#include "BulletWorldImporter/btBulletWorldImporter.h"
#include "Serialize/SerializeTestUtil.h"

using caliber_test::TestWorld;
using caliber_test::WarningLog;

namespace
{
// A ground, a plain collision object, three boxes and a sphere, joined by a hinge with a limit and a
// motor, a point-to-point joint to the world and a spring2 joint; stepped so that they move.
struct Scene
{
	TestWorld t;
	btBoxShape* box = t.shape(new btBoxShape(btVector3(0.5, 0.5, 0.5)));
	btSphereShape* ball = t.shape(new btSphereShape(0.4));
	btRigidBody* ground = t.body(t.shape(new btBoxShape(btVector3(20, 1, 20))), 0, btVector3(0, -1, 0));
	btCollisionObject wall;
	btRigidBody* a = t.body(box, 1, btVector3(0, 3, 0));
	btRigidBody* b = t.body(box, 2, btVector3(1.2, 3, 0));
	btRigidBody* c = t.body(ball, 1, btVector3(-2, 4, 0));
	btRigidBody* d = t.body(box, 1, btVector3(3, 2, 1));
	btHingeConstraint* hinge;
	btPoint2PointConstraint* point;
	btGeneric6DofSpring2Constraint* spring;

	Scene()
	{
		wall.setCollisionShape(box);
		wall.getWorldTransform().setOrigin(btVector3(6, 0.5, 0));
		t.world.addCollisionObject(&wall);
		btTransform fa, fb;
		fa.setIdentity();
		fb.setIdentity();
		fa.setOrigin(btVector3(0.6, 0, 0));
		fb.setOrigin(btVector3(-0.6, 0, 0));
		hinge = t.joint(new btHingeConstraint(*a, *b, fa, fb));
		hinge->setLimit(-0.5, 0.7);
		hinge->enableAngularMotor(true, 1.5, 3);
		point = t.joint(new btPoint2PointConstraint(*c, btVector3(0, 0.5, 0)));
		spring = t.joint(new btGeneric6DofSpring2Constraint(*b, *d, fa, fb));
		spring->enableSpring(1, true);
		spring->setStiffness(1, 40);
		for (int i = 0; i < 30; ++i) t.world.stepSimulation(btScalar(1) / 60, 0);
	}
	~Scene() { t.world.removeCollisionObject(&wall); }

	// Changes every kind of state and setting the file holds.
	void mutate()
	{
		btTransform moved;
		moved.setIdentity();
		moved.setOrigin(btVector3(9, 9, 9));
		moved.setRotation(btQuaternion(btVector3(1, 0, 0), 0.3));
		a->setCenterOfMassTransform(moved);
		a->setLinearVelocity(btVector3(5, 0, 0));
		b->setAngularVelocity(btVector3(0, 7, 0));
		c->setFriction(0.01);
		c->setDamping(0.4, 0.4);
		d->forceActivationState(DISABLE_DEACTIVATION);
		d->setGravity(btVector3(0, 3, 0));
		wall.getWorldTransform().setOrigin(btVector3(-6, 0, 0));
		wall.setRestitution(0.9);
		hinge->setLimit(-0.1, 0.1);
		hinge->enableAngularMotor(false, 0, 0);
		hinge->setEnabled(false);
		point->setPivotA(btVector3(1, 1, 1));
		spring->setStiffness(1, 5);
		spring->setBreakingImpulseThreshold(12);
		t.world.setGravity(btVector3(0, 0, 0));
	}

	std::vector<btCollisionObject*> objects() const
	{
		const btCollisionObjectArray& o = t.world.getCollisionObjectArray();
		return std::vector<btCollisionObject*>(&o[0], &o[0] + o.size());
	}
	std::vector<btTypedConstraint*> joints()
	{
		std::vector<btTypedConstraint*> out;
		for (int i = 0; i < t.world.getNumConstraints(); ++i) out.push_back(t.world.getConstraint(i));
		return out;
	}
};

bool restore(btBulletWorldImporter& importer, std::vector<char> file)
{
	importer.setImporterFlags(eRESTORE_EXISTING_OBJECTS);
	return importer.loadFileFromMemory(file.data(), int(file.size()));
}
}  // namespace

TEST(RestoreExistingObjects, AChangedWorldGetsItsSavedStateBackInTheSameObjectsAndSavesToTheSameBytes)
{
	Scene s;
	const std::vector<char> saved = s.t.save();
	const std::vector<btCollisionObject*> objects = s.objects();
	const std::vector<btTypedConstraint*> joints = s.joints();
	const btScalar upper = s.hinge->getUpperLimit();
	s.mutate();
	ASSERT_NE(s.t.save(), saved);  // the changes reach the file: the comparison below can fail

	WarningLog log;
	btBulletWorldImporter importer(&s.t.world);
	ASSERT_TRUE(restore(importer, saved)) << log.all();
	EXPECT_EQ(log.count(), 0) << log.all();
	// Nothing created, nothing added: the same objects and joints in the same order.
	EXPECT_EQ(importer.getNumRigidBodies(), 0);
	EXPECT_EQ(importer.getNumCollisionShapes(), 0);
	EXPECT_EQ(importer.getNumConstraints(), 0);
	EXPECT_EQ(s.objects(), objects);
	EXPECT_EQ(s.joints(), joints);
	// Every field the file holds is back: the world saves to the saved bytes.
	EXPECT_EQ(s.t.save(), saved);
	EXPECT_TRUE(s.hinge->isEnabled());
	EXPECT_EQ(s.hinge->getUpperLimit(), upper);
	EXPECT_EQ(s.point->getPivotInA(), btVector3(0, 0.5, 0));
	EXPECT_EQ(s.t.world.getGravity(), btVector3(0, -10, 0));
}

TEST(RestoreExistingObjects, ObjectsTheImporterLoadedAreMatchedByName)
{
	Scene source;
	btDefaultSerializer named;
	named.registerNameForPointer(source.a, "left");
	named.registerNameForPointer(source.b, "right");
	named.registerNameForPointer(source.c, "ball");
	named.registerNameForPointer(source.d, "last");
	named.registerNameForPointer(source.ground, "ground");
	named.registerNameForPointer(&source.wall, "wall");
	named.registerNameForPointer(source.hinge, "elbow");
	const std::vector<char> file = source.t.save(&named);

	TestWorld world;
	btBulletWorldImporter importer(&world.world);
	ASSERT_TRUE(importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));
	const int bodies = importer.getNumRigidBodies();
	btRigidBody* left = importer.getRigidBodyByName("left");
	ASSERT_NE(left, nullptr);
	for (int i = 0; i < 20; ++i) world.world.stepSimulation(btScalar(1) / 60, 0);
	ASSERT_NE(left->getWorldTransform().getOrigin(), source.a->getWorldTransform().getOrigin());

	WarningLog log;
	ASSERT_TRUE(restore(importer, file)) << log.all();
	EXPECT_EQ(log.count(), 0) << log.all();
	EXPECT_EQ(importer.getNumRigidBodies(), bodies);
	EXPECT_EQ(importer.getRigidBodyByName("left"), left);
	EXPECT_EQ(left->getWorldTransform().getOrigin(), source.a->getWorldTransform().getOrigin());
	EXPECT_EQ(left->getLinearVelocity(), source.a->getLinearVelocity());
	EXPECT_EQ(importer.getRigidBodyByName("ball")->getWorldTransform().getOrigin(),
	          source.c->getWorldTransform().getOrigin());
	importer.deleteAllData();
}

TEST(RestoreExistingObjects, ANameTheWorldDoesNotHaveIsReportedAndNothingElseChanges)
{
	Scene source;
	btDefaultSerializer named;
	named.registerNameForPointer(source.a, "left");
	const std::vector<char> file = source.t.save(&named);
	TestWorld world;
	btBulletWorldImporter importer(&world.world);
	ASSERT_TRUE(importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));

	Scene other;
	btDefaultSerializer renamed;
	renamed.registerNameForPointer(other.a, "nobody");
	WarningLog log;
	EXPECT_FALSE(restore(importer, other.t.save(&renamed)));
	EXPECT_TRUE(log.contains("rigid body 1 'nobody': no object of the world has its name")) << log.all();
	EXPECT_EQ(importer.getRigidBodyByName("left")->getWorldTransform().getOrigin(),
	          source.a->getWorldTransform().getOrigin());
	importer.deleteAllData();
}

TEST(RestoreExistingObjects, AnObjectOfAnotherKindOrShapeOrMassIsNotWrittenInto)
{
	Scene s;
	const std::vector<char> saved = s.t.save();
	// Same unique ids, other kinds: the ball's shape is now a box, the wall is a rigid body, the first box
	// has become static.
	Scene other;
	other.c->setCollisionShape(other.box);
	other.a->setMassProps(0, btVector3(0, 0, 0));
	const btVector3 cAt = other.c->getWorldTransform().getOrigin();
	WarningLog log;
	btBulletWorldImporter importer(&other.t.world);
	EXPECT_FALSE(restore(importer, saved));
	EXPECT_TRUE(log.contains("has a shape of another type")) << log.all();
	EXPECT_TRUE(log.contains("dynamic in the file and static in the world")) << log.all();
	EXPECT_EQ(other.c->getWorldTransform().getOrigin(), cAt);
	// A joint to a body that was not restored is not restored either.
	EXPECT_TRUE(log.contains("refers to a body that was not restored")) << log.all();
	EXPECT_EQ(importer.getNumRigidBodies(), 0);

	// A plain object in the file, a rigid body under its id in the world.
	TestWorld swapped;
	btRigidBody* first = swapped.body(s.box, 1, btVector3(0, 0, 0));
	btBulletWorldImporter second(&swapped.world);
	btDefaultSerializer one;
	one.startSerialization();
	s.wall.serializeSingleObject(&one);
	one.finishSerialization();
	const std::vector<char> wallOnly = caliber_test::bytesOf(one);
	// The pair cache hashes ids: the borrowed id is given back before the world is touched again.
	const int ownId = first->getBroadphaseHandle()->m_uniqueId;
	first->getBroadphaseHandle()->m_uniqueId = s.wall.getBroadphaseHandle()->m_uniqueId;
	WarningLog log2;
	EXPECT_FALSE(restore(second, wallOnly));
	first->getBroadphaseHandle()->m_uniqueId = ownId;
	EXPECT_TRUE(log2.contains("is of another kind")) << log2.all();
}

TEST(RestoreExistingObjects, DuplicateNamesRestoreOnlyOnceAndAreReported)
{
	Scene source;
	btDefaultSerializer twins;
	twins.setSerializationFlags(BT_SERIALIZE_NO_DUPLICATE_ASSERT);
	twins.registerNameForPointer(source.a, "twin");
	twins.registerNameForPointer(source.b, "twin");
	const std::vector<char> file = source.t.save(&twins);

	// The world holds two objects named "twin" (the importer loaded them so): ambiguous.
	TestWorld world;
	btBulletWorldImporter importer(&world.world);
	ASSERT_TRUE(importer.loadFileFromMemory(const_cast<char*>(file.data()), int(file.size())));
	WarningLog log;
	EXPECT_FALSE(restore(importer, file));
	EXPECT_TRUE(log.contains("2 objects of the world have its name")) << log.all();
	importer.deleteAllData();

	// Two file objects that resolve to one world object: the second is refused.
	// (The file is written while b borrows a's id; the pair cache hashes ids, so it is given back at once.)
	Scene s;
	const int ownId = s.b->getBroadphaseHandle()->m_uniqueId;
	s.b->getBroadphaseHandle()->m_uniqueId = s.a->getBroadphaseHandle()->m_uniqueId;
	const std::vector<char> saved = s.t.save();
	s.b->getBroadphaseHandle()->m_uniqueId = ownId;
	const btVector3 aAt = s.a->getWorldTransform().getOrigin();
	WarningLog log2;
	btBulletWorldImporter again(&s.t.world);
	EXPECT_FALSE(restore(again, saved));
	EXPECT_EQ(s.a->getWorldTransform().getOrigin(), aAt);
	EXPECT_TRUE(log2.contains("already restored from an earlier object of the file")) << log2.all();
}

TEST(RestoreExistingObjects, AWorldWithFewerObjectsRestoresWhatItHasAndReportsTheRest)
{
	Scene s;
	const std::vector<char> saved = s.t.save();
	// The same first objects (so the same unique ids), but not the rest.
	TestWorld smaller;
	smaller.body(s.box, 0, btVector3(0, 0, 0));
	btRigidBody* first = smaller.body(s.box, 1, btVector3(0, 0, 0));
	WarningLog log;
	btBulletWorldImporter importer(&smaller.world);
	EXPECT_FALSE(restore(importer, saved));
	EXPECT_TRUE(log.contains("no object of the world has its unique id")) << log.all();
	EXPECT_TRUE(log.contains("no joint of the world joins its bodies") || log.contains("was not restored"))
	    << log.all();
	EXPECT_EQ(smaller.world.getNumCollisionObjects(), 2);
	EXPECT_EQ(smaller.world.getNumConstraints(), 0);
	EXPECT_EQ(first->getWorldTransform().getOrigin(), s.a->getWorldTransform().getOrigin());
	EXPECT_EQ(first->getLinearVelocity(), s.a->getLinearVelocity());
}

TEST(RestoreExistingObjects, NoWorldIsRefused)
{
	Scene s;
	const std::vector<char> saved = s.t.save();
	WarningLog log;
	btBulletWorldImporter importer(0);
	EXPECT_FALSE(restore(importer, saved));
	EXPECT_TRUE(log.contains("needs the importer's world")) << log.all();
	EXPECT_EQ(importer.getNumRigidBodies(), 0);
}
