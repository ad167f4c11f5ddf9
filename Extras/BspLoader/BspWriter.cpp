// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "BspLoader/BspWriter.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace caliber
{
namespace
{
void putU32(std::vector<unsigned char>& out, std::uint32_t value)
{
	for (int i = 0; i < 4; ++i) out.push_back((unsigned char)((value >> (8 * i)) & 0xff));
}

void putI32(std::vector<unsigned char>& out, std::int32_t value)
{
	std::uint32_t bits;
	std::memcpy(&bits, &value, sizeof(bits));
	putU32(out, bits);
}

void putF32(std::vector<unsigned char>& out, float value)
{
	std::uint32_t bits;
	std::memcpy(&bits, &value, sizeof(bits));
	putU32(out, bits);
}

void setU32(std::vector<unsigned char>& out, std::size_t at, std::uint32_t value)
{
	for (int i = 0; i < 4; ++i) out[at + i] = (unsigned char)((value >> (8 * i)) & 0xff);
}
}  // namespace

std::vector<unsigned char> writeBsp(const BspWriterInput& input)
{
	std::vector<unsigned char> out(kBspMagic, kBspMagic + 4);
	putI32(out, kBspVersion);
	const std::size_t directory = out.size();
	out.resize(out.size() + kBspLumpCount * 8, 0);
	std::vector<unsigned char> lumps[kBspLumpCount];

	lumps[kBspLumpEntities].assign(input.entities.begin(), input.entities.end());
	lumps[kBspLumpEntities].push_back(0);
	for (const BspTexture& texture : input.textures)
	{
		std::vector<unsigned char>& lump = lumps[kBspLumpTextures];
		char name[64] = {};
		std::strncpy(name, texture.name.c_str(), 63);
		lump.insert(lump.end(), name, name + 64);
		putI32(lump, texture.surfaceFlags);
		putI32(lump, texture.contents);
	}
	int planeCount = 0, sideCount = 0;
	for (const BspWriterBrush& brush : input.brushes)
	{
		putI32(lumps[kBspLumpBrushes], sideCount);
		putI32(lumps[kBspLumpBrushes], std::int32_t(brush.planes.size()));
		putI32(lumps[kBspLumpBrushes], brush.texture);
		for (const BspWriterBrush::Plane& plane : brush.planes)
		{
			for (float n : plane.normal) putF32(lumps[kBspLumpPlanes], n);
			putF32(lumps[kBspLumpPlanes], plane.dist);
			putI32(lumps[kBspLumpBrushSides], planeCount++);
			putI32(lumps[kBspLumpBrushSides], 0);  // the side's texture: not read by the loader
			++sideCount;
		}
	}
	// Model 0, the world: bounds left zero (the loader computes hulls itself), no faces, every brush.
	for (int i = 0; i < 6; ++i) putF32(lumps[kBspLumpModels], 0);
	putI32(lumps[kBspLumpModels], 0);
	putI32(lumps[kBspLumpModels], 0);
	putI32(lumps[kBspLumpModels], 0);
	putI32(lumps[kBspLumpModels], std::int32_t(input.brushes.size()));

	for (int i = 0; i < kBspLumpCount; ++i)
	{
		while (out.size() % 4 != 0) out.push_back(0);  // lumps start 4-byte aligned, as Quake's tools write them
		setU32(out, directory + 8 * i, std::uint32_t(out.size()));
		setU32(out, directory + 8 * i + 4, std::uint32_t(lumps[i].size()));
		out.insert(out.end(), lumps[i].begin(), lumps[i].end());
	}
	return out;
}

BspWriterBrush makeBoxBrush(const float min[3], const float max[3], int texture)
{
	BspWriterBrush brush;
	brush.texture = texture;
	for (int axis = 0; axis < 3; ++axis)
	{
		BspWriterBrush::Plane positive = {{0, 0, 0}, max[axis]};
		positive.normal[axis] = 1;
		BspWriterBrush::Plane negative = {{0, 0, 0}, -min[axis]};
		negative.normal[axis] = -1;
		brush.planes.push_back(positive);
		brush.planes.push_back(negative);
	}
	return brush;
}

BspWriterInput makeExampleRoom()
{
	BspWriterInput level;
	level.textures.push_back({"textures/caliber/concrete", 0, kBspContentsSolid});
	level.textures.push_back({"textures/caliber/water", 0, 32});  // CONTENTS_WATER: not solid
	level.entities =
	    "{\n\"classname\" \"worldspawn\"\n\"message\" \"Caliber example room\"\n}\n"
	    "{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"0 0 32\"\n}\n";
	const auto box = [&level](float x0, float y0, float z0, float x1, float y1, float z1, int texture)
	{
		const float min[3] = {x0, y0, z0}, max[3] = {x1, y1, z1};
		level.brushes.push_back(makeBoxBrush(min, max, texture));
	};
	box(-256, -256, -16, 256, 256, 0, 0);   // floor, top at z = 0
	box(-272, -256, 0, -256, 256, 256, 0);  // walls, 256 high
	box(256, -256, 0, 272, 256, 256, 0);
	box(-272, -272, 0, 272, -256, 256, 0);
	box(-272, 256, 0, 272, 272, 256, 0);

	// Ramp: 128 long, 128 wide, rising from z = 0 at x = -96 to z = 64 at x = -224 (slope 1:2, 26.6 degrees).
	BspWriterBrush ramp;
	const float s = 1.0f / std::sqrt(5.0f);
	ramp.planes.push_back({{0, 0, -1}, 0});
	ramp.planes.push_back({{-1, 0, 0}, 224});
	ramp.planes.push_back({{0, 1, 0}, 64});
	ramp.planes.push_back({{0, -1, 0}, 64});
	ramp.planes.push_back({{s, 0, 2 * s}, -96 * s});  // through (-96, y, 0) and (-224, y, 64)
	level.brushes.push_back(ramp);

	box(112, 112, 0, 144, 144, 192, 0);  // square pillars, 32 wide, 192 high
	box(112, -144, 0, 144, -112, 192, 0);
	box(-144, 144, 0, -112, 176, 192, 0);

	// Octagonal pillar at (0, -160): apothem 24, 8 sides, 192 high.
	BspWriterBrush octagon;
	const float cx = 0, cy = -160, apothem = 24;
	for (int k = 0; k < 8; ++k)
	{
		const float angle = float(k) * 0.785398163f + 0.392699082f;
		const float nx = std::cos(angle), ny = std::sin(angle);
		octagon.planes.push_back({{nx, ny, 0}, nx * cx + ny * cy + apothem});
	}
	octagon.planes.push_back({{0, 0, 1}, 192});
	octagon.planes.push_back({{0, 0, -1}, 0});
	level.brushes.push_back(octagon);

	box(32, -64, 0, 96, 64, 16, 1);  // a pool of water: the converter skips it
	return level;
}
}  // namespace caliber
