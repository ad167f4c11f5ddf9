// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// COLLADA import of <asset>'s unit and up axis (a Z-up centimetre scene is the Y-up metre scene) and of
// polylist and polygons meshes (triangulated as the triangles they stand for), with their bad input.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "BulletCollision/CollisionShapes/btTriangleCallback.h"
#include "Extras/ColladaTestSupport.h"
#include "Serialize/ColladaConverter/ColladaPhysics.h"

using caliber::ColladaPhysicsScene;
using collada_test::EmptyWorld;
using collada_test::import;
using collada_test::replaced;

namespace
{

// One scene, written either in Caliber's frame (Y_UP, metres) or as a Blender export would (Z_UP,
// centimetres): there every node hangs under a root turned +90 degrees about x (the document's axes seen
// from the world's), every length is 100 times larger, inertia 10^4 times, and world vectors (gravity,
// velocities) are given in the document's axes: world (x, y, z) is document (x, -z, y).
std::string scene(bool zUpCentimetres)
{
	const double k = zUpCentimetres ? 100 : 1;
	auto n = [&](double metres)
	{
		char text[32];
		std::snprintf(text, sizeof(text), "%.9g", metres * k);
		return std::string(text);
	};
	auto v = [&](double a, double b, double c) { return n(a) + " " + n(b) + " " + n(c); };
	// A world vector in the document's axes (lengths scaled by s).
	auto w = [&](double x, double y, double z, double s)
	{
		char text[96];
		if (zUpCentimetres)
			std::snprintf(text, sizeof(text), "%.9g %.9g %.9g", x * s, -z * s, y * s);
		else
			std::snprintf(text, sizeof(text), "%.9g %.9g %.9g", x, y, z);
		return std::string(text);
	};
	std::string d = "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\">\n";
	d += zUpCentimetres ? "<asset><unit name=\"centimeter\" meter=\"0.01\"/><up_axis>Z_UP</up_axis></asset>\n"
	                    : "<asset><unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis></asset>\n";
	d += "<library_geometries><geometry id=\"ramp\"><mesh><source id=\"rampPoints\"><float_array count=\"12\">" +
	     v(-4, -0.5, -2) + " " + v(-2, 0.5, -2) + " " + v(-2, 0.5, 2) + " " + v(-4, -0.5, 2) +
	     "</float_array></source><vertices id=\"rampVertices\"><input semantic=\"POSITION\" source=\"#rampPoints\"/>"
	     "</vertices><polylist count=\"1\"><input semantic=\"VERTEX\" source=\"#rampVertices\" offset=\"0\"/>"
	     "<vcount>4</vcount><p>0 1 2 3</p></polylist></mesh></geometry></library_geometries>\n";
	d += "<library_physics_models><physics_model id=\"model\">\n"
	     "<rigid_body sid=\"ground\"><technique_common><dynamic>false</dynamic>"
	     "<shape><plane><equation>0 1 0 " +
	     n(0.5) +
	     "</equation></plane></shape></technique_common></rigid_body>\n"
	     "<rigid_body sid=\"ramp\"><technique_common><dynamic>false</dynamic>"
	     "<shape><instance_geometry url=\"#ramp\"/></shape></technique_common></rigid_body>\n"
	     "<rigid_body sid=\"box\"><technique_common><dynamic>true</dynamic><mass>2</mass>"
	     "<inertia>" +
	     v(0.125 * k, 0.25 * k, 0.375 * k) +
	     "</inertia>"
	     "<shape><box><half_extents>" +
	     v(0.5, 0.25, 0.75) +
	     "</half_extents></box></shape></technique_common></rigid_body>\n"
	     "<rigid_body sid=\"dumbbell\"><technique_common><dynamic>true</dynamic><mass>3</mass>"
	     "<shape><translate>" +
	     v(-0.4, 0, 0) + "</translate><sphere><radius>" + n(0.2) +
	     "</radius></sphere></shape>"
	     "<shape><translate>" +
	     v(0.4, 0, 0) + "</translate><capsule><height>" + n(0.3) + "</height><radius>" + n(0.1) + " " + n(0.1) +
	     "</radius></capsule></shape></technique_common></rigid_body>\n"
	     "<rigid_constraint sid=\"joint\"><ref_attachment rigid_body=\"box\"><translate>" +
	     v(0.5, 0, 0) + "</translate></ref_attachment><attachment rigid_body=\"dumbbell\"><translate>" +
	     v(-0.3, 0.1, 0) +
	     "</translate><rotate>0 0 1 20</rotate></attachment><technique_common><limits><swing_cone_and_twist>"
	     "<min>-15 -10 0</min><max>15 10 0</max></swing_cone_and_twist><linear><min>" +
	     v(-0.2, 0, 0) + "</min><max>" + v(0.2, 0, 0) +
	     "</max></linear></limits></technique_common></rigid_constraint>\n"
	     "</physics_model></library_physics_models>\n";
	d += "<library_physics_scenes><physics_scene id=\"scene\"><instance_physics_model url=\"#model\">"
	     "<instance_rigid_body body=\"ground\" target=\"#groundNode\"/>"
	     "<instance_rigid_body body=\"ramp\" target=\"#rampNode\"/>"
	     "<instance_rigid_body body=\"box\" target=\"#boxNode\"><technique_common><velocity>" +
	     w(1, 0, -0.5, 100) + "</velocity><angular_velocity>" + w(0, 90, 30, 1) +
	     "</angular_velocity></technique_common></instance_rigid_body>"
	     "<instance_rigid_body body=\"dumbbell\" target=\"#dumbbellNode\"/>"
	     "<instance_rigid_constraint constraint=\"joint\"/></instance_physics_model>"
	     "<technique_common><gravity>" +
	     w(0, -9.81, 0, 100) +
	     "</gravity><time_step>0.01</time_step></technique_common>"
	     "</physics_scene></library_physics_scenes>\n";
	d += "<library_visual_scenes><visual_scene id=\"visual\">";
	d += zUpCentimetres ? "<node id=\"root\"><rotate>1 0 0 90</rotate>" : "<node id=\"root\">";
	d += "<node id=\"groundNode\"/><node id=\"rampNode\"/>"
	     "<node id=\"boxNode\"><translate>" +
	     v(0, 1, 0) +
	     "</translate><rotate>1 2 3 40</rotate></node>"
	     "<node id=\"dumbbellNode\"><translate>" +
	     v(1, 1.2, 0) + "</translate><rotate>0 1 0 30</rotate></node>";
	d += "</node></visual_scene></library_visual_scenes>\n"
	     "<scene><instance_physics_scene url=\"#scene\"/></scene>\n</COLLADA>\n";
	return d;
}

void expectNear(const btVector3& a, const btVector3& b, double tolerance, const char* what, std::size_t body)
{
	for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tolerance) << what << " of body " << body << ", axis " << i;
}

