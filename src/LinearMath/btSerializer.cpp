// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "LinearMath/btSerializer.h"

#include "LinearMath/btWarningHook.h"
#include "LinearMath/SerializerDna.h"

#include <limits.h>
#include <stdint.h>
#include <stdio.h>

#include <string>

btDefaultSerializer::btDefaultSerializer(int totalSize, unsigned char* buffer)
    : m_uniqueIdGenerator(0),
      m_totalSize(totalSize > 0 ? totalSize : 0),
      m_buffer(buffer),
      m_ownsBuffer(buffer == 0),
      m_currentSize(0),
      m_dna(0),
      m_dnaLength(0),
      m_serializationFlags(0)
{
	if (buffer && totalSize <= 0)
	{
		// A caller's buffer without a size cannot be written safely: use our own.
		btAssert(!"btDefaultSerializer: a buffer needs a positive totalSize");
		btReportWarning("Caliber: btDefaultSerializer: a buffer was given without a positive size; it is not used\n");
		m_buffer = 0;
		m_ownsBuffer = true;
	}
	initDNA(getMemoryDna(), getMemoryDnaSizeInBytes());
}

btDefaultSerializer::~btDefaultSerializer()
{
	for (int i = 0; i < m_chunkPtrs.size(); ++i) btAlignedFree(m_chunkPtrs[i]);
	if (m_buffer && m_ownsBuffer) btAlignedFree(m_buffer);
	if (m_dna) btAlignedFree(m_dna);
}

int btDefaultSerializer::getMemoryDnaSizeInBytes() { return caliber::memoryDna().size; }

const char* btDefaultSerializer::getMemoryDna() { return caliber::memoryDna().bytes; }

void btDefaultSerializer::initDNA(const char* bdnaOrg, int dnalen)
{
	if (m_dna) return;
	m_dna = btAlignedAlloc(size_t(dnalen), 16);
	memcpy(m_dna, bdnaOrg, size_t(dnalen));
	m_dnaLength = dnalen;
	// The tables point into our copy; the block was built by this build, so it is well formed.
	caliber::DnaView view;
	caliber::parseMemoryDna(static_cast<char*>(m_dna), dnalen, view);
	for (int i = 0; i < view.typeCount; ++i)
	{
		mTypes.push_back(view.types[i]);
		mTlens.push_back(view.typeLengths[i]);
	}
	short* strc = view.structs;
	for (int i = 0; i < view.structCount; ++i)
	{
		mStructs.push_back(strc);
		mStructReverse.insert(btHashInt(strc[0]), i);
		mTypeLookup.insert(btHashString(mTypes[strc[0]]), i);
		strc += 2 + 2 * strc[1];
	}
}

int btDefaultSerializer::getReverseType(const char* type) const
{
	const int* found = mTypeLookup.find(btHashString(type));
	return found ? *found : -1;
}

void* btDefaultSerializer::findPointer(void* oldPtr)
{
	void* const* found = m_chunkP.find(btHashPtr(oldPtr));
	return found ? *found : 0;
}

void btDefaultSerializer::writeHeader(unsigned char* buffer) const
{
#ifdef BT_USE_DOUBLE_PRECISION
	memcpy(buffer, "BULLETd", 7);
#else
	memcpy(buffer, "BULLETf", 7);
#endif
	buffer[7] = sizeof(void*) == 8 ? '-' : '_';
	const int one = 1;
	unsigned char firstByte;
	memcpy(&firstByte, &one, 1);
	buffer[8] = firstByte == 1 ? 'v' : 'V';
	// The version of Bullet whose interface and format Caliber follows.
	buffer[9] = '2';
	buffer[10] = '8';
	buffer[11] = '9';
}

void btDefaultSerializer::startSerialization()
{
	for (int i = 0; i < m_chunkPtrs.size(); ++i) btAlignedFree(m_chunkPtrs[i]);
	m_chunkPtrs.clear();
	m_chunkP.clear();
	m_uniquePointers.clear();
	m_uniqueIdGenerator = 1;
	m_currentSize = BT_HEADER_LENGTH;
}

void btDefaultSerializer::writeDNA()
{
	btChunk* dnaChunk = allocate(size_t(m_dnaLength), 1);
	if (!dnaChunk) return;
	memcpy(dnaChunk->m_oldPtr, m_dna, size_t(m_dnaLength));
	dnaChunk->m_dna_nr = 0;
	dnaChunk->m_chunkCode = BT_DNA_CODE;
	// The DNA chunk is found by its code; its id only has to be unique.
	dnaChunk->m_oldPtr = getUniquePointer(m_dna);
}

