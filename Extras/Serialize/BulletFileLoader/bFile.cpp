// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
//
// The reader of Bullet's chunk format. Every chunk is converted field by field from the file's DNA
// to the reader's: fields are matched by name, numbers are converted between the basic types (float
// and double, the integer widths), byte order is swapped, pointers of either width become fix-ups
// resolved once all chunks are in memory. All sizes, counts and indices are checked against the
// file before use (docs/serialization.md, "Bad input").
#include "bFile.h"

#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btWarningHook.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include <string>
#include <vector>

namespace bParse
{
namespace
{
const int kDnaCode = ('D') | ('N' << 8) | ('A' << 16) | ('1' << 24);
const int kEndCode = ('E') | ('N' << 8) | ('D' << 16) | ('B' << 24);
// Converted data larger than this is refused (a corrupt count must not exhaust memory).
const long long kMaxBlockBytes = 1ll << 30;
const int kMaxStructDepth = 16;

uint32_t swap32(uint32_t v) { return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24); }

uint64_t readUnsigned(const char* p, int bytes, bool swap)
{
	unsigned char b[8];
	memcpy(b, p, size_t(bytes));
	uint64_t v = 0;
	for (int i = 0; i < bytes; ++i)
	{
		const int shift = 8 * (swap ? bytes - 1 - i : i);
		v |= uint64_t(b[i]) << shift;
	}
	// The loop reads little-endian; on a big-endian host "no swap" means big-endian bytes.
	const uint16_t probe = 1;
	unsigned char first;
	memcpy(&first, &probe, 1);
	if (first == 0)
	{
		v = 0;
		for (int i = 0; i < bytes; ++i)
		{
			const int shift = 8 * (swap ? i : bytes - 1 - i);
			v |= uint64_t(b[i]) << shift;
		}
	}
	return v;
}

int readInt(const char* p, bool swap)
{
	uint32_t v;
	memcpy(&v, p, 4);
	if (swap) v = swap32(v);
	int out;
	memcpy(&out, &v, 4);
	return out;
}

struct FieldLayout
{
	short type;
	int offset;
	int count;
	int elemSize;
	bool pointer;
	std::string base;
};

struct StructLayout
{
	int size = 0;
	std::vector<FieldLayout> fields;
};

// The identifier inside a DNA name: "*m_x[4]" and "(*m_f)()" both give m_x / m_f.
std::string baseName(const char* name)
{
	std::string out;
	for (const char* c = name; *c; ++c)
	{
		if (*c == '[' || *c == ')') break;
		if (*c == '*' || *c == '(') continue;
		out += *c;
	}
	return out;
}

// Offsets by summing sizes; false (with reason) when a struct's fields do not add up to its length.
bool computeLayouts(bDNA& dna, int ptrSize, std::vector<StructLayout>& out, std::string& reason)
{
	out.assign(size_t(dna.getNumStructs()), StructLayout());
	for (int s = 0; s < dna.getNumStructs(); ++s)
	{
		short* strc = dna.getStruct(s);
		long long offset = 0;
		for (int f = 0; f < strc[1]; ++f)
		{
			FieldLayout field;
			field.type = strc[2 + 2 * f];
			const char* name = dna.getName(strc[3 + 2 * f]);
			field.pointer = name[0] == '*' || (name[0] == '(' && name[1] == '*');
			field.count = dna.getArraySizeNew(strc[3 + 2 * f]);
			field.elemSize = field.pointer ? ptrSize : dna.getLength(field.type);
			field.base = baseName(name);
			if (field.elemSize < 0) field.elemSize = 0;
			field.offset = int(offset);
			offset += (long long)field.elemSize * field.count;
			if (offset > 32767)
			{
				reason =
				    std::string("the DNA's struct ") + dna.getType(strc[0]) + " is longer than a DNA struct can be";
				return false;
			}
			out[size_t(s)].fields.push_back(field);
		}
		out[size_t(s)].size = int(offset);
		if (offset != dna.getLength(strc[0]))
		{
			reason = std::string("the DNA's struct ") + dna.getType(strc[0]) + " has fields of " +
			         std::to_string(offset) + " bytes but a length of " + std::to_string(dna.getLength(strc[0]));
			return false;
		}
	}
	return true;
}

enum BasicKind
{
	kNotBasic,
	kChar,
	kUChar,
	kShort,
	kUShort,
	kInt,
	kUInt,
	kFloat,
	kDouble
};

BasicKind basicKind(const char* type)
{
	if (!strcmp(type, "char")) return kChar;
	if (!strcmp(type, "uchar")) return kUChar;
	if (!strcmp(type, "short")) return kShort;
	if (!strcmp(type, "ushort")) return kUShort;
	if (!strcmp(type, "int") || !strcmp(type, "long")) return kInt;
	if (!strcmp(type, "ulong")) return kUInt;
	if (!strcmp(type, "float")) return kFloat;
	if (!strcmp(type, "double")) return kDouble;
	return kNotBasic;
}

int kindSize(BasicKind k)
{
	switch (k)
	{
		case kChar:
		case kUChar:
			return 1;
		case kShort:
		case kUShort:
			return 2;
		case kInt:
		case kUInt:
		case kFloat:
			return 4;
		case kDouble:
			return 8;
		default:
			return 0;
	}
}

double readNumber(const char* p, BasicKind k, bool swap)
{
	const uint64_t raw = readUnsigned(p, kindSize(k), swap);
	switch (k)
	{
		case kChar:
			return double(int8_t(uint8_t(raw)));
		case kUChar:
			return double(uint8_t(raw));
		case kShort:
			return double(int16_t(uint16_t(raw)));
		case kUShort:
			return double(uint16_t(raw));
		case kInt:
			return double(int32_t(uint32_t(raw)));
		case kUInt:
			return double(uint32_t(raw));
		case kFloat:
		{
			const uint32_t bits = uint32_t(raw);
			float f;
			memcpy(&f, &bits, 4);
			return double(f);
		}
		case kDouble:
		{
			double d;
			memcpy(&d, &raw, 8);
			return d;
		}
		default:
			return 0;
	}
}

// Integer targets get the value clamped into range (NaN gives 0), so no conversion is undefined.
long long clampToInteger(double v, long long lo, long long hi)
{
	if (!(v == v)) return 0;
	if (v <= double(lo)) return lo;
	if (v >= double(hi)) return hi;
	return (long long)v;
}

void writeNumber(char* p, BasicKind k, double v)
{
	switch (k)
	{
		case kChar:
		{
			const int8_t x = int8_t(clampToInteger(v, -128, 127));
			memcpy(p, &x, 1);
			break;
		}
		case kUChar:
		{
			const uint8_t x = uint8_t(clampToInteger(v, 0, 255));
			memcpy(p, &x, 1);
			break;
		}
		case kShort:
		{
			const int16_t x = int16_t(clampToInteger(v, -32768, 32767));
			memcpy(p, &x, 2);
			break;
		}
		case kUShort:
		{
			const uint16_t x = uint16_t(clampToInteger(v, 0, 65535));
			memcpy(p, &x, 2);
			break;
		}
		case kInt:
		{
			const int32_t x = int32_t(clampToInteger(v, INT_MIN, INT_MAX));
			memcpy(p, &x, 4);
			break;
		}
		case kUInt:
		{
			const uint32_t x = uint32_t(clampToInteger(v, 0, UINT_MAX));
			memcpy(p, &x, 4);
			break;
		}
		case kFloat:
		{
			// Out-of-range doubles become infinities rather than an undefined conversion.
			float x;
			if (v > double(FLT_MAX))
				x = HUGE_VALF;
			else if (v < -double(FLT_MAX))
				x = -HUGE_VALF;
			else
				x = float(v);
			memcpy(p, &x, 4);
			break;
		}
		case kDouble:
			memcpy(p, &v, 8);
			break;
		default:
			break;
	}
}

struct Fixup
{
	size_t block;  // index in the converted block list
	int offset;    // of the pointer within the block
	uint64_t oldPtr;
};

struct Converter
{
	bDNA& fileDna;
	const std::vector<StructLayout>& fileLayouts;
	bDNA& memDna;
	const std::vector<StructLayout>& memLayouts;
	bool swap;
	int filePtrSize;
	std::vector<Fixup>& fixups;

