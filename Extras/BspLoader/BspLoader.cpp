// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
// The file is read field by field from bytes (little-endian, as Quake 3 writes it), never by casting
// the buffer to structs, so that alignment, padding and the host's byte order do not matter.
#include "BspLoader/BspLoader.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

#include "LinearMath/btScalar.h"

namespace caliber
{
namespace
{
// Sizes in bytes of the entries of the lumps the loader reads.
const std::size_t kTextureSize = 64 + 4 + 4;
const std::size_t kPlaneSize = 4 * 4;
const std::size_t kModelSize = 6 * 4 + 4 * 4;
const std::size_t kBrushSize = 3 * 4;
const std::size_t kBrushSideSize = 2 * 4;
const std::size_t kHeaderSize = 4 + 4 + kBspLumpCount * 8;

const char* const kLumpNames[kBspLumpCount] = {"entities",      "textures",       "planes",  "nodes",   "leafs",
                                               "leaf faces",    "leaf brushes",   "models",  "brushes", "brush sides",
                                               "vertexes",      "mesh verts",     "effects", "faces",   "lightmaps",
                                               "light volumes", "visibility data"};

std::uint32_t readU32(const unsigned char* p)
{
	return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) | (std::uint32_t(p[3]) << 24);
}

std::int32_t readI32(const unsigned char* p)
{
	const std::uint32_t bits = readU32(p);
	std::int32_t value;
	std::memcpy(&value, &bits, sizeof(value));
	return value;
}

float readF32(const unsigned char* p)
{
	const std::uint32_t bits = readU32(p);
	float value;
	std::memcpy(&value, &bits, sizeof(value));
	return value;
}

struct Lump
{
	const unsigned char* data = nullptr;
	std::size_t count = 0;  // entries
};

class BspReader
{
public:
	BspReader(const unsigned char* data, std::size_t size, BspLevel& level) : m_data(data), m_size(size), m_level(level)
	{
	}

	bool read()
	{
		if (m_size < kHeaderSize)
			return fail("the file is truncated: " + std::to_string(m_size) + " bytes, a header needs " +
			            std::to_string(kHeaderSize));
		if (std::memcmp(m_data, kBspMagic, 4) != 0) return fail("bad magic number (not 'IBSP')");
		const int version = readI32(m_data + 4);
		if (version != kBspVersion)
			return fail("unsupported version " + std::to_string(version) + " (Quake 3's is 46)");
		Lump entities, textures, planes, models, brushes, sides;
		if (!lump(kBspLumpEntities, 1, entities) || !lump(kBspLumpTextures, kTextureSize, textures) ||
		    !lump(kBspLumpPlanes, kPlaneSize, planes) || !lump(kBspLumpModels, kModelSize, models) ||
		    !lump(kBspLumpBrushes, kBrushSize, brushes) || !lump(kBspLumpBrushSides, kBrushSideSize, sides))
			return false;
		// The other lumps are not read, but a directory entry pointing outside the file means a damaged file.
		for (int i = 0; i < kBspLumpCount; ++i)
		{
			Lump ignored;
			if (!lump(BspLump(i), 1, ignored)) return false;
		}

		// The entities text may end in a NUL; keep the characters before it.
		m_level.entities.assign(reinterpret_cast<const char*>(entities.data), entities.count);
		const std::size_t nul = m_level.entities.find('\0');
		if (nul != std::string::npos) m_level.entities.resize(nul);

		m_level.textures.resize(textures.count);
		for (std::size_t i = 0; i < textures.count; ++i)
		{
			const unsigned char* entry = textures.data + i * kTextureSize;
			const char* name = reinterpret_cast<const char*>(entry);
			m_level.textures[i].name.assign(name, strnlen(name, 64));
			m_level.textures[i].surfaceFlags = readI32(entry + 64);
			m_level.textures[i].contents = readI32(entry + 68);
		}

		// Model 0 is the world; the other models are entities' brushes (doors, platforms), not level geometry.
		std::size_t firstBrush = 0, brushCount = brushes.count;
		if (models.count > 0)
		{
			const std::int64_t first = readI32(models.data + 32);
			const std::int64_t count = readI32(models.data + 36);
			if (first < 0 || count < 0 || std::uint64_t(first + count) > brushes.count)
				return fail("the world model's brushes " + std::to_string(first) + " + " + std::to_string(count) +
				            " are out of range (" + std::to_string(brushes.count) + " brushes)");
			firstBrush = std::size_t(first);
			brushCount = std::size_t(count);
		}

		m_level.brushes.resize(brushCount);
		for (std::size_t b = 0; b < brushCount; ++b)
		{
			const std::size_t brushIndex = firstBrush + b;
			const unsigned char* entry = brushes.data + brushIndex * kBrushSize;
			const std::int64_t firstSide = readI32(entry);
			const std::int64_t sideCount = readI32(entry + 4);
			const std::int64_t texture = readI32(entry + 8);
			const std::string which = "brush " + std::to_string(brushIndex);
			if (firstSide < 0 || sideCount < 0 || std::uint64_t(firstSide + sideCount) > sides.count)
				return fail(which + ": sides " + std::to_string(firstSide) + " + " + std::to_string(sideCount) +
				            " are out of range (" + std::to_string(sides.count) + " brush sides)");
			if (texture < 0 || std::uint64_t(texture) >= textures.count)
				return fail(which + ": texture " + std::to_string(texture) + " is out of range (" +
				            std::to_string(textures.count) + " textures)");
			BspBrush& brush = m_level.brushes[b];
			brush.texture = int(texture);
			brush.contents = m_level.textures[std::size_t(texture)].contents;
			brush.planes.reserve(int(sideCount));
			for (std::int64_t s = firstSide; s < firstSide + sideCount; ++s)
			{
				const std::int64_t plane = readI32(sides.data + std::size_t(s) * kBrushSideSize);
				if (plane < 0 || std::uint64_t(plane) >= planes.count)
					return fail(which + ": side " + std::to_string(s) + " names plane " + std::to_string(plane) +
					            ", out of range (" + std::to_string(planes.count) + " planes)");
				const unsigned char* p = planes.data + std::size_t(plane) * kPlaneSize;
				// Non-finite values are kept: the converter rejects such a brush with a message naming it.
				brush.planes.push_back(
				    btVector3(btScalar(readF32(p)), btScalar(readF32(p + 4)), btScalar(readF32(p + 8))));
				brush.planes[brush.planes.size() - 1].setW(-btScalar(readF32(p + 12)));
			}
		}
		return true;
	}

private:
	bool fail(const std::string& message)
	{
		const std::string error = message;
		m_level = BspLevel();
		m_level.error = error;
		return false;
	}