struct Triangles : btTriangleCallback
{
	std::vector<btVector3> corners;
	void processTriangle(btVector3* triangle, int, int) override
	{
		for (int i = 0; i < 3; ++i) corners.push_back(triangle[i]);
	}
};

Triangles trianglesOf(const ColladaPhysicsScene& scene, std::size_t body)
{
	Triangles triangles;
	const btConcaveShape* shape = static_cast<const btConcaveShape*>(scene.bodies[body]->getCollisionShape());
	shape->processAllTriangles(&triangles, btVector3(-1e6, -1e6, -1e6), btVector3(1e6, 1e6, 1e6));
	return triangles;
}
}  // namespace

// Both documents describe one world: after the import the poses, sizes (as bounding boxes), masses,
// inertias, velocities, joint frames and limits and the gravity agree. The centimetre document's numbers are
// 100 times the metre document's, and 0.01 is not a binary fraction, so they agree within float rounding
// of lengths of a few metres (1e-5 m; 1e-5 of the values in general).
TEST(ColladaUnits, ZUpCentimetreSceneImportsAsTheYUpMetreScene)
{
	ColladaPhysicsScene metres, centimetres;
	ASSERT_TRUE(import(scene(false), metres)) << metres.error;
	ASSERT_TRUE(import(scene(true), centimetres)) << centimetres.error;
	ASSERT_EQ(metres.bodies.size(), 4u);
	ASSERT_EQ(centimetres.bodies.size(), 4u);
	const double tolerance = 1e-5;
	expectNear(metres.gravity, centimetres.gravity, tolerance, "gravity", 0);
	EXPECT_EQ(metres.gravity, btVector3(0, btScalar(-9.81), 0)) << "Y_UP in metres is taken as it stands";
	for (std::size_t i = 0; i < 4; ++i)
	{
		const btRigidBody& a = *metres.bodies[i];
		const btRigidBody& b = *centimetres.bodies[i];
		expectNear(a.getWorldTransform().getOrigin(), b.getWorldTransform().getOrigin(), tolerance, "origin", i);
		for (int r = 0; r < 3; ++r)
			expectNear(a.getWorldTransform().getBasis()[r], b.getWorldTransform().getBasis()[r], tolerance, "basis", i);
		if (a.getCollisionShape()->getShapeType() != STATIC_PLANE_PROXYTYPE)
		{
			btVector3 minA, maxA, minB, maxB;
			a.getAabb(minA, maxA);
			b.getAabb(minB, maxB);
			expectNear(minA, minB, tolerance, "bounding box minimum", i);
			expectNear(maxA, maxB, tolerance, "bounding box maximum", i);
		}
		EXPECT_EQ(a.getInvMass(), b.getInvMass()) << "masses are not lengths: body " << i;
		expectNear(a.getInvInertiaDiagLocal(), b.getInvInertiaDiagLocal(),
		           tolerance * a.getInvInertiaDiagLocal().length(), "inverse inertia", i);
		expectNear(a.getLinearVelocity(), b.getLinearVelocity(), tolerance, "velocity", i);
		expectNear(a.getAngularVelocity(), b.getAngularVelocity(), tolerance, "angular velocity", i);
	}
	// The plane: 0.5 m below the origin in both.
	const auto* plane = static_cast<const btStaticPlaneShape*>(centimetres.bodies[0]->getCollisionShape());
	EXPECT_NEAR(plane->getPlaneConstant(), -0.5, tolerance);
	const auto* ja = static_cast<const btGeneric6DofConstraint*>(metres.constraints.at(0).get());
	const auto* jb = static_cast<const btGeneric6DofConstraint*>(centimetres.constraints.at(0).get());
	expectNear(ja->getFrameOffsetA().getOrigin(), jb->getFrameOffsetA().getOrigin(), tolerance, "joint frame A", 0);
	expectNear(ja->getFrameOffsetB().getOrigin(), jb->getFrameOffsetB().getOrigin(), tolerance, "joint frame B", 0);
	btVector3 la, lb;
	ja->getLinearUpperLimit(la);
	jb->getLinearUpperLimit(lb);
	expectNear(la, lb, tolerance, "linear limit", 0);
	EXPECT_NEAR(lb.x(), 0.2, tolerance);
	ja->getAngularUpperLimit(la);
	jb->getAngularUpperLimit(lb);
	expectNear(la, lb, tolerance, "angular limits (not lengths, not scaled)", 0);
}