	void convert(int memStruct, char* blockBase, int dstOffset, int fileStruct, const char* src, size_t blockIndex,
	             int depth)
	{
		if (depth > kMaxStructDepth) return;
		const StructLayout& mem = memLayouts[size_t(memStruct)];
		const StructLayout& file = fileLayouts[size_t(fileStruct)];
		for (const FieldLayout& mf : mem.fields)
		{
			const FieldLayout* ff = 0;
			for (const FieldLayout& candidate : file.fields)
				if (candidate.base == mf.base)
				{
					ff = &candidate;
					break;
				}
			if (!ff || ff->pointer != mf.pointer) continue;
			const int n = mf.count < ff->count ? mf.count : ff->count;
			char* dst = blockBase + dstOffset + mf.offset;
			const char* in = src + ff->offset;
			if (mf.pointer)
			{
				for (int i = 0; i < n; ++i)
				{
					const uint64_t old = readUnsigned(in + i * filePtrSize, filePtrSize, swap);
					if (old) fixups.push_back(Fixup{blockIndex, int(dst - blockBase) + i * mf.elemSize, old});
				}
				continue;
			}
			const char* memType = memDna.getType(mf.type);
			const char* fileType = fileDna.getType(ff->type);
			const int memSub = memDna.getReverseType(memType);
			if (memSub >= 0)
			{
				const int fileSub = fileDna.getReverseType(fileType);
				if (fileSub < 0 || strcmp(memType, fileType) != 0) continue;
				for (int i = 0; i < n; ++i)
					convert(memSub, blockBase, int(dst - blockBase) + i * mf.elemSize, fileSub, in + i * ff->elemSize,
					        blockIndex, depth + 1);
				continue;
			}
			const BasicKind mk = basicKind(memType);
			const BasicKind fk = basicKind(fileType);
			if (mk == kNotBasic || fk == kNotBasic) continue;
			if (kindSize(fk) != ff->elemSize || kindSize(mk) != mf.elemSize) continue;
			for (int i = 0; i < n; ++i)
				writeNumber(dst + i * mf.elemSize, mk, readNumber(in + i * ff->elemSize, fk, swap));
		}
	}
};
}  // namespace

