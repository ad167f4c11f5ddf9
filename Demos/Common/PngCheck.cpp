// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// caliber_png_check: checks that the demos' pictures show something. For each file: it decodes as a
// PNG, has the expected size (--size WxH, default 640x480), holds more than one colour, and at least
// 1% (--min-scene PERCENT) of its pixels differ from its most common colour (the background, or a
// ground filling the view), so a blank, a one-colour or a nearly empty frame fails. Prints one line per
// file; exit 1 if any fails.

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unordered_map>

#include "Png.h"

namespace
{
bool checkOne(const char* path, int width, int height, double minScene)
{
	caliber::demo::Image image;
	std::string error;
	if (!caliber::demo::readPng(path, image, error))
	{
		std::printf("%s: FAILED: %s\n", path, error.c_str());
		return false;
	}
	if (image.width != width || image.height != height)
	{
		std::printf("%s: FAILED: %d x %d, expected %d x %d\n", path, image.width, image.height, width, height);
		return false;
	}
	std::unordered_map<std::uint32_t, int> counts;
	for (int y = 0; y < image.height; ++y)
		for (int x = 0; x < image.width; ++x) ++counts[image.pixel(x, y)];
	int most = 0;
	for (const auto& entry : counts)
		if (entry.second > most) most = entry.second;
	const int total = image.width * image.height;
	const double scene = double(total - most) / total;
	const bool ok = counts.size() > 1 && scene >= minScene;
	std::printf("%s: %d x %d, %zu colours, %.1f%% scene pixels: %s\n", path, image.width, image.height, counts.size(),
	            100 * scene, ok ? "ok" : "FAILED (blank or nearly empty)");
	return ok;
}
}  // namespace

int main(int argc, char** argv)
{
	int width = 640, height = 480, first = 1;
	double minScene = 0.01;
	while (first + 1 < argc && argv[first][0] == '-')
	{
		const char* value = argv[first + 1];
		if (std::strcmp(argv[first], "--size") == 0)
		{
			if (std::sscanf(value, "%dx%d", &width, &height) != 2 || width < 1 || height < 1)
			{
				std::fprintf(stderr, "%s: --size needs WIDTHxHEIGHT, got '%s'\n", argv[0], value);
				return 2;
			}
		}
		else if (std::strcmp(argv[first], "--min-scene") == 0)
		{
			char* end = nullptr;
			const double percent = std::strtod(value, &end);
			if (*end != '\0' || !(percent > 0 && percent <= 100))
			{
				std::fprintf(stderr, "%s: --min-scene needs a percentage above 0 and up to 100, got '%s'\n", argv[0],
				             value);
				return 2;
			}
			minScene = percent / 100;
		}
		else
			break;
		first += 2;
	}
	if (first >= argc)
	{
		std::fprintf(stderr, "usage: %s [--size WxH] [--min-scene PERCENT] FILE.png...\n", argv[0]);
		return 2;
	}
	bool ok = true;
	for (int i = first; i < argc; ++i) ok = checkOne(argv[i], width, height, minScene) && ok;
	return ok ? 0 : 1;
}