void btDefaultSerializer::finishSerialization()
{
	writeDNA();
	size_t total = BT_HEADER_LENGTH;
	for (int i = 0; i < m_chunkPtrs.size(); ++i) total += sizeof(btChunk) + size_t(m_chunkPtrs[i]->m_length);
	if (total > size_t(INT_MAX))
	{
		btAssert(!"btDefaultSerializer: the file would exceed 2 GB");
		btReportWarning(
		    "Caliber: btDefaultSerializer::finishSerialization: the file would exceed 2 GB; nothing was written\n");
		startSerialization();
		m_currentSize = 0;
		return;
	}
	if (!m_ownsBuffer && total > size_t(m_totalSize))
	{
		const std::string message = "Caliber: btDefaultSerializer: the file needs " + std::to_string(total) +
		                            " bytes but the caller's buffer holds " + std::to_string(m_totalSize) +
		                            "; the serializer keeps it in its own buffer\n";
		btReportWarning(message.c_str());
		m_buffer = 0;
		m_ownsBuffer = true;
	}
	if (m_ownsBuffer)
	{
		if (m_buffer) btAlignedFree(m_buffer);
		m_buffer = static_cast<unsigned char*>(btAlignedAlloc(total, 16));
	}
	writeHeader(m_buffer);
	unsigned char* cursor = m_buffer + BT_HEADER_LENGTH;
	for (int i = 0; i < m_chunkPtrs.size(); ++i)
	{
		const size_t length = sizeof(btChunk) + size_t(m_chunkPtrs[i]->m_length);
		memcpy(cursor, m_chunkPtrs[i], length);
		cursor += length;
		btAlignedFree(m_chunkPtrs[i]);
	}
	m_chunkPtrs.clear();
	m_chunkP.clear();
	m_nameMap.clear();
	m_uniquePointers.clear();
	m_skipPointers.clear();
	m_currentSize = int(total);
}

void* btDefaultSerializer::getUniquePointer(void* oldPtr)
{
	if (!oldPtr) return 0;
	const btPointerUid* known = m_uniquePointers.find(btHashPtr(oldPtr));
	if (known) return known->m_ptr;
	if (m_skipPointers.find(btHashPtr(oldPtr))) return 0;
	++m_uniqueIdGenerator;
	btPointerUid uid;
	uid.m_ptr = 0;
	uid.m_uniqueIds[0] = m_uniqueIdGenerator;
	if (sizeof(void*) >= 2 * sizeof(int)) uid.m_uniqueIds[1] = m_uniqueIdGenerator;
	m_uniquePointers.insert(btHashPtr(oldPtr), uid);
	return uid.m_ptr;
}

void btDefaultSerializer::finalizeChunk(btChunk* chunk, const char* structType, int chunkCode, void* oldPtr)
{
	if (!chunk) return;
	if (!(m_serializationFlags & BT_SERIALIZE_NO_DUPLICATE_ASSERT)) btAssert(!findPointer(oldPtr));
	chunk->m_dna_nr = getReverseType(structType);
	// Plain arrays (names, index lists, a soft body's weights) are written as "char", "int" or "float"
	// and have no struct.
	if (chunk->m_dna_nr < 0 && strcmp(structType, "char") != 0 && strcmp(structType, "int") != 0 &&
	    strcmp(structType, "float") != 0)
	{
		btAssert(!"btDefaultSerializer::finalizeChunk: the DNA has no such struct");
		const std::string message =
		    std::string("Caliber: btDefaultSerializer::finalizeChunk: the DNA has no struct '") +
		    (structType ? structType : "(null)") + "'; the chunk is written without a type and readers skip it\n";
		btReportWarning(message.c_str());
	}
	chunk->m_chunkCode = chunkCode;
	void* uniquePtr = getUniquePointer(oldPtr);
	m_chunkP.insert(btHashPtr(oldPtr), uniquePtr);
	chunk->m_oldPtr = uniquePtr;
}

unsigned char* btDefaultSerializer::internalAlloc(size_t size)
{
	unsigned char* ptr = static_cast<unsigned char*>(btAlignedAlloc(size, 16));
	// Zeroed, so that padding bytes are the same in every file written from the same state.
	memset(ptr, 0, size);
	m_currentSize += int(size);
	return ptr;
}

btChunk* btDefaultSerializer::allocate(size_t size, int numElements)
{
	if (numElements < 0 || (numElements > 0 && size > size_t(INT_MAX / 2) / size_t(numElements)))
	{
		btAssert(!"btDefaultSerializer::allocate: nonsense size or count");
		btReportWarning("Caliber: btDefaultSerializer::allocate: negative count or a chunk over 1 GB; no chunk\n");
		return 0;
	}
	const int length = int(size) * numElements;
	unsigned char* ptr = internalAlloc(sizeof(btChunk) + size_t(length));
	btChunk* chunk = reinterpret_cast<btChunk*>(ptr);
	chunk->m_chunkCode = 0;
	chunk->m_oldPtr = ptr + sizeof(btChunk);
	chunk->m_length = length;
	chunk->m_dna_nr = -1;
	chunk->m_number = numElements;
	m_chunkPtrs.push_back(chunk);
	return chunk;
}

const char* btDefaultSerializer::findNameForPointer(const void* ptr) const
{
	const char* const* name = m_nameMap.find(btHashPtr(ptr));
	return name ? *name : 0;
}

void btDefaultSerializer::registerNameForPointer(const void* ptr, const char* name)
{
	m_nameMap.insert(btHashPtr(ptr), name);
}

void btDefaultSerializer::serializeName(const char* name)
{
	if (!name || findPointer(const_cast<char*>(name))) return;
	const int length = btStrLen(name);
	if (length == 0) return;
	// The terminator included, padded to 4 bytes so that the next chunk stays aligned.
	const int padded = (length + 1 + 3) & ~3;
	btChunk* chunk = allocate(1, padded);
	if (!chunk) return;
	memcpy(chunk->m_oldPtr, name, size_t(length));
	finalizeChunk(chunk, "char", BT_ARRAY_CODE, const_cast<char*>(name));
}

const btChunk* btDefaultSerializer::getChunk(int chunkIndex) const
{
	if (chunkIndex < 0 || chunkIndex >= m_chunkPtrs.size())
	{
		btAssert(!"btDefaultSerializer::getChunk: index out of range");
		return 0;
	}
	return m_chunkPtrs[chunkIndex];
}
