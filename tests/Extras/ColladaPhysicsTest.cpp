// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// COLLADA physics: export then import is exact, the imported scene simulates like the original, and
// malformed documents fail with a message naming the line.
#include <gtest/gtest.h>

#include <cstring>

#include "BulletCollision/CollisionShapes/btCapsuleShape.h"
#include "BulletCollision/CollisionShapes/btConeShape.h"
#include "BulletCollision/CollisionShapes/btCylinderShape.h"
#include "BulletCollision/CollisionShapes/btTriangleMesh.h"
#include "Extras/ColladaTestSupport.h"
#include "Serialize/ColladaConverter/ColladaPhysics.h"

using caliber::ColladaPhysicsScene;
using collada_test::EmptyWorld;
using collada_test::import;
using collada_test::replaced;

namespace
{
// A world of every shape the converter writes, at rotated poses, with materials and velocities.
struct ShowcaseWorld
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher{&configuration};
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
	btStaticPlaneShape ground{btVector3(0, 1, 0), btScalar(-0.5)};
	btBoxShape box{btVector3(btScalar(0.5), btScalar(0.25), btScalar(0.75))};
	btSphereShape sphere{btScalar(0.3)};
	btCylinderShape cylinder{btVector3(btScalar(0.2), btScalar(0.4), btScalar(0.2))};
	btCapsuleShape capsule{btScalar(0.15), btScalar(0.6)};
	btConvexHullShape hull;
	btTriangleMesh rampMesh;
	std::unique_ptr<btBvhTriangleMeshShape> ramp;
	btCompoundShape dumbbell;
	btSphereShape bell{btScalar(0.2)};
	btBoxShape bar{btVector3(btScalar(0.4), btScalar(0.05), btScalar(0.05))};
	std::vector<std::unique_ptr<btRigidBody>> bodies;
	std::vector<std::unique_ptr<btGeneric6DofConstraint>> joints;

	ShowcaseWorld()
	{
		world.setGravity(btVector3(0, btScalar(-9.81), 0));
		const btScalar tetra[4][3] = {{0, 0, 0}, {btScalar(0.6), 0, 0}, {0, btScalar(0.6), 0}, {0, 0, btScalar(0.6)}};
		for (const auto& p : tetra) hull.addPoint(btVector3(p[0], p[1], p[2]));
		rampMesh.addTriangle(btVector3(-4, btScalar(-0.5), -2), btVector3(-2, btScalar(0.5), -2),
		                     btVector3(-2, btScalar(0.5), 2));
		rampMesh.addTriangle(btVector3(-4, btScalar(-0.5), -2), btVector3(-2, btScalar(0.5), 2),
		                     btVector3(-4, btScalar(-0.5), 2));
		ramp.reset(new btBvhTriangleMeshShape(&rampMesh, true));
		btTransform left, right, middle;
		left.setIdentity();
		left.setOrigin(btVector3(btScalar(-0.4), 0, 0));
		right.setIdentity();
		right.setOrigin(btVector3(btScalar(0.4), 0, 0));
		middle.setIdentity();
		dumbbell.addChildShape(left, &bell);
		dumbbell.addChildShape(right, &bell);
		dumbbell.addChildShape(middle, &bar);

		add(&ground, 0, btVector3(0, 0, 0), btQuaternion::getIdentity());
		add(ramp.get(), 0, btVector3(0, 0, 0), btQuaternion::getIdentity());
		add(&box, 2, btVector3(0, 1, 0), btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7)));
		add(&sphere, 1, btVector3(1, 2, 0), btQuaternion::getIdentity());
		add(&cylinder, btScalar(1.5), btVector3(-1, 2, 1), btQuaternion(btVector3(0, 0, 1), btScalar(1.2)));
		add(&capsule, btScalar(0.7), btVector3(2, 1, 1), btQuaternion(btVector3(1, 0, 0), btScalar(0.3)));
		add(&hull, btScalar(0.9), btVector3(1, 3, -1), btQuaternion(btVector3(0, 1, 0), btScalar(2.0)));
		add(&dumbbell, 3, btVector3(-1, 3, -1), btQuaternion(btVector3(1, 1, 0).normalized(), btScalar(0.4)));
		bodies[3]->setLinearVelocity(btVector3(btScalar(0.5), 0, btScalar(-0.25)));
		bodies[3]->setFriction(btScalar(0.3));
		bodies[4]->setRestitution(btScalar(0.6));

		// A 6-DoF joint with rotated frames, a free slide along x and limited swings; and a locked one whose
		// bodies may interpenetrate.
		btTransform frameA(btQuaternion(btVector3(0, 0, 1), btScalar(0.5)), btVector3(btScalar(0.5), 0, 0));
		btTransform frameB(btQuaternion(btVector3(1, 0, 0), btScalar(-0.25)),
		                   btVector3(btScalar(-0.3), btScalar(0.1), 0));
		joints.emplace_back(new btGeneric6DofConstraint(*bodies[2], *bodies[3], frameA, frameB, true));
		joints.back()->setLinearLowerLimit(btVector3(1, 0, 0));
		joints.back()->setLinearUpperLimit(btVector3(-1, 0, 0));
		joints.back()->setAngularLowerLimit(btVector3(btScalar(-0.3), btScalar(-0.2), 0));
		joints.back()->setAngularUpperLimit(btVector3(btScalar(0.3), btScalar(0.2), 0));
		world.addConstraint(joints.back().get());
		joints.emplace_back(new btGeneric6DofConstraint(*bodies[5], *bodies[6], btTransform::getIdentity(),
		                                                btTransform::getIdentity(), false));
		world.addConstraint(joints.back().get(), true);
	}

	void add(btCollisionShape* shape, btScalar mass, const btVector3& at, const btQuaternion& rotation)
	{
		btVector3 inertia(0, 0, 0);
		if (mass > 0) shape->calculateLocalInertia(mass, inertia);
		bodies.emplace_back(new btRigidBody(mass, nullptr, shape, inertia));
		// Not setWorldTransform: that leaves the world inertia tensor of the identity pose until the first step.
		bodies.back()->setCenterOfMassTransform(btTransform(rotation, at));
		world.addRigidBody(bodies.back().get());
	}

	~ShowcaseWorld()
	{
		for (auto& joint : joints) world.removeConstraint(joint.get());
		for (auto& body : bodies) world.removeRigidBody(body.get());
	}
};

