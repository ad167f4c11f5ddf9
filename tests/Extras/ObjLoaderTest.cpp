// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The OBJ loader: what it reads, what it refuses (with line numbers), and the shapes it builds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "BulletCollision/CollisionDispatch/btCollisionWorld.h"
#include "ObjLoader/MeshShapes.h"
#include "ObjLoader/ObjLoader.h"
#include "btBulletDynamicsCommon.h"

using caliber::ObjMesh;
using caliber::ObjModel;

namespace
{
const char* const kCube =
    "# unit cube, quads\n"
    "o cube\n"
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2 3 7 6\nf 4 1 5 8\n";

ObjModel load(const std::string& text)
{
	ObjModel model;
	caliber::loadObjFromMemory(text.data(), text.size(), model);
	return model;
}

// Every index of every mesh names one of its vertices and every vertex is finite: what "never silent
// garbage" means for a model that loaded.
void expectConsistent(const ObjModel& model)
{
	for (const ObjMesh& mesh : model.meshes)
	{
		ASSERT_EQ(mesh.indices.size() % 3, 0);
		for (int i = 0; i < mesh.indices.size(); ++i)
		{
			ASSERT_GE(mesh.indices[i], 0);
			ASSERT_LT(mesh.indices[i], mesh.vertices.size());
		}
		for (int v = 0; v < mesh.vertices.size(); ++v)
			for (int axis = 0; axis < 3; ++axis) ASSERT_TRUE(std::isfinite(mesh.vertices[v][axis]));
	}
}

double signedAreaXY(const ObjMesh& mesh, int triangle)
{
	const btVector3& a = mesh.vertices[mesh.indices[3 * triangle]];
	const btVector3& b = mesh.vertices[mesh.indices[3 * triangle + 1]];
	const btVector3& c = mesh.vertices[mesh.indices[3 * triangle + 2]];
	return 0.5 * ((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}
}  // namespace

TEST(ObjLoader, CubeOfQuadsGivesTwelveTrianglesOverEightVertices)
{
	const ObjModel model = load(kCube);
	ASSERT_TRUE(model.ok()) << model.describeErrors();
	ASSERT_EQ(model.meshes.size(), 1u);
	EXPECT_EQ(model.meshes[0].name, "cube");
	EXPECT_EQ(model.meshes[0].vertices.size(), 8);
	EXPECT_EQ(model.meshes[0].numTriangles(), 12);
	EXPECT_TRUE(model.warnings.empty());
	expectConsistent(model);
}

// A 10-pointed star started at an inner (reflex) corner: a fan from the first corner would cover area
// outside the outline. Ear clipping must give 8 triangles, all wound like the polygon (counter-clockwise
// in the xy plane), whose areas add up to the star's: 10 triangles (centre, outer, inner) of
// 0.5 * 1 * 0.4 * sin(36 deg) each.
TEST(ObjLoader, ConcavePolygonIsTriangulatedInsideItsOutline)
{
	std::string text;
	const double pi = 3.14159265358979323846;
	for (int i = 0; i < 10; ++i)
	{
		const double radius = (i % 2 == 0) ? 0.4 : 1.0;
		const double angle = i * pi / 5;
		text +=
		    "v " + std::to_string(radius * std::cos(angle)) + " " + std::to_string(radius * std::sin(angle)) + " 0\n";
	}
	text += "f 1 2 3 4 5 6 7 8 9 10\n";
	const ObjModel model = load(text);
	ASSERT_TRUE(model.ok()) << model.describeErrors();
	const ObjMesh& mesh = model.meshes[0];
	ASSERT_EQ(mesh.numTriangles(), 8);
	double total = 0;
	for (int t = 0; t < mesh.numTriangles(); ++t)
	{
		EXPECT_GT(signedAreaXY(mesh, t), 0) << "triangle " << t << " is wound against the polygon";
		total += signedAreaXY(mesh, t);
	}
	EXPECT_NEAR(total, 10 * 0.5 * 0.4 * std::sin(pi / 5), 1e-5);  // 1e-6 per printed coordinate
}

TEST(ObjLoader, GroupsBecomeSeparateMeshesAndARepeatedGroupNameAppends)
{
	const ObjModel model = load(
	    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\n"
	    "g left\nf 1 2 3\n"
	    "g right side\nf 4 5 6\n"
	    "g empty\n"
	    "g left\nf 3 2 1\n");
	ASSERT_TRUE(model.ok()) << model.describeErrors();
	ASSERT_EQ(model.meshes.size(), 2u);
	EXPECT_EQ(model.meshes[0].name, "left");
	EXPECT_EQ(model.meshes[0].numTriangles(), 2);
	EXPECT_EQ(model.meshes[0].vertices.size(), 3);  // only the vertices its faces use
	EXPECT_EQ(model.meshes[1].name, "right side");
	EXPECT_EQ(model.meshes[1].vertices.size(), 3);
	EXPECT_FLOAT_EQ(model.meshes[1].vertices[0].x(), 5);
}

TEST(ObjLoader, NegativeIndicesAndSlashFormsNameTheRightVertices)
{
	const ObjModel model = load(
	    "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n"
	    "f -3/1/1 -2//1 3/1\r\n"
	    "usemtl steel\ns off\nl 1 2\n");
	ASSERT_TRUE(model.ok()) << model.describeErrors();
	const ObjMesh& mesh = model.meshes[0];
	ASSERT_EQ(mesh.numTriangles(), 1);
	EXPECT_FLOAT_EQ(mesh.vertices[mesh.indices[0]].x(), 0);
	EXPECT_FLOAT_EQ(mesh.vertices[mesh.indices[1]].x(), 1);
	EXPECT_FLOAT_EQ(mesh.vertices[mesh.indices[2]].y(), 1);
	EXPECT_TRUE(model.warnings.empty());
}

TEST(ObjLoader, MalformedLinesAreReportedWithTheirLineNumbers)
{
	const ObjModel model = load(
	    "v 0 0 0\n"
	    "v 1 0 0\n"
	    "v 0 abc 0\n"     // line 3: not a number
	    "v 0 1\n"         // line 4: too few coordinates
	    "f 1 2\n"         // line 5: too few corners
	    "f 1 x 2\n"       // line 6: not an index
	    "f 1/a 2 1\n"     // line 7: malformed texture index
	    "\x01\x02 1 2\n"  // line 8: not a statement
	    "v 0 1 0\nf 1 2 3\n");
	EXPECT_FALSE(model.ok());
	EXPECT_TRUE(model.meshes.empty()) << "a failed load must not hand out a partial model";
	ASSERT_EQ(model.errors.size(), 6u) << model.describeErrors();
	const int expectedLines[] = {3, 4, 5, 6, 7, 8};
	for (int i = 0; i < 6; ++i) EXPECT_EQ(model.errors[i].line, expectedLines[i]) << model.errors[i].text;
	EXPECT_NE(model.describeErrors().find("line 3: vertex coordinate 'abc' is not a number"), std::string::npos)
	    << model.describeErrors();
	EXPECT_NE(model.errors[5].text.find("\\x01\\x02"), std::string::npos) << model.errors[5].text;
}

TEST(ObjLoader, HugeAndNonFiniteNumbersAreRejected)
{
	const char* const bad[] = {"1e999", "-1e999", "1e20", "nan", "NaN", "inf", "-inf", "1e400", "0x10", "1..2", "--1"};
	for (const char* number : bad)
	{
		const ObjModel model = load(std::string("v 0 0 0\nv 1 0 0\nv ") + number + " 1 0\nf 1 2 3\n");
		EXPECT_FALSE(model.ok()) << number;
		ASSERT_GE(model.errors.size(), 1u) << number;  // the face on line 4 then names a missing vertex
		EXPECT_EQ(model.errors[0].line, 3) << number;
	}
	// The largest accepted magnitude, and small or signed forms, load.
	const ObjModel fine = load("v 0 0 0\nv 1e15 0 0\nv +1 -1e-300 0\nf 1 2 3\n");
	EXPECT_TRUE(fine.ok()) << fine.describeErrors();
}

TEST(ObjLoader, IndicesOutOfRangeOrForwardAreErrors)
{
	const char* const faces[] = {"f 0 1 2", "f 1 2 4", "f -4 1 2", "f 1 2 99999999999999999999", "f 1 2 -0"};
	for (const char* face : faces)
	{
		const ObjModel model = load(std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n") + face + "\nv 1 1 1\n");
		EXPECT_FALSE(model.ok()) << face;
		ASSERT_EQ(model.errors.size(), 1u) << face;
		EXPECT_EQ(model.errors[0].line, 4) << face;
	}
}

TEST(ObjLoader, InputWithoutFacesFailsWithOneErrorForTheWholeInput)
{
	const char* const inputs[] = {"", "\n\n", "# only a comment\n", "v 0 0 0\nv 1 0 0\nv 0 1 0\n", "f 1 1 1\n"};
	for (const char* input : inputs)
	{
		const ObjModel model = load(input);
		EXPECT_FALSE(model.ok()) << "'" << input << "'";
		EXPECT_TRUE(model.meshes.empty());
	}
	const ObjModel empty = load("");
	ASSERT_EQ(empty.errors.size(), 1u);
	EXPECT_EQ(empty.errors[0].line, 0);
}

TEST(ObjLoader, RepeatedVertexInAFaceDropsItsDegenerateTrianglesWithAWarning)
{
	const ObjModel model = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 2\nf 1 2 4 3\n");
	ASSERT_TRUE(model.ok()) << model.describeErrors();
	EXPECT_EQ(model.numTriangles(), 2);
	ASSERT_EQ(model.warnings.size(), 1u);
	EXPECT_EQ(model.warnings[0].line, 5);
}

TEST(ObjLoader, UnknownStatementIsAWarningWithItsLine)
{
	const ObjModel model = load("v 0 0 0\ncstype bspline\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
	ASSERT_TRUE(model.ok()) << model.describeErrors();
	ASSERT_EQ(model.warnings.size(), 1u);
	EXPECT_EQ(model.warnings[0].line, 2);
}

TEST(ObjLoader, ErrorsAreCappedAndParsingStops)
{
	std::string text;
	for (int i = 0; i < 1000; ++i) text += "v x y z\n";
	const ObjModel model = load(text);
	EXPECT_EQ(int(model.errors.size()), caliber::kObjMaxErrors + 1);
	EXPECT_NE(model.errors.back().text.find("too many errors"), std::string::npos);
}

// Every prefix of a valid file (a file cut short anywhere) either loads a consistent model or fails
// with errors; never a crash, never an index out of range.
TEST(ObjLoader, EveryTruncationOfAValidFileLoadsConsistentlyOrFails)
{
	const std::string cube = kCube;
	for (std::size_t length = 0; length <= cube.size(); ++length)
	{
		const ObjModel model = load(cube.substr(0, length));
		if (model.ok())
			expectConsistent(model);
		else
			EXPECT_TRUE(model.meshes.empty());
	}
	// Cut in the middle of the last face: that line is the one reported.
	const std::string cut = cube.substr(0, cube.size() - 5);  // "f 4 1 5 8\n" -> "f 4 1"
	const ObjModel model = load(cut);
	ASSERT_FALSE(model.ok());
	EXPECT_EQ(model.errors[0].line, 16);
}

// Random byte edits of a valid file (fixed seed) never crash and never give an inconsistent model.
TEST(ObjLoader, RandomByteEditsNeverCrashOrGiveInconsistentModels)
{
	std::mt19937 random(22);
	const std::string cube = kCube;
	int failed = 0;
	for (int trial = 0; trial < 2000; ++trial)
	{
		std::string text = cube;
		const int edits = 1 + int(random() % 4);
		for (int e = 0; e < edits; ++e) text[random() % text.size()] = char(random() % 256);
		const ObjModel model = load(text);
		if (model.ok())
			expectConsistent(model);
		else
			++failed;
	}
	EXPECT_GT(failed, 0);  // the edits do break some files, so both paths were exercised
}

TEST(ObjLoader, FileLoadReadsTheFileAndAMissingFileIsAnError)
{
	const std::string path = ::testing::TempDir() + "caliber_obj_loader_test.obj";
	std::FILE* file = std::fopen(path.c_str(), "wb");
	ASSERT_NE(file, nullptr);
	std::fputs(kCube, file);
	std::fclose(file);
	ObjModel model;
	EXPECT_TRUE(caliber::loadObjFile(path.c_str(), model)) << model.describeErrors();
	EXPECT_EQ(model.numTriangles(), 12);
	std::remove(path.c_str());
	EXPECT_FALSE(caliber::loadObjFile(path.c_str(), model));
	ASSERT_EQ(model.errors.size(), 1u);
	EXPECT_EQ(model.errors[0].line, 0);
	EXPECT_TRUE(model.meshes.empty());
}

#if CALIBER_ASSERTS_ENABLED
TEST(ObjLoaderDeathTest, NullTextWithASizeOrANullPathAsserts)
{
	ObjModel model;
	EXPECT_DEATH(caliber::loadObjFromMemory(nullptr, 5, model), "assertion failed");
	EXPECT_DEATH(caliber::loadObjFile(nullptr, model), "assertion failed");
}
#else
TEST(ObjLoader, NullTextWithASizeOrANullPathFailsWithAnError)
{
	ObjModel model;
	EXPECT_FALSE(caliber::loadObjFromMemory(nullptr, 5, model));
	EXPECT_EQ(model.errors.size(), 1u);
	EXPECT_FALSE(caliber::loadObjFile(nullptr, model));
	EXPECT_EQ(model.errors.size(), 1u);
}
#endif

TEST(ObjLoader, NullTextOfSizeZeroIsJustEmptyInput)
{
	ObjModel model;
	EXPECT_FALSE(caliber::loadObjFromMemory(nullptr, 0, model));
	ASSERT_EQ(model.errors.size(), 1u);
	EXPECT_NE(model.errors[0].text.find("no faces"), std::string::npos);
}

// ---- shapes ---------------------------------------------------------------------------------------

TEST(ObjMeshShapes, ConvexHullOfTheCubeHasItsEightCornersAndExactExtent)
{
	const ObjModel model = load(kCube);
	std::unique_ptr<btConvexHullShape> hull = caliber::buildConvexHullShape(model.meshes[0]);
	ASSERT_NE(hull, nullptr);
	EXPECT_EQ(hull->getNumPoints(), 8);
	const btVector3 support = hull->localGetSupportingVertexWithoutMargin(btVector3(1, 2, 3));
	EXPECT_FLOAT_EQ(support.x(), 1);
	EXPECT_FLOAT_EQ(support.y(), 1);
	EXPECT_FLOAT_EQ(support.z(), 1);
}

TEST(ObjMeshShapes, FlatOrTinyMeshGivesNoConvexHull)
{
	const ObjModel quad = load("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
	ASSERT_TRUE(quad.ok());
	EXPECT_EQ(caliber::buildConvexHullShape(quad.meshes[0]), nullptr);
	const ObjModel triangle = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
	EXPECT_EQ(caliber::buildConvexHullShape(triangle.meshes[0]), nullptr);
	EXPECT_TRUE(caliber::buildConvexHullShapes(load("garbage!")).empty());
}

TEST(ObjMeshShapes, StaticMeshHasOneSubpartPerGroupAndAFailedModelGivesNone)
{
	const ObjModel model = load("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 0 0\nv 6 0 0\nv 5 1 0\ng a\nf 1 2 3\ng b\nf 4 5 6\n");
	caliber::StaticMeshShape mesh = caliber::buildStaticMeshShape(model);
	ASSERT_NE(mesh.shape, nullptr);
	EXPECT_EQ(mesh.mesh->getNumSubParts(), 2);
	btVector3 aabbMin, aabbMax;
	btTransform identity;
	identity.setIdentity();
	mesh.shape->getAabb(identity, aabbMin, aabbMax);
	EXPECT_NEAR(aabbMax.x(), 6, 0.1);  // the box covers both groups (plus the shape's margin)

	const caliber::StaticMeshShape none = caliber::buildStaticMeshShape(load("v 1 2\n"));
	EXPECT_EQ(none.shape, nullptr);
	EXPECT_EQ(none.mesh, nullptr);
}

#if CALIBER_ASSERTS_ENABLED
TEST(ObjMeshShapesDeathTest, AddingAMeshWithABadIndexAsserts)
{
	ObjMesh mesh;
	mesh.vertices.push_back(btVector3(0, 0, 0));
	mesh.indices.push_back(0);
	mesh.indices.push_back(0);
	mesh.indices.push_back(7);
	caliber::OwnedTriangleIndexVertexArray array;
	EXPECT_DEATH(array.addMesh(mesh), "assertion failed");
}
#else
TEST(ObjMeshShapes, AddingAMeshWithABadIndexIsRefused)
{
	ObjMesh mesh;
	mesh.vertices.push_back(btVector3(0, 0, 0));
	mesh.indices.push_back(0);
	mesh.indices.push_back(0);
	mesh.indices.push_back(7);
	caliber::OwnedTriangleIndexVertexArray array;
	EXPECT_FALSE(array.addMesh(mesh));
	EXPECT_EQ(array.getNumSubParts(), 0);
}
#endif

// A sphere of radius 0.5 dropped onto a ground made of an OBJ quad (two triangles after ear clipping)
// comes to rest with its centre one radius above it: the mesh collides where the file says it is. The
// tolerance (1 cm) covers the contact's allowed penetration and the shapes' margins.
TEST(ObjMeshShapes, SphereRestsOnAStaticGroundLoadedFromObj)
{
	const ObjModel model = load("v -10 0 -10\nv 10 0 -10\nv 10 0 10\nv -10 0 10\nf 1 4 3 2\n");
	caliber::StaticMeshShape ground = caliber::buildStaticMeshShape(model);
	ASSERT_NE(ground.shape, nullptr);

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	btTransform pose;
	pose.setIdentity();
	btRigidBody groundBody(0, nullptr, ground.shape.get());
	world.addRigidBody(&groundBody);
	btSphereShape sphere(0.5);
	pose.setOrigin(btVector3(1, 2, 1));
	btVector3 inertia;
	sphere.calculateLocalInertia(1, inertia);
	btRigidBody ball(1, nullptr, &sphere, inertia);
	ball.setWorldTransform(pose);
	world.addRigidBody(&ball);
	for (int i = 0; i < 240; ++i) world.stepSimulation(1.0 / 60, 0);
	EXPECT_NEAR(ball.getWorldTransform().getOrigin().y(), 0.5, 0.01);
	world.removeRigidBody(&ball);
	world.removeRigidBody(&groundBody);
}
