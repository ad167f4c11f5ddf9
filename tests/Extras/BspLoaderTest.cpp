// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The Quake 3 BSP loader and converter: the example level our own tool writes, and damaged files.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

#include "BspLoader/BspConverter.h"
#include "BspLoader/BspLoader.h"
#include "BspLoader/BspWriter.h"
#include "ConvexDecomposition/ConvexDecomposition.h"
#include "btBulletDynamicsCommon.h"

using caliber::BspConversion;
using caliber::BspLevel;

namespace
{
std::vector<unsigned char> exampleBytes() { return caliber::writeBsp(caliber::makeExampleRoom()); }

BspLevel load(const std::vector<unsigned char>& bytes)
{
	BspLevel level;
	caliber::loadBspFromMemory(bytes.data(), bytes.size(), level);
	return level;
}

double hullVolume(const btAlignedObjectArray<btVector3>& points) { return caliber::convexHullVolume(points); }

void setLump(std::vector<unsigned char>& bytes, int lump, std::int32_t offset, std::int32_t length)
{
	std::memcpy(&bytes[8 + 8 * lump], &offset, 4);  // the tests run on little-endian hosts, like the format
	std::memcpy(&bytes[8 + 8 * lump + 4], &length, 4);
}

std::int32_t lumpOffset(const std::vector<unsigned char>& bytes, int lump)
{
	std::int32_t offset;
	std::memcpy(&offset, &bytes[8 + 8 * lump], 4);
	return offset;
}

caliber::BspWriterBrush unitBox()
{
	const float min[3] = {0, 0, 0}, max[3] = {1, 1, 1};
	return caliber::makeBoxBrush(min, max, 0);
}

// A level of one brush with the given planes (Quake form), solid.
BspConversion convertSingleBrush(const caliber::BspWriterBrush& brush)
{
	caliber::BspWriterInput input;
	input.textures.push_back({"solid", 0, caliber::kBspContentsSolid});
	input.brushes.push_back(brush);
	return caliber::convertBspBrushes(load(caliber::writeBsp(input)), 1);
}
}  // namespace

TEST(BspLoader, TheToolsFileIsTheExampleLevelWithItsBrushesTexturesAndEntities)
{
	BspLevel level;
	ASSERT_TRUE(caliber::loadBspFile(CALIBER_EXAMPLE_BSP, level)) << level.error;
	EXPECT_EQ(level.brushes.size(), 11u);
	ASSERT_EQ(level.textures.size(), 2u);
	EXPECT_EQ(level.textures[0].name, "textures/caliber/concrete");
	EXPECT_EQ(level.textures[1].contents, 32);
	EXPECT_NE(level.entities.find("worldspawn"), std::string::npos);
	EXPECT_EQ(level.brushes[0].planes.size(), 6);
	// Quake's "normal.p <= dist" became btGeometryUtil's "normal.p + w <= 0": the floor's top plane z <= 0.
	EXPECT_FLOAT_EQ(level.brushes[0].planes[4].z(), 1);
	EXPECT_FLOAT_EQ(level.brushes[0].planes[4].w(), 0);

	std::FILE* file = std::fopen(CALIBER_EXAMPLE_BSP, "rb");
	ASSERT_NE(file, nullptr);
	std::vector<unsigned char> onDisk(1 << 16);
	onDisk.resize(std::fread(onDisk.data(), 1, onDisk.size(), file));
	std::fclose(file);
	EXPECT_EQ(onDisk, exampleBytes()) << "the file on disk is what makeExampleRoom writes";
}

// Each solid brush becomes a hull with the brush's exact corners and volume (analytic values in Quake units):
// the floor is 512 x 512 x 16, the ramp a triangular prism of 0.5 * 128 * 64 * 128, the octagonal pillar
// 8 * apothem^2 * tan(22.5 deg) * 192. The water brush is not solid and is left out.
TEST(BspConverter, SolidBrushesBecomeHullsWithTheBrushesCornersAndVolumes)
{
	const BspConversion conversion = caliber::convertBspBrushes(load(exampleBytes()), 1);
	EXPECT_TRUE(conversion.warnings.empty());
	EXPECT_EQ(conversion.nonSolidBrushes, 1);
	ASSERT_EQ(conversion.pieces.size(), 10u);
	EXPECT_EQ(conversion.pieces[0].vertices.size(), 8);
	EXPECT_NEAR(hullVolume(conversion.pieces[0].vertices), 512.0 * 512 * 16, 1e-4 * 512 * 512 * 16);
	EXPECT_EQ(conversion.pieces[5].vertices.size(), 6);  // the ramp: a wedge
	EXPECT_NEAR(hullVolume(conversion.pieces[5].vertices), 0.5 * 128 * 64 * 128, 1e-4 * 0.5 * 128 * 64 * 128);
	EXPECT_EQ(conversion.pieces[9].vertices.size(), 16);  // the octagon
	const double octagon = 8 * 24.0 * 24.0 * std::tan(3.14159265358979 / 8) * 192;
	EXPECT_NEAR(hullVolume(conversion.pieces[9].vertices), octagon, 1e-4 * octagon);
	for (const caliber::BspConvexPiece& piece : conversion.pieces) EXPECT_NE(piece.brush, 10);  // water
}

