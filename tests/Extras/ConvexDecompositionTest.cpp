// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The convex decomposition: convex meshes stay whole, concave ones split where they bend, volumes are
// exact, bad meshes and parameters are refused.
#include <gtest/gtest.h>

#include <cmath>

#include "ConvexDecomposition/ConvexDecomposition.h"
#include "ConvexDecomposition/ExampleMeshes.h"
#include "ConvexDecomposition/TriangleSoup.h"
#include "btBulletDynamicsCommon.h"

using caliber::ConvexDecompositionParameters;
using caliber::ConvexDecompositionResult;
using caliber::ExampleMesh;

namespace
{
bool decompose(const ExampleMesh& mesh, const ConvexDecompositionParameters& parameters,
               ConvexDecompositionResult& result)
{
	return caliber::decomposeConvex(mesh.vertices.size() ? &mesh.vertices[0] : nullptr, mesh.vertices.size(),
	                                mesh.indices.size() ? &mesh.indices[0] : nullptr, mesh.indices.size(), parameters,
	                                result);
}

const double kPi = 3.14159265358979323846;
}  // namespace

// The cap construction keeps a cut piece closed: halves of a unit cube cut anywhere have the exact
// volumes of the two boxes, and cutting a half again keeps adding up.
TEST(TriangleSoup, SplitHalvesAreClosedWithExactVolumes)
{
	const ExampleMesh box = caliber::makeBoxMesh(btVector3(1, 1, 1));
	caliber::decomposition::TriangleSoup soup;
	for (int t = 0; t < box.indices.size(); t += 3)
	{
		caliber::decomposition::SoupTriangle triangle;
		triangle.cap = false;
		for (int i = 0; i < 3; ++i)
		{
			const btVector3& v = box.vertices[box.indices[t + i]];
			triangle.corner[i] = {{v.x(), v.y(), v.z()}, true};
		}
		soup.push_back(triangle);
	}
	EXPECT_NEAR(caliber::decomposition::soupVolume(soup), 8, 1e-12);
	caliber::decomposition::TriangleSoup below, above, belowBelow, belowAbove;
	caliber::decomposition::splitSoup(soup, {1, 0, 0}, 0.3, below, above);
	EXPECT_NEAR(caliber::decomposition::soupVolume(below), 1.3 * 4, 1e-12);
	EXPECT_NEAR(caliber::decomposition::soupVolume(above), 0.7 * 4, 1e-12);
	const double s = 1 / std::sqrt(3.0);  // an oblique plane through the cube's centre halves it
	caliber::decomposition::splitSoup(below, {s, s, s}, 0, belowBelow, belowAbove);
	EXPECT_NEAR(caliber::decomposition::soupVolume(belowBelow) + caliber::decomposition::soupVolume(belowAbove), 5.2,
	            1e-12);
}

TEST(ConvexDecomposition, ConvexMeshesGiveOneHullWithTheMeshsVolume)
{
	ConvexDecompositionResult result;
	ASSERT_TRUE(decompose(caliber::makeBoxMesh(btVector3(1, 2, 3)), ConvexDecompositionParameters(), result))
	    << result.error;
	ASSERT_EQ(result.hulls.size(), 1u);
	EXPECT_NEAR(result.meshVolume, 48, 1e-9);
	EXPECT_NEAR(result.hullVolume, 48, 1e-4);  // float corners
	EXPECT_EQ(result.hulls[0].vertices.size(), 8);
	EXPECT_TRUE(result.withinTolerance);

	// A faceted sphere-like solid of revolution (convex): still one hull.
	btAlignedObjectArray<btVector3> profile;
	for (int k = 0; k <= 8; ++k)
	{
		const double angle = -kPi / 2 + kPi * k / 8;
		profile.push_back(btVector3(btScalar(k == 0 || k == 8 ? 0 : std::cos(angle)), btScalar(std::sin(angle)), 0));
	}
	ASSERT_TRUE(decompose(caliber::makeRevolvedMesh(profile, 16), ConvexDecompositionParameters(), result))
	    << result.error;
	EXPECT_EQ(result.hulls.size(), 1u);
	EXPECT_LT(result.volumeError(), 1e-5);
}

