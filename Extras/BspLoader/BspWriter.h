// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_BSP_WRITER_H
#define CALIBER_EXTRAS_BSP_WRITER_H

/// Writing small Quake 3 BSP files (brushes only) for tests and demos: our own levels, no game data needed.

#include <string>
#include <vector>

#include "BspLoader/BspLoader.h"

namespace caliber
{
/// A brush to write: its planes in Quake's form (unit normal and dist, points inside have normal.p <= dist).
struct BspWriterBrush
{
	struct Plane
	{
		float normal[3];
		float dist;
	};
	std::vector<Plane> planes;
	/// Index into BspWriterInput::textures.
	int texture = 0;
};

/// What a written file holds. The world model (model 0) covers every brush; the lumps the loader does not
/// read (nodes, leafs, faces, ...) are written empty, so the file is for collision, not for rendering.
struct BspWriterInput
{
	std::vector<BspTexture> textures;
	std::vector<BspWriterBrush> brushes;
	std::string entities;
};

/// The BSP file image (IBSP version 46, little-endian) of input. Texture names are cut to 63 characters.
std::vector<unsigned char> writeBsp(const BspWriterInput& input);

/// The axis-aligned box [min, max] as a brush of 6 planes.
BspWriterBrush makeBoxBrush(const float min[3], const float max[3], int texture);

/// The example level (Quake units, z up): a 512 x 512 room with a floor, four walls and no ceiling, a ramp,
/// three square pillars and an octagonal one (10 solid brushes), and a pool of water (1 non-solid brush).
/// tools/MakeBspLevel writes it; the BSP tests and Demos/BspDemo read it.
BspWriterInput makeExampleRoom();
}  // namespace caliber

#endif  // CALIBER_EXTRAS_BSP_WRITER_H
