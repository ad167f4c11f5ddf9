// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// caliber_png_check: checks that the demos' pictures show something. For each file: it decodes as a
// PNG, has the expected size (--size WxH, default 640x480), holds more than one colour, and at least
// 1% (--min-scene PERCENT) of its pixels differ from its most common colour (the background, or a
// ground filling the view), so a blank, a one-colour or a nearly empty frame fails. Prints one line per
// file; exit 1 if any fails.
//
// Measurements for the browser's interaction tests (.ci/lib.sh): --box adds a line with the box around
// the scene pixels (x0 y0 x1 y1, inclusive), --near R,G,B one with how many pixels are within 60 of that
// colour in each channel (0-255), and --diff A B compares two pictures of the same size instead: how
// many pixels differ.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unordered_map>

#include "Png.h"

namespace
{
struct Measures
{
	bool box = false;
	bool near = false;
	int color[3] = {0, 0, 0};
};

bool isNear(std::uint32_t pixel, const int color[3])
{
	for (int c = 0; c < 3; ++c)
	{
		const int value = int((pixel >> (16 - 8 * c)) & 0xff);
		if (std::abs(value - color[c]) > 60) return false;
	}
	return true;
}

bool checkOne(const char* path, int width, int height, double minScene, const Measures& measures)
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
	std::uint32_t background = 0;
	for (const auto& entry : counts)
		if (entry.second > most)
		{
			most = entry.second;
			background = entry.first;
		}
	const int total = image.width * image.height;
	const double scene = double(total - most) / total;
	const bool ok = counts.size() > 1 && scene >= minScene;
	std::printf("%s: %d x %d, %zu colours, %.1f%% scene pixels: %s\n", path, image.width, image.height, counts.size(),
	            100 * scene, ok ? "ok" : "FAILED (blank or nearly empty)");
	if (measures.box)
	{
		int x0 = image.width, y0 = image.height, x1 = -1, y1 = -1;
		for (int y = 0; y < image.height; ++y)
			for (int x = 0; x < image.width; ++x)
				if (image.pixel(x, y) != background)
				{
					x0 = std::min(x0, x);
					y0 = std::min(y0, y);
					x1 = std::max(x1, x);
					y1 = std::max(y1, y);
				}
		std::printf("%s: box %d %d %d %d\n", path, x0, y0, x1, y1);
	}
	if (measures.near)
	{
		int near = 0;
		for (int y = 0; y < image.height; ++y)
			for (int x = 0; x < image.width; ++x) near += isNear(image.pixel(x, y), measures.color);
		std::printf("%s: near %d,%d,%d: %d pixels\n", path, measures.color[0], measures.color[1], measures.color[2],
		            near);
	}
	return ok;
}

// --diff A B: how many pixels of two same-sized pictures differ.
int diff(const char* a, const char* b)
{
	caliber::demo::Image first, second;
	std::string error;
	if (!caliber::demo::readPng(a, first, error) || !caliber::demo::readPng(b, second, error))
	{
		std::printf("--diff: FAILED: %s\n", error.c_str());
		return 1;
	}
	if (first.width != second.width || first.height != second.height)
	{
		std::printf("--diff: FAILED: %d x %d against %d x %d\n", first.width, first.height, second.width,
		            second.height);
		return 1;
	}
	int differ = 0;
	for (int y = 0; y < first.height; ++y)
		for (int x = 0; x < first.width; ++x) differ += first.pixel(x, y) != second.pixel(x, y);
	std::printf("%s vs %s: %d pixels differ (%.2f%%)\n", a, b, differ, 100.0 * differ / (first.width * first.height));
	return 0;
}
}  // namespace

int main(int argc, char** argv)
{
	int width = 640, height = 480, first = 1;
	double minScene = 0.01;
	Measures measures;
	if (argc == 4 && std::strcmp(argv[1], "--diff") == 0) return diff(argv[2], argv[3]);
	while (first + 1 < argc && argv[first][0] == '-')
	{
		const char* value = argv[first + 1];
		if (std::strcmp(argv[first], "--box") == 0)
		{
			measures.box = true;
			first += 1;
			continue;
		}
		if (std::strcmp(argv[first], "--near") == 0)
		{
			char trailing = 0;
			const int read =
			    std::sscanf(value, "%d,%d,%d%c", &measures.color[0], &measures.color[1], &measures.color[2], &trailing);
			bool inRange = read == 3;
			for (int c = 0; c < 3; ++c) inRange = inRange && measures.color[c] >= 0 && measures.color[c] <= 255;
			if (!inRange)
			{
				std::fprintf(stderr, "%s: --near needs R,G,B from 0 to 255, got '%s'\n", argv[0], value);
				return 2;
			}
			measures.near = true;
		}
		else if (std::strcmp(argv[first], "--size") == 0)
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
		std::fprintf(stderr,
		             "usage: %s [--size WxH] [--min-scene PERCENT] [--box] [--near R,G,B] FILE.png...\n"
		             "       %s --diff A.png B.png\n",
		             argv[0], argv[0]);
		return 2;
	}
	bool ok = true;
	for (int i = first; i < argc; ++i) ok = checkOne(argv[i], width, height, minScene, measures) && ok;
	return ok ? 0 : 1;
}