bFile::bFile(const char* filename, const char headerString[7])
    : mOwnsBuffer(true),
      mFileBuffer(0),
      mFileLen(0),
      mVersion(0),
      mDataStart(0),
      mFileDNA(0),
      mMemoryDNA(0),
      mFlags(FD_INVALID)
{
	memcpy(m_headerString, headerString, 6);
	m_headerString[6] = 0;
	FILE* fp = filename ? fopen(filename, "rb") : 0;
	if (!fp)
	{
		fail("the file cannot be opened");
		return;
	}
	fseek(fp, 0, SEEK_END);
	const long size = ftell(fp);
	fseek(fp, 0, SEEK_SET);
	if (size <= 0 || size > long(INT_MAX))
	{
		fclose(fp);
		fail("the file is empty or larger than 2 GB");
		return;
	}
	mFileLen = int(size);
	mFileBuffer = static_cast<char*>(btAlignedAlloc(size_t(size), 16));
	const size_t got = fread(mFileBuffer, 1, size_t(size), fp);
	fclose(fp);
	if (got != size_t(size))
	{
		fail("the file could not be read completely");
		return;
	}
	mFlags = FD_OK;
	parseInternal(-1, 0, 0);
}

bFile::bFile(char* memoryBuffer, int len, const char headerString[7])
    : mOwnsBuffer(false),
      mFileBuffer(memoryBuffer),
      mFileLen(len),
      mVersion(0),
      mDataStart(0),
      mFileDNA(0),
      mMemoryDNA(0),
      mFlags(FD_INVALID)
{
	memcpy(m_headerString, headerString, 6);
	m_headerString[6] = 0;
	if (!memoryBuffer || len <= 0)
	{
		// btBulletFile() (no buffer at all) is a valid empty object; anything else is a bad buffer.
		if (memoryBuffer || len != 0)
			fail("the buffer is empty or its length is negative");
		else
			mFlags = FD_INVALID;
		return;
	}
	mFlags = FD_OK;
	parseInternal(-1, 0, 0);
}

