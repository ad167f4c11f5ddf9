// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef __BCHUNK_H__
#define __BCHUNK_H__

/// Chunk headers of .bullet files as the file stores them (docs/serialization.md).

namespace bParse
{
/// A chunk header written with 4-byte pointers.
class bChunkPtr4
{
public:
	bChunkPtr4() {}
	int code;
	int len;
	int uniqueInt;
	int dna_nr;
	int nr;
};

/// A chunk header written with 8-byte pointers.
class bChunkPtr8
{
public:
	bChunkPtr8() {}
	int code, len;
	int uniqueInts[2];
	int dna_nr, nr;
};

/// A chunk header in the reader's terms: the old pointer widened to 64 bits, byte order fixed.
class bChunkInd
{
public:
	bChunkInd() : code(0), len(0), oldPtr(0), dna_nr(-1), nr(0) {}
	int code, len;
	/// The id the writer gave the chunk (its old address), as written.
	unsigned long long oldPtr;
	int dna_nr;
	int nr;
};
}  // namespace bParse

#endif