// And they simulate alike: 1 s of the box on its joint falling onto the ramp and the ground. The starting
// states differ by float rounding (1e-7 m); contacts and the joint magnify that but over 1 s stay far
// below a millimetre, while a wrong axis or scale would move the bodies by decimetres.
TEST(ColladaUnits, ZUpCentimetreSceneSimulatesAsTheYUpMetreScene)
{
	ColladaPhysicsScene metres, centimetres;
	ASSERT_TRUE(import(scene(false), metres)) << metres.error;
	ASSERT_TRUE(import(scene(true), centimetres)) << centimetres.error;
	EmptyWorld a, b;
	metres.addTo(a.world);
	centimetres.addTo(b.world);
	const btVector3 start = metres.bodies[2]->getWorldTransform().getOrigin();
	for (int i = 0; i < 60; ++i)
	{
		a.world.stepSimulation(btScalar(1) / 60, 0);
		b.world.stepSimulation(btScalar(1) / 60, 0);
	}
	EXPECT_GT((metres.bodies[2]->getWorldTransform().getOrigin() - start).length(), 0.3) << "the box moved";
	for (std::size_t i = 2; i < 4; ++i)
		expectNear(metres.bodies[i]->getWorldTransform().getOrigin(),
		           centimetres.bodies[i]->getWorldTransform().getOrigin(), 1e-3, "origin after 1 s", i);
	metres.removeFrom(a.world);
	centimetres.removeFrom(b.world);
}

