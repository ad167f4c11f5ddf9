// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#ifndef BT_SERIALIZER_H
#define BT_SERIALIZER_H

/// Writing `.bullet` files: Bullet's serializer interface and its default implementation.
/// The file is a 12-byte header, a list of chunks (a chunk header followed by the bytes of one or
/// more structs described by the DNA) and a DNA chunk that names every struct and field, so that a
/// reader built with another precision, pointer size or byte order maps each field by name.
/// Format, limits and bad-input rules: docs/serialization.md.

#include "LinearMath/btScalar.h"
#include "LinearMath/btAlignedObjectArray.h"
#include "LinearMath/btHashMap.h"

#include <string.h>

/// Length of a C string; 0 for null.
SIMD_FORCE_INLINE int btStrLen(const char* str)
{
	if (!str) return 0;
	return int(strlen(str));
}

/// The header in front of each chunk's data, as the file stores it in the writer's pointer size.
class btChunk
{
public:
	/// One of the BT_*_CODE values (what kind of object the chunk holds).
	int m_chunkCode;
	/// Bytes of data after the header (all m_number structs).
	int m_length;
	/// While writing: the chunk's data. In the file: the unique id other chunks use to point here.
	void* m_oldPtr;
	/// Index of the struct in the DNA's struct list.
	int m_dna_nr;
	/// How many structs follow.
	int m_number;
};

/// Options of btSerializer::setSerializationFlags.
enum btSerializationFlags
{
	BT_SERIALIZE_NO_BVH = 1,               ///< Triangle meshes are written without their BVH.
	BT_SERIALIZE_NO_TRIANGLEINFOMAP = 2,   ///< Triangle meshes are written without their triangle info map.
	BT_SERIALIZE_NO_DUPLICATE_ASSERT = 4,  ///< Writing the same object twice does not assert.
	BT_SERIALIZE_CONTACT_MANIFOLDS = 8,    ///< Also write the dispatcher's contact manifolds (btPersistentManifoldData chunks).
};

/// The interface every serialize() method writes through.
class btSerializer
{
public:
	virtual ~btSerializer() {}
	/// The finished file (valid after finishSerialization).
	virtual const unsigned char* getBufferPointer() const = 0;
	/// Bytes written so far; after finishSerialization, the file's size.
	virtual int getCurrentBufferSize() const = 0;
	/// A new chunk with room for numElements structs of size bytes each (data at chunk->m_oldPtr).
	virtual btChunk* allocate(size_t size, int numElements) = 0;
	/// Names the chunk's struct type and code, and records oldPtr (the object written) as its id.
	virtual void finalizeChunk(btChunk* chunk, const char* structType, int chunkCode, void* oldPtr) = 0;
	/// The unique id of the chunk already written for oldPtr, or 0.
	virtual void* findPointer(void* oldPtr) = 0;
	/// The unique id that stands for oldPtr in the file (0 for null); the same pointer gets the same id.
	virtual void* getUniquePointer(void* oldPtr) = 0;
	/// Starts a file: clears the chunks and ids of an earlier one.
	virtual void startSerialization() = 0;
	/// Appends the DNA and assembles header and chunks into one buffer.
	virtual void finishSerialization() = 0;
	/// The name registered for ptr, or 0.
	virtual const char* findNameForPointer(const void* ptr) const = 0;
	/// Gives the object at ptr a name that its serialize() writes (the string must outlive the file).
	virtual void registerNameForPointer(const void* ptr, const char* name) = 0;
	/// Writes name as a char array chunk (once per string).
	virtual void serializeName(const char* ptr) = 0;
	/// The btSerializationFlags in use.
	virtual int getSerializationFlags() const = 0;
	/// Sets btSerializationFlags.
	virtual void setSerializationFlags(int flags) = 0;
	/// Number of chunks written so far.
	virtual int getNumChunks() const = 0;
	/// Chunk chunkIndex (0 <= chunkIndex < getNumChunks()).
	virtual const btChunk* getChunk(int chunkIndex) const = 0;
};

#define BT_HEADER_LENGTH 12
#if defined(__sgi) || defined(__sparc) || defined(__sparc__) || defined(__PPC__) || defined(__ppc__) || \
    defined(__BIG_ENDIAN__)
#define BT_MAKE_ID(a, b, c, d) ((int)(a) << 24 | (int)(b) << 16 | (c) << 8 | (d))
#else
#define BT_MAKE_ID(a, b, c, d) ((int)(d) << 24 | (int)(c) << 16 | (b) << 8 | (a))
#endif

