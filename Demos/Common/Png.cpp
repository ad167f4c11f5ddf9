// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "Png.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

#ifdef CALIBER_HAVE_PNG
#include <png.h>
#endif

namespace caliber
{
namespace demo
{
#ifdef CALIBER_HAVE_PNG
bool pngAvailable() { return true; }

// libpng's simplified API (png_image_*) reports errors through the image's message instead of longjmp,
// which keeps C++ objects on the stack safe.
bool writePng(const std::string& path, const Image& image, std::string& error)
{
	if (image.width < 1 || image.height < 1 ||
	    image.rgb.size() != std::size_t(image.width) * std::size_t(image.height) * 3)
	{
		error = "cannot write '" + path + "': the image is empty or its size does not match its pixels";
		return false;
	}
	std::FILE* file = std::fopen(path.c_str(), "wb");
	if (!file)
	{
		error = "cannot write '" + path + "': " + std::strerror(errno);
		return false;
	}
	png_image png;
	std::memset(&png, 0, sizeof(png));
	png.version = PNG_IMAGE_VERSION;
	png.width = png_uint_32(image.width);
	png.height = png_uint_32(image.height);
	png.format = PNG_FORMAT_RGB;
	const bool written = png_image_write_to_stdio(&png, file, 0, image.rgb.data(), 0, nullptr) != 0;
	const bool closed = std::fclose(file) == 0;
	if (!written || !closed)
	{
		error =
		    "cannot write '" + path + "': " + (written ? std::string(std::strerror(errno)) : std::string(png.message));
		std::remove(path.c_str());
		return false;
	}
	return true;
}

bool readPng(const std::string& path, Image& image, std::string& error)
{
	image = Image();
	png_image png;
	std::memset(&png, 0, sizeof(png));
	png.version = PNG_IMAGE_VERSION;
	if (!png_image_begin_read_from_file(&png, path.c_str()))
	{
		error = "cannot read '" + path + "': " + png.message;
		return false;
	}
	png.format = PNG_FORMAT_RGB;
	std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(png));
	if (!png_image_finish_read(&png, nullptr, pixels.data(), 0, nullptr))
	{
		error = "cannot read '" + path + "': " + png.message;
		png_image_free(&png);
		return false;
	}
	image.width = int(png.width);
	image.height = int(png.height);
	image.rgb.swap(pixels);
	return true;
}
#else
bool pngAvailable() { return false; }

namespace
{
const char* const kNoPng =
    "pictures are unavailable: this build has no libpng (install the Debian package libpng-dev and reconfigure)";
}

bool writePng(const std::string& path, const Image&, std::string& error)
{
	error = "cannot write '" + path + "': " + kNoPng;
	return false;
}

bool readPng(const std::string& path, Image& image, std::string& error)
{
	image = Image();
	error = "cannot read '" + path + "': " + kNoPng;
	return false;
}
#endif
}  // namespace demo
}  // namespace caliber