TEST(ColladaUnits, XUpTurnsTheDocumentsXToTheWorldsY)
{
	std::string text = replaced(scene(false), "<up_axis>Y_UP</up_axis>", "<up_axis> X_UP\n</up_axis>");
	text = replaced(text, "<gravity>0 -9.81 0</gravity>", "<gravity>-9.81 0 0</gravity>");
	ColladaPhysicsScene scene;
	ASSERT_TRUE(import(text, scene)) << scene.error;
	EXPECT_NEAR(scene.gravity.y(), -9.81, 1e-6);
	EXPECT_NEAR(scene.gravity.x(), 0, 1e-6);
	// The box's node is 1 up the document's y, which X_UP turns to the world's -x.
	EXPECT_NEAR(scene.bodies[2]->getWorldTransform().getOrigin().x(), -1, 1e-6);
}

TEST(ColladaUnits, BadUnitOrUpAxisFailsWithTheLine)
{
	const std::string good = scene(false);
	const struct
	{
		std::string from, to, expected;
	} cases[] = {
	    {"meter=\"1\"", "meter=\"0\"", "line 3: <unit>'s meter must be a number from 1e-6 to 1e6"},
	    {"meter=\"1\"", "meter=\"-0.01\"", "meter must be"},
	    {"meter=\"1\"", "meter=\"1e9\"", "meter must be"},
	    {"meter=\"1\"", "meter=\"nan\"", "meter must be"},
	    {"meter=\"1\"", "meter=\"0.01cm\"", "meter must be"},
	    {"meter=\"1\"", "meter=\"\"", "meter must be"},
	    {"<up_axis>Y_UP</up_axis>", "<up_axis>W_UP</up_axis>", "line 3: <up_axis> must be X_UP, Y_UP or Z_UP"},
	    {"<up_axis>Y_UP</up_axis>", "<up_axis/>", "must be X_UP"},
	    {"<up_axis>Y_UP</up_axis>", "<up_axis>y_up</up_axis>", "must be X_UP"},
	};
	for (const auto& c : cases)
	{
		ColladaPhysicsScene scene;
		EXPECT_FALSE(import(replaced(good, c.from, c.to), scene)) << c.to;
		EXPECT_NE(scene.error.find(c.expected), std::string::npos) << c.to << ": " << scene.error;
		EXPECT_TRUE(scene.bodies.empty());
	}
	// No <asset>, or one without unit and up axis: COLLADA's defaults, metres and Y_UP.
	ColladaPhysicsScene bare, empty;
	EXPECT_TRUE(import(replaced(good, "<unit name=\"meter\" meter=\"1\"/><up_axis>Y_UP</up_axis>", ""), empty));
	const std::size_t from = good.find("<asset>"), to = good.find("</asset>") + 8;
	EXPECT_TRUE(import(std::string(good).erase(from, to - from), bare)) << bare.error;
	EXPECT_EQ(bare.bodies[2]->getWorldTransform().getOrigin(), btVector3(0, 1, 0));
}