bFile::~bFile()
{
	if (mOwnsBuffer && mFileBuffer) btAlignedFree(mFileBuffer);
	for (int i = 0; i < m_pointerFixupArray.size(); ++i) btAlignedFree(m_pointerFixupArray[i]);
	delete mFileDNA;
	delete mMemoryDNA;
}

void bFile::fail(const char* reason)
{
	mFlags = FD_INVALID;
	std::string message = std::string("Caliber: bFile: not a readable .bullet file: ") + reason + "\n";
	btReportWarning(message.c_str());
}

void* bFile::findLibPointer(void* ptr)
{
	bStructHandle** found = mLibPointers.find(btHashPtr(ptr));
	return found ? *found : 0;
}

// Called twice: by the constructors with no memory DNA (header checks only), then by parse() with
// the reader's DNA (chunks, DNA and conversion).
void bFile::parseInternal(int verboseMode, char* memDna, int memDnaLength)
{
	if (!ok()) return;
	if (!memDna)
	{
		if (mFileLen < 12)
		{
			fail("it is shorter than the 12-byte header");
			return;
		}
		if (memcmp(mFileBuffer, m_headerString, 6) != 0)
		{
			fail("the header does not start with the expected magic (BULLET)");
			return;
		}
		const char precision = mFileBuffer[6], pointer = mFileBuffer[7], order = mFileBuffer[8];
		if ((precision != 'f' && precision != 'd') || (pointer != '_' && pointer != '-') ||
		    (order != 'v' && order != 'V'))
		{
			fail("the header's precision, pointer size or byte order mark is unknown");
			return;
		}
		for (int i = 9; i < 12; ++i)
			if (mFileBuffer[i] < '0' || mFileBuffer[i] > '9')
			{
				fail("the header's version is not three digits");
				return;
			}
		mVersion = (mFileBuffer[9] - '0') * 100 + (mFileBuffer[10] - '0') * 10 + (mFileBuffer[11] - '0');
		if (precision == 'd') mFlags |= FD_DOUBLE_PRECISION;
		if (pointer == '-') mFlags |= FD_FILE_64;
		if (sizeof(void*) == 8) mFlags |= FD_VOID_IS_8;
		if (((mFlags & FD_FILE_64) != 0) != (sizeof(void*) == 8)) mFlags |= FD_BITS_VARIES;
		const uint16_t probe = 1;
		unsigned char first;
		memcpy(&first, &probe, 1);
		const bool hostLittle = first == 1;
		if ((order == 'v') != hostLittle) mFlags |= FD_ENDIAN_SWAP;
		mDataStart = 12;
		return;
	}

	const bool swap = (mFlags & FD_ENDIAN_SWAP) != 0;
	const int ptrSize = (mFlags & FD_FILE_64) ? 8 : 4;
	const int headerSize = 16 + ptrSize;
	// 1. The chunk list.
	int pos = mDataStart;
	int dnaIndex = -1;
	std::vector<int> dataOffsets;
	m_chunks.clear();
	while (pos < mFileLen)
	{
		const int remaining = mFileLen - pos;
		if (remaining >= 4 && readInt(mFileBuffer + pos, false) == kEndCode) break;
		if (remaining < headerSize)
		{
			fail(("a chunk header at offset " + std::to_string(pos) + " is cut off (the file is truncated)").c_str());
			return;
		}
		const char* h = mFileBuffer + pos;
		bChunkInd chunk;
		chunk.code = readInt(h, false);  // codes are four characters, compared as bytes
		chunk.len = readInt(h + 4, swap);
		chunk.oldPtr = readUnsigned(h + 8, ptrSize, swap);
		chunk.dna_nr = readInt(h + 8 + ptrSize, swap);
		chunk.nr = readInt(h + 12 + ptrSize, swap);
		if (chunk.code == kEndCode) break;
		if (chunk.len < 0 || chunk.len > remaining - headerSize)
		{
			fail(("the chunk at offset " + std::to_string(pos) + " claims " + std::to_string(chunk.len) +
			      " bytes but only " + std::to_string(remaining - headerSize) + " remain")
			         .c_str());
			return;
		}
		if (chunk.code == kDnaCode) dnaIndex = m_chunks.size();
		m_chunks.push_back(chunk);
		dataOffsets.push_back(pos + headerSize);
		pos += headerSize + chunk.len;
	}
	if (dnaIndex < 0)
	{
		fail("it has no DNA1 chunk (truncated, or not written by a .bullet serializer)");
		return;
	}
	// 2. The file's DNA and ours.
	mFileDNA = new bDNA();
	mFileDNA->init(mFileBuffer + dataOffsets[size_t(dnaIndex)], m_chunks[dnaIndex].len, swap);
	if (mFileDNA->getNumStructs() == 0)
	{
		mFlags |= FD_BROKEN_DNA;
		fail("its DNA block is malformed");
		return;
	}
	if (mFileDNA->getPointerSize() && mFileDNA->getPointerSize() != ptrSize)
	{
		mFlags |= FD_BROKEN_DNA;
		fail("its DNA's pointer size disagrees with the header's");
		return;
	}
	std::vector<StructLayout> fileLayouts, memLayouts;
	std::string reason;
	if (!computeLayouts(*mFileDNA, ptrSize, fileLayouts, reason))
	{
		mFlags |= FD_BROKEN_DNA;
		fail(reason.c_str());
		return;
	}
	mMemoryDNA = new bDNA();
	mMemoryDNA->init(memDna, memDnaLength, false);
	if (!computeLayouts(*mMemoryDNA, int(sizeof(void*)), memLayouts, reason))
	{
		fail(("the reader's own DNA is inconsistent: " + reason).c_str());
		return;
	}
	mFileDNA->initCmpFlags(mMemoryDNA);
	if (verboseMode & FD_VERBOSE_DUMP_DNA_TYPE_DEFINITIONS) mFileDNA->dumpTypeDefinitions();
	// 3. Convert each chunk.
	std::vector<Fixup> fixups;
	Converter converter = {*mFileDNA, fileLayouts, *mMemoryDNA, memLayouts, swap, ptrSize, fixups};
	for (int c = 0; c < m_chunks.size(); ++c)
	{
		if (c == dnaIndex) continue;
		bChunkInd chunk = m_chunks[c];
		const char* src = mFileBuffer + dataOffsets[size_t(c)];
		char* block = 0;
		if (chunk.dna_nr >= 0 && chunk.dna_nr < mFileDNA->getNumStructs())
		{
			const char* typeName = mFileDNA->getType(mFileDNA->getStruct(chunk.dna_nr)[0]);
			const int memStruct = mMemoryDNA->getReverseType(typeName);
			if (memStruct < 0) continue;  // a struct this reader does not know: skipped
			const long long fileSize = fileLayouts[size_t(chunk.dna_nr)].size;
			const long long memSize = memLayouts[size_t(memStruct)].size;
			if (chunk.nr > 0 && fileSize * chunk.nr > chunk.len &&
			    (long long)chunk.len == (long long)chunk.nr * ptrSize &&
			    (long long)chunk.nr * long(sizeof(void*)) <= kMaxBlockBytes)
			{
				// An array of pointers (the target of a `**` field, such as a soft body's materials): Bullet
				// writes it with the pointed-to struct's type and pointer-sized elements. Each element becomes a
				// fix-up; the block is marked kPointerArrayDna and ends with a null.
				const size_t bytes = size_t(chunk.nr + 1) * sizeof(void*);
				block = static_cast<char*>(btAlignedAlloc(bytes, 16));
				memset(block, 0, bytes);
				m_pointerFixupArray.push_back(block);
				for (int e = 0; e < chunk.nr; ++e)
				{
					const uint64_t old = readUnsigned(src + e * ptrSize, ptrSize, swap);
					if (old)
						fixups.push_back(Fixup{size_t(m_pointerFixupArray.size() - 1), int(e * sizeof(void*)), old});
				}
				chunk.dna_nr = kPointerArrayDna;
				chunk.len = int(size_t(chunk.nr) * sizeof(void*));
			}
			else if (chunk.nr <= 0 || fileSize * chunk.nr > chunk.len || memSize * chunk.nr > kMaxBlockBytes)
			{
				fail(("a chunk of " + std::string(typeName) + " claims " + std::to_string(chunk.nr) +
				      " structs, more than its " + std::to_string(chunk.len) + " bytes hold")
				         .c_str());
				return;
			}
			else
			{
				const size_t bytes = size_t(memSize * chunk.nr);
				block = static_cast<char*>(btAlignedAlloc(bytes > 0 ? bytes : 1, 16));
				memset(block, 0, bytes > 0 ? bytes : 1);
				m_pointerFixupArray.push_back(block);
				for (int e = 0; e < chunk.nr; ++e)
					converter.convert(memStruct, block, int(e * memSize), chunk.dna_nr, src + e * fileSize,
					                  size_t(m_pointerFixupArray.size() - 1), 0);
				chunk.dna_nr = memStruct;
				chunk.len = int(bytes);
			}
		}
		else
		{
			// Plain bytes (names, raw arrays): copied, with a terminator so a name always ends.
			block = static_cast<char*>(btAlignedAlloc(size_t(chunk.len) + 1, 16));
			memcpy(block, src, size_t(chunk.len));
			block[chunk.len] = 0;
			m_pointerFixupArray.push_back(block);
			chunk.dna_nr = -1;
		}
		m_chunkPtrPtrMap.insert(btHashPtr(block), chunk);
		void* oldKey = reinterpret_cast<void*>(uintptr_t(m_chunks[c].oldPtr));
		if (m_chunks[c].oldPtr && !mLibPointers.find(btHashPtr(oldKey)))
			mLibPointers.insert(btHashPtr(oldKey), reinterpret_cast<bStructHandle*>(block));
		if (verboseMode & FD_VERBOSE_DUMP_CHUNKS)
			printf("chunk %d: code %.4s, %d bytes, dna %d, %d structs\n", c, reinterpret_cast<const char*>(&chunk.code),
			       chunk.len, chunk.dna_nr, chunk.nr);
	}
	// 4. Pointers: each old id becomes the converted block with that id (or null when none has it).
	for (const Fixup& f : fixups)
	{
		void* oldKey = reinterpret_cast<void*>(uintptr_t(f.oldPtr));
		void* target = findLibPointer(oldKey);
		memcpy(m_pointerFixupArray[int(f.block)] + f.offset, &target, sizeof(void*));
	}
}

void bFile::resolvePointers(int verboseMode)
{
	// Pointers are resolved as the chunks are converted (parseInternal); kept for Bullet's interface.
	(void)verboseMode;
}

void bFile::dumpChunks(bDNA* dna)
{
	for (int i = 0; i < m_chunks.size(); ++i)
	{
		const bChunkInd& c = m_chunks[i];
		const char* type =
		    dna && c.dna_nr >= 0 && c.dna_nr < dna->getNumStructs() ? dna->getType(dna->getStruct(c.dna_nr)[0]) : "?";
		printf("chunk %.4s %s: %d bytes, %d structs\n", reinterpret_cast<const char*>(&c.code), type, c.len, c.nr);
	}
}
}  // namespace bParse