#define BT_MULTIBODY_CODE BT_MAKE_ID('M', 'B', 'D', 'Y')
#define BT_MB_LINKCOLLIDER_CODE BT_MAKE_ID('M', 'B', 'L', 'C')
#define BT_SOFTBODY_CODE BT_MAKE_ID('S', 'B', 'D', 'Y')
#define BT_COLLISIONOBJECT_CODE BT_MAKE_ID('C', 'O', 'B', 'J')
#define BT_RIGIDBODY_CODE BT_MAKE_ID('R', 'B', 'D', 'Y')
#define BT_CONSTRAINT_CODE BT_MAKE_ID('C', 'O', 'N', 'S')
#define BT_BOXSHAPE_CODE BT_MAKE_ID('B', 'O', 'X', 'S')
#define BT_QUANTIZED_BVH_CODE BT_MAKE_ID('Q', 'B', 'V', 'H')
#define BT_TRIANLGE_INFO_MAP BT_MAKE_ID('T', 'M', 'A', 'P')
#define BT_SHAPE_CODE BT_MAKE_ID('S', 'H', 'A', 'P')
#define BT_ARRAY_CODE BT_MAKE_ID('A', 'R', 'A', 'Y')
#define BT_SBMATERIAL_CODE BT_MAKE_ID('S', 'B', 'M', 'T')
#define BT_SBNODE_CODE BT_MAKE_ID('S', 'B', 'N', 'D')
#define BT_DYNAMICSWORLD_CODE BT_MAKE_ID('D', 'W', 'L', 'D')
#define BT_CONTACTMANIFOLD_CODE BT_MAKE_ID('C', 'O', 'N', 'T')
#define BT_DNA_CODE BT_MAKE_ID('D', 'N', 'A', '1')

/// A unique id stored where the file expects a pointer.
struct btPointerUid
{
	union
	{
		void* m_ptr;
		int m_uniqueIds[2];
	};
};

/// The default serializer: chunks are kept apart while written and joined into one buffer (header,
/// chunks, DNA) by finishSerialization. Its DNA describes Caliber's own *Data structs; it is built
/// by tools/makedna from the public headers (docs/serialization.md).
class btDefaultSerializer : public btSerializer
{
protected:
	/// Type names of the DNA.
	btAlignedObjectArray<char*> mTypes;
	/// Each struct of the DNA: type, field count, then (type, name) pairs.
	btAlignedObjectArray<short*> mStructs;
	/// Byte size of each type.
	btAlignedObjectArray<short> mTlens;
	/// Struct index by type index.
	btHashMap<btHashInt, int> mStructReverse;
	/// Struct index by type name.
	btHashMap<btHashString, int> mTypeLookup;
	/// Unique id of each object written as a chunk.
	btHashMap<btHashPtr, void*> m_chunkP;
	/// Names registered with registerNameForPointer.
	btHashMap<btHashPtr, const char*> m_nameMap;
	/// Unique id handed out for each pointer.
	btHashMap<btHashPtr, btPointerUid> m_uniquePointers;
	/// The last unique id handed out.
	int m_uniqueIdGenerator;
	/// Size of the caller's buffer (0: the serializer owns its buffer).
	int m_totalSize;
	/// The finished file.
	unsigned char* m_buffer;
	/// True when m_buffer is ours to free.
	bool m_ownsBuffer;
	/// Bytes written (header, chunk headers, data).
	int m_currentSize;
	/// The DNA block.
	void* m_dna;
	/// Bytes of m_dna.
	int m_dnaLength;
	/// btSerializationFlags.
	int m_serializationFlags;
	/// Chunks in the order written (each a separate allocation until finishSerialization).
	btAlignedObjectArray<btChunk*> m_chunkPtrs;

	void* findPointer(void* oldPtr) override;
	/// Appends the DNA chunk.
	virtual void writeDNA();
	/// The struct index of type name type, or -1.
	int getReverseType(const char* type) const;
	/// Reads the DNA's type and struct tables into mTypes, mStructs, mTlens and the lookups.
	void initDNA(const char* bdnaOrg, int dnalen);

public:
	/// Pointers that getUniquePointer maps to null (objects left out of the file).
	btHashMap<btHashPtr, void*> m_skipPointers;

	/// totalSize and buffer: an optional caller-owned buffer for the finished file. If the file does
	/// not fit, a warning is reported and the serializer keeps the file in its own buffer instead.
	btDefaultSerializer(int totalSize = 0, unsigned char* buffer = 0);
	~btDefaultSerializer() override;

	/// Size of the DNA this build writes.
	static int getMemoryDnaSizeInBytes();
	/// The DNA this build writes (SDNA block).
	static const char* getMemoryDna();

	/// Writes the 12-byte header (BULLETf/BULLETd, pointer size, byte order, version) at buffer.
	void writeHeader(unsigned char* buffer) const;
	void startSerialization() override;
	void finishSerialization() override;
	void* getUniquePointer(void* oldPtr) override;
	const unsigned char* getBufferPointer() const override { return m_buffer; }
	int getCurrentBufferSize() const override { return m_currentSize; }
	void finalizeChunk(btChunk* chunk, const char* structType, int chunkCode, void* oldPtr) override;
	/// Allocates size bytes for one chunk (header included).
	virtual unsigned char* internalAlloc(size_t size);
	btChunk* allocate(size_t size, int numElements) override;
	const char* findNameForPointer(const void* ptr) const override;
	void registerNameForPointer(const void* ptr, const char* name) override;
	void serializeName(const char* name) override;
	int getSerializationFlags() const override { return m_serializationFlags; }
	void setSerializationFlags(int flags) override { m_serializationFlags = flags; }
	int getNumChunks() const override { return m_chunkPtrs.size(); }
	const btChunk* getChunk(int chunkIndex) const override;
};

#endif  // BT_SERIALIZER_H
