// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The demos' software renderer: coverage and depth against geometry worked out by hand, and what it
// does with input it cannot use.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "Renderer.h"
#include "ShapeMesher.h"
#include "btBulletCollisionCommon.h"

using namespace caliber::demo;

namespace
{
// Pixels that differ from the background colour.
int countScenePixels(const Image& image, const RenderOptions& options)
{
	const std::uint32_t background = (std::uint32_t(std::lround(double(options.background.x()) * 255)) << 16) |
	                                 (std::uint32_t(std::lround(double(options.background.y()) * 255)) << 8) |
	                                 std::uint32_t(std::lround(double(options.background.z()) * 255));
	int count = 0;
	for (int y = 0; y < image.height; ++y)
		for (int x = 0; x < image.width; ++x)
			if (image.pixel(x, y) != background) ++count;
	return count;
}

Camera lookingDownMinusZ(btScalar distance)
{
	Camera camera;
	camera.eye = btVector3(0, 0, distance);
	camera.target = btVector3(0, 0, 0);
	camera.up = btVector3(0, 1, 0);
	camera.fieldOfViewDegrees = 40;
	return camera;
}

// The red channel of a pixel, and the blue one: the tests tell a red box from a blue one by these.
int red(std::uint32_t pixel) { return int(pixel >> 16); }
int blue(std::uint32_t pixel) { return int(pixel & 0xff); }
}  // namespace

// A sphere of radius r seen from distance D along the view axis has a circular silhouette of angular
// radius asin(r / D), so on screen a disc of radius rho = f r / sqrt(D^2 - r^2) pixels (f the focal
// length in pixels). Counting covered pixel centres gives pi rho^2 up to the tessellation (a 48-gon
// inscribed in the circle has 0.29% less area) and pixels along the edge (at most half the perimeter).
TEST(DemoRenderer, SphereSilhouetteAreaIsPiRhoSquared)
{
	Scene scene;
	btSphereShape sphere(1);
	MeshStyle style;
	style.color = btVector3(0.8f, 0.2f, 0.2f);
	ASSERT_TRUE(addShape(scene, &sphere, btTransform::getIdentity(), style));
	RenderOptions options;
	options.width = options.height = 401;
	options.supersampling = 1;
	const double distance = 4;
	Image image;
	std::string error;
	ASSERT_TRUE(render(scene, lookingDownMinusZ(btScalar(distance)), options, image, error)) << error;
	const double focal = 0.5 * options.height / std::tan(20 * M_PI / 180);
	const double rho = focal / std::sqrt(distance * distance - 1);
	const double expected = M_PI * rho * rho;
	const double polygonLoss = 1 - 48 / (2 * M_PI) * std::sin(2 * M_PI / 48);
	const double edge = M_PI * rho;  // half the perimeter, in pixels
	const double counted = countScenePixels(image, options);
	EXPECT_GT(counted, expected * (1 - polygonLoss) - edge) << "rho " << rho << " px, pi rho^2 " << expected;
	EXPECT_LT(counted, expected + edge) << "rho " << rho << " px, pi rho^2 " << expected;
	// And much tighter than that bound in practice: within 1% of the inscribed polygon's area.
	EXPECT_NEAR(counted / (expected * (1 - polygonLoss / 2)), 1, 0.01);
}

// The z-buffer: a red box in front hides the middle of a larger blue box behind it, whichever is drawn
// first; outside the red box's outline the blue one shows.
TEST(DemoRenderer, BoxInFrontHidesBoxBehindInEitherDrawingOrder)
{
	for (int order = 0; order < 2; ++order)
	{
		Scene scene;
		btBoxShape front(btVector3(btScalar(0.5), btScalar(0.5), btScalar(0.5)));
		btBoxShape back(btVector3(2, 2, btScalar(0.5)));
		MeshStyle redStyle, blueStyle;
		redStyle.color = btVector3(1, 0, 0);
		blueStyle.color = btVector3(0, 0, 1);
		const btTransform frontPose(btQuaternion::getIdentity(), btVector3(0, 0, 1));
		const btTransform backPose(btQuaternion::getIdentity(), btVector3(0, 0, -3));
		if (order == 0)
		{
			addShape(scene, &front, frontPose, redStyle);
			addShape(scene, &back, backPose, blueStyle);
		}
		else
		{
			addShape(scene, &back, backPose, blueStyle);
			addShape(scene, &front, frontPose, redStyle);
		}
		RenderOptions options;
		options.width = options.height = 200;
		Image image;
		std::string error;
		ASSERT_TRUE(render(scene, lookingDownMinusZ(10), options, image, error)) << error;
		const std::uint32_t centre = image.pixel(100, 100);
		EXPECT_GT(red(centre), 2 * blue(centre) + 20) << "order " << order << ": centre pixel " << std::hex << centre;
		// With f = 100 / tan 20 = 274.7 px, the front box's near face (0.5 wide, 8.5 away) spans 16 px
		// either side of the centre and the back box's (2 wide, 12.5 away) 44 px: 35 px off centre is
		// outside the first and inside the second.
		const std::uint32_t side = image.pixel(100 + 35, 100);
		EXPECT_GT(blue(side), 2 * red(side) + 20) << "order " << order << ": side pixel " << std::hex << side;
	}
}