std::string exportOf(const btDiscreteDynamicsWorld& world)
{
	std::string text, error;
	EXPECT_TRUE(caliber::exportColladaPhysics(world, btScalar(1) / 60, text, error)) << error;
	return text;
}

// A small valid document to damage: one dynamic box on a node.
const char* const kBoxDocument = R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<library_physics_models>
<physics_model id="model">
<rigid_body sid="box"><technique_common><dynamic>true</dynamic><mass>2</mass>
<shape><box><half_extents>0.5 0.5 0.5</half_extents></box></shape>
</technique_common></rigid_body>
</physics_model>
</library_physics_models>
<library_physics_scenes>
<physics_scene id="scene"><instance_physics_model url="#model">
<instance_rigid_body body="box" target="#node"/>
</instance_physics_model>
<technique_common><gravity>0 -9.81 0</gravity><time_step>0.01</time_step></technique_common>
</physics_scene>
</library_physics_scenes>
<library_visual_scenes><visual_scene id="visual">
<node id="node"><translate>1 2 3</translate><rotate>0 1 0 90</rotate></node>
</visual_scene></library_visual_scenes>
<scene><instance_physics_scene url="#scene"/></scene>
</COLLADA>
)";

}  // namespace

// Export, import, export again: the second document is the first, character for character, and every body
// has the original's pose, mass, inertia, material and velocity bit for bit.
TEST(ColladaPhysics, ExportThenImportIsExact)
{
	ShowcaseWorld original;
	const std::string first = exportOf(original.world);
	ColladaPhysicsScene scene;
	ASSERT_TRUE(import(first, scene)) << scene.error;
	ASSERT_EQ(scene.bodies.size(), original.bodies.size());
	EXPECT_EQ(scene.timeStep, btScalar(1) / 60);
	EmptyWorld copy;
	scene.addTo(copy.world);
	EXPECT_EQ(exportOf(copy.world), first);
	for (std::size_t i = 0; i < scene.bodies.size(); ++i)
	{
		const btRigidBody& a = *original.bodies[i];
		const btRigidBody& b = *scene.bodies[i];
		const btTransform& ta = a.getWorldTransform();
		const btTransform& tb = b.getWorldTransform();
		for (int r = 0; r < 3; ++r)
		{
			EXPECT_EQ(ta.getBasis()[r], tb.getBasis()[r]) << "body " << i;
			EXPECT_EQ(ta.getOrigin()[r], tb.getOrigin()[r]) << "body " << i;
		}
		EXPECT_EQ(a.getInvMass(), b.getInvMass()) << "body " << i;
		EXPECT_EQ(a.getInvInertiaDiagLocal(), b.getInvInertiaDiagLocal()) << "body " << i;
		EXPECT_EQ(a.getFriction(), b.getFriction()) << "body " << i;
		EXPECT_EQ(a.getRestitution(), b.getRestitution()) << "body " << i;
		EXPECT_EQ(a.getLinearVelocity(), b.getLinearVelocity()) << "body " << i;
		EXPECT_EQ(a.getCollisionShape()->getShapeType(), b.getCollisionShape()->getShapeType()) << "body " << i;
	}
	ASSERT_EQ(scene.constraints.size(), 2u);
	EXPECT_EQ(scene.constraintsInterpenetrate, std::vector<bool>({false, true}));
	for (std::size_t j = 0; j < 2; ++j)
	{
		const btGeneric6DofConstraint& a = *original.joints[j];
		const btGeneric6DofConstraint& b = static_cast<const btGeneric6DofConstraint&>(*scene.constraints[j]);
		for (int r = 0; r < 3; ++r)
		{
			EXPECT_EQ(a.getFrameOffsetA().getBasis()[r], b.getFrameOffsetA().getBasis()[r]) << "joint " << j;
			EXPECT_EQ(a.getFrameOffsetB().getBasis()[r], b.getFrameOffsetB().getBasis()[r]) << "joint " << j;
		}
		EXPECT_EQ(a.getFrameOffsetA().getOrigin(), b.getFrameOffsetA().getOrigin()) << "joint " << j;
		EXPECT_EQ(a.getFrameOffsetB().getOrigin(), b.getFrameOffsetB().getOrigin()) << "joint " << j;
		btVector3 la, lb;
		a.getAngularLowerLimit(la);
		b.getAngularLowerLimit(lb);
		EXPECT_EQ(la, lb) << "joint " << j;
		a.getLinearUpperLimit(la);
		b.getLinearUpperLimit(lb);
		EXPECT_EQ(la, lb) << "joint " << j;
		EXPECT_EQ(a.getUseLinearReferenceFrameA(), b.getUseLinearReferenceFrameA()) << "joint " << j;
	}
	scene.removeFrom(copy.world);
}