	bool lump(BspLump which, std::size_t entrySize, Lump& out)
	{
		const unsigned char* entry = m_data + 8 + std::size_t(which) * 8;
		const std::int64_t offset = readI32(entry);
		const std::int64_t length = readI32(entry + 4);
		const std::string name = std::string("the ") + kLumpNames[which] + " lump";
		if (offset < 0 || length < 0 || std::uint64_t(offset) + std::uint64_t(length) > m_size)
			return fail(name + " (offset " + std::to_string(offset) + ", length " + std::to_string(length) +
			            ") lies outside the file of " + std::to_string(m_size) + " bytes");
		if (std::uint64_t(length) % entrySize != 0)
			return fail(name + "'s length " + std::to_string(length) + " is not a multiple of its entry size " +
			            std::to_string(entrySize));
		out.data = m_data + offset;
		out.count = std::size_t(length) / entrySize;
		return true;
	}

	const unsigned char* m_data;
	std::size_t m_size;
	BspLevel& m_level;
};
}  // namespace

bool loadBspFromMemory(const void* data, std::size_t size, BspLevel& level)
{
	level = BspLevel();
	if (!data && size != 0)
	{
		btAssert(!"loadBspFromMemory: null data with a non-zero size");
		level.error = "null data with a non-zero size";
		return false;
	}
	BspReader reader(static_cast<const unsigned char*>(data), data ? size : 0, level);
	return reader.read();
}

bool loadBspFile(const char* path, BspLevel& level)
{
	level = BspLevel();
	if (!path)
	{
		btAssert(!"loadBspFile: null path");
		level.error = "null path";
		return false;
	}
	std::FILE* file = std::fopen(path, "rb");
	if (!file)
	{
		level.error = std::string("cannot open '") + path + "'";
		return false;
	}
	std::vector<unsigned char> bytes;
	unsigned char buffer[65536];
	std::size_t got = 0;
	while ((got = std::fread(buffer, 1, sizeof(buffer), file)) > 0) bytes.insert(bytes.end(), buffer, buffer + got);
	const bool readError = std::ferror(file) != 0;
	std::fclose(file);
	if (readError)
	{
		level.error = std::string("cannot read '") + path + "'";
		return false;
	}
	return loadBspFromMemory(bytes.data(), bytes.size(), level);
}
}  // namespace caliber