// A quad as a polylist is the two triangles of its fan; with a NORMAL input the VERTEX index is found at its
// offset; polygons give the same triangles.
TEST(ColladaMeshes, PolylistAndPolygonsAreTriangulatedAsFans)
{
	const std::string good = scene(false);
	const std::string quadAsTriangles =
	    replaced(good,
	             "<polylist count=\"1\"><input semantic=\"VERTEX\" source=\"#rampVertices\" "
	             "offset=\"0\"/><vcount>4</vcount><p>0 1 2 3</p></polylist>",
	             "<triangles count=\"2\"><input semantic=\"VERTEX\" source=\"#rampVertices\" offset=\"0\"/><p>0 1 2 0 "
	             "2 3</p></triangles>");
	const std::string withNormals = replaced(
	    good, "<input semantic=\"VERTEX\" source=\"#rampVertices\" offset=\"0\"/><vcount>4</vcount><p>0 1 2 3</p>",
	    "<input semantic=\"NORMAL\" source=\"#normals\" offset=\"0\"/><input semantic=\"VERTEX\" "
	    "source=\"#rampVertices\" offset=\"1\"/><vcount>4</vcount><p>9 0 9 1 9 2 9 3</p>");
	const std::string asPolygons = replaced(good,
	                                        "<polylist count=\"1\"><input semantic=\"VERTEX\" source=\"#rampVertices\" "
	                                        "offset=\"0\"/><vcount>4</vcount><p>0 1 2 3</p></polylist>",
	                                        "<polygons count=\"1\"><input semantic=\"VERTEX\" source=\"#rampVertices\" "
	                                        "offset=\"0\"/><p>0 1 2 3</p></polygons>");
	ColladaPhysicsScene expected;
	ASSERT_TRUE(import(quadAsTriangles, expected)) << expected.error;
	const std::vector<btVector3> triangles = trianglesOf(expected, 1).corners;
	ASSERT_EQ(triangles.size(), 6u);
	for (const std::string& text : {good, withNormals, asPolygons})
	{
		ColladaPhysicsScene scene;
		ASSERT_TRUE(import(text, scene)) << scene.error;
		EXPECT_EQ(trianglesOf(scene, 1).corners, triangles);
	}
	// A triangle, a quad and a pentagon in one polylist: 1 + 2 + 3 triangles.
	std::string mixed =
	    replaced(good, "<float_array count=\"12\">", "<float_array count=\"24\">0 0 0 1 0 0 1 0 1 0 0 1 ");
	mixed = replaced(mixed, "<vcount>4</vcount><p>0 1 2 3</p>", "<vcount>3 4 5</vcount><p>0 1 2 0 1 2 3 4 5 6 7 0</p>");
	mixed = replaced(mixed, "<polylist count=\"1\">", "<polylist count=\"3\">");
	ColladaPhysicsScene scene;
	ASSERT_TRUE(import(mixed, scene)) << scene.error;
	EXPECT_EQ(trianglesOf(scene, 1).corners.size(), 18u);
}

