// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The demos' shared command line and their world pictures: wrong options are refused before a demo
// runs, and a world's picture frames what moves and shows its joints.

#include <gtest/gtest.h>

#include <cstdio>
#include <initializer_list>
#include <vector>

#include "DemoPictures.h"
#include "Png.h"
#include "WorldScene.h"
#include "btBulletDynamicsCommon.h"

using namespace caliber::demo;

namespace
{
// Parses a command line given as words (the program name first).
DemoPictures parse(std::initializer_list<const char*> words, bool sequences = true, int defaultFrames = 100)
{
	std::vector<char*> argv;
	for (const char* w : words) argv.push_back(const_cast<char*>(w));
	DemoCommandLine commandLine;
	commandLine.name = "TestDemo";
	commandLine.defaultFrames = defaultFrames;
	commandLine.sequences = sequences;
	return DemoPictures(int(argv.size()), argv.data(), commandLine);
}
}  // namespace

TEST(DemoCommandLine, DefaultsAndGoodOptions)
{
	DemoPictures none = parse({"demo"});
	EXPECT_TRUE(none.ok());
	EXPECT_EQ(none.frames(), 100);
	EXPECT_FALSE(none.shortened());
	EXPECT_FALSE(none.wanted());
	DemoPictures some = parse({"demo", "--frames", "30", "--size", "320x200", "--draw", "contacts,aabbs"});
	EXPECT_TRUE(some.ok());
	EXPECT_EQ(some.frames(), 30);
	EXPECT_TRUE(some.shortened());
}

TEST(DemoCommandLine, RefusesBadOptionsWithUsageErrorCode)
{
	const std::vector<std::vector<const char*>> bad = {{"demo", "--frames", "0"},
	                                                   {"demo", "--frames", "-3"},
	                                                   {"demo", "--frames", "12abc"},
	                                                   {"demo", "--frames"},
	                                                   {"demo", "--png"},
	                                                   {"demo", "--png", ""},
	                                                   {"demo", "--size", "0x480"},
	                                                   {"demo", "--size", "640"},
	                                                   {"demo", "--size", "9000x10"},
	                                                   {"demo", "--draw", "everything"},
	                                                   {"demo", "--every", "5"},
	                                                   {"demo", "--every", "0"},
	                                                   {"demo", "--wobble"},
	                                                   {"demo", "stray"}};
	for (const auto& words : bad)
	{
		std::vector<char*> argv;
		for (const char* w : words) argv.push_back(const_cast<char*>(w));
		DemoCommandLine commandLine;
		commandLine.name = "TestDemo";
		commandLine.defaultFrames = 100;
		commandLine.sequences = true;
		DemoPictures pictures(int(argv.size()), argv.data(), commandLine);
		EXPECT_FALSE(pictures.ok()) << words.back();
		EXPECT_EQ(pictures.exitCode(), 2) << words.back();
	}
}

TEST(DemoCommandLine, FramesBeyondAScriptedDemosLengthAreRefused)
{
	std::vector<char*> argv = {const_cast<char*>("demo"), const_cast<char*>("--frames"), const_cast<char*>("13")};
	DemoCommandLine commandLine;
	commandLine.defaultFrames = 12;
	commandLine.maxFrames = 12;
	EXPECT_FALSE(DemoPictures(3, argv.data(), commandLine).ok());
	argv[2] = const_cast<char*>("12");
	EXPECT_TRUE(DemoPictures(3, argv.data(), commandLine).ok());
}