// Same inputs, same outputs: the imported copy of the scene, stepped 2 s, ends where the original does.
TEST(ColladaPhysics, ImportedSceneSimulatesExactlyLikeTheOriginal)
{
	ShowcaseWorld original;
	ColladaPhysicsScene scene;
	ASSERT_TRUE(import(exportOf(original.world), scene)) << scene.error;
	EmptyWorld copy;
	scene.addTo(copy.world);
	for (int i = 0; i < 120; ++i)
	{
		original.world.stepSimulation(btScalar(1) / 60, 0);
		copy.world.stepSimulation(btScalar(1) / 60, 0);
	}
	for (std::size_t i = 0; i < scene.bodies.size(); ++i)
		EXPECT_EQ(original.bodies[i]->getWorldTransform().getOrigin(), scene.bodies[i]->getWorldTransform().getOrigin())
		    << "body " << i;
	scene.removeFrom(copy.world);
}

// COLLADA gives angular velocity in degrees per second, which does not convert back bit for bit; the export
// also carries Caliber's radians in an <extra>, so a Caliber round trip is exact, and without the <extra>
// (another tool's document) the degrees are read.
TEST(ColladaPhysics, AngularVelocityIsExactWithCalibersExtraAndReadInDegreesWithout)
{
	ShowcaseWorld original;
	const btVector3 spin(btScalar(0.1), btScalar(-2.5), btScalar(1) / 3);
	original.bodies[2]->setAngularVelocity(spin);
	const std::string text = exportOf(original.world);
	ColladaPhysicsScene scene;
	ASSERT_TRUE(import(text, scene)) << scene.error;
	EXPECT_EQ(scene.bodies[2]->getAngularVelocity(), spin);

	std::string degreesOnly = text;
	for (std::size_t at; (at = degreesOnly.find("<extra>")) != std::string::npos;)
		degreesOnly.erase(at, degreesOnly.find("</extra>", at) + 8 - at);
	ColladaPhysicsScene fromDegrees;
	ASSERT_TRUE(import(degreesOnly, fromDegrees)) << fromDegrees.error;
	const btVector3 w = fromDegrees.bodies[2]->getAngularVelocity();
	EXPECT_NEAR(w.x(), spin.x(), 1e-6);
	EXPECT_NEAR(w.y(), spin.y(), 1e-6);
	EXPECT_NEAR(w.z(), spin.z(), 1e-6);
}

