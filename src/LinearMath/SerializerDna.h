// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef CALIBER_SERIALIZER_DNA_H
#define CALIBER_SERIALIZER_DNA_H

// The DNA block this build writes into .bullet files (docs/serialization.md, "The DNA").

#include <vector>

namespace caliber
{
/// The SDNA block of this build, built once from the tables tools/makedna generated.
struct MemoryDnaBlock
{
	const char* bytes;
	int size;
};

/// The block (thread-safe, built on first use, never freed).
const MemoryDnaBlock& memoryDna();

/// Tables of a DNA block written by memoryDna (pointers into the block).
struct DnaView
{
	int typeCount;
	std::vector<char*> types;
	short* typeLengths;
	int structCount;
	short* structs;
};

/// Reads the tables of a block that memoryDna built (a copy of it): no checks beyond that origin.
void parseMemoryDna(char* block, int size, DnaView& view);
}  // namespace caliber

#endif
