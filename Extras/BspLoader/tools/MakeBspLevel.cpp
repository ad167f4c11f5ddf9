// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// Writes Caliber's example Quake 3 BSP level (caliber::makeExampleRoom) to the file named on the command line.
#include <cstdio>

#include "BspLoader/BspWriter.h"

int main(int argc, char** argv)
{
	if (argc != 2)
	{
		std::fprintf(stderr, "usage: %s OUTPUT.bsp\n", argv[0]);
		return 2;
	}
	const std::vector<unsigned char> bytes = caliber::writeBsp(caliber::makeExampleRoom());
	std::FILE* file = std::fopen(argv[1], "wb");
	if (!file || std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size() || std::fclose(file) != 0)
	{
		std::fprintf(stderr, "MakeBspLevel: cannot write '%s'\n", argv[1]);
		return 1;
	}
	std::printf("MakeBspLevel: wrote %s (%zu bytes)\n", argv[1], bytes.size());
	return 0;
}