TEST(BspConverter, ScaleMultipliesTheCorners)
{
	const BspConversion conversion = caliber::convertBspBrushes(load(exampleBytes()), btScalar(1) / 32);
	ASSERT_EQ(conversion.pieces.size(), 10u);
	btVector3 lo(1e9, 1e9, 1e9), hi(-1e9, -1e9, -1e9);
	for (int i = 0; i < conversion.pieces[0].vertices.size(); ++i)
	{
		lo.setMin(conversion.pieces[0].vertices[i]);
		hi.setMax(conversion.pieces[0].vertices[i]);
	}
	EXPECT_NEAR(lo.x(), -8, 1e-4);
	EXPECT_NEAR(hi.y(), 8, 1e-4);
	EXPECT_NEAR(lo.z(), -0.5, 1e-4);
	EXPECT_NEAR(hi.z(), 0, 1e-4);
}

// Spheres of radius 0.25 m dropped into the level (scaled 1/32: floor top at z = 0, pillar tops at 6 m)
// come to rest one radius above the surface under them; one dropped on the ramp rolls down and stays in
// the room. The level hulls are shrunk by their margin, so the surfaces are where the brushes say; the
// tolerance (1 cm) covers the contact's allowed penetration.
TEST(BspConverter, BodiesDroppedIntoTheLevelRestOnItsSurfaces)
{
	const BspConversion conversion = caliber::convertBspBrushes(load(exampleBytes()), btScalar(1) / 32);
	caliber::BspLevelShape levelShape = caliber::buildBspLevelShape(conversion);
	ASSERT_NE(levelShape.compound, nullptr);
	EXPECT_EQ(levelShape.compound->getNumChildShapes(), 10);

	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	world.setGravity(btVector3(0, 0, -9.81));  // Quake levels are z-up
	btRigidBody levelBody(0, nullptr, levelShape.compound.get());
	world.addRigidBody(&levelBody);

	btSphereShape sphere(0.25);
	btVector3 inertia;
	sphere.calculateLocalInertia(1, inertia);
	const btVector3 drops[3] = {btVector3(0, 0, 2), btVector3(4, 4, 8), btVector3(-6, 0, 4)};  // floor, pillar, ramp
	std::vector<std::unique_ptr<btRigidBody>> balls;
	for (const btVector3& at : drops)
	{
		balls.emplace_back(new btRigidBody(1, nullptr, &sphere, inertia));
		btTransform pose;
		pose.setIdentity();
		pose.setOrigin(at);
		balls.back()->setWorldTransform(pose);
		balls.back()->setRollingFriction(0.05);  // the ramp's ball stops rolling within the room
		world.addRigidBody(balls.back().get());
	}
	for (int i = 0; i < 600; ++i) world.stepSimulation(1.0 / 60, 0);
	EXPECT_NEAR(balls[0]->getWorldTransform().getOrigin().z(), 0.25, 0.01);
	EXPECT_NEAR(balls[1]->getWorldTransform().getOrigin().z(), 6.25, 0.01);
	const btVector3 rolled = balls[2]->getWorldTransform().getOrigin();
	EXPECT_NEAR(rolled.z(), 0.25, 0.01) << "the ramp's ball ends on the floor";
	EXPECT_GT(rolled.x(), -3.0) << "it rolled down the ramp (which ends at x = -3 m)";
	EXPECT_LT(std::fabs(rolled.x()), 8.0);
	EXPECT_LT(std::fabs(rolled.y()), 8.0);
	for (auto& ball : balls) world.removeRigidBody(ball.get());
	world.removeRigidBody(&levelBody);
}

