// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// PNG files of the demos' pictures: a written picture reads back pixel for pixel, and paths that
// cannot be written or read give a message that names the path and the reason.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "Png.h"
#include "ShapeMesher.h"
#include "btBulletCollisionCommon.h"

using namespace caliber::demo;

namespace
{
Image renderedSphere()
{
	Scene scene;
	btSphereShape sphere(1);
	MeshStyle style;
	style.color = btVector3(0.2f, 0.6f, 0.9f);
	addShape(scene, &sphere, btTransform::getIdentity(), style);
	RenderOptions options;
	options.width = 97;  // odd sizes catch row-stride mistakes
	options.height = 61;
	Image image;
	std::string error;
	EXPECT_TRUE(render(scene, frameScene(scene, options), options, image, error)) << error;
	return image;
}
}  // namespace

TEST(DemoPng, WrittenPictureDecodesToTheSamePixels)
{
	ASSERT_TRUE(pngAvailable()) << "this build has no libpng; CI installs libpng-dev";
	const Image image = renderedSphere();
	const std::string path = ::testing::TempDir() + "caliber_png_roundtrip.png";
	std::string error;
	ASSERT_TRUE(writePng(path, image, error)) << error;
	Image decoded;
	ASSERT_TRUE(readPng(path, decoded, error)) << error;
	EXPECT_EQ(decoded.width, image.width);
	EXPECT_EQ(decoded.height, image.height);
	EXPECT_TRUE(decoded.rgb == image.rgb);
	std::remove(path.c_str());
}

TEST(DemoPng, UnwritablePathGivesAClearError)
{
	ASSERT_TRUE(pngAvailable());
	const Image image = renderedSphere();
	std::string error;
	EXPECT_FALSE(writePng("/nonexistent-caliber-folder/picture.png", image, error));
	EXPECT_NE(error.find("/nonexistent-caliber-folder/picture.png"), std::string::npos) << error;
	EXPECT_NE(error.find("No such file or directory"), std::string::npos) << error;
	// A folder is not a file.
	EXPECT_FALSE(writePng(::testing::TempDir(), image, error));
	EXPECT_NE(error.find("cannot write"), std::string::npos) << error;
}

TEST(DemoPng, EmptyOrInconsistentImagesAreNotWritten)
{
	ASSERT_TRUE(pngAvailable());
	const std::string path = ::testing::TempDir() + "caliber_png_empty.png";
	std::remove(path.c_str());
	Image empty;
	std::string error;
	EXPECT_FALSE(writePng(path, empty, error));
	EXPECT_NE(error.find("empty"), std::string::npos) << error;
	Image torn = renderedSphere();
	torn.rgb.resize(torn.rgb.size() / 2);
	EXPECT_FALSE(writePng(path, torn, error));
	// No file is left behind.
	EXPECT_FALSE(std::ifstream(path).good());
}

TEST(DemoPng, ReadingANonPngOrMissingFileFails)
{
	ASSERT_TRUE(pngAvailable());
	const std::string path = ::testing::TempDir() + "caliber_not_a.png";
	std::ofstream(path) << "this is text, not a picture";
	Image image;
	std::string error;
	EXPECT_FALSE(readPng(path, image, error));
	EXPECT_NE(error.find(path), std::string::npos) << error;
	EXPECT_EQ(image.width, 0);
	std::remove(path.c_str());
	EXPECT_FALSE(readPng(path, image, error));
}