// An L bracket (legs 3, width 1, depth 1: volume 5) is two boxes. Its hull has volume 7 (the triangle
// between the legs' ends adds 2), so it must split; the inner corner's coordinates are candidate planes,
// so two hulls cover it exactly.
TEST(ConvexDecomposition, LBracketSplitsIntoTwoHullsThatCoverItsVolume)
{
	ConvexDecompositionParameters parameters;
	parameters.maxHulls = 8;
	parameters.concavityTolerance = 0.01;
	ConvexDecompositionResult result;
	ASSERT_TRUE(decompose(caliber::makeLBracketMesh(3, 1, 1), parameters, result)) << result.error;
	EXPECT_NEAR(result.meshVolume, 5, 1e-9);
	EXPECT_GE(result.hulls.size(), 2u);
	EXPECT_LE(result.hulls.size(), 3u);
	EXPECT_TRUE(result.withinTolerance);
	EXPECT_LE(result.volumeError(), parameters.concavityTolerance);
	EXPECT_GE(result.volumeError(), -1e-6) << "hulls never cover less than the mesh";
	double covered = 0;
	for (const auto& hull : result.hulls)
	{
		EXPECT_GE(hull.volume, hull.meshVolume - 1e-6);
		covered += hull.meshVolume;
		// Every hull corner lies in the bracket's bounding box.
		for (int i = 0; i < hull.vertices.size(); ++i)
		{
			EXPECT_GE(hull.vertices[i].x(), -1e-5);
			EXPECT_LE(hull.vertices[i].x(), 3 + 1e-5);
		}
	}
	EXPECT_NEAR(covered, 5, 1e-6) << "the pieces partition the mesh";

	// With one hull allowed, the result is the plain hull and says it is not within tolerance.
	parameters.maxHulls = 1;
	ASSERT_TRUE(decompose(caliber::makeLBracketMesh(3, 1, 1), parameters, result));
	ASSERT_EQ(result.hulls.size(), 1u);
	EXPECT_NEAR(result.hullVolume, 7, 1e-4);
	EXPECT_FALSE(result.withinTolerance);
}

// A torus cannot be covered by one hull (which fills the hole); within 16 hulls the error drops below the
// tolerance or the hull budget is used up.
TEST(ConvexDecomposition, TorusNeedsManyHullsAndTheErrorFalls)
{
	const ExampleMesh torus = caliber::makeTorusMesh(1, btScalar(0.3), 12, 6);
	ConvexDecompositionParameters parameters;
	parameters.maxHulls = 1;
	ConvexDecompositionResult one;
	ASSERT_TRUE(decompose(torus, parameters, one)) << one.error;
	parameters.maxHulls = 16;
	parameters.concavityTolerance = 0.1;
	parameters.planesPerAxis = 8;  // enough for a ring, and quick in the sanitizer build
	ConvexDecompositionResult many;
	ASSERT_TRUE(decompose(torus, parameters, many)) << many.error;
	EXPECT_GE(many.hulls.size(), 4u);
	EXPECT_LT(many.volumeError(), one.volumeError() / 4);
	EXPECT_TRUE(many.withinTolerance || many.hulls.size() == 16u);
	// The faceted torus is its hexagon profile (area 3 r^2 sin 60 deg, centroid at radius R) swept through
	// 12 wedges of planar trapezoids: each wedge holds A * R * sin(2 pi / 12), so the volume is 12 times that.
	const double faceted = 3 * 0.09 * std::sin(kPi / 3) * 1 * 12 * std::sin(2 * kPi / 12);
	EXPECT_NEAR(many.meshVolume, faceted, 1e-4 * faceted);
}

TEST(ConvexDecomposition, InwardWoundMeshIsTurnedWithAWarning)
{
	ExampleMesh box = caliber::makeBoxMesh(btVector3(1, 1, 1));
	for (int t = 0; t < box.indices.size(); t += 3) box.indices.swap(t + 1, t + 2);
	ConvexDecompositionResult result;
	ASSERT_TRUE(decompose(box, ConvexDecompositionParameters(), result)) << result.error;
	EXPECT_NEAR(result.meshVolume, 8, 1e-9);
	ASSERT_EQ(result.warnings.size(), 1u);
	EXPECT_NE(result.warnings[0].find("inwards"), std::string::npos);
}

TEST(ConvexDecomposition, OpenEmptyFlatOrBrokenMeshesAreRefusedWithAReason)
{
	const ConvexDecompositionParameters parameters;
	ConvexDecompositionResult result;

	ExampleMesh open = caliber::makeBoxMesh(btVector3(1, 1, 1));
	open.indices.resize(open.indices.size() - 3);  // one triangle missing
	EXPECT_FALSE(decompose(open, parameters, result));
	EXPECT_NE(result.error.find("not closed"), std::string::npos) << result.error;
	EXPECT_TRUE(result.hulls.empty());

	ExampleMesh doubled = caliber::makeBoxMesh(btVector3(1, 1, 1));
	for (int i = 0; i < 3; ++i) doubled.indices.push_back(doubled.indices[i]);  // a triangle twice
	EXPECT_FALSE(decompose(doubled, parameters, result));
	EXPECT_NE(result.error.find("not closed"), std::string::npos) << result.error;

	EXPECT_FALSE(decompose(ExampleMesh(), parameters, result));
	EXPECT_NE(result.error.find("at least 4 triangles"), std::string::npos) << result.error;

	ExampleMesh flat = caliber::makeBoxMesh(btVector3(1, 1, 0));  // both z faces at z = 0
	EXPECT_FALSE(decompose(flat, parameters, result));
	EXPECT_FALSE(result.error.empty());

	ExampleMesh outOfRange = caliber::makeBoxMesh(btVector3(1, 1, 1));
	outOfRange.indices[5] = 8;
	EXPECT_FALSE(decompose(outOfRange, parameters, result));
	EXPECT_NE(result.error.find("out of range"), std::string::npos) << result.error;

	ExampleMesh notFinite = caliber::makeBoxMesh(btVector3(1, 1, 1));
	notFinite.vertices[3].setX(btScalar(NAN));
	EXPECT_FALSE(decompose(notFinite, parameters, result));
	EXPECT_NE(result.error.find("vertex 3"), std::string::npos) << result.error;

	ExampleMesh huge = caliber::makeBoxMesh(btVector3(1, 1, 1));
	huge.vertices[0].setY(btScalar(1e30));
	EXPECT_FALSE(decompose(huge, parameters, result));
}