// Every collision shape the demos use draws as a closed set of triangles inside its own bounding box
// (to the tessellation's rounding): nothing is left out and nothing sticks out.
TEST(DemoRenderer, EveryShapeDrawsInsideItsAabb)
{
	btBoxShape box(btVector3(1, 2, 3));
	btSphereShape sphere(btScalar(0.7));
	btCapsuleShape capsule(btScalar(0.3), 1);
	btCapsuleShapeX capsuleX(btScalar(0.3), 1);
	btCylinderShape cylinder(btVector3(btScalar(0.5), 1, btScalar(0.5)));
	btCylinderShapeZ cylinderZ(btVector3(btScalar(0.5), btScalar(0.5), 1));
	btConeShape cone(btScalar(0.5), 2);
	const btVector3 centres[2] = {btVector3(0, 0, 0), btVector3(1, 0, 0)};
	const btScalar radii[2] = {btScalar(0.5), btScalar(0.3)};
	btMultiSphereShape multiSphere(centres, radii, 2);
	btConvexHullShape hull;
	hull.addPoint(btVector3(0, 0, 0), false);
	hull.addPoint(btVector3(1, 0, 0), false);
	hull.addPoint(btVector3(0, 1, 0), false);
	hull.addPoint(btVector3(0, 0, 1), true);
	btCompoundShape compound;
	compound.addChildShape(btTransform(btQuaternion::getIdentity(), btVector3(2, 0, 0)), &box);
	compound.addChildShape(btTransform::getIdentity(), &sphere);
	btTriangleMesh mesh;
	mesh.addTriangle(btVector3(0, 0, 0), btVector3(1, 0, 0), btVector3(0, 0, 1));
	mesh.addTriangle(btVector3(1, 0, 0), btVector3(1, 0, 1), btVector3(0, 0, 1));
	btBvhTriangleMeshShape meshShape(&mesh, true);
	const float heights[9] = {0, 0, 0, 0, 1, 0, 0, 0, 0};
	btHeightfieldTerrainShape field(3, 3, heights, btScalar(0), btScalar(1), 1, false);
	const btCollisionShape* shapes[] = {&box,  &sphere,      &capsule, &capsuleX, &cylinder,  &cylinderZ,
	                                    &cone, &multiSphere, &hull,    &compound, &meshShape, &field};
	const int minimumTriangles[] = {12, 48, 48, 48, 48, 48, 48, 20, 4, 60, 2, 8};
	const btTransform pose(btQuaternion(btVector3(1, 2, 3).normalized(), btScalar(0.7)), btVector3(3, -1, 2));
	for (std::size_t i = 0; i < sizeof(shapes) / sizeof(shapes[0]); ++i)
	{
		Scene scene;
		ASSERT_TRUE(addShape(scene, shapes[i], pose, MeshStyle())) << shapes[i]->getName();
		EXPECT_GE(int(scene.triangles().size()), minimumTriangles[i]) << shapes[i]->getName();
		btVector3 aabbMin, aabbMax;
		shapes[i]->getAabb(pose, aabbMin, aabbMax);
		const btVector3 slack(btScalar(1e-3), btScalar(1e-3), btScalar(1e-3));
		for (const SceneTriangle& t : scene.triangles())
			for (const btVector3& c : t.corner)
			{
				EXPECT_TRUE(c.x() >= aabbMin.x() - slack.x() && c.y() >= aabbMin.y() - slack.y() &&
				            c.z() >= aabbMin.z() - slack.z() && c.x() <= aabbMax.x() + slack.x() &&
				            c.y() <= aabbMax.y() + slack.y() && c.z() <= aabbMax.z() + slack.z())
				    << shapes[i]->getName() << " corner (" << c.x() << ", " << c.y() << ", " << c.z() << ")";
			}
	}
}