// A hand-written document with translate and rotate: the node's pose, gravity, time step, inertia from the shape.
TEST(ColladaPhysics, HandWrittenDocumentGivesThePosesAndSettingsItStates)
{
	ColladaPhysicsScene scene;
	ASSERT_TRUE(import(kBoxDocument, scene)) << scene.error;
	ASSERT_EQ(scene.bodies.size(), 1u);
	EXPECT_EQ(scene.bodyNames[0], "box");
	EXPECT_EQ(scene.gravity, btVector3(0, btScalar(-9.81), 0));
	EXPECT_EQ(scene.timeStep, btScalar(0.01));
	const btTransform& pose = scene.bodies[0]->getWorldTransform();
	EXPECT_EQ(pose.getOrigin(), btVector3(1, 2, 3));
	// 90 degrees about y takes x to -z.
	const btVector3 x = pose.getBasis() * btVector3(1, 0, 0);
	EXPECT_NEAR(x.z(), -1, 1e-6);
	EXPECT_FLOAT_EQ(1 / scene.bodies[0]->getInvMass(), 2);
	// A 1 m cube of 2 kg: inertia m (a^2 + a^2) / 12 = 1/3 about each axis.
	EXPECT_NEAR(1 / scene.bodies[0]->getInvInertiaDiagLocal().x(), 2.0 / 3.0 * 0.5 * 1.0, 0.02);
}

