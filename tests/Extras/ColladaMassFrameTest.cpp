// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// COLLADA mass_frame: a rigid body's centre of mass and principal axes in its node's frame. The imported
// body sits on its centre of mass, its shapes and joint frames stay where the document put them, and it
// spins about that centre.
#include <gtest/gtest.h>

#include <string>

#include "Extras/ColladaTestSupport.h"
#include "Serialize/ColladaConverter/ColladaPhysics.h"

using caliber::ColladaPhysicsScene;
using collada_test::EmptyWorld;
using collada_test::import;

namespace
{

// A dynamic box (inertia given) on a node turned 90 degrees about y, joined to a static ball; massFrame is
// put into the box's technique_common.
std::string document(const std::string& massFrame, const std::string& gravity = "0 -9.81 0")
{
	return R"(<?xml version="1.0"?>
<COLLADA version="1.4.1">
<library_physics_models><physics_model id="model">
<rigid_body sid="box"><technique_common><dynamic>true</dynamic><mass>2</mass>)" +
	       massFrame + R"(
<inertia>0.5 1 1.5</inertia><shape><box><half_extents>0.5 0.25 0.75</half_extents></box></shape>
</technique_common></rigid_body>
<rigid_body sid="ball"><technique_common><dynamic>false</dynamic><mass_frame><translate>5 5 5</translate></mass_frame>
<shape><sphere><radius>0.3</radius></sphere></shape></technique_common></rigid_body>
<rigid_constraint sid="joint"><ref_attachment rigid_body="box"><translate>0.5 0 0</translate><rotate>1 0 0 30</rotate>
</ref_attachment><attachment rigid_body="ball"/></rigid_constraint>
</physics_model></library_physics_models>
<library_physics_scenes><physics_scene id="scene"><instance_physics_model url="#model">
<instance_rigid_body body="box" target="#boxNode"/><instance_rigid_body body="ball" target="#ballNode"/>
<instance_rigid_constraint constraint="joint"/>
</instance_physics_model><technique_common><gravity>)" +
	       gravity + R"(</gravity></technique_common></physics_scene></library_physics_scenes>
<library_visual_scenes><visual_scene id="visual">
<node id="boxNode"><translate>1 2 3</translate><rotate>0 1 0 90</rotate></node>
<node id="ballNode"><translate>0 4 0</translate></node>
</visual_scene></library_visual_scenes>
<scene><instance_physics_scene url="#scene"/></scene>
</COLLADA>
)";
}

const char* const kMassFrame = "<mass_frame><translate>0.2 0.1 0</translate><rotate>0 0 1 90</rotate></mass_frame>";

void expectNear(const btVector3& a, const btVector3& b, double tolerance, const char* what)
{
	for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << what << ", axis " << i;
}

// Float rounding of a few unit-sized products (quaternion to matrix, frame inverses): 1e-5.
const double kRounding = 1e-5;
}  // namespace

TEST(ColladaMassFrame, BodySitsOnItsCentreOfMassWithItsShapeAndJointWhereTheDocumentPutThem)
{
	ColladaPhysicsScene plain, framed;
	ASSERT_TRUE(import(document(""), plain)) << plain.error;
	ASSERT_TRUE(import(document(kMassFrame), framed)) << framed.error;
	const btRigidBody& a = *plain.bodies[0];
	const btRigidBody& b = *framed.bodies[0];
	// The node turns 90 degrees about y (x to -z): the centre (0.2, 0.1, 0) lies at (1, 2.1, 2.8).
	expectNear(b.getCenterOfMassPosition(), btVector3(1, btScalar(2.1), btScalar(2.8)), kRounding, "centre of mass");
	expectNear(a.getCenterOfMassPosition(), btVector3(1, 2, 3), kRounding, "centre without a mass frame");
	// The box itself has not moved.
	btVector3 minA, maxA, minB, maxB;
	a.getAabb(minA, maxA);
	b.getAabb(minB, maxB);
	expectNear(minA, minB, kRounding, "bounding box minimum");
	expectNear(maxA, maxB, kRounding, "bounding box maximum");
	// The principal axes: the mass frame's x (inertia 0.5) is the node's y (rotate 0 0 1 90), which is the
	// world's y; its y (inertia 1) is the node's -x, the world's z.
	expectNear(b.getInvInertiaTensorWorld() * btVector3(0, 1, 0), btVector3(0, 2, 0), kRounding, "about world y");
	expectNear(b.getInvInertiaTensorWorld() * btVector3(0, 0, 1), btVector3(0, 0, 1), kRounding, "about world z");
	// The joint's frame on the box is at the same place in the world with and without the mass frame.
	const auto* ja = static_cast<const btGeneric6DofConstraint*>(plain.constraints[0].get());
	const auto* jb = static_cast<const btGeneric6DofConstraint*>(framed.constraints[0].get());
	const btTransform pivotA = a.getCenterOfMassTransform() * ja->getFrameOffsetA();
	const btTransform pivotB = b.getCenterOfMassTransform() * jb->getFrameOffsetA();
	expectNear(pivotA.getOrigin(), pivotB.getOrigin(), kRounding, "joint pivot");
	for (int r = 0; r < 3; ++r) expectNear(pivotA.getBasis()[r], pivotB.getBasis()[r], kRounding, "joint axes");
	// A static body's mass frame means nothing: the ball stays on its node.
	EXPECT_EQ(framed.bodies[1]->getCenterOfMassPosition(), btVector3(0, 4, 0));
}