// A sphere's tessellation lies on the sphere, and its normals point away from the centre.
TEST(DemoRenderer, SphereMeshLiesOnTheSphere)
{
	btSphereShape sphere(2);
	Scene scene;
	const btVector3 centre(1, 2, 3);
	addShape(scene, &sphere, btTransform(btQuaternion::getIdentity(), centre), MeshStyle());
	for (const SceneTriangle& t : scene.triangles())
		for (int k = 0; k < 3; ++k)
		{
			EXPECT_NEAR(double((t.corner[k] - centre).length()), 2, 1e-5);
			EXPECT_GT(double(t.normal[k].dot(t.corner[k] - centre)), 0);
		}
}

// A static plane is infinite; it is drawn as a square patch of the asked size, centred where the
// asked centre projects onto the plane.
TEST(DemoRenderer, StaticPlaneIsAFinitePatchAroundTheCentre)
{
	btStaticPlaneShape plane(btVector3(0, 1, 0), 2);
	MeshStyle style;
	style.planeCentre = btVector3(5, 10, -3);
	style.planeHalfSize = 4;
	Scene scene;
	ASSERT_TRUE(addShape(scene, &plane, btTransform::getIdentity(), style));
	ASSERT_EQ(scene.triangles().size(), 2u);
	btVector3 aabbMin, aabbMax;
	ASSERT_TRUE(scene.contentBounds(aabbMin, aabbMax));
	EXPECT_NEAR(double(aabbMin.y()), 2, 1e-6);
	EXPECT_NEAR(double(aabbMax.y()), 2, 1e-6);
	EXPECT_NEAR(double((aabbMin.x() + aabbMax.x()) / 2), 5, 1e-5);
	EXPECT_NEAR(double((aabbMin.z() + aabbMax.z()) / 2), -3, 1e-5);
	EXPECT_NEAR(double(aabbMax.x() - aabbMin.x()), 8, 1e-5);
}

// Camera::frame keeps the whole box in view: every corner of the framed box projects inside the image.
TEST(DemoRenderer, FramedBoxIsEntirelyInView)
{
	const btVector3 aabbMin(-3, 0, -1), aabbMax(5, 2, 7);
	btBoxShape box((aabbMax - aabbMin) / 2);
	Scene scene;
	addShape(scene, &box, btTransform(btQuaternion::getIdentity(), (aabbMin + aabbMax) / 2), MeshStyle());
	scene.focusOn(aabbMin, aabbMax);
	RenderOptions options;
	options.width = 160;
	options.height = 90;
	const Camera camera = frameScene(scene, options);
	Image image;
	std::string error;
	ASSERT_TRUE(render(scene, camera, options, image, error)) << error;
	// In view and not cut: the border rows and columns are background.
	const std::uint32_t background = image.pixel(0, 0);
	for (int x = 0; x < image.width; ++x)
	{
		EXPECT_EQ(image.pixel(x, 0), background);
		EXPECT_EQ(image.pixel(x, image.height - 1), background);
	}
	for (int y = 0; y < image.height; ++y)
	{
		EXPECT_EQ(image.pixel(0, y), background);
		EXPECT_EQ(image.pixel(image.width - 1, y), background);
	}
	EXPECT_GT(countScenePixels(image, options), image.width * image.height / 20);
}

// A line is drawn even inside a solid (linesOnTop, for joint frames inside bodies) and hidden by it
// when depth-tested.
TEST(DemoRenderer, LinesOnTopShowThroughSolidsAndDepthTestedOnesDoNot)
{
	Scene scene;
	btBoxShape box(btVector3(1, 1, 1));
	MeshStyle style;
	style.color = btVector3(0, 0, 1);
	addShape(scene, &box, btTransform::getIdentity(), style);
	scene.addLine(btVector3(-0.5f, 0, 0), btVector3(0.5f, 0, 0), btVector3(1, 0, 0));
	RenderOptions options;
	options.width = options.height = 100;
	options.supersampling = 1;  // the centre pixel is then wholly the line's
	for (int onTop = 0; onTop < 2; ++onTop)
	{
		options.linesOnTop = onTop != 0;
		Image image;
		std::string error;
		ASSERT_TRUE(render(scene, lookingDownMinusZ(8), options, image, error)) << error;
		const std::uint32_t centre = image.pixel(50, 50);
		if (onTop)
			EXPECT_EQ(centre, 0xff0000u);
		else
			EXPECT_GT(blue(centre), red(centre));
	}
}