TEST(BspLoader, DamagedHeadersFailWithAClearMessage)
{
	EXPECT_NE(load({}).error.find("truncated"), std::string::npos);
	std::vector<unsigned char> bytes = exampleBytes();
	EXPECT_NE(load(std::vector<unsigned char>(bytes.begin(), bytes.begin() + 100)).error.find("truncated"),
	          std::string::npos);

	std::vector<unsigned char> magic = bytes;
	magic[0] = 'V';
	EXPECT_NE(load(magic).error.find("magic"), std::string::npos);

	std::vector<unsigned char> version = bytes;
	version[4] = 47;
	EXPECT_NE(load(version).error.find("version 47"), std::string::npos);

	std::vector<unsigned char> outside = bytes;
	setLump(outside, caliber::kBspLumpPlanes, std::int32_t(bytes.size()) - 8, 16);
	EXPECT_NE(load(outside).error.find("planes lump"), std::string::npos) << load(outside).error;

	std::vector<unsigned char> negative = bytes;
	setLump(negative, caliber::kBspLumpVisData, -4, 4);
	EXPECT_NE(load(negative).error.find("visibility data lump"), std::string::npos);

	std::vector<unsigned char> huge = bytes;
	setLump(huge, caliber::kBspLumpBrushes, 0x7fffffff, 0x7fffffff);
	EXPECT_NE(load(huge).error.find("outside the file"), std::string::npos);

	std::vector<unsigned char> ragged = bytes;
	setLump(ragged, caliber::kBspLumpBrushes, lumpOffset(bytes, caliber::kBspLumpBrushes), 13);
	EXPECT_NE(load(ragged).error.find("not a multiple"), std::string::npos);
	EXPECT_TRUE(load(ragged).brushes.empty()) << "a failed load holds nothing";
}

TEST(BspLoader, IndicesOutOfRangeFailTheLoadNamingTheBrush)
{
	const std::vector<unsigned char> bytes = exampleBytes();
	const std::int32_t brushes = lumpOffset(bytes, caliber::kBspLumpBrushes);
	const std::int32_t sides = lumpOffset(bytes, caliber::kBspLumpBrushSides);
	const std::int32_t models = lumpOffset(bytes, caliber::kBspLumpModels);
	const struct
	{
		std::int32_t at, value;
		const char* expected;
	} cases[] = {
	    {brushes + 12 * 3 + 0, 100000, "brush 3: sides"},      // first side beyond the lump
	    {brushes + 12 * 3 + 4, -1, "brush 3: sides"},          // negative side count
	    {brushes + 12 * 3 + 4, 0x7fffffff, "brush 3: sides"},  // a count that would overflow 32 bits
	    {brushes + 12 * 2 + 8, 2, "brush 2: texture 2"},       // texture out of range
	    {brushes + 12 * 2 + 8, -5, "brush 2: texture -5"},
	    {sides + 8 * 7, 9999, "names plane 9999"},  // side 7 (brush 1) names a missing plane
	    {models + 36, 12, "world model"},           // the world model claims 12 of 11 brushes
	};
	for (const auto& c : cases)
	{
		std::vector<unsigned char> damaged = bytes;
		std::memcpy(&damaged[c.at], &c.value, 4);
		const BspLevel level = load(damaged);
		EXPECT_FALSE(level.ok()) << c.expected;
		EXPECT_NE(level.error.find(c.expected), std::string::npos) << level.error;
	}
}

// A file cut short anywhere, or with random bytes changed (fixed seed), loads or fails, and whatever loads
// converts to finite hulls without a crash.
TEST(BspLoader, TruncatedOrRandomlyEditedFilesNeverCrashOrGiveNonFiniteHulls)
{
	const std::vector<unsigned char> bytes = exampleBytes();
	int nonFinite = 0;
	const auto check = [&nonFinite](const std::vector<unsigned char>& data)
	{
		const BspLevel level = load(data);
		const BspConversion conversion = caliber::convertBspBrushes(level, 1);
		for (const caliber::BspConvexPiece& piece : conversion.pieces)
			for (int i = 0; i < piece.vertices.size(); ++i)
				for (int axis = 0; axis < 3; ++axis) nonFinite += !std::isfinite(piece.vertices[i][axis]);
		return level.ok();
	};
	int loaded = 0;
	for (std::size_t length = 0; length < bytes.size(); length += 7)  // every header field and lump boundary region
		loaded += check(std::vector<unsigned char>(bytes.begin(), bytes.begin() + length));
	EXPECT_EQ(loaded, 0) << "the last lump ends at the end of the file, so every cut damages a lump";
	std::mt19937 random(46);
	int failed = 0;
	for (int trial = 0; trial < 300; ++trial)
	{
		std::vector<unsigned char> damaged = bytes;
		const int edits = 1 + int(random() % 4);
		for (int e = 0; e < edits; ++e) damaged[random() % damaged.size()] = (unsigned char)(random() % 256);
		failed += !check(damaged);
	}
	EXPECT_GT(failed, 0);
	EXPECT_LT(failed, 300);
	EXPECT_EQ(nonFinite, 0);
}

