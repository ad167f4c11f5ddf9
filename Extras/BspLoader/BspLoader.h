// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_EXTRAS_BSP_LOADER_H
#define CALIBER_EXTRAS_BSP_LOADER_H

/// Quake 3 BSP (IBSP version 46) reading: the world's brushes as plane sets (docs/extras.md, "BSP levels").

#include <cstddef>
#include <string>
#include <vector>

#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btVector3.h"

namespace caliber
{
/// Quake 3's content flag of solid brushes (CONTENTS_SOLID).
const int kBspContentsSolid = 1;
/// The file's magic number and the version this loader reads.
const char kBspMagic[4] = {'I', 'B', 'S', 'P'};
const int kBspVersion = 46;

/// The lumps of a Quake 3 BSP file, in the order of the header's directory.
enum BspLump
{
	kBspLumpEntities,
	kBspLumpTextures,
	kBspLumpPlanes,
	kBspLumpNodes,
	kBspLumpLeafs,
	kBspLumpLeafFaces,
	kBspLumpLeafBrushes,
	kBspLumpModels,
	kBspLumpBrushes,
	kBspLumpBrushSides,
	kBspLumpVertexes,
	kBspLumpMeshVerts,
	kBspLumpEffects,
	kBspLumpFaces,
	kBspLumpLightmaps,
	kBspLumpLightVols,
	kBspLumpVisData,
	kBspLumpCount
};

/// One texture (shader) entry; its contents flags say whether brushes using it are solid.
struct BspTexture
{
	std::string name;
	int surfaceFlags = 0;
	int contents = 0;
};

/// One brush of the world model: the planes bounding it, with its texture's contents flags.
struct BspBrush
{
	/// Outward planes in btGeometryUtil's form: normal in x, y, z and offset in w, so that points p of the
	/// brush satisfy normal.p + w <= 0 (Quake's plane normal.p = dist becomes w = -dist).
	btAlignedObjectArray<btVector3> planes;
	/// Index into BspLevel::textures.
	int texture = 0;
	/// The texture's contents flags (kBspContentsSolid for solid brushes).
	int contents = 0;
};

/// What a BSP file holds that collision needs.
struct BspLevel
{
	std::vector<BspTexture> textures;
	/// The world model's brushes (model 0), in file order; every brush when the file has no model lump entry.
	std::vector<BspBrush> brushes;
	/// The entities lump's text (key/value blocks), unparsed.
	std::string entities;
	/// Why the load failed; empty when it succeeded.
	std::string error;

	/// True when the file loaded.
	bool ok() const { return error.empty(); }
};

/// Reads a BSP file image of size bytes into level (cleared first). Returns level.ok(). Any structural
/// problem (truncated header, bad magic or version, a lump outside the file or of a size that is not a
/// whole number of entries, an index out of range) fails the whole load with one message in level.error.
/// A null data pointer with a non-zero size is a programming error: btAssert, else a failed load.
bool loadBspFromMemory(const void* data, std::size_t size, BspLevel& level);

/// Reads and parses the file at path; a file that cannot be read fails the load.
bool loadBspFile(const char* path, BspLevel& level);
}  // namespace caliber

#endif  // CALIBER_EXTRAS_BSP_LOADER_H