// Bad input: sizes out of range and unusable cameras are refused with a message, not a crash or a
// huge allocation; non-finite geometry is dropped and counted.
TEST(DemoRenderer, RefusesUnusableSizesAndCameras)
{
	Scene scene;
	const int sizes[][2] = {{0, 480}, {640, 0}, {-5, 10}, {kMaxImageSide + 1, 10}};
	for (const auto& size : sizes)
	{
		RenderOptions options;
		options.width = size[0];
		options.height = size[1];
		Image image;
		std::string error;
		EXPECT_FALSE(render(scene, lookingDownMinusZ(5), options, image, error));
		EXPECT_NE(error.find("image size"), std::string::npos) << error;
		EXPECT_EQ(image.width, 0);
		EXPECT_TRUE(image.rgb.empty());
	}
	RenderOptions options;
	options.supersampling = 0;
	Image image;
	std::string error;
	EXPECT_FALSE(render(scene, lookingDownMinusZ(5), options, image, error));
	EXPECT_NE(error.find("supersampling"), std::string::npos) << error;
	options = RenderOptions();
	Camera camera;
	camera.eye = camera.target;
	EXPECT_FALSE(render(scene, camera, options, image, error));
	EXPECT_NE(error.find("camera"), std::string::npos) << error;
	camera = Camera();
	camera.eye.setX(std::numeric_limits<btScalar>::quiet_NaN());
	EXPECT_FALSE(render(scene, camera, options, image, error));
}

TEST(DemoRenderer, DropsAndCountsNonFiniteGeometry)
{
	const btScalar nan = std::numeric_limits<btScalar>::quiet_NaN();
	const btScalar inf = std::numeric_limits<btScalar>::infinity();
	Scene scene;
	scene.addFlatTriangle(btVector3(0, 0, 0), btVector3(nan, 0, 0), btVector3(0, 1, 0), btVector3(1, 1, 1));
	scene.addLine(btVector3(0, inf, 0), btVector3(0, 0, 0), btVector3(1, 1, 1));
	scene.addPoint(btVector3(0, 0, nan), btVector3(1, 1, 1));
	scene.focusOn(btVector3(nan, 0, 0), btVector3(1, 1, 1));
	EXPECT_EQ(scene.skippedNonFinite(), 3);
	EXPECT_TRUE(scene.triangles().empty());
	EXPECT_TRUE(scene.lines().empty());
	EXPECT_TRUE(scene.points().empty());
	EXPECT_FALSE(scene.hasFocus());
	// A shape at a non-finite pose adds nothing and says so.
	btSphereShape sphere(1);
	EXPECT_FALSE(addShape(scene, &sphere, btTransform(btQuaternion::getIdentity(), btVector3(nan, 0, 0)), MeshStyle()));
	EXPECT_FALSE(addShape(scene, nullptr, btTransform::getIdentity(), MeshStyle()));
	EXPECT_TRUE(scene.triangles().empty());
	// The empty scene still renders (to background), with the default framing.
	RenderOptions options;
	options.width = options.height = 16;
	Image image;
	std::string error;
	ASSERT_TRUE(render(scene, frameScene(scene, options), options, image, error)) << error;
	EXPECT_EQ(countScenePixels(image, options), 0);
}

// Geometry far larger than the view, crossing the camera's near plane, is clipped: a 2000 km ground
// under the camera fills the lower half of the picture (the horizon is at the centre row, the camera
// looking level) and nothing is drawn above the horizon; a point far off screen draws nothing.
TEST(DemoRenderer, HugeGeometryIsClippedToTheViewAndNearPlane)
{
	Scene scene;
	const btScalar size = btScalar(1e6);
	const btVector3 color(0.2f, 0.6f, 0.2f);
	scene.addFlatTriangle(btVector3(-size, -1, -size), btVector3(size, -1, -size), btVector3(size, -1, size), color);
	scene.addFlatTriangle(btVector3(-size, -1, -size), btVector3(size, -1, size), btVector3(-size, -1, size), color);
	scene.addPoint(btVector3(btScalar(1e5), 0, -1), btVector3(1, 0, 0));
	RenderOptions options;
	options.width = 64;
	options.height = 48;
	options.supersampling = 1;
	Camera camera;
	camera.eye = btVector3(0, 0, 0);
	camera.target = btVector3(0, 0, -1);
	Image image;
	std::string error;
	ASSERT_TRUE(render(scene, camera, options, image, error)) << error;
	const std::uint32_t background = image.pixel(0, 0);
	for (int x = 0; x < image.width; ++x)
	{
		EXPECT_EQ(image.pixel(x, 10), background) << "sky at column " << x;
		EXPECT_NE(image.pixel(x, image.height - 1), background) << "ground at column " << x;
	}
	EXPECT_NE(image.pixel(image.width - 1, image.height / 2), 0xff0000u) << "the off-screen point is not drawn";
}
