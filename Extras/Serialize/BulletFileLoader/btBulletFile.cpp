// Caliber physics SDK. Copyright (c) 2026 the Caliber authors. zlib licence (see LICENSE.txt).
#include "btBulletFile.h"

#include "LinearMath/btAlignedAllocator.h"
#include "LinearMath/btSerializer.h"

#include <stdio.h>
#include <string.h>

namespace bParse
{
namespace
{
const char kMagic[7] = "BULLET";

int codeOf(const char* text) { return text[0] | (text[1] << 8) | (text[2] << 16) | (text[3] << 24); }
}  // namespace

btBulletFile::btBulletFile() : bFile(static_cast<char*>(0), 0, kMagic), m_DnaCopy(0) {}

btBulletFile::btBulletFile(const char* fileName) : bFile(fileName, kMagic), m_DnaCopy(0) {}

btBulletFile::btBulletFile(char* memoryBuffer, int len) : bFile(memoryBuffer, len, kMagic), m_DnaCopy(0) {}

btBulletFile::~btBulletFile()
{
	if (m_DnaCopy) btAlignedFree(m_DnaCopy);
}

void btBulletFile::addDataBlock(char* dataBlock) { m_dataBlocks.push_back(dataBlock); }

int btBulletFile::write(const char* fileName, bool fixupPointers)
{
	(void)fixupPointers;
	if (!mFileBuffer || mFileLen <= 0 || !fileName) return -1;
	FILE* fp = fopen(fileName, "wb");
	if (!fp) return -1;
	const size_t written = fwrite(mFileBuffer, 1, size_t(mFileLen), fp);
	fclose(fp);
	return written == size_t(mFileLen) ? 0 : -1;
}

void btBulletFile::parse(int verboseMode)
{
	if (!ok()) return;
	const int length = btDefaultSerializer::getMemoryDnaSizeInBytes();
	if (!m_DnaCopy)
	{
		m_DnaCopy = static_cast<char*>(btAlignedAlloc(size_t(length), 16));
		memcpy(m_DnaCopy, btDefaultSerializer::getMemoryDna(), size_t(length));
	}
	parseInternal(verboseMode, m_DnaCopy, length);
	if (ok()) parseData();
}

void btBulletFile::parseData()
{
	// The converted blocks in file order, each sorted by its chunk's code.
	for (int c = 0; c < m_chunks.size(); ++c)
	{
		void* oldKey = reinterpret_cast<void*>(static_cast<uintptr_t>(m_chunks[c].oldPtr));
		bStructHandle* block = m_chunks[c].oldPtr ? static_cast<bStructHandle*>(findLibPointer(oldKey)) : 0;
		if (!block) continue;
		const bChunkInd* info = m_chunkPtrPtrMap.find(btHashPtr(block));
		if (!info || info->dna_nr < 0) continue;  // names and raw arrays are reached through pointers only
		addDataBlock(reinterpret_cast<char*>(block));
		const int code = m_chunks[c].code;
		if (code == codeOf("SHAP"))
			m_collisionShapes.push_back(block);
		else if (code == codeOf("RBDY"))
			m_rigidBodies.push_back(block);
		else if (code == codeOf("COBJ"))
			m_collisionObjects.push_back(block);
		else if (code == codeOf("CONS"))
			m_constraints.push_back(block);
		else if (code == codeOf("DWLD"))
			m_dynamicsWorldInfo.push_back(block);
		else if (code == codeOf("QBVH"))
			m_bvhs.push_back(block);
		else if (code == codeOf("TMAP"))
			m_triangleInfoMaps.push_back(block);
		else if (code == codeOf("SBDY"))
			m_softBodies.push_back(block);
		else if (code == codeOf("MBDY"))
			m_multiBodies.push_back(block);
		else if (code == codeOf("MBLC"))
			m_multiBodyLinkColliders.push_back(block);
		else if (code == codeOf("CONT"))
			m_contactManifolds.push_back(block);
	}
}
}  // namespace bParse
