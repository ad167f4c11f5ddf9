// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_DEMOS_COMMON_PNG_H
#define CALIBER_DEMOS_COMMON_PNG_H
// PNG files for the demos' pictures, through Debian's libpng. libpng is optional: without it the demos
// still build, pngAvailable() is false and both calls fail with a message that says so.

#include <string>

#include "Renderer.h"

namespace caliber
{
namespace demo
{
/// True when this build can write and read PNG files (it found libpng).
bool pngAvailable();
/// Writes image as an 8-bit RGB PNG. Returns false with a message naming the path and the reason (an
/// empty image, a folder that does not exist, no permission, a full disk, no libpng) in error.
bool writePng(const std::string& path, const Image& image, std::string& error);
/// Reads a PNG (any colour type, converted to 8-bit RGB). Returns false with the reason in error.
bool readPng(const std::string& path, Image& image, std::string& error);
}  // namespace demo
}  // namespace caliber

#endif