TEST(BspConverter, OpenEmptyFlatOrNonFiniteBrushesAreSkippedWithAWarningNamingThem)
{
	caliber::BspWriterBrush open = unitBox();
	open.planes.erase(open.planes.begin());  // no +x side: open towards +x
	caliber::BspWriterBrush tooFew = unitBox();
	tooFew.planes.resize(3);
	caliber::BspWriterBrush empty = unitBox();
	empty.planes[1].dist = -2;  // x >= 2 and x <= 1
	caliber::BspWriterBrush flat = unitBox();
	flat.planes[0].dist = 0;  // x <= 0 and x >= 0
	caliber::BspWriterBrush notFinite = unitBox();
	notFinite.planes[2].dist = NAN;
	caliber::BspWriterBrush zeroNormal = unitBox();
	zeroNormal.planes[3].normal[1] = 0;
	caliber::BspWriterBrush far = unitBox();
	far.planes[0].dist = 1e9f;
	const struct
	{
		caliber::BspWriterBrush brush;
		const char* reason;
	} cases[] = {{open, "open"},     {tooFew, "3 planes"},      {empty, "empty"},
	             {flat, "flat"},     {notFinite, "not finite"}, {zeroNormal, "zero normal"},
	             {far, "beyond 1e6"}};
	for (const auto& c : cases)
	{
		const BspConversion conversion = convertSingleBrush(c.brush);
		EXPECT_TRUE(conversion.pieces.empty()) << c.reason;
		ASSERT_EQ(conversion.warnings.size(), 1u) << c.reason;
		EXPECT_NE(conversion.warnings[0].find("brush 0"), std::string::npos) << conversion.warnings[0];
		EXPECT_NE(conversion.warnings[0].find(c.reason), std::string::npos) << conversion.warnings[0];
	}
	// A brush with a redundant extra plane (x <= 5 behind x <= 1) is still the unit cube.
	caliber::BspWriterBrush redundant = unitBox();
	redundant.planes.push_back({{1, 0, 0}, 5});
	const BspConversion conversion = convertSingleBrush(redundant);
	ASSERT_EQ(conversion.pieces.size(), 1u);
	EXPECT_NEAR(hullVolume(conversion.pieces[0].vertices), 1.0, 1e-5);
}

TEST(BspConverter, AFailedLoadConvertsToNothingWithTheLoadsError)
{
	const BspConversion conversion = caliber::convertBspBrushes(load({1, 2, 3}), 1);
	EXPECT_TRUE(conversion.pieces.empty());
	ASSERT_EQ(conversion.warnings.size(), 1u);
	EXPECT_NE(conversion.warnings[0].find("truncated"), std::string::npos);
	EXPECT_EQ(caliber::buildBspLevelShape(conversion).compound, nullptr);
	BspLevel level;
	EXPECT_FALSE(caliber::loadBspFile("/nonexistent/caliber.bsp", level));
	EXPECT_NE(level.error.find("cannot open"), std::string::npos);
}

#if CALIBER_ASSERTS_ENABLED
TEST(BspLoaderDeathTest, NullDataNullPathOrABadScaleAsserts)
{
	BspLevel level;
	EXPECT_DEATH(caliber::loadBspFromMemory(nullptr, 10, level), "assertion failed");
	EXPECT_DEATH(caliber::loadBspFile(nullptr, level), "assertion failed");
	const BspLevel good = load(exampleBytes());
	EXPECT_DEATH(caliber::convertBspBrushes(good, 0), "assertion failed");
	EXPECT_DEATH(caliber::convertBspBrushes(good, NAN), "assertion failed");
}
#else
TEST(BspLoader, NullDataNullPathOrABadScaleFailsWithAMessage)
{
	BspLevel level;
	EXPECT_FALSE(caliber::loadBspFromMemory(nullptr, 10, level));
	EXPECT_FALSE(level.error.empty());
	EXPECT_FALSE(caliber::loadBspFile(nullptr, level));
	const BspLevel good = load(exampleBytes());
	for (btScalar scale : {btScalar(0), btScalar(-1), btScalar(NAN), btScalar(INFINITY)})
	{
		const BspConversion conversion = caliber::convertBspBrushes(good, scale);
		EXPECT_TRUE(conversion.pieces.empty());
		EXPECT_EQ(conversion.warnings.size(), 1u);
	}
}
#endif