// A sequence writes one picture every K frames, numbered in order, each of the asked size.
TEST(DemoCommandLine, SequenceWritesEveryKthFrame)
{
	ASSERT_TRUE(pngAvailable());
	const std::string dir = ::testing::TempDir() + "caliber_sequence_test";
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	btBoxShape shape(btVector3(1, 1, 1));
	btRigidBody box(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &shape, btVector3(1, 1, 1)));
	world.addRigidBody(&box);
	DemoPictures pictures =
	    parse({"demo", "--png-sequence", dir.c_str(), "--every", "2", "--frames", "5", "--size", "32x24"});
	ASSERT_TRUE(pictures.ok());
	for (int n = 1; n <= pictures.frames(); ++n)
	{
		world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
		pictures.frame(world, n);
	}
	EXPECT_EQ(pictures.finish(0), 0);
	for (int k = 1; k <= 3; ++k)
	{
		const std::string path = dir + "/TestDemo-000" + std::to_string(k) + ".png";
		Image image;
		std::string error;
		if (k <= 2)
		{
			ASSERT_TRUE(readPng(path, image, error)) << error;
			EXPECT_EQ(image.width, 32);
			EXPECT_EQ(image.height, 24);
			std::remove(path.c_str());
		}
		else
			EXPECT_FALSE(readPng(path, image, error)) << "frames 2 and 4 only";
	}
	std::remove(dir.c_str());
	world.removeRigidBody(&box);
}

TEST(DemoCommandLine, OptionsADemoDoesNotOfferAreRefused)
{
	// A demo without a frame loop has no --frames; one without sequences has no --png-sequence.
	EXPECT_FALSE(parse({"demo", "--frames", "10"}, false, 0).ok());
	EXPECT_FALSE(parse({"demo", "--png-sequence", "out"}, false).ok());
	EXPECT_EQ(parse({"demo", "--help"}).exitCode(), 0);
	EXPECT_FALSE(parse({"demo", "--help"}).ok());
}

TEST(DemoCommandLine, PictureOfTheLastFrameIsWrittenAndAMissingOneIsAnError)
{
	ASSERT_TRUE(pngAvailable());
	const std::string path = ::testing::TempDir() + "caliber_demo_last.png";
	std::remove(path.c_str());
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	btSphereShape shape(1);
	btRigidBody ball(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &shape, btVector3(1, 1, 1)));
	world.addRigidBody(&ball);
	{
		DemoPictures pictures = parse({"demo", "--png", path.c_str(), "--frames", "3", "--size", "64x48"});
		ASSERT_TRUE(pictures.ok());
		for (int n = 1; n <= pictures.frames(); ++n)
		{
			world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
			pictures.frame(world, n);
		}
		EXPECT_EQ(pictures.finish(0), 0);
		Image image;
		std::string error;
		ASSERT_TRUE(readPng(path, image, error)) << error;
		EXPECT_EQ(image.width, 64);
		EXPECT_EQ(image.height, 48);
	}
	{
		// The demo stopped early (never reached frame 3): no picture, and the exit code says so.
		DemoPictures pictures = parse({"demo", "--png", path.c_str(), "--frames", "3"});
		pictures.frame(world, 1);
		EXPECT_EQ(pictures.finish(0), 1);
		EXPECT_EQ(pictures.finish(7), 7);  // a demo's own failure code is kept
	}
	world.removeRigidBody(&ball);
	std::remove(path.c_str());
}

// addWorld frames what moves (a small ball above a huge static ground) and draws joints as lines.
TEST(DemoWorldScene, FramesMovingBodiesAndDrawsJoints)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	btBoxShape groundShape(btVector3(50, 50, 50));
	btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
	ground.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, -50, 0)));
	world.addRigidBody(&ground);
	btSphereShape ballShape(btScalar(0.5));
	btRigidBody ball(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &ballShape, btVector3(1, 1, 1)));
	ball.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 3, 0)));
	world.addRigidBody(&ball);
	btHingeConstraint hinge(ball, btVector3(0, 1, 0), btVector3(0, 0, 1));
	world.addConstraint(&hinge);

	Scene scene;
	EXPECT_EQ(addWorld(scene, world), 0);
	ASSERT_TRUE(scene.hasFocus());
	// The ball's AABB (radius plus its margin-free box), not the ground's 100 m.
	EXPECT_LT(double((scene.focusMax() - scene.focusMin()).length()), 2);
	EXPECT_FALSE(scene.triangles().empty());
	EXPECT_FALSE(scene.lines().empty()) << "the hinge's frame and limits are drawn";
	// No overlay asked for: no lines. The world's own drawer is left as it was.
	Scene solidsOnly;
	WorldStyle style;
	style.debugMode = 0;
	addWorld(solidsOnly, world, style);
	EXPECT_TRUE(solidsOnly.lines().empty());
	EXPECT_EQ(world.getDebugDrawer(), nullptr);
	world.removeConstraint(&hinge);
	world.removeRigidBody(&ball);
	world.removeRigidBody(&ground);
}