// Without gravity or contacts a body spinning about a principal axis keeps its centre of mass still
// (momentum conservation) while the box's middle, 0.22 m from it, goes round it.
TEST(ColladaMassFrame, FreeBodySpinsAboutItsCentreOfMass)
{
	std::string text = document(kMassFrame, "0 0 0");
	const std::string from = "<instance_rigid_body body=\"box\" target=\"#boxNode\"/>";
	text.replace(text.find(from), from.size(),
	             "<instance_rigid_body body=\"box\" target=\"#boxNode\"><technique_common><angular_velocity>0 90 0"
	             "</angular_velocity></technique_common></instance_rigid_body>");
	text.replace(text.find("<instance_rigid_constraint constraint=\"joint\"/>"), 47, "");
	ColladaPhysicsScene scene;
	ASSERT_TRUE(import(text, scene)) << scene.error;
	EmptyWorld w;
	scene.addTo(w.world);
	btRigidBody& box = *scene.bodies[0];
	const btTransform toMiddle =
	    box.getCenterOfMassTransform().inverse() * btTransform(btQuaternion::getIdentity(), btVector3(1, 2, 3));
	const btVector3 centre = box.getCenterOfMassPosition();
	for (int i = 0; i < 60; ++i) w.world.stepSimulation(btScalar(1) / 60, 0);
	const btVector3 middle = (box.getCenterOfMassTransform() * toMiddle).getOrigin();
	expectNear(box.getCenterOfMassPosition(), centre, kRounding, "centre of mass after 1 s");
	// A quarter turn (90 degrees per second for 1 s) about y moves the middle by sqrt(2) * 0.2 m.
	EXPECT_NEAR((middle - btVector3(1, 2, 3)).length(), std::sqrt(2.0) * 0.2, 1e-3);
	EXPECT_NEAR((middle - centre).length(), std::sqrt(0.05), kRounding) << "the body stays rigid";
	scene.removeFrom(w.world);
}

TEST(ColladaMassFrame, BadMassFramesFailWithTheLine)
{
	const struct
	{
		std::string frame, expected;
	} cases[] = {
	    {"<mass_frame><scale>2 2 2</scale></mass_frame>", "line 4: <scale> is not supported"},
	    {"<mass_frame><translate>0 1</translate></mass_frame>", "needs 3 numbers, found 2"},
	    {"<mass_frame><rotate>0 0 0 30</rotate></mass_frame>", "zero axis"},
	    {"<mass_frame><translate>0 nan 0</translate></mass_frame>", "not finite"},
	    {"<mass_frame><matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 2</matrix></mass_frame>", "not a rotation and translation"},
	};
	for (const auto& c : cases)
	{
		ColladaPhysicsScene scene;
		EXPECT_FALSE(import(document(c.frame), scene)) << c.frame;
		EXPECT_NE(scene.error.find(c.expected), std::string::npos) << c.frame << ": " << scene.error;
		EXPECT_TRUE(scene.bodies.empty());
	}
	// An empty mass frame is the body's frame.
	ColladaPhysicsScene empty;
	ASSERT_TRUE(import(document("<mass_frame/>"), empty)) << empty.error;
	EXPECT_EQ(empty.bodies[0]->getCollisionShape()->getShapeType(), BOX_SHAPE_PROXYTYPE);
}

// Caliber writes no mass_frame (a body's frame is its centre of mass): export and import again keep the
// centre, the box and the joint pivot.
TEST(ColladaMassFrame, ExportOfAnImportedMassFrameKeepsTheBody)
{
	ColladaPhysicsScene framed;
	ASSERT_TRUE(import(document(kMassFrame), framed)) << framed.error;
	EmptyWorld w;
	framed.addTo(w.world);
	std::string text, error;
	ASSERT_TRUE(caliber::exportColladaPhysics(w.world, btScalar(1) / 60, text, error)) << error;
	framed.removeFrom(w.world);
	EXPECT_EQ(text.find("mass_frame"), std::string::npos);
	ColladaPhysicsScene again;
	ASSERT_TRUE(import(text, again)) << again.error;
	expectNear(again.bodies[0]->getCenterOfMassPosition(), framed.bodies[0]->getCenterOfMassPosition(), kRounding,
	           "centre of mass");
	btVector3 minA, maxA, minB, maxB;
	framed.bodies[0]->getAabb(minA, maxA);
	again.bodies[0]->getAabb(minB, maxB);
	expectNear(minA, minB, kRounding, "bounding box minimum");
	expectNear(maxA, maxB, kRounding, "bounding box maximum");
}