TEST(ColladaMeshes, PolylistAndPolygonsWithBadCountsFail)
{
	const std::string good = scene(false);
	const std::string polygons = replaced(good,
	                                      "<polylist count=\"1\"><input semantic=\"VERTEX\" source=\"#rampVertices\" "
	                                      "offset=\"0\"/><vcount>4</vcount><p>0 1 2 3</p></polylist>",
	                                      "<polygons count=\"1\"><input semantic=\"VERTEX\" source=\"#rampVertices\" "
	                                      "offset=\"0\"/><p>0 1 2 3</p></polygons>");
	const struct
	{
		std::string document, expected;
	} cases[] = {
	    {replaced(good, "<vcount>4</vcount>", "<vcount>5</vcount>"), "count does not match its indices"},
	    {replaced(good, "<vcount>4</vcount>", "<vcount>3</vcount>"), "count does not match its indices"},
	    {replaced(good, "<vcount>4</vcount>", "<vcount>2 2</vcount>"), "does not match its <vcount>'s 2 numbers"},
	    {replaced(replaced(good, "count=\"1\"><input semantic=\"VERTEX\"", "count=\"2\"><input semantic=\"VERTEX\""),
	              "<vcount>4</vcount>", "<vcount>2 2</vcount>"),
	     "at least 3 corners"},
	    {replaced(good, "<vcount>4</vcount>", "<vcount>4.5</vcount>"), "whole numbers"},
	    {replaced(good, "<vcount>4</vcount>", "<vcount>-4</vcount>"), "whole numbers"},
	    {replaced(good, "<vcount>4</vcount>", "<vcount>1e12</vcount>"), "whole numbers"},
	    {replaced(good, "<vcount>4</vcount>", "<vcount>four</vcount>"), "not a number"},
	    {replaced(good, "<vcount>4</vcount>", ""), "<polylist> has no <vcount>"},
	    {replaced(good, "<p>0 1 2 3</p>", "<p>0 1 2 4</p>"), "polygon 0 has an index out of range"},
	    {replaced(good, "<p>0 1 2 3</p>", "<p>0 1 2 -1</p>"), "index out of range"},
	    {replaced(good, "<p>0 1 2 3</p>", ""), "<polylist> has no <p>"},
	    {replaced(good, "<polylist count=\"1\">", "<polylist>"), "needs a positive count"},
	    {replaced(replaced(good, "<polylist count=\"1\">", "<triangles count=\"2147483647\">"), "</polylist>",
	              "</triangles>"),
	     "count does not match its indices"},
	    {replaced(good, "offset=\"0\"/><vcount>", "offset=\"-1\"/><vcount>"), "offset must be from 0 to 63"},
	    {replaced(good, "offset=\"0\"/><vcount>", "offset=\"1000000\"/><vcount>"), "offset must be from 0 to 63"},
	    {replaced(good, "<polylist count=\"1\">", "<lines count=\"1\">"), "malformed XML"},
	    {replaced(replaced(good, "<polylist count=\"1\">", "<lines count=\"1\">"), "</polylist>", "</lines>"),
	     "<lines> meshes are not read"},
	    {replaced(replaced(good, "<polylist count=\"1\">", "<other>"), "</polylist>", "</other>"),
	     "has no <triangles>, <polylist> or <polygons>"},
	    {replaced(polygons, "<polygons count=\"1\">", "<polygons count=\"2\">"), "count does not match its <p>"},
	    {replaced(polygons, "<p>0 1 2 3</p>", "<p>0 1</p>"), "at least 3 corners"},
	    {replaced(polygons, "<p>0 1 2 3</p>", "<p>0 1 2 7</p>"), "index out of range"},
	    {replaced(polygons, "<p>0 1 2 3</p>", "<ph><p>0 1 2 3</p><h>0 1 2</h></ph>"), "holes"},
	};
	for (const auto& c : cases)
	{
		ColladaPhysicsScene scene;
		EXPECT_FALSE(import(c.document, scene)) << c.expected;
		EXPECT_NE(scene.error.find(c.expected), std::string::npos) << c.expected << ": " << scene.error;
		EXPECT_TRUE(scene.bodies.empty() && scene.meshes.empty() && scene.shapes.empty());
	}
}

// Cut and randomly edited Z_UP centimetre documents with a polylist (fixed seed) import or fail, never crash
// (the sanitizer build checks for undefined behaviour on the way).
TEST(ColladaUnits, TruncatedOrEditedDocumentsNeverCrash)
{
	collada_test::expectCutOrEditedDocumentsNeverCrash(scene(true), 7, 300, 22);
}