// A scripted demo's budget: spent after exactly N counted steps; a check is judged unless --frames cut
// the run short and the budget is spent.
TEST(DemoStepBudget, SpentAfterNStepsAndSkipsOnlyShortenedChecks)
{
	StepBudget shortened(3, true);
	for (int i = 0; i < 3; ++i)
	{
		EXPECT_FALSE(shortened.spent()) << i;
		EXPECT_TRUE(shortened.reached("a phase that finished"));
		shortened.count();
	}
	EXPECT_TRUE(shortened.spent());
	EXPECT_FALSE(shortened.reached("a phase cut short"));
	// Without --frames the budget is the demo's own length: spent or not, every check is judged.
	StepBudget full(1, false);
	full.count();
	EXPECT_TRUE(full.spent());
	EXPECT_TRUE(full.reached("the last phase"));
}

// A raycast vehicle's wheels, which the world does not hold, are drawn at the wheel transforms: every
// corner lies within the wheel's radius (across) and half its width (along the axle) of its centre.
TEST(DemoWorldScene, VehicleWheelsAreDrawnAtTheWheels)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	btBoxShape chassisShape(btVector3(1, btScalar(0.3), 2));
	btRigidBody chassis(btRigidBody::btRigidBodyConstructionInfo(800, nullptr, &chassisShape, btVector3(1, 1, 1)));
	chassis.setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 2, 0)));
	world.addRigidBody(&chassis);
	btRaycastVehicle::btVehicleTuning tuning;
	btDefaultVehicleRaycaster raycaster(&world);
	btRaycastVehicle car(tuning, &chassis, &raycaster);
	car.setCoordinateSystem(0, 1, 2);
	const btScalar radius = btScalar(0.4), width = btScalar(0.3);
	for (int i = 0; i < 4; ++i)
		car.addWheel(btVector3((i & 1) ? -1 : 1, 0, i < 2 ? 1 : -1), btVector3(0, -1, 0), btVector3(-1, 0, 0),
		             btScalar(0.6), radius, tuning, i < 2);
	Scene scene;
	addVehicleWheels(scene, car, width);
	ASSERT_GE(scene.triangles().size(), 4u * 48u);
	for (const SceneTriangle& t : scene.triangles())
		for (const btVector3& c : t.corner)
		{
			bool nearAWheel = false;
			for (int i = 0; i < 4; ++i)
			{
				const btTransform& wheel = car.getWheelInfo(i).m_worldTransform;
				const btVector3 local = wheel.invXform(c);
				const btScalar across = btSqrt(local.y() * local.y() + local.z() * local.z());
				if (btFabs(local.x()) <= width / 2 + btScalar(1e-4) && across <= radius + btScalar(1e-4))
					nearAWheel = true;
			}
			EXPECT_TRUE(nearAWheel) << "(" << c.x() << ", " << c.y() << ", " << c.z() << ")";
		}
	world.removeRigidBody(&chassis);
}