TEST(ColladaPhysics, MalformedDocumentsFailWithTheLineAndTheReason)
{
	const struct
	{
		std::string document;
		const char* expected;
	} cases[] = {
	    {"<COLLADA><unclosed></COLLADA>", "malformed XML"},
	    {"<?xml version=\"1.0\"?>\n<scene/>", "not COLLADA"},
	    {"<COLLADA/>", "no physics scene"},
	    {replaced(kBoxDocument, "url=\"#model\"", "url=\"#nothing\""), "'#nothing' names no <physics_model>"},
	    {replaced(kBoxDocument, "target=\"#node\"", "target=\"#elsewhere\""), "names no node"},
	    {replaced(kBoxDocument, "body=\"box\"", "body=\"ghost\""), "no rigid body 'ghost'"},
	    {replaced(kBoxDocument, "0.5 0.5 0.5", "0.5 abc 0.5"), "not a number"},
	    {replaced(kBoxDocument, "0.5 0.5 0.5", "0.5 0.5"), "needs 3 numbers, found 2"},
	    {replaced(kBoxDocument, "0.5 0.5 0.5", "0.5 nan 0.5"), "not finite"},
	    {replaced(kBoxDocument, "0.5 0.5 0.5", "0.5 1e300 0.5"), "beyond 1e15"},
	    {replaced(kBoxDocument, "0.5 0.5 0.5", "0.5 -0.5 0.5"), "must be positive"},
	    {replaced(kBoxDocument, "<mass>2</mass>", ""), "needs a <mass>"},
	    {replaced(kBoxDocument, "<mass>2</mass>", "<mass>0</mass>"), "mass must be positive"},
	    {replaced(kBoxDocument, "<dynamic>true</dynamic>", "<dynamic>yes</dynamic>"), "true or false"},
	    {replaced(kBoxDocument, "<translate>1 2 3</translate>", "<scale>2 2 2</scale>"), "not supported"},
	    {replaced(kBoxDocument, "<translate>1 2 3</translate>", "<matrix>2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1</matrix>"),
	     "scale and shear"},
	    {replaced(kBoxDocument, "<box><half_extents>0.5 0.5 0.5</half_extents></box>",
	              "<plane><equation>0 1 0 0</equation></plane>"),
	     "plane can only be static"},
	    {replaced(kBoxDocument, "<box><half_extents>0.5 0.5 0.5</half_extents></box>",
	              "<cylinder><height>1</height><radius>0.5 0.25</radius></cylinder>"),
	     "elliptic"},
	    {replaced(kBoxDocument, "<box><half_extents>0.5 0.5 0.5</half_extents></box>", "<tapered_cylinder/>"),
	     "not supported"},
	    {replaced(kBoxDocument, "<box><half_extents>0.5 0.5 0.5</half_extents></box>", "<cone/>"), "no shape"},
	    {replaced(kBoxDocument, "<box><half_extents>0.5 0.5 0.5</half_extents></box>",
	              "<instance_geometry url=\"#g\"/>"),
	     "names no <geometry>"},
	    {replaced(kBoxDocument, "<time_step>0.01</time_step>", "<time_step>-1</time_step>"),
	     "time step must be positive"},
	    {replaced(
	         kBoxDocument, "<instance_rigid_body body=\"box\" target=\"#node\"/>",
	         "<instance_rigid_body body=\"box\" target=\"#node\"/><instance_rigid_constraint constraint=\"hinge\"/>"),
	     "no rigid constraint 'hinge'"},
	    {replaced(replaced(kBoxDocument, "</physics_model>",
	                       "<rigid_constraint sid=\"j\"><ref_attachment rigid_body=\"box\"/><attachment "
	                       "rigid_body=\"lid\"/></rigid_constraint></physics_model>"),
	              "<instance_rigid_body body=\"box\" target=\"#node\"/>",
	              "<instance_rigid_body body=\"box\" target=\"#node\"/><instance_rigid_constraint constraint=\"j\"/>"),
	     "'lid' names no rigid body"},
	};
	for (const auto& c : cases)
	{
		ColladaPhysicsScene scene;
		EXPECT_FALSE(import(c.document, scene)) << c.expected;
		EXPECT_TRUE(scene.bodies.empty());
		EXPECT_NE(scene.error.find(c.expected), std::string::npos) << scene.error;
		EXPECT_EQ(scene.error.rfind("line ", 0), 0u) << scene.error;
	}
	// The line is the damaged element's.
	ColladaPhysicsScene scene;
	EXPECT_FALSE(import(replaced(kBoxDocument, "0.5 0.5 0.5", "0.5 0.5"), scene));
	EXPECT_EQ(scene.error.rfind("line 6:", 0), 0u) << scene.error;
}

TEST(ColladaPhysics, MeshesWithBadCountsOrIndicesFail)
{
	ShowcaseWorld original;
	const std::string text = exportOf(original.world);
	const std::size_t p = text.find("<p>0 1 2");
	ASSERT_NE(p, std::string::npos);
	ColladaPhysicsScene scene;
	EXPECT_FALSE(import(std::string(text).replace(p, 8, "<p>0 1 9"), scene));
	EXPECT_NE(scene.error.find("index out of range"), std::string::npos) << scene.error;
	const std::size_t count = text.find("<triangles count=\"2\"");
	ASSERT_NE(count, std::string::npos);
	ColladaPhysicsScene scene2;
	EXPECT_FALSE(import(std::string(text).replace(count, 20, "<triangles count=\"3\""), scene2));
	EXPECT_NE(scene2.error.find("count does not match"), std::string::npos) << scene2.error;
	const std::size_t array = text.find("count=\"12\">");  // the tetrahedron's 4 x 3 coordinates
	ASSERT_NE(array, std::string::npos);
	ColladaPhysicsScene scene3;
	EXPECT_FALSE(import(std::string(text).replace(array, 11, "count=\"13\">"), scene3));
	EXPECT_NE(scene3.error.find("count does not match"), std::string::npos) << scene3.error;
}

