// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef __BFILE_H__
#define __BFILE_H__

#include "bChunk.h"
#include "bDNA.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btHashMap.h"

#include <stdio.h>

/// Reading files in Bullet's chunk format: header, chunks, DNA, and the conversion of every chunk to
/// the reader's own structs (docs/serialization.md, "Reading").

namespace bParse
{
/// Opaque handle of a converted struct.
struct bStructHandle
{
	int unused;
};
/// Old pointer (the writer's id) to converted data.
typedef btHashMap<btHashPtr, bStructHandle*> bPtrMap;

/// What bFile::getFlags reports.
enum bFileFlags
{
	FD_INVALID = 0,
	FD_OK = 1,
	FD_VOID_IS_8 = 2,
	FD_ENDIAN_SWAP = 4,
	FD_FILE_64 = 8,
	FD_BITS_VARIES = 16,
	FD_VERSION_VARIES = 32,
	FD_DOUBLE_PRECISION = 64,
	FD_BROKEN_DNA = 128,
	FD_FILEDNA_IS_MEMDNA = 256
};

/// The dna_nr a converted block's chunk header gets when the block is an array of pointers (the target of a
/// `**` field): nr pointers into other converted blocks (or null), then one null.
const int kPointerArrayDna = -2;

/// Verbosity bits of parse().
enum bFileVerboseMode
{
	FD_VERBOSE_EXPORT_XML = 1,
	FD_VERBOSE_DUMP_DNA_TYPE_DEFINITIONS = 2,
	FD_VERBOSE_DUMP_CHUNKS = 4,
	FD_VERBOSE_DUMP_FILE_INFO = 8,
};

/// A file in Bullet's chunk format. The constructors read and check the header; parse() (in the
/// derived class) reads the chunks and the DNA and converts every chunk. Any malformed part makes
/// ok() false and reports the reason through btReportWarning; nothing is read out of bounds.
class bFile
{
protected:
	/// The first 6 bytes every file of this kind starts with ("BULLET").
	char m_headerString[7];
	/// True when mFileBuffer is ours to free.
	bool mOwnsBuffer;
	/// The file's bytes.
	char* mFileBuffer;
	/// Bytes of mFileBuffer.
	int mFileLen;
	/// The version from the header (e.g. 289).
	int mVersion;
	/// Old pointer of each chunk to its converted data.
	bPtrMap mLibPointers;
	/// Offset of the first chunk.
	int mDataStart;
	/// The file's DNA.
	bDNA* mFileDNA;
	/// The reader's DNA.
	bDNA* mMemoryDNA;
	/// Every chunk header, in file order.
	btAlignedObjectArray<bChunkInd> m_chunks;
	/// Header of the chunk each converted block came from (dna_nr in the reader's DNA).
	btHashMap<btHashPtr, bChunkInd> m_chunkPtrPtrMap;
	/// btBulletFile: the converted blocks, to free.
	btAlignedObjectArray<char*> m_pointerFixupArray;
	/// FD_* flags.
	int mFlags;

	/// Reads chunks and DNA and converts the chunks into structs of memDna (the reader's DNA).
	void parseInternal(int verboseMode, char* memDna, int memDnaLength);
	/// Marks the file broken and reports why.
	void fail(const char* reason);

public:
	/// Reads the file fileName; headerString is the 6-byte magic it must start with.
	bFile(const char* filename, const char headerString[7]);
	/// Reads len bytes at memoryBuffer (not copied: it must outlive the bFile).
	bFile(char* memoryBuffer, int len, const char headerString[7]);
	virtual ~bFile();

	/// The file's DNA (0 before parse or for a broken file).
	bDNA* getFileDNA() { return mFileDNA; }
	/// Called for each converted chunk.
	virtual void addDataBlock(char* dataBlock) = 0;
	/// FD_* flags.
	int getFlags() const { return mFlags; }
	/// Old pointer to converted data.
	bPtrMap& getLibPointers() { return mLibPointers; }
	/// Converted data of an old pointer, or 0.
	void* findLibPointer(void* ptr);
	/// True while the file is well formed.
	bool ok() { return (mFlags & FD_OK) != 0; }
	/// Reads and converts the chunks.
	virtual void parse(int verboseMode) = 0;
	/// Writes the file's bytes to fileName (as read); returns 0 on success.
	virtual int write(const char* fileName, bool fixupPointers = false) = 0;
	/// Sets every pointer of the converted structs from the old pointers they held.
	void resolvePointers(int verboseMode);
	/// Prints the chunk list.
	void dumpChunks(bDNA* dna);
	/// The version from the header.
	int getVersion() const { return mVersion; }
};
}  // namespace bParse

#endif