// The browser's recording: while set, a demo's pictures become shots (one per frame of its run and
// per capture, each framed as its picture would be), nothing is written, and --png is refused (it
// would write behind the browser's back). Cleared, everything is as before.
TEST(DemoSceneRecording, KeepsAShotPerFrameAndCaptureAndWritesNothing)
{
	btDefaultCollisionConfiguration configuration;
	btCollisionDispatcher dispatcher(&configuration);
	btDbvtBroadphase broadphase;
	btSequentialImpulseConstraintSolver solver;
	btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
	btSphereShape shape(1);
	btRigidBody ball(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &shape, btVector3(1, 1, 1)));
	world.addRigidBody(&ball);

	SceneRecording recording;
	setSceneRecording(&recording);
	{
		DemoPictures pictures = parse({"demo", "--frames", "3"}, false);
		ASSERT_TRUE(pictures.ok());
		EXPECT_TRUE(pictures.recording());
		EXPECT_TRUE(pictures.wanted()) << "demos build their picture scenes for the recording";
		for (int n = 1; n <= pictures.frames(); ++n)
		{
			world.stepSimulation(btScalar(1. / 60.), 1, btScalar(1. / 60.));
			pictures.frame(world, n);
		}
		Scene own;
		own.addPoint(btVector3(5, 0, 0), btVector3(1, 0, 0));
		pictures.setViewDirection(btVector3(0, -1, 0));
		pictures.capture(own);
		EXPECT_EQ(pictures.finish(0), 0);
		DemoPictures refused = parse({"demo", "--png", "never-written.png"}, false);
		EXPECT_FALSE(refused.ok());
		EXPECT_EQ(refused.exitCode(), 2);
	}
	setSceneRecording(nullptr);
	ASSERT_EQ(recording.shots.size(), 4u);
	// The frames show the falling ball, framed on it (unit radius: a box about 2 m across, lower each frame).
	for (int n = 0; n < 3; ++n)
	{
		EXPECT_FALSE(recording.shots[size_t(n)].scene.triangles().empty());
		EXPECT_NEAR(double(recording.shots[size_t(n)].focusMax.x() - recording.shots[size_t(n)].focusMin.x()), 2, 0.2);
	}
	EXPECT_LT(recording.shots[2].focusMax.y(), recording.shots[0].focusMax.y());
	// The captured scene is framed on its content (a point at x = 5), seen from the direction set.
	EXPECT_EQ(recording.shots[3].scene.points().size(), 1u);
	EXPECT_EQ(recording.shots[3].focusMin, btVector3(5, 0, 0));
	EXPECT_EQ(recording.shots[3].viewDirection, btVector3(0, -1, 0));
	std::FILE* file = std::fopen("never-written.png", "rb");
	EXPECT_EQ(file, nullptr);
	if (file) std::fclose(file);
	DemoPictures after = parse({"demo"});
	EXPECT_FALSE(after.recording());
	EXPECT_FALSE(after.wanted());
	world.removeRigidBody(&ball);
}

// Scene::append adds another scene's primitives, not its focus.
TEST(DemoScene, AppendAddsPrimitivesAndKeepsTheFocus)
{
	Scene a, b;
	a.addLine(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(1, 1, 1));
	a.focusOn(btVector3(-1, -1, -1), btVector3(1, 1, 1));
	b.addFlatTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 1, 0), btVector3(1, 0, 0), true);
	b.addPoint(btVector3(9, 9, 9), btVector3(0, 1, 0));
	b.focusOn(btVector3(8, 8, 8), btVector3(10, 10, 10));
	a.append(b);
	EXPECT_EQ(a.lines().size(), 1u);
	ASSERT_EQ(a.triangles().size(), 1u);
	EXPECT_TRUE(a.triangles()[0].checker);
	EXPECT_EQ(a.points().size(), 1u);
	EXPECT_EQ(a.focusMax(), btVector3(1, 1, 1));
	a.append(a);  // appending itself doubles it
	EXPECT_EQ(a.lines().size(), 2u);
	EXPECT_EQ(a.triangles().size(), 2u);
}