// Every prefix of an exported document and random byte edits (fixed seed) import or fail, never crash.
TEST(ColladaPhysics, TruncatedOrEditedDocumentsNeverCrash)
{
	collada_test::expectCutOrEditedDocumentsNeverCrash(kBoxDocument, 3, 500, 14);
}

TEST(ColladaPhysics, ExportRefusesObjectsAndShapesItCannotWrite)
{
	EmptyWorld empty;
	btConeShape cone(1, 2);
	btRigidBody coneBody(1, nullptr, &cone, btVector3(1, 1, 1));
	empty.world.addRigidBody(&coneBody);
	std::string text, error;
	EXPECT_FALSE(caliber::exportColladaPhysics(empty.world, btScalar(1) / 60, text, error));
	EXPECT_NE(error.find("no COLLADA form"), std::string::npos) << error;
	EXPECT_TRUE(text.empty());
	empty.world.removeRigidBody(&coneBody);

	btSphereShape ball(1);
	btRigidBody first(1, nullptr, &ball, btVector3(1, 1, 1)), second(1, nullptr, &ball, btVector3(1, 1, 1));
	empty.world.addRigidBody(&first);
	empty.world.addRigidBody(&second);
	btHingeConstraint hinge(first, second, btVector3(0, 0, 0), btVector3(0, 2, 0), btVector3(0, 0, 1),
	                        btVector3(0, 0, 1));
	empty.world.addConstraint(&hinge);
	EXPECT_FALSE(caliber::exportColladaPhysics(empty.world, btScalar(1) / 60, text, error));
	EXPECT_NE(error.find("only btGeneric6DofConstraint"), std::string::npos) << error;
	empty.world.removeConstraint(&hinge);
	btGeneric6DofConstraint toWorld(second, btTransform::getIdentity(), true);
	empty.world.addConstraint(&toWorld);
	EXPECT_FALSE(caliber::exportColladaPhysics(empty.world, btScalar(1) / 60, text, error));
	EXPECT_NE(error.find("joints to the world"), std::string::npos) << error;
	empty.world.removeConstraint(&toWorld);
	empty.world.removeRigidBody(&first);
	empty.world.removeRigidBody(&second);

	btBoxShape box(btVector3(1, 1, 1));
	btCollisionObject plain;
	plain.setCollisionShape(&box);
	empty.world.addCollisionObject(&plain);
	EXPECT_FALSE(caliber::exportColladaPhysics(empty.world, btScalar(1) / 60, text, error));
	EXPECT_NE(error.find("not a rigid body"), std::string::npos) << error;
	empty.world.removeCollisionObject(&plain);
}

TEST(ColladaPhysics, EmptyDocumentOrMissingFileFails)
{
	ColladaPhysicsScene scene;
	EXPECT_FALSE(caliber::importColladaPhysics("", 0, scene));
	EXPECT_NE(scene.error.find("empty"), std::string::npos);
	ColladaPhysicsScene other;
	EXPECT_FALSE(caliber::importColladaPhysicsFile("/nonexistent/scene.dae", other));
	EXPECT_NE(other.error.find("cannot open"), std::string::npos);
}

#if CALIBER_ASSERTS_ENABLED
TEST(ColladaPhysicsDeathTest, NullTextOrAReusedSceneAsserts)
{
	ColladaPhysicsScene scene;
	EXPECT_DEATH(caliber::importColladaPhysics(nullptr, 5, scene), "assertion failed");
	ASSERT_TRUE(import(kBoxDocument, scene));
	EXPECT_DEATH(import(kBoxDocument, scene), "assertion failed");
}
#else
TEST(ColladaPhysics, NullTextOrAReusedSceneFails)
{
	ColladaPhysicsScene scene;
	EXPECT_FALSE(caliber::importColladaPhysics(nullptr, 5, scene));
	ASSERT_TRUE(import(kBoxDocument, scene));
	EXPECT_FALSE(import(kBoxDocument, scene));
	EXPECT_EQ(scene.bodies.size(), 1u) << "the scene keeps what it had";
}
#endif