#if CALIBER_ASSERTS_ENABLED
TEST(ConvexDecompositionDeathTest, BadParametersOrNullArraysAssert)
{
	const ExampleMesh box = caliber::makeBoxMesh(btVector3(1, 1, 1));
	ConvexDecompositionParameters none;
	none.maxHulls = 0;
	ConvexDecompositionResult result;
	EXPECT_DEATH(decompose(box, none, result), "assertion failed");
	ConvexDecompositionParameters nanTolerance;
	nanTolerance.concavityTolerance = NAN;
	EXPECT_DEATH(decompose(box, nanTolerance, result), "assertion failed");
	EXPECT_DEATH(caliber::decomposeConvex(nullptr, 8, &box.indices[0], 36, ConvexDecompositionParameters(), result),
	             "assertion failed");
}
#else
TEST(ConvexDecomposition, BadParametersOrNullArraysFailWithAReason)
{
	const ExampleMesh box = caliber::makeBoxMesh(btVector3(1, 1, 1));
	ConvexDecompositionResult result;
	for (int maxHulls : {0, -3})
	{
		ConvexDecompositionParameters parameters;
		parameters.maxHulls = maxHulls;
		EXPECT_FALSE(decompose(box, parameters, result));
		EXPECT_TRUE(result.hulls.empty());
	}
	ConvexDecompositionParameters nanTolerance;
	nanTolerance.concavityTolerance = NAN;
	EXPECT_FALSE(decompose(box, nanTolerance, result));
	ConvexDecompositionParameters tooManyPlanes;
	tooManyPlanes.planesPerAxis = 1000;
	EXPECT_FALSE(decompose(box, tooManyPlanes, result));
	EXPECT_FALSE(caliber::decomposeConvex(nullptr, 8, &box.indices[0], 36, ConvexDecompositionParameters(), result));
	EXPECT_FALSE(result.error.empty());
}
#endif

// The compound of an L bracket's hulls, dropped flat on the ground, comes to rest with its lowest face on
// the ground (the hulls are shrunk by their margin, so hull plus margin is the bracket): its centre of mass
// then sits half the depth (0.25) above the ground, within the contact's allowed penetration (1 cm).
TEST(ConvexDecomposition, CompoundOfTheHullsRestsOnItsFace)
{
	ConvexDecompositionParameters parameters;
	parameters.concavityTolerance = 0.01;
	ConvexDecompositionResult result;
	ASSERT_TRUE(decompose(caliber::makeLBracketMesh(3, 1, btScalar(0.5)), parameters, result));
	caliber::DecompositionShape shape = caliber::buildDecompositionShape(result);
	ASSERT_NE(shape.compound, nullptr);
	EXPECT_EQ(shape.compound->getNumChildShapes(), int(result.hulls.size()));

	// Centre the compound on its centre of mass, as a dynamic body needs.
	btAlignedObjectArray<btScalar> masses;
	for (const auto& hull : result.hulls) masses.push_back(btScalar(hull.meshVolume / result.meshVolume));
	btTransform principal;
	btVector3 inertia;
	shape.compound->calculatePrincipalAxisTransform(&masses[0], principal, inertia);
	btCompoundShape centred;
	for (int i = 0; i < shape.compound->getNumChildShapes(); ++i)
		centred.addChildShape(principal.inverse() * shape.compound->getChildTransform(i),
		                      shape.compound->getChildShape(i));

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, 0, -9.81));
	btStaticPlaneShape groundShape(btVector3(0, 0, 1), 0);
	btRigidBody ground(0, nullptr, &groundShape);
	world.addRigidBody(&ground);
	btTransform start = principal;
	start.setOrigin(principal.getOrigin() + btVector3(0, 0, 1));
	btRigidBody body(1, nullptr, &centred, inertia);
	body.setWorldTransform(start);
	world.addRigidBody(&body);
	for (int i = 0; i < 180; ++i) world.stepSimulation(1.0 / 60, 0);
	EXPECT_NEAR(body.getWorldTransform().getOrigin().z(), 0.25, 0.01);
	world.removeRigidBody(&body);
	world.removeRigidBody(&ground);
}
